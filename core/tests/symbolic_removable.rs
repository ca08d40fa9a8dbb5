//! Removable singularities: the truncated-Taylor evaluator returns the limit (value and
//! derivatives to order 3) where the quotient is 0/0, and agrees with the 256-bit evaluation
//! of the derivative formulas near the point.

use mechdiff_core::error::Error;
use mechdiff_core::num_dual::Dual3_64;
use mechdiff_core::symbolic::Graph;

/// The formulas, the singular point, and `[f, f′, f″, f‴]` there from closed-form series:
/// - sin x / x = 1 − x²/6 + x⁴/120 − …: f = 1, f′ = 0, f″ = 2·(−1/6) = −1/3, f‴ = 0;
/// - (1 − cos x)/x² = 1/2 − x²/24 + …: 1/2, 0, 2·(−1/24) = −1/12, 0;
/// - x / tan x = 1 − x²/3 − x⁴/45 − …: 1, 0, 2·(−1/3) = −2/3, 0;
/// - (x² − 1)/(x − 1) = x + 1 at x = 1 (t = x − 1: (2t + t²)/t = 2 + t): 2, 1, 0, 0;
/// - (eˣ − 1)/x = 1 + x/2 + x²/6 + x³/24 + …: 1, 1/2, 2/6 = 1/3, 6/24 = 1/4.
const CASES: [(&str, f64, [f64; 4]); 5] = [
    ("sin(x)/x", 0.0, [1.0, 0.0, -1.0 / 3.0, 0.0]),
    ("(1 - cos(x))/x^2", 0.0, [0.5, 0.0, -1.0 / 12.0, 0.0]),
    ("x/tan(x)", 0.0, [1.0, 0.0, -2.0 / 3.0, 0.0]),
    ("(x^2 - 1)/(x - 1)", 1.0, [2.0, 1.0, 0.0, 0.0]),
    ("(exp(x) - 1)/x", 0.0, [1.0, 0.5, 1.0 / 3.0, 0.25]),
];

/// |a − b| relative to |b|, absolute where b = 0.
fn relative(a: f64, b: f64) -> f64 {
    if b == 0.0 {
        (a - b).abs()
    } else {
        ((a - b) / b).abs()
    }
}

#[test]
fn limits_at_the_point_match_the_closed_form_series() {
    for (text, x0, expected) in CASES {
        let mut graph = Graph::new();
        let f = graph.parse_infix(text).unwrap();
        // The plain evaluation refuses the 0/0 …
        assert!(
            matches!(
                graph.evaluate_f64(&[f], &[("x", x0)]),
                Err(Error::ZeroOverZero { .. })
            ),
            "{text}"
        );
        // … the series evaluation takes the limit and says so.
        let limits = graph.limit_jets::<f64>(&[f], "x", &[("x", x0)]).unwrap();
        assert!(limits.removed, "{text}: the limit is flagged");
        for (k, (got, want)) in limits.jets[0].iter().zip(expected).enumerate() {
            // 1e-13 relative (absolute for a zero): a handful of roundings in series of
            // 8 terms whose coefficients are O(1).
            assert!(
                relative(*got, want) <= 1e-13,
                "{text} order {k}: {got} vs {want}"
            );
        }
    }
}

