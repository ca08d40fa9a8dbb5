//! A bounded fuzz test: every shipped scene (`scenes/` recursively — linkages, cams, rotors,
//! formula scenes, the cam-driven linkage — and `tests/data`), mutated (numbers set to
//! extremes, lines deleted or duplicated, names swapped, the text truncated), goes through
//! `check` and `run` in-process. Whatever the mutation, the library must not panic or hang;
//! `check` and `run` must agree (a run may refuse what `check` accepted only with an error
//! found by solving, [`mechdiff::Error::is_found_by_solving`]); and a run that succeeds
//! gives only finite numbers.

use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use mechdiff::accuracy::formula;
use mechdiff::scene::any::{self, AnyScene};
use mechdiff::{Error, report, scene};
use proptest::prelude::*;
use proptest::test_runner::{Config, FileFailurePersistence, TestRunner};

/// How many mutated scenes are tried in `cargo test`: in a debug build about 20 s on one core
/// (the time is printed). Each run draws new cases (failures are kept in
/// `proptest-regressions/` and tried first); a longer fuzz by hand sets `PROPTEST_CASES`, e.g.
/// `PROPTEST_CASES=100000 cargo test --release --test integration fuzz_scenes::`.
const CASES: u32 = 1000;

/// Longest time one mutated scene may take before it counts as a hang. A case that runs a
/// full sweep with dead positions and dynamics takes well under a second in a debug build.
const HANG: Duration = Duration::from_secs(60);

/// Sweeps longer than this are only checked, not run, so the test stays bounded (the
/// position limit itself is tested in `scene_inputs.rs`).
const LONGEST_SWEEP: usize = 5_000;

/// Values a number is replaced with: zeros, the smallest and largest f64, just past the
/// overflow thresholds of squares and products, TOML's nan and inf, formulas whose value is
/// not finite, and ordinary values that keep the scene valid but change its geometry (so
/// that cases reach the solver and the dynamics, not only the checks).
const EXTREMES: &[&str] = &[
    "0.5",
    "2",
    "-3",
    "45",
    "1000",
    "0.001",
    "1e6",
    "0",
    "-0.0",
    "1e-324",
    "5e-324",
    "1e-300",
    "1e-9",
    "-1",
    "1e9",
    "1e155",
    "1e308",
    "-1e308",
    "123456789",
    "nan",
    "inf",
    "-inf",
    "\"1/0\"",
    "\"0/0\"",
    "\"1e308*10\"",
    "\"nan\"",
    "\"2*pi\"",
];

/// Factors a number is multiplied by.
const FACTORS: &[f64] = &[0.5, 2.0, -1.0, 1.01, 0.99, 10.0, 0.1, 3.0];

/// One change to a scene's text; the indices are reduced modulo what the text has.
#[derive(Debug, Clone)]
enum Mutation {
    /// Replace the k-th number with `EXTREMES[e]`.
    Number(usize, usize),
    /// Multiply the k-th number by `FACTORS[f]` (a plausible scene with other geometry:
    /// cases that reach the solver's refusals, toggles and branches).
    Scale(usize, usize),
    /// Delete the k-th line.
    DeleteLine(usize),
    /// Write the k-th line twice.
    DuplicateLine(usize),
    /// Swap the j-th and k-th quoted names.
    SwapNames(usize, usize),
    /// Cut the text at byte k.
    Truncate(usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        4 => (any::<usize>(), 0..EXTREMES.len()).prop_map(|(k, e)| Mutation::Number(k, e)),
        4 => (any::<usize>(), 0..FACTORS.len()).prop_map(|(k, f)| Mutation::Scale(k, f)),
        1 => any::<usize>().prop_map(Mutation::DeleteLine),
        1 => any::<usize>().prop_map(Mutation::DuplicateLine),
        2 => (any::<usize>(), any::<usize>()).prop_map(|(j, k)| Mutation::SwapNames(j, k)),
        1 => any::<usize>().prop_map(Mutation::Truncate),
    ]
}

