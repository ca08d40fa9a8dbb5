//! Sweeps that stream: the same bytes for any number of threads, batch, chunk and piece size
//! (the parallel solve: closed-form and Newton scenes, limit positions and ill-conditioned
//! poses inside the sweep); the first error in drive order with the rows before it; files whole or not at all; no cap on
//! the number of drive positions of a streamed run.

use crate::common;

use std::io::Write;
use std::path::PathBuf;
use std::process::Command;

use mechdiff::scene::{self, Scene, table};
use mechdiff::stream::{self, Options, Sink, Sinks, Speculation};
use mechdiff::{Error, Result};

/// `scenes/slider_crank.toml` of this repository (offset slider-crank in mm and degrees,
/// speed 1500 rpm, dead positions of `s`), swept at `step` degrees.
fn slider_crank(step: &str) -> Scene {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/slider_crank.toml");
    let text = std::fs::read_to_string(path).unwrap();
    assert!(text.contains("step = 5\n"));
    let text = text.replace("step = 5\n", &format!("step = {step}\n"));
    scene::parse("slider_crank.toml", &text).unwrap()
}

/// The offset slider-crank of `tests/sweep_limits.rs` (r = 1 m, e = 0.5 m, l = 1.49 m): the
/// crank cannot pass sin φ < −0.99, ≈ 261.89°–278.11°; swept 0–360° at 1°.
const BLOCKED: &str = r#"
[units]
length = "m"
angle = "deg"
[points]
O = [0, 0]
A = [1, 0]
B = [2.4036025078347505, 0.5]
G0 = [0, 0.5]
G1 = [1, 0.5]
[links]
ground = ["O", "G0", "G1"]
crank = ["O", "A"]
rod = ["A", "B"]
slider = ["B"]
[joints]
O = { type = "revolute", at = "O", links = ["ground", "crank"] }
A = { type = "revolute", at = "A", links = ["crank", "rod"] }
B = { type = "revolute", at = "B", links = ["rod", "slider"] }
guide = { type = "prismatic", line = ["G0", "G1"], point = "B", links = ["ground", "slider"] }
[drive]
joint = "O"
line = ["O", "A"]
[sweep]
from = 0
to = 360
step = 1
[[output]]
name = "s"
slider = "guide"
quantities = ["position", "velocity_coefficient"]
[[output]]
name = "rod"
angle = ["A", "B"]
quantities = ["position"]
"#;

/// The three outputs of a streamed run, and how it ended.
struct Outputs {
    result: Result<stream::Streamed>,
    table: Vec<u8>,
    csv: Vec<u8>,
    jsonl: Vec<u8>,
}

fn streamed(scene: &Scene, options: &Options) -> Outputs {
    let (mut table, mut csv, mut jsonl) = (Vec::new(), Vec::new(), Vec::new());
    let sink = |path: &str, out| {
        Some(Sink {
            path: PathBuf::from(path),
            out,
        })
    };
    let mut sinks = Sinks {
        table: sink("<stdout>", &mut table),
        csv: sink("out.csv", &mut csv),
        jsonl: sink("out.jsonl", &mut jsonl),
    };
    let result = stream::run(scene, &mut sinks, options);
    drop(sinks);
    Outputs {
        result,
        table,
        csv,
        jsonl,
    }
}

fn options(threads: usize, batch: usize, chunk: usize) -> Options {
    Options {
        threads,
        batch,
        chunk,
        ..Options::default()
    }
}

fn text(bytes: &[u8]) -> &str {
    std::str::from_utf8(bytes).unwrap()
}

