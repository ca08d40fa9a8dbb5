//! `mechdiff run` and `mechdiff check` as a user calls them: exit status, what is printed,
//! and the CSV file.

use std::path::Path;

use mechdiff::scene;

mod common;
use common::{mechdiff, stderr, stdout, temp_file};

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
