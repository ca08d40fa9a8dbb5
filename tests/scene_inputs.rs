//! Issue 9, "Overflow" and "Scenes": every number is range-checked where it is written, a
//! quoted constant formula is a number, a joint listing three links stands for two joints,
//! and the mistakes TOML makes easy (dotted names, unquoted formulas, a non-UTF-8 file, an
//! endless list) get messages that say what is wrong, where, and how to fix it.

use std::path::Path;

use mechdiff::Error;
use mechdiff::scene::{self, Report};

use crate::common;
use common::assert_message;

/// The text of `scenes/<name>`.
fn scene_text(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(name);
    std::fs::read_to_string(path).unwrap()
}

/// `scenes/<name>` with `from` replaced by `to` (once), parsed as `bad.toml`; the error and
/// the 1-based line of `to` in the modified text.
fn refused(name: &str, from: &str, to: &str) -> (Error, usize) {
    let text = scene_text(name);
    assert!(text.contains(from), "test bug: `{from}` is not in {name}");
    let text = text.replacen(from, to, 1);
    let line = text[..text.find(to).unwrap()].matches('\n').count() + 1;
    match scene::parse("bad.toml", &text) {
        Ok(_) => panic!("`{to}` was accepted"),
        Err(e) => (e, line),
    }
}

fn assert_all_finite(report: &Report) {
    for row in &report.rows {
        assert!(row.iter().all(|v| v.is_finite()), "{row:?}");
    }
}

// --- Overflow -------------------------------------------------------------------------

/// The issue's first example: a drive speed ≥ ~1e155 squared overflows. It is refused where
/// it is written, with the limit in the file's unit (1e6 rad/s = 9549296.58551372 rpm).
#[test]
fn a_drive_speed_of_1e155_is_refused_where_it_is_written() {
    let (e, line) = refused("slider_crank.toml", "speed = 1500 ", "speed = 1e155 ");
    assert!(matches!(e, Error::OutOfRange { .. }), "{e:?}");
    assert_message(
        &e,
        line,
        &[
            "`[drive] speed` = 1e155 rpm",
            "at most 9549296.58551372 rpm",
        ],
    );
}

/// Variants: the speed written as a formula, as TOML's `inf` and `nan`, and a drive
/// acceleration far beyond any machine.
#[test]
fn non_finite_or_huge_drive_values_are_refused() {
    for (to, part) in [
        ("speed = \"1e100*1e100\" ", "out of range"),
        ("speed = inf ", "must be a finite number"),
        ("speed = nan ", "must be a finite number"),
        (
            "speed = 1500\nacceleration = 1e200 ",
            "`[drive] acceleration`",
        ),
    ] {
        let (e, line) = refused("slider_crank.toml", "speed = 1500 ", to);
        let line = line + usize::from(to.contains('\n'));
        assert_message(&e, line, &[part]);
    }
}

/// A mass of 1e308 kg (the issue's second example) is refused at the mass.
#[test]
fn a_mass_of_1e308_is_refused() {
    let (e, line) = refused(
        "whitworth_forces.toml",
        "crank = { mass = 15,",
        "crank = { mass = 1e308,",
    );
    assert!(matches!(e, Error::OutOfRange { .. }), "{e:?}");
    assert_message(&e, line, &["the mass of link `crank` = 1e308 kg"]);
}

/// A motor ratio of 5e-324 (the smallest subnormal: its reciprocal is infinite) is refused.
#[test]
fn a_motor_ratio_of_5e_324_is_refused() {
    let (e, line) = refused(
        "rack_slotted_link_dynamics.toml",
        "ratio = 0.03333333333333333",
        "ratio = 5e-324",
    );
    assert_message(
        &e,
        line,
        &["the motor's `ratio`", "≥ 0.000001 and ≤ 1000000"],
    );
}

/// A rack radius of 1e308 hung `check` and `run`; now it is refused while reading (this test
/// finishing is part of the fact).
#[test]
fn a_rack_radius_of_1e308_is_refused_before_solving() {
    let (e, line) = refused("rack_slotted_link.toml", "radius = 0.04", "radius = 1e308");
    assert_message(&e, line, &["`radius` of joint `mesh`", "at most"]);
}

