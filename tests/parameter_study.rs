//! Issue 14, parameter studies: `--sweep NAME=FROM:TO:COUNT` runs a scene once per value
//! of a parameter and joins the tables, the parameter as the first column.

use mechdiff::Error;
use mechdiff::scene::{self, parameters::Setting, study};

/// Norton's four-bar from its lengths (the scene shipped in `scenes/`).
const NORTON: &str = include_str!("../scenes/norton_four_bar.toml");

#[test]
fn each_block_of_a_parameter_sweep_is_the_run_with_that_value_set() {
    let sweep: study::ParameterSweep = "b=1.95:1.85:3".parse().unwrap();
    let (_, joined) = study::run_sweep("norton.toml", NORTON, &[], &sweep).unwrap();
    assert_eq!(joined.columns[0].name, "b");
    assert_eq!(joined.columns[1].name, "phi");
    let mut rows = joined.rows.iter();
    // Downwards: 1.95, 1.9, 1.85 (1.95 + (1.85 - 1.95)·0.5 is 1.9 to one rounding).
    for b in [1.95, 1.9, 1.85] {
        let set = [Setting {
            name: "b".to_owned(),
            value: b.to_string(),
        }];
        let alone = scene::run(&scene::parse_with("norton.toml", NORTON, &set).unwrap()).unwrap();
        for want in &alone.rows {
            let got = rows.next().expect("a row per drive position and value");
            // 1e-15: the parameter column holds the value computed from the range, within
            // one rounding of the decimal written here.
            assert!((got[0] - b).abs() <= 1e-15, "{} vs {b}", got[0]);
            // The same scene text and value: the same computation, bit for bit, unless the
            // middle value differs from 1.9 by its rounding (then 1e-12: psi moves by at
            // most |dpsi/db|·1e-16 ≈ 1e-16 rad; the solver converges to 1e-13).
            for (x, y) in got[1..].iter().zip(want) {
                assert!(
                    (x - y).abs() <= 1e-12 * y.abs().max(1.0),
                    "b = {b}: {x} vs {y}"
                );
            }
        }
    }
    assert!(
        rows.next().is_none(),
        "3 values × 11 positions, no more rows"
    );
}

#[test]
fn the_swept_geometry_really_changes_the_coupler_length() {
    // An independent fact: at every row, |A B| is the swept b (A on the crank of length
    // a = 0.86 at angle phi; B from the output columns).
    let text = NORTON.replace(
        "quantities = [\"position\", \"velocity_coefficient\", \"velocity\"]",
        "quantities = [\"position\"]\n\n[[output]]\npoint = \"B\"\nquantities = [\"position\"]",
    );
    let sweep: study::ParameterSweep = "b=1.8,1.9,2.0".parse().unwrap();
    let (_, report) = study::run_sweep("norton.toml", &text, &[], &sweep).unwrap();
    let (b, phi) = (report.column("b").unwrap(), report.column("phi").unwrap());
    let (x, y) = (report.column("x_B").unwrap(), report.column("y_B").unwrap());
    for k in 0..b.len() {
        let (ax, ay) = (0.86 * phi[k].cos(), 0.86 * phi[k].sin());
        // 1e-12: the solver holds each joint to its convergence tolerance (1e-13 scale).
        assert!(
            ((x[k] - ax).hypot(y[k] - ay) - b[k]).abs() < 1e-12,
            "row {k}"
        );
    }
}

#[test]
fn a_sweep_that_fails_names_the_value_and_a_set_sweep_is_refused() {
    let sweep: study::ParameterSweep = "b=1.85,0.5".parse().unwrap();
    let e = study::run_sweep("norton.toml", NORTON, &[], &sweep).unwrap_err();
    assert!(matches!(e, Error::AtParameter { .. }), "{e:?}");
    assert!(
        e.to_string()
            .starts_with("with b=0.5 (of --sweep): norton.toml:"),
        "{e}"
    );
    assert!(e.to_string().contains("do not meet"), "{e}");
    let set = ["b=1.9".parse().unwrap()];
    let e = study::run_sweep("norton.toml", NORTON, &set, &sweep).unwrap_err();
    assert!(e.to_string().contains("both set and swept"), "{e}");
    let unknown: study::ParameterSweep = "q=1,2".parse().unwrap();
    let e = study::run_sweep("norton.toml", NORTON, &[], &unknown).unwrap_err();
    assert!(e.to_string().contains("no parameter `q`"), "{e}");
    // Named by the option that asked for it, not as a `--set`.
    assert!(e.to_string().starts_with("--sweep q: "), "{e}");
}

