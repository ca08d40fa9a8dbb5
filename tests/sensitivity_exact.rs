//! Issue 14: the exact (dual-number) derivative columns of `[sensitivity]` against
//! independent references: Richardson-extrapolated differences of whole runs (with their
//! own error estimate), the chain rule through a parameter formula, a unit's factor.

use mechdiff::sensitivity::{self, Method, Options, Parameter};

const NORTON: &str = include_str!("../scenes/norton_four_bar.toml");

fn with_study(text: &str, columns: &[&str]) -> String {
    let quoted: Vec<String> = columns.iter().map(|c| format!("\"{c}\"")).collect();
    format!("{text}\n[sensitivity]\ncolumns = [{}]\n", quoted.join(", "))
}

/// The columns `names` of a study of `text`, each asserted exact.
fn exact_columns(text: &str, names: &[&str]) -> Vec<Vec<f64>> {
    let (_, report, study) =
        sensitivity::run("t.toml", &with_study(text, names), &[], &Options::default()).unwrap();
    let study = study.unwrap();
    names
        .iter()
        .map(|name| {
            let d = study.derivatives.iter().find(|d| d.name == *name).unwrap();
            assert_eq!(d.method, Method::Exact, "{name}");
            report.column(name).unwrap()
        })
        .collect()
}

fn largest(values: &[f64]) -> f64 {
    values.iter().fold(0.0, |m: f64, v| m.max(v.abs()))
}

#[test]
fn norton_exact_columns_agree_with_richardson_to_its_error_estimate_for_every_length() {
    for p in ["a", "b", "c", "d"] {
        let names = [
            format!("d(psi)/d({p})"),
            format!("d(psi')/d({p})"),
            format!("d(psi_dot)/d({p})"),
        ];
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        let exact = exact_columns(NORTON, &names);
        let value = match p {
            "a" => 0.86,
            "b" => 1.85,
            "c" => 0.86,
            _ => 2.22,
        };
        let parameter = Parameter {
            name: p.to_owned(),
            value,
            tolerance: None,
        };
        let r = sensitivity::extrapolated("t.toml", NORTON, &[], &parameter).unwrap();
        // Columns psi, psi', psi_dot are 1, 2, 3 of the table.
        for (j, column) in exact.iter().enumerate() {
            let k = j + 1;
            // The estimate printed: the column's largest disagreement of the last two
            // extrapolations, the error of the one before the last, an upper bound of the
            // last one's (by ~1000 here); plus 1e-14 of the column for the rounding of both.
            let bound = r.disagreement.iter().map(|d| d[k]).fold(0.0, f64::max);
            for (row, e) in column.iter().enumerate() {
                let diff = (e - r.values[row][k]).abs();
                assert!(
                    diff <= bound + 1e-14 * largest(column),
                    "d({k})/d({p}) row {row}: exact {e} vs Richardson {} (estimate {bound:e})",
                    r.values[row][k]
                );
            }
        }
    }
}

#[test]
fn a_parameter_through_a_formula_follows_the_chain_rule_exactly() {
    // b = 2a + 0.13 (1.85 at a = 0.86): d/da of the chained scene = ∂/∂a + 2 ∂/∂b of the
    // plain one.
    let chained = NORTON.replace("b = 1.85", "b = \"2*a + 0.13\"");
    let total = exact_columns(&chained, &["d(psi)/d(a)", "d(psi')/d(a)"]);
    let plain = exact_columns(
        NORTON,
        &["d(psi)/d(a)", "d(psi')/d(a)", "d(psi)/d(b)", "d(psi')/d(b)"],
    );
    for j in 0..2 {
        let scale = largest(&total[j]);
        for row in 0..total[j].len() {
            let want = plain[j][row] + 2.0 * plain[j + 2][row];
            // Two exact derivatives in f64, summed: a few roundings of the column's size.
            assert!(
                (total[j][row] - want).abs() <= 1e-13 * scale,
                "column {j} row {row}: {} vs {want}",
                total[j][row]
            );
        }
    }
}

#[test]
fn a_parameter_in_inches_is_differentiated_per_inch() {
    let inches = NORTON.replace("a = 0.86", "a = { value = \"0.86/0.0254\", unit = \"in\" }");
    let per_inch = exact_columns(&inches, &["d(psi)/d(a)", "d(psi')/d(a)"]);
    let per_metre = exact_columns(NORTON, &["d(psi)/d(a)", "d(psi')/d(a)"]);
    for j in 0..2 {
        let scale = largest(&per_metre[j]);
        for (row, (i, m)) in per_inch[j].iter().zip(&per_metre[j]).enumerate() {
            // 0.0254 m per inch; the scenes differ in a's last bit (0.86/0.0254·0.0254).
            assert!(
                (i - 0.0254 * m).abs() <= 1e-13 * 0.0254 * scale,
                "column {j} row {row}: {i} vs {}",
                0.0254 * m
            );
        }
    }
}

#[test]
fn a_velocity_by_the_drive_speed_is_the_velocity_coefficient() {
    // ψ̇ = ω·ψ′ with ω = w: ∂ψ̇/∂w = ψ′ (in the file's speed unit per w), and ∂ψ/∂w = 0.
    let text = NORTON
        .replace("speed = 10 ", "speed = \"w\" ")
        .replace("theta = 30", "theta = 30\nw = 10");
    let (_, report, study) = sensitivity::run(
        "t.toml",
        &with_study(&text, &["d(psi_dot)/d(w)", "d(psi)/d(w)"]),
        &[],
        &Options::default(),
    )
    .unwrap();
    assert!(study.unwrap().derivatives.iter().all(|d| d.is_exact()));
    let (got, zero) = (
        report.column("d(psi_dot)/d(w)").unwrap(),
        report.column("d(psi)/d(w)").unwrap(),
    );
    let psi1 = report.column("psi'").unwrap();
    for row in 0..got.len() {
        // One product in Dual64: ω·ψ′'s ε part is 1·ψ′ exactly.
        assert_eq!(got[row], psi1[row], "row {row}");
        assert_eq!(zero[row], 0.0, "row {row}");
    }
}
