//! Scenes with `[simulate]`: the machine moving under its motor, read, run and checked —
//! located errors for bad input, the scene's outputs along the motion equal to a
//! prescribed-motion run's at the simulated state, rows streamed, and the shipped examples
//! (seed 000's shaper, seed 001's rack machine) against physical facts.

use mechdiff::scene::motion::{MotionReport, run};
use mechdiff::scene::{self, Positions, Scene};
use mechdiff::stream::Sink;
use mechdiff::stream::motion::MotionSinks;
use std::path::PathBuf;

fn text(name: &str) -> String {
    std::fs::read_to_string(format!("{}/scenes/{name}", env!("CARGO_MANIFEST_DIR"))).unwrap()
}

/// The 1-based line of the first occurrence of `needle` in `text`.
fn line_of(text: &str, needle: &str) -> usize {
    let at = text.find(needle).unwrap_or_else(|| panic!("{needle} not in the scene"));
    text[..at].lines().count() + usize::from(text[..at].ends_with('\n'))
}

/// The rows of a CSV table in SI (each value times its column's factor).
fn rows_si(csv: &[u8], columns: &[mechdiff::scene::Column]) -> Vec<Vec<f64>> {
    let text = String::from_utf8(csv.to_vec()).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap();
    assert_eq!(header.split(',').count(), columns.len());
    lines
        .map(|l| {
            l.split(',')
                .zip(columns)
                .map(|(v, c)| v.parse::<f64>().unwrap() * c.factor)
                .collect()
        })
        .collect()
}

/// Runs the `[simulate]` of `scene`: its report and its tables over time and over the angle
/// (SI).
fn simulated(scene: &Scene) -> (MotionReport, Vec<Vec<f64>>, Vec<Vec<f64>>) {
    let (mut time, mut steady) = (Vec::new(), Vec::new());
    let mut sinks = MotionSinks {
        table: None,
        time_csv: Some(Sink {
            path: PathBuf::from("time.csv"),
            out: &mut time,
        }),
        steady_csv: Some(Sink {
            path: PathBuf::from("steady.csv"),
            out: &mut steady,
        }),
    };
    let report = run(scene, &mut sinks).unwrap();
    drop(sinks);
    let t = if time.is_empty() {
        Vec::new()
    } else {
        rows_si(&time, &report.time_columns)
    };
    let s = if steady.is_empty() {
        Vec::new()
    } else {
        rows_si(&steady, &report.steady_columns)
    };
    (report, t, s)
}

/// The prescribed-motion run of `scene` (without `[simulate]`) at drive position `phi` with
/// speed `omega` and acceleration `alpha` (SI): its columns' names and its one row.
fn prescribed(scene: &Scene, phi: f64, omega: f64, alpha: f64) -> (Vec<String>, Vec<f64>) {
    let mut s = scene.clone();
    s.motion = None;
    s.positions = Positions::List(vec![phi]);
    s.drive.speed = Some(omega);
    s.drive.acceleration = alpha;
    let report = scene::run(&s).unwrap();
    let names = report.columns.iter().map(|c| c.name.clone()).collect();
    (names, report.rows[0].clone())
}

/// Bad `[simulate]` and motor data are refused where they are written, saying what is
/// wrong: a tolerance of 0, turns and time out of their bounds or not finite, a negative
/// flywheel or rotor inertia, a breakdown slip of 0, a characteristic's missing number.
#[test]
fn bad_simulate_sections_are_located_errors() {
    let good = text("shaper_motor.toml");
    let cases: [(&str, &str, &str, &str); 8] = [
        ("tolerance = 1e-10", "tolerance = 0", "tolerance = 0", "tolerance"),
        ("turns = 200", "turns = 1e9", "turns = 1e9", "whole number from 2"),
        ("time = 20 ", "time = inf ", "time = inf", "longest simulated time"),
        ("turns = 200", "turns = 200\nflywheel = -1", "flywheel = -1", "must be ≥ 0"),
        ("rotor_inertia = 0.012", "rotor_inertia = -0.012", "rotor_inertia", "rotor_inertia"),
        ("breakdown_slip = 0.25", "breakdown_slip = 0", "characteristic =", "breakdown_slip"),
        (
            "breakdown_torque = 66, ",
            "",
            "characteristic =",
            "needs `breakdown_torque`",
        ),
        ("delta = 0.02 ", "delta = 2 ", "delta = 2", "`delta`"),
    ];
    for (old, new, at, says) in cases {
        assert!(good.contains(old), "{old}");
        let bad = good.replacen(old, new, 1);
        let e = scene::parse("shaper_motor.toml", &bad).unwrap_err().to_string();
        let line = line_of(&bad, at);
        assert!(
            e.starts_with(&format!("shaper_motor.toml:{line}:")) && e.contains(says),
            "{new}: {e}"
        );
    }
    // A flywheel without its δ, and a steady state of a drive that slides.
    let bad = good.replacen("delta = 0.02 ", "", 1);
    let e = scene::parse("s.toml", &bad).unwrap_err().to_string();
    assert!(e.contains("add `delta"), "{e}");
}

/// A motor too weak to move the machine against the cutting force where it starts is a
/// located error at the motor's characteristic, with the drive position in degrees; a
/// steady state not found within the turns allowed is one at `turns`. Neither hangs or
/// gives a NaN.
#[test]
fn a_motor_that_cannot_start_and_a_missing_steady_state_are_located_errors() {
    let good = text("shaper_motor.toml");
    let weak = good
        .replacen(
            "characteristic = { type = \"induction\", synchronous_speed = 1500, breakdown_torque = 66, breakdown_slip = 0.25 }",
            "characteristic = { type = \"constant\", torque = 0.001 }",
            1,
        )
        .replacen("speed = 95 ", "start = 180\nspeed = 95 ", 1);
    let scene = scene::parse("shaper_motor.toml", &weak).unwrap();
    let mut sinks = MotionSinks::default();
    let e = run(&scene, &mut sinks).unwrap_err().to_string();
    let line = line_of(&weak, "characteristic =");
    assert!(
        e.starts_with(&format!("shaper_motor.toml:{line}:"))
            && e.contains("cannot start")
            && e.contains("180 deg"),
        "{e}"
    );

    // A motor whose breakdown torque cannot carry the cut: every turn loses energy.
    let stalling = good
        .replacen("breakdown_torque = 66", "breakdown_torque = 5", 1)
        .replacen("find = [\"start_up\", \"steady_state\", \"flywheel\"]", "find = [\"steady_state\"]", 1)
        .replacen("delta = 0.02 ", "", 1);
    let scene = scene::parse("shaper_motor.toml", &stalling).unwrap();
    let e = run(&scene, &mut MotionSinks::default())
        .unwrap_err()
        .to_string();
    let line = line_of(&stalling, "turns = 200");
    assert!(
        e.starts_with(&format!("shaper_motor.toml:{line}:")) && e.contains("steady"),
        "{e}"
    );
}
