//! The derivative rules: one table, one arm per primitive.
//!
//! `differential` gives `d f(args)` from the arguments, their derivatives and the node
//! itself (so `d exp(u) = exp(u) du` reuses the node). Adding a primitive means adding one
//! arm here, its name in [`super::ops`] and its numeric evaluation in [`super::eval`].
//!
//! The driver ([`Graph::derivative`]) applies the table bottom-up, memoized per
//! (node, variable), so derivatives of any order and mixed partial derivatives are repeated
//! applications that share every subexpression with the value and with each other.

use super::graph::{Graph, Id, Node};
use super::ops::{Binary, Comparison, Unary};
use crate::error::Error;

/// The highest derivative order [`Graph::try_derivatives`] computes.
pub const MAX_DERIVATIVE_ORDER: usize = 32;

/// The default size limit of [`Graph::try_derivatives`]: one million nodes (about 150 MB).
pub const MAX_NODES: usize = 1_000_000;

/// `d op(u)` given `u`, `du` and the node `f = op(u)`.
fn unary_differential(g: &mut Graph, op: Unary, u: Id, du: Id, f: Id) -> Id {
    let one = g.number(1.0);
    let derivative = match op {
        Unary::Neg => return g.neg(du),
        Unary::Sqrt => {
            let twice = g.add(f, f);
            return g.div(du, twice);
        }
        Unary::Cbrt => {
            let square = g.powi(f, 2);
            let three = g.number(3.0);
            let denominator = g.mul(three, square);
            return g.div(du, denominator);
        }
        Unary::Exp => f,
        Unary::Ln => return g.div(du, u),
        Unary::Sin => g.cos(u),
        Unary::Cos => {
            let sin = g.sin(u);
            g.neg(sin)
        }
        Unary::Tan => {
            let square = g.powi(f, 2);
            g.add(one, square)
        }
        Unary::Asin | Unary::Acos => {
            let square = g.powi(u, 2);
            let rest = g.sub(one, square);
            let root = g.sqrt(rest);
            let quotient = g.div(du, root);
            return if op == Unary::Asin {
                quotient
            } else {
                g.neg(quotient)
            };
        }
        Unary::Atan => {
            let square = g.powi(u, 2);
            let denominator = g.add(one, square);
            return g.div(du, denominator);
        }
        Unary::Sinh => g.cosh(u),
        Unary::Cosh => g.sinh(u),
        Unary::Tanh => sech_squared(g, u),
        Unary::Abs => {
            let zero = g.number(0.0);
            let minus_one = g.number(-1.0);
            g.select(Comparison::Less, u, zero, minus_one, one)
        }
    };
    g.mul(derivative, du)
}

/// sech²(u) = tanh′(u), in a form that neither cancels nor overflows, nor do its own
/// derivatives (the rules applied to it give tanh″, tanh‴, …):
/// - `1 / cosh²(u)` for |u| < 1 (not `1 − tanh²(u)`, which cancels to 0 for |u| > 19, where
///   sech² is still 1e-16 and more);
/// - `4t / (1 + t)²` with t = e^(−2|u|) ≤ e^(−2) elsewhere (where `1 / cosh²` and its
///   derivatives `−2 sinh / cosh³`, … are ∞/∞ = NaN once cosh overflows, |u| > 710): every
///   factor lies in [0, 4], no difference cancels (1 − t ≥ 0.86), and far out the value
///   underflows gracefully to 0.
fn sech_squared(g: &mut Graph, u: Id) -> Id {
    let one = g.number(1.0);
    let magnitude = g.abs(u);
    let cosh = g.cosh(u);
    let cosh_squared = g.powi(cosh, 2);
    let near = g.div(one, cosh_squared);
    let minus_two = g.number(-2.0);
    let exponent = g.mul(minus_two, magnitude);
    let t = g.exp(exponent);
    let four = g.number(4.0);
    let numerator = g.mul(four, t);
    let one_plus_t = g.add(one, t);
    let denominator = g.powi(one_plus_t, 2);
    let far = g.div(numerator, denominator);
    g.select(Comparison::Less, magnitude, one, near, far)
}

