//! Numeric evaluation of expressions: in `f64`, in any num-dual type, in arbitrary precision.
//!
//! An [`Arithmetic`] says how to compute each primitive on one kind of value; evaluation
//! walks the arena once, children before parents, computing only the nodes the outputs need.

use std::marker::PhantomData;

use crate::Scalar;

use super::constants::{self, Formula};
use super::graph::{Graph, Id, Node};
use super::ops::{Binary, Comparison, Unary};
use crate::error::Error;

/// How to compute each primitive on one kind of value.
pub trait Arithmetic {
    /// The values computed with.
    type Value: Clone;

    /// The constant `c` (an exact `f64`).
    fn constant(&mut self, c: f64) -> Self::Value;
    /// `op(u)`.
    fn unary(&mut self, op: Unary, u: &Self::Value) -> Self::Value;
    /// `op(a, b)`.
    fn binary(&mut self, op: Binary, a: &Self::Value, b: &Self::Value) -> Self::Value;
    /// `u.powi(n)`.
    fn powi(&mut self, u: &Self::Value, n: i32) -> Self::Value;
    /// Whether `a <cmp> b` holds (on the real part: a piecewise function takes the branch
    /// of its value).
    fn compare(&mut self, cmp: Comparison, a: &Self::Value, b: &Self::Value) -> bool;

    /// What went wrong in the last primitive computed (a 0/0, an infinite derivative), if
    /// anything; cleared by the call. [`Graph::evaluate`] reports it as an error when the
    /// node's value reaches an output (not when it is in a piecewise branch not taken).
    fn take_trouble(&mut self) -> Option<Trouble> {
        None
    }

    /// The named constant `name` (`std::f64::consts::PI`, …; see [`super::constants`]),
    /// computed from its formula in this arithmetic's precision; `None` if `name` is not one.
    fn named_constant(&mut self, name: &str) -> Option<Self::Value> {
        let (_, formula) = constants::lookup(name)?;
        Some(match formula {
            Formula::PiTimes(a, b) => {
                let one = self.constant(1.0);
                let quarter = self.unary(Unary::Atan, &one);
                let scale = self.constant(4.0 * a);
                let pi_a = self.binary(Binary::Mul, &scale, &quarter);
                let b = self.constant(b);
                self.binary(Binary::Div, &pi_a, &b)
            }
            Formula::Exp(a) => {
                let a = self.constant(a);
                self.unary(Unary::Exp, &a)
            }
            Formula::Sqrt(a) => {
                let a = self.constant(a);
                self.unary(Unary::Sqrt, &a)
            }
            Formula::Ln(a) => {
                let a = self.constant(a);
                self.unary(Unary::Ln, &a)
            }
        })
    }
}

/// A point where a primitive's result is not defined (see [`Arithmetic::take_trouble`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Trouble {
    /// 0/0: the value is undefined (a removable singularity if the quotient has a limit).
    ZeroOverZero,
    /// `powf` at a base of exactly 0 in dual numbers (`exp(v·ln 0)`: NaN derivatives).
    PowerOfZero,
    /// The derivative of `op` is infinite at `at` (asin and acos at ±1, sqrt and cbrt at 0).
    InfiniteDerivative {
        /// The function.
        op: Unary,
        /// Its argument.
        at: f64,
    },
}

/// Evaluation in a num-dual type `D` (and in `f64`, which is one).
#[derive(Debug, Clone, Copy, Default)]
pub struct DualArithmetic<D> {
    trouble: Option<Trouble>,
    scalar: PhantomData<D>,
}

impl<D> DualArithmetic<D> {
    /// The arithmetic of `D`.
    pub fn new() -> Self {
        DualArithmetic {
            trouble: None,
            scalar: PhantomData,
        }
    }
}

impl<D: Scalar> Arithmetic for DualArithmetic<D> {
    type Value = D;

    fn constant(&mut self, c: f64) -> D {
        D::from(c)
    }

    fn unary(&mut self, op: Unary, u: &D) -> D {
        let x = u.re();
        // Derivatives of these are 1/√(1 − x²), 1/(2√x) and 1/(3∛x²): infinite at the
        // domain's edge or at 0, and NaN once multiplied by a zero derivative of u.
        let edge = match op {
            Unary::Asin | Unary::Acos => x.abs() == 1.0,
            Unary::Sqrt | Unary::Cbrt => x == 0.0,
            _ => false,
        };
        if edge && D::NDERIV > 0 {
            self.trouble = Some(Trouble::InfiniteDerivative { op, at: x });
        }
        match op {
            Unary::Neg => -*u,
            Unary::Sqrt => u.sqrt(),
            Unary::Cbrt => u.cbrt(),
            Unary::Exp => u.exp(),
            Unary::Ln => u.ln(),
            Unary::Sin => u.sin(),
            Unary::Cos => u.cos(),
            Unary::Tan => u.tan(),
            Unary::Asin => u.asin(),
            Unary::Acos => u.acos(),
            Unary::Atan => u.atan(),
            Unary::Sinh => u.sinh(),
            Unary::Cosh => u.cosh(),
            // finite derivatives far out (num-dual's sinh/cosh is NaN past 710)
            Unary::Tanh => crate::tanh(*u),
            Unary::Abs => {
                if u.re() < 0.0 {
                    -*u
                } else {
                    *u
                }
            }
        }
    }

