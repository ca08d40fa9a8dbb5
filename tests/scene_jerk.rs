//! Jerk as an output of a geometry scene: the Whitworth of reference 000 with `jerk_coefficient`
//! and `jerk` asked for, against the third derivatives of its closed form, derived by hand here
//! (independently of the engine's dual numbers and implicit differentiation).

use std::f64::consts::PI;
use std::path::Path;

use mechdiff::pictures::run::diagram;
use mechdiff::scene::{self, Scene};

use crate::common;
use common::{column, scaled_error};

/// The Whitworth scene with jerks asked for, and a drive acceleration of 3 rad/s² so that the
/// chain rule's 3ωα x″ term counts.
fn whitworth_with_jerk() -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/whitworth.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let all = "[\"position\", \"velocity_coefficient\", \"acceleration_coefficient\", \
               \"velocity\", \"acceleration\"]";
    assert_eq!(text.matches(all).count(), 2, "the scene's outputs changed");
    let text = text
        .replace(
            all,
            "[\"position\", \"velocity_coefficient\", \"acceleration_coefficient\", \
             \"jerk_coefficient\", \"velocity\", \"acceleration\", \"jerk\"]",
        )
        .replace("acceleration = 0\n", "acceleration = 3\n");
    scene::parse("whitworth_jerk.toml", &text).unwrap_or_else(|e| panic!("{e}"))
}

/// tan ψ = λ sin φ / (1 − λ cos φ), n = 1 − 2λ cos φ + λ²: ψ′ = λ(cos φ − λ)/n (source 1.35),
/// ψ″ = −λ(1 − λ²) sin φ / n² (1.36), and by hand ψ‴ = −λ(1 − λ²)(n cos φ − 4λ sin² φ)/n³
/// (the derivative of 1.36 with n′ = 2λ sin φ). The ram x_C = h tan ψ:
/// x‴ = h sec²ψ (ψ‴ + 6 tan ψ ψ′ψ″ + (4 tan²ψ + 2 sec²ψ) ψ′³).
/// Time derivatives at ω = 100 rpm, α = 3 rad/s², φ⃛ = 0: x⃛ = 3ωα x″ + ω³ x‴.
/// Tolerance 1e-12 of each quantity's largest magnitude over the turn, the bar of the first
/// and second derivatives in `tests/scenes.rs` (the third derivative of the solved pose is as
/// exact: closed forms in dual numbers; the hand formula in f64 is good to some ulp of its
/// largest term; measured: ≤ 2e-15).
#[test]
fn whitworth_jerk_matches_the_hand_derived_third_derivative() {
    let scene = whitworth_with_jerk();
    let report = scene::run(&scene).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(report.plan.order, 3);
    let (lambda, h) = (0.150 / 0.400, 0.650);
    let (omega, alpha) = (100.0 * PI / 30.0, 3.0);
    let phi = column(&report, "phi");
    assert_eq!(phi.len(), 721);
    let mut want: [Vec<f64>; 4] = Default::default();
    for &p in &phi {
        let (s, c) = p.sin_cos();
        let n = 1.0 - 2.0 * lambda * c + lambda * lambda;
        let psi = (lambda * s).atan2(1.0 - lambda * c);
        let d1 = lambda * (c - lambda) / n;
        let d2 = -lambda * (1.0 - lambda * lambda) * s / (n * n);
        let d3 = -lambda * (1.0 - lambda * lambda) * (n * c - 4.0 * lambda * s * s) / n.powi(3);
        let (t, sec2) = (psi.tan(), 1.0 / psi.cos().powi(2));
        let x2 = h * sec2 * (d2 + 2.0 * t * d1 * d1);
        let x3 = h * sec2 * (d3 + 6.0 * t * d1 * d2 + (4.0 * t * t + 2.0 * sec2) * d1.powi(3));
        let jerk = |d2: f64, d3: f64| 3.0 * omega * alpha * d2 + omega.powi(3) * d3;
        for (v, x) in want.iter_mut().zip([d3, jerk(d2, d3), x3, jerk(x2, x3)]) {
            v.push(x);
        }
    }
    for (name, want) in ["psi'''", "psi_dddot", "x_C'''", "x_C_dddot"]
        .iter()
        .zip(&want)
    {
        let error = scaled_error(&column(&report, name), want);
        assert!(error <= 1e-12, "{name}: scaled error {error:e}");
    }
}

/// The jerk columns carry their units (coefficients in radians and the length unit, time
/// derivatives per s³), and the diagram gets a panel for each.
#[test]
fn jerk_columns_have_units_and_diagram_panels() {
    let scene = whitworth_with_jerk();
    let report = scene::run(&scene).unwrap_or_else(|e| panic!("{e}"));
    let unit = |name: &str| {
        let c = report.columns.iter().find(|c| c.name == name).unwrap();
        (c.unit.as_str(), c.factor)
    };
    assert_eq!(unit("psi'''"), ("1/rad^2", 1.0));
    assert_eq!(unit("psi_dddot"), ("rad/s^3", 1.0));
    assert_eq!(unit("x_C'''"), ("m/rad^3", 1.0));
    assert_eq!(unit("x_C_dddot"), ("m/s^3", 1.0));
    let mut csv = Vec::new();
    scene::table::write_csv(&report, &mut csv).unwrap();
    let header = String::from_utf8(csv).unwrap();
    let header = header.lines().next().unwrap();
    assert!(header.contains("psi_dddot [rad/s^3]"), "{header}");
    assert!(header.contains("x_C''' [m/rad^3]"), "{header}");
    // Without `[plot] panels`, every quantity is a panel.
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/whitworth.toml"),
    )
    .unwrap()
    .replace(
        "panels = [\"psi_ddot\", \"x_C_ddot\"]",
        "panels = [\"psi_dddot\", \"x_C_dddot\"]",
    )
    .replace(
        "quantities = [\"position\", \"velocity_coefficient\", \"acceleration_coefficient\", \
         \"velocity\", \"acceleration\"]",
        "quantities = [\"position\", \"jerk\"]",
    );
    let scene = scene::parse("whitworth_jerk_panels.toml", &text).unwrap_or_else(|e| panic!("{e}"));
    let report = scene::run(&scene).unwrap_or_else(|e| panic!("{e}"));
    let d = diagram(&scene, &report).unwrap();
    let labels: Vec<&str> = d.panels.iter().map(|p| p.y_label.as_str()).collect();
    // Picture labels are written in symbols (issue 24 item 4): a third time derivative is
    // the letter with three dots above (U+20DB), `psi` is ψ; the columns keep their names.
    assert_eq!(
        labels,
        ["\u{3c8}\u{20db} [rad/s^3]", "x\u{20db}_C [m/s^3]"],
        "the jerk panels"
    );
    assert!(
        report.column("psi_dddot").is_some(),
        "the column keeps its name"
    );
}

/// Asking for a jerk without a drive speed is refused, naming the jerk.
#[test]
fn jerk_without_a_speed_is_refused() {
    let text = r#"
[points]
O = [0, 0]
A = [1, 0]
[links]
ground = ["O"]
crank = ["O", "A"]
[joints]
O = { type = "revolute", at = "O", links = ["ground", "crank"] }
[drive]
joint = "O"
line = ["O", "A"]
[sweep]
from = 0
to = 1
step = 0.5
[[output]]
name = "theta"
angle = ["O", "A"]
quantities = ["position", "jerk"]
"#;
    let e = scene::parse("no_speed.toml", text).unwrap_err().to_string();
    assert!(
        e.contains("asks for the jerk") && e.contains("no `speed`"),
        "{e}"
    );
}