/// `d op(a, b)` given the arguments, their derivatives and the node `f = op(a, b)`.
fn binary_differential(g: &mut Graph, op: Binary, [a, b, da, db]: [Id; 4], f: Id) -> Id {
    match op {
        Binary::Add => g.add(da, db),
        Binary::Sub => g.sub(da, db),
        Binary::Mul => {
            let left = g.mul(da, b);
            let right = g.mul(a, db);
            g.add(left, right)
        }
        // (a/b)' = (a' - f b') / b with f = a/b: no b² (which overflows for |b| > 1e154 and
        // underflows for |b| < 1e-154 while the derivative itself is of ordinary size)
        Binary::Div if g.is_number(db, 0.0) => g.div(da, b),
        Binary::Div => {
            let right = g.mul(f, db);
            let numerator = g.sub(da, right);
            g.div(numerator, b)
        }
        // a constant exponent: (aᶜ)' = c aᶜ⁻¹ a' (finite at a = 0 for c ≥ 1, where
        // aᶜ · c a' / a is 0 / 0)
        Binary::Powf if g.is_number(db, 0.0) => {
            let one = g.number(1.0);
            let lower = g.sub(b, one);
            let power = g.powf(a, lower);
            let scaled = g.mul(b, power);
            g.mul(scaled, da)
        }
        // a constant base: (cᵇ)' = cᵇ ln c b'
        Binary::Powf if g.is_number(da, 0.0) => {
            let log = g.ln(a);
            let rate = g.mul(f, log);
            g.mul(rate, db)
        }
        // (aᵇ)' = aᵇ (b' ln a + b a' / a)
        Binary::Powf => {
            let log = g.ln(a);
            let left = g.mul(db, log);
            let ratio = g.div(da, a);
            let right = g.mul(b, ratio);
            let sum = g.add(left, right);
            g.mul(f, sum)
        }
        // atan2(a, b)' = (b a' - a b') / (a² + b²): one division for both partials
        Binary::Atan2 => {
            let left = g.mul(b, da);
            let right = g.mul(a, db);
            let numerator = g.sub(left, right);
            let a2 = g.powi(a, 2);
            let b2 = g.powi(b, 2);
            let denominator = g.add(a2, b2);
            g.div(numerator, denominator)
        }
        // hypot(a, b)' = (a/f) a' + (b/f) b': direction cosines times rates, never a product
        // of two lengths (which leaves f64 for lengths beyond 1e±154)
        Binary::Hypot => {
            let cos_a = g.div(a, f);
            let left = g.mul(cos_a, da);
            let cos_b = g.div(b, f);
            let right = g.mul(cos_b, db);
            g.add(left, right)
        }
    }
}

/// The other leg `b` when `h` is `hypot(a, b)` or `hypot(b, a)`.
fn direction_cosine(g: &Graph, a: Id, h: Id) -> Option<Id> {
    match *g.node(h) {
        Node::Binary(Binary::Hypot, p, q) if p == a => Some(q),
        Node::Binary(Binary::Hypot, p, q) if q == a => Some(p),
        _ => None,
    }
}

/// `d f` for any node `f`, given the derivatives of its children.
fn differential(g: &mut Graph, f: Id, known: &[Option<Id>]) -> Id {
    let derivative_of = |c: Id| known[c.index()].expect("children are differentiated first");
    match g.node(f).clone() {
        Node::Num(_) | Node::Sym(_) => unreachable!("leaves are handled by the driver"),
        // atan(a / b)' = atan2(a, b)' = (b a' - a b') / (a² + b²): no derivative of the quotient
        Node::Unary(Unary::Atan, u) if matches!(g.node(u), Node::Binary(Binary::Div, ..)) => {
            let Node::Binary(Binary::Div, a, b) = *g.node(u) else {
                unreachable!("matched above")
            };
            let quotient_rule = [a, b, derivative_of(a), derivative_of(b)];
            binary_differential(g, Binary::Atan2, quotient_rule, f)
        }
        // a direction cosine a / hypot(a, b) (what hypot's own rule is made of):
        // d(a/h) = (b/h) (a′ (b/h) − (a/h) b′) / h, not the quotient rule's
        // (a′ − (a/h) h′)/h, whose a′ (1 − (a/h)²) cancels where |a| ≫ |b| (7 digits lost
        // at a = 1000 b) while the true value (b/h)² a′ / h does not
        Node::Binary(Binary::Div, a, h) if direction_cosine(g, a, h).is_some() => {
            let b = direction_cosine(g, a, h).expect("matched above");
            let (da, db) = (derivative_of(a), derivative_of(b));
            let cos = f;
            let sin = g.div(b, h);
            let left = g.mul(da, sin);
            let right = g.mul(cos, db);
            let turn = g.sub(left, right);
            let rate = g.div(turn, h);
            g.mul(sin, rate)
        }
        Node::Unary(op, u) => unary_differential(g, op, u, derivative_of(u), f),
        Node::Binary(op, a, b) => {
            binary_differential(g, op, [a, b, derivative_of(a), derivative_of(b)], f)
        }
        // (uⁿ)' = n uⁿ⁻¹ u'
        Node::Powi(u, n) => {
            let lower = g.powi(u, n - 1);
            let factor = g.number(f64::from(n));
            let scaled = g.mul(factor, lower);
            g.mul(scaled, derivative_of(u))
        }
        // the derivative of the branch taken
        Node::Select(cmp, [a, b, then, otherwise]) => {
            g.select(cmp, a, b, derivative_of(then), derivative_of(otherwise))
        }
    }
}

