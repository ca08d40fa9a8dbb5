//! `mechdiff run` of a formula scene (`scenes/hard/`): the outputs and their derivatives to
//! order 3 at each drive position, the limit taken where the formula is 0/0 or a power meets
//! a zero base — with a note naming the position — and a typed error naming the position
//! where there is no limit. Never NaN.

use crate::common;
use common::{mechdiff, stderr, stdout, temp_file};

/// The CSV rows of `run <scene> --csv`, as numbers (header checked by the caller).
fn csv_rows(scene: &str) -> (String, Vec<Vec<f64>>, String) {
    let csv = temp_file(&format!("{}.csv", scene.replace('/', "_")));
    let output = mechdiff(&["run", scene, "--csv", csv.to_str().unwrap()]);
    assert!(output.status.success(), "{scene}: {}", stderr(&output));
    let text = std::fs::read_to_string(&csv).unwrap();
    std::fs::remove_file(&csv).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().to_owned();
    let rows = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    (header, rows, stdout(&output))
}

/// sin φ / φ swept through 0: the row at 0 is the limit 1, 0, −1/3, 0 (1e-13 relative,
/// absolute for a zero: a few roundings in an 8-term series of O(1) coefficients), the note
/// names the position, nothing is NaN.
#[test]
fn run_of_a_removable_singularity_takes_the_limit_with_a_note() {
    let (header, rows, printed) = csv_rows("scenes/hard/removable_sinc_unguarded.toml");
    assert_eq!(header, "phi [rad],sinc,sinc',sinc'',sinc'''");
    let zero = rows.iter().find(|r| r[0] == 0.0).expect("φ = 0 is swept");
    for (got, want) in zero[1..].iter().zip([1.0, 0.0, -1.0 / 3.0, 0.0]) {
        let scale = if want == 0.0 { 1.0 } else { f64::abs(want) };
        assert!((got - want).abs() <= 1e-13 * scale, "{got} vs {want}");
    }
    assert!(
        printed.contains("note: removable singularity at φ = 0 rad: limit taken"),
        "{printed}"
    );
    assert!(
        !printed.contains("NaN") && !printed.contains("inf"),
        "{printed}"
    );
}

/// φ^3.5 from 0: the one-sided limit (all 0) with a note saying it is one-sided.
#[test]
fn run_of_a_one_sided_power_says_one_sided() {
    let (_, rows, printed) = csv_rows("scenes/hard/one_sided_power.toml");
    assert_eq!(rows[0][0], 0.0);
    assert!(rows[0][1..].iter().all(|&x| x == 0.0), "{:?}", rows[0]);
    assert!(
        printed.contains("note: one-sided limit at φ = 0 rad (real only for φ ≥ 0)"),
        "{printed}"
    );
}

/// 1/φ through 0 and sqrt(φ²) = |φ| at 0: no limit (a pole; one-sided derivatives that
/// differ): the run fails, naming the position and the reason, and prints no table.
#[test]
fn run_without_a_limit_fails_naming_the_position() {
    for (formula, reason) in [
        ("1/phi", "`y`, derivative order 0"),
        ("sqrt(phi^2)", "differ on the two sides"),
    ] {
        let scene = temp_file(&format!("{}.toml", formula.len()));
        std::fs::write(
            &scene,
            format!(
                "title = \"t\"\n[outputs]\ny = \"{formula}\"\n[sweep]\nfrom = -1\nto = 1\n\
                 step = 0.5\nunit = \"rad\"\n"
            ),
        )
        .unwrap();
        let output = mechdiff(&["run", scene.to_str().unwrap()]);
        std::fs::remove_file(&scene).unwrap();
        assert!(!output.status.success(), "{formula}");
        let message = stderr(&output);
        for part in ["φ = 0 rad", reason] {
            assert!(
                message.contains(part),
                "{formula}: `{part}` missing: {message}"
            );
        }
        assert!(stdout(&output).is_empty());
    }
}

/// A formula scene has no `[parameters]` to sweep from the command line in `run`: options
/// other than `--csv` are refused by name, not ignored.
#[test]
fn run_of_a_formula_scene_refuses_options_it_cannot_honour() {
    let output = mechdiff(&[
        "run",
        "scenes/hard/removable_sinc_unguarded.toml",
        "--json",
        "x.json",
    ]);
    assert!(!output.status.success());
    assert!(
        stderr(&output).contains("--json does not apply"),
        "{}",
        stderr(&output)
    );
}