/// Near the point the quotient is computed as written (a difference that cancels, divided
/// by a small number): rounding ε in the numerator is amplified by 1/|t|^(k+m) in order k,
/// where t is the distance to the point and m the order of the denominator's zero (2 for
/// x², 1 otherwise). Both the ordinary Dual3 path and the series path stay within that
/// bound (with a factor 8 for the few roundings per term) of the 256-bit evaluation of the
/// derivative formulas — and no further: this is the known loss of digits beside a
/// removable singularity, which the limit at the point does not remove.
#[test]
fn near_the_point_errors_stay_within_the_cancellation_bound() {
    for (text, x0, _) in CASES {
        let m = if text.ends_with("x^2") { 2 } else { 1 };
        let mut graph = Graph::new();
        let f = graph.parse_infix(text).unwrap();
        let jet = graph.derivatives(f, "x", 3);
        for offset in [1e-3, 1e-8] {
            let x = x0 + offset;
            let t = x - x0;
            let decimal = format!("{x:e}");
            let reference: Vec<f64> = graph
                .evaluate_big(&jet, &[("x", &decimal)], 256)
                .unwrap()
                .iter()
                .map(|r| r.to_f64())
                .collect();
            let scale = reference.iter().fold(1.0_f64, |s, r| s.max(r.abs()));
            let limits = graph.limit_jets::<f64>(&[f], "x", &[("x", x)]).unwrap();
            assert!(!limits.removed, "{text} at {x}: no 0/0 here");
            let d = graph
                .evaluate_dual(&[f], &[("x", Dual3_64::from(x).derivative())])
                .unwrap()[0];
            for (k, dual3) in [d.re, d.v1, d.v2, d.v3].into_iter().enumerate() {
                let bound = 8.0 * f64::EPSILON / t.abs().powi(k as i32 + m);
                let series = limits.jets[0][k];
                for (path, value) in [("Dual3", dual3), ("series", series)] {
                    let e = (value - reference[k]).abs() / scale;
                    assert!(
                        e <= bound,
                        "{text} {path} at {x}, order {k}: {e:e} > {bound:e}"
                    );
                }
            }
        }
    }
}

#[test]
fn a_true_pole_or_a_deeper_zero_stays_an_error() {
    let mut graph = Graph::new();
    // 1/x at 0: a pole, no limit. sin(x)^5/x^5: five orders to cancel, more than carried.
    for text in ["sin(x)/x^2", "sin(x)^5/x^5"] {
        let f = graph.parse_infix(text).unwrap();
        let result = graph.limit_jets::<f64>(&[f], "x", &[("x", 0.0)]);
        assert!(
            matches!(result, Err(Error::ZeroOverZero { .. })),
            "{text}: {result:?}"
        );
    }
}

/// Every primitive's series recurrence at a regular point against num-dual's `Dual3` (an
/// independent implementation of the same derivatives): 1e-13 of the jet's largest entry
/// (both paths a few roundings per order of O(1) terms).
#[test]
fn series_of_every_primitive_match_dual3_at_a_regular_point() {
    let formulas = [
        "sqrt(x + 1)",
        "cbrt(x + 2)",
        "cbrt(-x - 2)",
        "exp(2*x)",
        "ln(x + 1)",
        "sin(3*x)",
        "cos(x^2)",
        "tan(x)",
        "asin(x)",
        "acos(x)",
        "atan(x^3 + x)",
        "sinh(x)",
        "cosh(x)",
        "tanh(2*x)",
        "abs(x - 1)",
        "(x + 1)^2.5",
        "x^(-3)",
        "atan2(x, 1 - x)",
        "atan2(-1 - x, -x)",
        "hypot(x, 2*x + 1)",
        "-x/(1 + x^2)",
    ];
    for text in formulas {
        let mut graph = Graph::new();
        let f = graph.parse_infix(text).unwrap();
        let x = 0.3;
        let series = graph.limit_jets::<f64>(&[f], "x", &[("x", x)]).unwrap();
        assert!(!series.removed, "{text}");
        let d = graph
            .evaluate_dual(&[f], &[("x", Dual3_64::from(x).derivative())])
            .unwrap()[0];
        let dual = [d.re, d.v1, d.v2, d.v3];
        let scale = dual.iter().fold(1.0_f64, |s, v| s.max(v.abs()));
        for (k, (s, d)) in series.jets[0].iter().zip(dual).enumerate() {
            let e = (s - d).abs() / scale;
            assert!(e <= 1e-13, "{text} order {k}: {s} vs {d} ({e:e})");
        }
    }
}
