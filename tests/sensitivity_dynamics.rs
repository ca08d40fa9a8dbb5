//! Issue 14: the exact (dual-number) derivatives of the dynamics columns by a parameter that
//! moves the geometry and the masses with it (a uniform bar's density per length: its mass,
//! centre and moment follow its moving ends), against the Richardson-extrapolated
//! differences of whole runs (`sensitivity::extrapolated`, an independent method) within
//! their own error estimate.

use mechdiff::scene::parameters::Setting;
use mechdiff::sensitivity::{self, Method, Options, Parameter};

const NORTON: &str = include_str!("../scenes/norton_four_bar.toml");

/// Norton's four-bar with uniform bars of 10 kg/m for its three moving links, gravity and
/// the drive torque, the reactions and the kinetic energy as outputs.
fn norton_with_bars() -> String {
    format!(
        "{NORTON}
[masses]
crank = {{ density = 10 }}
coupler = {{ density = 10 }}
rocker = {{ density = 10 }}
[gravity]
g = 9.81
[[dynamics]]
output = \"drive_torque\"
[[dynamics]]
output = \"reactions\"
joints = [\"O2\"]
[[dynamics]]
output = \"kinetic_energy\"
"
    )
}

/// An offset slider-crank whose rod is a uniform bar of `rho` kg/m from A to B (the rod's
/// length `l` moves B, its mass and moment), the crank another of length `r` (its centre
/// given at `[cx, 0.03]`), gravity `gr`,
/// a motor of rotor inertia `J`, a torque load `ml` on the rod and a force `[fx, 0]` at B
/// (which moves with r and l).
const SLIDER_CRANK: &str = r#"
[parameters]
r = 0.1
l = 0.4
rho = 3.0
ml = 2.0
gr = 9.81
J = 0.002
fx = -50
cx = 0.02
[points]
O = [0, 0]
A = { from = "O", length = "r", angle = "pi/3" }
G0 = [0, -0.012]
G1 = [1, -0.012]
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
speed = 30
acceleration = 5
[sweep]
from = 0
to = 6
step = 1
[masses]
crank = { density = 5, center = ["cx", 0.03] }
rod = { density = "rho" }
slider = { mass = 1.5, center = "B" }
[gravity]
g = "gr"
[motor]
rotor_inertia = "J"
ratio = 0.5
[[load]]
link = "rod"
torque = "ml"
[[load]]
link = "slider"
point = "B"
force = ["fx", 0]
[[dynamics]]
output = "drive_torque"
[[dynamics]]
output = "kinetic_energy"
"#;

/// For each parameter of `parameters` (name, value): every dynamics column of `text`
/// (`columns`, by name), exact, against the Richardson-extrapolated differences, within
/// their estimate. Returns the largest |exact − Richardson| relative to the column found.
fn exact_against_richardson(text: &str, parameters: &[(&str, f64)], columns: &[&str]) -> f64 {
    let nominal = mechdiff::scene::run(&mechdiff::scene::parse("t.toml", text).unwrap()).unwrap();
    let mut worst: f64 = 0.0;
    for &(p, value) in parameters {
        let names: Vec<String> = columns.iter().map(|c| format!("d({c})/d({p})")).collect();
        let quoted: Vec<String> = names.iter().map(|n| format!("\"{n}\"")).collect();
        let study_text = format!("{text}\n[sensitivity]\ncolumns = [{}]\n", quoted.join(", "));
        let (_, report, study) =
            sensitivity::run("t.toml", &study_text, &[], &Options::default()).unwrap();
        let study = study.unwrap();
        let parameter = Parameter {
            name: p.to_owned(),
            value,
            tolerance: None,
        };
        let r = sensitivity::extrapolated("t.toml", text, &[], &parameter).unwrap();
        for (c, name) in columns.iter().zip(&names) {
            let d = study.derivatives.iter().find(|d| d.name == *name).unwrap();
            assert_eq!(d.method, Method::Exact, "{name}");
            let exact = report.column(name).unwrap();
            let k = nominal.columns.iter().position(|x| x.name == *c).unwrap();
            let scale = exact.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
            assert!(scale > 0.0, "{name} is 0: not a comparison");
            // The estimate printed for a Richardson column: the largest disagreement of its
            // last two extrapolations (the error of the one before the last, an upper bound
            // of the last one's); plus the rounding of the runs it combines, which the
            // estimate does not see when the column is affine in p: the extrapolation
            // (64·D(h/4) − 20·D(h/2) + D(h))/45 of central differences D with errors
            // ε·|y|/h' sums it to ≈ 6.6·ε·|y|/h, taken as 16·ε·max|y|/h (the runs' own
            // rounding is a few ε of |y| too); plus 1e-12 of the
            // column for the rounding of the exact equilibrium (an LU solve in f64).
            let values = nominal.rows.iter().map(|row| row[k].abs());
            let rounding = 16.0 * f64::EPSILON * values.fold(0.0, f64::max) / r.step.abs();
            let bound = r.disagreement.iter().map(|d| d[k]).fold(0.0, f64::max);
            for (row, e) in exact.iter().enumerate() {
                let diff = (e - r.values[row][k]).abs();
                worst = worst.max(diff / scale);
                assert!(
                    diff <= bound + rounding + 1e-12 * scale,
                    "{name} row {row}: exact {e} vs Richardson {} (estimate {bound:e})",
                    r.values[row][k]
                );
            }
        }
    }
    worst
}

#[test]
fn norton_drive_torque_by_each_length_with_bar_masses_is_exact() {
    let worst = exact_against_richardson(
        &norton_with_bars(),
        &[("a", 0.86), ("b", 1.85), ("c", 0.86), ("d", 2.22)],
        &["M_drive", "Fy_O2", "T"],
    );
    eprintln!("Norton: largest |exact − Richardson| / column = {worst:e}");
}

#[test]
fn a_length_that_moves_a_bar_and_its_mass_and_the_effects_numbers_are_exact() {
    let worst = exact_against_richardson(
        SLIDER_CRANK,
        &[("r", 0.1), ("l", 0.4), ("rho", 3.0)],
        &["M_drive", "M_motor", "T"],
    )
    .max(exact_against_richardson(
        SLIDER_CRANK,
        &[("ml", 2.0), ("gr", 9.81), ("fx", -50.0), ("cx", 0.02)],
        &["M_drive", "M_motor"],
    ));
    eprintln!("slider-crank: largest |exact − Richardson| / column = {worst:e}");
}

#[test]
fn the_motor_torque_by_the_rotor_inertia_is_its_acceleration() {
    // M_motor = J·ω̇_d + (the drive's torque through the gearbox), and only the first term
    // has J: d(M_motor)/dJ = ω̇_d = α/ratio = 5/0.5 = 10 at every position. 1e-13 relative:
    // exact in f64. (Richardson's differences are off by ε·|M_motor|/h ≈ 1e-11 here.)
    let text = format!("{SLIDER_CRANK}\n[sensitivity]\ncolumns = [\"d(M_motor)/d(J)\"]\n");
    let (_, report, study) = sensitivity::run("t.toml", &text, &[], &Options::default()).unwrap();
    assert!(study.unwrap().derivatives.iter().all(|d| d.is_exact()));
    for (row, v) in report.column("d(M_motor)/d(J)").unwrap().iter().enumerate() {
        assert!((v - 10.0).abs() <= 1e-13 * 10.0, "row {row}: {v}");
    }
}

#[test]
fn norton_drive_torque_by_the_crank_length_converges_with_central_differences() {
    // d(M_drive)/d(a) with the bars' masses following a, against central differences of the
    // scene's own runs at a ± h: truncation O(h²) (measured 2e-7 of the column at h = 1e-4,
    // large near the end of the sweep, 16° before the crank's limit), rounding O(ε/h). The
    // error must shrink ≥ 30× (100× for O(h²)) from h = 1e-4 to 1e-5 and end below 1e-8 of
    // the column: the agreement is the derivative's, not a coincidence.
    let text = norton_with_bars();
    let study = format!("{text}\n[sensitivity]\ncolumns = [\"d(M_drive)/d(a)\"]\n");
    let (_, report, s) = sensitivity::run("t.toml", &study, &[], &Options::default()).unwrap();
    assert!(s.unwrap().derivatives[0].is_exact());
    let exact = report.column("d(M_drive)/d(a)").unwrap();
    let drive_torque = |a: f64| {
        let set: Setting = format!("a={a:.17e}").parse().unwrap();
        let scene = mechdiff::scene::parse_with("t.toml", &text, &[set]).unwrap();
        mechdiff::scene::run(&scene)
            .unwrap()
            .column("M_drive")
            .unwrap()
    };
    let error = |h: f64| {
        let (up, down) = (drive_torque(0.86 + h), drive_torque(0.86 - h));
        (exact.iter().zip(up.iter().zip(&down)))
            .map(|(e, (u, d))| (e - (u - d) / (2.0 * h)).abs())
            .fold(0.0, f64::max)
    };
    let scale = exact.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
    let (coarse, fine) = (error(1e-4), error(1e-5));
    eprintln!(
        "Norton d(M_drive)/d(a): differences off by {coarse:e} (h = 1e-4), {fine:e} (h = 1e-5) \
         of {scale}"
    );
    assert!(fine <= 1e-8 * scale, "{fine:e} of {scale}");
    assert!(
        fine <= coarse / 30.0,
        "no O(h²) convergence: {coarse:e} → {fine:e}"
    );
}
