//! Issue 14 item 6, conventions: sweeps in either direction, negative drive speeds, static
//! analysis (speed 0), the signs of the drive torque, joint reactions and slider normal
//! forces as docs/scene-format.md ("Conventions") states them, and dynamics columns
//! printed in the file's force and torque units.

mod common;

use mechdiff::scene::{self, Report};

/// Norton's four-bar from its lengths (the scene shipped in `scenes/`), with masses from a
/// density, gravity, and the drive torque and reactions asked for.
fn norton(sweep: &str, speed: &str) -> String {
    include_str!("../scenes/norton_four_bar.toml")
        .replace(
            "speed = 10 ",
            &format!("speed = {speed}\nacceleration = 5 "),
        )
        .replace("from = 0\nto = 100\nstep = 10", sweep)
        .replace(
            "\"velocity\"]",
            "\"velocity\", \"acceleration_coefficient\", \"acceleration\"]\ndead_positions = true",
        )
        + r#"
[gravity]
g = 9.81

[masses]
crank = { density = 2 }
coupler = { density = 2 }
rocker = { density = 2 }

[[dynamics]]
output = "drive_torque"

[[dynamics]]
output = "reactions"
"#
}

fn run(text: &str) -> Report {
    common::run_text("conventions.toml", text)
}

/// `a` and `b` agree to `tol` relative to each value's magnitude (absolute below 1).
fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * b.abs().max(1.0)
}

#[test]
fn a_sweep_downwards_gives_the_rows_of_the_sweep_upwards_in_reverse() {
    let up = run(&norton("from = 0\nto = 100\nstep = 10", "10"));
    for down in [
        "from = 100\nto = 0\nstep = 10",
        "from = 100\nto = 0\nstep = -10",
    ] {
        let down = run(&norton(down, "10"));
        assert_eq!(down.rows.len(), 11);
        for (d, u) in down.rows.iter().zip(up.rows.iter().rev()) {
            for (k, (x, y)) in d.iter().zip(u).enumerate() {
                // 1e-12: each loop is solved in closed form from the same drive position
                // (exact multiples of 10° either way); only the previous pose used to pick
                // the turn differs (measured: equal to the last bit or nearly).
                assert!(close(*x, *y, 1e-12), "{}: {x} vs {y}", down.columns[k].name);
            }
        }
        // The same dead position (ψ' = 0 near φ = 15°) is found either way, 1e-12 rad.
        let (d, u) = (&down.dead_positions[0], &up.dead_positions[0]);
        assert_eq!(d.positions.len(), u.positions.len());
        assert!(
            !u.positions.is_empty(),
            "the rocker turns back within 0°…100°"
        );
        for (a, b) in d.positions.iter().zip(&u.positions) {
            assert!((a.phi - b.phi).abs() < 1e-12, "{} vs {}", a.phi, b.phi);
        }
    }
    let e = scene::parse("c.toml", &norton("from = 0\nto = 100\nstep = -10", "10")).unwrap_err();
    assert!(
        e.to_string().contains("negative but `to` is above `from`"),
        "{e}"
    );
}

#[test]
fn a_negative_speed_reverses_velocities_and_keeps_accelerations_and_the_drive_torque() {
    let forward = run(&norton("from = 0\nto = 100\nstep = 10", "10"));
    let backward = run(&norton("from = 0\nto = 100\nstep = 10", "-10"));
    // With ω → −ω: velocities ω·q′ change sign; accelerations α·q′ + ω²·q″ and so every
    // inertial force, reaction and the drive torque (no friction) are unchanged. Both runs
    // solve the same poses: equal to rounding, 1e-12 relative.
    for (k, column) in forward.columns.iter().enumerate() {
        let sign = if column.name == "psi_dot" { -1.0 } else { 1.0 };
        for (f, b) in forward.rows.iter().zip(&backward.rows) {
            assert!(
                close(b[k], sign * f[k], 1e-12),
                "{}: {} vs {}",
                column.name,
                b[k],
                f[k]
            );
        }
    }
    assert!(
        forward
            .column("psi_dot")
            .unwrap()
            .iter()
            .any(|v| v.abs() > 1.0)
    );
}

