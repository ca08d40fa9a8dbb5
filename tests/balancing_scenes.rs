//! The balancing sections of scenes: the Whitworth's crank counterweight against the
//! closed-form least squares of one rotating vector, the crankshaft rotor's printed answers,
//! CSV columns, and bad balancing input with `file:line:column`.

use std::path::Path;

use mechdiff::Error;
use mechdiff::scene::balancing::{RotorScene, rotor_scene};
use mechdiff::scene::{self};

use crate::common;
use common::{column, mechdiff, run_scene as run};

/// At constant speed ω a crank counterweight b (global, at the sketch) adds the force
/// ω² R(θ) b, θ the crank's rotation (= φ here: the sketch is at φ = 0). With N positions
/// evenly over a revolution, Σ R(θ)ᵀ R(θ) = N I, so the least squares has the closed form
/// b = −Σ R(θ)ᵀ F₀ / (N ω²), computed here from the scene's own shaking-force columns
/// (the dynamics code, not the balancing code).
#[test]
fn whitworth_crank_counterweight_is_the_closed_form_least_squares() {
    let r = run("whitworth_balancing.toml");
    let phi = column(&r, "phi");
    let (fx, fy) = (column(&r, "SumF_x"), column(&r, "SumF_y"));
    let omega = 100.0 * std::f64::consts::TAU / 60.0;
    let n = phi.len() as f64;
    assert_eq!(phi.len(), 72);
    let mut b = [0.0, 0.0];
    for ((p, x), y) in phi.iter().zip(&fx).zip(&fy) {
        let (s, c) = p.sin_cos();
        b[0] -= (c * x + s * y) / (n * omega * omega);
        b[1] -= (-s * x + c * y) / (n * omega * omega);
    }
    let linkage = r.balancing.as_ref().unwrap().linkage.as_ref().unwrap();
    let cw = &linkage.counterweights[0];
    // 1e-12 relative: both sum 72 terms of the same size; the SVD adds its rounding.
    let size = b[0].hypot(b[1]);
    assert!((cw.vector[0] - b[0]).hypot(cw.vector[1] - b[1]) <= 1e-12 * size);
    // The mechanism is symmetric about the vertical through A0 and B0: the counterweight
    // lies opposite the crank pin (180° from A0→A, to the rounding of the sums).
    assert!((cw.angle.abs() - std::f64::consts::PI).abs() < 1e-12);
    // After = before + ω² R(θ) b at every position: the dynamics of the mechanism with the
    // counterweight added as a point mass agree with the linear model (1e-9 of the largest
    // force: rounding of the dynamics, two sweeps).
    let (ax, ay) = (column(&r, "SumF_x_bal"), column(&r, "SumF_y_bal"));
    let scale = linkage.before.max_force();
    for j in 0..phi.len() {
        let (s, c) = phi[j].sin_cos();
        let w2 = omega * omega;
        let ex = fx[j] + w2 * (c * cw.vector[0] - s * cw.vector[1]);
        let ey = fy[j] + w2 * (s * cw.vector[0] + c * cw.vector[1]);
        assert!(
            (ax[j] - ex).hypot(ay[j] - ey) <= 1e-9 * scale,
            "φ = {}",
            phi[j]
        );
    }
    // The foundation load goes down (the numbers are in the README).
    assert!(linkage.after.max_force() < linkage.before.max_force());
    assert!(linkage.after.rms_force() < linkage.before.rms_force());
}

fn rotor(name: &str) -> RotorScene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(name);
    rotor_scene::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn rotor_scene_prints_the_stated_variant() {
    let text = rotor("rotor_balancing.toml").lines().unwrap().join("\n");
    // √0.19 m = 435.889894354067 mm (core/tests/balancing_rotor.rs derives it by hand).
    assert!(text.contains("plane at 435.889894354067 mm"), "{text}");
    assert!(
        text.contains("none needed (the mr polygon closes)"),
        "{text}"
    );
    assert!(text.contains("plane at -400 mm: m r = "), "{text}");
}

