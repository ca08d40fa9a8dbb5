//! `mechdiff synthesize` and the `[synthesize]` section: the shipped scenes' known answers
//! recovered, the scene written with the parameters found run as is, the residual table
//! against the objective, and bad input (unknown names, bounds that exclude every assembly,
//! targets out of reach, zero and huge limits) answered with located errors, never a hang.
//!
//! The known answers are the dimensions the targets were computed from (in Python, by the
//! closed form written out in each scene's comment, 17 digits); the scene run checks the
//! answer with the scene's own geometry solver (Newton on the sketch's constraints), a
//! route independent of the synthesis's closed forms.

use std::time::Duration;

use mechdiff::Error;
use mechdiff::scene::{self, synthesize};
use mechdiff_core::synthesis::{Report, StopReason};

use crate::common::{column, mechdiff, scene_path, stderr, stdout, temp_file};

/// A shipped scene's text.
pub(crate) fn text(name: &str) -> String {
    std::fs::read_to_string(scene_path(name)).unwrap()
}

/// Reads `text` as the scene `name` and runs its synthesis with the section's settings.
pub(crate) fn solve(name: &str, text: &str) -> (synthesize::Setup, Report) {
    let setup = synthesize::read(name, text).unwrap_or_else(|e| panic!("{e}"));
    let report = setup
        .solve(&setup.settings)
        .unwrap_or_else(|e| panic!("{e}"));
    (setup, report)
}

/// Asserts the objective ≤ 1e-20 and every `known` value (in the file's units) to 1e-9
/// (dimensions of order 1 m; angles in degrees, 1e-9 deg is far below the 1e-12 the
/// objective allows).
fn assert_known(setup: &synthesize::Setup, report: &Report, known: &[(&str, f64)]) {
    assert!(report.objective <= 1e-20, "objective {}", report.objective);
    for (name, value) in known {
        let k = (setup.variables.iter())
            .position(|v| v.parameter.as_deref().unwrap_or(&v.name) == *name)
            .unwrap_or_else(|| panic!("no variable {name}"));
        let found = setup.in_file_units(report, k);
        assert!(
            (found - value).abs() <= 1e-9,
            "{name}: {found} against {value}"
        );
    }
}

const PATH: &str = "synthesis_four_bar_path.toml";
const FUNCTION: &str = "synthesis_four_bar_function.toml";
const MOTION: &str = "synthesis_four_bar_motion.toml";

/// The four-bar the path and motion targets come from (m), see the scenes' comments.
const FOUR_BAR: [(&str, f64); 9] = [
    ("o2x", 0.0),
    ("o2y", 0.0),
    ("o4x", 1.2),
    ("o4y", 0.1),
    ("crank", 0.4),
    ("coupler", 1.1),
    ("rocker", 0.9),
    ("px", 0.5),
    ("py", 0.35),
];

#[test]
fn four_bar_path_known_answer_is_recovered_and_its_scene_meets_the_targets() {
    // Symmetries: the mirror image (P right of A→B) is excluded by py > 0, and the
    // cognates by the timing (they trace the curve with other crank angles), so the answer
    // is unique within the bounds.
    let (setup, report) = solve(PATH, &text(PATH));
    let mut known = FOUR_BAR.to_vec();
    known.push(("drive0", 20.0));
    assert_known(&setup, &report, &known);
    // The scene written with the answer runs as is; its own solver puts P on the targets
    // (Newton's tolerance on lengths of order 1 m: 1e-9 m is far above it).
    let found = setup.found_scene(&report);
    // Drawn at the first target: `sketch = "theta"` set to drive0 + 0 = 20° (to 1e-9 deg,
    // as drive0 above).
    let source = scene::Source::new("found.toml", found.as_str());
    let values = scene::parameters::read(&found, &source, &[]).unwrap();
    let theta = values.iter().find(|(n, _)| n == "theta").unwrap().1;
    assert!((theta - 20.0).abs() <= 1e-9, "{theta}");
    let scene = scene::parse("found.toml", &found).unwrap_or_else(|e| panic!("{e}"));
    let drive: Vec<f64> = (0..10).map(|k| 20.0 + 30.0 * f64::from(k)).collect();
    let run = scene::run(&scene.with_positions(&drive).unwrap()).unwrap();
    let (x, y) = (column(&run, "x_P"), column(&run, "y_P"));
    let mechdiff_core::synthesis::Task::Path { targets, .. } = setup.problem.task() else {
        panic!("a path task")
    };
    for (k, t) in targets.iter().enumerate() {
        assert!((x[k] - t[0]).hypot(y[k] - t[1]) <= 1e-9, "target {k}");
    }
    // The scene's solver places A, B and P where the engine's closed forms do.
    let check = setup.check_scene(&report, &found).unwrap();
    assert_eq!(check.compared, ["A", "B", "P"]);
    assert!(check.deviation <= 1e-9, "{}", check.deviation);
    // And the whole sweep of the written scene runs (the crank turns fully).
    assert_eq!(scene::run(&scene).unwrap().rows.len(), 37);
}

