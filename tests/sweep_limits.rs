//! Scenes whose sweeps meet a limit position, a change point or an ill-conditioned pose:
//! `run` reports them (never a table that jumps them), `check` prints the drive's motion
//! range, and unrelated far points change nothing.

use crate::common;

use mechdiff::Error;
use mechdiff::scene;

/// Offset slider-crank r = 1 m, e = 0.5 m (guide above the crank pivot), l = 1.49 m,
/// sketched at φ = 0 (B = (1 + √(l² − e²), e), 17 digits); swept 0–360° at 20°. The crank
/// cannot pass sin φ < (e − l)/r = −0.99: ≈ 261.89°–278.11°.
const BLOCKED: &str = r#"
[units]
length = "m"
angle = "deg"
[points]
O = [0, 0]
A = [1, 0]
B = [2.4036025078347505, 0.5]
G0 = [0, 0.5]
G1 = [1, 0.5]
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
[sweep]
from = 0
to = 360
step = 20
[[output]]
name = "s"
slider = "guide"
quantities = ["position", "velocity_coefficient"]
"#;

fn degrees(text: &str) -> f64 {
    text.trim_end_matches(" deg").parse().unwrap()
}

#[test]
fn a_20_degree_sweep_reports_the_blocked_range_not_a_full_turn() {
    let s = scene::parse("blocked.toml", BLOCKED).unwrap();
    let e = scene::run(&s).unwrap_err();
    let Error::Blocked {
        from, to, limit, ..
    } = &e
    else {
        panic!("expected Blocked, got {e:?}")
    };
    assert_eq!((&**from, &**to), ("260 deg", "280 deg"));
    // 180° + asin 0.99, printed to 15 significant digits: 1e-11 deg.
    let exact = 180.0 + 0.99f64.asin().to_degrees();
    assert!((degrees(limit) - exact).abs() < 1e-11, "{limit} vs {exact}");
    assert!(
        e.to_string().starts_with(
            "blocked.toml: cannot assemble between drive positions 260 deg and 280 deg: the \
             loop of joints A, B, guide first fails at 261.89"
        ),
        "{e}"
    );
}

#[test]
fn check_reports_the_motion_range_between_the_limit_positions() {
    // The sweep stops at 240°, inside the motion range: `check` accepts it and prints the
    // range (the full 0–360° sweep is refused by `check` as by `run`: the next test).
    let within = BLOCKED.replace("to = 360", "to = 240");
    let s = scene::parse("blocked.toml", &within).unwrap();
    let range = scene::check(&s).unwrap().motion_range.unwrap();
    let (lower, upper) = (range.lower.clone().unwrap(), range.upper.clone().unwrap());
    // SI radians, to 1e-12: the limit positions r sin φ − e = −l.
    let limit = 0.99f64.asin();
    assert!((upper.phi - (std::f64::consts::PI + limit)).abs() < 1e-12);
    assert!((lower.phi + limit).abs() < 1e-12);
    let text = scene::run::describe_motion_range(&s, &range);
    assert!(
        text.starts_with("from -81.89") && text.contains("to 261.89"),
        "{text}"
    );
}

#[test]
fn check_refuses_a_sweep_past_the_limit_position_as_run_does() {
    let s = scene::parse("blocked.toml", BLOCKED).unwrap();
    let (Error::Blocked { limit: checked, .. }, Error::Blocked { limit, .. }) =
        (scene::check(&s).unwrap_err(), scene::run(&s).unwrap_err())
    else {
        panic!("check and run must both report the blocked range")
    };
    // The same limit position; 15 significant digits of 180° + asin 0.99 (1e-11 deg).
    let exact = 180.0 + 0.99f64.asin().to_degrees();
    assert!((degrees(&checked) - exact).abs() < 1e-11, "{checked}");
    assert!((degrees(&limit) - exact).abs() < 1e-11, "{limit}");
}

