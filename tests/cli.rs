//! `mechdiff run` and `mechdiff check` as a user calls them: exit status, what is printed,
//! and the CSV file; a scene's text reaches the terminal and generated code escaped.

use std::path::Path;

use mechdiff::scene;

use crate::common;
use common::{mechdiff, scene_path, stderr, stdout, temp_file};

/// The table of the offset slider-crank (millimetres, rpm): plan line, headers with units,
/// 73 rows, dead positions and stroke. Snapshot of what a user sees.
#[test]
fn run_prints_the_plan_the_table_and_the_dead_positions() {
    let output = mechdiff(&["run", "scenes/slider_crank.toml"]);
    assert!(output.status.success(), "{}", stderr(&output));
    insta::assert_snapshot!(stdout(&output));
}

/// `--csv`: one column per output quantity, `name [unit]` headers, every value in the scene's
/// units with all its digits: read back and converted to SI, each equals the library's value
/// to 1 ulp (one division and one multiplication by the unit factor).
#[test]
fn run_writes_csv_with_named_columns_and_full_precision() {
    let csv = temp_file("slider_crank.csv");
    let output = mechdiff(&[
        "run",
        "scenes/slider_crank.toml",
        "--csv",
        csv.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = std::fs::read_to_string(&csv).unwrap();
    std::fs::remove_file(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "phi [deg],s [mm],s' [mm/rad],s'' [mm/rad^2],s_dot [mm/s],s_ddot [mm/s^2],beta [deg],beta_dot [rad/s],beta_ddot [rad/s^2]"
    );
    let scene = scene::load(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/slider_crank.toml"))
        .unwrap();
    let report = scene::run(&scene).unwrap();
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), 73);
    for (line, row) in rows.iter().zip(&report.rows) {
        let cells: Vec<f64> = line.split(',').map(|c| c.parse().unwrap()).collect();
        assert_eq!(cells.len(), report.columns.len());
        for ((cell, si), column) in cells.iter().zip(row).zip(&report.columns) {
            let back = cell * column.factor;
            assert!(
                (back - si).abs() <= 2.0 * f64::EPSILON * si.abs(),
                "{} {cell} vs {si}",
                column.name
            );
        }
    }
}

#[test]
fn check_validates_without_running() {
    let output = mechdiff(&["check", "scenes/whitworth.toml"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    assert!(
        text.starts_with("scenes/whitworth.toml: ok: 7 points, 4 links"),
        "{text}"
    );
    assert!(text.contains("1 degree(s) of freedom"), "{text}");
    assert!(
        text.contains("plan: 721 drive positions, phi from 0 deg to 360 deg"),
        "{text}"
    );
}

#[test]
fn a_bad_scene_fails_with_its_location_on_stderr() {
    let bad = temp_file("bad.toml");
    let text =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/four_bar.toml"))
            .unwrap()
            .replace(
                r#"angular_velocity = "rad/s""#,
                r#"angular_velocity = "rps""#,
            );
    std::fs::write(&bad, text).unwrap();
    for command in ["check", "run"] {
        let output = mechdiff(&[command, bad.to_str().unwrap()]);
        assert!(!output.status.success());
        let message = stderr(&output);
        let expected = format!("error: {}:13:20: unknown value `rps`", bad.display());
        assert!(message.starts_with(&expected), "{message}");
        assert!(
            message.contains("expected one of `rad/s`, `deg/s`, `rpm`"),
            "{message}"
        );
    }
    std::fs::remove_file(&bad).unwrap();
}

#[test]
fn a_missing_scene_file_is_an_error_not_a_panic() {
    let output = mechdiff(&["run", "scenes/no_such_scene.toml"]);
    assert!(!output.status.success());
    assert!(
        stderr(&output).starts_with("error: cannot read scenes/no_such_scene.toml"),
        "{}",
        stderr(&output)
    );
}

#[test]
fn check_lists_every_links_lengths_with_set_applied() {
    let output = mechdiff(&["check", "scenes/norton_four_bar.toml", "--set", "b=1.9"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    // The lengths are the parameters, tidied to 15 digits (the construction rounds them
    // by a few ulps).
    for line in [
        "parameter b = 1.9",
        "length ground: O2–O4 = 2.22 m",
        "length crank: O2–A = 0.86 m",
        "length coupler: A–B = 1.9 m",
        "length rocker: O4–B = 0.86 m",
    ] {
        assert!(text.contains(line), "`{line}` missing from: {text}");
    }
    let output = mechdiff(&["check", "scenes/norton_four_bar.toml", "--set", "e=1"]);
    assert!(!output.status.success());
    assert!(stderr(&output).contains("--set e=1: the scene has no parameter `e`"));
}

#[test]
fn run_sweep_prints_one_long_table_with_the_parameter_first() {
    let output = mechdiff(&[
        "run",
        "scenes/norton_four_bar.toml",
        "--sweep",
        "b=1.85:1.95:3",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    let header = text.lines().find(|l| l.contains("psi_dot")).unwrap();
    assert!(header.trim_start().starts_with("b "), "{header}");
    // 3 values × 11 drive positions, each row starting with its b.
    let rows = text
        .lines()
        .filter(|l| l.trim_start().starts_with("1."))
        .count();
    assert_eq!(rows, 33, "{text}");
    let output = mechdiff(&["run", "scenes/norton_four_bar.toml", "--sweep", "b=1:2"]);
    assert!(!output.status.success());
    assert!(
        stderr(&output).contains("NAME=FROM:TO:COUNT"),
        "{}",
        stderr(&output)
    );
}

/// Issue 22: ESC sequences (and BEL) in a title, an output's name, an unknown name quoted by
/// an error and the scene's path reach the terminal as text (`\u{1b}`), never as the raw
/// byte 0x1b a terminal would obey.
#[test]
fn control_characters_reach_the_terminal_escaped() {
    let text = std::fs::read_to_string(scene_path("slider_crank.toml")).unwrap();
    let line = "title = \"Offset slider-crank, r = 100 mm, l = 400 mm, e = -12 mm\"";
    assert!(text.contains(line) && text.contains("name = \"s\"\n"));
    let text = text
        .replace(line, r#"title = "T\u001b[31mRED\u0007""#)
        .replace("name = \"s\"\n", "name = \"s\\u001b[2J\"\n");
    let path = temp_file("esc\u{1b}]0;title\u{7}.toml");
    std::fs::write(&path, &text).unwrap();
    let file = path.to_str().unwrap();
    let shown = file.replace('\u{1b}', r"\u{1b}").replace('\u{7}', r"\u{7}");
    let no_escape = |output: &std::process::Output| {
        assert!(!output.stdout.contains(&0x1b) && !output.stderr.contains(&0x1b));
        assert!(!output.stdout.contains(&0x07) && !output.stderr.contains(&0x07));
    };
    let run = mechdiff(&["run", file]);
    assert!(run.status.success(), "{}", stderr(&run));
    no_escape(&run);
    let printed = stdout(&run);
    assert!(printed.starts_with(r"T\u{1b}[31mRED\u{7}"), "{printed}");
    assert!(printed.contains(r"s\u{1b}[2J"), "{printed}");
    let check = mechdiff(&["check", file]);
    assert!(check.status.success(), "{}", stderr(&check));
    no_escape(&check);
    assert!(stdout(&check).starts_with(&format!("{shown}: ok")));
    let bad = text.replace("joint = \"O\"", "joint = \"\\u001b]0;owned\\u0007\"");
    assert_ne!(bad, text);
    std::fs::write(&path, bad).unwrap();
    let error = mechdiff(&["run", file]);
    assert!(!error.status.success());
    no_escape(&error);
    assert!(
        stderr(&error).contains(r"\u{1b}]0;owned\u{7}"),
        "{}",
        stderr(&error)
    );
    std::fs::remove_file(&path).unwrap();
}

/// Issue 22: a scene path holding a newline (and `*/`) is shown in `mechdiff codegen`'s
/// header as `\u{a}`, so it stays in the comment: no line of the module starts with the
/// code the path carries, and every line holding it is a comment.
#[test]
fn a_newline_in_the_scene_path_cannot_add_a_line_of_rust() {
    // A folder `…x⏎fn injected() {} *` holding `s.toml`: the path holds `*/` too.
    let dir = temp_file("x\nfn injected() {} *");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("s.toml");
    std::fs::copy(scene_path("slider_crank.toml"), &path).unwrap();
    let output = mechdiff(&["codegen", path.to_str().unwrap()]);
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(output.status.success(), "{}", stderr(&output));
    let module = stdout(&output);
    let first = module.lines().next().unwrap();
    assert!(
        first.starts_with("// Generated by `mechdiff codegen "),
        "{first}"
    );
    assert!(
        first.contains(r"x\u{a}fn injected() {} */s.toml"),
        "{first}"
    );
    for line in module.lines().filter(|l| l.contains("injected")) {
        assert!(line.starts_with("//"), "{line}");
    }
    assert!(module.contains("pub fn pose("));
}

/// Issue 22, item 8: `check` gives every error `run` gives before solving — a drive speed of
/// 0 for a power balance or for counterweights, counterweights on a link without mass data
/// or of a radius whose mass would overflow — and refuses a sweep past the limit
/// position of the motion range it prints itself, as `run` does when it reaches it.
#[test]
fn check_refuses_what_run_refuses_before_solving() {
    let cases = [
        (
            "rack_slotted_link_dynamics.toml",
            "speed = ",
            "speed = 0 #",
            "non-zero drive `speed`",
        ),
        (
            "whitworth_balancing.toml",
            "speed = ",
            "speed = 0 #",
            "non-zero `speed`",
        ),
        (
            "norton_four_bar.toml",
            "to = 100",
            "to = 200",
            "116.037128629205 deg",
        ),
        // Found by the fuzz test: run refused these before solving, check accepted them.
        (
            "whitworth_balancing.toml",
            "crank = { mass = 15, center = \"S1\" }\n",
            "",
            "link(s) crank have none",
        ),
        (
            "whitworth_balancing.toml",
            "radius = 0.1 }",
            "radius = 5e-324 }",
            "expected at least 1e-9 m",
        ),
    ];
    for (name, from, to, expected) in cases {
        let text = std::fs::read_to_string(common::scene_path(name)).unwrap();
        assert!(text.contains(from), "{name}");
        let scene = temp_file(name);
        std::fs::write(&scene, text.replacen(from, to, 1)).unwrap();
        let path = scene.to_str().unwrap();
        let checked = mechdiff(&["check", path]);
        let ran = mechdiff(&["run", path]);
        std::fs::remove_file(&scene).unwrap();
        for output in [&checked, &ran] {
            assert!(!output.status.success(), "{name}: {}", stdout(output));
            assert!(
                stderr(output).contains(expected),
                "{name}: {}",
                stderr(output)
            );
        }
        // `check` refuses before it prints anything.
        assert!(stdout(&checked).is_empty(), "{name}: {}", stdout(&checked));
    }
}

/// Every shipped formula scene passes `check` (they were all refused with "unknown field
/// `outputs`" while `run` accepted them), and `check` prints what it found.
#[test]
fn check_accepts_the_formula_scenes() {
    for folder in ["scenes/hard", "scenes/formulas"] {
        for entry in std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join(folder)).unwrap()
        {
            let path = entry.unwrap().path();
            let output = mechdiff(&["check", path.to_str().unwrap()]);
            assert!(
                output.status.success(),
                "{}: {}",
                path.display(),
                stderr(&output)
            );
            assert!(
                stdout(&output).contains("ok: formula scene of"),
                "{}",
                stdout(&output)
            );
        }
    }
}

/// Issue 22: counts a user writes on the command line are bounded before any work starts
/// (`--monte-carlo 18446744073709551615` panicked, 4e9 aborted, `--repeats 1e9` aborted,
/// `--threads 2^64-1` ran for 30 s): each is refused at once, the message naming the
/// option, the value given and the limit.
#[test]
fn counts_over_their_limits_are_refused_before_any_work() {
    let cases: [(&[&str], &str, &str); 5] = [
        (
            &[
                "run",
                "scenes/four_bar.toml",
                "--monte-carlo",
                "18446744073709551615",
            ],
            "'18446744073709551615' for '--monte-carlo <N>'",
            "0..=1000000",
        ),
        (
            &["run", "scenes/four_bar.toml", "--monte-carlo", "4000000000"],
            "'4000000000' for '--monte-carlo <N>'",
            "0..=1000000",
        ),
        (
            &[
                "run",
                "scenes/four_bar.toml",
                "--threads",
                "18446744073709551615",
            ],
            "'18446744073709551615' for '--threads <N>'",
            "0..=1024",
        ),
        (
            &["accuracy", "whitworth", "--repeats", "1000000000"],
            "'1000000000' for '--repeats <REPEATS>'",
            "0..=1000",
        ),
        (
            &["run", "scenes/four_bar.toml", "--threads=-1"],
            "'-1' for '--threads <N>'",
            "",
        ),
    ];
    for (args, value, limit) in cases {
        let output = mechdiff(args);
        let err = stderr(&output);
        assert!(!output.status.success(), "{args:?} was accepted");
        assert!(
            err.contains(value) && err.contains(limit),
            "{args:?}: {err}"
        );
        assert!(!err.contains("panicked"), "{err}");
    }
}

/// Issue 22: a point named `P,Q` used as an output made a CSV of 18 header fields over
/// 12-field rows. The header is now written by the `csv` crate: the names with a comma are
/// quoted (and their quotes doubled), and the `csv` crate reads the file back with 12 fields in every record and the
/// names as written; the table a library user writes (`table::write_csv`) is the same.
#[test]
fn a_name_with_a_comma_or_a_quote_stays_one_csv_field() {
    let text = std::fs::read_to_string("scenes/four_bar.toml")
        .unwrap()
        .replace("\nP = [", "\n'P,\"Q\"' = [")
        .replace("\"B\", \"P\"]", "\"B\", 'P,\"Q\"']")
        .replace("point = \"P\"", "point = 'P,\"Q\"'");
    let scene_file = temp_file("comma_names.toml");
    std::fs::write(&scene_file, &text).unwrap();
    let csv_file = temp_file("comma_names.csv");
    let output = mechdiff(&[
        "run",
        scene_file.to_str().unwrap(),
        "--csv",
        csv_file.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let written = std::fs::read(&csv_file).unwrap();
    std::fs::remove_file(&csv_file).unwrap();
    std::fs::remove_file(&scene_file).unwrap();
    let read_back = |bytes: &[u8]| {
        let mut reader = csv::Reader::from_reader(bytes);
        let header: Vec<String> = reader
            .headers()
            .unwrap()
            .iter()
            .map(str::to_owned)
            .collect();
        let rows: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
        (header, rows)
    };
    let (header, rows) = read_back(&written);
    assert_eq!(header.len(), 12);
    assert_eq!(header[1], "psi [deg]");
    assert_eq!(header[6], "x_P,\"Q\" [m]");
    assert_eq!(header[11], "ay_P,\"Q\" [m/s^2]");
    assert_eq!(rows.len(), 73);
    assert!(rows.iter().all(|r| r.len() == 12));
    // The library's writer gives the same bytes.
    let report = scene::run(&scene::parse("comma_names.toml", &text).unwrap()).unwrap();
    let mut library = Vec::new();
    scene::table::write_csv(&report, &mut library).unwrap();
    assert_eq!(library, written);
}
