//! Issue 14, "Writing a mechanism as a designer thinks of it": `[parameters]` and `--set`,
//! points built from lengths, masses from a density, and inch scenes.
//!
//! The four-bar is Norton's (Design of Machinery, the non-Grashof four-bar with
//! a = 0.86, b = 1.85, c = 0.86, d = 2.22 m as given in issue 14): crank O2–A = a,
//! coupler A–B = b, rocker O4–B = c, ground O2–O4 = d. s + l = 3.08 > p + q = 2.71, so the
//! crank rocks: |A O4| ≤ b + c holds for crank angles within ±116.0°, and the sweep stays
//! within 0°…100°.

use mechdiff::Error;
use mechdiff::scene::{self, Report, parameters::Setting};

use crate::common;
use common::line_of;

const A: f64 = 0.86;
const B: f64 = 1.85;
const C: f64 = 0.86;
const D: f64 = 2.22;
/// The crank angle of the sketch (deg).
const SKETCH: f64 = 30.0;

/// Everything after `[points]` that the two versions of the four-bar share.
const REST: &str = r#"
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
acceleration = 5

[sweep]
from = 0
to = 100
step = 10

[[output]]
name = "psi"
angle = ["O4", "B"]
quantities = ["position", "velocity_coefficient", "acceleration_coefficient", "velocity", "acceleration"]

[[output]]
point = "B"
"#;

/// The four-bar written with its lengths only.
fn from_lengths() -> String {
    format!(
        r#"[parameters]
a = 0.86
b = 1.85
c = 0.86
d = 2.22
theta = {SKETCH}

[units]
angle = "deg"

[points]
O2 = [0, 0]
O4 = ["d", 0]
A = {{ from = "O2", length = "a", angle = "theta" }}
B = {{ circles = ["A", "O4"], radii = ["b", "c"], side = "left" }}
{REST}"#
    )
}

/// The four-bar with coordinates computed here, independently of the scene's construction:
/// B from the triangle A–O4–B by the law of cosines at O4, the branch left of A → O4.
fn from_coordinates() -> String {
    let theta = SKETCH.to_radians();
    let a = [A * theta.cos(), A * theta.sin()];
    let e = (a[0] - D).hypot(a[1]);
    let gamma = ((C * C + e * e - B * B) / (2.0 * C * e)).acos();
    let towards_a = a[1].atan2(a[0] - D);
    let candidates = [towards_a + gamma, towards_a - gamma].map(|t| [D + C * t.cos(), C * t.sin()]);
    let left = |p: [f64; 2]| (D - a[0]) * (p[1] - a[1]) - (0.0 - a[1]) * (p[0] - a[0]) > 0.0;
    let b = candidates.into_iter().find(|&p| left(p)).unwrap();
    format!(
        "[units]\nangle = \"deg\"\n\n[points]\nO2 = [0, 0]\nO4 = [{D:e}, 0]\nA = [{:e}, {:e}]\n\
         B = [{:e}, {:e}]\n{REST}",
        a[0], a[1], b[0], b[1]
    )
}

fn run(text: &str, settings: &[Setting]) -> Report {
    let scene = scene::parse_with("test.toml", text, settings).unwrap_or_else(|e| panic!("{e}"));
    scene::run(&scene).unwrap_or_else(|e| panic!("{e}"))
}

/// Asserts two reports have the same columns and agree to `tol` relative to each value's
/// magnitude, or absolute below 1 (SI).
fn assert_same(got: &Report, want: &Report, tol: f64) {
    assert_eq!(got.columns.len(), want.columns.len());
    for (g, w) in got.rows.iter().zip(&want.rows) {
        for (k, (x, y)) in g.iter().zip(w).enumerate() {
            assert!(
                (x - y).abs() <= tol * y.abs().max(1.0),
                "column {}: {x} vs {y}",
                got.columns[k].name
            );
        }
    }
    assert_eq!(got.rows.len(), want.rows.len());
}

