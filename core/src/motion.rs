//! From derivatives with respect to φ to derivatives with respect to time.
//!
//! With the drive variable φ(t) and ω = φ̇, α = φ̈, φ⃛ given, the chain rule gives for any
//! quantity x(φ):
//!
//! - ẋ = ω x′
//! - ẍ = α x′ + ω² x″
//! - x⃛ = φ⃛ x′ + 3ωα x″ + ω³ x‴
//!
//! α = 0 (constant drive speed) is a special case of these formulas, never an assumption.
//!
//! [`DriveState`] and [`Motion`] are generic over the scalar (`f64` by default): with dual
//! numbers carrying a derivative with respect to a parameter (which ω and α may depend on
//! too), the same chain rule gives the time derivatives' sensitivities.

use crate::jet::Jet;
use crate::scalar::Scalar;

/// The state of the drive at an instant: ω = φ̇, α = φ̈ and φ⃛.
///
/// For a rotating drive the units are rad/s, rad/s², rad/s³; for a linear drive m/s, m/s², m/s³.
/// `D` is the scalar: `f64`, or a dual number (see the module documentation).
///
/// ```
/// use mechdiff_core::{DriveState, Jet};
/// let drive = DriveState::constant_speed(2.0);
/// let x = Jet::new(1.0, [0.5, 0.25]).motion(&drive);
/// assert_eq!((x.velocity, x.acceleration), (1.0, 1.0));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DriveState<D = f64> {
    /// Drive speed ω = φ̇.
    pub omega: D,
    /// Drive acceleration α = φ̈.
    pub alpha: D,
    /// Third time derivative of the drive variable, φ⃛.
    pub jerk: D,
}

impl DriveState {
    /// A drive turning (or moving) at constant speed ω: α = φ⃛ = 0.
    pub const fn constant_speed(omega: f64) -> Self {
        Self {
            omega,
            alpha: 0.0,
            jerk: 0.0,
        }
    }

    /// A drive with speed ω and acceleration α (φ⃛ = 0).
    pub const fn accelerating(omega: f64, alpha: f64) -> Self {
        Self {
            omega,
            alpha,
            jerk: 0.0,
        }
    }

    /// The same drive with φ⃛ set.
    pub const fn with_jerk(self, jerk: f64) -> Self {
        Self { jerk, ..self }
    }

    /// Drive speed from revolutions per minute: ω = 2πn/60.
    pub fn from_rpm(n: f64) -> Self {
        Self::constant_speed(n * std::f64::consts::PI / 30.0)
    }
}

impl<D: Scalar> DriveState<D> {
    /// ẋ = ω x′, from x′ = `d1`.
    pub fn velocity(&self, d1: D) -> D {
        self.omega * d1
    }

    /// ẍ = α x′ + ω² x″, from x′ = `d1` and x″ = `d2`.
    pub fn acceleration(&self, d1: D, d2: D) -> D {
        self.alpha * d1 + self.omega * self.omega * d2
    }

    /// x⃛ = φ⃛ x′ + 3ωα x″ + ω³ x‴, from x′ = `d1`, x″ = `d2` and x‴ = `d3`.
    pub fn jerk(&self, d1: D, d2: D, d3: D) -> D {
        self.jerk * d1 + self.omega * 3.0 * self.alpha * d2 + self.omega.powi(3) * d3
    }
}

/// A quantity and its time derivatives at one instant.
///
/// Fields beyond the order of the jet it was computed from are `None`: a `Jet<1>` gives a
/// velocity but no acceleration. `D` is the scalar, as for [`DriveState`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Motion<D = f64> {
    /// The value x.
    pub position: D,
    /// ẋ = ω x′.
    pub velocity: D,
    /// ẍ = α x′ + ω² x″.
    pub acceleration: D,
    /// x⃛ = φ⃛ x′ + 3ωα x″ + ω³ x‴, where the jet has a third derivative.
    pub jerk: Option<D>,
}

impl<D: Scalar> Motion<D> {
    /// Time derivatives of `x` given with its derivatives `[x′, x″]` or `[x′, x″, x‴]` with
    /// respect to the drive position, for the drive state `drive`.
    pub fn from_derivatives(x: D, derivatives: &[D], drive: &DriveState<D>) -> Self {
        let (d1, d2) = (derivatives[0], derivatives[1]);
        Self {
            position: x,
            velocity: drive.velocity(d1),
            acceleration: drive.acceleration(d1, d2),
            jerk: derivatives.get(2).map(|&d3| drive.jerk(d1, d2, d3)),
        }
    }
}

