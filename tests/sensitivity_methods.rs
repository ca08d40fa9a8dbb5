//! Issue 14: which route each derivative column of `[sensitivity]` takes, and that the
//! output says so — exact (dual numbers) where the exact route reaches, Richardson-
//! extrapolated differences, labelled with the reason, where it does not.

use crate::common;

use mechdiff::sensitivity::{self, Method, Options, Study};

fn study_of(file: &str, text: &str) -> Study {
    let (_, _, study) = sensitivity::run(file, text, &[], &Options::default()).unwrap();
    study.expect("a study")
}

fn summary(study: &Study) -> String {
    let mut out = Vec::new();
    sensitivity::write_summary(study, &mut out).unwrap();
    String::from_utf8(out).unwrap()
}

/// The reason a column fell back, or `None` when it is exact.
fn why(study: &Study, name: &str) -> Option<String> {
    let column = study.derivatives.iter().find(|d| d.name == name).unwrap();
    match &column.method {
        Method::Exact => None,
        Method::Richardson { why, .. } => Some(why.clone()),
    }
}

#[test]
fn a_cam_driven_scene_falls_back_to_richardson_and_says_why() {
    let path = common::scene_path("cam_driven_rocker.toml");
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace("A = [60, 80]", "A = [\"ax\", 80]")
        .replace("[points]", "[parameters]\nax = 60\n\n[points]")
        .replace("step = 15", "step = 90")
        + "\n[sensitivity]\ncolumns = [\"d(x_A)/d(ax)\"]\n";
    let text = text.replace(
        "[[output]]",
        "[[output]]\npoint = \"A\"\nquantities = [\"position\"]\n\n[[output]]",
    );
    let study = study_of(path.to_str().unwrap(), &text);
    let reason = why(&study, "d(x_A)/d(ax)").expect("a Richardson column");
    assert!(reason.contains("a cam drives the scene"), "{reason}");
    let printed = summary(&study);
    assert!(
        printed.contains("d(x_A)/d(ax): Richardson-extrapolated central differences")
            && printed.contains("not exact because a cam drives the scene"),
        "{printed}"
    );
}

/// A slider-crank with a slider mass: the drive torque's derivative by the mass.
const SLIDER_CRANK: &str = r#"
[parameters]
r = 0.1
l = 0.4
m3 = 2.0
[points]
O = [0, 0]
A = { from = "O", length = "r", angle = "pi/2" }
G0 = [0, 0]
G1 = [1, 0]
B = { circle = "A", radius = "l", line = ["G0", "G1"], along = "forward" }
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
speed = 50
[sweep]
from = 0
to = 6
step = 1
[[output]]
name = "s"
slider = "guide"
quantities = ["position"]
[masses]
slider = { mass = "m3", center = "B" }
[[dynamics]]
output = "drive_torque"
[sensitivity]
columns = ["d(s)/d(r)", "d(M_drive)/d(m3)", "d(M_drive)/d(r)"]
"#;

#[test]
fn a_mass_a_length_a_force_and_a_centre_are_exact_and_an_uncarried_number_falls_back_labelled() {
    // A load's `active` range is a discrete choice the exact route does not differentiate:
    // `on` moves a number the scene's tangent does not carry.
    let text = SLIDER_CRANK
        .replace("m3 = 2.0", "m3 = 2.0\nF = -100\ncx = 0.2\non = 3.5")
        .replace(
            "slider = { mass = \"m3\", center = \"B\" }",
            "slider = { mass = \"m3\", center = \"B\" }\nrod = { mass = 1, center = [\"cx\", 0] }",
        )
        .replace(
            "[[dynamics]]",
            "[[load]]\nlink = \"slider\"\npoint = \"B\"\nforce = [\"F\", 0]\nactive = [0, \"on\"]\n\
             [[dynamics]]",
        )
        .replace(
            "\"d(M_drive)/d(r)\"]",
            "\"d(M_drive)/d(r)\", \"d(M_drive)/d(F)\", \"d(M_drive)/d(cx)\", \"d(M_drive)/d(on)\"]",
        );
    let study = study_of("t.toml", &text);
    // The slider's position by r is kinematic: exact; the drive torque by the slider's mass,
    // by the crank's length (which moves A and B, the slider's centre and the force's point),
    // by the force and by the rod's centre: exact.
    for exact in [
        "d(s)/d(r)",
        "d(M_drive)/d(m3)",
        "d(M_drive)/d(r)",
        "d(M_drive)/d(F)",
        "d(M_drive)/d(cx)",
    ] {
        assert_eq!(why(&study, exact), None, "{exact}");
    }
    let reason = why(&study, "d(M_drive)/d(on)").expect("a Richardson column");
    assert!(
        reason.contains("`on` moves `load[0].active[1]` (t.toml:")
            && reason.contains("does not carry"),
        "{reason}"
    );
    let printed = summary(&study);
    assert!(
        printed.contains("d(M_drive)/d(m3): exact (dual numbers")
            && printed.contains("d(M_drive)/d(on): Richardson-extrapolated")
            && printed.contains("not exact because `on` moves `load[0].active[1]`"),
        "{printed}"
    );
}

