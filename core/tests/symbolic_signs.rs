//! The simplifications that rest on proven signs (`core/src/symbolic/signs.rs`, ranges from
//! `range.rs`) and the quotient cancellations that come with them (`simplify.rs`): each
//! rewritten expression agrees, value and derivatives, with the formula as
//! written evaluated directly in num-dual `Dual2_64` (not through the graph), on random
//! inputs; and every node's range holds its value.

use std::f64::consts::PI;

use mechdiff_core::symbolic::{Graph, Id};
use num_dual::{Dual2_64, DualNum};
use num_traits::Signed;
use proptest::prelude::*;

/// atan2 in `Dual2` by the half-angle formulas θ = 2 atan(y / (r + x)) = 2 atan((r − x) / y)
/// with r = √(x² + y²), valid off the origin: num-dual's own `atan2` differentiates
/// atan(y / x), which is NaN at x = 0.
trait HalfAngle {
    fn atan2_ref(self, x: Self) -> Self;
}

impl HalfAngle for Dual2_64 {
    fn atan2_ref(self, x: Self) -> Self {
        let r = (self * self + x * x).sqrt();
        // tan(θ/2) = y / (r + x) = (r − x) / y: the form without cancellation
        if x.re >= 0.0 {
            (self / (r + x)).atan() * 2.0
        } else if self.re.abs() >= -x.re {
            ((r - x) / self).atan() * 2.0
        } else {
            // x < 0 and |y| < |x|: (r − x)/y grows without bound as y → 0 (the branch cut),
            // and its derivatives cancel (2⁻³⁵ off at 8e-6 from the cut); atan(y/x) ± π
            // has the same derivatives and is well conditioned there
            let half_turn = if self.re >= 0.0 { PI } else { -PI };
            (self / x).atan() + half_turn
        }
    }
}