/// Coordinates, gravity, loads and gear ratios have their ranges too.
#[test]
fn coordinates_gravity_and_loads_are_range_checked() {
    let (e, line) = refused("slider_crank.toml", "B = [384, -12]", "B = [384, 1e300]");
    assert_message(&e, line, &["the y coordinate of point `B` = 1e300 mm"]);
    let (e, line) = refused(
        "whitworth_forces.toml",
        "[masses]",
        "[gravity]\ng = 1e308\n\n[masses]",
    );
    assert_message(&e, line + 1, &["g (m/s²) = 1e308"]);
    let (e, line) = refused(
        "whitworth_forces.toml",
        "[masses]",
        "[[load]]\nlink = \"ram\"\npoint = \"C\"\nforce = [1e300, 0]\n\n[masses]",
    );
    assert_message(&e, line + 3, &["the force's x component = 1e300 N"]);
}

/// Within the limits, the largest drive speed gives finite numbers: the limits are chosen
/// so that ω²·ψ″ and the like stay inside f64.
#[test]
fn the_largest_accepted_speed_gives_finite_results() {
    let text = scene_text("slider_crank.toml").replacen("speed = 1500 ", "speed = 9549296 ", 1);
    let report = scene::run(&scene::parse("fast.toml", &text).unwrap()).unwrap();
    assert_all_finite(&report);
}

// --- Scenes -----------------------------------------------------------------------------

/// A four-bar O2–A–B–O4 with a slider dyad B–C hung at B: the hinge at B joins three links.
const SIX_BAR: &str = r#"
[points]
O2 = [0, 0]
A = [0, 1]
O4 = [4, 0]
B = [4, 3]
C = [8, 0]
G0 = [5, 0]
G1 = [10, 0]

[links]
ground = ["O2", "O4", "G0", "G1"]
crank = ["O2", "A"]
coupler = ["A", "B"]
rocker = ["O4", "B"]
rod = ["B", "C"]
slider = ["C"]

[joints]
O2 = { type = "revolute", at = "O2", links = ["ground", "crank"] }
A = { type = "revolute", at = "A", links = ["crank", "coupler"] }
HINGE
O4 = { type = "revolute", at = "O4", links = ["ground", "rocker"] }
C = { type = "revolute", at = "C", links = ["rod", "slider"] }
guide = { type = "prismatic", line = ["G0", "G1"], point = "C", links = ["ground", "slider"] }

[drive]
joint = "O2"
line = ["O2", "A"]
speed = 10

[sweep]
from = 0
to = 6
step = 0.25

[[output]]
name = "s"
slider = "guide"
quantities = ["position", "velocity_coefficient", "acceleration_coefficient"]

[[output]]
name = "rod"
angle = ["B", "C"]
quantities = ["position", "velocity_coefficient", "acceleration_coefficient"]
"#;

/// `links = [rocker, coupler, rod]` at B is expanded into rocker–coupler and rocker–rod, as
/// Pyslvs and PMKS write a ternary hinge; the results equal those of the two joints written
/// out. Same equations in the same order: equal to 4 ulp of each column's largest value
/// (the solver's arithmetic is the same; the bound only allows for a different summation
/// order).
#[test]
fn a_joint_given_three_links_equals_the_two_joints_written_out() {
    let three = SIX_BAR.replace(
        "HINGE",
        r#"B = { type = "revolute", at = "B", links = ["rocker", "coupler", "rod"] }"#,
    );
    let two = SIX_BAR.replace(
        "HINGE",
        "B = { type = \"revolute\", at = \"B\", links = [\"rocker\", \"coupler\"] }\n\
         B2 = { type = \"revolute\", at = \"B\", links = [\"rocker\", \"rod\"] }",
    );
    let (three, two) = (
        scene::parse("three.toml", &three).unwrap(),
        scene::parse("two.toml", &two).unwrap(),
    );
    let names: Vec<&str> = three.joints.iter().map(|j| j.name.as_str()).collect();
    assert_eq!(names, ["O2", "A", "B", "B:rod", "O4", "C", "guide"]);
    let (a, b) = (scene::run(&three).unwrap(), scene::run(&two).unwrap());
    assert_eq!(a.rows.len(), 25);
    for k in 0..a.columns.len() {
        let scale = b.rows.iter().map(|r| r[k].abs()).fold(0.0, f64::max);
        for (x, y) in a.rows.iter().zip(&b.rows) {
            assert!(
                (x[k] - y[k]).abs() <= 4.0 * f64::EPSILON * scale,
                "{}: {} vs {}",
                a.columns[k].name,
                x[k],
                y[k]
            );
        }
    }
}