#[test]
fn friction_in_the_plan_leaves_the_drive_torque_by_a_mass_to_richardson_labelled() {
    let text = SLIDER_CRANK.replace(
        "[[dynamics]]",
        "[friction]\nguide = { coefficient = 0.1 }\n[[dynamics]]",
    );
    let study = study_of("t.toml", &text);
    assert_eq!(why(&study, "d(s)/d(r)"), None);
    let reason = why(&study, "d(M_drive)/d(m3)").expect("a Richardson column");
    assert!(reason.contains("friction (joint `guide`)"), "{reason}");
}

#[test]
fn the_drive_torques_derivative_by_a_mass_is_exact_and_matches_its_closed_form() {
    // A slider alone, no gravity, α = 0: M_drive·ω = m3·ṡ·s̈ = m3·ω³·s′·s″, so
    // M_drive = m3·ω²·s′·s″ and ∂M_drive/∂m3 = ω²·s′·s″, from the run's own s′, s″ (exact).
    let text = SLIDER_CRANK.replace(
        "quantities = [\"position\"]",
        "quantities = [\"position\", \"velocity_coefficient\", \"acceleration_coefficient\"]",
    );
    let (_, report, study) = sensitivity::run("t.toml", &text, &[], &Options::default()).unwrap();
    let study = study.unwrap();
    assert_eq!(why(&study, "d(M_drive)/d(m3)"), None);
    let got = report.column("d(M_drive)/d(m3)").unwrap();
    let (s1, s2) = (report.column("s'").unwrap(), report.column("s''").unwrap());
    let want: Vec<f64> = (s1.iter().zip(&s2))
        .map(|(a, b)| 50.0 * 50.0 * a * b)
        .collect();
    let scale = want.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
    assert!(scale > 1.0, "not a vacuous comparison: {scale}");
    for (row, (g, w)) in got.iter().zip(&want).enumerate() {
        // 1e-12 of the column: both exact in f64 (the equilibrium solved in Dual64, the
        // closed form from the run's exact s′, s″).
        assert!((g - w).abs() <= 1e-12 * scale, "row {row}: {g} vs {w}");
    }
}

#[test]
fn the_drive_torques_derivative_by_the_speed_is_exact_and_matches_its_closed_form() {
    // ω = w: a slider alone, no gravity, α = 0: M_drive·ω = m3·ṡ·s̈ = m3·ω³·s′·s″, so
    // M_drive = m3·ω²·s′·s″ and ∂M_drive/∂w = 2·m3·w·s′·s″, from the run's own s′, s″ (exact).
    let text = SLIDER_CRANK
        .replace("m3 = 2.0", "m3 = 2.0\nw = 50")
        .replace("speed = 50", "speed = \"w\"")
        .replace(
            "quantities = [\"position\"]",
            "quantities = [\"position\", \"velocity_coefficient\", \"acceleration_coefficient\"]",
        )
        .replace("\"d(M_drive)/d(r)\"]", "\"d(M_drive)/d(w)\"]");
    let (_, report, study) = sensitivity::run("t.toml", &text, &[], &Options::default()).unwrap();
    let study = study.unwrap();
    assert_eq!(why(&study, "d(M_drive)/d(w)"), None);
    let got = report.column("d(M_drive)/d(w)").unwrap();
    let (s1, s2) = (report.column("s'").unwrap(), report.column("s''").unwrap());
    let want: Vec<f64> = s1
        .iter()
        .zip(&s2)
        .map(|(a, b)| 2.0 * 2.0 * 50.0 * a * b)
        .collect();
    let scale = want.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
    for (row, (g, w)) in got.iter().zip(&want).enumerate() {
        // 1e-12 of the column: both exact in f64 (the drive torque's equilibrium solved in
        // Dual64, the closed form from the run's exact s′, s″).
        assert!((g - w).abs() <= 1e-12 * scale, "row {row}: {g} vs {w}");
    }
}
