//! Simplifying constructors: every node enters the [`Graph`] through these.
//!
//! Rules, applied locally as a node is built (so the derivative expressions are simplified
//! as they are produced, and never grow first):
//! - constant folding, only where the `f64` result is **exact** (`2 * 3`, `1 - 0.375`, but
//!   not `0.1 + 0.2` or `sin(1)`), so that no rounding is frozen into a constant and the
//!   arbitrary-precision evaluation stays exact;
//! - identities: `x + 0`, `x - 0`, `0 - x`, `x * 1`, `x * -1`, `x / 1`, `x - x = 0`,
//!   `x / x = 1`, `x + x = 2 * x`, `--x = x`, `-(a - b) = b - a`, `a + -b = a - b`;
//! - `0 * x = 0` and `0 / x = 0`: "safe" here because `x` is always part of the value or of a
//!   lower derivative that is returned too, so a non-finite `x` stays visible there (and the
//!   derivative of a constant is then 0, not `0 * inf = NaN`);
//! - negation is pulled out of products and quotients, negative factors become `neg`;
//! - `tan(atan2(a, b)) = a / b`, `tan(atan(x)) = x`;
//! - `ln(exp(s)) = s`, `ln(uⁿ) = n ln u` (n odd) or `n ln |u|` (n even), `ln(u^c) = c ln u`
//!   for a constant c, `ln(u^v) = v ln u` for u known positive;
//! - common factors of a quotient cancel: `(x·u)/u = x`, `x·u/uⁿ = x/uⁿ⁻¹`,
//!   `(x·u)/(y·u) = x/y`, `(x·√u)/u = x/√u` (and `x·√u·(1/u)` likewise), `(x·(p/c))/(q/c) = (x·p)/q`;
//! - what a proven sign allows (`|u| = u` for u ≥ 0, `atan2` without a positive factor its
//!   coordinates share, `atan2(y, x) = atan(y / x)` for x > 0): see [`super::signs`];
//! - integer powers: `x * x = x²`, `xᵐ · xⁿ = xᵐ⁺ⁿ`, `(xᵐ)ⁿ = xᵐⁿ`, `x⁰ = 1`, `x¹ = x`,
//!   `x⁻ⁿ = 1 / xⁿ`, `(-x)ⁿ = ±xⁿ`, `x.powf(n)` with an integer constant `n` is `x.powi(n)`;
//! - commutative operands are put in a canonical order (constants first, then by id), so
//!   `a * b` and `b * a` are one node.
//!
//! `sin` and `cos` of one argument are computed once by the emitter (`sin_cos`).
//!
//! **Bounded.** One construction (a constructor called from outside, with every constructor
//! its rules call in turn) enters at most [`MAX_REWRITES`] constructors, nested at most
//! [`MAX_REWRITE_DEPTH`] deep; past that budget a node is stored as it is, correct but not
//! simplified. So a set of rules that rewrite a node into itself (as `atan2(c, c)` once did,
//! through the factor 1 of `atan2(1, 1)`) cannot loop forever or overflow the stack.

use super::graph::{Graph, Id, Node};
use super::ops::{Binary, Comparison, Unary};

fn exact_mul(x: f64, y: f64) -> Option<f64> {
    let p = x * y;
    (p.is_finite() && x.mul_add(y, -p) == 0.0).then_some(p)
}

fn exact_div(x: f64, y: f64) -> Option<f64> {
    let q = x / y;
    (y != 0.0 && q.is_finite() && q.mul_add(y, -x) == 0.0).then_some(q)
}

fn exact_powi(x: f64, n: i32) -> Option<f64> {
    let mut p = 1.0;
    for _ in 0..n.unsigned_abs() {
        p = exact_mul(p, x)?;
    }
    if n < 0 { exact_div(1.0, p) } else { Some(p) }
}

/// The value of `op(c)` when it is exact in `f64`.
fn exact_unary(op: Unary, c: f64) -> Option<f64> {
    match op {
        Unary::Neg => Some(-c),
        Unary::Abs => Some(c.abs()),
        Unary::Sqrt => {
            let r = c.sqrt();
            (c >= 0.0 && r.mul_add(r, -c) == 0.0).then_some(r)
        }
        Unary::Cbrt => {
            let r = c.cbrt();
            (exact_powi(r, 3) == Some(c)).then_some(r)
        }
        Unary::Sin
        | Unary::Tan
        | Unary::Asin
        | Unary::Atan
        | Unary::Sinh
        | Unary::Tanh
        | Unary::Exp
        | Unary::Cos
        | Unary::Cosh
            if c == 0.0 =>
        {
            Some(if matches!(op, Unary::Exp | Unary::Cos | Unary::Cosh) {
                1.0
            } else {
                0.0
            })
        }
        Unary::Ln | Unary::Acos if c == 1.0 => Some(0.0),
        _ => None,
    }
}