/// Byte ranges of the number literals outside comments (a digit not inside a name).
fn numbers(text: &str) -> Vec<std::ops::Range<usize>> {
    let mut found = Vec::new();
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let code = line.split('#').next().unwrap_or("");
        let b = code.as_bytes();
        let mut i = 0;
        while i < b.len() {
            let starts = (b[i].is_ascii_digit()
                || (b[i] == b'-' && b.get(i + 1).is_some_and(u8::is_ascii_digit)))
                && (i == 0
                    || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_' || b[i - 1] == b'.'));
            if !starts {
                i += 1;
                continue;
            }
            let start = i;
            i += 1;
            while i < b.len()
                && (b[i].is_ascii_alphanumeric() || matches!(b[i], b'.' | b'+' | b'-' | b'_'))
            {
                i += 1;
            }
            // Digits inside a quoted name (`"G0"`) are not numbers.
            let quotes = code[..start].matches('"').count();
            if quotes % 2 == 0 {
                found.push(offset + start..offset + i);
            }
        }
        offset += line.len();
    }
    found
}

/// Byte ranges of the quoted names (`"..."`), quotes excluded.
fn names(text: &str) -> Vec<std::ops::Range<usize>> {
    let mut found = Vec::new();
    let mut open = None;
    for (i, c) in text.char_indices() {
        match (c, open) {
            ('"', None) => open = Some(i + 1),
            ('"', Some(start)) => {
                found.push(start..i);
                open = None;
            }
            ('\n', Some(_)) => open = None,
            _ => {}
        }
    }
    found
}

fn apply(text: &str, m: &Mutation) -> String {
    let lines: Vec<&str> = text.split_inclusive('\n').collect();
    if lines.is_empty() {
        // A scene truncated to nothing has no line to delete or duplicate.
        return text.to_owned();
    }
    match *m {
        Mutation::Number(k, e) => {
            let found = numbers(text);
            if found.is_empty() {
                return text.to_owned();
            }
            let r = found[k % found.len()].clone();
            format!("{}{}{}", &text[..r.start], EXTREMES[e], &text[r.end..])
        }
        Mutation::Scale(k, f) => {
            let found = numbers(text);
            if found.is_empty() {
                return text.to_owned();
            }
            let r = found[k % found.len()].clone();
            let Ok(v) = text[r.clone()].parse::<f64>() else {
                return text.to_owned();
            };
            format!("{}{:?}{}", &text[..r.start], v * FACTORS[f], &text[r.end..])
        }
        Mutation::DeleteLine(k) => {
            let k = k % lines.len();
            lines
                .iter()
                .enumerate()
                .filter(|(i, _)| *i != k)
                .map(|(_, l)| *l)
                .collect()
        }
        Mutation::DuplicateLine(k) => {
            let k = k % lines.len();
            let mut out = String::new();
            for (i, l) in lines.iter().enumerate() {
                out.push_str(l);
                if i == k {
                    out.push_str(l);
                }
            }
            out
        }
        Mutation::SwapNames(j, k) => {
            let found = names(text);
            if found.len() < 2 {
                return text.to_owned();
            }
            let (mut a, mut b) = (
                found[j % found.len()].clone(),
                found[k % found.len()].clone(),
            );
            if a.start > b.start {
                std::mem::swap(&mut a, &mut b);
            }
            if a == b {
                return text.to_owned();
            }
            format!(
                "{}{}{}{}{}",
                &text[..a.start],
                &text[b.clone()],
                &text[a.end..b.start],
                &text[a.clone()],
                &text[b.end..]
            )
        }
        Mutation::Truncate(k) => {
            let mut k = k % (text.len() + 1);
            while !text.is_char_boundary(k) {
                k -= 1;
            }
            text[..k].to_owned()
        }
    }
}

/// How far the cases got: read, passed `check`, run to the end; and how many the check and
/// the run refused alike, and how many `check` accepted and the run refused while solving.
static CHECKED: AtomicUsize = AtomicUsize::new(0);
static RAN: AtomicUsize = AtomicUsize::new(0);
static REFUSED_BY_BOTH: AtomicUsize = AtomicUsize::new(0);
static REFUSED_WHILE_SOLVING: AtomicUsize = AtomicUsize::new(0);

/// `mechdiff check`, in-process: the reader `run` uses ([`any::read`]), then for a linkage
/// its mobility and its motion range held against the sweep.
fn check(file: &str, text: &str) -> Result<(), Error> {
    match any::read(file, text, &[])? {
        AnyScene::Linkage(scene) => scene::check(&scene).map(drop),
        AnyScene::Cam(_) | AnyScene::Rotor(_) | AnyScene::Formula(..) => Ok(()),
    }
}