#[test]
fn run_prints_counterweights_and_writes_the_columns_after_to_csv() {
    let csv = std::env::temp_dir().join(format!("mechdiff-bal-{}.csv", std::process::id()));
    let out = mechdiff(&[
        "run",
        "scenes/whitworth_balancing.toml",
        "--csv",
        csv.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("counterweight on `crank`: m r = "), "{text}");
    assert!(
        text.contains("largest |SumF| (foundation load): "),
        "{text}"
    );
    let csv_text = std::fs::read_to_string(&csv).unwrap();
    std::fs::remove_file(&csv).unwrap();
    let header = csv_text.lines().next().unwrap();
    assert!(
        header.ends_with("SumF_x_bal [N],SumF_y_bal [N],M_shaking_bal [N m],M_drive_bal [N m]"),
        "{header}"
    );
    assert_eq!(csv_text.lines().count(), 73);
}

/// The four-bar of bad_scenes.rs with masses, a speed and one full revolution.
const FOUR_BAR: &str = r#"[points]
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
to = 6
step = 0.5
"#;

const MASSES: &str = r#"[masses]
crank = { mass = 1, center = [0.0, 0.05] }
coupler = { mass = 2, center = [0.2, 0.2] }
rocker = { mass = 1.5, center = [0.4, 0.15] }
"#;

fn error(text: &str) -> Error {
    let scene = match scene::parse("bal.toml", text) {
        Ok(s) => s,
        Err(e) => return e,
    };
    scene::run(&scene).expect_err("a bad balancing request")
}

#[test]
fn four_bar_scene_is_fully_force_balanced_by_crank_and_rocker() {
    let text = format!(
        "{FOUR_BAR}{MASSES}[balancing]\ncounterweights = [\n  {{ link = \"crank\", line = [\"O2\", \"A\"], radius = 0.05 }},\n  {{ link = \"rocker\", line = [\"O4\", \"B\"], radius = 0.05 }},\n]\n"
    );
    let scene = scene::parse("fb.toml", &text).unwrap();
    let r = scene::run(&scene).unwrap();
    let b = r.balancing.unwrap();
    let linkage = b.linkage.unwrap();
    // Berkof–Lowen: crank and rocker counterweights make the centre of mass stationary
    // (core/tests/balancing_linkage.rs checks the counterweights against their formula).
    assert!(linkage.full_force_balance());
    assert!(b.lines.iter().any(|l| l.contains("full force balance")));
}

#[test]
fn bad_balancing_input_is_located() {
    let cw = |c: &str| format!("[balancing]\ncounterweights = [{c}]\n");
    // Zero radius.
    let e = error(&format!(
        "{FOUR_BAR}{MASSES}{}",
        cw(r#"{ link = "crank", line = ["O2", "A"], radius = 0 }"#)
    ));
    assert!(
        matches!(&e, Error::NonPositiveLength { location, .. } if location.line == 29 && location.column == 66),
        "{e}"
    );
    // A coupler counterweight: no fixed pivot.
    let e = error(&format!(
        "{FOUR_BAR}{MASSES}{}",
        cw(r#"{ link = "coupler", line = ["A", "B"], radius = 0.05 }"#)
    ));
    assert!(e.to_string().contains("fixed pivot"), "{e}");
    assert!(e.to_string().starts_with("bal.toml:29:19"), "{e}");
    // Links without mass data.
    let e = error(&format!(
        "{FOUR_BAR}{}",
        cw(r#"{ link = "crank", line = ["O2", "A"], radius = 0.05 }"#)
    ));
    assert!(e.to_string().contains("mass data"), "{e}");
    // A line point that is not on the link.
    let e = error(&format!(
        "{FOUR_BAR}{MASSES}{}",
        cw(r#"{ link = "crank", line = ["O2", "B"], radius = 0.05 }"#)
    ));
    assert!(
        e.to_string().contains("must be a point of link `crank`"),
        "{e}"
    );
    // No drive speed.
    let e = error(&format!(
        "{}{MASSES}{}",
        FOUR_BAR.replace("speed = 10\n", ""),
        cw(r#"{ link = "crank", line = ["O2", "A"], radius = 0.05 }"#)
    ));
    assert!(e.to_string().contains("speed"), "{e}");
    // Rotor: coincident correction planes, zero correction radius, no masses.
    let rotor = |extra: &str| {
        format!(
            "{FOUR_BAR}[rotor]\nmasses = [{{ mass = 1, radius = 0.1, angle = 0, plane = 0.2 }}]\n{extra}"
        )
    };
    let e = error(&rotor("planes = [0.3, 0.3]\n"));
    assert!(
        e.to_string().contains("two distinct correction planes"),
        "{e}"
    );
    let e = error(&rotor("correction_radius = 0\n"));
    assert!(matches!(e, Error::NonPositiveLength { .. }), "{e}");
    let e = error(&format!("{FOUR_BAR}[rotor]\nmasses = []\n"));
    assert!(e.to_string().contains("empty"), "{e}");
    let e = error(&format!(
        "{FOUR_BAR}[rotor]\nmasses = [{{ mass = 1, radius = 0.1, angle = 0, plane = 0.2 }}]\nplanes = [0.3, 0.30000000000000004]\n"
    ));
    assert!(e.to_string().contains("coincide"), "{e}");
}

/// The balancing pictures: the rotor's polygons with their corrections drawn in red, and the
/// shaking force locus before and after; each SVG renders, and the correction colour
/// (#c0392b) is on the rendered polygon.
#[test]
fn balancing_pictures_are_drawn() {
    let load = |name: &str| {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("scenes")
            .join(name);
        let scene = scene::load(path).unwrap();
        let report = scene::run(&scene).unwrap();
        mechdiff::pictures::balancing::pictures(&scene, &report).unwrap()
    };
    let polygons =
        mechdiff::pictures::balancing::rotor_polygons(&rotor("rotor_balancing.toml").rotor)
            .unwrap();
    for drawing in &polygons {
        let raster = mechdiff::pictures::raster::render(&drawing.to_svg()).unwrap();
        let red = (0..raster.width)
            .flat_map(|x| (0..raster.height).map(move |y| (x, y)))
            .filter(|&(x, y)| {
                raster
                    .pixel(x, y)
                    .is_some_and(|p| p[0] > 150 && p[1] < 100 && p[2] < 100)
            })
            .count();
        assert!(red > 50, "{red} red pixels");
    }
    let linkage = load("whitworth_balancing.toml");
    assert_eq!(linkage.len(), 1);
    assert!(linkage[0].1.contains("locus"));
}

/// An in-line slider-crank (r = 0.1 m, l = 0.4 m) with a crank of 1 kg at 0.03 m, a rod of
/// 0.6 kg at mid-length and a slider of 2 kg, at 100 rad/s. By hand: m_rec = 2.3 kg,
/// m_rot r = 0.06 kg·m, primary 2.3·0.1·100² = 2300 N, secondary 575 N; the half balance
/// needs 0.06 + 0.5·2.3·0.1 = 0.175 kg·m and leaves 1150 N along and 1150 N across.
const SLIDER_CRANK: &str = r#"[points]
O = [0.0, 0.0]
A = [0.1, 0.0]
B = [0.5, 0.0]
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
joint = "O"
line = ["O", "A"]
speed = 100
[sweep]
positions = [0]
[masses]
crank = { mass = 1, center = [0.03, 0.0] }
rod = { mass = 0.6, center = [0.3, 0.0] }
slider = { mass = 2, center = "B" }
[balancing]
slider_crank = { crank = "crank", rod = "rod", slider = "slider" }
"#;

#[test]
fn slider_crank_unbalance_is_printed() {
    let scene = scene::parse("sc.toml", SLIDER_CRANK).unwrap();
    let r = scene::run(&scene).unwrap();
    let text = r.balancing.unwrap().lines.join("\n");
    assert!(text.contains("reciprocating mass 2.300000000 kg"), "{text}");
    assert!(text.contains("rotating m r 0.060000000 kg m"), "{text}");
    assert!(text.contains("primary unbalance 2300.000000 N"), "{text}");
    assert!(text.contains("secondary 575.000000 N"), "{text}");
    assert!(text.contains("m r = 0.175000000 kg m"), "{text}");
    assert!(
        text.contains("1150.000000 N along the line, 1150.000000 N across"),
        "{text}"
    );
    // An offset guide: the formulas do not apply, and the error says so.
    let offset = SLIDER_CRANK
        .replace("B = [0.5, 0.0]", "B = [0.5, -0.01]")
        .replace("X = [1.0, 0.0]", "X = [1.0, -0.01]\nG = [0.0, -0.01]")
        .replace("ground = [\"O\", \"X\"]", "ground = [\"O\", \"X\", \"G\"]")
        .replace("line = [\"O\", \"X\"]", "line = [\"G\", \"X\"]");
    let e = error(&offset);
    assert!(e.to_string().contains("in-line"), "{e}");
}

/// Runs `mechdiff run SCENE --csv` and parses the CSV back: header and rows of cells.
fn rotor_csv(scene: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let csv = std::env::temp_dir().join(format!(
        "mechdiff-rotor-{}-{}.csv",
        std::process::id(),
        scene.file_stem().unwrap().to_str().unwrap()
    ));
    let out = mechdiff(&[
        "run",
        scene.to_str().unwrap(),
        "--csv",
        csv.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    std::fs::remove_file(&csv).unwrap();
    let mut lines = text
        .lines()
        .map(|l| l.split(',').map(str::to_owned).collect());
    (lines.next().unwrap(), lines.collect())
}

fn cell(header: &[String], row: &[String], name: &str) -> f64 {
    let k = header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("{name}"));
    row[k]
        .parse()
        .unwrap_or_else(|e| panic!("{name} = `{}`: {e}", row[k]))
}

/// The crankshaft's CSV holds the API's values (the same f64: written with the fewest digits
/// that read back exactly) and the couple-plane distance √0.19 m derived by hand in
/// core/tests/balancing_rotor.rs.
#[test]
fn rotor_csv_holds_the_answers_exactly() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/rotor_balancing.toml");
    let (header, rows) = rotor_csv(&path);
    let expected_header = "row,index,plane [mm],mass [kg],radius [mm],m r x [kg m],m r y [kg m],\
        m r [kg m],m r angle [deg],m r d x [kg m^2],m r d y [kg m^2],m r d [kg m^2],\
        m r d angle [deg]";
    assert_eq!(header.join(","), expected_header);
    let kinds: Vec<&str> = rows.iter().map(|r| r[0].as_str()).collect();
    assert_eq!(
        kinds,
        [
            "mass",
            "mass",
            "mass",
            "resultant",
            "static",
            "two_plane",
            "two_plane",
            "couple_plane",
            "couple_plane_gap"
        ]
    );
    let scene = rotor_scene::load(&path).unwrap();
    let a = scene.rotor.answers().unwrap();
    let mm = 1000.0;
    let u = &scene.units;
    let si = |x: f64, d| u.from_si(x, d);
    use mechdiff::scene::units::Dimension::{Angle, Length};
    let c = |row: usize, name: &str| cell(&header, &rows[row], name);
    // Exact (==): the CSV is the API's f64 through the scene's own unit conversion.
    for i in 0..3 {
        assert_eq!(c(i, "m r x [kg m]"), a.polygons.force[i][0]);
        assert_eq!(c(i, "m r y [kg m]"), a.polygons.force[i][1]);
        assert_eq!(c(i, "m r d x [kg m^2]"), a.polygons.couple[i][0]);
        assert_eq!(c(i, "m r d y [kg m^2]"), a.polygons.couple[i][1]);
        let m = scene.rotor.rotor.masses()[i];
        assert_eq!(c(i, "plane [mm]"), si(m.axial, Length));
        // The given angles 0°, 120°, 240° come back from atan2 to 1e-12° (rounding of the
        // degree conversion and of sin/cos, ~1e-14°).
        let back = c(i, "m r angle [deg]");
        let off = (back - 120.0 * i as f64).rem_euclid(360.0);
        assert!(off.min(360.0 - off) < 1e-12, "{back}");
    }
    for (row, correction) in [
        (4, a.static_balance),
        (5, a.two_plane.unwrap().left),
        (6, a.two_plane.unwrap().right),
        (7, a.couple_plane.unwrap().correction),
    ] {
        assert_eq!(c(row, "plane [mm]"), si(correction.axial, Length));
        assert_eq!(c(row, "m r x [kg m]"), correction.vector[0]);
        assert_eq!(c(row, "m r y [kg m]"), correction.vector[1]);
        assert_eq!(c(row, "m r [kg m]"), correction.mass_radius);
        assert_eq!(c(row, "mass [kg]"), correction.mass_radius / 0.1);
        if row > 4 {
            assert_eq!(c(row, "m r angle [deg]"), si(correction.angle, Angle));
        }
    }
    // The static correction is rounding noise (the cranks are in static balance): its angle
    // is left empty, as "none needed" is printed.
    assert_eq!(
        rows[4][header.iter().position(|h| h == "m r angle [deg]").unwrap()],
        ""
    );
    // √0.19 m from the reference plane (1e-12 mm: a few roundings of 436 mm).
    assert!((c(7, "plane [mm]") - 0.19f64.sqrt() * mm).abs() < 1e-12);
    // m r = 0.075 kg m, the given crank (1e-16: a hypot of a rescaled vector).
    assert!((c(7, "m r [kg m]") - 0.075).abs() <= 1e-16);
    // Two-plane corrections cancel the couple about −400 mm: U_R·800 mm = −Σ Uᵢ (zᵢ + 400 mm).
    let right = [c(6, "m r x [kg m]"), c(6, "m r y [kg m]")];
    let gap = a.resultant[0];
    // Σ Uᵢ zᵢ by hand: 0.075·0.3·(1, 0) + 0.075·(−0.2)·(−1/2, −√3/2) = (0.03, 0.015·√3/2).
    let couple = [
        0.075 * 0.3 + 0.075 * 0.2 * 0.5,
        0.075 * 0.2 * 3f64.sqrt() / 2.0,
    ];
    let about_left = [couple[0] + 0.4 * gap[0], couple[1] + 0.4 * gap[1]];
    // 1e-15 kg m: terms of 0.02 kg m², divided by 0.8 m, a few roundings.
    assert!((right[0] + about_left[0] / 0.8).abs() < 1e-15, "{right:?}");
    assert!((right[1] + about_left[1] / 0.8).abs() < 1e-15, "{right:?}");
}

/// Reference 002's static example as a rotor-only scene: the CSV's static correction is
/// mr4 = 0.04709564735726647 kg m at 266.3477772196937° (values in core/tests/balancing_rotor.rs).
#[test]
fn rotor_csv_static_example_of_reference_002() {
    let path = std::env::temp_dir().join(format!("mechdiff-static-{}.toml", std::process::id()));
    std::fs::write(
        &path,
        "title = \"static\"\n[units]\nangle = \"deg\"\n[rotor]\nmasses = [\n  \
         { mass = 1, radius = 0.003, angle = 0, plane = 0 },\n  \
         { mass = 1, radius = 0.0470, angle = 90, plane = 0.1 },\n]\n",
    )
    .unwrap();
    let check = mechdiff(&["check", path.to_str().unwrap()]);
    assert!(
        check.status.success(),
        "{}",
        String::from_utf8_lossy(&check.stderr)
    );
    let (header, rows) = rotor_csv(&path);
    std::fs::remove_file(&path).unwrap();
    let row = rows.iter().find(|r| r[0] == "static").unwrap();
    // 1e-12 kg m and 1e-9°: the reference's own rounding (its 13 digits), as in balancing_rotor.rs.
    assert!((cell(&header, row, "m r [kg m]") - 0.04709564735726647).abs() <= 1e-12);
    let theta = cell(&header, row, "m r angle [deg]").rem_euclid(360.0);
    assert!((theta - 266.3477772196937).abs() <= 1e-9, "{theta}");
}

/// Options a rotor or cam scene cannot honour are refused by name, never silently ignored:
/// `--jsonl` (a rotor has no drive positions), `--set` and `--sweep` (only linkages have
/// `[parameters]`).
#[test]
fn options_a_scene_kind_cannot_honour_are_refused() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let rotor = root.join("scenes/rotor_balancing.toml");
    let cam = root.join("scenes/cams/rise_dwell_return_dwell.toml");
    let json = std::env::temp_dir().join(format!("mechdiff-refused-{}.json", std::process::id()));
    for (args, option) in [
        (
            vec![
                "run",
                rotor.to_str().unwrap(),
                "--jsonl",
                json.to_str().unwrap(),
            ],
            "--jsonl",
        ),
        (
            vec!["run", rotor.to_str().unwrap(), "--set", "m=1"],
            "--set",
        ),
        (
            vec!["check", cam.to_str().unwrap(), "--set", "m=1"],
            "--set",
        ),
    ] {
        let out = mechdiff(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} was accepted");
        assert!(
            stderr.contains(&format!("{option} does not apply")),
            "{stderr}"
        );
        assert!(!json.exists(), "a refused run wrote {}", json.display());
    }
}

/// Issue 22: rotor inputs are range-checked like every other number (finite, positive where
/// physical, bounded so every answer stays finite), with located errors; quoted formulas are
/// accepted; `--json` holds the CSV's answers.
mod rotor_inputs {
    use super::*;

    const ROTOR: &str = "title = \"r\"\n[units]\nlength = \"mm\"\nangle = \"deg\"\n[rotor]\n\
        masses = [\n  { mass = 0.5, radius = 150, angle = 0, plane = 300 },\n  \
        { mass = 0.5, radius = 150, angle = 120, plane = 0 },\n]\nplanes = [-400, 400]\n\
        correction_radius = 100\ncouple_mass_radius = 0.075\n";

    fn refused(from: &str, to: &str) -> String {
        let text = ROTOR.replacen(from, to, 1);
        assert_ne!(text, ROTOR);
        // As `check` and `run` read it: the answers computed too.
        match rotor_scene::parse("r.toml", &text).and_then(|r| r.rotor.answers()) {
            Ok(_) => panic!("accepted: {to}"),
            Err(e) => e.to_string(),
        }
    }

    /// The line and column of `needle` in `ROTOR` (1-based), as errors print them.
    fn at(needle: &str) -> String {
        let line = ROTOR.lines().position(|l| l.contains(needle)).unwrap();
        let column = ROTOR.lines().nth(line).unwrap().find(needle).unwrap();
        format!("r.toml:{}:{}:", line + 1, column + 1)
    }

    #[test]
    fn out_of_range_rotor_numbers_are_refused_where_written() {
        // The issue's example: `mass = 1e308` printed "plane at inf mm", exit 0.
        let e = refused(
            "mass = 0.5, radius = 150, angle = 0",
            "mass = 1e308, radius = 150, angle = 0",
        );
        assert!(e.starts_with(&at("0.5, radius = 150, angle = 0")), "{e}");
        assert!(e.contains("≤ 1e9 kg"), "{e}");
        for bad in ["0", "-1", "nan", "inf", "\"1/0\""] {
            let e = refused(
                "mass = 0.5, radius = 150, angle = 0",
                &format!("mass = {bad}, radius = 150, angle = 0"),
            );
            assert!(
                e.starts_with(&at("0.5, radius = 150, angle = 0")),
                "{bad}: {e}"
            );
        }
        let e = refused("radius = 150, angle = 0", "radius = 1e300, angle = 0");
        assert!(e.contains("at most 1000000000000 mm"), "{e}");
        let e = refused("planes = [-400, 400]", "planes = [-400, 1e300]");
        assert!(e.starts_with(&at("[-400, 400]")), "{e}");
        let e = refused("couple_mass_radius = 0.075", "couple_mass_radius = 1e300");
        assert!(e.contains("1e18 kg m"), "{e}");
        // Each input in range, the answers not: planes a hair apart overflow the correction.
        let e = refused("planes = [-400, 400]", "planes = [0, 1e-320]");
        assert!(
            e.starts_with(&at("[-400, 400]")) && e.contains("coincide"),
            "{e}"
        );
        assert!(e.len() < 300, "no number with 300 digits: {e}");
        let e = refused("correction_radius = 100", "correction_radius = 1e-320");
        assert!(e.contains("overflow"), "{e}");
    }

    /// Quoted formulas give the same rotor as the numbers (bit for bit).
    #[test]
    fn formulas_are_accepted_in_rotor() {
        let text = ROTOR
            .replace(
                "mass = 0.5, radius = 150",
                "mass = \"1/2\", radius = \"100 + 50\"",
            )
            .replace("planes = [-400, 400]", "planes = [\"-2*200\", \"2*200\"]")
            .replace(
                "couple_mass_radius = 0.075",
                "couple_mass_radius = \"0.15/2\"",
            );
        let a = rotor_scene::parse("r.toml", ROTOR).unwrap();
        let b = rotor_scene::parse("r.toml", &text).unwrap();
        assert_eq!(a.rotor, b.rotor);
    }

    /// `mechdiff run rotor.toml --json FILE`: one object per CSV row, keyed by the CSV's
    /// headers, the same numbers (the same shortest f64 text, read back).
    #[test]
    fn run_writes_the_rotor_answers_as_json() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/rotor_balancing.toml");
        let (header, rows) = rotor_csv(&path);
        let json = std::env::temp_dir().join(format!("mechdiff-rotor-{}.json", std::process::id()));
        let out = mechdiff(&[
            "run",
            path.to_str().unwrap(),
            "--json",
            json.to_str().unwrap(),
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let value: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        std::fs::remove_file(&json).ok();
        let objects = value["rows"].as_array().unwrap();
        assert_eq!(objects.len(), rows.len());
        for (object, row) in objects.iter().zip(&rows) {
            for (key, cell) in header.iter().zip(row) {
                match cell.parse::<f64>() {
                    Ok(x) => assert_eq!(object[key].as_f64(), Some(x), "{key}"),
                    Err(_) if cell.is_empty() => assert!(object[key].is_null(), "{key}"),
                    Err(_) => assert_eq!(object[key].as_str(), Some(cell.as_str()), "{key}"),
                }
            }
        }
    }
}

/// Run once: a scene with a kinematic output (its dead positions searched), `[[dynamics]]`
/// and counterweights solves each of its 72 drive positions once — the sweep's tracker moves
/// 72 times and `[[dynamics]]` and the counterweights read those poses (the dynamics' trace
/// counts 72 evaluated positions, the balancing 72 before and 72 after, none of them with a
/// tracker of its own) — while the dead-position search's own solves are counted apart.
/// Counts are exact (integers).
#[test]
fn a_scene_with_outputs_dynamics_and_balancing_solves_each_position_once() {
    let path = common::scene_path("whitworth_balancing.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let text = format!(
        "{text}\n[[output]]\nname = \"x_C\"\nslider = \"ram_guide\"\n\
         quantities = [\"position\", \"acceleration\"]\ndead_positions = true\n"
    );
    let r = common::run_text("whitworth_balancing.toml", &text);
    let n = 72;
    assert_eq!(r.rows.len(), n);
    let s = r.stats;
    assert_eq!(
        (s.sweep.rows, s.sweep.solves, s.sweep.program_steps),
        (n, n, 0)
    );
    let trace = &r.dynamics.as_ref().unwrap().run.trace;
    assert_eq!((trace.positions, trace.derivatives), (n, n));
    let linkage = r.balancing.as_ref().unwrap().linkage.as_ref().unwrap();
    assert_eq!((linkage.before.phi.len(), linkage.after.phi.len()), (n, n));
    // The dead positions of x_C (the ram's ends) were searched by solves of their own,
    // counted; no `[sweep] of`.
    assert_eq!(r.dead_positions[0].positions.len(), 2);
    assert!(s.dead_positions > 0, "{s:?}");
    assert_eq!((s.sweep_of, s.limit_walks), (0, 1));
}

/// A drive speed whose square underflows (1e-300 rad/s: ω² = 0 in f64) leaves the shaking
/// force zero at every position, so the counterweights are not determined: `check` refuses
/// it before solving, as `run` does, naming `[balancing]` (found by tests/fuzz_scenes.rs,
/// where `check` passed it and `run` refused it only after the sweep).
#[test]
fn a_drive_speed_whose_square_underflows_is_refused_before_solving() {
    let path = format!(
        "{}/scenes/whitworth_balancing.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).unwrap();
    let text = text.replace("speed = 100 ", "speed = 1e-300 ");
    assert!(
        text.contains("speed = 1e-300"),
        "the scene's speed line moved"
    );
    let scene = scene::parse(&path, &text).unwrap();
    let checked = scene::check(&scene).expect_err("check refuses an underflowing speed");
    let ran = scene::run(&scene).expect_err("run refuses it too");
    for e in [checked, ran] {
        assert!(!e.is_found_by_solving(), "{e}");
        assert!(e.to_string().contains("underflows to zero"), "{e}");
    }
}
