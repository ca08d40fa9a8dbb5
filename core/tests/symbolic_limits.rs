//! The symbolic engine's limits and costs: sums cost near-linear memory in their size, the
//! derivative order and graph size are bounded with errors, named constants are exact.

use mechdiff_core::Error;
#[cfg(feature = "big-float")]
use mechdiff_core::symbolic::BigReal;
use mechdiff_core::symbolic::Graph;
use mechdiff_core::symbolic::rules::{MAX_DERIVATIVE_ORDER, MAX_NODES};

/// Nodes stored, characters of emitted code and of its longest statement for the sum of
/// `n` distinct terms `sin(k·x)`, differentiated twice.
#[cfg(feature = "emit")]
fn cost_of_sum(n: usize) -> (usize, usize, usize) {
    let formula: Vec<String> = (1..=n).map(|k| format!("sin({k}*x)")).collect();
    let mut graph = Graph::new();
    let value = graph.parse_infix(&formula.join(" + ")).unwrap();
    let outputs = graph.try_derivatives(value, "x", 2, MAX_NODES).unwrap();
    let emission = graph.emit(&outputs, &["value", "d1", "d2"]);
    let text: usize = emission
        .statements
        .iter()
        .chain(&emission.results)
        .map(|t| t.to_string().len())
        .sum();
    let longest = emission
        .statements
        .iter()
        .chain(&emission.results)
        .map(|t| t.to_string().len())
        .max()
        .unwrap();
    (graph.len(), text, longest)
}

#[test]
#[cfg(feature = "emit")]
fn a_sum_of_distinct_terms_costs_linear_memory() {
    // doubling the terms doubles the nodes and the code (before the fix, emission kept
    // every partial sum's tokens: quadratic). 2.1: linear plus the few shared nodes.
    let (nodes_1, text_1, longest_1) = cost_of_sum(400);
    let (nodes_2, text_2, longest_2) = cost_of_sum(800);
    assert!(
        nodes_2 as f64 / nodes_1 as f64 <= 2.1,
        "{nodes_1} -> {nodes_2} nodes"
    );
    // the code's text grows a little faster: its temporaries' names get longer (t99, t999)
    assert!(
        text_2 as f64 / text_1 as f64 <= 2.3,
        "{text_1} -> {text_2} characters"
    );
    // no statement grows with the sum (the emitter held every partial sum's tokens while
    // writing one n-term expression: memory ~n²); 1.2: longer temporary names only
    assert!(
        longest_2 as f64 / longest_1 as f64 <= 1.2,
        "longest statement {longest_1} -> {longest_2} characters"
    );
}

#[test]
fn like_terms_within_a_long_sum_still_cancel() {
    // x + y1 + … + y40 - x = y1 + … + y40: within the look-through of one simplification
    let mut graph = Graph::new();
    let ys: Vec<String> = (1..=40).map(|k| format!("y{k}")).collect();
    let with_x = graph
        .parse_infix(&format!("x + {} - x", ys.join(" + ")))
        .unwrap();
    assert!(!graph.symbols(&[with_x]).contains(&"x"), "x cancels");
    let d = graph.derivative(with_x, "x");
    assert!(graph.is_number(d, 0.0));
}

#[test]
fn derivative_order_and_graph_size_are_bounded() {
    let mut graph = Graph::new();
    let f = graph.parse_infix("exp(sin(x)) / (1 + x^2)").unwrap();
    match graph.try_derivatives(f, "x", MAX_DERIVATIVE_ORDER + 1, MAX_NODES) {
        Err(Error::DerivativeOrderTooHigh { order, limit }) => {
            assert_eq!((order, limit), (33, 32));
        }
        other => panic!("expected DerivativeOrderTooHigh, got {other:?}"),
    }
    // each derivative of this quotient is larger than the one before: 2000 nodes are
    // outgrown before order 32
    match graph.try_derivatives(f, "x", 32, 2000) {
        Err(Error::ExpressionTooLarge { order, limit: 2000 }) => assert!(order < 32),
        other => panic!("expected ExpressionTooLarge, got {other:?}"),
    }
}

#[test]
#[cfg(feature = "big-float")]
fn pi_is_pi_in_f64_and_in_256_bit_evaluation() {
    let mut graph = Graph::new();
    let pi = graph.parse_infix("pi").unwrap();
    let tau = graph.parse_infix("std::f64::consts::TAU").unwrap();
    let values = graph.evaluate_f64(&[pi, tau], &[]).unwrap();
    // exactly the std constants (the emitted code names them)
    assert_eq!(values, [std::f64::consts::PI, std::f64::consts::TAU]);
    let big = graph.evaluate_big(&[pi], &[], 256).unwrap();
    // π to 60 digits (OEIS A000796): agreement to 1e-58 relative shows π is computed in
    // 256 bits, not taken from the f64 value (which differs by 1.2e-16 relative)
    let reference = BigReal::parse(
        "3.14159265358979323846264338327950288419716939937510582097494",
        256,
    )
    .unwrap();
    assert!(big[0].relative_difference(&reference) < 1e-58);
    // a constant of the formula: d/dx (pi x) = pi
    let f = graph.parse_infix("PI * x").unwrap();
    let d = graph.derivative(f, "x");
    assert_eq!(d, pi);
}

#[test]
fn a_derivative_with_a_constant_zero_over_zero_is_found() {
    let mut graph = Graph::new();
    let zero = graph.number(0.0);
    let nan = graph.intern(mechdiff_core::symbolic::Node::Binary(
        mechdiff_core::symbolic::Binary::Div,
        zero,
        zero,
    ));
    let x = graph.symbol("x");
    let f = graph.mul(x, nan);
    let (id, value) = graph.non_finite_constant(&[f]).unwrap();
    assert_eq!(id, nan);
    assert!(value.is_nan());
    let g = graph.parse_infix("x * sin(1/3)").unwrap();
    assert!(graph.non_finite_constant(&[g]).is_none());
}