/// `mechdiff run`, in-process, with every output it can write (`--csv`, `--json`, the
/// profile, the report) written to memory: `Ok(None)` for a sweep too long to run here,
/// `Ok(Some(problems))` (empty when every number is finite), or its error.
fn run(file: &str, text: &str) -> Result<Option<String>, Error> {
    let mut out = Vec::new();
    let mut problems = String::new();
    let written = |r: std::io::Result<()>| r.expect("writing to memory");
    match any::read(file, text, &[])? {
        AnyScene::Linkage(scene) => {
            if scene.positions.len() > LONGEST_SWEEP {
                return Ok(None);
            }
            let report = scene::run(&scene)?;
            for row in &report.rows {
                for (v, c) in row.iter().zip(&report.columns) {
                    if !(v.is_finite() && (v / c.factor).is_finite()) {
                        problems += &format!("column {} is {v} at {}; ", c.header(), row[0]);
                    }
                }
            }
            for dead in &report.dead_positions {
                for d in &dead.positions {
                    if !(d.phi.is_finite() && d.value.is_finite()) {
                        problems += &format!("dead position of {}: {d:?}; ", dead.output);
                    }
                }
            }
        }
        AnyScene::Cam(cam) => {
            written(report::cam::write_report(&cam, &mut out));
            written(report::cam::write_svaj_csv(&cam, &mut out));
            written(report::cam::write_profile_csv(&cam, &mut out));
            written(report::cam::write_json(&cam, &mut out));
        }
        AnyScene::Rotor(rotor) => {
            let answers = rotor.rotor.answers()?;
            out.extend(rotor.lines()?.join("\n").bytes());
            written(report::rotor::write_csv(&rotor, &answers, &mut out));
            written(report::rotor::write_json(&rotor, &answers, &mut out));
        }
        AnyScene::Formula(formulas, _) => {
            let table = formula::table(&formulas, file)?;
            for (phi, row) in table.positions.iter().zip(&table.rows) {
                if !(phi.is_finite() && row.iter().flatten().all(|v| v.is_finite())) {
                    problems += &format!("a value at φ = {phi} is not finite; ");
                }
            }
        }
    }
    let out = String::from_utf8_lossy(&out);
    if let Some(word) = non_finite_word(&out) {
        problems += &format!("the run wrote `{word}`:\n{out}");
    }
    Ok(Some(problems))
}

/// A word of the output that is not a finite number: `inf`, `NaN` (as Rust prints them).
fn non_finite_word(text: &str) -> Option<&str> {
    text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '-'))
        .find(|w| matches!(w.trim_start_matches('-'), "inf" | "NaN" | "nan"))
}

/// Checks and runs a mutated scene; `Err` describes a broken promise: `check` and `run`
/// disagree (run accepts what check refused, or refuses before solving what check accepted),
/// or a run that succeeded gave a number that is not finite. Errors of the scene are the
/// expected answer.
fn check_and_run(file: &str, text: &str) -> Result<(), String> {
    let checked = check(file, text);
    let ran = run(file, text);
    if checked.is_ok() {
        CHECKED.fetch_add(1, Ordering::Relaxed);
    }
    match (&checked, &ran) {
        (Err(c), Ok(Some(_))) => Err(format!("`run` accepts what `check` refused: {c}")),
        (Ok(()), Err(r)) if !r.is_found_by_solving() => Err(format!(
            "`check` accepts what `run` refuses before solving: {r}"
        )),
        (Ok(()), Err(_)) => {
            REFUSED_WHILE_SOLVING.fetch_add(1, Ordering::Relaxed);
            Ok(())
        }
        (Err(_), Err(_)) => {
            REFUSED_BY_BOTH.fetch_add(1, Ordering::Relaxed);
            Ok(())
        }
        (_, Ok(None)) => Ok(()),
        (Ok(()), Ok(Some(problems))) => {
            RAN.fetch_add(1, Ordering::Relaxed);
            if problems.is_empty() {
                Ok(())
            } else {
                Err(format!(
                    "the run succeeded with numbers that are not finite: {problems}"
                ))
            }
        }
    }
}

/// Runs `check_and_run` on its own thread so a hang is reported (after [`HANG`]) instead of
/// stopping the test run; a panic there is reported as a failure with its message.
fn guarded(file: String, text: String) -> Result<(), String> {
    let (send, receive) = mpsc::channel();
    let worker = std::thread::spawn(move || {
        let _ = send.send(check_and_run(&file, &text));
    });
    match receive.recv_timeout(HANG) {
        Ok(result) => {
            let _ = worker.join();
            result
        }
        Err(mpsc::RecvTimeoutError::Timeout) => Err(format!("no answer within {HANG:?} (a hang)")),
        Err(mpsc::RecvTimeoutError::Disconnected) => {
            Err("panicked (see the message above)".to_owned())
        }
    }
}

