//! One-line derivative-rule and simplification tests: `"(d x (sin x))" => "(cos x)"`.
//!
//! Both sides are parsed into one hash-consed graph, so they are equal exactly when they
//! are the same simplified expression; on failure the message shows both s-expressions.

use mechdiff_core::symbolic::Graph;

fn check(lhs: &str, rhs: &str) {
    let mut graph = Graph::new();
    let left = graph.parse_sexpr(lhs).unwrap();
    let right = graph.parse_sexpr(rhs).unwrap();
    assert_eq!(
        graph.to_sexpr(left),
        graph.to_sexpr(right),
        "{lhs} should simplify to {rhs}"
    );
    assert_eq!(
        left, right,
        "{lhs} and {rhs} print alike but are different nodes"
    );
}

macro_rules! rules {
    ($($name:ident: $lhs:literal => $rhs:literal;)*) => {
        $(
            #[test]
            fn $name() {
                check($lhs, $rhs);
            }
        )*
    };
}

rules! {
    // one rule per primitive
    d_add: "(d x (+ x y))" => "1";
    d_sub: "(d x (- y x))" => "-1";
    d_mul: "(d x (* y x))" => "y";
    d_div: "(d x (/ x y))" => "(/ 1 y)";
    // (a' − f b′)/b with f = a/b: no b², which leaves f64 for |b| beyond 1e±154
    d_div_denominator: "(d x (/ y x))" => "(neg (/ (/ y x) x))";
    d_neg: "(d x (neg x))" => "-1";
    d_powi: "(d x (powi x 3))" => "(* 3 (powi x 2))";
    // c xᶜ⁻¹, not xᶜ c / x (0 / 0 at x = 0)
    d_powf_constant_exponent: "(d x (powf x 2.5))" => "(* 2.5 (powf x 1.5))";
    d_powf_parameter_exponent: "(d x (powf x n))" => "(* n (powf x (- n 1)))";
    d_powf_both: "(d x (powf x x))" => "(* (powf x x) (+ (ln x) (* x (/ 1 x))))";
    d_powf_variable_exponent: "(d x (powf 2 x))" => "(* (powf 2 x) (ln 2))";
    d_sqrt: "(d x (sqrt x))" => "(/ 1 (* 2 (sqrt x)))";
    d_cbrt: "(d x (cbrt x))" => "(/ 1 (* 3 (powi (cbrt x) 2)))";
    d_exp: "(d x (exp x))" => "(exp x)";
    d_ln: "(d x (ln x))" => "(/ 1 x)";
    d_sin: "(d x (sin x))" => "(cos x)";
    d_cos: "(d x (cos x))" => "(neg (sin x))";
    d_tan: "(d x (tan x))" => "(+ 1 (powi (tan x) 2))";
    d_asin: "(d x (asin x))" => "(/ 1 (sqrt (- 1 (powi x 2))))";
    d_acos: "(d x (acos x))" => "(neg (/ 1 (sqrt (- 1 (powi x 2)))))";
    d_atan: "(d x (atan x))" => "(/ 1 (+ 1 (powi x 2)))";
    d_atan_of_quotient_is_atan2_rule: "(d x (atan (/ x y)))" => "(/ y (+ (powi x 2) (powi y 2)))";
    d_atan2_numerator: "(d x (atan2 x y))" => "(/ y (+ (powi x 2) (powi y 2)))";
    d_atan2_denominator: "(d x (atan2 y x))" => "(neg (/ y (+ (powi y 2) (powi x 2))))";
    d_sinh: "(d x (sinh x))" => "(cosh x)";
    d_cosh: "(d x (cosh x))" => "(sinh x)";
    // sech², not 1 - tanh² (which cancels to 0 for |x| > 19): 1/cosh² near 0, and
    // 4e^(−2|x|)/(1 + e^(−2|x|))² beyond |x| = 1 (cosh² overflows past 355, and the
    // derivatives of 1/cosh² are ∞/∞ past 710)
    d_tanh: "(d x (tanh x))" => "(if (< (abs x) 1) (/ 1 (powi (cosh x) 2)) \
        (/ (* 4 (exp (neg (* 2 (abs x))))) (powi (+ 1 (exp (neg (* 2 (abs x))))) 2)))";
    d_hypot: "(d x (hypot x y))" => "(/ x (hypot x y))";
    d_abs: "(d x (abs x))" => "(if (< x 0) -1 1)";
    d_select_takes_the_branch: "(d x (if (< x 1) (sin x) (* 2 x)))" => "(if (< x 1) (cos x) 2)";
    // chain rule, higher orders, partials
    d_chain: "(d x (sin (* 2 x)))" => "(* 2 (cos (* 2 x)))";
    d2_sin: "(d x (d x (sin x)))" => "(neg (sin x))";
    d3_sin: "(d x (d x (d x (sin x))))" => "(neg (cos x))";
    d_other_symbol_is_constant: "(d x (sin y))" => "0";
    d_mixed_partial: "(d y (d x (* x (* y y))))" => "(* 2 y)";
    // simplification
    fold_exact_constants: "(+ 1 (* 2 3))" => "7";
    no_fold_of_inexact_sum: "(+ 0.1 0.2)" => "(+ 0.1 0.2)";
    no_fold_of_transcendental: "(sin 1)" => "(sin 1)";
    add_zero: "(+ x 0)" => "x";
    mul_one: "(* 1 x)" => "x";
    mul_zero: "(* 0 (sin x))" => "0";
    sub_self: "(- (sin x) (sin x))" => "0";
    double_negation: "(neg (neg x))" => "x";
    add_negated_is_sub: "(+ x (neg y))" => "(- x y)";
    negative_factor_pulled_out: "(* -2 x)" => "(neg (* 2 x))";
    commutative_operands_are_one_node: "(* y x)" => "(* x y)";
    square_of_product: "(* x x)" => "(powi x 2)";
    powi_folding: "(powi (powi x 2) 3)" => "(powi x 6)";
    powi_merging: "(* (powi x 2) x)" => "(powi x 3)";
    powi_negative_exponent: "(powi x -2)" => "(/ 1 (powi x 2))";
    powf_integer_is_powi: "(powf x 3)" => "(powi x 3)";
    ln_of_exp: "(ln (exp (sin x)))" => "(sin x)";
    ln_of_odd_power: "(ln (powi x 3))" => "(* 3 (ln x))";
    ln_of_even_power: "(ln (powi x 2))" => "(* 2 (ln (abs x)))";
    ln_of_constant_power: "(ln (powf x 2.5))" => "(* 2.5 (ln x))";
    ln_of_power_of_positive_base: "(ln (powf (exp y) x))" => "(* x y)";
    ln_of_power_of_unknown_sign_kept: "(ln (powf y x))" => "(ln (powf y x))";
    constant_factors_merge: "(* 2 (* 3 x))" => "(* 6 x)";
    quotient_cancels_a_factor: "(/ (* a u) u)" => "a";
    quotient_cancels_into_a_power: "(/ (* a u) (powi u 3))" => "(/ a (powi u 2))";
    select_with_equal_branches: "(if (< x 0) y y)" => "y";
}