#[test]
fn nortons_four_bar_from_its_lengths_moves_as_its_coordinate_version() {
    let lengths = run(&from_lengths(), &[]);
    let coordinates = run(&from_coordinates(), &[]);
    // 1e-12 (relative above 1) on values of order 1–100 (rad, m, rad/s²): the two sketches
    // differ by a few ulps (two derivations of B), and both sweeps solve the same loop from
    // them (measured: at most 8e-13 absolute, on an acceleration).
    assert_same(&lengths, &coordinates, 1e-12);
    // The crank length really is a: |A| at every row is checked through B's distance to O4.
    let (bx, by) = (
        lengths.column("x_B").unwrap(),
        lengths.column("y_B").unwrap(),
    );
    for (x, y) in bx.iter().zip(&by) {
        // 1e-12: the rocker length is held by the solver to its convergence tolerance.
        assert!(((x - D).hypot(*y) - C).abs() < 1e-12);
    }
}

#[test]
fn set_replaces_a_parameter_and_formulas_follow_it() {
    // The ground twice as long with the crank and rocker scaled with it: every length × 2,
    // so angles are unchanged and positions double (exact: scaling by 2 is exact in f64, and
    // the construction and the solver commute with it up to rounding, 1e-12).
    let text = from_lengths()
        .replace("a = 0.86", "s = 1\na = \"0.86*s\"")
        .replace("b = 1.85", "b = \"1.85*s\"")
        .replace("c = 0.86", "c = \"0.86*s\"")
        .replace("d = 2.22", "d = \"2.22*s\"");
    let one = run(&text, &[]);
    let two = run(&text, &["s=2".parse().unwrap()]);
    let (psi1, psi2) = (one.column("psi").unwrap(), two.column("psi").unwrap());
    for (p1, p2) in psi1.iter().zip(&psi2) {
        assert!((p1 - p2).abs() < 1e-12, "{p1} vs {p2}");
    }
    let (x1, x2) = (one.column("x_B").unwrap(), two.column("x_B").unwrap());
    for (a, b) in x1.iter().zip(&x2) {
        assert!((2.0 * a - b).abs() < 1e-12, "{a} vs {b}");
    }
    let e = scene::parse_with("test.toml", &text, &["q=2".parse().unwrap()]).unwrap_err();
    assert!(matches!(e, Error::Setting { .. }), "{e:?}");
    assert!(
        e.to_string()
            .contains("no parameter `q`; its parameters are: "),
        "{e}"
    );
}

#[test]
fn a_formula_naming_an_unknown_parameter_is_refused_at_its_column() {
    let text = from_lengths().replace("radii = [\"b\", \"c\"]", "radii = [\"b\", \"2*cc\"]");
    let e = scene::parse("bad.toml", &text).unwrap_err();
    let message = e.to_string();
    // The location is the name itself: its line and column in the file.
    let line = line_of(&text, "B = {");
    let column = text.lines().nth(line - 1).unwrap().find("cc\"").unwrap() + 1;
    assert!(
        message.starts_with(&format!("bad.toml:{line}:{column}:")),
        "{message}"
    );
    assert!(
        message.contains("uses `cc` (column 3 of the formula)"),
        "{message}"
    );
    assert!(message.contains("the parameters are: "), "{message}");
}

#[test]
fn circles_that_do_not_meet_are_refused_naming_the_construction_and_its_lengths() {
    // b + c = 2.71 < |A O4| once the coupler is 0.5: the circles are apart.
    let text = from_lengths().replace("b = 1.85", "b = 0.5");
    let e = scene::parse("bad.toml", &text).unwrap_err();
    assert!(matches!(e, Error::Unconstructible { .. }), "{e:?}");
    let message = e.to_string();
    assert!(
        message.starts_with(&format!("bad.toml:{}:", line_of(&text, "B = {"))),
        "{message}"
    );
    for part in [
        "point `B`",
        "`A` of radius 0.5 m",
        "`O4` of radius 0.86 m",
        "more than the sum",
    ] {
        assert!(message.contains(part), "`{part}` missing from: {message}");
    }
}

