//! Every kind of bad input gives a typed error that names where it is (`file:line:column`)
//! and what was expected — never a panic.

use mechdiff::Error;
use mechdiff::scene;

use crate::common;
use common::assert_message;

/// A valid four-bar; each test breaks one thing in it.
const FOUR_BAR: &str = r#"[units]
length = "m"
angle = "deg"

[points]
O2 = [0.0, 0.0]
O4 = [0.4, 0.0]
A = [0.0, 0.1]
B = [0.4, 0.3]

[links]
ground = ["O2", "O4"]
crank = ["O2", "A"]
coupler = ["A", "B"]
rocker = ["O4", "B"]

[joints]
O2 = { type = "revolute", at = "O2", links = ["ground", "crank"] }
A = { type = "revolute", at = "A", links = ["crank", "coupler"] }
B = { type = "revolute", at = "B", links = ["coupler", "rocker"] }
O4 = { type = "revolute", at = "O4", links = ["ground", "rocker"] }

[drive]
joint = "O2"
line = ["O2", "A"]
speed = 10

[sweep]
from = 0
to = 360
step = 10

[[output]]
name = "psi"
angle = ["O4", "B"]
"#;

/// Replaces `from` (which must occur in the base scene) and parses the result as `bad.toml`.
fn parse_with(from: &str, to: &str) -> Error {
    assert!(
        FOUR_BAR.contains(from),
        "test bug: `{from}` is not in the base scene"
    );
    match scene::parse("bad.toml", &FOUR_BAR.replacen(from, to, 1)) {
        Ok(_) => panic!("`{to}` was accepted"),
        Err(e) => e,
    }
}

#[test]
fn the_base_scene_is_valid() {
    let scene = scene::parse("bad.toml", FOUR_BAR).unwrap();
    scene::run(&scene).unwrap();
}

