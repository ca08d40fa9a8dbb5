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
//! Where the proof fails (the range of a factor holds 0), nothing is rewritten.

use super::graph::{Graph, Id, Node};
use super::ops::Binary;

/// The named constant π/2 (see [`super::constants`]).
const FRAC_PI_2: &str = "std::f64::consts::FRAC_PI_2";

/// The named constant π.
const PI: &str = "std::f64::consts::PI";

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
        if self.range(x).is_positive() {
            let quotient = self.div(y, x);
            return self.atan(quotient);
        }
        let range = self.range(y);
        if range.is_positive() || range.is_negative() {
            let half_pi = self.symbol(FRAC_PI_2);
            let quarter = if range.is_positive() {
                half_pi
            } else {
                self.neg(half_pi)
            };
            let quotient = self.div(x, y);
            let atan = self.atan(quotient);
            return self.sub(quarter, atan);
        }
        if self.is_number(y, 0.0) && self.range(x).is_negative() {
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
            .filter(|f| in_x.contains(f) && self.range(*f).is_positive())
            .max()?;
        let y = self.without(y, common)?;
        let x = self.without(x, common)?;
        Some((y, x))
    }
}