#[test]
fn a_slider_crank_built_from_a_circle_and_a_line_moves_as_its_coordinate_version() {
    // Crank 0.1 at 60°, connecting rod 0.35, the slider on the x axis ahead of the crank.
    let rest = r#"
[links]
ground = ["O", "G"]
crank = ["O", "A"]
rod = ["A", "C"]
slider = ["C"]

[joints]
O = { type = "revolute", at = "O", links = ["ground", "crank"] }
A = { type = "revolute", at = "A", links = ["crank", "rod"] }
C = { type = "revolute", at = "C", links = ["rod", "slider"] }
S = { type = "prismatic", links = ["ground", "slider"], line = ["O", "G"], point = "C" }

[drive]
joint = "O"
line = ["O", "A"]
speed = 1

[sweep]
from = 0
to = 360
step = 30

[[output]]
slider = "S"
"#;
    let built = format!(
        "[units]\nangle = \"deg\"\n[points]\nO = [0, 0]\nG = [1, 0]\n\
         A = {{ from = \"O\", length = 0.1, angle = 60 }}\n\
         C = {{ circle = \"A\", radius = 0.35, line = [\"O\", \"G\"], along = \"forward\" }}\n{rest}"
    );
    // C = A_x + sqrt(0.35² − A_y²) on the x axis.
    let (ax, ay) = (
        0.1 * 60f64.to_radians().cos(),
        0.1 * 60f64.to_radians().sin(),
    );
    let c = ax + (0.35f64 * 0.35 - ay * ay).sqrt();
    let coordinates = format!(
        "[units]\nangle = \"deg\"\n[points]\nO = [0, 0]\nG = [1, 0]\nA = [{ax:e}, {ay:e}]\n\
         C = [{c:e}, 0]\n{rest}"
    );
    // 1e-12 absolute on slider travel of order 0.1 m: the two sketches agree to rounding.
    assert_same(&run(&built, &[]), &run(&coordinates, &[]), 1e-12);
}

/// Mass per length of the Norton four-bar's moving links (kg/m), as a steel bar of about
/// 10 cm² section.
const RHO: f64 = 7.8;

/// The dynamic sections: masses from the density, or as written by `masses`.
fn with_dynamics(text: &str, masses: &str) -> String {
    format!(
        "{text}\n[gravity]\ng = 9.81\n\n[masses]\n{masses}\n[[dynamics]]\noutput = \"drive_torque\"\n"
    )
}

#[test]
fn nortons_drive_torque_from_a_density_matches_explicit_masses() {
    let density = format!(
        "crank = {{ density = {RHO} }}\ncoupler = {{ density = {RHO} }}\nrocker = {{ density = \"{RHO}\" }}\n"
    );
    let built = run(&with_dynamics(&from_lengths(), &density), &[]);
    // The explicit version: coordinates as in `from_coordinates`, each link a uniform bar
    // written out here (m = ρL at the midpoint, I = mL²/12), with L the link's length.
    let coordinates = from_coordinates();
    let xy = |name: &str| -> [f64; 2] {
        let line = coordinates
            .lines()
            .find(|l| l.starts_with(&format!("{name} = [")))
            .unwrap();
        let inner = line.split('[').nth(1).unwrap().trim_end_matches(']');
        let v: Vec<f64> = inner
            .split(',')
            .map(|t| t.trim().parse().unwrap())
            .collect();
        [v[0], v[1]]
    };
    let mut masses = String::new();
    for (link, p, q, length) in [
        ("crank", "O2", "A", A),
        ("coupler", "A", "B", B),
        ("rocker", "O4", "B", C),
    ] {
        let (p, q) = (xy(p), xy(q));
        let m = RHO * length;
        masses.push_str(&format!(
            "{link} = {{ mass = {m:e}, center = [{:e}, {:e}], inertia = {:e} }}\n",
            0.5 * (p[0] + q[0]),
            0.5 * (p[1] + q[1]),
            m * length * length / 12.0
        ));
    }
    let explicit = run(&with_dynamics(&coordinates, &masses), &[]);
    let torque = |r: &Report| r.column("M_drive").expect("a drive torque column");
    let (got, want) = (torque(&built), torque(&explicit));
    let largest = want.iter().fold(0.0f64, |m, t| m.max(t.abs()));
    assert!(
        largest > 1.0,
        "the torque is not trivially small: {largest}"
    );
    for (g, w) in got.iter().zip(&want) {
        // 1e-12 of the largest torque: the two sketches and the two bar lengths (from the
        // sketch, and the parameter) differ by a few ulps.
        assert!((g - w).abs() <= 1e-12 * largest, "{g} vs {w}");
    }
}