/// How many simplifying constructors one construction may enter in all (its own and every
/// nested one): far above what a real expression needs (at most 49 in the test suite, the
/// scenes' generated code included), small enough that a cycle of rewrites that never ends
/// (a rule undoing another) costs a millisecond, not forever.
pub const MAX_REWRITES: usize = 10_000;

/// How deeply simplifying constructors may nest: far above what a real expression needs (at
/// most 7 in the test suite), low enough that the nesting stays well within a thread's
/// stack.
pub const MAX_REWRITE_DEPTH: usize = 64;

impl Graph {
    /// `rules(self)`, the simplification of the node `raw`, within the budget of the
    /// simplification under way ([`MAX_REWRITES`], [`MAX_REWRITE_DEPTH`]); past it, `raw`
    /// is stored as it is (a correct node, only not simplified), so every construction ends.
    fn rewrite(&mut self, raw: Node, rules: impl FnOnce(&mut Self) -> Id) -> Id {
        let budget = self.rewriting;
        if budget.depth >= MAX_REWRITE_DEPTH || budget.spent >= MAX_REWRITES {
            return self.intern(raw);
        }
        self.rewriting.depth += 1;
        self.rewriting.spent += 1;
        let id = rules(self);
        self.rewriting.depth -= 1;
        if self.rewriting.depth == 0 {
            self.rewriting.spent = 0;
        }
        id
    }
}

macro_rules! unary_constructors {
    ($($fname:ident => $op:ident,)*) => {
        impl Graph {
            $(
                #[doc = concat!("`", stringify!($fname), "(u)`, simplified.")]
                pub fn $fname(&mut self, u: Id) -> Id {
                    self.unary(Unary::$op, u)
                }
            )*
        }
    };
}

unary_constructors! {
    sqrt => Sqrt, cbrt => Cbrt, exp => Exp, ln => Ln, sin => Sin, cos => Cos, tan => Tan,
    asin => Asin, acos => Acos, atan => Atan, sinh => Sinh, cosh => Cosh, tanh => Tanh,
    abs => Abs,
}

impl Graph {
    fn constant_pair(&self, a: Id, b: Id) -> Option<(f64, f64)> {
        Some((self.as_number(a)?, self.as_number(b)?))
    }

    fn negated(&self, id: Id) -> Option<Id> {
        match self.node(id) {
            Node::Unary(Unary::Neg, x) => Some(*x),
            _ => None,
        }
    }

    fn ordered(&self, a: Id, b: Id) -> (Id, Id) {
        let key = |id: Id| (self.as_number(id).is_none(), id);
        if key(a) <= key(b) { (a, b) } else { (b, a) }
    }

    /// `a + b`, simplified (a linear combination: see [`super::sums`]).
    pub fn add(&mut self, a: Id, b: Id) -> Id {
        self.rewrite(Node::Binary(Binary::Add, a, b), |g| g.sum(a, 1.0, b))
    }

    /// `a - b`, simplified (a linear combination: see [`super::sums`]).
    pub fn sub(&mut self, a: Id, b: Id) -> Id {
        self.rewrite(Node::Binary(Binary::Sub, a, b), |g| g.sum(a, -1.0, b))
    }

    /// `a * b`, simplified.
    pub fn mul(&mut self, a: Id, b: Id) -> Id {
        self.rewrite(Node::Binary(Binary::Mul, a, b), |g| g.mul_rules(a, b))
    }