#[test]
fn four_bar_function_known_answer_is_recovered() {
    // Only the shape counts for an angle output; the ground is fixed, so the answer is
    // unique.
    let (setup, report) = solve(FUNCTION, &text(FUNCTION));
    let known = [
        ("crank", 0.3),
        ("coupler", 1.0),
        ("rocker", 0.8),
        // The pairs' drive values are the known crank's angles: the start is 0.
        ("drive0", 0.0),
    ];
    assert_known(&setup, &report, &known);
}

#[test]
fn four_bar_motion_known_answer_is_recovered() {
    let (setup, report) = solve(MOTION, &text(MOTION));
    let mut known = FOUR_BAR.to_vec();
    known.push(("pose_angle", 0.0));
    assert_known(&setup, &report, &known);
}

#[test]
fn a_scene_that_draws_another_linkage_is_caught_by_the_scene_check() {
    // P drawn right of A→B while the engine puts it left (py > 0): the search succeeds,
    // and the scene's check says the scene is not the linkage sized (P mirrored about the
    // coupler: 2·py = 0.7 m away, far above 1e-3 m).
    let bad = text(PATH).replace(
        "\"hypot(coupler - px, py)\"], side = \"left\"",
        "\"hypot(coupler - px, py)\"], side = \"right\"",
    );
    assert_ne!(bad, text(PATH));
    let (setup, report) = solve("bad.toml", &bad);
    let check = setup
        .check_scene(&report, &setup.found_scene(&report))
        .unwrap();
    assert!(check.deviation > 1e-3, "{}", check.deviation);
}

/// The function scene with a target no four-bar of the bounds reaches: the rocker asked to
/// turn 170° more at the last pair.
fn unreachable() -> String {
    text(FUNCTION).replace("[200, 133.53754519579596]", "[200, 303.53754519579596]")
}

#[test]
fn unreachable_targets_give_the_best_found_and_why_with_residuals_summing_to_the_objective() {
    let path = temp_file("unreachable.toml");
    std::fs::write(&path, unreachable()).unwrap();
    let out = mechdiff(&[
        "synthesize",
        path.to_str().unwrap(),
        "--starts",
        "200",
        "--time-limit",
        "20",
    ]);
    std::fs::remove_file(&path).ok();
    assert!(out.status.success(), "{}", stderr(&out));
    let printed = stdout(&out);
    assert!(printed.contains("not better because:"), "{printed}");
    let objective: f64 = printed
        .lines()
        .find_map(|l| l.strip_prefix("objective: "))
        .and_then(|l| l.split_whitespace().next())
        .unwrap()
        .parse()
        .unwrap();
    assert!(objective > 1e-3, "{objective}");
    // The rows under `target output`: 6 significant digits each, so each square is within
    // 1e-6 relative, and the objective printed within 5e-7: 3e-6 covers both.
    let rows = printed
        .lines()
        .skip_while(|l| !l.trim_start().starts_with("target"))
        .skip(1)
        .take_while(|l| !l.trim().is_empty());
    let sum: f64 = rows
        .map(|l| l.split_whitespace().nth(1).unwrap().parse::<f64>().unwrap())
        .map(|r| r * r)
        .sum();
    assert!(
        (sum - objective).abs() <= 3e-6 * objective,
        "{sum} against {objective}"
    );
}