/// A crank alone, its mass on its tip: `M_drive = m·g·a·cos φ` (the torque that holds the
/// crank against its weight, counter-clockwise positive); the ground holds it up at O.
#[test]
fn a_static_crank_needs_the_torque_of_its_weight_counter_clockwise_positive() {
    let text = r#"
[units]
angle = "deg"
[points]
O = [0, 0]
A = [0.5, 0]
[links]
ground = ["O"]
crank = ["O", "A"]
[joints]
O = { type = "revolute", at = "O", links = ["ground", "crank"] }
[drive]
joint = "O"
line = ["O", "A"]
speed = 0
[sweep]
from = 0
to = 330
step = 30
[gravity]
g = 9.81
[masses]
crank = { mass = 2, center = "A" }
[[dynamics]]
output = "drive_torque"
[[dynamics]]
output = "reactions"
"#;
    let report = run(text);
    let (phi, torque) = (
        report.column("phi").unwrap(),
        report.column("M_drive").unwrap(),
    );
    let (fx, fy) = (
        report.column("Fx_O").unwrap(),
        report.column("Fy_O").unwrap(),
    );
    for k in 0..phi.len() {
        // m·g·a = 9.81 N·m; 1e-12 relative to it: a 2×2 equilibrium solved in f64.
        let want = 2.0 * 9.81 * 0.5 * phi[k].cos();
        assert!(
            (torque[k] - want).abs() < 9.81e-12,
            "phi {}: {}",
            phi[k],
            torque[k]
        );
        // The ground (first link) on the crank (second): up, m·g = 19.62 N.
        assert!(
            fx[k].abs() < 1e-12 && (fy[k] - 19.62).abs() < 19.62e-12,
            "{} {}",
            fx[k],
            fy[k]
        );
    }
}

/// A slider-crank at rest with weight on the slider only: the guide carries it. Its normal
/// force is along the guide's normal `n` (the guide line's direction turned +90°): +m·g
/// for a guide drawn O → B (u = +x, n = +y), −m·g for one drawn B → O.
#[test]
fn a_slider_normal_force_is_along_the_guide_direction_turned_counter_clockwise() {
    let text = |line: &str| {
        format!(
            r#"
[units]
angle = "deg"
[points]
O = [0, 0]
A = [0, 0.1]
B = [0.3, 0]
[links]
ground = ["O", "B"]
crank = ["O", "A"]
rod = ["A", "B"]
slider = ["B"]
[joints]
O = {{ type = "revolute", at = "O", links = ["ground", "crank"] }}
A = {{ type = "revolute", at = "A", links = ["crank", "rod"] }}
B = {{ type = "revolute", at = "B", links = ["rod", "slider"] }}
G = {{ type = "prismatic", links = ["ground", "slider"], line = {line}, point = "B" }}
[drive]
joint = "O"
line = ["O", "A"]
speed = 0
[sweep]
from = 0
to = 330
step = 30
[gravity]
g = 9.81
[masses]
slider = {{ mass = 3, center = "B" }}
[[dynamics]]
output = "drive_torque"
[[dynamics]]
output = "reactions"
"#
        )
    };
    let mg = 3.0 * 9.81;
    for (line, sign) in [(r#"["O", "B"]"#, 1.0), (r#"["B", "O"]"#, -1.0)] {
        let report = run(&text(line));
        // The rod is never vertical (crank 0.1 < rod 0.316 m), so it carries no force: the
        // drive torque is 0 and the guide takes the weight (1e-12 of m·g: a small linear
        // system in f64).
        for (n, m) in report
            .column("N_G")
            .unwrap()
            .iter()
            .zip(report.column("M_drive").unwrap())
        {
            assert!((n - sign * mg).abs() < 1e-12 * mg, "{line}: N_G = {n}");
            assert!(m.abs() < 1e-12 * mg, "{line}: M_drive = {m}");
        }
    }
}

#[test]
fn dynamics_columns_are_printed_in_the_files_force_and_torque_units() {
    let lbf = 0.45359237 * 9.80665;
    let metric = norton("from = 0\nto = 100\nstep = 10", "10");
    let inch = metric.replace(
        "angle = \"deg\"",
        "angle = \"deg\"\nforce = \"lbf\"\ntorque = \"lbf*in\"",
    );
    let (m, i) = (run(&metric), run(&inch));
    let unit = |r: &Report, name: &str| {
        let c = r.columns.iter().find(|c| c.name == name).unwrap();
        (c.unit.clone(), c.factor)
    };
    assert_eq!(unit(&m, "M_drive"), ("N m".to_owned(), 1.0));
    assert_eq!(unit(&i, "M_drive"), ("lbf*in".to_owned(), lbf * 0.0254));
    assert_eq!(unit(&i, "Fx_O2"), ("lbf".to_owned(), lbf));
    // The values stay SI (the factor only changes the printing): the same numbers, since
    // `force` and `torque` units apply to loads only and this scene has none.
    assert_eq!(m.column("M_drive"), i.column("M_drive"));
    let mut csv = Vec::new();
    scene::table::write_csv(&i, &mut csv).unwrap();
    let csv = String::from_utf8(csv).unwrap();
    assert!(
        csv.lines().next().unwrap().contains("M_drive [lbf*in]"),
        "{csv}"
    );
}
