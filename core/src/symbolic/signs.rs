//! Simplifications that hold where a sign is proven by the nodes' ranges
//! ([`super::range`]), each exact in real arithmetic on the domain stated:
//!
//! - `|u| = u` where u ≥ 0, and `|u| = −u` where u ≤ 0;
//! - `atan2(c·y, c·x) = atan2(y, x)` for a factor c > 0, and `atan2(y/c, x/c)` likewise:
//!   scaling a point towards or away from the origin keeps its angle (so `√D`, `1/D`, `0.8`
//!   shared by both coordinates of a direction leave its angle);
//! - `atan2(y, x) = atan(y / x)` where x > 0 (the angle is in (−π/2, π/2)),
//!   `= π/2 − atan(x / y)` where y > 0 (in (0, π)), `= −π/2 − atan(x / y)` where y < 0
//!   (in (−π, 0)), `= π` where y = 0 and x < 0: the same principal value in (−π, π], with
//!   one `atan` (cheaper than `atan2`), and π/2 as the named constant
//!   `std::f64::consts::FRAC_PI_2` (so that `π/2 − (π/2 − a)` cancels to `a`, and no rounded
//!   value is frozen: arbitrary-precision evaluation takes π to its own precision).
//!
//! Where the proof fails (the range of a factor holds 0), nothing is rewritten; the rewrites
//! of `atan2` as `atan` also ask the sign to be robust in `f64` (see `ROBUST`).

use super::graph::{Graph, Id, Node};
use super::ops::Binary;
use super::range::Range;

/// The named constant π/2 (see [`super::constants`]).
const FRAC_PI_2: &str = "std::f64::consts::FRAC_PI_2";

/// The named constant π.
const PI: &str = "std::f64::consts::PI";

/// How far from 0 a range's nearest bound must be, relative to its farthest finite bound,
/// for a rewrite whose result jumps with the sign (`atan2(y, x)` as `atan(y / x)`): then
/// the `f64` value of the node, a few roundings away from its real value, has the sign too.
/// (A range [1e-300, 1] proves x > 0 in real arithmetic, but x may round to 0 or below,
/// where `atan(y / x)` and `atan2(y, x)` differ by π.)
const ROBUST: f64 = 1e-6;

/// The sign of every value of `range` (`1` or `-1`) when it is robust (see [`ROBUST`]).
fn robust_sign(range: Range) -> Option<f64> {
    let (lo, hi) = (range.lo(), range.hi());
    if lo > 0.0 && (hi.is_infinite() || lo >= ROBUST * hi) {
        Some(1.0)
    } else if hi < 0.0 && (lo.is_infinite() || -hi >= ROBUST * -lo) {
        Some(-1.0)
    } else {
        None
    }
}

impl Graph {
    /// `|u|` when the sign of `u` is proven: `u` or `−u`.
    pub(super) fn abs_of_signed(&mut self, u: Id) -> Option<Id> {
        let range = self.range(u);
        if range.is_nonnegative() {
            Some(u)
        } else if range.is_nonpositive() {
            Some(self.neg(u))
        } else {
            None
        }
    }

    /// `atan2(y, x)`, simplified by the rules of this module.
    pub(super) fn atan2_simplified(&mut self, y: Id, x: Id) -> Id {
        if let Some((y, x)) = self.without_positive_factor(y, x) {
            return self.atan2(y, x);
        }
        if robust_sign(self.range(x)) == Some(1.0) {
            let quotient = self.div(y, x);
            return self.atan(quotient);
        }
        if let Some(sign) = robust_sign(self.range(y)) {
            let half_pi = self.symbol(FRAC_PI_2);
            let quarter = if sign > 0.0 {
                half_pi
            } else {
                self.neg(half_pi)
            };
            let quotient = self.div(x, y);
            let atan = self.atan(quotient);
            return self.sub(quarter, atan);
        }
        if self.is_number(y, 0.0) && robust_sign(self.range(x)) == Some(-1.0) {
            return self.symbol(PI);
        }
        self.intern(Node::Binary(Binary::Atan2, y, x))
    }

    /// `(y, x)` without one positive factor they share: a common positive denominator, or
    /// the largest positive factor of both products.
    fn without_positive_factor(&mut self, y: Id, x: Id) -> Option<(Id, Id)> {
        if let (Node::Binary(Binary::Div, ny, dy), Node::Binary(Binary::Div, nx, dx)) =
            (self.node(y).clone(), self.node(x).clone())
            && dy == dx
            && self.range(dy).is_positive()
        {
            return Some((ny, nx));
        }
        let in_x = self.product_nodes(x);
        let common = self
            .product_nodes(y)
            .into_iter()
            .filter(|f| {
                !self.is_number(*f, 1.0) && in_x.contains(f) && self.range(*f).is_positive()
            })
            .max()?;
        let without_y = self.without(y, common)?;
        let without_x = self.without(x, common)?;
        // a factor 1 (the constants `atan2(c, c)` become `atan2(1, 1)`) is no factor: taking
        // it out again would rewrite the node into itself forever
        ((without_y, without_x) != (y, x)).then_some((without_y, without_x))
    }
}
