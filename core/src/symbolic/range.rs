//! Ranges of expressions: for every node, an interval that holds every real value the node
//! takes, whatever its symbols are, computed by interval arithmetic from its children's
//! ranges as the node is stored (`sin` and `cos` lie in [−1, 1], squares, square roots and
//! absolute values are ≥ 0, a named constant is its value, a parameter can be anything).
//!
//! The simplifier asks ranges for **signs**: a factor proven positive leaves an `atan2`, the
//! absolute value of a node proven ≥ 0 is the node itself, `atan2(y, x)` with x proven
//! positive is `atan(y / x)` (see [`super::signs`]).
//!
//! Soundness: the enclosure is of the real function (where it is defined; a square root of
//! a negative number has no value to enclose). Each bound computed in `f64` is rounded
//! outwards: by one ulp after a correctly rounded operation (`+ − × ÷ √`), by a relative
//! `LIBM_SLACK` after a library function, whose result may be a few ulps off; where
//! anything is in doubt (a division by a range that holds 0, a `tan`, a NaN bound) the
//! range is the whole real line, which proves nothing.

use super::constants;
use super::graph::{Graph, Id, Node};
use super::ops::{Binary, Unary};

/// The relative error allowed to a library function (`exp`, `atan`, …) when it bounds a
/// range: the C libraries' documented worst cases are a few ulps (≤ 1e-15 relative).
const LIBM_SLACK: f64 = 8.0 * f64::EPSILON;

/// A closed interval `[lo, hi]` of the extended reals holding every value of a node.
///
/// ```
/// use mechdiff_core::symbolic::Graph;
///
/// let mut graph = Graph::new();
/// let d = graph.parse_infix("(0.15*sin(phi))^2 + (0.4 - 0.15*cos(phi))^2").unwrap();
/// let range = graph.range(d);
/// // [0.0625, 0.325] rounded outwards (the true maximum is 0.3025: interval arithmetic
/// // does not know that sin² + cos² = 1, so its bounds are safe, not tight)
/// assert!(range.lo() > 0.0624 && range.hi() < 0.3251);
/// assert!(range.is_positive());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Range {
    lo: f64,
    hi: f64,
}

/// `x` lowered by a relative `slack` and one ulp (an infinite `x` stays).
fn down(x: f64, slack: f64) -> f64 {
    if x.is_infinite() {
        x
    } else {
        (x - x.abs() * slack).next_down()
    }
}

/// `x` raised by a relative `slack` and one ulp (an infinite `x` stays).
fn up(x: f64, slack: f64) -> f64 {
    if x.is_infinite() {
        x
    } else {
        (x + x.abs() * slack).next_up()
    }
}

/// `x · y` with `0 · ∞ = 0` (a real factor 0 makes the real product 0).
fn product(x: f64, y: f64) -> f64 {
    if x == 0.0 || y == 0.0 { 0.0 } else { x * y }
}

impl Range {
    /// The whole real line: nothing is known.
    pub const ALL: Range = Range {
        lo: f64::NEG_INFINITY,
        hi: f64::INFINITY,
    };

    /// `[lo, hi]`, or [`Range::ALL`] if a bound is NaN or `lo > hi`.
    fn new(lo: f64, hi: f64) -> Self {
        if lo.is_nan() || hi.is_nan() || lo > hi {
            Range::ALL
        } else {
            Range { lo, hi }
        }
    }

    /// `[lo, hi]` computed with correctly rounded operations, rounded outwards.
    fn rounded(lo: f64, hi: f64) -> Self {
        Range::new(down(lo, 0.0), up(hi, 0.0))
    }

    /// `[lo, hi]` computed with a library function, rounded outwards.
    fn library(lo: f64, hi: f64) -> Self {
        Range::new(down(lo, LIBM_SLACK), up(hi, LIBM_SLACK))
    }

    /// The single value `c`.
    fn point(c: f64) -> Self {
        Range::new(c, c)
    }

    /// The lower bound.
    pub fn lo(self) -> f64 {
        self.lo
    }

    /// The upper bound.
    pub fn hi(self) -> f64 {
        self.hi
    }

    /// Whether every value is > 0.
    pub fn is_positive(self) -> bool {
        self.lo > 0.0
    }

    /// Whether every value is < 0.
    pub fn is_negative(self) -> bool {
        self.hi < 0.0
    }

    /// Whether every value is ≥ 0.
    pub fn is_nonnegative(self) -> bool {
        self.lo >= 0.0
    }

    /// Whether every value is ≤ 0.
    pub fn is_nonpositive(self) -> bool {
        self.hi <= 0.0
    }

    fn contains_zero(self) -> bool {
        self.lo <= 0.0 && self.hi >= 0.0
    }

    fn hull(self, other: Range) -> Range {
        Range::new(self.lo.min(other.lo), self.hi.max(other.hi))
    }

    fn neg(self) -> Range {
        Range::new(-self.hi, -self.lo)
    }

    fn abs(self) -> Range {
        if self.lo >= 0.0 {
            self
        } else if self.hi <= 0.0 {
            self.neg()
        } else {
            Range::new(0.0, self.hi.max(-self.lo))
        }
    }

    fn add(self, other: Range) -> Range {
        Range::rounded(self.lo + other.lo, self.hi + other.hi)
    }

    fn sub(self, other: Range) -> Range {
        self.add(other.neg())
    }

