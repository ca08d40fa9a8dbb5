//! The joint types that the reference scenes do not use (gear, weld), each in a small scene
//! whose motion is known exactly.

use mechdiff::scene;

/// Two gears on fixed pivots, `ratio = -0.5` (external mesh, the driven gear twice the size):
/// θ2 = −φ/2 exactly, so θ2′ = −0.5, θ2″ = 0 and θ̇2 = −0.5 ω. 1e-13: the pose is solved to
/// rounding and the angles are of order 1.
#[test]
fn a_gear_pair_turns_at_its_ratio() {
    let text = r#"
[units]
angle = "deg"
[points]
O1 = [0.0, 0.0]
P1 = [0.1, 0.0]
O2 = [0.3, 0.0]
P2 = [0.5, 0.0]
[links]
ground = ["O1", "O2"]
pinion = ["O1", "P1"]
wheel = ["O2", "P2"]
[joints]
g1 = { type = "revolute", at = "O1", links = ["ground", "pinion"] }
g2 = { type = "revolute", at = "O2", links = ["ground", "wheel"] }
mesh = { type = "gear", gears = ["g1", "g2"], ratio = -0.5 }
[drive]
joint = "g1"
line = ["O1", "P1"]
speed = 2.0
[sweep]
from = 0
to = 300
step = 30
[[output]]
name = "theta2"
angle = ["O2", "P2"]
quantities = ["position", "velocity_coefficient", "acceleration_coefficient", "velocity"]
"#;
    let report = scene::run(&scene::parse("gears.toml", text).unwrap()).unwrap();
    let phi = report.column("phi").unwrap();
    let theta2 = report.column("theta2").unwrap();
    for (p, t) in phi.iter().zip(&theta2) {
        assert!((t + 0.5 * p).abs() <= 1e-13, "{p}: {t}");
    }
    assert!(
        report
            .column("theta2'")
            .unwrap()
            .iter()
            .all(|d| (d + 0.5).abs() <= 1e-13)
    );
    assert!(
        report
            .column("theta2''")
            .unwrap()
            .iter()
            .all(|d| d.abs() <= 1e-13)
    );
    assert!(
        report
            .column("theta2_dot")
            .unwrap()
            .iter()
            .all(|v| (v + 1.0).abs() <= 1e-13)
    );
}

/// A crank made of two welded pieces: the far piece's point B turns with the crank,
/// B = R(φ) (0.1, 0.05). 1e-15 m: rounding of a rotation of a 0.11 m vector.
#[test]
fn welded_links_move_as_one_body() {
    let text = r#"
[points]
O = [0.0, 0.0]
A = [0.1, 0.0]
B = [0.1, 0.05]
[links]
ground = ["O"]
arm = ["O", "A"]
finger = ["A", "B"]
[joints]
O = { type = "revolute", at = "O", links = ["ground", "arm"] }
w = { type = "weld", links = ["arm", "finger"] }
[drive]
joint = "O"
line = ["O", "A"]
[sweep]
positions = [0.0, 0.5, 1.0, 2.0, 3.0, -1.0]
[[output]]
point = "B"
quantities = ["position", "velocity_coefficient"]
"#;
    let report = scene::run(&scene::parse("weld.toml", text).unwrap()).unwrap();
    let phi = report.column("phi").unwrap();
    let (x, y) = (report.column("x_B").unwrap(), report.column("y_B").unwrap());
    let dx = report.column("x_B'").unwrap();
    for k in 0..phi.len() {
        let (s, c) = phi[k].sin_cos();
        assert!((x[k] - (0.1 * c - 0.05 * s)).abs() <= 1e-15, "{}", phi[k]);
        assert!((y[k] - (0.1 * s + 0.05 * c)).abs() <= 1e-15, "{}", phi[k]);
        assert!((dx[k] - (-0.1 * s - 0.05 * c)).abs() <= 1e-15, "{}", phi[k]);
    }
}