impl Motion {
    /// Time derivatives of a jet of order 2 or 3 for the given drive state.
    pub fn from_jet<const N: usize>(jet: &Jet<N>, drive: &DriveState) -> Self {
        const { assert!(N >= 2, "accelerations need a jet of order 2 or more") };
        Self::from_derivatives(jet.value, &jet.derivatives, drive)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// x(φ) = φ³ with φ(t) = t²: x(t) = t⁶, so ẋ = 6t⁵, ẍ = 30t⁴, x⃛ = 120t³. At t = 1.5 every
    /// term of the chain rule is non-zero (ω = 2t, α = 2, φ⃛ = 0; then with a jerk term checked
    /// separately). Exact in f64 up to a few ulp: 1e-13 relative.
    #[test]
    fn chain_rule_matches_a_closed_form_time_history() {
        let t: f64 = 1.5;
        let phi = t * t;
        let jet = Jet::new(phi.powi(3), [3.0 * phi * phi, 6.0 * phi, 6.0]);
        let m = jet.motion(&DriveState::accelerating(2.0 * t, 2.0));
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-13 * b.abs();
        assert!(close(m.velocity, 6.0 * t.powi(5)));
        assert!(close(m.acceleration, 30.0 * t.powi(4)));
        assert!(close(m.jerk.unwrap(), 120.0 * t.powi(3)));
    }

    /// The chain rule in dual numbers gives the time derivatives' sensitivities: x(φ) = φ³
    /// with φ(t) = p t², so x(t) = p³ t⁶ and d/dp of ẋ = 6p³t⁵, ẍ = 30p³t⁴, x⃛ = 120p³t³ are
    /// 18p²t⁵, 90p²t⁴, 360p²t³ (written out by hand, independent of the chain rule). ω = 2pt,
    /// α = 2p and φ carry d/dp; at p = 1.25, t = 1.5 every term is non-zero. A few roundings
    /// of numbers of size 10³: 1e-13 relative. The f64 parts are the f64 chain rule's, bit
    /// for bit.
    #[test]
    fn chain_rule_in_dual_numbers_differentiates_with_respect_to_a_parameter() {
        use num_dual::{Dual64, DualNum};
        let (p, t) = (1.25_f64, 1.5_f64);
        let phi = Dual64::new(p * t * t, t * t);
        let derivatives = [phi * phi * 3.0, phi * 6.0, Dual64::from(6.0)];
        let drive = DriveState {
            omega: Dual64::new(2.0 * p * t, 2.0 * t),
            alpha: Dual64::new(2.0 * p, 2.0),
            jerk: Dual64::from(0.0),
        };
        let m = Motion::from_derivatives(phi.powi(3), &derivatives, &drive);
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-13 * b.abs();
        assert!(close(m.velocity.eps, 18.0 * p * p * t.powi(5)));
        assert!(close(m.acceleration.eps, 90.0 * p * p * t.powi(4)));
        assert!(close(m.jerk.unwrap().eps, 360.0 * p * p * t.powi(3)));
        let real = Jet::new(phi.re.powi(3), derivatives.map(|d| d.re));
        let f64_motion = real.motion(&DriveState::accelerating(drive.omega.re, drive.alpha.re));
        assert_eq!(m.velocity.re, f64_motion.velocity);
        assert_eq!(m.acceleration.re, f64_motion.acceleration);
        assert_eq!(m.jerk.unwrap().re, f64_motion.jerk.unwrap());
    }

    /// x(φ) = φ with φ(t) = t³: x⃛ = 6 comes from the φ⃛ term alone (at t = 0, ω = α = 0).
    #[test]
    fn jerk_of_the_drive_passes_through() {
        let jet = Jet::new(0.0, [1.0, 0.0, 0.0]);
        let m = jet.motion(&DriveState::accelerating(0.0, 0.0).with_jerk(6.0));
        assert_eq!(m.jerk, Some(6.0));
    }

    /// 100 rpm is 10π/3 rad/s (the Whitworth's crank speed), to 1 ulp.
    #[test]
    fn rpm_converts_to_rad_per_second() {
        let omega = DriveState::from_rpm(100.0).omega;
        assert!((omega - 10.471975511965978).abs() <= f64::EPSILON * 10.5);
    }
}