    fn mul(self, other: Range) -> Range {
        let corners = [
            product(self.lo, other.lo),
            product(self.lo, other.hi),
            product(self.hi, other.lo),
            product(self.hi, other.hi),
        ];
        let lo = corners.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = corners.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        Range::rounded(lo, hi)
    }

    fn div(self, other: Range) -> Range {
        if other.contains_zero() {
            return Range::ALL;
        }
        let reciprocal = Range::rounded(1.0 / other.hi, 1.0 / other.lo);
        self.mul(reciprocal)
    }

    /// `uⁿ` for `n ≥ 1`: by repeated multiplication of the range (of its absolute value for
    /// even n, so that the square of [−1, 1] is [0, 1], not [−1, 1]).
    fn powi(self, n: u32) -> Range {
        let base = if n.is_multiple_of(2) {
            self.abs()
        } else {
            self
        };
        let mut power = base;
        for _ in 1..n.min(64) {
            power = power.mul(base);
        }
        if n > 64 {
            // beyond 64 factors only the sign is kept
            return if n.is_multiple_of(2) || base.lo >= 0.0 {
                Range::new(0.0, f64::INFINITY)
            } else if base.hi <= 0.0 {
                Range::new(f64::NEG_INFINITY, 0.0)
            } else {
                Range::ALL
            };
        }
        if n.is_multiple_of(2) {
            Range::new(power.lo.max(0.0), power.hi)
        } else {
            power
        }
    }

    /// A nondecreasing library function `f` on `self`.
    fn increasing(self, f: impl Fn(f64) -> f64) -> Range {
        Range::library(f(self.lo), f(self.hi))
    }
}

/// π rounded up (the `f64` constant is below π).
fn pi_up() -> f64 {
    std::f64::consts::PI.next_up()
}

/// The range of `op(u)` from the range of `u`.
fn unary_range(op: Unary, u: Range) -> Range {
    let half_pi = pi_up() / 2.0;
    match op {
        Unary::Neg => u.neg(),
        Unary::Abs => u.abs(),
        Unary::Sqrt if u.hi < 0.0 => Range::ALL,
        Unary::Sqrt => {
            let r = Range::rounded(u.lo.max(0.0).sqrt(), u.hi.sqrt());
            Range::new(r.lo.max(0.0), r.hi)
        }
        Unary::Cbrt => u.increasing(f64::cbrt),
        Unary::Exp => {
            let r = u.increasing(f64::exp);
            Range::new(r.lo.max(0.0), r.hi)
        }
        Unary::Ln if u.hi <= 0.0 => Range::ALL,
        Unary::Ln => Range::library(
            if u.lo > 0.0 {
                u.lo.ln()
            } else {
                f64::NEG_INFINITY
            },
            u.hi.ln(),
        ),
        Unary::Sin | Unary::Cos | Unary::Tanh => Range::new(-1.0, 1.0),
        Unary::Tan => Range::ALL,
        Unary::Asin => Range::new(-half_pi, half_pi),
        Unary::Acos => Range::new(0.0, pi_up()),
        Unary::Atan => {
            let r = u.increasing(f64::atan);
            Range::new(r.lo.max(-half_pi), r.hi.min(half_pi))
        }
        Unary::Sinh => u.increasing(f64::sinh),
        Unary::Cosh => {
            let m = u.abs();
            Range::library(1.0, m.hi.cosh())
        }
    }
}

/// The range of `op(a, b)` from the ranges of `a` and `b`.
fn binary_range(op: Binary, a: Range, b: Range) -> Range {
    match op {
        Binary::Add => a.add(b),
        Binary::Sub => a.sub(b),
        Binary::Mul => a.mul(b),
        Binary::Div => a.div(b),
        Binary::Atan2 => {
            let pi = pi_up();
            if a.lo >= 0.0 {
                Range::new(0.0, pi)
            } else if b.lo > 0.0 {
                Range::new(-pi / 2.0, pi / 2.0)
            } else {
                Range::new(-pi, pi)
            }
        }
        Binary::Hypot => {
            let (a, b) = (a.abs(), b.abs());
            Range::library(a.lo.max(b.lo), a.hi.hypot(b.hi))
        }
        // a positive base gives a positive power; anything else is not bounded here
        Binary::Powf if a.lo > 0.0 => Range::new(0.0, f64::INFINITY),
        Binary::Powf => Range::ALL,
    }
}

impl Graph {
    /// The range of the node `node`, whose children are stored (see the module doc).
    pub(super) fn range_of(&self, node: &Node) -> Range {
        let range = |id: &Id| self.range(*id);
        match node {
            Node::Num(n) => Range::point(n.value()),
            // the f64 value of a named constant is within an ulp of the constant
            Node::Sym(name) => constants::lookup(name)
                .map_or(Range::ALL, |(value, _)| Range::rounded(value, value)),
            Node::Unary(op, u) => unary_range(*op, range(u)),
            Node::Binary(op, a, b) => binary_range(*op, range(a), range(b)),
            Node::Powi(_, 0) => Range::point(1.0),
            Node::Powi(u, n) if *n > 0 => range(u).powi(n.unsigned_abs()),
            Node::Powi(u, n) => Range::point(1.0).div(range(u).powi(n.unsigned_abs())),
            Node::Select(_, [_, _, then, otherwise]) => range(then).hull(range(otherwise)),
        }
    }
}
