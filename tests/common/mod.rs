//! What the integration tests share: running the `mechdiff` binary, scene files of the
//! `scenes/` folder, columns of a report, temporary files and error-message checks.
//!
//! Each test file that needs it says `mod common;`; not every file uses every helper.
#![allow(dead_code)]

pub mod chromium;
pub mod many_names;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use mechdiff::Error;
use mechdiff::scene::{self, Report};

/// Runs the `mechdiff` binary in the package folder (so `scenes/…` paths work).
pub fn mechdiff(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_mechdiff"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the mechdiff binary runs")
}

/// What a run printed on standard output.
pub fn stdout(output: &Output) -> String {
    String::from_utf8(output.stdout.clone()).expect("standard output is UTF-8")
}

/// What a run printed on standard error.
pub fn stderr(output: &Output) -> String {
    String::from_utf8(output.stderr.clone()).expect("standard error is UTF-8")
}

/// A path in the temporary folder, unique to this test process and `name`.
pub fn temp_file(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("mechdiff-test-{}-{name}", std::process::id()))
}

/// The path of a file in the `scenes/` folder (`"whitworth.toml"`, `"cams/…"`).
pub fn scene_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(name)
}

/// Loads and runs a scene of the `scenes/` folder; panics with the error's message.
pub fn run_scene(name: &str) -> Report {
    let scene = scene::load(scene_path(name)).unwrap_or_else(|e| panic!("{e}"));
    scene::run(&scene).unwrap_or_else(|e| panic!("{e}"))
}

/// Parses and runs a scene given as text (named `file` in messages); panics with the error.
pub fn run_text(file: &str, text: &str) -> Report {
    let scene = scene::parse(file, text).unwrap_or_else(|e| panic!("{e}"));
    scene::run(&scene).unwrap_or_else(|e| panic!("{e}"))
}

/// A column of a report by name; panics naming the column when there is none.
pub fn column(report: &Report, name: &str) -> Vec<f64> {
    report
        .column(name)
        .unwrap_or_else(|| panic!("no column `{name}`"))
}

/// max |a − b| divided by max |b|: relative where the values are large, and absolute
/// (scaled by the largest magnitude) where they pass through zero.
pub fn scaled_error(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
        / scale
}

/// The line (1-based) of the first occurrence of `what` in `text`.
pub fn line_of(text: &str, what: &str) -> usize {
    let at = text
        .find(what)
        .unwrap_or_else(|| panic!("test bug: `{what}` is not in the text"));
    text[..at].matches('\n').count() + 1
}

/// Asserts that a scene error is located at `bad.toml:{line}:` and names every part.
pub fn assert_message(error: &Error, line: usize, parts: &[&str]) {
    let message = error.to_string();
    assert!(
        message.starts_with(&format!("bad.toml:{line}:")),
        "expected line {line}: {message}"
    );
    for part in parts {
        assert!(message.contains(part), "`{part}` missing from: {message}");
    }
}

/// The triad of `tests/data/triad.toml` (a loop solved by Newton only) with `rest` appended:
/// its `[sweep]` and `[[output]]` sections.
pub fn triad(rest: &str) -> String {
    format!("{}{rest}", include_str!("../data/triad.toml"))
}

/// The slotted lever of `tests/data/slotted_lever_near_hinge.toml` (ill-conditioned at
/// −90°) with `rest` appended: its `[sweep]` and `[[output]]` sections.
pub fn slotted_lever(rest: &str) -> String {
    format!(
        "{}{rest}",
        include_str!("../data/slotted_lever_near_hinge.toml")
    )
}

/// A parallelogram four-bar (crank 100 mm, ground and coupler 300 mm) sketched at φ = 20°:
/// its coupler and rocker fold onto the ground line at φ = 0, a change point (the margin of
/// the dyad A–B–B0 touches zero there: a double root).
pub const PARALLELOGRAM: &str = r#"
[units]
length = "mm"
angle = "deg"
[points]
A0 = [0, 0]
B0 = [300, 0]
A = [93.96926207859084, 34.20201433256687]
B = [393.96926207859084, 34.20201433256687]
[links]
ground = ["A0", "B0"]
crank = ["A0", "A"]
coupler = ["A", "B"]
rocker = ["B0", "B"]
[joints]
A0 = { type = "revolute", at = "A0", links = ["ground", "crank"] }
A = { type = "revolute", at = "A", links = ["crank", "coupler"] }
B = { type = "revolute", at = "B", links = ["coupler", "rocker"] }
B0 = { type = "revolute", at = "B0", links = ["ground", "rocker"] }
[drive]
joint = "A0"
line = ["A0", "A"]
[[output]]
name = "psi"
angle = ["B0", "B"]
quantities = ["position"]
"#;