    fn binary(&mut self, op: Binary, a: &D, b: &D) -> D {
        match op {
            Binary::Add => *a + *b,
            Binary::Sub => *a - *b,
            Binary::Mul => *a * *b,
            Binary::Div => {
                if a.re() == 0.0 && b.re() == 0.0 {
                    self.trouble = Some(Trouble::ZeroOverZero);
                }
                *a / *b
            }
            Binary::Powf => {
                if a.re() == 0.0 && D::NDERIV > 0 {
                    self.trouble = Some(Trouble::PowerOfZero);
                }
                a.powd(*b)
            }
            // Plain f64: libm's atan2, as the emitted code calls it (bit for bit). Dual
            // numbers: the project's atan2, exact derivatives on the y axis too (num-dual's
            // differentiates atan(y/x): NaN at x = 0).
            Binary::Atan2 => {
                use std::any::Any;
                let (y, x) = (a as &dyn Any, b as &dyn Any);
                if let (Some(y), Some(x)) = (y.downcast_ref::<f64>(), x.downcast_ref::<f64>())
                    && let Some(angle) = (&y.atan2(*x) as &dyn Any).downcast_ref::<D>()
                {
                    return *angle;
                }
                crate::atan2(*a, *b)
            }
            // Scaled: no overflow of x² + y² for arguments near f64::MAX.
            Binary::Hypot => crate::scalar::hypot(*a, *b),
        }
    }

    fn powi(&mut self, u: &D, n: i32) -> D {
        u.powi(n)
    }

    fn compare(&mut self, cmp: Comparison, a: &D, b: &D) -> bool {
        cmp.holds(&a.re(), &b.re())
    }

    fn take_trouble(&mut self) -> Option<Trouble> {
        self.trouble.take()
    }

    /// The `f64` value of the constant (as the emitted code's `std::f64::consts` path).
    fn named_constant(&mut self, name: &str) -> Option<D> {
        constants::lookup(name).map(|(value, _)| D::from(value))
    }
}

impl Graph {
    /// The first node needed by `outputs` that has no variables (named constants aside) and
    /// whose `f64` value is not finite (`0 / 0`), with that value; `None` if there is none.
    pub fn non_finite_constant(&self, outputs: &[Id]) -> Option<(Id, f64)> {
        let needed = self.reachable(outputs);
        let mut values: Vec<Option<f64>> = vec![None; needed.len()];
        let mut f64s = DualArithmetic::<f64>::new();
        for (index, node) in self.nodes().iter().enumerate() {
            if !needed[index] {
                continue;
            }
            let of = |id: &Id| values[id.index()];
            let value = match node {
                Node::Num(n) => Some(n.value()),
                Node::Sym(name) => f64s.named_constant(name),
                Node::Unary(op, a) => of(a).map(|a| f64s.unary(*op, &a)),
                Node::Binary(op, a, b) => of(a).zip(of(b)).map(|(a, b)| f64s.binary(*op, &a, &b)),
                Node::Powi(a, n) => of(a).map(|a| a.powi(*n)),
                Node::Select(cmp, [a, b, t, e]) => match (of(a), of(b)) {
                    (Some(a), Some(b)) => of(if cmp.holds(&a, &b) { t } else { e }),
                    _ => None,
                },
            };
            if let Some(v) = value.filter(|v| !v.is_finite()) {
                return Some((Id::at(index), v));
            }
            values[index] = value;
        }
        None
    }