/// Without the third link, the rod hangs free: proof that the expansion did not just drop it
/// (the scene is refused as under-constrained).
#[test]
fn the_third_link_is_not_dropped() {
    let dropped = SIX_BAR.replace(
        "HINGE",
        r#"B = { type = "revolute", at = "B", links = ["rocker", "coupler"] }"#,
    );
    let e = scene::check(&scene::parse("dropped.toml", &dropped).unwrap()).unwrap_err();
    assert!(e.to_string().contains("under-constrained"), "{e}");
}

/// Joints that join exactly two links say so when given three.
#[test]
fn a_slide_given_three_links_is_refused() {
    let (e, line) = refused(
        "slider_crank.toml",
        "point = \"B\", links = [\"ground\", \"slider\"]",
        "point = \"B\", links = [\"ground\", \"slider\", \"rod\"]",
    );
    assert_message(
        &e,
        line,
        &["lists 3 links", "a `prismatic` joint joins exactly two"],
    );
}

/// Every other pair (a line, a slot, two gears, a force) takes exactly two entries.
#[test]
fn a_line_of_three_points_is_refused() {
    let (e, line) = refused(
        "slider_crank.toml",
        "line = [\"O\", \"A\"]    #",
        "line = [\"O\", \"A\", \"B\"]    #",
    );
    assert_message(&e, line, &["expected exactly two names, found 3"]);
}

/// `CoM.AB = [..]` is a TOML table `CoM` with a key `AB`: the message says so and shows the
/// quoted name; the quoted name works.
#[test]
fn a_dotted_point_name_is_explained_and_the_quoted_name_works() {
    let (e, line) = refused(
        "slider_crank.toml",
        "G0 = [0, -12]",
        "CoM.AB = [1, 1]\nG0 = [0, -12]",
    );
    assert!(matches!(e, Error::Syntax { .. }), "{e:?}");
    assert_message(
        &e,
        line,
        &["dotted key", "table `CoM`", "`\"CoM.AB\" = [1, 1]`"],
    );
    let text = scene_text("slider_crank.toml").replacen(
        "G0 = [0, -12]",
        "\"CoM.AB\" = [1, 1]\nG0 = [0, -12]",
        1,
    );
    let scene = scene::parse("ok.toml", &text).unwrap();
    assert!(scene.points.iter().any(|p| p.name == "CoM.AB"));
}

/// `mass = 23.4791*0.86` is not TOML: the message says a formula must be quoted. Quoted, it
/// is read by the symbolic engine's infix parser: exactly the f64 product (one rounding, as
/// in Rust).
#[test]
fn an_unquoted_formula_is_explained_and_a_quoted_one_is_a_number() {
    let (e, line) = refused(
        "whitworth_forces.toml",
        "crank = { mass = 15,",
        "crank = { mass = 23.4791*0.86,",
    );
    assert_message(
        &e,
        line,
        &["`23.4791*0.86` is a formula", "write `\"23.4791*0.86\"`"],
    );
    let text = scene_text("whitworth_forces.toml").replacen(
        "crank = { mass = 15,",
        "crank = { mass = \"23.4791*0.86\",",
        1,
    );
    let scene = scene::parse("ok.toml", &text).unwrap();
    let dynamics = scene.dynamics.unwrap();
    let (_, crank) = dynamics.masses.iter().find(|(l, _)| l == "crank").unwrap();
    assert_eq!(crank.mass, 23.4791 * 0.86);
}

/// Quoted formulas work in points, lists and angles; a bad one is located at its string.
#[test]
fn quoted_formulas_are_numbers_everywhere_and_bad_ones_are_located() {
    let text = scene_text("slider_crank.toml")
        .replacen("A = [0, 100]", "A = [0, \"50*2\"]", 1)
        .replacen("step = 5", "step = \"10/2\"", 1);
    let a = scene::parse("ok.toml", &text).unwrap();
    let b = scene::parse("ok.toml", &scene_text("slider_crank.toml")).unwrap();
    // 50*2 and 10/2 are exact in f64: the scenes are identical.
    assert_eq!(a.positions, b.positions);
    assert_eq!(a.points[1].sketch, b.points[1].sketch);
    for (to, part) in [
        ("step = \"1/0\"", "division by zero"),
        (
            "step = \"5*x\"",
            "uses `x` (column 3 of the formula), which is neither a parameter nor a constant",
        ),
        ("step = \"5*(\"", "cannot be read"),
    ] {
        let (e, line) = refused("slider_crank.toml", "step = 5", to);
        assert_message(&e, line, &[part]);
    }
}

