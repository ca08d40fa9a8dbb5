//! The tangent of a scene (`mechdiff::scene::tangent`): the exact d/dp of every number of
//! its mechanism, against derivatives of the constructions written by hand here —
//! implicit differentiation of the equations that define each constructed point
//! (|B − A| = b, |B − O4| = c; a point on a line at a distance), independent of the
//! construction code. Tolerances: both sides are a few f64 operations on numbers of order
//! 1, so they agree to a few ulps (1e-14 absolute on derivatives of order 1).

use mechdiff::scene::tangent::{SceneTangent, scene_tangent};

const NORTON: &str = include_str!("../scenes/norton_four_bar.toml");

/// A few ulps of numbers of order 1: both sides are short f64 computations.
const TOLERANCE: f64 = 1e-14;

fn tangent(text: &str, p: &str) -> SceneTangent {
    scene_tangent("t.toml", text, &[], p).unwrap()
}

fn point(scene: &mechdiff::scene::Scene, name: &str) -> [f64; 2] {
    scene.points.iter().find(|q| q.name == name).unwrap().sketch
}

fn index(scene: &mechdiff::scene::Scene, name: &str) -> usize {
    scene.points.iter().position(|q| q.name == name).unwrap()
}

/// Solves the 2×2 system `[r0; r1] x = [b0, b1]` by Cramer's rule.
fn solve2(r0: [f64; 2], r1: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    let det = r0[0] * r1[1] - r0[1] * r1[0];
    [
        (b[0] * r1[1] - r0[1] * b[1]) / det,
        (r0[0] * b[1] - b[0] * r1[0]) / det,
    ]
}

fn close(got: [f64; 2], want: [f64; 2], what: &str) {
    for k in 0..2 {
        assert!(
            (got[k] - want[k]).abs() <= TOLERANCE * want[k].abs().max(1.0),
            "{what}: {got:?} vs {want:?}"
        );
    }
}

/// B = the circles about A (radius b) and O4 (radius c): differentiating |B − A|² = b² and
/// |B − O4|² = c² gives (B − A)·(B′ − A′) = b b′ and (B − O4)·(B′ − O4′) = c c′.
fn circles_by_hand(
    scene: &mechdiff::scene::Scene,
    t: &SceneTangent,
    radii_tangents: [f64; 2],
) -> [f64; 2] {
    let (a, b, o4) = (point(scene, "A"), point(scene, "B"), point(scene, "O4"));
    let (ta, to4) = (t.points[index(scene, "A")], t.points[index(scene, "O4")]);
    let r0 = [b[0] - a[0], b[1] - a[1]];
    let r1 = [b[0] - o4[0], b[1] - o4[1]];
    let (lb, lc) = (r0[0].hypot(r0[1]), r1[0].hypot(r1[1]));
    solve2(
        r0,
        r1,
        [
            lb * radii_tangents[0] + r0[0] * ta[0] + r0[1] * ta[1],
            lc * radii_tangents[1] + r1[0] * to4[0] + r1[1] * to4[1],
        ],
    )
}

#[test]
fn norton_points_move_with_each_length_as_their_constructions_differentiated_by_hand() {
    let scene = mechdiff::scene::parse("t.toml", NORTON).unwrap();
    let theta = 30f64.to_radians();
    // d/da: A = a(cos θ, sin θ) moves along the crank; B follows by the circles.
    let t = tangent(NORTON, "a");
    assert!(t.not_carried.is_empty(), "{:?}", t.not_carried);
    close(t.points[index(&scene, "O2")], [0.0, 0.0], "O2");
    close(t.points[index(&scene, "O4")], [0.0, 0.0], "O4");
    close(
        t.points[index(&scene, "A")],
        [theta.cos(), theta.sin()],
        "A",
    );
    let want = circles_by_hand(&scene, &t, [0.0, 0.0]);
    close(t.points[index(&scene, "B")], want, "B by a");
    // The drive's angle at the sketch is θ, whatever a.
    assert!(
        t.drive_at_sketch.abs() <= TOLERANCE,
        "{}",
        t.drive_at_sketch
    );
    // d/db, d/dc: the radii; d/dd: O4 = (d, 0) moves along x.
    for (p, radii) in [("b", [1.0, 0.0]), ("c", [0.0, 1.0]), ("d", [0.0, 0.0])] {
        let t = tangent(NORTON, p);
        let want = circles_by_hand(&scene, &t, radii);
        close(t.points[index(&scene, "B")], want, &format!("B by {p}"));
    }
    close(
        tangent(NORTON, "d").points[index(&scene, "O4")],
        [1.0, 0.0],
        "O4 by d",
    );
    // d/dθ per degree (the file's angle unit): A turns, and so does the drive's angle.
    let t = tangent(NORTON, "theta");
    let per_degree = 1f64.to_radians();
    close(
        t.points[index(&scene, "A")],
        [
            -0.86 * theta.sin() * per_degree,
            0.86 * theta.cos() * per_degree,
        ],
        "A by theta",
    );
    assert!((t.drive_at_sketch - per_degree).abs() <= TOLERANCE * per_degree);
}

