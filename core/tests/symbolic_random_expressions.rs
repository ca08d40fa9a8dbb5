//! For random expressions, the engine's symbolic derivatives (rule table + simplification)
//! agree with forward-mode automatic differentiation of the same expression (num-dual
//! `Dual3_64` evaluated through the IR): orders 1 to 3, and a mixed partial derivative with
//! `HyperDual64`.
//!
//! The expressions are built only from domain-safe compositions (`ln(2 + sin u)`,
//! `sqrt(1 + u²)`, division by `2 + cos u`, …), so every value is finite. Tolerance:
//! 1e-11 × max(1, |dual|): both sides are exact formulas in f64, but for random trees of
//! depth 4 the third derivative sums many terms of size up to ~1e3 that partly cancel, so a
//! few ulp of the largest term (1e3 × 1e-16 × ~100 terms) are allowed — far below any error
//! of a wrong rule, which shows up at O(1).

use mechdiff_core::symbolic::{Graph, Id};
#[cfg(feature = "jit")]
use mechdiff_core::trace::{JitProgram, Program};
use num_dual::{Dual3_64, HyperDual64};
use proptest::prelude::*;

#[derive(Clone, Debug)]
enum Tree {
    X,
    A,
    Constant(f64),
    Unary(&'static str, Box<Tree>),
    Binary(&'static str, Box<Tree>, Box<Tree>),
}

fn tree() -> impl Strategy<Value = Tree> {
    let leaf = prop_oneof![
        Just(Tree::X),
        Just(Tree::A),
        (-2.0f64..2.0).prop_map(|c| Tree::Constant((c * 4.0).round() / 4.0)),
    ];
    leaf.prop_recursive(4, 24, 2, |inner| {
        prop_oneof![
            (
                prop::sample::select(vec![
                    "sin",
                    "cos",
                    "atan",
                    "tanh",
                    "neg",
                    "exp_sin",
                    "ln_safe",
                    "sqrt_safe",
                    "cbrt_safe",
                    "asin_safe",
                    "acos_safe",
                    "sinh_sin",
                    "cosh_sin",
                    "abs_shift",
                    "tan_safe",
                    "square",
                    "cube",
                ]),
                inner.clone()
            )
                .prop_map(|(op, a)| Tree::Unary(op, Box::new(a))),
            (
                prop::sample::select(vec![
                    "+",
                    "-",
                    "*",
                    "div_safe",
                    "atan2",
                    "hypot_safe",
                    "powf_safe"
                ]),
                inner.clone(),
                inner
            )
                .prop_map(|(op, a, b)| Tree::Binary(op, Box::new(a), Box::new(b))),
        ]
    })
}

/// Builds the tree in the graph as an s-expression (domain-safe forms spelled out), with
/// `a` for the leaf `A` (a symbol or a number).
fn sexpr(tree: &Tree, a_leaf: &str) -> String {
    match tree {
        Tree::X => "x".into(),
        Tree::A => a_leaf.into(),
        Tree::Constant(c) => format!("{c}"),
        Tree::Unary(op, a) => {
            let a = sexpr(a, a_leaf);
            match *op {
                "exp_sin" => format!("(exp (sin {a}))"),
                "ln_safe" => format!("(ln (+ 2 (sin {a})))"),
                "sqrt_safe" => format!("(sqrt (+ 1 (powi {a} 2)))"),
                "cbrt_safe" => format!("(cbrt (+ 2 (cos {a})))"),
                "asin_safe" => format!("(asin (* 0.5 (sin {a})))"),
                "acos_safe" => format!("(acos (* 0.5 (cos {a})))"),
                "sinh_sin" => format!("(sinh (sin {a}))"),
                "cosh_sin" => format!("(cosh (sin {a}))"),
                "abs_shift" => format!("(abs (+ 3 (sin {a})))"),
                "tan_safe" => format!("(tan (* 0.5 (sin {a})))"),
                "square" => format!("(powi {a} 2)"),
                "cube" => format!("(powi (sin {a}) 3)"),
                name => format!("({name} {a})"),
            }
        }
        Tree::Binary(op, a, b) => {
            let (a, b) = (sexpr(a, a_leaf), sexpr(b, a_leaf));
            match *op {
                "div_safe" => format!("(/ {a} (+ 2 (cos {b})))"),
                "atan2" => format!("(atan2 {a} (+ 2 (cos {b})))"),
                // hypot is not differentiable at (0, 0) (a random tree such as
                // hypot(0·x, −0.75 + 0.75) lands there: dual numbers give 0/0 = NaN while the
                // simplified graph is the constant 0); the second argument is kept ≥ 1.
                "hypot_safe" => format!("(hypot {a} (+ 1 (powi {b} 2)))"),
                "powf_safe" => format!("(powf (+ 2 (sin {a})) (sin {b}))"),
                name => format!("({name} {a} {b})"),
            }
        }
    }
}

fn close(what: &str, symbolic: f64, dual: f64, expression: &str) {
    let tolerance = 1e-11 * dual.abs().max(1.0);
    assert!(
        (symbolic - dual).abs() <= tolerance,
        "{what}: symbolic {symbolic:e}, dual {dual:e} for {expression}"
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn symbolic_derivatives_agree_with_dual_numbers(
        t in tree(), x in -2.0f64..2.0, a in -2.0f64..2.0
    ) {
        let expression = sexpr(&t, "a");
        let mut graph = Graph::new();
        let f = graph.parse_sexpr(&expression).unwrap();
        let jet: Vec<Id> = graph.derivatives(f, "x", 3);
        let symbolic = graph.evaluate_f64(&jet, &[("x", x), ("a", a)]).unwrap();
        let seeded = [("x", Dual3_64::new(x, 1.0, 0.0, 0.0)), ("a", Dual3_64::from(a))];
        let dual = graph.evaluate_dual(&[f], &seeded).unwrap()[0];
        for (k, reference) in [dual.re, dual.v1, dual.v2, dual.v3].into_iter().enumerate() {
            close(&format!("order {k}"), symbolic[k], reference, &expression);
        }

        let dx = graph.derivative(f, "x");
        let mixed = graph.derivative(dx, "a");
        let symbolic = graph.evaluate_f64(&[mixed], &[("x", x), ("a", a)]).unwrap()[0];
        let seeded = [
            ("x", HyperDual64::new(x, 1.0, 0.0, 0.0)),
            ("a", HyperDual64::new(a, 0.0, 1.0, 0.0)),
        ];
        let dual = graph.evaluate_dual(&[f], &seeded).unwrap()[0];
        close("∂²/∂x∂a", symbolic, dual.eps1eps2, &expression);
    }
}

#[cfg(feature = "jit")]
proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// The run-time evaluator compiled to native code computes the interpreter's bits, and
    /// both those of the graph's own `f64` evaluation, for a random expression in `x` and
    /// its derivatives 1 to 3 (no tolerance: all three round each operation once, in the
    /// same order, and call the same functions for the rest).
    #[test]
    fn compiled_and_interpreted_programs_compute_the_graphs_bits(
        t in tree(), a in -2.0f64..2.0, xs in prop::collection::vec(-2.0f64..2.0, 4)
    ) {
        let expression = sexpr(&t, &format!("{a:?}"));
        let mut graph = Graph::new();
        let f = graph.parse_sexpr(&expression).unwrap();
        let jet: Vec<Id> = graph.derivatives(f, "x", 3);
        let program = Program::compile(&graph, &jet, "x").unwrap();
        let jit = JitProgram::compile(&program).unwrap();
        let (mut registers, mut interpreted, mut compiled) =
            (program.registers(), [0.0; 4], [0.0; 4]);
        for x in xs {
            let graph_values = graph.evaluate_f64(&jet, &[("x", x)]).unwrap();
            program.evaluate(x, &mut registers, &mut interpreted);
            jit.evaluate(x, &mut compiled);
            for k in 0..4 {
                let bits = [graph_values[k], interpreted[k], compiled[k]].map(f64::to_bits);
                prop_assert!(
                    bits[0] == bits[1] && bits[1] == bits[2],
                    "order {k} of {expression} at x = {x}: graph {:e}, interpreted {:e}, \
                     compiled {:e}",
                    graph_values[k], interpreted[k], compiled[k]
                );
            }
        }
    }
}

/// Any formula, domain or not: every primitive on any arguments, with constants that make
/// equal, zero and negative operands likely (`atan2(2, 2)`, `powf(0, 0)`, `ln(-1)`).
fn any_tree() -> impl Strategy<Value = Tree> {
    let leaf = prop_oneof![
        Just(Tree::X),
        Just(Tree::A),
        prop::sample::select(vec![0.0, 1.0, 2.0, 0.5, -1.0, 3.0, 1e300, 1e-300])
            .prop_map(Tree::Constant),
    ];
    let unary: Vec<&'static str> = mechdiff_core::symbolic::Unary::ALL
        .iter()
        .map(|op| op.name())
        .collect();
    let binary: Vec<&'static str> = mechdiff_core::symbolic::Binary::ALL
        .iter()
        .map(|op| op.name())
        .collect();
    leaf.prop_recursive(5, 32, 2, move |inner| {
        prop_oneof![
            (prop::sample::select(unary.clone()), inner.clone())
                .prop_map(|(op, a)| Tree::Unary(op, Box::new(a))),
            (prop::sample::select(binary.clone()), inner.clone(), inner)
                .prop_map(|(op, a, b)| Tree::Binary(op, Box::new(a), Box::new(b))),
        ]
    })
}

/// The plain s-expression of a tree (no domain-safe forms).
fn plain_sexpr(tree: &Tree) -> String {
    match tree {
        Tree::X => "x".into(),
        Tree::A => "a".into(),
        Tree::Constant(c) => format!("{c:?}"),
        Tree::Unary(op, a) => format!("({op} {})", plain_sexpr(a)),
        Tree::Binary(op, a, b) => format!("({op} {} {})", plain_sexpr(a), plain_sexpr(b)),
    }
}

/// What a random formula may take at most, in wall-clock time, to be parsed, simplified,
/// differentiated three times and evaluated: each takes milliseconds (a debug build, a
/// loaded machine: well under 100 ms); 5 s is a hang, not a slow case (`atan2(c, c)` with
/// c > 0 once never returned).
const WALL_CLOCK: std::time::Duration = std::time::Duration::from_secs(5);

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Every formula is built, simplified, differentiated to order 3 and evaluated in bounded
    /// time, whatever its constants and domains (its values may be NaN: only termination is
    /// asserted here).
    #[test]
    fn any_formula_is_simplified_and_differentiated_in_bounded_time(
        t in any_tree(), x in -2.0f64..2.0, a in -2.0f64..2.0
    ) {
        let expression = plain_sexpr(&t);
        let (done, wait) = std::sync::mpsc::channel();
        let text = expression.clone();
        std::thread::spawn(move || {
            let mut graph = Graph::new();
            let f = graph.parse_sexpr(&text).unwrap();
            let jet = graph.derivatives(f, "x", 3);
            let _ = graph.evaluate_f64(&jet, &[("x", x), ("a", a)]);
            let _ = done.send(());
        });
        prop_assert!(
            wait.recv_timeout(WALL_CLOCK).is_ok(),
            "{expression} took more than {WALL_CLOCK:?} (or panicked)"
        );
    }
}

/// The formulas of issue 22, in the infix syntax of scenes: constant `atan2`s fold or
/// evaluate, promptly, to their value (π/4 × 10 to 1 ulp of the f64 evaluation).
#[test]
fn constant_atan2_is_built_promptly_with_its_value() {
    for (formula, value) in [
        ("10*atan2(1,1)", 10.0 * std::f64::consts::FRAC_PI_4),
        ("atan2(2, 2)", std::f64::consts::FRAC_PI_4),
        ("atan2(0.5*3, 1.5)", std::f64::consts::FRAC_PI_4),
        ("atan2(-3, -3)", -3.0 * std::f64::consts::FRAC_PI_4),
        ("atan2(1e300, 1e300) + x", std::f64::consts::FRAC_PI_4),
    ] {
        let (done, wait) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let mut graph = Graph::new();
            let f = graph.parse_infix(formula).unwrap();
            let jet = graph.derivatives(f, "x", 3);
            let _ = done.send(graph.evaluate_f64(&jet, &[("x", 0.0)]).unwrap());
        });
        let values = wait.recv_timeout(WALL_CLOCK).expect(formula);
        assert!(
            (values[0] - value).abs() <= f64::EPSILON * value.abs(),
            "{formula}: {values:?}"
        );
    }
}