/// `mechdiff run NORTON --sweep b=1.85:1.95:3 --plot DIR --report FILE` with `[plot]
/// positions`, in the folder `dir` (the scene written there): the run's output.
fn study_pictures(dir: &std::path::Path) -> std::process::Output {
    std::fs::create_dir_all(dir).unwrap();
    let scene = dir.join("norton.toml");
    std::fs::write(&scene, format!("{NORTON}\n[plot]\npositions = [0, 50]\n")).unwrap();
    std::process::Command::new(env!("CARGO_BIN_EXE_mechdiff"))
        .args([
            "run",
            scene.to_str().unwrap(),
            "--sweep",
            "b=1.85:1.95:3",
            "--plot",
        ])
        .arg(dir.join("pictures"))
        .arg("--report")
        .arg(dir.join("study.html"))
        .output()
        .unwrap()
}

/// The texts of an SVG file and the x ranges of its plot frames.
fn svg_texts(path: &std::path::Path) -> (Vec<String>, Vec<(f64, f64)>) {
    let svg = std::fs::read_to_string(path).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let texts = (doc.descendants())
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text().map(|t| t.trim().to_owned()))
        .collect();
    let frames = (doc.descendants())
        .filter(|n| n.attribute("class") == Some("plot-frame"))
        .map(|n| {
            let at = |a| n.attribute(a).unwrap().parse::<f64>().unwrap();
            (at("data-x0"), at("data-x1"))
        })
        .collect();
    (texts, frames)
}

/// Issue 24, item 3: the pictures of a parameter study. Before: the swept parameter was
/// drawn on the crank-angle axis, each panel carried the previous column's unit, and a
/// `[plot] positions` list failed with "drive position 0 deg is outside the sweep
/// (105.99… deg to 111.72… deg)" (the values of b read as radians). Now, parsed from the
/// SVGs: the diagram's x axis is the drive φ [deg] over the sweep's 0°–100° (each frame's
/// data range holds it and no more than 5 % padding beyond), each panel is labelled with its
/// own column's unit, one curve per value with a legend `b = …`; the drawings at the
/// `[plot] positions` are written; `sweep_summary.svg` draws the headline numbers against
/// `b [as set]`; and `--report` holds the same families.
#[test]
fn a_parameter_studys_pictures_are_families_on_the_drive_axis() {
    let dir = std::env::temp_dir().join(format!("mechdiff-study-{}", std::process::id()));
    let out = study_pictures(&dir);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let pictures = dir.join("pictures");
    let (texts, frames) = svg_texts(&pictures.join("diagram.svg"));
    assert!(texts.iter().any(|t| t == "φ [deg]"), "{texts:?}");
    assert!(!frames.is_empty());
    for (x0, x1) in &frames {
        assert!(
            *x0 <= 0.0 && *x0 >= -5.0 && *x1 >= 100.0 && *x1 <= 105.0,
            "{x0}..{x1}"
        );
    }
    // Each column's label with its own unit (psi: deg; psi': deg/deg; psi_dot: rad/s).
    let sweep: study::ParameterSweep = "b=1.85:1.95:3".parse().unwrap();
    let (_, report) = study::run_sweep("norton.toml", NORTON, &[], &sweep).unwrap();
    let symbol = mechdiff::pictures::symbols::symbol;
    let columns = &report.columns;
    assert_eq!(columns.len(), 5, "b, phi, psi, psi', psi_dot");
    for k in 2..columns.len() {
        let label = format!("{} [{}]", symbol(&columns[k].name), columns[k].unit);
        assert!(texts.contains(&label), "{label} not in {texts:?}");
        if columns[k - 1].unit != columns[k].unit {
            let wrong = format!("{} [{}]", symbol(&columns[k].name), columns[k - 1].unit);
            assert!(!texts.contains(&wrong), "{wrong} in {texts:?}");
        }
    }
    for value in ["b = 1.85", "b = 1.9", "b = 1.95"] {
        assert!(texts.iter().any(|t| t == value), "{value} not in {texts:?}");
    }
    for file in [
        "mechanism_at_0_deg.svg",
        "mechanism_at_50_deg.svg",
        "sweep_summary.svg",
    ] {
        assert!(pictures.join(file).exists(), "{file}");
    }
    // `--report` alone draws the same families.
    let report_html = std::fs::read_to_string(dir.join("study.html")).unwrap();
    assert!(report_html.contains("b = 1.9") && report_html.contains("ψ\u{307} [rad/s]"));
    let (texts, frames) = svg_texts(&pictures.join("sweep_summary.svg"));
    assert!(
        texts.iter().any(|t| t == "min μ_eff rocker [deg]"),
        "{texts:?}"
    );
    assert!(texts.iter().any(|t| t == "b [as set]"), "{texts:?}");
    assert!(texts.iter().any(|t| t == "Δψ [deg]"), "{texts:?}");
    for (x0, x1) in &frames {
        assert!(*x0 <= 1.85 && *x1 >= 1.95 && *x1 <= 2.0, "{x0}..{x1}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
