//! `mechdiff accuracy` as a user calls it: the table, the CSV and SVG files, the errors.

use crate::common;
use common::{mechdiff, temp_file};

/// `mechdiff accuracy whitworth` prints one row per method — every exact method and the
/// finite differences at their best steps — and the step scans with the best step of each
/// scheme.
#[test]
fn whitworth_table_lists_every_method_and_the_best_steps() {
    let output = mechdiff(&["accuracy", "whitworth", "--repeats", "1"]);
    assert!(output.status.success());
    let text = String::from_utf8(output.stdout).unwrap();
    for method in [
        "hand-derived",
        "symbolic (generated)",
        "Dual1",
        "Dual2",
        "HyperDual",
        "Dual3",
        "geometry closed form",
        "geometry Newton + implicit",
        "central h=",
        "forward h=",
        "Richardson h=",
        "central: best h",
    ] {
        assert!(text.contains(method), "{method} missing:\n{text}");
    }
    assert!(!text.contains("FAILED"), "{text}");
}

/// A formula scene with `--csv` and `--svg`: both files are written (CSV: the header and one
/// row per method and per scanned step, 17 columns each; SVG: two `<svg` documents, the
/// second named `…-angle.svg`).
#[test]
fn formula_scene_writes_csv_and_svg() {
    let (csv, svg) = (temp_file("dwell.csv"), temp_file("dwell.svg"));
    let output = mechdiff(&[
        "accuracy",
        "scenes/hard/dwell_dead_position.toml",
        "--repeats",
        "1",
        "--csv",
        csv.to_str().unwrap(),
        "--svg",
        svg.to_str().unwrap(),
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let table = std::fs::read_to_string(&csv).unwrap();
    let mut lines = table.lines();
    assert!(
        lines
            .next()
            .unwrap()
            .starts_with("method,kind,step,order,time_median_s")
    );
    let rows: Vec<&str> = lines.collect();
    // 5 exact methods, at least one row per scheme, 3 × 37 scanned steps.
    assert!(rows.len() >= 5 + 3 + 3 * 37, "{} rows", rows.len());
    assert!(rows.iter().all(|r| r.matches(',').count() == 16), "{table}");
    assert!(std::fs::read_to_string(&svg).unwrap().contains("<svg"));
    let angle = svg.with_file_name(format!(
        "{}-angle.svg",
        svg.file_stem().unwrap().to_string_lossy()
    ));
    assert!(std::fs::read_to_string(&angle).unwrap().contains("<svg"));
    let _ = (
        std::fs::remove_file(csv),
        std::fs::remove_file(svg),
        std::fs::remove_file(angle),
    );
}

/// A mechanism scene (points, links, joints) whose loops all have closed forms is measured:
/// both geometry paths, the symbolic run-time evaluator and the finite differences, against
/// the double-double reference named under the title.
#[test]
fn mechanism_scene_is_measured() {
    let output = mechdiff(&["accuracy", "scenes/slider_crank.toml", "--repeats", "1"]);
    assert!(output.status.success(), "{output:?}");
    let text = String::from_utf8(output.stdout).unwrap();
    for part in [
        "double-double",
        "geometry closed form",
        "geometry Newton + implicit",
        "symbolic (run-time evaluator)",
        "central h=",
        "Richardson: best h",
    ] {
        assert!(text.contains(part), "{part} missing:\n{text}");
    }
}

/// A mixed plan (a closed-form crank driving a triad solved by Newton) is measured by the
/// geometry methods against the double-double Newton reference; the run-time evaluator's
/// row, which evaluates each position on its own, says why it is not measured.
#[test]
fn mixed_plan_is_measured_and_the_evaluator_row_says_why_not() {
    let output = mechdiff(&[
        "accuracy",
        "tests/data/triad_slider.toml",
        "--repeats",
        "1",
        "--positions",
        "2",
    ]);
    assert!(output.status.success(), "{output:?}");
    let text = String::from_utf8(output.stdout).unwrap();
    for part in [
        "Newton and implicit derivatives in double-double",
        "geometry closed form + Newton (mixed)",
        "symbolic (run-time evaluator): not measured: a mixed plan: the loop [A, B, C, D, G2, \
         G3] is solved by Newton inside the evaluator",
    ] {
        assert!(text.contains(part), "{part} missing:\n{text}");
    }
}

/// A cam scene is measured (its laws by the dual-number methods against the program in
/// double-double), and a rotor scene gets its table of balancing answers, with the line that
/// says why it has no method table; `--svg` is refused for the rotor (nothing to plot).
#[test]
fn cam_and_rotor_scenes_are_measured() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes");
    let cam = format!("{dir}/cams/rise_dwell_return_dwell.toml");
    let output = mechdiff(&["accuracy", &cam, "--repeats", "1", "--positions", "5"]);
    assert!(output.status.success(), "{output:?}");
    let text = String::from_utf8(output.stdout).unwrap();
    for part in [
        "Dual1",
        "Dual3",
        "HyperDual",
        "central h=",
        "right-hand limit",
    ] {
        assert!(text.contains(part), "{part} missing:\n{text}");
    }
    let rotor = format!("{dir}/rotor_balancing.toml");
    let output = mechdiff(&["accuracy", &rotor]);
    assert!(output.status.success(), "{output:?}");
    let text = String::from_utf8(output.stdout).unwrap();
    for part in [
        "no method table",
        "two-plane correction, plane 1: m·r",
        "negligible",
    ] {
        assert!(text.contains(part), "{part} missing:\n{text}");
    }
    let svg = temp_file("rotor.svg");
    let output = mechdiff(&["accuracy", &rotor, "--svg", svg.to_str().unwrap()]);
    assert!(!output.status.success());
    let message = String::from_utf8(output.stderr).unwrap();
    assert!(message.contains("no drive sweep"), "{message}");
    assert!(!svg.exists());
}

/// A formula with an unknown symbol names the file, the output and the symbol.
#[test]
fn unknown_symbol_is_named_with_the_file() {
    let path = temp_file("bad.toml");
    std::fs::write(
        &path,
        "title = \"t\"\n[outputs]\ny = \"sin(phi)*k\"\n[sweep]\nfrom = 0\nto = 10\nstep = 5\n",
    )
    .unwrap();
    let output = mechdiff(&["accuracy", path.to_str().unwrap()]);
    assert!(!output.status.success());
    let message = String::from_utf8(output.stderr).unwrap();
    assert!(
        message.contains("bad.toml") && message.contains("[outputs] y") && message.contains("`k`"),
        "{message}"
    );
    let _ = std::fs::remove_file(path);
}

/// A bare quotient swept through its 0/0 (sin φ/φ at 0) is measured: the limit is taken
/// there and the report says so, never silently.
#[test]
fn removable_singularity_is_measured_with_the_limit_flagged() {
    let output = mechdiff(&[
        "accuracy",
        "scenes/hard/removable_sinc_unguarded.toml",
        "--repeats",
        "1",
    ]);
    assert!(output.status.success(), "{output:?}");
    let text = String::from_utf8(output.stdout).unwrap();
    for part in [
        "removable singularity at φ = 0 rad: limit taken",
        "Dual3 (evaluator)",
    ] {
        assert!(text.contains(part), "{part} missing:\n{text}");
    }
    assert!(!text.contains("NaN"), "{text}");
}
