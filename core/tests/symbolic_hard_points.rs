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
