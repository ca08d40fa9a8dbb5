//! `powf`, `tanh` and `hypot` differentiated symbolically, evaluated near their hard points,
//! against num-dual `Dual3_64` (forward-mode AD of the same function, an independent
//! derivation) and, where forward AD itself loses digits, against closed forms:
//! - `powf(a x, c)` for small x > 0 and at x = 0 (c ≥ 3: finite derivatives, which the old
//!   rule `u^c · c u′ / u` made 0 / 0);
//! - `tanh(a x + b)` for |a x + b| up to 40, where `1 − tanh²` cancels to 0 (num-dual's
//!   `sinh / cosh` as well: it is compared for |u| ≤ 3 only, the closed form everywhere);
//! - `hypot(u, v)` near the origin and at magnitudes up to 1e150.
//!
//! Tolerances: 1e-13 relative to the natural size of the k-th derivative. Both sides are
//! exact formulas rounded in f64 (a few ulp per operation, at most ~20 operations), so
//! 1e-13 leaves a factor ~50 of margin; a wrong rule or a cancellation errs at O(1).

use mechdiff_core::symbolic::Graph;
use num_dual::{Dual3_64, DualNum};
use proptest::prelude::*;

/// Value and derivatives 1 to 3 in x of the infix `formula` at `x`.
fn symbolic(formula: &str, x: f64, bindings: &[(&str, f64)]) -> [f64; 4] {
    let mut graph = Graph::new();
    let f = graph.parse_infix(formula).unwrap();
    let jet = graph.derivatives(f, "x", 3);
    let mut all = bindings.to_vec();
    all.push(("x", x));
    let values = graph.evaluate_f64(&jet, &all).unwrap();
    [values[0], values[1], values[2], values[3]]
}

fn jet(d: Dual3_64) -> [f64; 4] {
    [d.re, d.v1, d.v2, d.v3]
}

fn seed(x: f64) -> Dual3_64 {
    Dual3_64::new(x, 1.0, 0.0, 0.0)
}