#[test]
fn an_unrelated_point_far_away_changes_no_verdict() {
    // A ground point 3e4 m or 1e9 m away: the same check and the same blocked range (it
    // used to make φ = 0 a "toggle", and at 1e9 the guide "not positive").
    for far in ["3e4", "1e9"] {
        let text = BLOCKED
            .replace("G1 = [1, 0.5]", &format!("G1 = [1, 0.5]\nFAR = [{far}, 0]"))
            .replace(
                r#"ground = ["O", "G0", "G1"]"#,
                r#"ground = ["O", "G0", "G1", "FAR"]"#,
            );
        let s = scene::parse("far.toml", &text).unwrap();
        // `check` refuses the sweep past the limit position with the error `run` gives.
        let checked = scene::check(&s).unwrap_err();
        let Error::Blocked { limit, .. } = scene::run(&s).unwrap_err() else {
            panic!("{far}")
        };
        let Error::Blocked { limit: checked, .. } = checked else {
            panic!("{far}: check gave {checked}")
        };
        assert_eq!(checked, limit, "{far}");
        let exact = 180.0 + 0.99f64.asin().to_degrees();
        assert!((degrees(&limit) - exact).abs() < 1e-11, "{far}: {limit}");
    }
}

#[test]
fn a_far_ground_point_puts_no_limit_behind_the_start_of_a_travel() {
    // The rack scene of reference 001 with the wheel's hinge 1e8 m or 1e9 m away (found by
    // the scene fuzzer): the displacement drive's search steps grow with the sketch, the
    // margin's Newton step went back past the start to the lower limit, and `check` refused
    // a sweep that `run` sweeps. The lower limit stays where the loop C, D, incline stops
    // closing; nothing is found above.
    let shipped = include_str!("../scenes/rack_slotted_link_travel.toml");
    for far in ["1e8", "1e9"] {
        let text = shipped.replace("W = [0.0, 0.04]", &format!("W = [{far}, 0.04]"));
        assert_ne!(text, shipped);
        let s = scene::parse("far.toml", &text).unwrap();
        let range = scene::check(&s)
            .unwrap_or_else(|e| panic!("{far}: {e}"))
            .motion_range
            .unwrap();
        let lower = range.lower.unwrap().phi;
        // 1e-12 relative: the distance of C from the incline equals |CD| = 0.723 m, solved
        // with mpmath at 40 digits (B, θ7, θ8 and the lengths of the scene's comments).
        assert!(
            (lower - 0.296_594_731_016_183_4).abs() < 1e-12,
            "{far}: {lower}"
        );
        assert!(range.upper.is_none(), "{far}: {:?}", range.upper);
        scene::run(&s).unwrap();
    }
}

#[test]
fn an_ill_conditioned_position_is_computed_with_a_warning() {
    // Slotted lever: crank l1 = 0.999999 m about O = (0, 1), pin A in the slot of a lever
    // hinged at B0 = (0, 0). At φ = 0 (crank pointing down) the pin passes 1e-6 m from B0
    // and ψ′ = −l1/(l0 − l1) ≈ −1e6: regular, computed, flagged.
    let text = common::slotted_lever(
        r#"
[sweep]
positions = [-90]
[[output]]
name = "psi"
angle = ["B0", "S"]
quantities = ["position", "velocity_coefficient"]
"#,
    );
    let s = scene::parse("lever.toml", &text).unwrap();
    let report = scene::run(&s).unwrap();
    let psi1 = report.column("psi'").unwrap()[0];
    // −l1/(l0 − l1) to 1e-8 relative (expected error ~ amplification·ε ≈ 4e-10).
    let exact = -0.999999 / (1.0 - 0.999999);
    assert!((psi1 / exact - 1.0).abs() < 1e-8, "{psi1} vs {exact}");
    assert_eq!(report.warnings.len(), 1, "{:?}", report.warnings);
    assert!(
        report.warnings[0].contains("ill-conditioned position at drive position -90 deg"),
        "{}",
        report.warnings[0]
    );
}

