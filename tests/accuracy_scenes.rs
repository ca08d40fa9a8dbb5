//! Issue 13, the accuracy report on scenes: the reference (the solver's closed forms
//! evaluated in `Dual3<DoubleDouble>`) checked against an independent 256-bit one; the
//! double-double Newton reference of a loop without closed forms checked against the closed
//! forms; every scene of `scenes/` (all folders) run by the command; every exact method
//! within its bound; cam joints not counted against finite differences.

use std::path::Path;

use crate::common;

use mechdiff::accuracy::reference::Formulas;
use mechdiff::accuracy::{Timing, scene as scene_case};
use mechdiff::scene;
use mechdiff_core::symbolic::Graph;

fn load(relative: &str) -> scene::Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(relative);
    scene::load(&path).unwrap()
}

/// The double-double reference of tests/data/accuracy/whitworth_binary.toml (every length
/// and the drive's zero exact in binary, so the model's parameters are exactly l0 = 0.5,
/// l1 = 0.25, h = 1) against the closed formula ψ = atan2(l1 sin φ, l0 + l1 cos φ),
/// y_C = h tan ψ, differentiated by the symbolic engine and evaluated at 256 bits: a
/// different formula (the solver's slotted-rocker closed form is written with complex
/// products, not this quotient), different differentiation (symbolic against forward mode)
/// and different precision. Agreement to 1e-28 of the output's scale: double-double keeps
/// ~2⁻¹⁰⁴ ≈ 5e-32 per operation, and a few hundred well-conditioned operations (λ = 0.5:
/// |ψ′| ≤ 1, reached at φ = 180°) stay well below that; an `f64` evaluation would miss by
/// ~1e-16.
#[test]
fn scene_reference_agrees_with_the_256_bit_formula() {
    let scene = load("tests/data/accuracy/whitworth_binary.toml");
    let mechanism = scene::build::mechanism(&scene).unwrap();
    let case = scene_case::case(&scene, &mechanism).unwrap();
    let mut graph = Graph::new();
    let psi = graph
        .parse_infix("atan2(l1*sin(phi), l0 + l1*cos(phi))")
        .unwrap();
    let y = graph
        .parse_infix("h*l1*sin(phi)/(l0 + l1*cos(phi))")
        .unwrap();
    let formulas = Formulas::new(graph, &[psi, y], "phi", &["l0", "l1", "h"]);
    let scales = case.scales();
    for (i, &phi) in case.positions.iter().enumerate() {
        let (expected, _) = formulas.reference(phi, &[0.5, 0.25, 1.0]).unwrap();
        for (o, outputs) in expected.iter().enumerate() {
            for k in 0..4 {
                let got = case.reference[i][o][k];
                let e = outputs[k];
                // (got − e) in double-double, relative to the output's scale.
                let difference = ((got.hi - e.hi) + (got.lo - e.lo)).abs() / scales[o][k];
                assert!(
                    difference <= 1e-28,
                    "{} order {k} at φ = {phi}: {difference:e}",
                    case.outputs[o]
                );
            }
        }
    }
    assert_eq!(case.positions.len(), 36, "0°, 10°, …, 350°");
}

