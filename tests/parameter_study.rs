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