#[test]
fn a_mass_needs_exactly_one_of_mass_and_density() {
    let text = with_dynamics(
        &from_lengths(),
        "crank = { mass = 1, density = 2, center = \"A\" }\n",
    );
    let e = scene::parse("bad.toml", &text).unwrap_err();
    assert!(e.to_string().contains("exactly one of `mass`"), "{e}");
    let text = with_dynamics(&from_lengths(), "crank = { mass = 1 }\n");
    let e = scene::parse("bad.toml", &text).unwrap_err();
    assert!(e.to_string().contains("without its `center`"), "{e}");
}

/// Norton's four-bar in a unit system: every number written in it, converted from the
/// inch-native values here. `length`, `mass`, `force` and `torque` are SI per file unit.
fn in_units(units: &str, length: f64, mass: f64, force: f64, torque: f64) -> String {
    let l = |inches: f64| format!("{:e}", inches * 0.0254 / length);
    // Densities, masses and moments in pound-inch terms, converted.
    let pound = 0.45359237;
    let density = format!("{:e}", 0.28 * pound / 0.0254 / (mass / length));
    let coupler_mass = format!("{:e}", 20.0 * pound / mass);
    let inertia = format!(
        "{:e}",
        9000.0 * pound * 0.0254 * 0.0254 / (mass * length * length)
    );
    let lbf = 0.45359237 * 9.80665;
    let force = format!("{:e}", 15.0 * lbf / force);
    let torque = format!("{:e}", 40.0 * lbf * 0.0254 / torque);
    format!(
        r#"[parameters]
a = {a}
b = {b}
c = {c}
d = {d}

[units]
{units}
angle = "deg"
angular_velocity = "rpm"

[points]
O2 = [0, 0]
O4 = ["d", 0]
A = {{ from = "O2", length = "a", angle = 30 }}
B = {{ circles = ["A", "O4"], radii = ["b", "c"], side = "left" }}
M = {{ from = "A", length = "b/2", angle = 0 }}

[links]
ground = ["O2", "O4"]
crank = ["O2", "A"]
coupler = ["A", "B", "M"]
rocker = ["O4", "B"]

[joints]
O2 = {{ type = "revolute", at = "O2", links = ["ground", "crank"] }}
A = {{ type = "revolute", at = "A", links = ["crank", "coupler"] }}
B = {{ type = "revolute", at = "B", links = ["coupler", "rocker"] }}
O4 = {{ type = "revolute", at = "O4", links = ["ground", "rocker"] }}

[drive]
joint = "O2"
line = ["O2", "A"]
speed = 60

[sweep]
from = 0
to = 100
step = 10

[[output]]
point = "B"

[gravity]
g = 9.81

[masses]
crank = {{ density = {density} }}
rocker = {{ density = {density} }}
coupler = {{ mass = {coupler_mass}, center = "M", inertia = {inertia} }}

[[load]]
link = "coupler"
point = "B"
force = [0, "-{force}"]

[[load]]
link = "rocker"
torque = {torque}

[[dynamics]]
output = "drive_torque"

[[dynamics]]
output = "reactions"
"#,
        a = l(34.0),
        b = l(73.0),
        c = l(34.0),
        d = l(87.0),
    )
}

#[test]
fn an_inch_scene_gives_the_si_results_of_its_metric_twin() {
    let lbf = 0.45359237 * 9.80665;
    let inch = in_units(
        "length = \"in\"\nmass = \"lb\"\nforce = \"lbf\"\ntorque = \"lbf*in\"\ninertia = \"lb*in^2\"",
        0.0254,
        0.45359237,
        lbf,
        lbf * 0.0254,
    );
    let metric = in_units("length = \"m\"", 1.0, 1.0, 1.0, 1.0);
    let slug = 0.45359237 * 9.80665 / 0.3048;
    let feet = in_units(
        "length = \"ft\"\nmass = \"slug\"\ntorque = \"lbf*ft\"\ninertia = \"slug*ft^2\"",
        0.3048,
        slug,
        1.0,
        lbf * 0.3048,
    );
    let (inch, metric, feet) = (run(&inch, &[]), run(&metric, &[]), run(&feet, &[]));
    let largest = metric
        .rows
        .iter()
        .flatten()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    // 1e-12 of the largest value (a reaction of some hundred N): each number of the twins
    // is the same SI value up to two roundings (written in the unit, converted back).
    assert_same(&inch, &metric, 1e-12 * largest);
    assert_same(&feet, &metric, 1e-12 * largest);
    assert!(
        metric
            .column("M_drive")
            .unwrap()
            .iter()
            .any(|t| t.abs() > 1.0)
    );
}