/// Every exact method of the report on the example scenes, four-bar and offset
/// slider-crank: no failure, and the scaled error of value, ′, ″, ‴ at most 1e-14. Measured
/// (BENCHMARKS.md): at most 1.4e-15 (6 ε; no toggle near these sweeps); 1e-14 leaves a
/// factor 7 for other platforms' libm, and is 1e4 below the best central difference
/// (1.6e-10), so a derivative that lost its exactness cannot pass.
#[test]
fn exact_methods_on_the_example_scenes_stay_within_1e_14() {
    for file in ["scenes/four_bar.toml", "scenes/slider_crank.toml"] {
        let scene = load(file);
        let mechanism = scene::build::mechanism(&scene).unwrap();
        let report = scene_case::case(&scene, &mechanism)
            .unwrap()
            .measure(&Timing::quick())
            .unwrap();
        let exact: Vec<_> = report
            .measurements
            .iter()
            .filter(|m| m.name.starts_with("geometry"))
            .collect();
        assert_eq!(exact.len(), 2, "{file}: both geometry paths are reported");
        for m in exact {
            assert!(m.failure.is_none(), "{file}: {}: {:?}", m.name, m.failure);
            for k in 0..4 {
                assert!(
                    m.max[k] <= 1e-14,
                    "{file}: {} order {k}: {:e}",
                    m.name,
                    m.max[k]
                );
            }
        }
        // Finite differences are reported too, and are not exact: the best central ′ is
        // above 1e-12 (truncation and rounding, ~1e-10 measured).
        let central = report
            .measurements
            .iter()
            .find(|m| m.name.starts_with("central") && m.name.contains("best ′"))
            .expect("central differences reported");
        assert!(central.max[1] > 1e-12, "{file}: {:e}", central.max[1]);
    }
}

/// A triad (a ternary link held by three binary links: a class-III Assur group, four links
/// in one loop) matches no closed form: its loop is solved by Newton only.
fn triad() -> String {
    common::triad(
        r#"
[sweep]
from = 60
to = 90
step = 10
[[output]]
point = "C"
quantities = ["position"]
"#,
    )
}

/// The triad's report: the reference is the double-double Newton solve (the note names the
/// loop's joints), and both geometry paths (the crank's loop in closed form, the triad by
/// Newton; and everything by Newton) are within 1e-12 scaled of it over 60°–90°, with no
/// failure. 1e-12: the sweep ends 1.2° before the triad's limit position (91.17°), where
/// Φ_q is ill-conditioned (measured 5e-13 for ′–‴ at 90°, 1.6e-15 for the value); a
/// derivative that lost its exactness would be off by the best central difference's 3e-6.
#[test]
fn a_loop_solved_by_newton_only_gets_a_double_double_newton_reference() {
    let scene = scene::parse("triad.toml", &triad()).unwrap();
    let mechanism = scene::build::mechanism(&scene).unwrap();
    let case = scene_case::case(&scene, &mechanism).unwrap();
    let note = case.notes.join("\n");
    for part in ["Newton", "double-double", "A, B, C, D, G2, G3"] {
        assert!(note.contains(part), "`{part}` missing from: {note}");
    }
    assert_eq!(case.positions.len(), 4, "60°, 70°, 80°, 90°");
    let report = case.measure(&Timing::quick()).unwrap();
    let exact: Vec<_> = report
        .measurements
        .iter()
        .filter(|m| m.is_exact())
        .collect();
    assert_eq!(
        exact.len(),
        2,
        "the mixed and the Newton path; no traced form"
    );
    for m in exact {
        assert!(m.failure.is_none(), "{}: {:?}", m.name, m.failure);
        assert!(m.max.iter().all(|&e| e <= 1e-12), "{}: {:?}", m.name, m.max);
    }
}