/// A file that is not UTF-8 gets the byte offset, line and column of the first bad byte.
#[test]
fn a_scene_that_is_not_utf8_gets_the_place_of_the_bad_byte() {
    let path = std::env::temp_dir().join(format!("mechdiff-latin1-{}.toml", std::process::id()));
    // "# Kurbelschwinge, Länge" in Latin-1: ä is the single byte 0xe4.
    let mut bytes = b"title = \"x\"\n# Kurbelschwinge, L".to_vec();
    bytes.extend_from_slice(&[0xe4, b'n', b'g', b'e', b'\n']);
    std::fs::write(&path, &bytes).unwrap();
    let e = scene::load(&path).unwrap_err();
    std::fs::remove_file(&path).unwrap();
    let Error::NotUtf8 {
        location,
        offset,
        byte,
    } = &e
    else {
        panic!("{e:?}")
    };
    assert_eq!(
        (location.line, location.column, *offset, *byte),
        (2, 20, 31, 0xe4)
    );
    assert!(e.to_string().contains("byte offset 31"), "{e}");
}

/// `/dev/zero` as a scene is read up to the size limit, then refused.
#[cfg(unix)]
#[test]
fn an_endless_file_is_refused_at_the_size_limit() {
    let e = scene::load("/dev/zero").unwrap_err();
    assert!(matches!(e, Error::TooLarge { .. }), "{e:?}");
    assert!(e.to_string().contains("16777216 bytes"), "{e}");
}

/// The documented limit of 10⁶ drive positions holds for a `positions` list too; the error
/// is at the list.
#[test]
fn a_positions_list_longer_than_the_limit_is_refused() {
    let list = vec!["0"; 1_000_001].join(",");
    let (e, line) = refused(
        "slider_crank.toml",
        "from = 0\nto = 360\nstep = 5",
        &format!("positions = [{list}]"),
    );
    assert_message(&e, line, &["more than 1000000 entries"]);
}

/// A bad entry of a `positions` list is located at the entry itself.
#[test]
fn a_bad_position_in_a_list_is_located_at_the_entry() {
    let text = scene_text("slider_crank.toml").replacen(
        "from = 0\nto = 360\nstep = 5",
        "positions = [0, 90,\n    180, 1e300]",
        1,
    );
    let e = scene::parse("bad.toml", &text).unwrap_err();
    let line = text[..text.find("1e300").unwrap()].matches('\n').count() + 1;
    // Column 10: `    180, ` is nine characters.
    assert!(
        e.to_string().starts_with(&format!(
            "bad.toml:{line}:10: `positions` entry 4 = 1e300 deg"
        )),
        "{e}"
    );
}

/// A list far beyond the limit (the issue's 2·10⁶ entries, 2.3 GB) is refused before TOML
/// parses it, so it costs no memory.
#[test]
fn a_list_of_two_million_entries_is_refused_before_parsing() {
    let list = vec!["0"; 2_000_000].join(",");
    let (e, line) = refused(
        "slider_crank.toml",
        "from = 0\nto = 360\nstep = 5",
        &format!("positions = [{list}]"),
    );
    assert_message(&e, line, &["more than 1100000 list entries"]);
}

