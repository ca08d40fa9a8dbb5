//! Removable singularities: the truncated-Taylor evaluator returns the limit (value and
//! derivatives to order 3) where the quotient is 0/0, and agrees with the 256-bit evaluation
//! of the derivative formulas near the point; powers and roots through a zero of their base
//! give their (one-sided, flagged) limits or a typed error, never a wrong two-sided jet.

use mechdiff_core::error::Error;
use mechdiff_core::num_dual::Dual3_64;
use mechdiff_core::symbolic::Graph;
use mechdiff_core::symbolic::taylor::Side;
use proptest::prelude::*;

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
#[cfg(feature = "big-float")]
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

/// Powers through a zero of their base, `u = tᵐ·ũ`, `uᵖ = tᵐᵖ·ũᵖ` (docs of
/// `symbolic::taylor::power`), `[f, f′, f″, f‴]` at 0 from closed-form series:
/// - x^3.5 (real for x ≥ 0 only): ‴ = 3.5·2.5·1.5·x^0.5 → 0: all four 0, from above;
/// - (−x)^3.5: the same from below;
/// - cbrt(x³) = x: 0, 1, 0, 0; cbrt(x³ + x⁴) = x·∛(1 + x) = x + x²/3 − x³/9 + …:
///   0, 1, 2/3, −6/9;
/// - sqrt(x⁴) = x²: 0, 0, 2, 0; powf(x², 1.75) = |x|^3.5: all 0, both sides;
/// - powf(x³, 1/3) (powf: real for x ≥ 0 only) = x: 0, 1, 0, 0 from above.
#[allow(clippy::type_complexity)]
const POWERS: [(&str, [f64; 4], bool, Option<Side>); 8] = [
    ("x^3.5", [0.0; 4], true, Some(Side::Above)),
    ("powf(x, 3.5)", [0.0; 4], true, Some(Side::Above)),
    ("(-x)^3.5", [0.0; 4], true, Some(Side::Below)),
    ("cbrt(x^3)", [0.0, 1.0, 0.0, 0.0], true, None),
    (
        "cbrt(x^3 + x^4)",
        [0.0, 1.0, 2.0 / 3.0, -6.0 / 9.0],
        true,
        None,
    ),
    ("sqrt(x^4)", [0.0, 0.0, 2.0, 0.0], true, None),
    ("powf(x^2, 1.75)", [0.0; 4], true, None),
    (
        "powf(x^3, 1/3)",
        [0.0, 1.0, 0.0, 0.0],
        true,
        Some(Side::Above),
    ),
];

#[test]
fn powers_through_a_zero_of_their_base_take_their_limits_flagged() {
    for (text, expected, removed, side) in POWERS {
        let mut graph = Graph::new();
        let f = graph.parse_infix(text).unwrap();
        let limits = graph.limit_jets::<f64>(&[f], "x", &[("x", 0.0)]).unwrap();
        assert_eq!((limits.removed, limits.side), (removed, side), "{text}");
        for (k, (got, want)) in limits.jets[0].iter().zip(expected).enumerate() {
            // 1e-13 relative (absolute for a zero): a few roundings in 8-term series of O(1)
            // coefficients.
            assert!(
                relative(*got, want) <= 1e-13,
                "{text} order {k}: {got} vs {want}"
            );
        }
    }
}

/// Dual numbers cannot go through these points (num-dual's powf is exp(v·ln u), its cbrt′
/// is 1/(3∛u²)): the evaluator says so with a typed error instead of returning NaN.
#[test]
fn dual_numbers_at_a_zero_base_are_refused_not_nan() {
    let mut graph = Graph::new();
    let seed = Dual3_64::from(0.0).derivative();
    for (text, power) in [("x^3.5", true), ("cbrt(x^3)", false)] {
        let f = graph.parse_infix(text).unwrap();
        let result = graph.evaluate_dual(&[f], &[("x", seed)]);
        assert!(
            match result {
                Err(Error::PowerOfZero { .. }) => power,
                Err(Error::InfiniteDerivative { ref function, .. }) => function == "cbrt",
                _ => false,
            },
            "{text}: {result:?}"
        );
    }
}

/// Where the derivatives to order 3 do not exist, not even one-sided, the answer is a typed
/// error naming the reason — never a one-sided derivative passed off as two-sided:
/// |x| and sqrt(x²) at 0 (′ is ±1 on the two sides), powf(x², 1.5) = |x|³ (‴ is ±6),
/// x^2.5 (‴ infinite), sqrt(x) (′ infinite), a formula real on neither side
/// (powf(−x², 2.5)), or only above in one part and only below in another, and x^3.5 at
/// x = −1 (not real).
#[test]
fn powers_without_derivatives_at_the_point_are_errors_with_the_reason() {
    let cases = [
        ("abs(x)", 0.0, "abs"),
        ("abs(x^3)", 0.0, "abs"),
        ("sqrt(x^2)", 0.0, "differ on the two sides"),
        ("powf(x^2, 1.5)", 0.0, "differ on the two sides"),
        ("x^2.5", 0.0, "infinite"),
        ("sqrt(x)", 0.0, "infinite"),
        ("powf(-x^2, 2.5)", 0.0, "negative on both sides"),
        ("x^3.5 + (-x)^3.5", 0.0, "only below"),
        ("x^3.5", -1.0, "not real"),
    ];
    for (text, x0, reason) in cases {
        let mut graph = Graph::new();
        let f = graph.parse_infix(text).unwrap();
        match graph.limit_jets::<f64>(&[f], "x", &[("x", x0)]) {
            Err(e @ Error::NotDifferentiable { .. }) => {
                assert!(e.to_string().contains(reason), "{text}: {e}");
            }
            other => panic!("{text}: expected NotDifferentiable, got {other:?}"),
        }
    }
    // |x^5| at 0 is differentiable to order 4 (all zero), both sides: no error.
    let mut graph = Graph::new();
    let f = graph.parse_infix("abs(x^5)").unwrap();
    let limits = graph.limit_jets::<f64>(&[f], "x", &[("x", 0.0)]).unwrap();
    assert_eq!(limits.jets[0], [0.0; 4]);
}