/// `(expression as written, the same as a Rust formula in Dual2)` for inputs a (seeded) and b.
type Case = (&'static str, fn(Dual2_64, Dual2_64) -> Dual2_64);

/// p = 1.5 + sin a > 0; q = 2 + cos b > 0; u, v of any sign.
const CASES: &[Case] = &[
    // a positive factor shared by both coordinates leaves atan2 (the coordinates are a
    // rotation, never both 0)
    (
        "(atan2 (* (+ 1.5 (sin a)) (sin (+ a b))) (* (+ 1.5 (sin a)) (cos (+ a b))))",
        |a, b| {
            let p = a.sin() + 1.5;
            (p * (a + b).sin()).atan2_ref(p * (a + b).cos())
        },
    ),
    // a shared positive denominator, and a shared positive constant
    (
        "(atan2 (/ (sin a) (+ 2 (cos b))) (/ (cos a) (+ 2 (cos b))))",
        |a, b| {
            let q = b.cos() + 2.0;
            (a.sin() / q).atan2_ref(a.cos() / q)
        },
    ),
    (
        "(atan2 (* 0.8 (sin (* b a))) (* 0.8 (cos (* b a))))",
        |a, b| ((b * a).sin() * 0.8).atan2_ref((b * a).cos() * 0.8),
    ),
    // x > 0: atan(y / x)
    ("(atan2 (- b (sin a)) (+ 2 (cos b)))", |a, b| {
        (b - a.sin()).atan2_ref(b.cos() + 2.0)
    }),
    // y > 0 and y < 0: ±π/2 − atan(x / y)
    ("(atan2 (+ 2 (cos a)) (- b (* 3 a)))", |a, b| {
        (a.cos() + 2.0).atan2_ref(b - a * 3.0)
    }),
    ("(atan2 (- -2 (cos a)) (- b (* 3 a)))", |a, b| {
        (-a.cos() - 2.0).atan2_ref(b - a * 3.0)
    }),
    // π/2 − (π/2 − atan(u)) = atan(u): the Whitworth rocker (λ = 0.375), as traced
    (
        "(- (atan2 0.65 0) (atan2 (- 0.4 (* 0.15 (cos a))) (* 0.15 (sin a))))",
        |a, _| {
            Dual2_64::from(0.65f64.atan2(0.0)) - (-a.cos() * 0.15 + 0.4).atan2_ref(a.sin() * 0.15)
        },
    ),
    // |u| for u ≥ 0 and u ≤ 0
    ("(abs (+ 1.25 (sin a)))", |a, _| (a.sin() + 1.25).abs()),
    ("(abs (- (* -1 (powi a 2)) (exp b)))", |a, b| {
        (-(a * a) - b.exp()).abs()
    }),
    // √(D / |D|) = 1 for D > 0 (a loop's guard)
    (
        "(* (sqrt (/ (+ (powi (sin a) 2) (powi (- 2 (cos a)) 2)) (abs (+ (powi (sin a) 2) (powi (- 2 (cos a)) 2))))) b)",
        |a, b| {
            let d = a.sin().powi(2) + (-a.cos() + 2.0).powi(2);
            (d / d.abs()).sqrt() * b
        },
    ),
    // (x·u)/(y·u) = x/y
    (
        "(/ (* (sin a) (sqrt (+ 3 b))) (* (- (cos a) 2) (sqrt (+ 3 b))))",
        |a, b| a.sin() * (b + 3.0).sqrt() / ((a.cos() - 2.0) * (b + 3.0).sqrt()),
    ),
    // (x·√u)/u = x/√u, x·√u·(1/u) likewise, (x·(p/c))/(q/c) = (x·p)/q
    (
        "(/ (* (sin a) (sqrt (+ 3 (* b (cos a))))) (+ 3 (* b (cos a))))",
        |a, b| {
            let u = a.cos() * b + 3.0;
            a.sin() * u.sqrt() / u
        },
    ),
    (
        "(* (* (sin a) (sqrt (+ 3 (cos a)))) (/ 1 (+ 3 (cos a))))",
        |a, _| {
            let u = a.cos() + 3.0;
            a.sin() * u.sqrt() * (Dual2_64::from(1.0) / u)
        },
    ),
    (
        "(/ (* 0.65 (/ (sin a) (sqrt (+ 3 b)))) (/ (- 2 (cos a)) (sqrt (+ 3 b))))",
        |a, b| (a.sin() / (b + 3.0).sqrt()) * 0.65 / ((-a.cos() + 2.0) / (b + 3.0).sqrt()),
    ),
];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn sign_rewrites_agree_with_the_formulas_as_written(
        a in -3.0f64..3.0, b in -2.5f64..2.5
    ) {
        for (expression, formula) in CASES {
            let mut graph = Graph::new();
            let f = graph.parse_sexpr(expression).unwrap();
            let jet: Vec<Id> = graph.derivatives(f, "a", 2);
            let symbolic = graph.evaluate_f64(&jet, &[("a", a), ("b", b)]).unwrap();
            let reference = formula(Dual2_64::new(a, 1.0, 0.0), Dual2_64::from(b));
            for (k, exact) in [reference.re, reference.v1, reference.v2].into_iter().enumerate() {
                // 1e-12 scaled: both sides are a few f64 operations (each within a few ulps)
                // on inputs away from the formulas' poles (the atan2 coordinates are a
                // rotation, or one of them is ≥ 1; denominators ≥ 1; the reference's
                // half-angle form switched to atan(y/x) ± π near the branch cut, where it
                // cancelled), amplified by at most ~1e2 in the second derivative; a wrong
                // rule is off by O(1) (a lost π, a sign)
                prop_assert!(
                    (symbolic[k] - exact).abs() <= 1e-12 * exact.abs().max(1.0),
                    "order {k} of {expression} at a = {a}, b = {b}: {} vs {exact}",
                    symbolic[k]
                );
            }
        }
    }

    #[test]
    fn every_node_value_lies_in_its_range(a in -3.0f64..3.0, b in -2.5f64..2.5) {
        let mut graph = Graph::new();
        for (expression, _) in CASES {
            let f = graph.parse_sexpr(expression).unwrap();
            graph.derivatives(f, "a", 2);
        }
        let ids: Vec<Id> = graph
            .nodes()
            .iter()
            .map(|node| graph.lookup(node).unwrap())
            .collect();
        let values = graph.evaluate_f64(&ids, &[("a", a), ("b", b)]).unwrap();
        for (&id, &value) in ids.iter().zip(&values) {
            if !value.is_finite() {
                continue; // no real value there to enclose
            }
            let range = graph.range(id);
            // the range holds the real value; the f64 value is a few roundings from it
            // (1e-12 of its size: these nodes are short formulas of inputs below 3)
            let slack = 1e-12 * value.abs().max(1.0);
            prop_assert!(
                range.lo() - slack <= value && value <= range.hi() + slack,
                "{} = {value} outside [{}, {}]",
                graph.to_sexpr(id),
                range.lo(),
                range.hi()
            );
        }
    }
}