#[test]
fn a_formula_chain_and_a_unit_are_followed() {
    // b = 2a: d/da moves the coupler's radius by 2.
    let chain = NORTON.replace("b = 1.85", "b = \"2*a + 0.13\"");
    let scene = mechdiff::scene::parse("t.toml", &chain).unwrap();
    let t = tangent(&chain, "a");
    let want = circles_by_hand(&scene, &t, [2.0, 0.0]);
    close(
        t.points[index(&scene, "B")],
        want,
        "B by a through b = 2a + 0.13",
    );
    // a in inches: d/da is per inch, 0.0254 m.
    let inches = NORTON.replace("a = 0.86", "a = { value = \"0.86/0.0254\", unit = \"in\" }");
    let scene = mechdiff::scene::parse("t.toml", &inches).unwrap();
    let t = tangent(&inches, "a");
    let theta = 30f64.to_radians();
    close(
        t.points[index(&scene, "A")],
        [0.0254 * theta.cos(), 0.0254 * theta.sin()],
        "A per inch",
    );
    let want = circles_by_hand(&scene, &t, [0.0, 0.0]);
    close(t.points[index(&scene, "B")], want, "B per inch");
}

#[test]
fn the_drive_speed_and_a_mass_move_and_a_friction_coefficient_is_named_as_not_carried() {
    let text = NORTON.replace("speed = 10 ", "speed = \"10*a/0.86\" ")
        + "\n[masses]\ncrank = { mass = \"2*a\", center = \"A\", inertia = \"a*a\" }\n\
           [friction]\nO2 = { coefficient = \"0.1*a\", pin_radius = 0.01 }\n";
    let t = tangent(&text, "a");
    // ω = 10·a/0.86 in the file's unit of speed: dω/da = ω/0.86 (SI).
    let scene = mechdiff::scene::parse("t.toml", &text).unwrap();
    let omega = scene.drive.speed.unwrap();
    assert!(
        (t.speed - omega / 0.86).abs() <= TOLERANCE * omega,
        "{}",
        t.speed
    );
    // The crank's mass 2a, moment a², centre at A (which moves with a): d/da = 2, 2a, A's.
    assert_eq!(t.masses.len(), 1);
    let (link, m) = &t.masses[0];
    assert_eq!(link, "crank");
    assert!((m.mass - 2.0).abs() <= TOLERANCE * 2.0, "{}", m.mass);
    assert!(
        (m.moment - 2.0 * 0.86).abs() <= TOLERANCE * 2.0,
        "{}",
        m.moment
    );
    close(
        m.center,
        t.points[index(&scene, "A")],
        "the crank's centre by a",
    );
    // The friction coefficient moves and is not carried.
    assert_eq!(t.not_carried.len(), 1, "{:?}", t.not_carried);
    assert_eq!(t.not_carried[0].path, "friction.O2.coefficient");
    assert!(t.not_carried[0].location.starts_with("t.toml:"));
    assert!(t.carries_kinematics());
}

/// The offset slider-crank: B on the line y = e at distance l from A.
const SLIDER_CRANK: &str = r#"
[parameters]
r = 0.1
l = 0.4
e = -0.012
[points]
O = [0, 0]
A = { from = "O", length = "r", angle = "pi/3" }
G0 = [0, "e"]
G1 = [1, "e"]
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
joint = "guide"
[sweep]
positions = [0.45]
[[output]]
point = "B"
quantities = ["position"]
"#;

#[test]
fn a_point_on_a_line_moves_as_its_distance_equation_differentiated_by_hand() {
    let scene = mechdiff::scene::parse("t.toml", SLIDER_CRANK).unwrap();
    let (a, b) = (point(&scene, "A"), point(&scene, "B"));
    let phi = std::f64::consts::FRAC_PI_3;
    // B = (x, e): (B − A)·(B′ − A′) = l l′ with B′ = (x′, e′).
    for (p, ta, te, tl) in [
        ("r", [phi.cos(), phi.sin()], 0.0, 0.0),
        ("e", [0.0, 0.0], 1.0, 0.0),
        ("l", [0.0, 0.0], 0.0, 1.0),
    ] {
        let t = tangent(SLIDER_CRANK, p);
        close(t.points[index(&scene, "A")], ta, &format!("A by {p}"));
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let x = (0.4 * tl + dx * ta[0] + dy * ta[1] - dy * te) / dx;
        close(t.points[index(&scene, "B")], [x, te], &format!("B by {p}"));
        // The drive (the slider's displacement from G0 along x) is x_B − 0.
        assert!(
            (t.drive_at_sketch - x).abs() <= TOLERANCE,
            "{p}: {} vs {x}",
            t.drive_at_sketch
        );
    }
}

/// A point written `["2*l", "l^2"]` moves by d/dl = (2, 2l): the formulas are resolved in
/// dual numbers with `l` seeded, and the derivative rules of 2·l and l² give 2 and 2·l¹,
/// each exact in f64 (a doubling), so the comparison is exact. The scene read in f64 places
/// the point at (2l, l²): 2l is exact, l² is one correctly rounded operation either way
/// (1 ulp).
#[test]
fn a_point_of_formulas_moves_by_their_closed_form_derivatives_exactly() {
    let l = 0.3f64;
    let text = format!(
        r#"[parameters]
l = {l}
[points]
O = [0.0, 0.0]
A = ["2*l", "l^2"]
[links]
ground = ["O"]
crank = ["O", "A"]
[joints]
O = {{ type = "revolute", at = "O", links = ["ground", "crank"] }}
[drive]
joint = "O"
line = ["O", "A"]
[sweep]
positions = [0.0]
[[output]]
point = "A"
quantities = ["position"]
"#
    );
    let scene = mechdiff::scene::parse("t.toml", &text).unwrap();
    let a = point(&scene, "A");
    assert_eq!(a[0], 2.0 * l);
    assert!((a[1] - l * l).abs() <= f64::EPSILON * l * l, "{a:?}");
    let t = tangent(&text, "l");
    assert_eq!(t.points[index(&scene, "A")], [2.0, 2.0 * l]);
    assert_eq!(t.points[index(&scene, "O")], [0.0, 0.0]);
    assert!(t.not_carried.is_empty(), "{:?}", t.not_carried);
}