/// Issue 22: a parameter with a unit of the wrong dimension was converted silently
/// (`{ value = 0.86, unit = "lb" }` used as a length became 0.390 m, `"kg"` 0.86 m). Used
/// alone or in a sum where a length is written, it is refused there, naming the unit, its
/// dimension and the dimension expected; a length unit is converted as before (10 in =
/// 0.254 m to 1e-15 m: the factor 0.0254 m/in, one multiplication).
#[test]
fn a_parameter_with_a_unit_of_another_dimension_is_refused_where_it_is_used() {
    let with = |parameter: &str, x: &str| {
        scene_text("four_bar.toml")
            .replacen(
                "[points]",
                &format!("[parameters]\n{parameter}\n\n[points]"),
                1,
            )
            .replacen("O4 = [0.4, 0.0]", &format!("O4 = [{x}, 0.0]"), 1)
    };
    for (parameter, x, unit, dimension) in [
        (
            "L = { value = 0.86, unit = \"lb\" }",
            "\"L\"",
            "lb",
            "a mass",
        ),
        (
            "L = { value = 0.86, unit = \"kg\" }",
            "\"L - 0.46\"",
            "kg",
            "a mass",
        ),
        (
            "L = { value = 3, unit = \"deg\" }",
            "\"(L)\"",
            "deg",
            "an angle",
        ),
    ] {
        let text = with(parameter, x);
        let e = scene::parse("bad.toml", &text).map(|_| ()).unwrap_err();
        let line = common::line_of(&text, "O4 = [");
        assert_message(
            &e,
            line,
            &[
                &format!("unit `{unit}` of parameter `L` is {dimension}"),
                "used here as a length (the x coordinate of point `O4`)",
            ],
        );
    }
    let scene = scene::parse(
        "ok.toml",
        &with("L = { value = 10, unit = \"in\" }", "\"L\""),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let o4 = scene.points.iter().find(|p| p.name == "O4").unwrap();
    assert!((o4.sketch[0] - 0.254).abs() <= 1e-15, "{}", o4.sketch[0]);
}

/// Issue 22: reading was about O(n²) in the number of names (8 000 points 3.4 s; 450 000
/// points timed out). A scene of 10⁵ points on one link and 10⁴ outputs is read: every
/// point and output is there (the timing is in BENCHMARKS.md, "Reading a scene of n names").
#[test]
fn a_scene_of_a_hundred_thousand_names_is_read() {
    let text = common::many_names::many_names(100_000, 10_000);
    let scene = scene::parse("big.toml", &text).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.points.len(), 100_004);
    assert_eq!(scene.outputs.len(), 10_001);
    assert_eq!(scene.links[2].points.len(), 100_002);
}

/// Issue 22 item 5: the dimension of a formula is inferred over its parse tree, so a
/// parameter with a unit of another dimension is refused in products, quotients and sums
/// of them too, at the number (line and column), naming the parameter, the dimension found
/// and the one expected.
mod dimensions {
    use super::*;

    /// `four_bar.toml` with `[parameters]` and `O4`'s x coordinate replaced.
    fn with(parameters: &str, x: &str) -> String {
        scene_text("four_bar.toml")
            .replacen(
                "[points]",
                &format!("[parameters]\n{parameters}\n\n[points]"),
                1,
            )
            .replacen("O4 = [0.4, 0.0]", &format!("O4 = [{x}, 0.0]"), 1)
    }

    /// The error for `text`, asserted at the column of `O4`'s x coordinate, with `parts`.
    fn refused_at_x(text: &str, parts: &[&str]) {
        let e = scene::parse("bad.toml", text).map(|_| ()).unwrap_err();
        let line = common::line_of(text, "O4 = [");
        // The x coordinate starts after `O4 = [` (column 7).
        assert!(
            e.to_string().starts_with(&format!("bad.toml:{line}:7:")),
            "{e}"
        );
        assert_message(&e, line, parts);
    }

    /// `O4`'s x coordinate (m) in the scene read from `text`.
    fn x_of_o4(text: &str) -> f64 {
        let scene = scene::parse("ok.toml", text).unwrap_or_else(|e| panic!("{e}"));
        scene.points.iter().find(|p| p.name == "O4").unwrap().sketch[0]
    }

    #[test]
    fn products_quotients_and_sums_of_a_mass_are_refused_as_a_length() {
        let parameters = "L = { value = 0.86, unit = \"lb\" }\nk = 2";
        for x in ["\"2*L\"", "\"L*k\"", "\"L/2 + 0.1\""] {
            refused_at_x(
                &with(parameters, x),
                &[
                    "unit `lb` of parameter `L` is a mass",
                    "used here as a length (the x coordinate of point `O4`)",
                ],
            );
        }
    }

    #[test]
    fn a_length_times_a_length_is_an_area_not_a_length() {
        refused_at_x(
            &with("L = { value = 20, unit = \"mm\" }", "\"L*L\""),
            &[
                "`L*L` is an area",
                "unit `mm` of parameter `L` is a length",
                "used here as a length (the x coordinate of point `O4`)",
            ],
        );
    }

