//! Issue 13, the symbolic evaluator's findings: atan2 on the y axis, hypot of huge arguments,
//! infinite derivatives at a domain's edge and 0/0 — each either right (checked against the
//! symbolic derivatives evaluated at 256 bits) or a typed error, never a silent NaN.
// Its references are evaluated at 256 bits (feature `big-float`).
#![cfg(feature = "big-float")]

use mechdiff_core::Error;
use mechdiff_core::num_dual::{Dual3_64, Dual64};
use mechdiff_core::symbolic::Graph;

/// `formula` and its first derivative in `x` at 256 bits, at `x` and the other `bindings`
/// (exact `f64` values printed with every digit).
fn reference(formula: &str, bindings: &[(&str, f64)]) -> [f64; 2] {
    let mut graph = Graph::new();
    let f = graph.parse_infix(formula).unwrap();
    let d = graph.derivatives(f, "x", 1);
    let text: Vec<(&str, String)> = bindings
        .iter()
        .map(|(n, v)| (*n, format!("{v:e}")))
        .collect();
    let decimal: Vec<(&str, &str)> = text.iter().map(|(n, v)| (*n, v.as_str())).collect();
    let big = graph.evaluate_big(&d, &decimal, 256).unwrap();
    [big[0].to_f64(), big[1].to_f64()]
}

/// `formula` in `Dual64`, seeded in `x`.
fn dual(formula: &str, x: f64, others: &[(&str, f64)]) -> Result<Dual64, Error> {
    let mut graph = Graph::new();
    let f = graph.parse_infix(formula)?;
    let mut bindings = vec![("x", Dual64::new(x, 1.0))];
    bindings.extend(others.iter().map(|(n, v)| (*n, Dual64::from(*v))));
    Ok(graph.evaluate_dual(&[f], &bindings)?[0])
}

/// atan2(y, x) on the y axis (x = 0), a position every rotating link passes through:
/// ∂/∂x = −y/(x² + y²) = −1/y, exact in f64 for y = 2 (−0.5); num-dual's own atan2
/// differentiates atan(y/x) and gave NaN there. Compared with the 256-bit derivative to
/// 1 ulp (both exact here).
#[test]
fn atan2_is_differentiable_on_the_y_axis() {
    let got = dual("atan2(y, x)", 0.0, &[("y", 2.0)]).unwrap();
    let [value, slope] = reference("atan2(y, x)", &[("x", 0.0), ("y", 2.0)]);
    assert_eq!(got.re, value);
    assert_eq!(got.eps, slope);
    assert_eq!(slope, -0.5);
}

/// hypot(x, 4e300) at x = 3e300: x² overflows f64, and the evaluator used to return ∞
/// (value) and NaN (derivative). Scaled by a power of two, value 5e300 and ∂/∂x = x/hypot =
/// 0.6 agree with the 256-bit reference to 4 ε relative (a handful of roundings).
#[test]
fn hypot_of_huge_arguments_does_not_overflow() {
    let got = dual("hypot(x, y)", 3e300, &[("y", 4e300)]).unwrap();
    let [value, slope] = reference("hypot(x, y)", &[("x", 3e300), ("y", 4e300)]);
    assert!(
        (got.re - value).abs() <= 4.0 * f64::EPSILON * value,
        "{}",
        got.re
    );
    assert!(
        (got.eps - slope).abs() <= 4.0 * f64::EPSILON * slope,
        "{}",
        got.eps
    );
    // And for tiny ones (x² underflows to 0): 5e-300, slope 0.6.
    let tiny = dual("hypot(x, y)", 3e-300, &[("y", 4e-300)]).unwrap();
    assert!((tiny.re - 5e-300).abs() <= 4.0 * f64::EPSILON * 5e-300);
    assert!((tiny.eps - 0.6).abs() <= 4.0 * f64::EPSILON);
}

/// asin at 1: the value π/2 is fine in f64, but its derivative 1/√(1 − x²) is infinite: a
/// true singularity, reported with the function and the point instead of ∞/NaN. Beside it
/// (x = 1 − 2⁻³⁰) the derivative is finite and within its conditioning of the 256-bit one:
/// relative error ≤ 4 ε (1 + x²/(1 − x²)), the condition number of 1/√(1 − x²) in x.
#[test]
fn asin_at_one_is_an_infinite_derivative_reported_not_nan() {
    let mut graph = Graph::new();
    let f = graph.parse_infix("asin(x)").unwrap();
    let value = graph.evaluate_f64(&[f], &[("x", 1.0)]).unwrap()[0];
    assert_eq!(value, std::f64::consts::FRAC_PI_2);
    match graph.evaluate_dual(&[f], &[("x", Dual3_64::new(1.0, 1.0, 0.0, 0.0))]) {
        Err(Error::InfiniteDerivative { function, at, .. }) => {
            assert_eq!((function.as_str(), at), ("asin", 1.0));
        }
        other => panic!("expected InfiniteDerivative, got {other:?}"),
    }
    let x = 1.0 - f64::powi(2.0, -30);
    let got = dual("asin(x)", x, &[]).unwrap();
    let [_, slope] = reference("asin(x)", &[("x", x)]);
    let condition = 1.0 + x * x / (1.0 - x * x);
    let relative = (got.eps - slope).abs() / slope;
    assert!(
        relative <= 4.0 * f64::EPSILON * condition,
        "{relative:e} > {:e}",
        4.0 * f64::EPSILON * condition
    );
}

/// sin x / x at 0: 0/0 where the value is used is an error naming the quotient (the limit
/// is 1, but the formula as written is undefined there), in f64 and in dual numbers. The
/// same quotient in a piecewise branch not taken (`if(x == 0, 1, sin(x)/x)`, the way to
/// write the limit) is no error, and gives 1 with derivative 0 exactly.
#[test]
fn zero_over_zero_is_reported_where_it_is_used() {
    let mut graph = Graph::new();
    let f = graph.parse_infix("sin(x)/x").unwrap();
    for result in [
        graph.evaluate_f64(&[f], &[("x", 0.0)]).map(|v| v[0]),
        graph
            .evaluate_dual(&[f], &[("x", Dual64::new(0.0, 1.0))])
            .map(|v| v[0].re),
    ] {
        match result {
            Err(Error::ZeroOverZero { expression }) => {
                assert!(expression.contains("sin"), "{expression}");
            }
            other => panic!("expected ZeroOverZero, got {other:?}"),
        }
    }
    let guarded = graph
        .parse_infix_piecewise("if(x == 0, 1, sin(x)/x)")
        .unwrap();
    let at_zero = graph
        .evaluate_dual(&[guarded], &[("x", Dual64::new(0.0, 1.0))])
        .unwrap()[0];
    assert_eq!((at_zero.re, at_zero.eps), (1.0, 0.0));
}
