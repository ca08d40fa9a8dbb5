//! `mechdiff accuracy whitworth`: the reference against the published 30-digit values, the
//! exact methods against the reference, the finite-difference step scan, the plot.

use mechdiff::accuracy::{Timing, plot, whitworth};
use mechdiff::mechanisms::Whitworth;
use mechdiff::mechanisms::whitworth::Parameters;
use mechdiff::pictures::raster;
use mechdiff_core::symbolic::BigReal;
use serde_json::Value;

/// The report's reference formulas, evaluated at the decimal inputs of the 30-digit table
/// (l0 = 0.4 m, l1 = 0.15 m, h = 0.65 m, φ to 30 digits), reproduce its 38 rows of ψ, x_C and
/// their first three derivatives to 1e-25 relative (absolute where the value is below 1e-25:
/// ψ′ at the dead positions is zero up to the rounding of φ). The values were computed in
/// 40-digit arithmetic and given to 30 digits; the evaluation runs at 256 bits.
#[test]
fn reference_matches_the_30_digit_values() {
    let data: Value =
        serde_json::from_str(include_str!("data/whitworth_sweep_30digits.json")).unwrap();
    let rows = data["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 38);
    let formulas = whitworth::formulas();
    let big = |s: &str| BigReal::parse(s, 256).unwrap();
    let zero = big("0");
    let keys = [
        ["psi_rad", "psi_p", "psi_pp", "psi_ppp"],
        ["x_C_m", "x_C_p_m", "x_C_pp_m", "x_C_ppp_m"],
    ];
    for row in rows {
        let phi = big(row["phi_rad"].as_str().unwrap());
        let values = formulas
            .evaluate_big(&phi, &[big("0.4"), big("0.15"), big("0.65")])
            .unwrap();
        for (output, keys) in values.iter().zip(keys) {
            for (value, key) in output.iter().zip(keys) {
                let want = big(row[key].as_str().unwrap());
                let error = if want.to_f64().abs() < 1e-25 {
                    value.relative_difference(&zero)
                } else {
                    value.relative_difference(&want)
                };
                assert!(error <= 1e-25, "{key} at φ = {}: {error:e}", row["phi_deg"]);
            }
        }
    }
}

/// Every exact method (hand-derived, generated, Dual1/2/3, HyperDual, both geometry paths)
/// is within 1e-15 of the reference in scaled error at every order it computes, and none
/// returns NaN or ∞: they are exact up to a few roundings (2.2e-16 each) on this
/// well-conditioned machine (λ = 0.375).
#[test]
fn exact_methods_are_within_1e_15_scaled() {
    let shaper = Whitworth::reference();
    let linkage = whitworth::linkage(&shaper).unwrap();
    let report = whitworth::case(&shaper, &linkage)
        .unwrap()
        .measure(&Timing::quick())
        .unwrap();
    report.check_finite().unwrap();
    let exact: Vec<_> = report
        .measurements
        .iter()
        .filter(|m| m.is_exact())
        .collect();
    assert_eq!(exact.len(), 8, "every exact method is in the report");
    for m in exact {
        for k in 0..=m.order {
            // 1e-15 scaled (≈ 4.5 ε) for every exact method, the Newton path included: it
            // measured 2.1e-15 (′) and 7.3e-15 (″) while q′, q″ were solved with Φ_q at the
            // pose before the polishing Newton step (CHANGELOG); 5.9e-16 at most since.
            let bound = 1e-15;
            assert!(m.max[k] <= bound, "{} order {k}: {:e}", m.name, m.max[k]);
        }
    }
}

/// Central differences: the error against h is U-shaped. For each order its minimum is
/// inside the scanned range (not at either end), and at both ends of the range the error is
/// at least 100 times the minimum (truncation ∝ h² at 1e-1, rounding ∝ ε/hⁿ at 1e-10).
/// The minimum of ′ lies between 1e-7 and 1e-4 rad: (3ε/|x‴|)^(1/3) ≈ 1e-5 for an
/// O(1) function.
#[test]
fn central_differences_have_a_u_shaped_error_with_an_interior_minimum() {
    let shaper = Whitworth::reference();
    let linkage = whitworth::linkage(&shaper).unwrap();
    let report = whitworth::case(&shaper, &linkage)
        .unwrap()
        .measure(&Timing::quick())
        .unwrap();
    let central = &report.scans[0];
    assert_eq!(central.scheme.name(), "central");
    let last = central.steps.len() - 1;
    for k in 0..3 {
        let (h, best) = central.best[k];
        let j = central.steps.iter().position(|&s| s == h).unwrap();
        assert!(
            j > 0 && j < last,
            "order {}: minimum at the end, h = {h}",
            k + 1
        );
        assert!(central.errors[0][k] >= 100.0 * best, "order {}", k + 1);
        assert!(central.errors[last][k] >= 100.0 * best, "order {}", k + 1);
    }
    assert!((1e-7..=1e-4).contains(&central.best[0].0));
}

/// Near λ → 1 the machine is ill-conditioned; the exact methods still meet the bound
/// 16 ε (condition / scale + 1) at every position, output and order, with the condition
/// number Σ|x ∂f/∂x| computed from the reference formulas — all of them at λ = 0.9 and
/// 0.99, and the generated code and every dual-number method at λ = 0.999999. There, three
/// do not (measured; stated so that a change either way fails):
/// - the source's hand formulas (1.35), (1.41): 1 − 2λ cos φ + λ² = (1 − λ)² + 2λ(1 − cos φ)
///   cancels at φ = 0 (3113 times the bound for ψ′, 890 for x_C″), so below 1e4 times;
/// - the solver's closed form at the second dead position φ = 2π − acos λ: 3.5 to 7 times
///   the bound for ′, ″, ‴, so below 10 times;
/// - the solver's Newton path stops before the first dead position (next test).
#[test]
fn exact_methods_meet_the_conditioned_bound_as_lambda_tends_to_one() {
    for lambda in [0.9, 0.99, 0.999999] {
        let parameters = Parameters {
            l1: lambda * 0.4,
            ..Parameters::reference()
        };
        let shaper = Whitworth::new(parameters).unwrap();
        let linkage = whitworth::linkage(&shaper).unwrap();
        let mut case = whitworth::case(&shaper, &linkage).unwrap();
        for v in case.bound_violations().unwrap() {
            let allowed = match v.method.as_str() {
                _ if lambda < 0.999 => 1.0,
                "hand-derived" => 1e4,
                "geometry closed form" => 10.0,
                "geometry Newton + implicit" => f64::INFINITY,
                _ => 1.0,
            };
            assert!(
                v.error <= allowed * v.bound,
                "λ = {lambda}: {allowed} × bound: {v:?}"
            );
        }
    }
}

/// At λ = 0.999999 the Newton path reports, with a typed error, that it cannot reach the
/// dead position φ = acos λ ≈ 1.4e-3 rad (the solver's tolerance is not met so close to the
/// singular pose, residual ~3e-13): the report records it as that method's failure at that
/// position and does not time it; it never returns a silent NaN.
#[test]
fn newton_failure_near_the_pivot_is_reported_with_its_position() {
    let parameters = Parameters {
        l1: 0.999999 * 0.4,
        ..Parameters::reference()
    };
    let shaper = Whitworth::new(parameters).unwrap();
    let linkage = whitworth::linkage(&shaper).unwrap();
    let report = whitworth::case(&shaper, &linkage)
        .unwrap()
        .measure(&Timing::quick())
        .unwrap();
    for m in &report.measurements {
        match m.name.as_str() {
            "geometry Newton + implicit" => {
                let failure = m.failure.as_ref().expect("the Newton path fails");
                assert!(failure.reason.is_some() && failure.phi > 0.0 && failure.phi < 0.01);
                assert!(m.time[0].is_nan());
            }
            name if m.is_exact() => assert!(m.failure.is_none(), "{name}"),
            _ => {}
        }
    }
}

/// Both pictures render (resvg, through `mechdiff::pictures::raster`) to images that are not
/// blank: more than 1 % of their pixels are not white (axes, dots, curves, text).
#[test]
fn plots_render_to_non_empty_images() {
    let shaper = Whitworth::reference();
    let linkage = whitworth::linkage(&shaper).unwrap();
    let report = whitworth::case(&shaper, &linkage)
        .unwrap()
        .measure(&Timing::quick())
        .unwrap();
    let pareto = plot::pareto_svg(&report, 900, 600).unwrap();
    let along = plot::along_sweep(&report).to_svg().unwrap();
    for svg in [pareto, along] {
        let raster = raster::render(&svg).unwrap();
        let inked = raster
            .rgba
            .chunks(4)
            .filter(|p| p[3] > 0 && (p[0] < 240 || p[1] < 240 || p[2] < 240))
            .count();
        let pixels = (raster.width * raster.height) as usize;
        assert!(inked * 100 > pixels, "{inked} inked pixels of {pixels}");
    }
}
