//! The scalar a scene's numbers are resolved in: `f64` (the values) or [`Dual64`] (the values
//! with their derivative with respect to one seeded parameter).
//!
//! The resolver's steps (a number's value, the placement of points, the constructions, the
//! drive's measure, the dynamics' numbers) are generic over [`Carried`],
//! so the exact tangent of a scene is the same resolver run in
//! [`Dual64`].

use std::collections::HashMap;

use mechdiff_core::Scalar;
use mechdiff_core::num_dual::Dual64;

use crate::bindings::Bindings;

/// A scalar a scene's numbers are read in: `f64` (no derivative) or [`Dual64`] (the
/// derivative with respect to one parameter).
///
/// The operations whose `f64` form rounds differently from the generic one (`hypot`,
/// `atan2`) are the trait's, so that the real part of a dual result is the `f64` result bit
/// for bit.
pub trait Carried: Scalar {
    /// Whether the scalar carries a derivative (`false` for `f64`).
    const CARRIES: bool;
    /// The number `value` with derivative `tangent` (dropped by `f64`).
    fn with_tangent(value: f64, tangent: f64) -> Self;
    /// The derivative carried (0 for `f64`).
    fn tangent(&self) -> f64;
    /// The values of the scene's parameters in this scalar (with the seeded parameter's
    /// derivative, for a dual number).
    fn parameters(bindings: &Bindings) -> &HashMap<String, Self>;
    /// `√(self² + y²)`, its real part [`f64::hypot`].
    fn hypot(self, y: Self) -> Self {
        let h = self.re().hypot(y.re());
        Self::with_tangent(h, (self.re() * self.tangent() + y.re() * y.tangent()) / h)
    }
    /// The angle of the vector (x, y) = (`x`, `self`), its real part [`f64::atan2`].
    fn atan2(self, x: Self) -> Self {
        let (y, x_re) = (self.re(), x.re());
        let squared = x_re * x_re + y * y;
        Self::with_tangent(
            y.atan2(x_re),
            (x_re * self.tangent() - y * x.tangent()) / squared,
        )
    }
    /// `max(self, 0)`: 0 where the real part is negative (a tangency rounded below 0).
    fn non_negative(self) -> Self {
        if self.re() < 0.0 {
            Self::constant(0.0)
        } else {
            self
        }
    }
}

impl Carried for f64 {
    const CARRIES: bool = false;

    fn with_tangent(value: f64, _: f64) -> Self {
        value
    }

    fn tangent(&self) -> f64 {
        0.0
    }

    fn parameters(bindings: &Bindings) -> &HashMap<String, f64> {
        bindings.values()
    }

    fn hypot(self, y: f64) -> f64 {
        f64::hypot(self, y)
    }

    fn atan2(self, x: f64) -> f64 {
        f64::atan2(self, x)
    }
}

impl Carried for Dual64 {
    const CARRIES: bool = true;

    fn with_tangent(value: f64, tangent: f64) -> Self {
        Dual64::new(value, tangent)
    }

    fn tangent(&self) -> f64 {
        self.eps
    }

    fn parameters(bindings: &Bindings) -> &HashMap<String, Dual64> {
        bindings.duals()
    }
}