    /// Evaluates `outputs` with `arithmetic`; `value_of` gives the value of each symbol.
    ///
    /// # Errors
    /// [`Error::UnboundSymbol`] if a symbol the outputs depend on has no value.
    pub fn evaluate<A: Arithmetic>(
        &self,
        arithmetic: &mut A,
        outputs: &[Id],
        value_of: &dyn Fn(&str) -> Option<A::Value>,
    ) -> Result<Vec<A::Value>, Error> {
        let needed = self.reachable(outputs);
        let mut values: Vec<Option<A::Value>> = vec![None; needed.len()];
        let mut troubles: Vec<(usize, Trouble)> = Vec::new();
        // Per piecewise node, whether its condition held (the branch taken).
        let mut taken: Vec<Option<bool>> = vec![None; needed.len()];
        let get = |values: &[Option<A::Value>], id: Id| -> A::Value {
            values[id.index()]
                .clone()
                .expect("children are evaluated before their parents")
        };
        for (index, node) in self.nodes().iter().enumerate() {
            if !needed[index] {
                continue;
            }
            let value = match node {
                Node::Num(n) => arithmetic.constant(n.value()),
                Node::Sym(name) => value_of(name)
                    .or_else(|| arithmetic.named_constant(name))
                    .ok_or_else(|| Error::UnboundSymbol {
                        symbol: name.to_string(),
                    })?,
                Node::Unary(op, a) => arithmetic.unary(*op, &get(&values, *a)),
                Node::Binary(op, a, b) => {
                    arithmetic.binary(*op, &get(&values, *a), &get(&values, *b))
                }
                Node::Powi(a, n) => arithmetic.powi(&get(&values, *a), *n),
                Node::Select(cmp, [a, b, t, e]) => {
                    let holds = arithmetic.compare(*cmp, &get(&values, *a), &get(&values, *b));
                    taken[index] = Some(holds);
                    get(&values, if holds { *t } else { *e })
                }
            };
            if let Some(trouble) = arithmetic.take_trouble() {
                troubles.push((index, trouble));
            }
            values[index] = Some(value);
        }
        if !troubles.is_empty() {
            self.live_trouble(outputs, &taken, &troubles)?;
        }
        Ok(outputs.iter().map(|&id| get(&values, id)).collect())
    }

    /// The first of `troubles` whose node's value reaches an output through the piecewise
    /// branches taken, as an error.
    fn live_trouble(
        &self,
        outputs: &[Id],
        taken: &[Option<bool>],
        troubles: &[(usize, Trouble)],
    ) -> Result<(), Error> {
        let mut live = vec![false; self.len()];
        let mut stack: Vec<Id> = outputs.to_vec();
        while let Some(id) = stack.pop() {
            if std::mem::replace(&mut live[id.index()], true) {
                continue;
            }
            match (self.node(id), taken[id.index()]) {
                (Node::Select(_, [a, b, t, e]), Some(holds)) => {
                    stack.extend([*a, *b, if holds { *t } else { *e }]);
                }
                (node, _) => stack.extend(node.children()),
            }
        }
        let Some(&(index, trouble)) = troubles.iter().find(|(i, _)| live[*i]) else {
            return Ok(());
        };
        let mut expression = self.to_sexpr(Id::at(index));
        if expression.chars().count() > 80 {
            expression = expression.chars().take(77).collect::<String>() + "...";
        }
        Err(match trouble {
            Trouble::ZeroOverZero => Error::ZeroOverZero { expression },
            Trouble::PowerOfZero => Error::PowerOfZero { expression },
            Trouble::InfiniteDerivative { op, at } => Error::InfiniteDerivative {
                function: op.name().to_owned(),
                at,
                expression,
            },
        })
    }

    /// Evaluates `outputs` in `f64` with the symbol values `bindings`.
    ///
    /// ```
    /// use mechdiff_core::symbolic::Graph;
    ///
    /// let mut graph = Graph::new();
    /// let f = graph.parse_sexpr("(* a (sin x))").unwrap();
    /// let values = graph.evaluate_f64(&[f], &[("a", 2.0), ("x", 0.5)]).unwrap();
    /// assert_eq!(values[0], 2.0 * 0.5f64.sin());
    /// ```
    ///
    /// # Errors
    /// [`Error::UnboundSymbol`] if a symbol has no value.
    pub fn evaluate_f64(
        &self,
        outputs: &[Id],
        bindings: &[(&str, f64)],
    ) -> Result<Vec<f64>, Error> {
        self.evaluate_dual(outputs, bindings)
    }

    /// Evaluates `outputs` in the num-dual type `D` with the symbol values `bindings`.
    ///
    /// # Errors
    /// [`Error::UnboundSymbol`] if a symbol has no value.
    pub fn evaluate_dual<D: Scalar>(
        &self,
        outputs: &[Id],
        bindings: &[(&str, D)],
    ) -> Result<Vec<D>, Error> {
        let lookup = |name: &str| bindings.iter().find(|(n, _)| *n == name).map(|(_, v)| *v);
        self.evaluate(&mut DualArithmetic::<D>::new(), outputs, &lookup)
    }
}
