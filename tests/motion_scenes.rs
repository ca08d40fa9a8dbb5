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
    let at = text
        .find(needle)
        .unwrap_or_else(|| panic!("{needle} not in the scene"));
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

/// The motor torque a prescribed-motion run needs at the state `(φ, φ̇, φ̈)` is `motor`, to
/// 1e-9 relative (the equation of motion's Newton steps stop at 1e-13 of φ̈); `at` names the
/// row in the message.
fn assert_motor_torque_is_needed(scene: &Scene, state: (f64, f64, f64), motor: f64, at: &str) {
    let (names, values) = prescribed(scene, state.0, state.1, state.2);
    let needed = values[names.iter().position(|n| n == "M_motor").unwrap()];
    assert!(
        (needed - motor).abs() <= 1e-9 * motor.abs(),
        "{at}: {needed} vs {motor}"
    );
}

/// Bad `[simulate]` and motor data are refused where they are written, saying what is
/// wrong: a tolerance of 0, turns and time out of their bounds or not finite, a negative
/// flywheel or rotor inertia, a breakdown slip of 0, a characteristic's missing number.
#[test]
fn bad_simulate_sections_are_located_errors() {
    let good = text("shaper_motor.toml");
    let cases: [(&str, &str, &str, &str); 8] = [
        (
            "tolerance = 1e-10",
            "tolerance = 0",
            "tolerance = 0",
            "tolerance",
        ),
        (
            "turns = 200",
            "turns = 1e9",
            "turns = 1e9",
            "whole number from 2",
        ),
        (
            "time = 20 ",
            "time = inf ",
            "time = inf",
            "longest simulated time",
        ),
        (
            "turns = 200",
            "turns = 200\nflywheel = -1",
            "flywheel = -1",
            "must be ≥ 0",
        ),
        (
            "rotor_inertia = 0.012",
            "rotor_inertia = -0.012",
            "rotor_inertia",
            "rotor_inertia",
        ),
        (
            "breakdown_slip = 0.25",
            "breakdown_slip = 0",
            "characteristic =",
            "breakdown_slip",
        ),
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
        let e = scene::parse("shaper_motor.toml", &bad)
            .unwrap_err()
            .to_string();
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
        .replacen(
            "find = [\"start_up\", \"steady_state\", \"flywheel\"]",
            "find = [\"steady_state\"]",
            1,
        )
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

/// The columns of the scene's own outputs in a simulated table (after the machine's state
/// columns) by name, with the prescribed run's value of the same name.
fn compare_outputs(
    scene: &Scene,
    columns: &[mechdiff::scene::Column],
    first: usize,
    row: &[f64],
    (phi, omega, alpha): (f64, f64, f64),
) -> usize {
    let (names, values) = prescribed(scene, phi, omega, alpha);
    let mut compared = 0;
    for (c, v) in columns.iter().zip(row).skip(first) {
        let k = names.iter().position(|n| *n == c.name).unwrap();
        let w = values[k];
        // The same exact evaluation at the same state: equal to rounding; 1e-12 of the
        // value, or of 1 (SI) for a value near zero (a shaking moment crossing 0).
        assert!(
            (v - w).abs() <= 1e-12 * v.abs().max(w.abs()).max(1.0),
            "{} at φ = {phi}: {v} vs {w}",
            c.name
        );
        compared += 1;
    }
    compared
}

/// Item 5: along the simulated steady state, the scene's outputs (the ram's position,
/// velocity and acceleration, the shaking force) are those of a prescribed-motion run at the
/// same φ with ω and α set to the simulated ones, to 1e-12 (the same exact evaluation); and
/// the motor torque the prescribed run's `[[dynamics]] drive_torque` needs for that
/// acceleration is the characteristic's at that speed: the equation of motion holds, checked
/// by the kinetostatics (1e-9 relative: φ̈ is the engine's to its Newton/closed-form
/// rounding, the torque a difference of terms some 30 times larger).
#[test]
fn outputs_along_the_steady_state_equal_a_prescribed_run_at_the_simulated_state() {
    let scene = scene::load("scenes/shaper_motor.toml").unwrap();
    let (report, _, steady) = simulated(&scene);
    assert!(report.steady.is_some() && steady.len() > 10);
    let cols = &report.steady_columns;
    let index = |name: &str| cols.iter().position(|c| c.name == name).unwrap();
    let (phi, omega, alpha, motor) = (
        index("phi"),
        index("omega"),
        index("alpha"),
        index("M_motor"),
    );
    let first = index("J") + 1;
    for row in [
        &steady[1],
        &steady[steady.len() / 3],
        &steady[2 * steady.len() / 3],
    ] {
        let state = (row[phi], row[omega], row[alpha]);
        assert_eq!(compare_outputs(&scene, cols, first, row, state), 6);
        assert_motor_torque_is_needed(&scene, state, row[motor], "");
    }
}

/// Seed 001's rack machine under its DC motor, with gravity, the resisting force, Coulomb
/// friction in the slot and on the incline, the mesh's and the gearbox's efficiencies: at
/// every row of the start-up the motor torque the kinetostatics need for the simulated φ̈
/// (a prescribed-motion run at the row's φ, φ̇, φ̈) is the characteristic's torque at the
/// motor's speed — the implicit equation of motion with friction and efficiencies is met, to
/// 1e-9 relative (its Newton steps stop at 1e-13 of φ̈) — and the outputs agree as above.
/// The start-up reaches 1.2 rad/s in less time than the machine would take at the stall
/// torque's acceleration falling linearly to zero (a bound, not a result).
#[test]
fn the_rack_machine_starts_up_meeting_its_equation_of_motion_with_friction_and_efficiencies() {
    let scene = scene::load("scenes/rack_slotted_link_motor.toml").unwrap();
    let (report, time, _) = simulated(&scene);
    let s = report.start_up.unwrap();
    assert!(s.time_to_speed > 0.0 && s.time_to_speed < 1.0, "{s:?}");
    let cols = &report.time_columns;
    let index = |name: &str| cols.iter().position(|c| c.name == name).unwrap();
    let (t, omega, motor) = (index("t"), index("omega"), index("M_motor"));
    let last = time.last().unwrap();
    assert!((last[omega] - 1.2).abs() < 1e-12 && last[t] == s.time_to_speed);
    let first = index("event") + 1;
    for row in time.iter().skip(1) {
        let state = (row[index("phi")], row[omega], row[index("alpha")]);
        compare_outputs(&scene, cols, first, row, state);
        assert_motor_torque_is_needed(&scene, state, row[motor], &format!("t = {}", row[t]));
    }
}

/// The rows go to the outputs as the integration gives them: one write per CSV row (and one
/// for the header), while the report keeps only counts, the headline numbers and the
/// diagrams' curves, each thinned to at most `CURVE_POINTS` however long the run.
#[test]
fn simulated_rows_are_streamed_not_kept() {
    struct Counting {
        writes: usize,
        bytes: usize,
    }
    impl std::io::Write for Counting {
        fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
            self.writes += 1;
            self.bytes += buf.len();
            Ok(buf.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }
    let text = text("shaper_motor.toml")
        .replacen(
            "find = [\"start_up\", \"steady_state\", \"flywheel\"]",
            "find = [\"start_up\", \"steady_state\"]",
            1,
        )
        .replacen("delta = 0.02 ", "", 1);
    let scene = scene::parse("shaper_motor.toml", &text).unwrap();
    let mut csv = Counting {
        writes: 0,
        bytes: 0,
    };
    let mut sinks = MotionSinks {
        time_csv: Some(Sink {
            path: PathBuf::from("time.csv"),
            out: &mut csv,
        }),
        ..MotionSinks::default()
    };
    let report = run(&scene, &mut sinks).unwrap();
    drop(sinks);
    assert!(report.time_rows > 10);
    assert_eq!(csv.writes, report.time_rows + 1);
    let mut thinned = mechdiff::scene::motion::Thinned::default();
    for k in 0..1_000_000 {
        thinned.push([k as f64, 0.0]);
    }
    let cap = mechdiff::scene::motion::CURVE_POINTS;
    assert!(thinned.points.len() <= cap && thinned.points.len() >= cap / 2);
    assert_eq!(thinned.points[0], [0.0, 0.0]);
}

/// Seed 000's shaper under its induction motor: over one period of the steady state the
/// motor's work equals the cutting force's (a lossless machine whose kinetic energy returns),
/// W = F·stroke = 2000 N × 0.525875892721 m (whitworth_000.md: the load acts between the
/// dead positions, where the ram travels its whole stroke), to 1e-8 relative. The motor's
/// work ∫ M_motor/τ dφ is summed here over the table's rows by the trapezoid rule with its
/// end correction h²/12·(f′₀ − f′₁) (error O(h⁴)), f′ from the Kloss formula's derivative
/// written out here and the rows' φ̈ (continuous: the load switches where x_C′ = 0); at the
/// scene's tolerance 1e-13 it changes by 1.4e-10 relative from 1e-14. The steady time-mean
/// speed lies below the no-load 100 rpm (the motor slips under load) and the flywheel sized
/// for δ = 0.02 gives δ = 0.02 when simulated (to 1e-6).
#[test]
fn the_shaper_motor_work_over_a_steady_period_equals_the_cutting_work() {
    let text = text("shaper_motor.toml").replacen("tolerance = 1e-10", "tolerance = 1e-13", 1);
    let scene = scene::parse("shaper_motor.toml", &text).unwrap();
    let (report, _, steady) = simulated(&scene);
    let cols = &report.steady_columns;
    let index = |name: &str| cols.iter().position(|c| c.name == name).unwrap();
    let (phi, omega, alpha, motor) = (
        index("phi"),
        index("omega"),
        index("alpha"),
        index("M_motor"),
    );
    let tau = 1.0 / 15.0;
    let ws = 1500.0 * std::f64::consts::PI / 30.0;
    let (mk, sk) = (66.0, 0.25);
    // f = M_motor/τ; df/dφ = (dM/dω_m)(dω_m/dφ)/τ, dM/dω_m = −(dM/ds)/ω_s, dω_m/dφ = φ̈/(φ̇τ).
    let df = |r: &[f64]| {
        let s = (ws - r[omega] / tau) / ws;
        let dm_ds = 2.0 * mk * sk * (sk * sk - s * s) / (s * s + sk * sk).powi(2);
        -dm_ds / ws * r[alpha] / (r[omega] * tau) / tau
    };
    let mut work = 0.0;
    for p in steady.windows(2) {
        let h = p[1][phi] - p[0][phi];
        work +=
            0.5 * (p[0][motor] + p[1][motor]) / tau * h + h * h / 12.0 * (df(&p[0]) - df(&p[1]));
    }
    let load = 2000.0 * 0.525875892721;
    assert!((work / load - 1.0).abs() < 1e-8, "{work} vs {load}");
    assert!((steady.last().unwrap()[phi] - std::f64::consts::TAU).abs() < 1e-12);
    let s = report.steady.unwrap();
    let no_load = 100.0 * std::f64::consts::PI / 30.0;
    assert!(
        s.mean_time < no_load && s.mean_time > 0.9 * no_load,
        "{}",
        s.mean_time
    );
    let f = report.flywheel.unwrap();
    assert!(
        (f.steady.delta_time - 0.02).abs() < 1e-6,
        "{}",
        f.steady.delta_time
    );
    assert!(f.exact > 0.0 && f.classic > 0.0);
}

/// `mechdiff run` of a scene with `[simulate]` (the rack machine started, then coasting to
/// rest against its friction): the plan names the equation's terms, the tables and the
/// headline numbers are printed, `--csv` writes the table over time (its time increasing,
/// its last row at rest, event 4), `--plot` draws ω(t) and the motor's torque; an option
/// the run cannot honour (`--json`) is refused naming it.
#[test]
fn mechdiff_run_simulates_prints_and_writes_the_tables_and_diagrams() {
    use crate::common::{mechdiff, stderr, stdout, temp_file};
    let text = text("rack_slotted_link_motor.toml").replacen(
        "find = [\"start_up\"]",
        "find = [\"start_up\", \"coast_down\"]",
        1,
    );
    let path = temp_file("rack_motor.toml");
    std::fs::write(&path, &text).unwrap();
    let dir = temp_file("rack_motor_plot");
    let csv = temp_file("rack_motor.csv");
    let out = mechdiff(&[
        "run",
        path.to_str().unwrap(),
        "--csv",
        csv.to_str().unwrap(),
        "--plot",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let printed = stdout(&out);
    for says in [
        "J(φ)·φ̈ + ½·J′(φ)·φ̇²",
        "weights (g = 9.81",
        "Coulomb friction in A, incline",
        "the gearbox η = 0.9",
        "linear (DC shunt)",
        "the motion in time",
        "start-up from rest",
        "coast-down (motor off)",
    ] {
        assert!(printed.contains(says), "{says}: {printed}");
    }
    assert!(!printed.contains("steady state over one turn"));
    let written = std::fs::read_to_string(&csv).unwrap();
    let rows: Vec<Vec<f64>> = (written.lines().skip(1))
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert!(written.starts_with("t [s],phi [deg],omega [rad/s],alpha [rad/s^2],M_motor [N*m]"));
    assert!(rows.windows(2).all(|w| w[1][0] >= w[0][0]));
    let last = rows.last().unwrap();
    assert_eq!((last[2], last[7]), (0.0, 4.0));
    for name in ["omega_time.svg", "motor_torque.svg"] {
        assert!(
            std::fs::read_to_string(dir.join(name))
                .unwrap()
                .starts_with("<svg")
        );
    }
    assert!(!dir.join("omega_angle.svg").exists());
    let refused = mechdiff(&["run", path.to_str().unwrap(), "--json", "x.json"]);
    assert!(!refused.status.success() && stderr(&refused).contains("--json"));
    let _ = std::fs::remove_dir_all(&dir);
    for f in [path, csv] {
        let _ = std::fs::remove_file(f);
    }
}

/// The shaper's start-up and steady state without the flywheel's sizing (a shorter run).
fn shaper_without_flywheel() -> Scene {
    let text = text("shaper_motor.toml")
        .replacen(
            "find = [\"start_up\", \"steady_state\", \"flywheel\"]",
            "find = [\"start_up\", \"steady_state\"]",
            1,
        )
        .replacen("delta = 0.02 ", "", 1);
    scene::parse("shaper_motor.toml", &text).unwrap()
}

/// The report's playback (item 6, "a report that plays the motion in real time"): its frames
/// lie at equal steps of one clock (exact multiples of the step, a power of two of seconds),
/// at most `PLAYBACK_FRAMES`; the start-up's frames run from rest at t = 0 to within one step
/// of the time the speed was reached, the steady period's from t = 0 to within one step of
/// the period. Every frame lies on the simulated motion: its t(φ) equals the steady table's
/// t at that φ, interpolated between the table's rows (cubic Hermite with dt/dφ = 1/φ̇, the
/// other direction from the frames' φ(t)), to 1e-7 s (both interpolants err by about
/// h⁴/384·|d⁴t/dφ⁴| with the table's steps of h ≈ 1.6°: 1.0e-8 s measured; 1e-7 s is 1.6e-7
/// of the period and 1/20000 of a frame step); and each frame's row meets the equation of motion: the
/// motor torque a prescribed-motion run needs for the frame's φ, φ̇, φ̈ is the frame's
/// M_motor, to 1e-9 relative (as for the table's rows above).
#[test]
fn the_report_plays_the_simulated_motion_at_equal_steps_of_simulated_time() {
    use mechdiff::scene::motion::{MotionOptions, PLAYBACK_FRAMES, run_with};
    let scene = shaper_without_flywheel();
    let mut steady_csv = Vec::new();
    let mut sinks = MotionSinks {
        steady_csv: Some(Sink {
            path: PathBuf::from("steady.csv"),
            out: &mut steady_csv,
        }),
        ..MotionSinks::default()
    };
    let options = MotionOptions {
        playback: true,
        ..MotionOptions::default()
    };
    let report = run_with(&scene, &mut sinks, &options).unwrap();
    drop(sinks);
    let steady = rows_si(&steady_csv, &report.steady_columns);
    let p = report.playback.as_ref().unwrap();
    let names: Vec<&str> = p.columns.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(
        names[..8],
        [
            "clock", "t", "phi", "omega", "alpha", "M_motor", "M_drive", "J"
        ]
    );
    assert!(p.rows.len() <= PLAYBACK_FRAMES && p.rows.len() > 100);
    assert_eq!(p.step, 2f64.powi(p.step.log2().round() as i32));
    for (k, row) in p.rows.iter().enumerate() {
        assert_eq!(row[0], k as f64 * p.step);
    }
    assert_eq!(p.parts.len(), 2);
    let (up, period) = (&p.parts[0], &p.parts[1]);
    assert!(up.name.contains("start-up") && period.name.contains("steady"));
    assert_eq!((up.frames.start, up.frames.end), (0, period.frames.start));
    let s = report.start_up.unwrap();
    let last_up = &p.rows[up.frames.end - 1];
    assert_eq!(p.rows[0][1], 0.0);
    assert!(s.time_to_speed - last_up[1] < p.step && last_up[1] <= s.time_to_speed);
    let steady_state = report.steady.unwrap();
    let last = p.rows.last().unwrap();
    assert!(steady_state.period - last[1] < p.step && last[1] <= steady_state.period);

    let (t, phi, omega) = (1, 2, 3);
    let sc = &report.steady_columns;
    let at = |name: &str| sc.iter().position(|c| c.name == name).unwrap();
    let (sphi, st, somega) = (at("phi"), at("t"), at("omega"));
    let mut worst: f64 = 0.0;
    for row in &p.rows[period.frames.clone()] {
        let k = steady
            .partition_point(|r| r[sphi] <= row[phi])
            .clamp(1, steady.len() - 1);
        let (a, b) = (&steady[k - 1], &steady[k]);
        let h = b[sphi] - a[sphi];
        let u = (row[phi] - a[sphi]) / h;
        let (u2, u3) = (u * u, u * u * u);
        let t_of_phi = (2.0 * u3 - 3.0 * u2 + 1.0) * a[st]
            + (u3 - 2.0 * u2 + u) * h / a[somega]
            + (3.0 * u2 - 2.0 * u3) * b[st]
            + (u3 - u2) * h / b[somega];
        worst = worst.max((t_of_phi - row[t]).abs());
        assert!(row[omega] > 0.0);
    }
    assert!(worst < 1e-7, "t(φ) of the frames off by {worst} s");

    let motor = 5;
    for row in [
        &p.rows[up.frames.end / 2],
        &p.rows[period.frames.start + 100],
    ] {
        assert_motor_torque_is_needed(&scene, (row[phi], row[omega], row[4]), row[motor], "");
    }
}

/// `mechdiff run <simulate scene> --report FILE` writes the page: its data hold the frames
/// of the playback (the clock first, in s; the drive in the scene's deg), played at 1 clock
/// second per second at ×1, and each diagram sits in an element naming the columns of its
/// moving marker (t or φ on x; ω and M_motor on y) and the frames it moves during.
#[test]
fn mechdiff_run_writes_a_report_of_the_simulated_motion() {
    use crate::common::{mechdiff, stderr, temp_file};
    let path = temp_file("rack_motor_report.toml");
    let text = text("rack_slotted_link_motor.toml").replacen(
        "find = [\"start_up\"]",
        "find = [\"start_up\", \"coast_down\"]",
        1,
    );
    std::fs::write(&path, &text).unwrap();
    let html = temp_file("rack_motor_report.html");
    let out = mechdiff(&[
        "run",
        path.to_str().unwrap(),
        "--report",
        html.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let page = std::fs::read_to_string(&html).unwrap();
    let open = r#"<script type="application/json" id="data">"#;
    let start = page.find(open).unwrap() + open.len();
    let end = start + page[start..].find("</script>").unwrap();
    let data: serde_json::Value = serde_json::from_str(&page[start..end]).unwrap();
    let columns: Vec<(&str, &str)> = (data["columns"].as_array().unwrap().iter())
        .map(|c| (c["name"].as_str().unwrap(), c["unit"].as_str().unwrap()))
        .collect();
    assert_eq!(columns[..3], [("clock", "s"), ("t", "s"), ("phi", "deg")]);
    assert_eq!(data["rate"], 1.0);
    let values = data["values"].as_array().unwrap();
    assert_eq!(values.len(), data["xy"].as_array().unwrap().len());
    let clock: Vec<f64> = values.iter().map(|v| v[0].as_f64().unwrap()).collect();
    let step = clock[1] - clock[0];
    assert!(
        (clock.windows(2)).all(|w| w[1] - w[0] == step),
        "a clock at equal steps"
    );
    // The start-up, then the coast-down to rest: one motion over time, the last frame
    // within a step of rest.
    assert!(page.contains("the start-up, then the coast-down"));
    assert!(values.last().unwrap()[3].as_f64().unwrap().abs() < 1.0);
    assert!(page.contains(&format!(
        r#"data-column="1" data-y-columns="3 5" data-frames="0 {}""#,
        values.len()
    )));
    for f in [path, html] {
        let _ = std::fs::remove_file(f);
    }
}

/// `mechdiff check` of a scene with `[simulate]` describes the simulation in the words the
/// run's plan prints: the gearbox and the rotor reduced to the drive (J_d/τ² = 0.012 × 15² =
/// 2.7 kg·m²), each analysis with its target and limit, the tolerances and the events. Its
/// J(φ) range over one turn is the prescribed-motion run's `J_red` (the kinetic energy's
/// reduced inertia, the rotor included: another code path) at the same 1° positions, to the
/// 7 significant digits printed (5e-7 relative). The rack machine's check prints its start-up
/// speed's default (0.95 × 40 rad/s / 30) when `speed` is left out, and `mechdiff run` prints
/// the check's lines of the simulation verbatim.
#[test]
fn mechdiff_check_describes_the_simulation_as_the_run_plans_it() {
    use crate::common::{mechdiff, stderr, stdout, temp_file};
    let out = mechdiff(&["check", "scenes/shaper_motor.toml"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let printed = stdout(&out);
    for line in [
        "  gearbox: τ = 0.06666667 (drive speed / motor speed), η = 1; the rotor's J_d enters \
         the drive as J_d/τ² = 2.7 kg*m^2",
        "    start-up: from rest at 0 deg until the drive turns at 95 rpm, within 20 s (time to \
         speed, peak motor torque)",
        "    flywheel: on the drive shaft, for δ = 0.02 against the time mean 2π/T; exactly (the \
         periodic solution iterated, each iteration at most 200 turns) and by the classic \
         energy method",
        "  integration: relative tolerance 1e-10 and absolute 1e-10 per step, at most 1000000 \
         steps a run; located as events (never stepped over): load switches at 67.97569 deg, \
         292.0243 deg, turn ends, the start-up's speed, rest",
    ] {
        assert!(printed.lines().any(|l| l == line), "{line}\n{printed}");
    }
    assert!(printed.contains("    steady state: the periodic turn through 0 deg, by shooting"));
    let range = (printed.lines())
        .find_map(|l| l.strip_prefix("  J(φ) over one turn from 0 deg: "))
        .unwrap();
    let numbers: Vec<f64> = (range.split(' ')).filter_map(|w| w.parse().ok()).collect();
    let mut s = scene::load("scenes/shaper_motor.toml").unwrap();
    s.motion = None;
    s.positions = Positions::List((0..360).map(|k| (k as f64).to_radians()).collect());
    let extra = "[[dynamics]]\noutput = \"reduced_inertia\"\n";
    let with_j = scene::parse("shaper_motor.toml", &(text("shaper_motor.toml") + extra)).unwrap();
    s.dynamics = with_j.dynamics;
    s.outputs.clear();
    let report = scene::run(&s).unwrap();
    let j = report
        .columns
        .iter()
        .position(|c| c.name == "J_red")
        .unwrap();
    let (lo, hi) = (report.rows.iter()).fold((f64::INFINITY, 0.0f64), |(lo, hi), r| {
        (lo.min(r[j]), hi.max(r[j]))
    });
    assert_eq!(numbers.len(), 2, "{range}");
    assert!(
        (numbers[0] / lo - 1.0).abs() < 5e-7,
        "{} vs {lo}",
        numbers[0]
    );
    assert!(
        (numbers[1] / hi - 1.0).abs() < 5e-7,
        "{} vs {hi}",
        numbers[1]
    );

    let path = temp_file("rack_motor_check.toml");
    let text = text("rack_slotted_link_motor.toml").replacen("speed = 1.2 ", "", 1);
    assert!(!text.contains("speed = 1.2 "));
    std::fs::write(&path, &text).unwrap();
    let checked = stdout(&mechdiff(&["check", path.to_str().unwrap()]));
    let line = "    start-up: from rest at 0 deg until the drive turns at 1.266667 rad/s (0.95 × the \
                motor's no-load speed through the gearbox), within 10 s (time to speed, peak \
                motor torque)";
    assert!(checked.lines().any(|l| l == line), "{checked}");
    let ran = stdout(&mechdiff(&["run", path.to_str().unwrap()]));
    let plan: Vec<&str> = (checked.lines())
        .skip_while(|l| !l.starts_with("the machine in motion"))
        .take_while(|l| l.starts_with("the machine in motion") || l.starts_with("  "))
        .collect();
    assert!(
        plan.len() > 6 && ran.contains(&plan.join("\n")),
        "{plan:?}\n{ran}"
    );
    let _ = std::fs::remove_file(path);
}

/// Item 5, bad input: a start-up asked for a speed the motor never gives (120 rpm, above
/// its no-load 100 rpm at the crank) and a coast-down of a machine that nothing brakes (no
/// load, no friction: it coasts for ever) end at their `time` limit as errors located at
/// `time`, with the speeds in the scene's rpm and the way out — never a hang. The start-up's
/// highest speed (the crank swings above the motor's no-load 100 rpm within a turn: 107 rpm)
/// lies below the 120 rpm asked; the coasting machine still turns at the end.
#[test]
fn speeds_not_reached_within_the_time_are_located_errors_in_the_scene_units() {
    let good = text("shaper_motor.toml");
    let find = "find = [\"start_up\", \"steady_state\", \"flywheel\"]";
    let fast = good
        .replacen(find, "find = [\"start_up\"]", 1)
        .replacen("speed = 95 ", "speed = 120 ", 1)
        .replacen("time = 20 ", "time = 0.5 ", 1)
        .replacen("delta = 0.02 ", "", 1);
    let scene = scene::parse("shaper_motor.toml", &fast).unwrap();
    let e = run(&scene, &mut MotionSinks::default())
        .unwrap_err()
        .to_string();
    let line = line_of(&fast, "time = 0.5");
    assert!(
        e.starts_with(&format!("shaper_motor.toml:{line}:"))
            && e.contains("start-up (120 rpm not reached; the highest was ")
            && e.contains("allow more `time`"),
        "{e}"
    );
    let highest: f64 = e.split("the highest was ").nth(1).unwrap()[..8]
        .trim()
        .parse()
        .unwrap();
    assert!(highest > 0.0 && highest < 120.0, "{e}");

    let coasting = good
        .replacen(find, "find = [\"coast_down\"]", 1)
        .replacen("force = [2000, 0]", "force = [0, 0]", 1)
        .replacen("time = 20 ", "time = 0.5 ", 1)
        .replacen("delta = 0.02 ", "", 1);
    let scene = scene::parse("shaper_motor.toml", &coasting).unwrap();
    let e = run(&scene, &mut MotionSinks::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with(&format!("shaper_motor.toml:{line}:"))
            && e.contains("coast-down (0 rpm not reached; at the end it was "),
        "{e}"
    );
}