/// One-line checks of what the rules produce (both sides parsed into one graph).
fn same(lhs: &str, rhs: &str) {
    let mut graph = Graph::new();
    let (l, r) = (
        graph.parse_sexpr(lhs).unwrap(),
        graph.parse_sexpr(rhs).unwrap(),
    );
    assert_eq!(
        graph.to_sexpr(l),
        graph.to_sexpr(r),
        "{lhs} should be {rhs}"
    );
}

#[test]
fn atan2_loses_a_shared_positive_factor_and_keeps_one_of_unknown_sign() {
    same(
        "(atan2 (* (sqrt (+ 1 (powi x 2))) y) (* (sqrt (+ 1 (powi x 2))) z))",
        "(atan2 y z)",
    );
    same("(atan2 (* 2 y) (* 2 z))", "(atan2 y z)");
    // x may be negative: atan2(x y, x z) is atan2(y, z) + π there
    same("(atan2 (* x y) (* x z))", "(atan2 (* x y) (* x z))");
}

#[test]
fn atan2_with_a_robust_sign_is_one_atan() {
    same("(atan2 y (+ 2 (cos x)))", "(atan (/ y (+ 2 (cos x))))");
    same(
        "(atan2 (+ 2 (cos x)) y)",
        "(- std::f64::consts::FRAC_PI_2 (atan (/ y (+ 2 (cos x)))))",
    );
    same("(atan2 0.65 0)", "std::f64::consts::FRAC_PI_2");
    same("(atan2 0 (- -1 (powi x 2)))", "std::f64::consts::PI");
    // a range that reaches 1e-300 proves x > 0 in reals, not in f64: atan2 stays
    same(
        "(atan2 y (+ 1e-300 (powi x 2)))",
        "(atan2 y (+ 1e-300 (powi x 2)))",
    );
}

#[test]
fn abs_of_a_signed_node_is_the_node() {
    same("(abs (+ 2 (sin x)))", "(+ 2 (sin x))");
    same("(abs (sqrt x))", "(sqrt x)");
    same("(abs (sin x))", "(abs (sin x))");
}

#[test]
fn a_factor_shared_by_numerator_and_denominator_cancels() {
    same("(/ (* a u) (* b u))", "(/ a b)");
    same("(/ (* a (* c u)) (* (* b u) d))", "(/ (* a c) (* b d))");
    same("(/ (* x (sqrt u)) u)", "(/ x (sqrt u))");
    same("(* (* x (sqrt u)) (/ 1 u))", "(/ x (sqrt u))");
    same("(/ (* 2 (/ p c)) (/ q c))", "(/ (* 2 p) q)");
    // a reciprocal without the root of its factor stays a factor (the quotient rule's
    // f·b′ with f = 1/cosh² keeps cosh² apart, which tanh‴ needs where cosh² overflows)
    same("(* x (/ 1 u))", "(* x (/ 1 u))");
}