/// The double-double Newton solve against the closed forms in double-double, on the
/// Whitworth of tests/data/accuracy/whitworth_binary.toml (every loop in closed form, so
/// both exist; every length exact in binary, so the constraint equations and the closed
/// forms hold the very same model — with lengths rounded to `f64` the two models differ by
/// ~1e-17 relative): the pose jets q, q′, q″, q‴ agree to 1e-28 of each order's largest
/// coordinate at 0°, 50°, …, 300°. Two different algorithms (a Newton iteration on Φ against
/// explicit formulas) in the same precision: each keeps ~2⁻¹⁰⁴ ≈ 5e-32 per operation, and
/// this machine (λ = 0.5) is far from singular (cond(Φ_q) < 1e2), so 1e-28 leaves a margin
/// of 1e2 over that; an `f64` solve would miss by 1e-16.
#[test]
fn double_double_newton_agrees_with_the_closed_forms() {
    use mechdiff::accuracy::DoubleDouble;
    use mechdiff::accuracy::extended_newton::{self, Jet};
    use mechdiff_core::geometry::{Equations, Solver};

    let scene = load("tests/data/accuracy/whitworth_binary.toml");
    let mechanism = scene::build::mechanism(&scene).unwrap();
    let equations = Equations::new(&mechanism);
    let mut tracker = Solver::default().track(&mechanism).unwrap();
    let (one, zero) = (DoubleDouble::new(1.0), DoubleDouble::new(0.0));
    for k in 0..7 {
        let phi = (50.0 * f64::from(k)).to_radians();
        tracker.move_to(phi).unwrap();
        let x = Jet::new(DoubleDouble::new(phi), one, zero, zero);
        let closed = tracker.closed_form_pose(x).unwrap();
        let start: Vec<Jet> = tracker
            .kinematics::<3>()
            .unwrap()
            .coordinates
            .iter()
            .map(|j| extended_newton::lift(j.value, j.derivatives))
            .collect();
        let newton = extended_newton::solve(&equations, &start, x).unwrap();
        let parts = |q: &Jet| [q.re, q.v1, q.v2, q.v3];
        for order in 0..4 {
            let scale = closed
                .iter()
                .map(|q| parts(q)[order].hi.abs())
                .fold(0.0, f64::max);
            for (a, b) in closed.iter().zip(&newton) {
                let (a, b) = (parts(a)[order], parts(b)[order]);
                let difference = ((a.hi - b.hi) + (a.lo - b.lo)).abs();
                assert!(
                    difference <= 1e-28 * scale,
                    "φ = {phi}, order {order}: {difference:e} of {scale:e}"
                );
            }
        }
    }
}

/// A scene swept by an output's values (`[sweep] of`, the rack-driven slotted link of
/// reference 001 at θ3 = 63°) is measured at the drive positions `mechdiff run` solves
/// for: both geometry paths without failure, within 1e-13 (measured 2.1e-14 in ‴ of the
/// closed-form path: with one position the "scaled" error is relative to each output's own
/// value there, and the eleven outputs include small ones).
#[test]
fn a_sweep_of_an_output_is_measured_at_the_solved_drive_positions() {
    let scene = load("scenes/rack_slotted_link.toml");
    let mechanism = scene::build::mechanism(&scene).unwrap();
    let report = scene_case::case(&scene, &mechanism)
        .unwrap()
        .measure(&Timing::quick())
        .unwrap();
    for m in report
        .measurements
        .iter()
        .filter(|m| m.name.starts_with("geometry"))
    {
        assert!(m.failure.is_none(), "{}: {:?}", m.name, m.failure);
        assert!(m.max.iter().all(|&e| e <= 1e-13), "{}: {:?}", m.name, m.max);
    }
}

/// Every scene file under `scenes/`, in every folder, sorted.
fn every_scene() -> Vec<std::path::PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(&path, out);
            } else if path.extension().is_some_and(|e| e == "toml") {
                out.push(path);
            }
        }
    }
    let mut out = Vec::new();
    walk(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes"),
        &mut out,
    );
    out.sort();
    out
}

/// The rows of the method table of a report printed by `mechdiff accuracy`: from the
/// header line `method …` to the first empty line.
fn method_rows(text: &str) -> Vec<&str> {
    text.lines()
        .skip_while(|l| !l.starts_with("method "))
        .skip(1)
        .take_while(|l| !l.trim().is_empty())
        .collect()
}

