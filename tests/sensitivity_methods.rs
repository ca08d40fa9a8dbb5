//! Issue 14: which route each derivative column of `[sensitivity]` takes, and that the
//! output says so — exact (dual numbers) where the exact route reaches, Richardson-
//! extrapolated differences, labelled with the reason, where it does not.

mod common;

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
fn kinematic_columns_are_exact_and_dynamics_columns_labelled_richardson() {
    let study = study_of("t.toml", SLIDER_CRANK);
    // The slider's position by r is kinematic: exact.
    assert_eq!(why(&study, "d(s)/d(r)"), None);
    for name in ["d(M_drive)/d(m3)", "d(M_drive)/d(r)"] {
        let reason = why(&study, name).expect("a Richardson column");
        assert!(reason.contains("dynamics"), "{name}: {reason}");
    }
    let printed = summary(&study);
    assert!(
        printed.contains("d(s)/d(r): exact (dual numbers")
            && printed.contains("d(M_drive)/d(m3): Richardson-extrapolated")
            && printed.contains("not exact because the dynamics columns' exact route"),
        "{printed}"
    );
}