#[test]
fn constructions_in_a_cycle_are_refused() {
    let text = from_lengths().replace(
        "A = { from = \"O2\", length = \"a\", angle = \"theta\" }",
        "A = { circles = [\"O2\", \"B\"], radii = [\"a\", \"b\"], side = \"left\" }",
    );
    let e = scene::parse("bad.toml", &text).unwrap_err();
    assert!(e.to_string().contains("(a cycle)"), "{e}");
}

#[test]
fn a_long_chain_of_points_is_placed_without_recursion() {
    // 5000 polar points, each from the next one written after it, so that the first one
    // written needs the whole chain; read on a thread with a 256 KiB stack, which a
    // recursion over the chain would overflow.
    let n = 5000;
    let mut text = String::from("[points]\n");
    for i in 0..n {
        text.push_str(&format!(
            "P{i} = {{ from = \"P{}\", length = 1, angle = 0 }}\n",
            i + 1
        ));
    }
    text.push_str(&format!("P{n} = [0, 0]\n"));
    text.push_str(
        "[links]\nground = [\"P0\"]\ncrank = [\"P0\", \"P1\"]\n[joints]\n\
         O = { type = \"revolute\", at = \"P0\", links = [\"ground\", \"crank\"] }\n\
         [drive]\njoint = \"O\"\nline = [\"P0\", \"P1\"]\n[sweep]\npositions = [0]\n\
         [[output]]\npoint = \"P1\"\nquantities = [\"position\"]\n",
    );
    let scene = std::thread::Builder::new()
        .stack_size(256 * 1024)
        .spawn(move || scene::parse("chain.toml", &text).map_err(|e| e.to_string()))
        .unwrap()
        .join()
        .unwrap()
        .unwrap();
    // P0 is n unit steps along +x from P_n = (0, 0): exact (sums of integers).
    assert_eq!(scene.points[0].sketch, [n as f64, 0.0]);
}

/// Theo Jansen's "holy numbers" (mm): a … m as in his book The Great Pretender and on
/// strandbeest.com; the crank m turns about O, the fixed pivot Z is a left and l below it.
const HOLY: [(&str, f64); 13] = [
    ("a", 38.0),
    ("b", 41.5),
    ("c", 39.3),
    ("d", 40.1),
    ("e", 55.8),
    ("f", 39.4),
    ("g", 36.7),
    ("h", 65.7),
    ("i", 49.0),
    ("j", 50.0),
    ("k", 61.9),
    ("l", 7.8),
    ("m", 15.0),
];

/// Jansen's leg after `[points]`: crank O–P (m); j = P–Q, k = P–R; the triangle Z–Q–S
/// (b, d, e); c = Z–R; f = S–T; the foot triangle R–T–F (g, i, h). P, Z and R join three
/// links each.
const JANSEN_REST: &str = r#"
[links]
ground = ["O", "Z"]
crank = ["O", "P"]
j = ["P", "Q"]
k = ["P", "R"]
bde = ["Z", "Q", "S"]
c = ["Z", "R"]
f = ["S", "T"]
foot = ["R", "T", "F"]

[joints]
O = { type = "revolute", at = "O", links = ["ground", "crank"] }
P = { type = "revolute", at = "P", links = ["crank", "j", "k"] }
Q = { type = "revolute", at = "Q", links = ["j", "bde"] }
Z = { type = "revolute", at = "Z", links = ["ground", "bde", "c"] }
R = { type = "revolute", at = "R", links = ["k", "c", "foot"] }
S = { type = "revolute", at = "S", links = ["bde", "f"] }
T = { type = "revolute", at = "T", links = ["f", "foot"] }

