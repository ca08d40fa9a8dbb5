//! The symbolic differentiation engine, shared by the proc-macro (`mechdiff-macros`) and the
//! run time (`mechdiff codegen`, scene formulas).
//!
//! - [`graph`]: the IR, a flat hash-consed arena ([`Graph`], [`Id`], [`Node`]);
//! - [`sexpr`] and [`infix`]: text forms, with positioned parse errors;
//! - [`simplify`] and [`sums`]: the simplifying constructors every node is built with;
//! - [`range`] and [`signs`]: what each node's range proves of its sign, and the
//!   simplifications a proven sign allows (`atan2`, `abs`);
//! - [`constants`]: named constants (`std::f64::consts::PI`, `pi`);
//! - [`rules`]: the one table of derivative rules and the differentiation driver;
//! - [`eval`] and `bigfloat`: evaluation in `f64`, in num-dual types, in arbitrary
//!   precision (feature `big-float`);
//! - [`taylor`]: truncated Taylor series, the limits at removable singularities;
//! - `emit` and [`count`]: Rust tokens, formatted source (feature `emit`), operation counts.
//!
//! ```
//! use mechdiff_core::symbolic::Graph;
//!
//! let mut graph = Graph::new();
//! let psi = graph.parse_infix("atan2(lambda*sin(phi), 1 - lambda*cos(phi))").unwrap();
//! let jet = graph.derivatives(psi, "phi", 2); // [ψ, ψ′, ψ″]
//! let values = graph.evaluate_f64(&jet, &[("phi", 0.0), ("lambda", 0.375)]).unwrap();
//! // ψ′(0) = λ / (1 - λ)
//! assert!((values[1] - 0.375 / 0.625).abs() < 1e-15);
//! ```
//!
//! See `docs/symbolic.md` for the rules table and how to add a primitive.

#[cfg(feature = "big-float")]
#[cfg_attr(docsrs, doc(cfg(feature = "big-float")))]
pub mod bigfloat;
pub mod constants;
pub mod count;
#[cfg(feature = "emit")]
#[cfg_attr(docsrs, doc(cfg(feature = "emit")))]
pub mod emit;
pub mod eval;
pub mod graph;
pub mod infix;
pub mod ops;
pub mod piecewise;
pub mod range;
pub mod rules;
pub mod sexpr;
pub mod signs;
pub mod simplify;
pub mod sums;
pub mod taylor;

#[cfg(feature = "big-float")]
pub use bigfloat::{BigArithmetic, BigReal};
pub use count::OperationCount;
#[cfg(feature = "emit")]
pub use emit::{Emission, format_rust};
pub use eval::{Arithmetic, DualArithmetic};
pub use graph::{Graph, Id, Node, Number};
pub use ops::{Binary, Comparison, Unary};
pub use range::Range;
