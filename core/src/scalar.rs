//! The scalar types a position function is written for.
//!
//! A position function is written once, generic over `D: Scalar`; it is then evaluated with
//! `f64` for positions, or with a num-dual number to get exact derivatives.

use crate::trace::Traced;
use num_dual::DualNum;
use std::any::Any;
use std::f64::consts::{FRAC_PI_2, PI};

/// A real scalar or a dual number over `f64`: what generic position functions are written for.
///
/// Blanket-implemented for every `num_dual::DualNum<Primitive = f64> + Copy` type: `f64`,
/// `Dual64`, `Dual2_64`, `Dual3_64`, `HyperDual64`, … All of num-dual's functions (`sin`,
/// `sqrt`, `powi`, …) are available through [`DualNum`].
///
/// ```
/// use mechdiff_core::{Scalar, atan2};
/// fn rocker_angle<D: Scalar>(phi: D, lambda: f64) -> D {
///     atan2(phi.sin() * lambda, -phi.cos() * lambda + 1.0)
/// }
/// assert_eq!(rocker_angle(0.0, 0.375), 0.0);
/// ```
pub trait Scalar: DualNum<Primitive = f64> + Copy + Send + Sync {
    /// A constant: the number `value` with all derivative parts zero.
    fn constant(value: f64) -> Self {
        Self::from(value)
    }
}

impl<T: DualNum<Primitive = f64> + Copy + Send + Sync> Scalar for T {}

/// `atan2(y, x)`, the angle of the vector (x, y) in (−π, π], with exact derivatives everywhere
/// except at the origin.
///
/// num-dual's own `atan2` differentiates `atan(y/x)` and returns NaN derivatives on the y axis
/// (x = 0 exactly), a position every rotating link passes through. Here the quotient is formed
/// with the larger component as divisor, and the quadrant constant is added:
/// atan2(y, x) = atan(y/x) + kπ for |x| ≥ |y|, and π/2·sign(y) − atan(x/y) otherwise.
///
/// ```
/// use mechdiff_core::atan2;
/// use num_dual::Dual64;
/// // On the y axis, moving x: ∂/∂x atan2(y, x) = −y/(x² + y²) = −1 at (0, 1).
/// let angle = atan2(Dual64::from(1.0), Dual64::new(0.0, 1.0));
/// assert_eq!(angle.re, std::f64::consts::FRAC_PI_2);
/// assert_eq!(angle.eps, -1.0);
/// ```
pub fn atan2<D: Scalar>(y: D, x: D) -> D {
    if let Some(angle) = traced_atan2(&y, &x) {
        return angle;
    }
    let (yr, xr) = (y.re(), x.re());
    if xr.abs() >= yr.abs() {
        let quadrant = if xr > 0.0 {
            0.0
        } else if yr >= 0.0 {
            PI
        } else {
            -PI
        };
        (y / x).atan() + quadrant
    } else {
        let half_plane = if yr > 0.0 { FRAC_PI_2 } else { -FRAC_PI_2 };
        -(x / y).atan() + half_plane
    }
}

/// `tanh(u)` with derivatives that stay finite for every finite `u`.
///
/// num-dual's `tanh` of a dual number is `sinh / cosh`, ∞/∞ = NaN in every part once
/// |u| > 710. For |u| ≥ 1 this is `s (1 − w)/(1 + w)` with w = e^(−2s·u), s the sign of u:
/// w ≤ e^-2, so nothing overflows, 1 − w does not cancel, and far out the derivative parts
/// (sech² and its derivatives, ~w) underflow gracefully to 0. For |u| < 1, and for a plain
/// `f64` (bit for bit what emitted code computes), the library's `tanh`.
///
/// ```
/// use mechdiff_core::tanh;
/// use num_dual::Dual2_64;
/// let t = tanh(Dual2_64::new(800.0, 1.0, 0.0));
/// assert_eq!((t.re, t.v1, t.v2), (1.0, 0.0, 0.0));
/// ```
pub fn tanh<D: Scalar>(u: D) -> D {
    let x = u.re();
    if D::NDERIV == 0 || x.abs() < 1.0 || x.is_nan() {
        return u.tanh();
    }
    let sign = x.signum();
    let w = (u * (-2.0 * sign)).exp();
    (D::one() - w) / (D::one() + w) * sign
}

/// A traced `atan2` is recorded as one node, valid in every quadrant (the branches below
/// would record only the traced point's quadrant); `None` for every other scalar (the test
/// is on the type, resolved at compile time).
fn traced_atan2<D: Scalar>(y: &D, x: &D) -> Option<D> {
    let y = (y as &dyn Any).downcast_ref::<Traced>()?;
    let x = (x as &dyn Any).downcast_ref::<Traced>()?;
    let angle = y.atan2_node(*x);
    (&angle as &dyn Any).downcast_ref::<D>().copied()
}

/// `hypot(x, y) = √(x² + y²)`, the length of the vector (x, y), with derivatives.
///
/// Scaled by the power of two of the larger of |x|, |y| (a constant, and exact: the
/// derivatives and the rounding are unchanged), so that x² does not overflow for arguments
/// up to `f64::MAX` nor underflow for tiny ones.
///
/// ```
/// use mechdiff_core::hypot;
/// assert_eq!(hypot(3e300, 4e300), 5e300);
/// ```
pub fn hypot<D: Scalar>(x: D, y: D) -> D {
    let larger = x.re().abs().max(y.re().abs());
    // 2^⌊log₂ larger⌋: the exponent bits alone (0 for subnormals, ∞/NaN kept).
    let scale = f64::from_bits(larger.to_bits() & 0x7ff0_0000_0000_0000);
    if scale == 0.0 || !scale.is_finite() {
        return (x * x + y * y).sqrt();
    }
    let (u, v) = (x / scale, y / scale);
    (u * u + v * v).sqrt() * scale
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_dual::Dual2_64;

    /// atan2 agrees with f64::atan2 in all quadrants and on the axes, to 1 ulp-scale (4e-16 rad:
    /// both are correctly rounded up to a couple of ulp).
    #[test]
    fn atan2_value_matches_std_in_every_quadrant() {
        for k in 0..72 {
            let angle = -PI + (k as f64 + 0.5) * (2.0 * PI / 72.0);
            let (y, x) = (1.7 * angle.sin(), 1.7 * angle.cos());
            assert!((atan2(y, x) - y.atan2(x)).abs() < 4e-16 * PI, "{angle}");
        }
        assert_eq!(atan2(0.0, -1.0), PI);
        assert_eq!(atan2(1.0, 0.0), FRAC_PI_2);
        assert_eq!(atan2(-1.0, 0.0), -FRAC_PI_2);
    }

    /// On a circle x = cos t, y = sin t the angle is t: first derivative 1, second 0 exactly
    /// (up to rounding of the circle's coordinates, 1e-15).
    #[test]
    fn atan2_derivatives_along_a_circle_are_one_and_zero() {
        for k in 0..36 {
            let t = -PI + 0.1 + k as f64 * (2.0 * PI / 36.0);
            let td = Dual2_64::from(t).derivative();
            let angle = atan2(td.sin(), td.cos());
            assert!((angle.v1 - 1.0).abs() < 1e-15, "{t}: {}", angle.v1);
            assert!(angle.v2.abs() < 1e-15, "{t}: {}", angle.v2);
        }
    }
}