#[test]
fn an_unknown_joint_type_lists_the_types() {
    let e = parse_with(r#"A = { type = "revolute""#, r#"A = { type = "hinge""#);
    assert!(matches!(e, Error::Syntax { .. }), "{e:?}");
    assert_message(
        &e,
        19,
        &[
            "`hinge`",
            "`revolute`",
            "`prismatic`",
            "`pin_in_slot`",
            "`rack_pinion`",
            "`gear`",
            "`weld`",
        ],
    );
}

#[test]
fn a_missing_point_names_the_link_and_lists_the_points() {
    let e = parse_with(r#"coupler = ["A", "B"]"#, r#"coupler = ["A", "C"]"#);
    assert!(
        matches!(&e, Error::UnknownPoint { name, .. } if name == "C"),
        "{e:?}"
    );
    assert_message(
        &e,
        14,
        &["unknown point `C`", "link `coupler`", "A, B, O2, O4"],
    );
}

#[test]
fn a_missing_point_in_a_joint_is_located_too() {
    let e = parse_with(r#"at = "B""#, r#"at = "Bx""#);
    assert!(matches!(e, Error::UnknownPoint { .. }), "{e:?}");
    assert_message(&e, 20, &["unknown point `Bx`", "joint `B`"]);
}

#[test]
fn a_point_defined_twice_is_a_duplicate() {
    let e = parse_with("B = [0.4, 0.3]\n", "B = [0.4, 0.3]\nA = [0.0, 0.2]\n");
    assert!(
        matches!(&e, Error::DuplicatePoint { name, .. } if name == "A"),
        "{e:?}"
    );
    assert_message(&e, 10, &["point `A`", "`[points]`"]);
}

#[test]
fn a_point_listed_twice_in_a_link_is_a_duplicate() {
    let e = parse_with(r#"rocker = ["O4", "B"]"#, r#"rocker = ["O4", "B", "O4"]"#);
    assert!(matches!(e, Error::DuplicatePoint { .. }), "{e:?}");
    assert_message(&e, 15, &["point `O4`", "link `rocker`"]);
}

#[test]
fn a_non_positive_length_is_rejected() {
    let e = parse_with(
        "B = [0.4, 0.3]",
        r#"B = { from = "O4", length = -0.3, angle = 90 }"#,
    );
    assert!(
        matches!(e, Error::NonPositiveLength { value, .. } if value == -0.3),
        "{e:?}"
    );
    assert_message(
        &e,
        9,
        &["`length` of point `B`", "must be positive", "-0.3"],
    );
}

#[test]
fn a_line_through_two_coincident_points_has_zero_length() {
    let e = parse_with(r#"angle = ["O4", "B"]"#, r#"angle = ["O4", "O4"]"#);
    assert!(matches!(e, Error::NonPositiveLength { .. }), "{e:?}");
    assert_message(&e, 35, &["must be positive"]);
}

#[test]
fn a_zero_sweep_step_is_rejected() {
    let e = parse_with("step = 10", "step = 0");
    assert!(matches!(e, Error::Invalid { .. }), "{e:?}");
    assert_message(&e, 31, &["`[sweep] step` is zero", "negative to walk"]);
}

#[test]
fn an_unknown_unit_lists_the_units() {
    let e = parse_with(r#"length = "m""#, r#"length = "inch""#);
    assert!(matches!(e, Error::Syntax { .. }), "{e:?}");
    assert_message(&e, 2, &["`inch`", "`m`", "`mm`"]);
    let e = parse_with(r#"angle = "deg""#, r#"angle = "grad""#);
    assert_message(&e, 3, &["`grad`", "`rad`", "`deg`"]);
}

#[test]
fn a_misspelt_key_lists_the_keys_expected_there() {
    let e = parse_with("speed = 10", "sped = 10");
    assert!(matches!(e, Error::Syntax { .. }), "{e:?}");
    assert_message(&e, 26, &["`sped`", "`speed`", "`acceleration`", "`line`"]);
    let e = parse_with(
        r#"links = ["ground", "crank"]"#,
        r#"link = ["ground", "crank"]"#,
    );
    assert_message(&e, 18, &["`link`", "`links`", "`at`"]);
    let e = parse_with("[sweep]", "[swep]");
    assert_message(&e, 28, &["`swep`", "`sweep`"]);
}

#[test]
fn a_field_that_does_not_apply_to_a_joint_type_says_which_fields_do() {
    let e = parse_with(r#"at = "A", links"#, r#"at = "A", radius = 0.1, links"#);
    assert_message(
        &e,
        19,
        &[
            "`radius` does not apply",
            "`revolute` joint takes `type`, `links`, `at`",
        ],
    );
}

#[test]
fn a_toml_syntax_error_is_located() {
    let e = parse_with("step = 10", "step = ");
    assert!(matches!(e, Error::Syntax { .. }), "{e:?}");
    assert_message(&e, 31, &["expected"]);
}

#[test]
fn velocities_without_a_drive_speed_are_refused() {
    let e = parse_with("speed = 10\n", "");
    assert!(matches!(e, Error::Invalid { .. }), "{e:?}");
    assert_message(&e, 32, &["output `psi`", "velocity", "`speed`"]);
}

/// A non-Grashof four-bar (0.2 + 0.4 > 0.25 + 0.32) whose crank cannot turn past ~104°.
#[test]
fn geometry_that_cannot_assemble_names_the_position_and_the_loop() {
    let text = FOUR_BAR
        .replace("A = [0.0, 0.1]", "A = [0.0, 0.25]")
        .replace("B = [0.4, 0.3]", "B = [0.2, 0.25]")
        .replace("from = 0\nto = 360", "from = 90\nto = 180");
    let scene = scene::parse("bad.toml", &text).unwrap();
    let e = scene::run(&scene).unwrap_err();
    let Error::Blocked {
        from,
        to,
        limit,
        loop_joints,
        ..
    } = &e
    else {
        panic!("{e:?}")
    };
    assert_eq!((&**from, &**to), ("100 deg", "110 deg"));
    // The limit position: |A − O4| = |AB| + |BO4| = 0.2 + √(0.2² + 0.25²) with
    // |A − O4|² = 0.25² + 0.4² − 2·0.25·0.4 cos φ; printed to 15 digits, compared to
    // 1e-9 deg.
    let limit: f64 = limit.trim_end_matches(" deg").parse().unwrap();
    let reach = 0.2 + 0.2f64.hypot(0.25);
    let exact = ((0.0625 + 0.16 - reach * reach) / 0.2).acos().to_degrees();
    assert!((limit - exact).abs() < 1e-9, "{limit} vs {exact}");
    assert!(
        loop_joints.contains('A') && loop_joints.contains("O4"),
        "{e}"
    );
    assert!(
        e.to_string()
            .starts_with("bad.toml: cannot assemble between drive positions 100 deg and 110 deg"),
        "{e}"
    );
}

/// A centred slider-crank (r = 0.3 m, l = 0.5 m) driven by its slider: at s = l + r = 0.8 m
/// crank and rod are in line and the slider cannot turn the crank (toggle).
#[test]
fn a_toggle_of_the_driven_link_is_reported_singular_with_its_position() {
    let text = r#"
[points]
O = [0.0, 0.0]
A = [0.0, 0.3]
B = [0.4, 0.0]
X = [1.0, 0.0]
[links]
ground = ["O", "X"]
crank = ["O", "A"]
rod = ["A", "B"]
slider = ["B"]
[joints]
O = { type = "revolute", at = "O", links = ["ground", "crank"] }
A = { type = "revolute", at = "A", links = ["crank", "rod"] }
B = { type = "revolute", at = "B", links = ["rod", "slider"] }
guide = { type = "prismatic", line = ["O", "X"], point = "B", links = ["ground", "slider"] }
[drive]
joint = "guide"
[sweep]
positions = [0.4, 0.6, 0.8]
[[output]]
name = "crank"
angle = ["O", "A"]
quantities = ["position", "velocity_coefficient"]
"#;
    let scene = scene::parse("toggle.toml", text).unwrap();
    let e = scene::run(&scene).unwrap_err();
    let Error::Singular { position, .. } = &e else {
        panic!("{e:?}")
    };
    assert_eq!(position, "0.8 m");
    assert!(
        e.to_string()
            .starts_with("toggle.toml: singular position (toggle) at drive position 0.8 m"),
        "{e}"
    );
}

#[test]
fn a_pin_drawn_off_its_slot_is_located() {
    let text = FOUR_BAR.replace(
        r#"B = { type = "revolute", at = "B", links = ["coupler", "rocker"] }"#,
        r#"B = { type = "pin_in_slot", pin = "A", slot = ["O4", "B"], links = ["rocker", "coupler"] }"#,
    );
    let e = scene::parse("bad.toml", &text).unwrap_err();
    assert_message(&e, 20, &["point `A`", "off the line `O4`–`B`"]);
}

#[test]
fn dead_positions_need_a_scalar_output_and_a_range() {
    let with_point = FOUR_BAR.replace(
        r#"name = "psi"
angle = ["O4", "B"]"#,
        "point = \"B\"\ndead_positions = true",
    );
    let e = scene::parse("bad.toml", &with_point).unwrap_err();
    assert_message(
        &e,
        33,
        &["`dead_positions` applies to an angle or slider output"],
    );
    let one_position = FOUR_BAR
        .replace("from = 0\nto = 360\nstep = 10", "positions = [10]")
        .replace(
            r#"angle = ["O4", "B"]"#,
            "angle = [\"O4\", \"B\"]\ndead_positions = true",
        );
    let e = scene::parse("bad.toml", &one_position).unwrap_err();
    assert_message(&e, 31, &["output `psi`", "`dead_positions` needs a range"]);
}

/// Without the joint at B the coupler and the rocker swing freely: `check` names the
/// mobility problem (from the geometry model) with the file.
#[test]
fn an_under_constrained_mechanism_is_reported_by_check() {
    let text = FOUR_BAR.replace(
        "B = { type = \"revolute\", at = \"B\", links = [\"coupler\", \"rocker\"] }\n",
        "",
    );
    let scene = scene::parse("bad.toml", &text).unwrap();
    let e = scene::check(&scene).unwrap_err();
    assert!(matches!(e, Error::Model { .. }), "{e:?}");
    let message = e.to_string();
    assert!(
        message.starts_with("bad.toml: under-constrained"),
        "{message}"
    );
    assert!(
        message.contains("rocker") && message.contains("coupler"),
        "{message}"
    );
}

#[test]
fn a_missing_section_is_named_with_the_sections_a_scene_needs() {
    let e = parse_with("[sweep]\nfrom = 0\nto = 360\nstep = 10\n", "");
    assert!(matches!(e, Error::Syntax { .. }), "{e:?}");
    assert_message(
        &e,
        1,
        &[
            "missing field `sweep`",
            "`[points]`, `[links]`, `[joints]`, `[drive]`",
        ],
    );
}

/// `[sweep] of = "psi"` asks for drive positions where the rocker is at a given angle; 150°
/// is beyond the rocker's swing (78.1° to 122.6°), so no drive position gives it.
#[test]
fn an_output_value_out_of_reach_is_reported_with_the_output() {
    let text = FOUR_BAR.replace(
        "from = 0\nto = 360\nstep = 10",
        "of = \"psi\"\npositions = [100, 150]",
    );
    let scene = scene::parse("bad.toml", &text).unwrap();
    let e = scene::run(&scene).unwrap_err();
    let Error::NotReached { output, value, .. } = &e else {
        panic!("{e:?}")
    };
    assert_eq!((output.as_str(), value.as_str()), ("psi", "150 deg"));
    assert!(
        e.to_string()
            .starts_with("bad.toml: no drive position found where `psi` = 150 deg"),
        "{e}"
    );
    // 100° is within the swing: the same scene without 150° runs, and psi is 100° there.
    let text = FOUR_BAR.replace(
        "from = 0\nto = 360\nstep = 10",
        "of = \"psi\"\npositions = [100]",
    );
    let report = scene::run(&scene::parse("ok.toml", &text).unwrap()).unwrap();
    let psi = report.column("psi").unwrap()[0];
    assert!((psi - 100f64.to_radians()).abs() <= 1e-15, "{psi}");
}

/// In mechanism 001 the slotted link cannot reach θ3 = 250°: before it gets there, the rod
/// and slider toggle. Newton's search for the drive position steps beyond that toggle; the
/// step is halved back, and the error says where the search stopped and why, instead of
/// reporting a drive position the scene never asked for.
#[test]
fn sweep_of_past_a_toggle_says_where_and_why_the_search_stopped() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/rack_slotted_link.toml");
    let text = std::fs::read_to_string(path)
        .unwrap()
        .replace("positions = [63]", "positions = [63, 250]");
    let scene = scene::parse("far.toml", &text).unwrap();
    let e = scene::run(&scene).unwrap_err();
    let Error::NotReached {
        output,
        value,
        beyond,
        ..
    } = &e
    else {
        panic!("{e:?}")
    };
    assert_eq!((output.as_str(), value.as_str()), ("theta3", "250 deg"));
    assert!(
        beyond.contains("the loop of joints C, D, incline") && !beyond.contains("far.toml"),
        "{e}"
    );
}

#[test]
fn sweep_of_must_name_an_angle_or_slider_output() {
    let e = parse_with(
        "from = 0\nto = 360\nstep = 10",
        "of = \"phi3\"\npositions = [100]",
    );
    assert_message(&e, 29, &["no output is named `phi3`", "psi"]);
}

#[test]
fn a_key_missing_for_the_joint_type_says_which_keys_it_takes() {
    let e = parse_with(
        r#"O4 = { type = "revolute", at = "O4", links"#,
        r#"O4 = { type = "revolute", links"#,
    );
    assert!(matches!(e, Error::Invalid { .. }), "{e:?}");
    assert_message(
        &e,
        21,
        &[
            "joint `O4`: `at` is missing",
            "`revolute` joint takes `type`, `links`, `at`",
        ],
    );
}

/// A formula is read as written and evaluated by the resolver: its error is placed by the
/// formula's own span — at the unknown name inside the quotes when the message names its
/// column, else at the opening quote — in any section, with the scene's parameters known.
#[test]
fn a_formula_error_points_at_the_formula_line_and_column() {
    let with_parameters = FOUR_BAR.replacen("[points]", "[parameters]\nl = 0.1\n\n[points]", 1);
    let cases = [
        // (written in place of `B = [0.4, 0.3]`, what is located, its message)
        (
            "B = [0.4, \"3*l + q\"]",
            "q\"]",
            "uses `q` (column 7 of the formula)",
        ),
        (
            "B = [\"4*l\", \"0.3/(l - l)\"]",
            "\"0.3/(l - l)\"",
            "division by zero",
        ),
        ("B = [\"4*l\", \"sqrt(l\"]", "\"sqrt(l\"", "cannot be read"),
    ];
    for (to, at, part) in cases {
        let text = with_parameters.replacen("B = [0.4, 0.3]", to, 1);
        let e = scene::parse("bad.toml", &text).unwrap_err();
        assert!(matches!(e, Error::Syntax { .. }), "{e:?}");
        // The place, counted here from the text: the line holding `at` and its column
        // (1-based, ASCII).
        let offset = text.find(at).unwrap();
        let line = text[..offset].matches('\n').count() + 1;
        let column = offset - text[..offset].rfind('\n').map_or(0, |i| i + 1) + 1;
        let message = e.to_string();
        assert!(
            message.starts_with(&format!("bad.toml:{line}:{column}: ")),
            "expected bad.toml:{line}:{column}: {message}"
        );
        assert!(message.contains(part), "`{part}` missing from: {message}");
    }
    // The same formula in the dynamics sections (read by their own resolver step).
    let text = with_parameters.replacen(
        "[drive]",
        "[masses]\ncrank = { mass = \"2*m\", center = \"A\" }\n\n[drive]",
        1,
    );
    let e = scene::parse("bad.toml", &text).unwrap_err();
    let offset = text.find("m\", center").unwrap();
    let line = text[..offset].matches('\n').count() + 1;
    let column = offset - text[..offset].rfind('\n').map_or(0, |i| i + 1) + 1;
    assert!(
        e.to_string()
            .starts_with(&format!("bad.toml:{line}:{column}: ")),
        "expected bad.toml:{line}:{column}: {e}"
    );
}