/// `mechdiff accuracy` runs on every scene of `scenes/` — mechanism, cam-driven, cam, rotor,
/// formula and hard-case scenes — at 5 positions (`--positions 5`, one timed repeat): it
/// succeeds, and no method returns NaN or ∞ silently: every row of the method table that
/// shows one is named by a `FAILED:` line saying where and why. (The step-scan table may
/// show ∞ for a step whose stencil leaves the mechanism's range or the function's domain:
/// that is the scan's U-curve, the error of that step, not a method's value.) The rotor's
/// table has no NaN or ∞ at all.
#[test]
fn every_scene_runs_and_names_every_non_finite_value() {
    let scenes = every_scene();
    assert!(scenes.len() >= 30, "{} scenes found", scenes.len());
    for path in scenes {
        let file = path.to_str().unwrap();
        let rotor = scene::kind(&std::fs::read_to_string(&path).unwrap()) == scene::Kind::Rotor;
        let thin = ["--positions", "5"];
        let args = ["accuracy", file, "--repeats", "1"];
        // A rotor has no sweep to thin (the option is refused there).
        let output = common::mechdiff(&[&args[..], if rotor { &[] } else { &thin }].concat());
        let text = String::from_utf8(output.stdout).unwrap();
        let error = String::from_utf8(output.stderr).unwrap();
        assert!(output.status.success(), "{file}: {error}");
        let rows = method_rows(&text);
        if rows.is_empty() {
            assert!(text.contains("no method table"), "{file}:\n{text}");
            assert!(
                !text.contains("NaN") && !text.contains("inf"),
                "{file}:\n{text}"
            );
            continue;
        }
        for row in rows {
            if row.contains("NaN") || row.contains("inf") {
                let name = row.split("  ").next().unwrap().trim_end_matches(" *");
                assert!(
                    text.contains(&format!("FAILED: {name} ")),
                    "{file}: `{name}` shows a non-finite value without a FAILED line:\n{text}"
                );
            }
        }
    }
}

/// The scaled error every exact method of a mechanism, cam-driven or cam scene meets: 1e-12.
/// These cases have no computed condition number (a scene's inputs are its sketch's
/// coordinates), so the bound is a measured one: over the full sweeps of every such scene
/// the exact methods' largest scaled error is 7.7e-14 (2.5 digits lost: the run-time
/// evaluator's ‴ at the start of scenes/rack_slotted_link_travel.toml, where the slotted
/// link is steep; README, `mechdiff accuracy`, gives the command), 8.4e-15 on the others; 1e-12 leaves a
/// factor 13 for other platforms' libm, while a derivative that lost its exactness (the best
/// finite difference's ″ is above 1e-6 on every one of these scenes) fails.
const MEASURED_BOUND: f64 = 1e-12;

/// Every exact method on every scene of `scenes/` outside `scenes/hard/` (whose bounds, and
/// the methods that miss them by design, are asserted case by case in tests/hard_cases.rs),
/// at 5 positions, meets its bound and never fails:
/// - formula scenes: the conditioned bound 16 ε (condition/scale + 1), the condition number
///   Σ|x ∂f/∂x| computed from the 256-bit reference ([`Case::bounds`]);
/// - mechanism, cam-driven and cam scenes: [`MEASURED_BOUND`]; closed-form scenes without a
///   cam also have the symbolic run-time evaluator's row;
/// - the rotor: every answer that is not rounding noise within 1e-14 (relative, rad for
///   angles; measured ≤ 3e-16), and the statically balanced crankshaft's static correction
///   flagged as noise.
#[test]
fn exact_methods_on_every_scene_meet_their_bound() {
    use mechdiff::accuracy::{cam, formula, rotor};
    for path in every_scene() {
        let file = path.to_str().unwrap();
        if file.contains("/scenes/hard/") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        let report = match scene::kind(&text) {
            scene::Kind::Formula => {
                let parsed = formula::parse(&text, file).unwrap();
                let mut case = formula::case(&parsed, file).unwrap().thinned(5).unwrap();
                let violations = case.bound_violations().unwrap();
                assert!(violations.is_empty(), "{file}: {violations:?}");
                continue;
            }
            scene::Kind::Rotor => {
                let parsed = scene::balancing::rotor_scene::load(&path).unwrap();
                let report = rotor::report(&parsed).unwrap();
                for answer in &report.answers {
                    assert!(
                        answer.negligible || answer.error <= 1e-14,
                        "{file}: {answer:?}"
                    );
                }
                assert!(report.answers[0].negligible, "{file}: static balance holds");
                continue;
            }
            scene::Kind::Cam => {
                let parsed = scene::cam::parse(file, &text).unwrap();
                cam::case(&parsed, Some(5))
                    .unwrap()
                    .measure(&Timing::quick())
                    .unwrap()
            }
            scene::Kind::Linkage => {
                let mut parsed = scene::parse(file, &text).unwrap();
                scene_case::default_outputs(&mut parsed);
                let mechanism = scene::build::mechanism(&parsed).unwrap();
                let report = scene_case::case_at(&parsed, &mechanism, Some(5))
                    .unwrap()
                    .measure(&Timing::quick())
                    .unwrap();
                if parsed.drive.cam.is_none() {
                    assert!(
                        report
                            .measurements
                            .iter()
                            .any(|m| m.name == mechdiff::accuracy::evaluator::NAME),
                        "{file}: every loop has a closed form: the evaluator is measured"
                    );
                }
                report
            }
        };
        let exact: Vec<_> = report
            .measurements
            .iter()
            .filter(|m| m.is_exact())
            .collect();
        assert!(!exact.is_empty(), "{file}");
        for m in exact {
            assert!(m.failure.is_none(), "{file}: {}: {:?}", m.name, m.failure);
            for k in 0..=m.order {
                assert!(
                    m.max[k] <= MEASURED_BOUND,
                    "{file}: {} order {k}: {:e}",
                    m.name,
                    m.max[k]
                );
            }
        }
    }
}