/// Options added for linkages (`--monte-carlo`, `--evaluator`) are refused for a formula
/// scene too (the table of refused options is one for every kind of scene).
#[test]
fn run_of_a_formula_scene_refuses_linkage_only_options() {
    for options in [
        &["--monte-carlo", "10"][..],
        &["--evaluator", "program"][..],
    ] {
        let mut args = vec!["run", "scenes/hard/removable_sinc_unguarded.toml"];
        args.extend_from_slice(options);
        let output = mechdiff(&args);
        assert!(!output.status.success(), "{options:?}");
        assert!(
            stderr(&output).contains(&format!("{} does not apply", options[0])),
            "{}",
            stderr(&output)
        );
    }
}

/// Runs `mechdiff` with `args` in a thread, failing if it takes more than a minute (a
/// debug build runs these in well under a second; `10*atan2(1,1)` once never returned).
fn mechdiff_within_a_minute(args: &[&str]) -> std::process::Output {
    let args: Vec<String> = args.iter().map(|a| a.to_string()).collect();
    let (done, wait) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let _ = done.send(mechdiff(&args));
    });
    wait.recv_timeout(std::time::Duration::from_secs(60))
        .expect("mechdiff did not return within a minute")
}

/// Issue 22: tanh(φ) at ±800 has finite derivatives (sech² = 4e^-1600/(1 + e^-1600)²
/// underflows gracefully to 0; 1/cosh² gave NaN for ψ″, ψ‴), and a constant
/// `10*atan2(1,1)` runs promptly with its value 10π/4 (to 1 ulp of its f64 evaluation).
#[test]
fn run_of_tanh_far_out_and_a_constant_atan2_is_finite_and_prompt() {
    let scene = temp_file("tanh_far_out.toml");
    std::fs::write(
        &scene,
        "title = \"tanh far out\"\n[outputs]\ny = \"tanh(phi)\"\nz = \"10*atan2(1,1) + phi\"\n\
         [sweep]\nfrom = -800\nto = 800\nstep = 400\nunit = \"rad\"\n",
    )
    .unwrap();
    let csv = temp_file("tanh_far_out.csv");
    let output = mechdiff_within_a_minute(&[
        "run",
        scene.to_str().unwrap(),
        "--csv",
        csv.to_str().unwrap(),
    ]);
    std::fs::remove_file(&scene).unwrap();
    assert!(output.status.success(), "{}", stderr(&output));
    let text = std::fs::read_to_string(&csv).unwrap();
    std::fs::remove_file(&csv).unwrap();
    let rows: Vec<Vec<f64>> = (text.lines().skip(1))
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    let quarter_turns = 10.0 * std::f64::consts::FRAC_PI_4;
    for row in &rows {
        let phi = row[0];
        let y = if phi == 0.0 {
            [0.0, 1.0, 0.0, -2.0]
        } else {
            [phi.signum(), 0.0, 0.0, 0.0]
        };
        assert_eq!(&row[1..5], &y, "tanh at φ = {phi}: {row:?}");
        let z = quarter_turns + phi;
        assert!((row[5] - z).abs() <= f64::EPSILON * z.abs(), "{row:?}");
        assert_eq!(&row[6..9], &[1.0, 0.0, 0.0], "{row:?}");
    }
    assert_eq!(rows.len(), 5);
}

/// A linkage scene whose drive speed is the formula `10*atan2(1,1)` is checked and run
/// promptly (both once hung), the speed its value 10π/4 rad/s.
#[test]
fn check_and_run_of_a_constant_atan2_in_a_linkage_are_prompt() {
    let text = std::fs::read_to_string("scenes/four_bar.toml")
        .unwrap()
        .replace("speed = 10 ", "speed = \"10*atan2(1,1)\" ");
    assert!(text.contains("10*atan2"));
    let scene = temp_file("four_bar_atan2.toml");
    std::fs::write(&scene, text).unwrap();
    let check = mechdiff_within_a_minute(&["check", scene.to_str().unwrap()]);
    let run = mechdiff_within_a_minute(&["run", scene.to_str().unwrap()]);
    std::fs::remove_file(&scene).unwrap();
    assert!(check.status.success(), "{}", stderr(&check));
    assert!(run.status.success(), "{}", stderr(&run));
}