#[test]
fn malformed_sexpr_reports_the_position() {
    let mut graph = Graph::new();
    let error = graph.parse_sexpr("(sin x) )").unwrap_err().to_string();
    assert!(error.contains("column 9"), "{error}");
    let error = graph.parse_sexpr("(frob x)").unwrap_err().to_string();
    assert!(
        error.contains("unknown operator `frob`") && error.contains("column 2"),
        "{error}"
    );
}

#[test]
fn malformed_infix_reports_the_position() {
    let mut graph = Graph::new();
    let input = "atan2(lambda*sin(phi), 1 - lambda*cos(phi)";
    let error = graph.parse_infix(input).unwrap_err().to_string();
    assert!(
        error.contains("expected `)`, found the end (column 43)"),
        "{error}"
    );
    let error = graph.parse_infix("1 + * x").unwrap_err().to_string();
    assert!(
        error.contains("column 5") && error.contains("found `*`"),
        "{error}"
    );
    let error = graph.parse_infix("sine(x)").unwrap_err().to_string();
    assert!(error.contains("unknown function `sine`"), "{error}");
}

#[test]
fn infix_and_sexpr_build_the_same_node() {
    let mut graph = Graph::new();
    let a = graph.parse_infix("-x^2 + 2^x / y - powi(x, -1)").unwrap();
    let b = graph
        .parse_sexpr("(- (+ (neg (powi x 2)) (/ (powf 2 x) y)) (/ 1 x))")
        .unwrap();
    assert_eq!(graph.to_sexpr(a), graph.to_sexpr(b));
}

#[test]
fn mixed_partials_commute_numerically() {
    // ∂²/∂x∂y and ∂²/∂y∂x of sin(xy) = cos(xy) − xy·sin(xy) differ only in the order of
    // their operations; the two terms (≈ 0.61 and 0.72) cancel to ≈ −0.10, so a few ulp of
    // each term bound the difference: 8 ulp of the sum of the terms' magnitudes
    let mut graph = Graph::new();
    let xy = graph.parse_sexpr("(d y (d x (sin (* x y))))").unwrap();
    let yx = graph.parse_sexpr("(d x (d y (sin (* x y))))").unwrap();
    let values = graph
        .evaluate_f64(&[xy, yx], &[("x", 0.7), ("y", -1.3)])
        .unwrap();
    let xy = 0.7f64 * -1.3;
    let (first, second) = (xy.cos(), xy * xy.sin());
    let exact = first - second;
    let tolerance = 8.0 * f64::EPSILON * (first.abs() + second.abs());
    for value in values {
        assert!((value - exact).abs() <= tolerance, "{value} vs {exact}");
    }
}

rules! {
    // sums as linear combinations
    like_terms_cancel: "(+ x (- 1 x))" => "1";
    like_terms_merge: "(- (* 3 x) x)" => "(* 2 x)";
    common_factor_taken_out: "(+ (* a b) (* a c))" => "(* a (+ b c))";
    common_factor_with_coefficients: "(- (* a b) (* 2 (* a c)))" => "(* a (- b (* 2 c)))";
    constant_factor_hoisted: "(* x (* 2 y))" => "(* 2 (* x y))";
    tan_of_atan2_is_the_quotient: "(tan (atan2 y x))" => "(/ y x)";
    sum_without_cancellation_keeps_its_operands: "(+ (- a b) c)" => "(+ (- a b) c)";
}

rules! {
    // the derivative of a direction cosine a/hypot(a, b): (b/h)(a′(b/h) − (a/h)b′)/h, no
    // 1 − (a/h)² (which cancels where a ≫ b)
    d_direction_cosine: "(d x (/ x (hypot x y)))" =>
        "(* (/ y (hypot x y)) (/ (/ y (hypot x y)) (hypot x y)))";
    // constants of atan2 fold in bounded time: the common factor 2 leaves atan2(1, 1),
    // which is atan(1) (x = 1 > 0), not atan2(1, 1) again (it once looped forever)
    atan2_of_equal_constants: "(atan2 2 2)" => "(atan 1)";
    atan2_of_ones: "(atan2 1 1)" => "(atan 1)";
}