/// One thread with the default batches, and two or three threads with batches and chunks
/// that do not divide the 1441 positions: the same bytes in every output, for the table
/// printed from its values and for the streamed one.
#[test]
fn every_thread_count_and_batch_size_gives_the_same_bytes() {
    let scene = slider_crank("0.25");
    let one = streamed(&scene, &options(1, 1 << 14, 1 << 10));
    one.result.as_ref().unwrap();
    for (threads, batch, chunk) in [(2, 7, 3), (3, 100, 16), (2, 1441, 1)] {
        let other = streamed(&scene, &options(threads, batch, chunk));
        other.result.as_ref().unwrap();
        assert!(
            one.table == other.table,
            "table, {threads} threads, batch {batch}"
        );
        assert!(
            one.csv == other.csv,
            "csv, {threads} threads, batch {batch}"
        );
        assert!(
            one.jsonl == other.jsonl,
            "jsonl, {threads} threads, batch {batch}"
        );
    }
    let long = |threads, batch, chunk| Options {
        table_from_values: 0,
        ..options(threads, batch, chunk)
    };
    let a = streamed(&scene, &long(1, 1 << 14, 1 << 10));
    let b = streamed(&scene, &long(3, 13, 5));
    assert!(a.table == b.table);
    assert!(a.csv == one.csv);
    // The streamed table: title, plan, names, units, 1441 rows, then the dead positions.
    let lines: Vec<&str> = text(&a.table).lines().collect();
    assert!(
        lines[4].trim_start().starts_with("0.00000000e0"),
        "{}",
        lines[4]
    );
    assert!(lines[4 + 1440].trim_start().starts_with("3.60000000e2"));
    assert!(text(&a.table).contains("stroke of s: 200.096"));
}

/// The streamed outputs hold what a run in memory computes: the table as it always was
/// printed, and the CSV with the digits of Rust's `Display` (the format before streaming),
/// written here independently of the streamed formatter.
#[test]
fn streamed_outputs_hold_the_values_of_a_run_in_memory() {
    let scene = slider_crank("0.25");
    let out = streamed(&scene, &options(2, 64, 8));
    out.result.as_ref().unwrap();
    let report = scene::run(&scene).unwrap();
    let mut expected_table = Vec::new();
    table::write_table(&scene, &report, &mut expected_table).unwrap();
    assert!(out.table == expected_table, "{}", text(&out.table));
    let mut expected_csv = String::new();
    let header: Vec<String> = report.columns.iter().map(|c| c.header()).collect();
    expected_csv.push_str(&(header.join(",") + "\n"));
    for row in &report.rows {
        let cells: Vec<String> = (row.iter().zip(&report.columns))
            .map(|(v, c)| (v / c.factor + 0.0).to_string())
            .collect();
        expected_csv.push_str(&(cells.join(",") + "\n"));
    }
    assert_eq!(text(&out.csv), expected_csv);
}

/// Each JSON Lines record holds the CSV's headers as keys and the CSV's numbers: the same
/// `f64` exactly (both are shortest representations of one value, read back exactly).
#[test]
fn jsonl_records_hold_the_csv_values() {
    let scene = slider_crank("5");
    let out = streamed(&scene, &options(2, 10, 3));
    out.result.unwrap();
    let mut csv = text(&out.csv).lines();
    let header: Vec<&str> = csv.next().unwrap().split(',').collect();
    let records: Vec<&str> = text(&out.jsonl).lines().collect();
    assert_eq!(records.len(), 73);
    for (line, record) in csv.zip(records) {
        let record: serde_json::Map<String, serde_json::Value> =
            serde_json::from_str(record).unwrap();
        let keys: Vec<&str> = record.keys().map(String::as_str).collect();
        let mut sorted = header.clone();
        sorted.sort_unstable();
        assert_eq!(keys, sorted);
        for (name, cell) in header.iter().zip(line.split(',')) {
            let value: f64 = cell.parse().unwrap();
            assert_eq!(record[*name].as_f64().unwrap(), value, "{name}");
        }
    }
}

/// A sweep blocked at 261.89° fails at 262° with the error of a run in memory, whatever the
/// threads and batches; every output holds exactly the rows before it (0° to 261°), the
/// same bytes for one thread and for three.
#[test]
fn a_blocked_sweep_reports_the_first_error_in_drive_order_after_the_rows_before_it() {
    let scene = scene::parse("blocked.toml", BLOCKED).unwrap();
    let expected = scene::run(&scene).unwrap_err().to_string();
    let one = streamed(&scene, &options(1, 1 << 14, 1 << 10));
    for (threads, batch, chunk) in [(3, 5, 2), (2, 262, 7), (2, 261, 300)] {
        let out = streamed(&scene, &options(threads, batch, chunk));
        let e = out.result.unwrap_err();
        assert!(matches!(e, Error::Blocked { .. }), "{e:?}");
        assert_eq!(e.to_string(), expected);
        let rows: Vec<&str> = text(&out.csv).lines().skip(1).collect();
        assert_eq!(rows.len(), 262, "{threads} threads, batch {batch}");
        assert!(rows[261].starts_with("261,"), "{}", rows[261]);
        assert_eq!(text(&out.jsonl).lines().count(), 262);
        assert!(out.csv == one.csv && out.jsonl == one.jsonl);
        // The table of a short sweep is printed from its values, at the end: nothing yet.
        assert!(out.table.is_empty());
    }
}