/// Every scene file shipped (`scenes/` and its folders, recursively: linkages, cams, rotors,
/// formula scenes, the cam-driven linkage) and the test data scenes (`tests/data`).
fn shipped_scenes() -> Vec<(String, String)> {
    fn walk(dir: &Path, found: &mut Vec<std::path::PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(&path, found);
            } else if path.extension().is_some_and(|x| x == "toml") {
                found.push(path);
            }
        }
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut paths = Vec::new();
    walk(&root.join("scenes"), &mut paths);
    walk(&root.join("tests/data"), &mut paths);
    paths.sort();
    paths
        .into_iter()
        .map(|p| {
            (
                p.display().to_string(),
                std::fs::read_to_string(&p).unwrap(),
            )
        })
        .collect()
}

/// The shipped scenes themselves, every folder: each of `scenes/` passes `check` (the 17 formula scenes
/// were refused with "unknown field `outputs`" before), and `run` gives the same verdict (it
/// may only add an error found by solving: two hard formula scenes overflow at a position).
#[test]
fn every_shipped_scene_gets_the_same_verdict_from_check_and_run() {
    let scenes = shipped_scenes();
    for folder in [
        "scenes/cams/",
        "scenes/hard/",
        "scenes/formulas/",
        "tests/data/",
    ] {
        assert!(
            scenes.iter().any(|(p, _)| p.contains(folder)),
            "no scene from {folder}"
        );
    }
    for (path, text) in &scenes {
        // The scenes of `tests/data` include fragments and bad scenes on purpose.
        if !path.contains("tests/data") {
            check(path, text).unwrap_or_else(|e| panic!("check refuses {path}: {e}"));
        }
        check_and_run(path, text).unwrap_or_else(|e| panic!("{path}: {e}"));
    }
}

#[test]
fn mutated_scenes_give_an_error_or_finite_numbers_never_a_panic_or_a_hang() {
    let scenes = shipped_scenes();
    assert!(scenes.len() >= 40, "{} scenes shipped", scenes.len());
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(CASES);
    let config = Config {
        cases,
        // Failures are saved here (committed) and tried first next time.
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(
            "proptest-regressions/fuzz_scenes.txt",
        ))),
        ..Config::default()
    };
    let mut runner = TestRunner::new(config);
    let start = Instant::now();
    let strategy = (0..scenes.len(), prop::collection::vec(mutation(), 1..=3));
    runner
        .run(&strategy, |(k, mutations)| {
            let mut text = scenes[k].1.clone();
            for m in &mutations {
                text = apply(&text, m);
            }
            guarded(scenes[k].0.clone(), text.clone()).map_err(|e| {
                TestCaseError::fail(format!(
                    "{} mutated by {mutations:?}: {e}\n{text}",
                    scenes[k].0
                ))
            })
        })
        .unwrap();
    eprintln!(
        "fuzz: {cases} mutated cases of {} shipped scenes in {:.1} s: {} passed check, {} ran \
         to the end, {} refused while solving after check, {} refused by check and run alike",
        scenes.len(),
        start.elapsed().as_secs_f64(),
        CHECKED.load(Ordering::Relaxed),
        RAN.load(Ordering::Relaxed),
        REFUSED_WHILE_SOLVING.load(Ordering::Relaxed),
        REFUSED_BY_BOTH.load(Ordering::Relaxed),
    );
}

#[test]
fn the_mutations_find_numbers_and_names() {
    let text = "[points]\nG0 = [0, -12.5e-3] # 7 mm\n[links]\ncrank = [\"O\", \"A1\"]\n";
    let found: Vec<&str> = numbers(text).into_iter().map(|r| &text[r]).collect();
    assert_eq!(found, ["0", "-12.5e-3"]);
    let found: Vec<&str> = names(text).into_iter().map(|r| &text[r]).collect();
    assert_eq!(found, ["O", "A1"]);
    let swapped = apply(text, &Mutation::SwapNames(0, 1));
    assert!(swapped.contains("[\"A1\", \"O\"]"), "{swapped}");
}
