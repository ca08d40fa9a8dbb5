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

use crate::jet::Jet;

/// The state of the drive at an instant: ω = φ̇, α = φ̈ and φ⃛.
///
/// For a rotating drive the units are rad/s, rad/s², rad/s³; for a linear drive m/s, m/s², m/s³.
///
/// ```
/// use mechdiff_core::{DriveState, Jet};
/// let drive = DriveState::constant_speed(2.0);
/// let x = Jet::new(1.0, [0.5, 0.25]).motion(&drive);
/// assert_eq!((x.velocity, x.acceleration), (1.0, 1.0));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DriveState {
    /// Drive speed ω = φ̇.
    pub omega: f64,
    /// Drive acceleration α = φ̈.
    pub alpha: f64,
    /// Third time derivative of the drive variable, φ⃛.
    pub jerk: f64,
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

/// A quantity and its time derivatives at one instant.
///
/// Fields beyond the order of the jet it was computed from are `None`: a `Jet<1>` gives a
/// velocity but no acceleration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Motion {
    /// The value x.
    pub position: f64,
    /// ẋ = ω x′.
    pub velocity: f64,
    /// ẍ = α x′ + ω² x″.
    pub acceleration: f64,
    /// x⃛ = φ⃛ x′ + 3ωα x″ + ω³ x‴, where the jet has a third derivative.
    pub jerk: Option<f64>,
}

impl Motion {
    /// Time derivatives of a jet of order 2 or 3 for the given drive state.
    pub fn from_jet<const N: usize>(jet: &Jet<N>, drive: &DriveState) -> Self {
        const { assert!(N >= 2, "accelerations need a jet of order 2 or more") };
        let DriveState { omega, alpha, jerk } = *drive;
        let [d1, d2] = [jet.derivatives[0], jet.derivatives[1]];
        Self {
            position: jet.value,
            velocity: omega * d1,
            acceleration: alpha * d1 + omega * omega * d2,
            jerk: jet
                .derivatives
                .get(2)
                .map(|d3| jerk * d1 + 3.0 * omega * alpha * d2 + omega.powi(3) * d3),
        }
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