/// A writer that fails after `budget` bytes, like a full disk.
struct FailsAfter {
    budget: usize,
}

impl Write for FailsAfter {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if buf.len() > self.budget {
            return Err(std::io::Error::other("injected: no space left"));
        }
        self.budget -= buf.len();
        Ok(buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// A CSV that cannot be written ends the run with an error naming its path.
#[test]
fn a_failed_write_is_an_error_naming_the_file() {
    let scene = slider_crank("0.25");
    let mut failing = FailsAfter { budget: 5000 };
    let mut sinks = Sinks {
        csv: Some(Sink {
            path: PathBuf::from("out.csv"),
            out: &mut failing,
        }),
        ..Sinks::default()
    };
    let e = stream::run(&scene, &mut sinks, &options(2, 50, 10)).unwrap_err();
    assert!(matches!(e, Error::Write { .. }), "{e:?}");
    assert_eq!(
        e.to_string(),
        "cannot write out.csv: injected: no space left"
    );
}

/// `mechdiff run` of a sweep that fails mid-way: the error on stderr, the user's old CSV
/// intact, no JSON Lines file and no temporary file left in the folder.
#[test]
fn a_failed_sweep_leaves_the_old_files_and_no_temporary_file() {
    let dir = std::env::temp_dir().join(format!("mechdiff-stream-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("s.toml"), BLOCKED).unwrap();
    std::fs::write(dir.join("out.csv"), "old\n").unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_mechdiff"))
        .current_dir(&dir)
        .args(["run", "s.toml", "--csv", "out.csv", "--jsonl", "out.jsonl"])
        .args(["--threads", "2"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("cannot assemble between drive positions 261 deg and 262 deg"));
    assert_eq!(
        std::fs::read_to_string(dir.join("out.csv")).unwrap(),
        "old\n"
    );
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["out.csv", "s.toml"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `from`, `to`, `step` are counted on demand: 3.6·10⁷ positions parse at once (the cap of
/// 10⁶ is gone), a run that holds every row in memory refuses them, naming `step`, and
/// checking a sweep of 3.6·10¹¹ does not walk it.
#[test]
fn a_long_sweep_is_counted_not_stored() {
    let scene = slider_crank("0.00001");
    assert_eq!(scene.positions.len(), 36_000_001);
    // The last is 360° to 1e-12 relative (i·step in f64 rounds once or twice).
    let last = scene.positions.get(36_000_000);
    assert!((last / std::f64::consts::TAU - 1.0).abs() < 1e-12, "{last}");
    let e = scene::run(&scene).unwrap_err().to_string();
    assert!(
        e.starts_with("slider_crank.toml:40:8: the sweep has 36000001 positions"),
        "{e}"
    );
    // 3.6·10¹¹ positions: reading and checking the scene walks none of them.
    let scene = slider_crank("0.000000001");
    assert_eq!(scene.positions.len(), 360_000_000_001);
    let plan = scene::check(&scene).unwrap().plan;
    assert_eq!(plan.range.1, scene.positions.get(360_000_000_000));
}

/// A run solved in parallel pieces of `piece` positions (`speculation`), on `threads`.
fn pieces(threads: usize, batch: usize, piece: usize, speculation: Speculation) -> Options {
    Options {
        piece,
        speculation,
        ..options(threads, batch, 16)
    }
}

/// Every output and the warnings of two runs are the same, byte for byte.
fn assert_same(one: &Outputs, other: &Outputs, what: &str) {
    assert!(one.table == other.table, "table, {what}");
    assert!(one.csv == other.csv, "csv, {what}");
    assert!(one.jsonl == other.jsonl, "jsonl, {what}");
    let warnings = |o: &Outputs| o.result.as_ref().map(|s| s.warnings.clone()).ok();
    assert_eq!(warnings(one), warnings(other), "warnings, {what}");
}

/// The blocked slider-crank swept from −81.8° to 261.8° at 0.01° (34361 positions): both
/// limit positions (≈ −81.89° and 261.89°) lie within 0.1° beyond the ends, where the rod and
/// crank near a line. Solved in pieces of 7 to 4096 positions on two threads (piece starts
/// next to both ends and everywhere between), it gives the bytes of one thread walking in
/// order; every guessed start of a piece was the true state (closed forms: no piece solved
/// twice). Without the `parallel` feature there is one thread and nothing is guessed: the
/// same bytes.
#[test]
fn parallel_pieces_give_the_bytes_of_one_thread_up_to_two_limit_positions() {
    let text = BLOCKED.replace(
        "from = 0\nto = 360\nstep = 1",
        "from = -81.8\nto = 261.8\nstep = 0.01",
    );
    let scene = scene::parse("limits.toml", &text).unwrap();
    assert_eq!(scene.positions.len(), 34361);
    // The solver's pieces: `auto` would compile this long sweep of closed forms, whose
    // program walks in order (its state is not compared between pieces).
    let long = |o: Options| Options {
        table_from_values: 0,
        evaluator: mechdiff::evaluator::Evaluator::Solver,
        ..o
    };
    let one = streamed(
        &scene,
        &long(pieces(1, 1 << 14, 1 << 12, Speculation::Never)),
    );
    one.result.as_ref().unwrap();
    for (batch, piece) in [(1 << 14, 7), (5000, 4096), (34361, 1000), (999, 250)] {
        let other = streamed(&scene, &long(pieces(2, batch, piece, Speculation::Auto)));
        assert_same(&one, &other, &format!("batch {batch}, piece {piece}"));
        let counted = other.result.unwrap().pieces;
        if cfg!(feature = "parallel") {
            assert!(
                counted.guessed >= 34361 / piece - 34361 / batch,
                "{counted:?}"
            );
        } else {
            // Without the `parallel` feature the pool has one thread: `Speculation::Auto`
            // walks in order and guesses no piece's start.
            assert_eq!(counted.guessed, 0, "{counted:?}");
        }
        assert_eq!(counted.solved_again, 0, "{counted:?}");
    }
}

/// A slotted lever whose pin passes 1e-6 m from the lever's hinge at −90° (ψ′ ≈ −1e6, see
/// `tests/sweep_limits.rs`), swept from −100° to −80° at 0.01°: the most ill-conditioned
/// position is chosen among the pieces as in one walk, whether −90° starts a piece, ends one
/// or lies inside one, and the warning names it.
#[test]
fn the_most_ill_conditioned_position_is_the_same_in_pieces() {
    let text = common::slotted_lever(
        r#"
[sweep]
from = -100
to = -80
step = 0.01
[[output]]
name = "psi"
angle = ["B0", "S"]
quantities = ["position", "velocity_coefficient"]
"#,
    );
    let scene = scene::parse("lever.toml", &text).unwrap();
    let one = streamed(&scene, &pieces(1, 1 << 14, 1 << 12, Speculation::Never));
    let warnings = one.result.as_ref().unwrap().warnings.clone();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(
        warnings[0].contains("ill-conditioned position at drive position -90 deg"),
        "{}",
        warnings[0]
    );
    for piece in [1000, 1001, 999, 3] {
        let other = streamed(&scene, &pieces(2, 1 << 14, piece, Speculation::Auto));
        assert_same(&one, &other, &format!("piece {piece}"));
    }
}

/// The blocked slider-crank at 1° fails at 262°: solved in pieces whose joins lie at, just
/// before and just after the error (and a piece of 5), the same error after the same rows.
#[test]
fn parallel_pieces_report_the_first_error_in_drive_order() {
    let scene = scene::parse("blocked.toml", BLOCKED).unwrap();
    let one = streamed(&scene, &pieces(1, 1 << 14, 1 << 12, Speculation::Never));
    let expected = one.result.as_ref().unwrap_err().to_string();
    for piece in [262, 261, 263, 131, 5] {
        let other = streamed(&scene, &pieces(2, 361, piece, Speculation::Auto));
        assert_eq!(other.result.as_ref().unwrap_err().to_string(), expected);
        assert_same(&one, &other, &format!("piece {piece}"));
        assert_eq!(text(&other.csv).lines().count(), 1 + 262);
    }
}

/// A triad (a ternary link held by three binary links: one loop of four links, solved by
/// Newton, no closed form) swept from −1.4° to 91.1° at 0.1°, within a step of its two limit
/// positions (−1.45°, 91.17°). Newton's poses carry the last bits of their route, so a
/// guessed start is rarely the true state: forced to guess anyway, the run solves those
/// pieces again and still gives the bytes of one thread; left to itself it walks in order.
#[test]
fn a_newton_scene_in_pieces_gives_the_bytes_of_one_thread() {
    let text = common::triad(
        r#"
[sweep]
from = -1.4
to = 91.1
step = 0.1
[[output]]
point = "C"
quantities = ["position", "velocity_coefficient", "acceleration_coefficient"]
[[output]]
name = "third"
angle = ["G3", "D"]
quantities = ["position", "velocity_coefficient"]
"#,
    );
    let scene = scene::parse("triad.toml", &text).unwrap();
    assert_eq!(scene.positions.len(), 926);
    let one = streamed(&scene, &pieces(1, 1 << 14, 1 << 12, Speculation::Never));
    one.result.as_ref().unwrap();
    for (batch, piece) in [(1 << 14, 5), (300, 50), (926, 463)] {
        let other = streamed(&scene, &pieces(2, batch, piece, Speculation::Always));
        assert_same(&one, &other, &format!("batch {batch}, piece {piece}"));
        let counted = other.result.unwrap().pieces;
        assert!(counted.guessed > 0, "{counted:?}");
        assert!(counted.solved_again > 0, "{counted:?}");
    }
    let auto = streamed(&scene, &pieces(2, 1 << 14, 5, Speculation::Auto));
    assert_same(&one, &auto, "auto");
    assert_eq!(auto.result.unwrap().pieces, stream::Pieces::default());
}

/// A scene of this repository with its `[sweep]` replaced by `sweep`.
fn swept(name: &str, old: &str, sweep: &str) -> Scene {
    let path = format!("{}/scenes/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(path).unwrap();
    assert!(text.contains(old), "{name}");
    scene::parse(name, &text.replace(old, sweep)).unwrap()
}

/// The outputs of a run in memory, written by its writers.
fn in_memory(scene: &Scene) -> (Vec<u8>, Vec<u8>, Vec<u8>) {
    let report = scene::run(scene).unwrap();
    let (mut t, mut c, mut j) = (Vec::new(), Vec::new(), Vec::new());
    table::write_table(scene, &report, &mut t).unwrap();
    table::write_csv(&report, &mut c).unwrap();
    table::write_jsonl(&report, &mut j).unwrap();
    (t, c, j)
}

/// `[[dynamics]]` streams from the sweep's one walk: the Whitworth's forces (a kinematic
/// output, inertial forces, shaking force with its summary line) over 1000 positions,
/// streamed on two threads in speculative pieces of 16 and batches of 96, give the bytes of
/// the run in memory in the table (with the summary after it), the CSV and the JSON Lines;
/// each position solved once. A dynamics-and-balancing scene (the counterweights need every
/// position before their columns) streams the bytes of the run in memory too.
#[test]
fn streamed_dynamics_and_balancing_give_the_bytes_of_a_run_in_memory() {
    let forces = swept(
        "whitworth_forces.toml",
        "positions = [0, 67.9756871629578374, 180, 292.024312837042163]",
        "from = 0\nto = 359.64\nstep = 0.36",
    );
    assert_eq!(forces.positions.len(), 1000);
    let balancing = swept("whitworth_balancing.toml", "step = 5\n", "step = 2.5\n");
    for scene in [&forces, &balancing] {
        let (table, csv, jsonl) = in_memory(scene);
        let out = streamed(scene, &pieces(2, 96, 16, Speculation::Always));
        let stats = out.result.as_ref().unwrap().stats;
        assert!(text(&out.table).contains("shaking force over the sweep"));
        assert!(out.table == table, "{}", text(&out.table));
        assert!(out.csv == csv, "{}", scene.file);
        assert!(out.jsonl == jsonl, "{}", scene.file);
        let n = scene.positions.len();
        assert_eq!((stats.sweep.rows, stats.sweep.solves), (n, n));
    }
}

/// A table that goes nowhere (`discard_table`: the terminal is `/dev/null`) is neither
/// formatted nor written, and the run is otherwise the same: the same CSV and JSON Lines
/// bytes with the table printed from its values and with the streamed one; a blocked sweep
/// with no other output still walks to its first error and reports it.
#[test]
fn a_discarded_table_leaves_the_files_and_the_errors_as_they_were() {
    let scene = slider_crank("0.25");
    for table_from_values in [stream::TABLE_FROM_VALUES, 100] {
        let kept = Options {
            table_from_values,
            ..options(1, 1 << 14, 1 << 10)
        };
        let discarded = Options {
            discard_table: true,
            ..kept.clone()
        };
        let (kept, discarded) = (streamed(&scene, &kept), streamed(&scene, &discarded));
        assert!(kept.result.is_ok() && discarded.result.is_ok());
        assert!(!kept.table.is_empty() && discarded.table.is_empty());
        assert!(kept.csv == discarded.csv && kept.jsonl == discarded.jsonl);
    }
    let blocked = scene::parse("blocked.toml", BLOCKED).unwrap();
    let expected = scene::run(&blocked).unwrap_err().to_string();
    let mut table = Vec::new();
    let mut sinks = Sinks {
        table: Some(Sink {
            path: PathBuf::from("<stdout>"),
            out: &mut table,
        }),
        ..Sinks::default()
    };
    let discard = Options {
        discard_table: true,
        ..Options::default()
    };
    let e = stream::run(&blocked, &mut sinks, &discard).unwrap_err();
    drop(sinks);
    assert_eq!(e.to_string(), expected);
    assert!(table.is_empty());
}

/// `mechdiff run` with its standard output on `/dev/null` (where it formats no table):
/// the same CSV as with the table on a pipe, and a blocked sweep fails with the same error.
#[test]
fn a_run_to_dev_null_writes_the_same_csv_and_fails_the_same_way() {
    let dir = std::env::temp_dir().join(format!("mechdiff-null-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/slider_crank.toml");
    let toml = std::fs::read_to_string(path).unwrap();
    std::fs::write(
        dir.join("sc.toml"),
        toml.replace("step = 5\n", "step = 0.005\n"),
    )
    .unwrap();
    std::fs::write(dir.join("blocked.toml"), BLOCKED).unwrap();
    let run = |scene: &str, csv: &str, stdout: std::process::Stdio| {
        Command::new(env!("CARGO_BIN_EXE_mechdiff"))
            .current_dir(&dir)
            .args(["run", scene, "--csv", csv, "--threads", "1"])
            .stdout(stdout)
            .output()
            .unwrap()
    };
    let piped = run("sc.toml", "piped.csv", std::process::Stdio::piped());
    let null = run("sc.toml", "null.csv", std::process::Stdio::null());
    assert!(piped.status.success() && null.status.success());
    // 72 001 positions: the table is streamed (scientific columns), not held.
    assert!(text(&piped.stdout).lines().count() > 72_001);
    let read = |name: &str| std::fs::read(dir.join(name)).unwrap();
    assert!(read("piped.csv") == read("null.csv"));
    let piped = run("blocked.toml", "b1.csv", std::process::Stdio::piped());
    let null = run("blocked.toml", "b2.csv", std::process::Stdio::null());
    assert!(!piped.status.success() && !null.status.success());
    assert_eq!(text(&piped.stderr), text(&null.stderr));
    assert!(text(&null.stderr).contains("cannot assemble between drive positions 261 deg"));
    std::fs::remove_dir_all(&dir).unwrap();
}