/// The parabolic cam of reference 002: s″ jumps at 90° (the break of the rise) and 270°.
/// There the reference and every exact method take the right-hand limit — the exact
/// methods' error stays at rounding (≤ 1e-15 scaled, a few ε) — and the central
/// difference's ″ and ‴ are not counted (NaN in the per-position errors: its stencil
/// straddles the jump, the cam's and not the method's), while its value and ′ are counted.
#[test]
fn a_cam_jump_is_not_counted_against_finite_differences() {
    use mechdiff::accuracy::{Kind, cam, differences};
    let parsed = scene::cam::load(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cams/reference_002_parabolic.toml"),
    )
    .unwrap();
    let case = cam::case(&parsed, None).unwrap();
    let at = |degrees: f64| {
        case.positions
            .iter()
            .position(|p| (p.to_degrees() - degrees).abs() < 1e-9)
            .unwrap()
    };
    let (i90, i270) = (at(90.0), at(270.0));
    assert_eq!(case.jumps[i90], Some(2));
    assert_eq!(case.jumps[i270], Some(2));
    assert_eq!(case.jumps.iter().filter(|j| j.is_some()).count(), 2);
    let program = &parsed.mechanism.program;
    let right = program.svaj(case.positions[i90], mechdiff_core::cams::Side::Right);
    let r = case.reference[i90][0][2];
    assert!(((r.hi - right.d2()) + r.lo).abs() <= 1e-15 * right.d2().abs());
    let scales = case.scales();
    {
        let mut central = differences::method(
            &case.positions_f64,
            differences::Scheme::Central,
            1e-4,
            1,
            String::new(),
        );
        assert!(matches!(central.kind, Kind::Approximate { .. }));
        let (errors, _) = case.errors(&mut central, &scales).unwrap();
        for i in [i90, i270] {
            assert!(errors[i][0].is_finite() && errors[i][1].is_finite());
            assert!(
                errors[i][2].is_nan() && errors[i][3].is_nan(),
                "{:?}",
                errors[i]
            );
        }
    }
    let report = case.measure(&Timing::quick()).unwrap();
    for m in report.measurements.iter().filter(|m| m.is_exact()) {
        assert!(
            m.errors[i90].iter().take(m.order + 1).all(|&e| e <= 1e-15),
            "{}",
            m.name
        );
    }
}