    fn mul_rules(&mut self, a: Id, b: Id) -> Id {
        if let Some(c) = self.constant_pair(a, b).and_then(|(x, y)| exact_mul(x, y)) {
            return self.number(c);
        }
        if self.is_number(a, 0.0) || self.is_number(b, 0.0) {
            return self.number(0.0);
        }
        if self.is_number(a, 1.0) {
            return b;
        }
        if self.is_number(b, 1.0) {
            return a;
        }
        for (x, y) in [(a, b), (b, a)] {
            if let Some(c) = self.as_number(x).filter(|c| *c < 0.0) {
                let positive = self.number(-c);
                let product = self.mul(positive, y);
                return self.neg(product);
            }
            if let Some(inner) = self.negated(x) {
                let product = self.mul(inner, y);
                return self.neg(product);
            }
        }
        // x · (1/u) = x / u where x has the root of a factor of u, which then cancels
        // ((x·√u)/u = x/√u below; not in general: x·(1/u) keeps its factors apart, which
        // the quotient rule's f·b′ needs where u overflows)
        for (x, y) in [(a, b), (b, a)] {
            if let Node::Binary(Binary::Div, one, u) = *self.node(y)
                && self.is_number(one, 1.0)
                && self.has_root_of_a_factor(x, u)
            {
                return self.div(x, u);
            }
        }
        if a == b {
            return self.powi(a, 2);
        }
        let power = |g: &Self, id: Id| match g.node(id) {
            Node::Powi(base, n) => (*base, *n),
            _ => (id, 1),
        };
        let ((base_a, m), (base_b, n)) = (power(self, a), power(self, b));
        if base_a == base_b
            && let Some(sum) = m.checked_add(n)
        {
            return self.powi(base_a, sum);
        }
        // c1 * (c2 * y) = (c1 c2) * y when c1 c2 is exact; x * (c * y) = c * (x * y)
        for (x, y) in [(a, b), (b, a)] {
            if let Node::Binary(Binary::Mul, inner_c, inner_y) = *self.node(y)
                && let Some(c2) = self.as_number(inner_c)
            {
                match self.as_number(x) {
                    Some(c1) => {
                        if let Some(c) = exact_mul(c1, c2) {
                            let c = self.number(c);
                            return self.mul(c, inner_y);
                        }
                    }
                    None => {
                        let product = self.mul(x, inner_y);
                        return self.mul(inner_c, product);
                    }
                }
            }
        }
        let (a, b) = self.ordered(a, b);
        self.intern(Node::Binary(Binary::Mul, a, b))
    }

    /// Whether the product `x` has the factor `√v` for a factor `v` of `u`.
    fn has_root_of_a_factor(&self, x: Id, u: Id) -> bool {
        let in_u = self.product_nodes(u);
        self.product_nodes(x)
            .iter()
            .any(|f| matches!(*self.node(*f), Node::Unary(Unary::Sqrt, v) if in_u.contains(&v)))
    }

    /// `a / b`, simplified.
    pub fn div(&mut self, a: Id, b: Id) -> Id {
        self.rewrite(Node::Binary(Binary::Div, a, b), |g| g.div_rules(a, b))
    }

    fn div_rules(&mut self, a: Id, b: Id) -> Id {
        if let Some(c) = self.constant_pair(a, b).and_then(|(x, y)| exact_div(x, y)) {
            return self.number(c);
        }
        if self.is_number(a, 0.0) && !self.is_number(b, 0.0) {
            return a;
        }
        if self.is_number(b, 1.0) {
            return a;
        }
        if self.is_number(b, -1.0) {
            return self.neg(a);
        }
        if a == b && !self.is_number(a, 0.0) {
            return self.number(1.0);
        }
        if let Some(x) = self.negated(a) {
            let quotient = self.div(x, b);
            return self.neg(quotient);
        }
        // a common factor cancels: (x·u)/u = x, (x·u)/uⁿ = x/uⁿ⁻¹
        let (base, n) = match *self.node(b) {
            Node::Powi(base, n) => (base, n),
            _ => (b, 1),
        };
        if self.as_number(base).is_none()
            && let Some(rest) = self.without(a, base)
        {
            let lower = self.powi(base, n - 1);
            return self.div(rest, lower);
        }
        // a factor both share cancels: (x·u)/(y·u) = x/y (where u ≠ 0; at u = 0 the
        // quotient is 0/0), the largest shared factor first
        let in_a = self.product_nodes(a);
        let common = self
            .product_nodes(b)
            .into_iter()
            .filter(|f| self.as_number(*f).is_none() && in_a.contains(f))
            .max();
        if let Some(common) = common
            && let Some(rest_a) = self.without(a, common)
            && let Some(rest_b) = self.without(b, common)
        {
            return self.div(rest_a, rest_b);
        }
        // a square root over its radicand: (x·√u)/(y·u) = x/(y·√u) (u ≥ 0 wherever √u is
        // defined; at u = 0 both sides are 0/0 or x/0)
        let in_b = self.product_nodes(b);
        let root = in_a
            .iter()
            .copied()
            .find(|f| matches!(*self.node(*f), Node::Unary(Unary::Sqrt, u) if in_b.contains(&u)));
        if let Some(root) = root
            && let Node::Unary(Unary::Sqrt, u) = *self.node(root)
            && let Some(rest_a) = self.without(a, root)
            && let Some(rest_b) = self.without(b, u)
        {
            let denominator = self.mul(rest_b, root);
            return self.div(rest_a, denominator);
        }
        // quotients over one denominator: (x·(p/c))/(q/c) = (x·p)/q (where c ≠ 0)
        if let Node::Binary(Binary::Div, q, c) = *self.node(b) {
            let over_c = in_a
                .iter()
                .copied()
                .find(|f| matches!(*self.node(*f), Node::Binary(Binary::Div, _, d) if d == c));
            if let Some(over_c) = over_c
                && let Node::Binary(Binary::Div, p, _) = *self.node(over_c)
                && let Some(rest) = self.without(a, over_c)
            {
                let numerator = self.mul(rest, p);
                return self.div(numerator, q);
            }
        }
        if let Some(y) = self.negated(b) {
            let quotient = self.div(a, y);
            return self.neg(quotient);
        }
        self.intern(Node::Binary(Binary::Div, a, b))
    }