#[test]
fn a_rack_radius_of_1e308_is_an_error_not_a_hang() {
    // The pinion's centre at 1e308 m and its radius 1e308 m: the Jacobian overflows. The
    // SVD of the mobility check used to iterate forever on it; now its iterations are
    // bounded and a non-finite Jacobian is refused.
    let text = r#"
[points]
O = [0.0, 0.0]
X = [1.0, 0.0]
A = [0.5, 0.0]
W = [0.0, 1e308]
W1 = [1.0, 1e308]
[links]
ground = ["O", "X", "W"]
wheel = ["W", "W1"]
rack = ["A"]
[joints]
wheel_hinge = { type = "revolute", at = "W", links = ["ground", "wheel"] }
rack_guide = { type = "prismatic", line = ["O", "X"], point = "A", links = ["ground", "rack"] }
mesh = { type = "rack_pinion", pinion = "wheel_hinge", rack = "rack_guide", radius = 1e308 }
[drive]
joint = "rack_guide"
[sweep]
from = 0
to = 1
step = 0.5
[[output]]
name = "w"
angle = ["W", "W1"]
quantities = ["position"]
"#;
    // The scene reader refuses 1e308 m where it is written (beyond the 1e9 m length limit);
    // the solver's own refusal of a non-finite Jacobian is tested in core.
    let e = scene::parse("rack.toml", text).unwrap_err();
    assert!(e.to_string().contains("at most"), "{e}");
}

/// The blocked slider-crank swept from −81° to 261° at 1°: both limit positions
/// (−asin 0.99 ≈ −81.89° and 180° + asin 0.99 ≈ 261.89°) lie within a step beyond the ends.
fn reaching_both_limits() -> String {
    BLOCKED.replace(
        "from = 0\nto = 360\nstep = 20",
        "from = -81\nto = 261\nstep = 1",
    )
}

#[test]
fn a_sweep_that_ends_at_limit_positions_marks_and_lists_them() {
    let s = scene::parse("limits.toml", &reaching_both_limits()).unwrap();
    let report = scene::run(&s).unwrap();
    // Closed-form path: the limits are found to full precision; 1e-12 rad absolute.
    let limit = 0.99f64.asin();
    let phi: Vec<f64> = report.limits.iter().map(|l| l.limit.phi).collect();
    assert_eq!(phi.len(), 2, "{phi:?}");
    assert!((phi[0] + limit).abs() < 1e-12, "{phi:?}");
    assert!(
        (phi[1] - (std::f64::consts::PI + limit)).abs() < 1e-12,
        "{phi:?}"
    );
    // The diagram marks them in degrees (1e-10 deg: one conversion of exact radians).
    let diagram = mechdiff::pictures::run::diagram(&s, &report).unwrap();
    let marked: Vec<f64> = (diagram.markers.iter())
        .filter(|m| m.kind == mechdiff::pictures::MarkerKind::Limit)
        .map(|m| m.x)
        .collect();
    assert_eq!(marked.len(), 2, "{marked:?}");
    assert!((marked[0] + limit.to_degrees()).abs() < 1e-10, "{marked:?}");
    assert!(
        (marked[1] - 180.0 - limit.to_degrees()).abs() < 1e-10,
        "{marked:?}"
    );
    assert!(diagram.to_svg().unwrap().contains("limit position"));
    // `mechdiff run` lists them after the table.
    let mut out = Vec::new();
    scene::table::write_table(&s, &report, &mut out).unwrap();
    let out = String::from_utf8(out).unwrap();
    assert!(
        out.contains("the sweep reaches the end of the drive's motion range")
            && out.contains("  phi = -81.89")
            && out.contains("  phi = 261.89")
            && out.contains("limit position (loop of joints A, B, guide)"),
        "{out}"
    );
}

#[test]
fn a_sweep_more_than_a_step_from_the_limits_marks_none() {
    // 0° to 180° at 10°: the limits are 81.89° below and beyond, more than a step away.
    let text = BLOCKED.replace(
        "from = 0\nto = 360\nstep = 20",
        "from = 0\nto = 180\nstep = 10",
    );
    let s = scene::parse("inside.toml", &text).unwrap();
    let report = scene::run(&s).unwrap();
    assert!(report.limits.is_empty(), "{:?}", report.limits);
    let mut out = Vec::new();
    scene::table::write_table(&s, &report, &mut out).unwrap();
    assert!(!String::from_utf8(out).unwrap().contains("motion range"));
}