    #[test]
    fn a_sum_of_a_length_and_a_mass_is_refused_at_the_parameter() {
        let text = with(
            "L = { value = 0.2, unit = \"m\" }\nM = { value = 1, unit = \"kg\" }\nS = \"L + M\"",
            "\"S\"",
        );
        let e = scene::parse("bad.toml", &text).map(|_| ()).unwrap_err();
        assert_message(
            &e,
            common::line_of(&text, "S = "),
            &["parameter `S`", "adds a length and a mass"],
        );
    }

    /// 2 × 10 in = 0.508 m: the factor 0.0254 m/in, a product by 2 (exact) and the
    /// conversion: 1e-15 relative covers two roundings.
    #[test]
    fn twice_a_length_in_inches_is_a_length_in_metres() {
        let x = x_of_o4(&with("L = { value = 10, unit = \"in\" }", "\"2*L\""));
        let expected = 2.0 * 0.0254 * 10.0;
        assert!((x - expected).abs() <= 1e-15 * expected, "{x}");
    }

    #[test]
    fn a_parameter_defined_by_a_formula_of_unit_parameters_keeps_their_dimension() {
        let parameters = "L = { value = 0.86, unit = \"lb\" }\nD = \"2*L + 1\"";
        refused_at_x(
            &with(parameters, "\"D\""),
            &[
                "parameter `D` = \"2*L + 1\" is a mass",
                "used here as a length (the x coordinate of point `O4`)",
            ],
        );
        // A length from inches: D = 2·L in m (two roundings, as above).
        let parameters = "L = { value = 10, unit = \"in\" }\nD = \"2*L\"";
        let x = x_of_o4(&with(parameters, "\"D\""));
        assert!((x - 0.508).abs() <= 1e-15 * 0.508, "{x}");
    }

    #[test]
    fn an_angle_times_two_is_an_angle_not_a_length() {
        let angle = "a = { value = 2.5, unit = \"deg\" }";
        // As the sweep's step (an angle, deg): accepted, and the same positions as 5 deg.
        let text = with(angle, "0.4").replacen("step = 5", "step = \"a*2\"", 1);
        let stepped = scene::parse("ok.toml", &text).unwrap_or_else(|e| panic!("{e}"));
        let plain = scene::parse("ok.toml", &with(angle, "0.4")).unwrap();
        assert_eq!(
            format!("{:?}", stepped.positions),
            format!("{:?}", plain.positions)
        );
        refused_at_x(
            &with(angle, "\"a*2\""),
            &[
                "unit `deg` of parameter `a` is an angle",
                "used here as a length (the x coordinate of point `O4`)",
            ],
        );
    }

    /// sin takes radians: with the file's angles in radians, `L*sin(a)` (a = 30 deg) is a
    /// length, 0.8·sin(π/6) m = 0.4 m to a few roundings (4 ulp); with the file's angles in
    /// degrees, the angle's number is in degrees and the formula is refused.
    #[test]
    fn the_sine_of_an_angle_times_a_length_is_a_length() {
        let parameters = "L = { value = 0.8, unit = \"m\" }\na = { value = 30, unit = \"deg\" }";
        let text = with(parameters, "\"L*sin(a)\"");
        let in_radians = text.replacen("angle = \"deg\"", "angle = \"rad\"", 1);
        let x = x_of_o4(&in_radians);
        assert!((x - 0.4).abs() <= 4.0 * f64::EPSILON * 0.4, "{x}");
        refused_at_x(&text, &["takes the sin of an angle", "radians"]);
    }

    /// A force times a length is a torque in the file's force unit times its length unit
    /// (N·m here): accepted where the file's torque unit is N·m, refused where it is N·mm
    /// (the number would be read 1000 times too small), with the factor that converts it.
    #[test]
    fn a_force_times_a_length_is_a_torque_only_in_the_files_torque_unit() {
        let text = scene_text("rack_slotted_link_dynamics.toml")
            .replacen(
                "[points]",
                "[parameters]\nF = { value = 10, unit = \"lbf\" }\nr = { value = 2, unit = \
                 \"in\" }\n\n[points]",
                1,
            )
            .replacen(
                "[[load]]",
                "[[load]]\nlink = \"slider\"\ntorque = \"F*r\"\n\n[[load]]",
                1,
            );
        scene::parse("ok.toml", &text).unwrap_or_else(|e| panic!("{e}"));
        let text = text.replacen("length = \"m\"", "length = \"m\"\ntorque = \"N*mm\"", 1);
        let e = scene::parse("bad.toml", &text).map(|_| ()).unwrap_err();
        assert_message(
            &e,
            common::line_of(&text, "torque = \"F*r\""),
            &[
                "`F*r` is a torque",
                "`N*mm`",
                "multiply the formula by 1000",
            ],
        );
    }