/// Every order agrees within 1e-13 × `scale[k]` (and nothing is NaN or infinite).
fn assert_close(what: &str, got: [f64; 4], reference: [f64; 4], scale: [f64; 4]) {
    for k in 0..4 {
        assert!(got[k].is_finite(), "{what}: order {k} is {}", got[k]);
        let tolerance = 1e-13 * scale[k].max(reference[k].abs());
        assert!(
            (got[k] - reference[k]).abs() <= tolerance,
            "{what}: order {k}: symbolic {:e}, reference {:e}",
            got[k],
            reference[k]
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn powf_near_zero_base_agrees_with_dual3(
        x in 1e-6f64..1e-2,
        a in 0.5f64..2.0,
        c in 1.05f64..4.95,
    ) {
        let reference = jet((seed(x) * a).powf(c));
        // the exponent as a constant of the formula and as a parameter: both use c u^(c−1)
        let literal = symbolic(&format!("powf({a:?}*x, {c:?})"), x, &[]);
        let parameter = symbolic("powf(a*x, c)", x, &[("a", a), ("c", c)]);
        assert_close("powf literal", literal, reference, [0.0; 4]);
        assert_close("powf parameter", parameter, reference, [0.0; 4]);
    }

    #[test]
    fn tanh_far_out_agrees_with_sech_squared(u0 in -40.0f64..40.0, a in 0.5f64..2.0) {
        // u = a x + b at x = 1 (b = u0 - a)
        let (x, b) = (1.0, u0 - a);
        let got = symbolic("tanh(a*x + b)", x, &[("a", a), ("b", b)]);
        let u = a * x + b;
        // sech² from e^(-2|u|): no cancellation at any u
        let e = (-2.0 * u.abs()).exp();
        let sech2 = 4.0 * e / ((1.0 + e) * (1.0 + e));
        let t = u.tanh();
        let closed = [
            t,
            a * sech2,
            a * a * (-2.0 * t * sech2),
            a * a * a * (2.0 * sech2 * (2.0 * t * t - sech2)),
        ];
        // Each derivative is a^k sech²(u) times a polynomial in tanh u and sech² u of size
        // at most 2 (the third's `2t² − sech²` cancels near t² = 1/3, so its value alone is
        // no scale there): relative to a^k · 4 sech², which far out is as small as the
        // derivatives themselves, so the comparison stays relative where sech² underflows
        // towards e^-80.
        let natural = [1.0, a * sech2, a * a * 4.0 * sech2, a * a * a * 4.0 * sech2];
        assert_close("tanh", got, closed, natural);
        if u.abs() <= 3.0 {
            let reference = jet((seed(x) * a + b).tanh());
            // num-dual's sinh/cosh quotient: a few ulp of the O(1) terms
            assert_close("tanh vs dual", got, reference, [1.0, a, a * a, a * a * a]);
        }
    }

    #[test]
    fn hypot_near_the_origin_and_far_out_agrees_with_dual3(
        magnitude in prop::sample::select(vec![1e-100, 1e-8, 1.0, 1e8, 1e150]),
        p in -2.0f64..2.0,
        q in -1.0f64..1.0,
        r in -2.0f64..2.0,
        s in 0.1f64..1.0,
    ) {
        // u = m (p + q x), v = m (r x + s) at x = 0.5: |(u, v)| ~ m
        let x = 0.5;
        let (p, q, r, s) = (magnitude * p, magnitude * q, magnitude * r, magnitude * s);
        let got = symbolic("hypot(p + q*x, r*x + s)", x, &[("p", p), ("q", q), ("r", r), ("s", s)]);
        let (u, v) = (seed(x) * q + p, seed(x) * r + s);
        // (u² + v²)^½ with the scale taken out, so that squares do not leave f64
        let reference = jet(((u / magnitude).powi(2) + (v / magnitude).powi(2)).sqrt() * magnitude);
        let f = reference[0];
        let rate = q.abs() + r.abs();
        // the k-th derivative's natural size: rate^k / f^(k-1) (terms that may cancel)
        let scale = [f, rate, rate * rate / f, rate * rate * rate / (f * f)];
        assert_close("hypot", got, reference, scale);
    }
}

#[test]
fn powf_at_zero_base_has_the_limits_of_c_u_to_the_c_minus_1() {
    // (x^c)^(k) = c (c−1)…(c−k+1) x^(c−k): at x = 0, 0 for k < c (c = 3.5: all four)
    for formula in ["powf(x, 3.5)", "x^3.5"] {
        let got = symbolic(formula, 0.0, &[]);
        assert_eq!(got, [0.0; 4], "{formula}");
    }
    // c = 2.5: the third derivative is 2.5·1.5·0.5·x^(−0.5), infinite at 0 (a true
    // singularity, not 0/0): reported as +inf, not NaN
    let got = symbolic("powf(x, 2.5)", 0.0, &[]);
    assert_eq!(&got[..3], &[0.0; 3]);
    assert_eq!(got[3], f64::INFINITY);
}

#[test]
fn tanh_derivatives_stay_finite_where_cosh_overflows() {
    // u = 400: cosh² overflows, sech² = 4e-348 underflows to 0: every derivative is 0 (the
    // true values are below the smallest f64), tanh = 1; never NaN
    let got = symbolic("tanh(x)", 400.0, &[]);
    assert_eq!(got, [1.0, 0.0, 0.0, 0.0]);
}

/// Value and derivatives 1 to 3 of `formula` in `u` at `u`, as the engine's derivative
/// formulas give them in f64.
fn engine_jet(formula: &str, u: f64) -> [f64; 4] {
    let mut graph = Graph::new();
    let f = graph.parse_infix(formula).unwrap();
    let jet = graph.derivatives(f, "u", 3);
    let values = graph.evaluate_f64(&jet, &[("u", u)]).unwrap();
    [values[0], values[1], values[2], values[3]]
}

/// Bits of the reference: central differences of step h = 1e-60 of the formula itself
/// (never its derivative formulas), so truncation errs by ~h² = 1e-120 relative to the
/// ratio of neighbouring derivatives and rounding by ~2^-1024 / h³ = 1e-128 relative to
/// |f / f‴|: both far below f64's 1e-16 for every case here but tanh far out.
#[cfg(feature = "big-float")]
const REFERENCE_BITS: usize = 1024;

/// Bits for tanh: at u = 1000 its derivatives are ~e^-2000 = 1e-869 of its value 1, so the
/// differences of values must resolve 1e-869 · h · 1e-16 ≈ 1e-945 of it: 3140 bits; 4096
/// bits (1e-1233) leave a margin of 1e-288.
#[cfg(feature = "big-float")]
const TANH_REFERENCE_BITS: usize = 4096;

/// f, f′, f″, f‴ of `formula` (in `u`, a letter no primitive's name holds) at `u` from
/// central differences in [`REFERENCE_BITS`] bits: (f₁ − f₋₁)/2h, (f₁ − 2f₀ + f₋₁)/h²,
/// (f₂ − 2f₁ + 2f₋₁ − f₋₂)/2h³ with f_k = f(u + k h).
#[cfg(feature = "big-float")]
fn reference_jet(formula: &str, u: f64) -> [f64; 4] {
    let bits = if formula.contains("tanh") {
        TANH_REFERENCE_BITS
    } else {
        REFERENCE_BITS
    };
    let mut graph = Graph::new();
    let f: Vec<_> = [-2, -1, 0, 1, 2]
        .into_iter()
        .map(|k| {
            let shifted = formula.replace('u', &format!("(u + {k}*h)"));
            graph.parse_infix(&shifted).unwrap()
        })
        .collect();
    let (h, two) = (graph.symbol("h"), graph.number(2.0));
    let first = {
        let d = graph.sub(f[3], f[1]);
        let twice_h = graph.mul(two, h);
        graph.div(d, twice_h)
    };
    let second = {
        let outer = graph.add(f[3], f[1]);
        let middle = graph.mul(two, f[2]);
        let d = graph.sub(outer, middle);
        let h2 = graph.powi(h, 2);
        graph.div(d, h2)
    };
    let third = {
        let outer = graph.sub(f[4], f[0]);
        let inner = graph.sub(f[3], f[1]);
        let inner = graph.mul(two, inner);
        let d = graph.sub(outer, inner);
        let h3 = graph.powi(h, 3);
        let twice = graph.mul(two, h3);
        graph.div(d, twice)
    };
    // every argument here is a short binary fraction, so its shortest decimal is exact
    let u_text = format!("{u:e}");
    let values = graph
        .evaluate_big(
            &[f[2], first, second, third],
            &[("u", u_text.as_str()), ("h", "1e-60")],
            bits,
        )
        .unwrap();
    [0, 1, 2, 3].map(|k| values[k].to_f64())
}

/// Below this a derivative has left f64's normal range: the engine must give a finite
/// number as small (it underflows gracefully), not a relative accuracy.
#[cfg(feature = "big-float")]
const UNDERFLOW: f64 = 1e-290;

/// Every primitive's derivative formulas, orders 0 to 3, at large arguments (|u| = 1e3 where
/// the value is in f64's range; 700 for exp, sinh, cosh, whose values leave it at 710),
/// small ones (2⁻¹⁰) and near the ends of their domains (asin, acos at ±(1 − 2⁻¹⁰)), against
/// the high-precision reference: relative error at most 1e-13 wherever the reference is a
/// normal f64, and finite and below 1e-290 where it underflows (below 1e-100 |f| where the
/// derivative is 0 and the reference holds only its rounding).
///
/// Why 1e-13: each formula is a few (< 20) f64 operations on exact arguments, each
/// correctly rounded or within a few ulp (libm), and none of these values cancels (no
/// difference of nearly equal terms at these points), so the error is a few tens of ulp,
/// ~1e-14; 1e-13 leaves a factor ~10, while a formula that overflows, cancels or is wrong
/// errs at O(1) or gives NaN (1/cosh²'s derivatives at |u| = 800 gave NaN).
#[test]
#[cfg(feature = "big-float")]
fn every_primitive_derivative_matches_a_high_precision_reference_far_out() {
    let small = 2f64.powi(-10);
    let edge = 1.0 - small;
    let cases: &[(&str, &[f64])] = &[
        ("-u", &[1e3, -1e3]),
        ("sqrt(u)", &[1e3, small]),
        ("cbrt(u)", &[1e3, -1e3, small]),
        ("exp(u)", &[700.0, -700.0, -1e3, small]),
        ("ln(u)", &[1e3, small]),
        ("sin(u)", &[1e3, -1e3, small]),
        ("cos(u)", &[1e3, -1e3, small]),
        ("tan(u)", &[1e3, -1e3, small]),
        ("asin(u)", &[edge, -edge, small]),
        ("acos(u)", &[edge, -edge, small]),
        ("atan(u)", &[1e3, -1e3, small]),
        ("sinh(u)", &[700.0, -700.0, small]),
        ("cosh(u)", &[700.0, -700.0, small]),
        (
            "tanh(u)",
            &[
                1e3, -1e3, 800.0, -800.0, 300.0, 20.0, -20.0, 1.0, 0.5, -0.5, small,
            ],
        ),
        ("abs(u)", &[1e3, -1e3]),
        ("u^3", &[1e3, -1e3, small]),
        ("u^-2", &[1e3, small]),
        ("1/u", &[1e3, -1e3, small]),
        ("powf(u, 2.5)", &[1e3, small]),
        ("powf(2, u)", &[1e3, -1e3]),
        ("powf(u, u)", &[100.0, small]),
        ("atan2(u, 1)", &[1e3, -1e3, small]),
        // (not at u = +1e3: `signs` rewrites atan2(1, u) as π/2 − atan(u), whose value
        // (not its derivatives) cancels there, 1.2e-13 relative: a simplification's
        // accuracy, outside the derivative rules checked here)
        ("atan2(1, u)", &[-1e3, small]),
        ("atan2(u, -3)", &[1e3, -1e3]),
        ("hypot(u, 1)", &[1e3, -1e3, small]),
        ("hypot(2, u)", &[1e3, small]),
    ];
    let mut checked = 0;
    for &(formula, points) in cases {
        for &u in points {
            let got = engine_jet(formula, u);
            let reference = reference_jet(formula, u);
            // a derivative that is 0 (|u|″) comes out of the differences as rounding,
            // ~1e-125 |f|: below 1e-100 |f| a reference counts as 0
            let zero = UNDERFLOW.max(1e-100 * reference[0].abs());
            for (k, (&g, &r)) in got.iter().zip(&reference).enumerate() {
                let ok = if r.abs() >= zero {
                    (g - r).abs() <= 1e-13 * r.abs()
                } else {
                    g.is_finite() && g.abs() < zero
                };
                assert!(
                    ok,
                    "{formula} at u = {u}: order {k}: engine {g:e}, reference {r:e}"
                );
                checked += 1;
            }
        }
    }
    assert_eq!(checked, 4 * 76);
}

/// tanh at ±800 (the scene of issue 22): the engine's derivatives are finite, tanh = ±1
/// and sech² = 4e^-1600/(1 + e^-1600)² underflows to 0 with its derivatives: [±1, 0, 0, 0]
/// (the old 1/cosh² form gave [1, 0, NaN, NaN]).
#[test]
fn tanh_at_800_has_finite_derivatives() {
    assert_eq!(engine_jet("tanh(u)", 800.0), [1.0, 0.0, 0.0, 0.0]);
    assert_eq!(engine_jet("tanh(u)", -800.0), [-1.0, 0.0, 0.0, 0.0]);
    // and where sech² is still a normal f64 (u = 300: 4e^-600 = 1.1e-260), it is
    // computed, not flushed: tanh′ > 0, tanh″ = −2 sech² tanh < 0
    let far = engine_jet("tanh(u)", 300.0);
    assert!(
        far[1] > 1e-261 && far[2] < -1e-261 && far[3] > 1e-261,
        "{far:?}"
    );
}

/// Removable singularities are taken in Taylor series (`limit_jets`): tanh there was
/// sinh/cosh, ∞/∞ = NaN past |u| = 710. tanh(u + 800)·sin(u)/u at u = 0 is
/// [1, 0, −1/3, 0] (sech²(800) underflows: the terms with tanh's derivatives vanish), and
/// at −800 its negative.
#[test]
fn tanh_far_out_in_series_at_a_removable_singularity() {
    for (shift, sign) in [(800.0, 1.0), (-800.0, -1.0)] {
        let mut graph = Graph::new();
        let f = graph
            .parse_infix(&format!("tanh(u + {shift:?})*sin(u)/u"))
            .unwrap();
        let limits = graph.limit_jets::<f64>(&[f], "u", &[("u", 0.0)]).unwrap();
        let expected = [1.0, 0.0, -1.0 / 3.0, 0.0].map(|v: f64| v * sign);
        for (got, want) in limits.jets[0].iter().zip(expected) {
            // 1e-15: the series of sin(u)/u to order 3 is exact up to a rounding of 1/3
            assert!(
                (got - want).abs() <= 1e-15,
                "shift {shift}: {:?}",
                limits.jets[0]
            );
        }
    }
}
