//! A bounded fuzz test: every scene in `scenes/`, mutated (numbers set to extremes, lines
//! deleted or duplicated, names swapped, the text truncated), goes through `check` and `run`
//! in-process. Whatever the mutation, the library must not panic or hang, and either refuse
//! the scene with an error or give only finite numbers.

use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use mechdiff::scene;
use proptest::prelude::*;
use proptest::test_runner::{Config, FileFailurePersistence, TestRunner};

/// How many mutated scenes are tried. In a debug build the whole test takes about a minute on
/// one core (the time is printed); CI runs it with `cargo test --workspace`.
const CASES: u32 = 3000;

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

/// How far the cases got: parsed, checked, run to the end.
static PARSED: AtomicUsize = AtomicUsize::new(0);
static CHECKED: AtomicUsize = AtomicUsize::new(0);
static RAN: AtomicUsize = AtomicUsize::new(0);

/// Parses, checks and runs a mutated scene; `Err` describes a broken promise (a non-finite
/// number in the output). Errors of the scene are the expected answer.
fn check_and_run(text: &str) -> Result<(), String> {
    let Ok(scene) = scene::parse("fuzz.toml", text) else {
        return Ok(());
    };
    PARSED.fetch_add(1, Ordering::Relaxed);
    if scene::check(&scene).is_err() || scene.positions.len() > LONGEST_SWEEP {
        return Ok(());
    }
    CHECKED.fetch_add(1, Ordering::Relaxed);
    let Ok(report) = scene::run(&scene) else {
        return Ok(());
    };
    RAN.fetch_add(1, Ordering::Relaxed);
    for row in &report.rows {
        for (v, c) in row.iter().zip(&report.columns) {
            if !(v.is_finite() && (v / c.factor).is_finite()) {
                return Err(format!(
                    "column {} is {v} at drive position {}",
                    c.header(),
                    row[0]
                ));
            }
        }
    }
    for dead in &report.dead_positions {
        for d in &dead.positions {
            if !(d.phi.is_finite() && d.value.is_finite()) {
                return Err(format!("dead position of {}: {d:?}", dead.output));
            }
        }
    }
    Ok(())
}

/// Runs `check_and_run` on its own thread so a hang is reported (after [`HANG`]) instead of
/// stopping the test run; a panic there is reported as a failure with its message.
fn guarded(text: String) -> Result<(), String> {
    let (send, receive) = mpsc::channel();
    let worker = std::thread::spawn(move || {
        let _ = send.send(check_and_run(&text));
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

#[test]
fn mutated_scenes_give_an_error_or_finite_numbers_never_a_panic_or_a_hang() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut scenes: Vec<(String, String)> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| {
            (
                p.display().to_string(),
                std::fs::read_to_string(&p).unwrap(),
            )
        })
        .collect();
    scenes.sort();
    assert!(
        scenes.len() >= 8,
        "the scenes/ folder has {} scenes",
        scenes.len()
    );
    let config = Config {
        cases: CASES,
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
            guarded(text.clone()).map_err(|e| {
                TestCaseError::fail(format!(
                    "{} mutated by {mutations:?}: {e}\n{text}",
                    scenes[k].0
                ))
            })
        })
        .unwrap();
    eprintln!(
        "fuzz: {CASES} mutated scenes in {:.1} s: {} parsed, {} passed check, {} ran to the end",
        start.elapsed().as_secs_f64(),
        PARSED.load(Ordering::Relaxed),
        CHECKED.load(Ordering::Relaxed),
        RAN.load(Ordering::Relaxed),
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