[drive]
joint = "O"
line = ["O", "P"]
speed = 1

[sweep]
from = 0
to = 360
step = 10

[[output]]
point = "F"
"#;

#[test]
fn jansens_leg_from_its_thirteen_lengths_walks_as_its_coordinate_version() {
    let mut parameters = String::from("[parameters]\n");
    for (name, value) in HOLY {
        parameters.push_str(&format!("{name} = {value}\n"));
    }
    let lengths = format!(
        "{parameters}\n[units]\nlength = \"mm\"\nangle = \"deg\"\n\n[points]\n\
         O = [0, 0]\nZ = [\"-a\", \"-l\"]\nP = {{ from = \"O\", length = \"m\", angle = 0 }}\n\
         Q = {{ circles = [\"P\", \"Z\"], radii = [\"j\", \"b\"], side = \"left\" }}\n\
         R = {{ circles = [\"P\", \"Z\"], radii = [\"k\", \"c\"], side = \"left\" }}\n\
         S = {{ circles = [\"Q\", \"Z\"], radii = [\"d\", \"e\"], side = \"left\" }}\n\
         T = {{ circles = [\"S\", \"R\"], radii = [\"f\", \"g\"], side = \"left\" }}\n\
         F = {{ circles = [\"T\", \"R\"], radii = [\"h\", \"i\"], side = \"right\" }}\n\
         {JANSEN_REST}"
    );
    // The coordinate version: each apex by the angle at its first centre (law of cosines)
    // turned from the direction to the second, counter-clockwise for "left".
    let v = |name: &str| HOLY.iter().find(|(n, _)| *n == name).unwrap().1;
    let apex = |c1: [f64; 2], r1: f64, c2: [f64; 2], r2: f64, left: bool| {
        let dist = (c2[0] - c1[0]).hypot(c2[1] - c1[1]);
        let turn = ((r1 * r1 + dist * dist - r2 * r2) / (2.0 * r1 * dist)).acos();
        let towards = (c2[1] - c1[1]).atan2(c2[0] - c1[0]);
        let t = if left { towards + turn } else { towards - turn };
        [c1[0] + r1 * t.cos(), c1[1] + r1 * t.sin()]
    };
    let z = [-v("a"), -v("l")];
    let p = [v("m"), 0.0];
    let q = apex(p, v("j"), z, v("b"), true);
    let r = apex(p, v("k"), z, v("c"), true);
    let s = apex(q, v("d"), z, v("e"), true);
    let t = apex(s, v("f"), r, v("g"), true);
    let f = apex(t, v("h"), r, v("i"), false);
    let mut coordinates = String::from("[units]\nlength = \"mm\"\nangle = \"deg\"\n\n[points]\n");
    for (name, xy) in [
        ("O", [0.0, 0.0]),
        ("Z", z),
        ("P", p),
        ("Q", q),
        ("R", r),
        ("S", s),
        ("T", t),
        ("F", f),
    ] {
        coordinates.push_str(&format!("{name} = [{:e}, {:e}]\n", xy[0], xy[1]));
    }
    coordinates.push_str(JANSEN_REST);
    let (built, written) = (run(&lengths, &[]), run(&coordinates, &[]));
    // 1e-12 m absolute on a foot path of about 0.1 m (SI): the sketches differ by a few
    // ulps of 100 mm, and both sweeps solve the same loops from them.
    assert_same(&built, &written, 1e-12);
    // The branch is the walking leg (not a mirrored assembly): over a turn the foot stays
    // between about 94.7 and 63.5 mm below the crank axle (a plain-f64 Python sketch of the
    // same dyads at 5° steps; 1 mm covers the coarser 10° sampling here).
    let y = built.column("y_F").unwrap();
    let (lo, hi) = y
        .iter()
        .fold((f64::MAX, f64::MIN), |(lo, hi), &v| (lo.min(v), hi.max(v)));
    assert!(
        (lo + 0.0947).abs() < 1e-3 && (hi + 0.0635).abs() < 1e-3,
        "{lo} {hi}"
    );
}