    /// `-u`, simplified.
    pub fn neg(&mut self, u: Id) -> Id {
        self.rewrite(Node::Unary(Unary::Neg, u), |g| g.neg_rules(u))
    }

    fn neg_rules(&mut self, u: Id) -> Id {
        if let Some(c) = self.as_number(u) {
            return self.number(-c);
        }
        match *self.node(u) {
            Node::Unary(Unary::Neg, x) => x,
            Node::Binary(Binary::Sub, a, b) => self.sub(b, a),
            _ => self.intern(Node::Unary(Unary::Neg, u)),
        }
    }

    /// `u.powi(n)`, simplified.
    pub fn powi(&mut self, u: Id, n: i32) -> Id {
        self.rewrite(Node::Powi(u, n), |g| g.powi_rules(u, n))
    }

    fn powi_rules(&mut self, u: Id, n: i32) -> Id {
        if n == 0 {
            return self.number(1.0);
        }
        if n == 1 {
            return u;
        }
        if let Some(c) = self.as_number(u).and_then(|c| exact_powi(c, n)) {
            return self.number(c);
        }
        if n < 0
            && let Some(m) = n.checked_neg()
        {
            let one = self.number(1.0);
            let power = self.powi(u, m);
            return self.div(one, power);
        }
        match *self.node(u) {
            Node::Powi(base, m) if m.checked_mul(n).is_some() => self.powi(base, m * n),
            Node::Unary(Unary::Neg, x) => {
                let power = self.powi(x, n);
                if n % 2 == 0 { power } else { self.neg(power) }
            }
            _ => self.intern(Node::Powi(u, n)),
        }
    }

    /// `a.powf(b)`, simplified (an integer constant exponent gives `powi`).
    pub fn powf(&mut self, a: Id, b: Id) -> Id {
        self.rewrite(Node::Binary(Binary::Powf, a, b), |g| g.powf_rules(a, b))
    }

    fn powf_rules(&mut self, a: Id, b: Id) -> Id {
        if let Some(n) = self.as_number(b)
            && n.fract() == 0.0
            && n.abs() <= f64::from(i32::MAX)
        {
            return self.powi(a, n as i32);
        }
        self.intern(Node::Binary(Binary::Powf, a, b))
    }

    /// `op(u)`, simplified.
    pub fn unary(&mut self, op: Unary, u: Id) -> Id {
        self.rewrite(Node::Unary(op, u), |g| g.unary_rules(op, u))
    }