    /// The unit table has no area unit, so the area is a parameter defined as `L*L`: its
    /// square root is a length again, 20 mm = 0.02 m (the factor 1e-3, a square and a
    /// square root: a few roundings, 4 ulp); the square root of a length is refused.
    #[test]
    fn the_square_root_of_an_area_is_a_length() {
        let parameters = "L = { value = 20, unit = \"mm\" }\nA = \"L*L\"";
        let x = x_of_o4(&with(parameters, "\"sqrt(A)\""));
        assert!((x - 0.02).abs() <= 4.0 * f64::EPSILON * 0.02, "{x}");
        refused_at_x(
            &with(parameters, "\"sqrt(L)\""),
            &[
                "takes the square root of a length",
                "unit `mm` of parameter `L`",
            ],
        );
    }
}

// --- [solver] ------------------------------------------------------------------------

/// `scenes/whitworth.toml` with a `[solver]` table of `body` appended, parsed as `bad.toml`:
/// the error and the 1-based line of `body`'s first line.
fn refused_solver(body: &str) -> (Error, usize) {
    let text = format!("{}\n[solver]\n{body}\n", scene_text("whitworth.toml"));
    let line = text[..text.find(body).unwrap()].matches('\n').count() + 1;
    match scene::parse("bad.toml", &text) {
        Ok(_) => panic!("`{body}` was accepted"),
        Err(e) => (e, line),
    }
}

/// Every `[solver]` setting is bounded before anything is solved: a value outside its range
/// (NaN included) is refused at its line, with the range, why, and the default.
#[test]
fn solver_settings_outside_their_ranges_are_refused_where_they_are_written() {
    let cases: [(&str, &[&str]); 9] = [
        (
            "tolerance = 1e-20",
            &[
                "`[solver] tolerance` = 1e-20",
                "[1e-15, 1e-6]",
                "rounding",
                "(1e-13)",
            ],
        ),
        (
            "tolerance = 0.001",
            &["`[solver] tolerance` = 1e-3", "[1e-15, 1e-6]"],
        ),
        (
            "tolerance = nan",
            &["`[solver] tolerance` = NaN", "[1e-15, 1e-6]"],
        ),
        (
            "max_iterations = 0",
            &["`[solver] max_iterations` = 0", "[1, 1000]", "(50)"],
        ),
        (
            "max_iterations = 5000",
            &["`[solver] max_iterations` = 5000", "[1, 1000]"],
        ),
        (
            "max_subdivisions = -1",
            &["`[solver] max_subdivisions` = -1", "[0, 64]", "(24)"],
        ),
        (
            "max_subdivisions = 65",
            &["`[solver] max_subdivisions` = 65", "[0, 64]"],
        ),
        (
            "singular_condition = 1",
            &[
                "`[solver] singular_condition` = 1e0",
                "[10, 1e15]",
                "0.1/√tolerance",
            ],
        ),
        (
            "singular_condition = 1e20",
            &["`[solver] singular_condition` = 1e20", "[10, 1e15]"],
        ),
    ];
    for (body, parts) in cases {
        let (e, line) = refused_solver(body);
        assert!(matches!(e, Error::Invalid { .. }), "{body}: {e:?}");
        assert_message(&e, line, parts);
    }
}

/// A `[solver]` value of the wrong type, or a misspelt key, is refused at its line and column
/// with what was written and what was expected (the keys, for a misspelt one).
#[test]
fn mistyped_solver_settings_are_refused_where_they_are_written() {
    let cases: [(&str, &[&str]); 4] = [
        (
            "tolerance = \"tight\"",
            &["\"tight\"", "expected a number, such as 1e-13"],
        ),
        (
            "max_iterations = 2.5",
            &["2.5", "expected a whole number, such as 50"],
        ),
        ("closed_form = \"no\"", &["\"no\"", "expected a boolean"]),
        (
            "tolerence = 1e-12",
            &[
                "`tolerence`",
                "`tolerance`",
                "`max_iterations`",
                "`closed_form`",
            ],
        ),
    ];
    for (body, parts) in cases {
        let (e, line) = refused_solver(body);
        assert_message(&e, line, parts);
    }
}
