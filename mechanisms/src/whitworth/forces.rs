//! Accelerations of the centres of gravity and the inertial forces on the frame.
//!
//! By the principle of linear momentum each moving body i exerts the inertial force
//! F_i = −m_i a_Si (source eqs. 1.46–1.48); their sum F = F_1 + F_2 + F_3 (1.49–1.51) is the
//! shaking force the foundation must carry. The accelerations come from the position
//! equations' derivatives for any drive state: a = α x′ + ω² x″ (α = 0 is not assumed).

use super::{Parameters, Whitworth};
use crate::error::{Error, Result};
use mechdiff_core::method::{Differentiator, Dual2};
use mechdiff_core::{DriveState, Point};

/// The accelerations (m/s²) of the centres of gravity at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CentreAccelerations {
    /// Crank's centre of gravity S1.
    pub s1: Point<f64>,
    /// Rocker's centre of gravity S2.
    pub s2: Point<f64>,
    /// Ram's centre of gravity S3 (its y component is zero: the ram moves horizontally).
    pub s3: Point<f64>,
}

/// The inertial forces F_i = −m_i a_Si (N) of the three bodies, and their sum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InertialForces {
    /// Inertial force of the crank, −m1 a_S1.
    pub f1: Point<f64>,
    /// Inertial force of the rocker, −m2 a_S2.
    pub f2: Point<f64>,
    /// Inertial force of the ram, −m3 a_S3.
    pub f3: Point<f64>,
    /// The shaking force on the frame, F_1 + F_2 + F_3.
    pub sum: Point<f64>,
}

impl InertialForces {
    /// The inertial forces for the given accelerations and the masses of `parameters`.
    pub fn from_accelerations(parameters: &Parameters, a: &CentreAccelerations) -> Self {
        let f1 = -parameters.m1 * a.s1;
        let f2 = -parameters.m2 * a.s2;
        let f3 = -parameters.m3 * a.s3;
        Self {
            f1,
            f2,
            f3,
            sum: f1 + f2 + f3,
        }
    }
}

/// φ, ω and α must be finite (φ⃛ does not enter an acceleration).
fn check_inputs(phi: f64, drive: &DriveState) -> Result<()> {
    for (name, value) in [("φ", phi), ("ω", drive.omega), ("α", drive.alpha)] {
        if !value.is_finite() {
            return Err(Error::NonFiniteInput { name, value });
        }
    }
    Ok(())
}

impl Whitworth {
    /// The accelerations of S1, S2, S3 at crank angle `phi` (rad) for the drive state `drive`,
    /// from exact second derivatives (dual numbers).
    pub fn centre_accelerations(
        &self,
        phi: f64,
        drive: &DriveState,
    ) -> Result<CentreAccelerations> {
        self.centre_accelerations_with(&Dual2, phi, drive)
    }

    /// The accelerations of S1, S2, S3 with the derivatives computed by `method` (any
    /// second-order [`Differentiator`]: dual numbers, central differences, the hand-derived
    /// [`super::hand::pose`]).
    pub fn centre_accelerations_with(
        &self,
        method: &impl Differentiator<Self, 2>,
        phi: f64,
        drive: &DriveState,
    ) -> Result<CentreAccelerations> {
        check_inputs(phi, drive)?;
        let pose = method.jets(self, phi);
        Ok(CentreAccelerations {
            s1: pose.s1.acceleration(drive),
            s2: pose.s2.acceleration(drive),
            s3: pose.s3.acceleration(drive),
        })
    }

    /// The inertial forces of the three bodies and the shaking force on the frame at crank
    /// angle `phi` (rad) for the drive state `drive`.
    pub fn inertial_forces(&self, phi: f64, drive: &DriveState) -> Result<InertialForces> {
        let a = self.centre_accelerations(phi, drive)?;
        Ok(InertialForces::from_accelerations(&self.parameters, &a))
    }

    /// The shaking force on the frame, F = −m1 a_S1 − m2 a_S2 − m3 a_S3 (N).
    pub fn shaking_force(&self, phi: f64, drive: &DriveState) -> Result<Point<f64>> {
        Ok(self.inertial_forces(phi, drive)?.sum)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::whitworth::hand;

    /// With α ≠ 0 the tangential terms appear: ẍ_S1 = α l_S1 cos φ − ω² l_S1 sin φ (1.8),
    /// ÿ_S1 = α l_S1 sin φ + ω² l_S1 cos φ (1.9). Exact formulas in f64: 1e-14 relative.
    #[test]
    fn crank_centre_acceleration_includes_the_drive_acceleration() {
        let shaper = Whitworth::reference();
        let (phi, omega, alpha) = (0.7f64, 9.0, -25.0);
        let a = shaper
            .centre_accelerations(phi, &DriveState::accelerating(omega, alpha))
            .unwrap();
        let l = shaper.parameters().l_s1;
        let want = Point::new(
            alpha * l * phi.cos() - omega * omega * l * phi.sin(),
            alpha * l * phi.sin() + omega * omega * l * phi.cos(),
        );
        assert!((a.s1.x - want.x).abs() <= 1e-14 * want.x.abs());
        assert!((a.s1.y - want.y).abs() <= 1e-14 * want.y.abs());
        // And at α = 0 the source's constant-speed form (1.10), (1.11).
        let steady = shaper
            .centre_accelerations(phi, &DriveState::constant_speed(omega))
            .unwrap();
        let source = hand::crank_centre_acceleration(&shaper, phi, omega);
        assert!((steady.s1.x - source.x).abs() <= 1e-14 * source.x.abs());
    }

    /// A NaN crank angle or drive speed is an error, never a NaN force.
    #[test]
    fn non_finite_inputs_are_errors() {
        let shaper = Whitworth::reference();
        assert!(matches!(
            shaper.inertial_forces(f64::NAN, &shaper.drive()),
            Err(Error::NonFiniteInput { name: "φ", .. })
        ));
        assert!(matches!(
            shaper.inertial_forces(0.0, &DriveState::accelerating(1.0, f64::INFINITY)),
            Err(Error::NonFiniteInput { name: "α", .. })
        ));
    }
}