impl Graph {
    /// The derivative of `f` with respect to the symbol `variable` (every other symbol is
    /// held constant).
    ///
    /// ```
    /// use mechdiff_core::symbolic::Graph;
    ///
    /// let mut graph = Graph::new();
    /// let f = graph.parse_sexpr("(* x (sin x))").unwrap();
    /// let df = graph.derivative(f, "x");
    /// assert_eq!(graph.to_sexpr(df), "(+ (sin x) (* x (cos x)))");
    /// ```
    pub fn derivative(&mut self, f: Id, variable: &str) -> Id {
        self.derivative_within(f, variable, usize::MAX)
            .expect("no limit on the number of nodes")
    }

    /// The derivative of `f`, or `None` as soon as the graph holds more than `max_nodes`.
    fn derivative_within(&mut self, f: Id, variable: &str, max_nodes: usize) -> Option<Id> {
        // children before parents: differentiate every reachable node in arena order
        let reachable = self.reachable(&[f]);
        let mut derivative = vec![None; f.index() + 1];
        let zero = self.number(0.0);
        for index in 0..=f.index() {
            if !reachable[index] {
                continue;
            }
            let id = Id::at(index);
            let key = (id, Box::<str>::from(variable));
            let d = if let Some(&cached) = self.derivative_cache.get(&key) {
                cached
            } else {
                let d = match self.node(id) {
                    Node::Num(_) => zero,
                    Node::Sym(name) => self.number(if **name == *variable { 1.0 } else { 0.0 }),
                    node => {
                        let children = node.children();
                        if children.iter().all(|c| derivative[c.index()] == Some(zero)) {
                            zero
                        } else {
                            differential(self, id, &derivative)
                        }
                    }
                };
                if self.len() > max_nodes {
                    return None;
                }
                self.derivative_cache.insert(key, d);
                d
            };
            derivative[index] = Some(d);
        }
        derivative[f.index()]
    }

    /// Like [`Graph::derivatives`], within the engine's limits: `order` at most
    /// [`MAX_DERIVATIVE_ORDER`], the graph at most `max_nodes` nodes (see [`MAX_NODES`]).
    ///
    /// ```
    /// use mechdiff_core::symbolic::{Graph, rules::MAX_NODES};
    ///
    /// let mut graph = Graph::new();
    /// let f = graph.parse_infix("exp(sin(x))").unwrap();
    /// assert_eq!(graph.try_derivatives(f, "x", 3, MAX_NODES).unwrap().len(), 4);
    /// assert!(graph.try_derivatives(f, "x", 1_000_000_000, MAX_NODES).is_err());
    /// assert!(graph.try_derivatives(f, "x", 30, 500).is_err());
    /// ```
    ///
    /// # Errors
    /// [`Error::DerivativeOrderTooHigh`] above [`MAX_DERIVATIVE_ORDER`];
    /// [`Error::ExpressionTooLarge`] when the graph outgrows `max_nodes` (it then holds
    /// partial derivatives that no output uses: emit only what was returned).
    pub fn try_derivatives(
        &mut self,
        f: Id,
        variable: &str,
        order: usize,
        max_nodes: usize,
    ) -> Result<Vec<Id>, Error> {
        if order > MAX_DERIVATIVE_ORDER {
            return Err(Error::DerivativeOrderTooHigh {
                order,
                limit: MAX_DERIVATIVE_ORDER,
            });
        }
        let mut all = vec![f];
        for k in 1..=order {
            let last = *all.last().expect("not empty");
            let next = self.derivative_within(last, variable, max_nodes).ok_or(
                Error::ExpressionTooLarge {
                    order: k,
                    limit: max_nodes,
                },
            )?;
            all.push(next);
        }
        Ok(all)
    }

    /// `f` and its derivatives of order 1 to `order` with respect to `variable`:
    /// `[f, f′, f″, …]`.
    pub fn derivatives(&mut self, f: Id, variable: &str, order: usize) -> Vec<Id> {
        let mut all = vec![f];
        for _ in 0..order {
            let last = *all.last().expect("not empty");
            all.push(self.derivative(last, variable));
        }
        all
    }

    /// The partial derivatives of `f` with respect to each of `variables`, in order.
    pub fn gradient(&mut self, f: Id, variables: &[&str]) -> Vec<Id> {
        variables.iter().map(|v| self.derivative(f, v)).collect()
    }
}