/// The parallelogram's change point lies between two positions of the sweep: reported at
/// φ = 0 (to 1e-9 rad: Newton on the margin's slope converges to rounding), never jumped
/// onto the antiparallelogram branch (which it was when the Hermite minimum of the step's
/// margin came out a rounding above zero).
#[test]
fn a_change_point_between_two_positions_is_reported() {
    for positions in ["[5, -5]", "[0.2178, -0.01]", "[3, -7]", "[10, 1, -0.5]"] {
        let text = format!(
            "{}[sweep]\npositions = {positions}\n",
            common::PARALLELOGRAM
        );
        let s = scene::parse("parallelogram.toml", &text).unwrap();
        match scene::run(&s) {
            Err(Error::ChangePoint { position, .. }) => {
                let phi = degrees(&position).to_radians();
                assert!(phi.abs() < 1e-9, "{positions}: {position}");
            }
            Err(e) => panic!("{positions}: expected a change point, got: {e}"),
            Ok(_) => panic!("{positions}: the change point at 0 was jumped"),
        }
    }
}

/// `check` holds a range sweep against the motion range by bisection, not by walking it: a
/// sweep of 3.6·10¹¹ positions (step 1e-9°) past the limit is refused at once, naming the
/// first position past the limit and the one before it (a walk of every position hung the
/// fuzz test).
#[test]
fn check_of_a_sweep_of_a_third_of_a_trillion_positions_is_prompt() {
    let text = BLOCKED.replace("step = 20", "step = 1e-9");
    let s = scene::parse("blocked.toml", &text).unwrap();
    let Error::Blocked {
        from, to, limit, ..
    } = scene::check(&s).unwrap_err()
    else {
        panic!("check must report the blocked range")
    };
    let exact = 180.0 + 0.99f64.asin().to_degrees();
    assert!((degrees(&limit) - exact).abs() < 1e-11, "{limit}");
    // Two neighbouring positions 1e-9° apart (printed to 1e-9°), the second past the limit
    // by the check's slack, 1e-9·(1 + φ) rad (≈ 3.19e-7° here), give or take a step and
    // the printing's 1e-9°.
    let (from, to) = (degrees(&from), degrees(&to));
    assert!((to - from - 1e-9).abs() < 1.5e-9, "{from} {to}");
    let slack = (1e-9 * (1.0 + exact.to_radians())).to_degrees();
    assert!(
        (to - exact - slack).abs() < 3e-9,
        "{to} vs {exact} + {slack}"
    );
}

/// A move the solver cannot certify within its bound on checked sub-steps is refused while
/// solving, in the scene's units — not passed by `check` and then refused by `run` as if the
/// scene were malformed (found by tests/fuzz_scenes.rs: the Whitworth ψ scene with its crank
/// pivot moved to x = 1e9 m, a 1e9 m crank against a 0.8 m rocker, whose closure cannot be
/// proven at rounding scale, so the checked steps shrink to nothing).
#[test]
fn a_move_the_solver_cannot_certify_is_refused_while_solving_in_the_scene_units() {
    use mechdiff::scene::{self, any};
    let path = format!(
        "{}/tests/data/whitworth_psi.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace("A0 = [0.0, 0.400]", "A0 = [1e9, 0.400]");
    let any::AnyScene::Linkage(s) = any::read(&path, &text, &[]).unwrap() else {
        panic!("a linkage scene");
    };
    scene::check(&s).unwrap();
    let e = scene::run(&s).unwrap_err();
    assert!(
        matches!(e, mechdiff::Error::MoveTooLong { .. }) && e.is_found_by_solving(),
        "{e}"
    );
    let message = e.to_string();
    assert!(
        message.contains(" deg to 0 deg") && message.contains("sizes"),
        "{message}"
    );
}