    fn unary_rules(&mut self, op: Unary, u: Id) -> Id {
        if op == Unary::Neg {
            return self.neg(u);
        }
        if let Some(c) = self.as_number(u).and_then(|c| exact_unary(op, c)) {
            return self.number(c);
        }
        // tan(atan2(a, b)) = a / b and tan(atan(x)) = x (tan has period π)
        if op == Unary::Tan {
            match *self.node(u) {
                Node::Binary(Binary::Atan2, a, b) => return self.div(a, b),
                Node::Unary(Unary::Atan, x) => return x,
                _ => {}
            }
        }
        if op == Unary::Ln
            && let Some(log) = self.log_of_power(u)
        {
            return log;
        }
        if op == Unary::Abs {
            if let Some(magnitude) = self.abs_of_signed(u) {
                return magnitude;
            }
            match *self.node(u) {
                Node::Unary(Unary::Abs | Unary::Neg, x) => return self.abs(x),
                Node::Powi(_, n) if n % 2 == 0 => return u,
                _ => {}
            }
        }
        self.intern(Node::Unary(op, u))
    }

    /// `ln(u)` when `u` is an exponential or a power: `ln(exp(s)) = s`; `ln(uⁿ) = n ln u`
    /// for odd n and `n ln |u|` for even n; `ln(u^c) = c ln u` for a constant c (where
    /// `u^c` is real and positive, so is `u`, and at u = 0 both sides are the same
    /// infinity); `ln(u^v) = v ln u` when u is known positive (an exponential, a positive
    /// constant). `None` otherwise (`ln(u^v)` with u < 0 and v an even integer at run time
    /// is real while `v ln u` is not).
    fn log_of_power(&mut self, u: Id) -> Option<Id> {
        match *self.node(u) {
            Node::Unary(Unary::Exp, s) => Some(s),
            Node::Powi(base, n) => {
                let inner = if n % 2 == 0 { self.abs(base) } else { base };
                let log = self.ln(inner);
                let n = self.number(f64::from(n));
                Some(self.mul(n, log))
            }
            Node::Binary(Binary::Powf, base, exponent)
                if self.as_number(exponent).is_some() || self.is_positive(base) =>
            {
                let log = self.ln(base);
                Some(self.mul(exponent, log))
            }
            _ => None,
        }
    }

    /// Whether `id` is positive wherever it is defined: its range proves it (see
    /// [`super::range`]), or it is an exponential or a `cosh` (whose range may reach 0 in
    /// `f64` bounds).
    fn is_positive(&self, id: Id) -> bool {
        if self.range(id).is_positive() {
            return true;
        }
        match self.node(id) {
            Node::Num(n) => n.value() > 0.0,
            Node::Unary(Unary::Exp | Unary::Cosh, _) => true,
            Node::Sym(name) => super::constants::is_named_constant(name),
            _ => false,
        }
    }

    /// `op(a, b)`, simplified.
    pub fn binary(&mut self, op: Binary, a: Id, b: Id) -> Id {
        match op {
            Binary::Add => self.add(a, b),
            Binary::Sub => self.sub(a, b),
            Binary::Mul => self.mul(a, b),
            Binary::Div => self.div(a, b),
            Binary::Powf => self.powf(a, b),
            Binary::Atan2 => self.rewrite(Node::Binary(op, a, b), |g| g.atan2_simplified(a, b)),
            Binary::Hypot => self.intern(Node::Binary(op, a, b)),
        }
    }

    /// `a.atan2(b)`: the angle of the point (b, a).
    pub fn atan2(&mut self, a: Id, b: Id) -> Id {
        self.binary(Binary::Atan2, a, b)
    }

    /// `a.hypot(b)` = √(a² + b²).
    pub fn hypot(&mut self, a: Id, b: Id) -> Id {
        self.binary(Binary::Hypot, a, b)
    }

    /// `if a <cmp> b { then } else { otherwise }`, simplified (equal branches, constant
    /// conditions).
    pub fn select(&mut self, cmp: Comparison, a: Id, b: Id, then: Id, otherwise: Id) -> Id {
        let raw = Node::Select(cmp, [a, b, then, otherwise]);
        self.rewrite(raw, |g| g.select_rules(cmp, a, b, then, otherwise))
    }

    fn select_rules(&mut self, cmp: Comparison, a: Id, b: Id, then: Id, otherwise: Id) -> Id {
        if then == otherwise {
            return then;
        }
        if let Some((x, y)) = self.constant_pair(a, b) {
            return if cmp.holds(&x, &y) { then } else { otherwise };
        }
        self.intern(Node::Select(cmp, [a, b, then, otherwise]))
    }
}