/// The binomial series: `C(p, k) = p (p − 1) … (p − k + 1) / k!`.
fn binomial(p: f64, k: usize) -> f64 {
    (0..k).fold(1.0, |c, j| c * (p - j as f64) / (j + 1) as f64)
}

/// What `powf(a·xᵐ·(1 + c·x), p)` (or `cbrt`, p = 1/3) is at x = 0, from the closed form
/// `|t|^(m p)·|a|^p·Σ C(p, k) cᵏ tᵏ` with its sign on the side(s) where it is real:
/// `Ok((jet, side))`, or `Err(())` where the derivatives to order 3 do not exist. `q` is
/// `m p` when it is an integer by construction, `None` when it is not one.
fn closed_form_power(
    m: usize,
    a: f64,
    c: f64,
    p: f64,
    q: Option<usize>,
    odd: bool,
) -> Result<([f64; 4], Option<Side>), ()> {
    let integer_p = !odd && p.fract() == 0.0;
    let (above, below) = if integer_p || odd {
        (true, true)
    } else {
        (
            a > 0.0,
            a * if m.is_multiple_of(2) { 1.0 } else { -1.0 } > 0.0,
        )
    };
    let side = match (above, below) {
        (true, true) => None,
        (true, false) => Some(Side::Above),
        (false, true) => Some(Side::Below),
        (false, false) => return Err(()),
    };
    let Some(q) = q else {
        // |t|^q with q not an integer: 0 below order q, infinite above.
        let qf = m as f64 * p;
        return if qf > 3.0 {
            Ok(([0.0; 4], side))
        } else {
            Err(())
        };
    };
    // The sign of the leading factor on the side taken: aᵖ·tᵠ for integer p and for odd
    // roots; |a|ᵖ·|t|ᵠ for a real power, where |t|ᵠ = (−t)ᵠ below.
    let lead = if integer_p {
        a.powi(p as i32)
    } else if odd {
        a.cbrt()
    } else {
        a.abs().powf(p)
    };
    let sign = if side == Some(Side::Below) && q % 2 == 1 {
        -1.0
    } else {
        1.0
    };
    if side.is_none() && !integer_p && !odd && q % 2 == 1 {
        // |t|^q, q odd, both sides: the q-th derivatives differ.
        return if q > 3 { Ok(([0.0; 4], None)) } else { Err(()) };
    }
    let mut jet = [0.0; 4];
    let mut factorial = 1.0;
    for (k, x) in jet.iter_mut().enumerate() {
        if k > 0 {
            factorial *= k as f64;
        }
        if k >= q {
            *x = factorial * sign * lead * binomial(p, k - q) * c.powi((k - q) as i32);
        }
    }
    Ok((jet, side))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Random exponents p and orders m of the base's zero against the closed-form series:
    /// the same jet (1e-13 relative to max(|f⁽ᵏ⁾|, |a|ᵖ·(1 + |c|)³): a few roundings per
    /// order in the recurrence, whose terms are of that size), the same side, or both an
    /// error. p = q/m gives an integer m·p (as the rounded f64 exponent does within 4 ulp).
    #[test]
    fn powers_of_a_zero_of_order_m_match_the_binomial_series(
        m in 1usize..=4,
        a in prop_oneof![0.5f64..2.0, -2.0f64..-0.5],
        c in -1.0f64..1.0,
        integer_q in 1usize..=12,
        real_p in 0.05f64..5.0,
        integral in any::<bool>(),
        odd in any::<bool>(),
    ) {
        let (m, p, q) = if odd {
            (m + 3 * usize::from(integral), 1.0 / 3.0, None)
        } else if integral {
            (m, integer_q as f64 / m as f64, Some(integer_q))
        } else {
            (m, real_p, None)
        };
        let qf = m as f64 * p;
        let q = if odd && m % 3 == 0 { Some(m / 3) } else { q };
        // A real p whose m·p happens to be within 1e-6 of an integer is left to the p = q/m
        // branch.
        prop_assume!(q.is_some() || (qf - qf.round()).abs() > 1e-6);
        let text = if odd { "cbrt(a*x^m*(1 + c*x))" } else { "powf(a*x^m*(1 + c*x), p)" };
        let text = text.replace("^m", &format!("^{m}"));
        let mut graph = Graph::new();
        let f = graph.parse_infix(&text).unwrap();
        let got = graph.limit_jets::<f64>(&[f], "x", &[("x", 0.0), ("a", a), ("c", c), ("p", p)]);
        match (closed_form_power(m, a, c, p, q, odd), got) {
            (Ok((want, side)), Ok(limits)) => {
                prop_assert_eq!(limits.side, side);
                let scale = a.abs().powf(p) * (1.0 + c.abs()).powi(3);
                for (k, (&got, want)) in limits.jets[0].iter().zip(want).enumerate() {
                    let bound = 1e-13 * want.abs().max(scale);
                    prop_assert!((got - want).abs() <= bound,
                        "{} m={} p={} order {}: {} vs {}", text, m, p, k, got, want);
                }
            }
            (Err(()), Err(Error::NotDifferentiable { .. })) => {}
            (want, got) => prop_assert!(false, "{} m={} p={} a={}: {:?} vs {:?}", text, m, p, a, want, got),
        }
    }
}