#[test]
fn the_local_searches_on_two_threads_give_the_answer_of_one_thread_digit_for_digit() {
    // Targets out of reach: every local search runs, so two threads run them two at a time.
    // No time limit that the search could reach (the clock would decide where it stops).
    let path = temp_file("unreachable_threads.toml");
    std::fs::write(&path, unreachable()).unwrap();
    let scene = path.to_str().unwrap();
    let run = |threads: &str| {
        let out = mechdiff(&[
            "synthesize",
            scene,
            "--starts",
            "40",
            "--time-limit",
            "86400",
            "--threads",
            threads,
        ]);
        assert!(out.status.success(), "{threads}: {}", stderr(&out));
        stdout(&out)
    };
    let (one, two) = (run("1"), run("2"));
    let over = mechdiff(&["synthesize", scene, "--threads", "1025"]);
    std::fs::remove_file(&path).ok();
    // Everything but the time the search took (`search: …, 0.123 s; stopped by …`).
    let untimed = |printed: &str| -> Vec<String> {
        (printed.lines())
            .map(|l| match l.find(" s; stopped by") {
                Some(end) if l.starts_with("search: ") => {
                    let start = l[..end].rfind(", ").unwrap();
                    format!("{}{}", &l[..start], &l[end..])
                }
                _ => l.to_owned(),
            })
            .collect()
    };
    assert_eq!(untimed(&one), untimed(&two));
    let searches: usize = (one.lines())
        .find_map(|l| l.strip_prefix("search: "))
        .and_then(|l| l.split(", ").nth(2))
        .and_then(|l| l.split_whitespace().next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no count of local searches: {one}"));
    assert!(searches > 1, "{one}");
    assert!(one.contains("not better because:"), "{one}");
    // More threads than the limit are refused before any work.
    assert!(!over.status.success() && stdout(&over).is_empty());
    assert!(stderr(&over).contains("--threads"), "{}", stderr(&over));
}

/// The message of the error reading `text` as `file` gives (a panic if it is read).
pub(crate) fn read_error(file: &str, text: &str) -> String {
    match synthesize::read(file, text) {
        Ok(_) => panic!("{file} was accepted"),
        Err(e) => e.to_string(),
    }
}

/// The 1-based line of the first occurrence of `needle` in `text`.
pub(crate) fn line_of(text: &str, needle: &str) -> usize {
    text[..text.find(needle).unwrap()].lines().count() + 1
}

#[test]
fn an_unknown_point_is_a_located_error_listing_the_points() {
    let bad = text(PATH).replace(
        "[synthesize.path]\npoint = \"P\"",
        "[synthesize.path]\npoint = \"Z\"",
    );
    let message = read_error("bad.toml", &bad);
    let line = line_of(&bad, "point = \"Z\"");
    assert!(
        message.starts_with(&format!("bad.toml:{line}:")),
        "{message}"
    );
    assert!(
        message.contains("unknown point `Z`") && message.contains("A, B, P"),
        "{message}"
    );
}

#[test]
fn a_bound_on_a_name_that_is_no_design_variable_is_a_located_error() {
    let bad = text(PATH).replace("px = [-1.5, 1.5]", "pz = [-1.5, 1.5]");
    let message = read_error("bad.toml", &bad);
    let line = line_of(&bad, "pz = [");
    assert!(
        message.starts_with(&format!("bad.toml:{line}:")),
        "{message}"
    );
    assert!(
        message.contains("`pz` is not a design variable"),
        "{message}"
    );
}

#[test]
fn bounds_that_exclude_every_assembly_are_a_located_error_with_the_defects_counted() {
    // The ground is at least 1.4 m long (o4x ≥ 1.4 with O2 near the origin) and the
    // coupler and rocker together at most 0.4 m: no four-bar closes.
    let bad = text(PATH)
        .replace("o4x = [0, 2]", "o4x = [1.4, 2]")
        .replace("coupler = [0.1, 2]", "coupler = [0.1, 0.2]")
        .replace("rocker = [0.1, 2]", "rocker = [0.1, 0.2]")
        .replace("crank = [0.1, 1]", "crank = [0.01, 0.05]")
        .replace("starts = 2000", "starts = 300");
    let setup = synthesize::read("bad.toml", &bad).unwrap();
    let error = setup.solve(&setup.settings).unwrap_err();
    let message = error.to_string();
    assert!(matches!(error, Error::Synthesis { .. }), "{message}");
    let line = line_of(&bad, "[synthesize.bounds]");
    assert!(
        message.starts_with(&format!("bad.toml:{line}:")),
        "{message}"
    );
    assert!(message.contains("widen the bounds"), "{message}");
    assert!(!message.contains("NaN"), "{message}");
}

#[test]
fn zero_and_huge_limits_are_located_errors_before_any_work() {
    for (from, to, says) in [
        ("time_limit = 60", "time_limit = 0", "time limit"),
        ("time_limit = 60", "time_limit = 1e9", "time limit"),
        ("starts = 2000", "starts = 0", "`starts` = 0"),
        (
            "starts = 2000",
            "starts = 100000000",
            "`starts` = 100000000",
        ),
        (
            "local_searches = 200",
            "local_searches = 5000",
            "`local_searches`",
        ),
        ("seed = 1", "seed = 1\nevaluations = 0", "`evaluations` = 0"),
    ] {
        let bad = text(PATH).replace(from, to);
        let message = read_error("bad.toml", &bad);
        let line = line_of(&bad, to.lines().last().unwrap());
        assert!(
            message.starts_with(&format!("bad.toml:{line}:")),
            "{to}: {message}"
        );
        assert!(message.contains(says), "{to}: {message}");
    }
}

#[test]
fn the_time_limit_is_honoured_on_targets_out_of_reach() {
    // Many starts and local searches on targets out of reach: only the time limit stops
    // it. One local search step is far below a second, so 0.5 s + 10 s of slack for a
    // loaded debug machine cannot fail by the search overrunning its check.
    let bad = unreachable()
        .replace("starts = 2000", "starts = 100000")
        .replace("local_searches = 200", "local_searches = 100000")
        .replace("time_limit = 60", "time_limit = 0.5");
    let (setup, report) = solve("bad.toml", &bad);
    assert_eq!(setup.settings.time_limit, Some(Duration::from_millis(500)));
    assert_eq!(report.stop, StopReason::Time);
    assert!(
        report.elapsed < Duration::from_secs_f64(10.5),
        "{:?}",
        report.elapsed
    );
    assert!(report.objective.is_finite() && report.residuals.iter().all(|r| r.is_finite()));
}

#[test]
fn out_is_written_runs_as_a_scene_and_is_never_an_existing_file_or_an_input() {
    let out = temp_file("found_function.toml");
    std::fs::remove_file(&out).ok();
    let scene = scene_path(FUNCTION);
    let args = |target: &str, force: bool| {
        let mut a = vec!["synthesize", scene.to_str().unwrap(), "--out", target]
            .into_iter()
            .map(str::to_owned)
            .collect::<Vec<_>>();
        if force {
            a.push("--force".into());
        }
        a
    };
    let run = |a: Vec<String>| mechdiff(&a.iter().map(String::as_str).collect::<Vec<_>>());
    let first = run(args(out.to_str().unwrap(), false));
    assert!(first.status.success(), "{}", stderr(&first));
    let written = std::fs::read_to_string(&out).unwrap();
    let source = scene::Source::new("found", written.as_str());
    let values = scene::parameters::read(&written, &source, &[]).unwrap();
    let crank = values.iter().find(|(n, _)| n == "crank").unwrap().1;
    // The known crank (m), as the known-answer test recovers it.
    assert!((crank - 0.3).abs() <= 1e-9, "{crank}");
    let ran = mechdiff(&["run", out.to_str().unwrap()]);
    assert!(ran.status.success(), "{}", stderr(&ran));
    // An existing file needs --force; the scene itself is refused even with it.
    let again = run(args(out.to_str().unwrap(), false));
    assert!(!again.status.success() && stderr(&again).contains("--force"));
    let input = run(args(scene.to_str().unwrap(), true));
    assert!(!input.status.success() && stderr(&input).contains("refusing to write"));
    std::fs::remove_file(&out).ok();
}

#[test]
fn a_function_given_as_a_formula_is_sampled_over_its_drive_range_in_the_files_units() {
    // 5 positions from 40° to 200° (40° apart) of a line 88° + 0.3·(phi − 40°): the pairs
    // in SI are (40° + 40°k, 88° + 12°k) in radians, to rounding (1e-15 rad).
    let written = text(FUNCTION);
    let start = written.find("pairs = [").unwrap();
    let end = start + written[start..].find("\n]\n").unwrap() + 2;
    let formula = "formula = \"88 + 0.3*(phi - 40)\"\nfrom = 40\nto = 200\ncount = 5";
    let with_formula = format!("{}{formula}{}", &written[..start], &written[end..]);
    let setup = synthesize::read("formula.toml", &with_formula).unwrap_or_else(|e| panic!("{e}"));
    let mechdiff_core::synthesis::Task::Function { pairs, .. } = setup.problem.task() else {
        panic!("a function task")
    };
    assert_eq!(pairs.len(), 5);
    for (k, pair) in pairs.iter().enumerate() {
        let k = k as f64;
        assert!(
            (pair[0] - (40.0 + 40.0 * k).to_radians()).abs() <= 1e-15,
            "{pair:?}"
        );
        assert!(
            (pair[1] - (88.0 + 12.0 * k).to_radians()).abs() <= 1e-15,
            "{pair:?}"
        );
    }
    // A count over the limit is refused at `count` before any sample is computed.
    let huge = with_formula.replace("count = 5", "count = 1000000");
    let message = read_error("formula.toml", &huge);
    let line = line_of(&huge, "count = 1000000");
    assert!(
        message.starts_with(&format!("formula.toml:{line}:")),
        "{message}"
    );
}

#[test]
fn free_timing_makes_each_targets_drive_position_a_design_variable() {
    let free = text(PATH)
        .replace("timing = \"relative\"", "timing = \"free\"")
        .replace(
            "drive = [0, 30, 60, 90, 120, 150, 180, 210, 240, 270]\n",
            "",
        );
    let setup = synthesize::read("free.toml", &free).unwrap_or_else(|e| panic!("{e}"));
    let names: Vec<&str> = setup.variables.iter().map(|v| v.name.as_str()).collect();
    let drives: Vec<String> = (1..=10).map(|i| format!("drive{i}")).collect();
    assert_eq!(
        names[9..],
        drives.iter().map(String::as_str).collect::<Vec<_>>()[..]
    );
    // Free timing with drive positions given is a located error saying what to remove.
    let both = text(PATH).replace("timing = \"relative\"", "timing = \"free\"");
    let message = read_error("free.toml", &both);
    let line = line_of(&both, "drive = [0, 30");
    assert!(
        message.starts_with(&format!("free.toml:{line}:")),
        "{message}"
    );
    assert!(message.contains("remove `drive`"), "{message}");
}

#[test]
fn check_describes_the_synthesis() {
    let out = mechdiff(&["check", scene_path(PATH).to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        stdout(&out).contains(
            "synthesis: four_bar, path generation of point P, 10 targets, 10 of 10 design \
             variables free"
        ),
        "{}",
        stdout(&out)
    );
}

#[test]
fn check_names_the_weights_and_the_grashof_class_a_section_gives() {
    // The path scene with a weight per target (not all 1) and a Grashof class (the one its
    // `crank_rotates = true` implies, so the section stays valid).
    let weights = "weights = [1, 2, 0.5, 1, 1, 1, 1, 1, 1, 3]";
    let written = text(PATH)
        .replace("seed = 1", "seed = 1\ngrashof = \"crank-rocker\"")
        .replace("targets = [", &format!("{weights}\ntargets = ["));
    let path = temp_file("check_weighted.toml");
    std::fs::write(&path, &written).unwrap();
    let out = mechdiff(&["check", path.to_str().unwrap()]);
    std::fs::remove_file(&path).ok();
    assert!(out.status.success(), "{}", stderr(&out));
    let printed = stdout(&out);
    let line = (printed.lines())
        .find(|l| l.starts_with("synthesis: "))
        .unwrap_or_else(|| panic!("no synthesis line: {printed}"));
    assert_eq!(
        line,
        "synthesis: four_bar, path generation of point P, 10 targets (weights 1, 2, 0.5, 1, 1, \
         1, 1, 1, 1, 3), 10 of 10 design variables free, Grashof class crank-rocker required; \
         `mechdiff synthesize` sizes them"
    );
    // More weights than the line lists: the first twelve, then how many in all.
    let formula = "formula = \"88 + 0.3*(phi - 40)\"\nfrom = 40\nto = 200\ncount = 15";
    let function = text(FUNCTION);
    let start = function.find("pairs = [").unwrap();
    let end = start + function[start..].find("\n]\n").unwrap() + 2;
    let many = (1..=15)
        .map(|k| k.to_string())
        .collect::<Vec<_>>()
        .join(", ");
    let with_weights = format!(
        "{}{formula}\nweights = [{many}]{}",
        &function[..start],
        &function[end..]
    );
    let setup = synthesize::read("many.toml", &with_weights).unwrap_or_else(|e| panic!("{e}"));
    let described = synthesize::describe(&setup);
    assert!(
        described.contains(
            "15 targets (weights 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, … (15 in all)), "
        ) && !described.contains("Grashof"),
        "{described}"
    );
}

#[test]
fn command_line_limits_out_of_range_are_refused_before_any_work() {
    let scene = scene_path(PATH);
    for (option, value, says) in [
        ("--time-limit", "0", "more than 0"),
        ("--time-limit", "1e9", "at most 86400"),
        ("--starts", "0", "from 1 to 100000"),
        ("--starts", "1000000", "from 1 to 100000"),
    ] {
        let out = mechdiff(&["synthesize", scene.to_str().unwrap(), option, value]);
        assert!(!out.status.success(), "{option} {value}");
        let message = stderr(&out);
        assert!(
            message.contains(option) && message.contains(says),
            "{message}"
        );
        assert!(
            stdout(&out).is_empty(),
            "{option} {value}: {}",
            stdout(&out)
        );
    }
}
