//! A motor driving the drive joint through a gearbox: rotor inertia `J_d` behind the gear
//! ratio `τ = φ̇ / ω_d`, and the gearbox efficiency `η` (by direction of power flow).
//!
//! With `M′` the torque the kinetostatics need at the drive joint and `P_out = M′·φ̇`, the
//! power entering the gearbox is `W_e = P_out/η` for direct flow (`P_out ≥ 0`) and
//! `W_e = η·P_out` for reverse flow; the motor torque is `M_d = W_e/ω_d + J_d·ω̇_d`
//! (equivalently `M_d = J_d ω̇_d + M′ τ/η` or `+ M′ τ η`).

use crate::{DriveState, Error, Scalar};

/// Motor data (in an [`super::EffectsTangent`], the derivatives of its numbers with respect to
/// a parameter).
///
/// ```
/// use mechdiff_core::dynamics::Motor;
/// let m = Motor { rotor_inertia: 0.002, ratio: 1.0 / 30.0, efficiency: 0.9 };
/// let s = m.state(26.869788081459216, &mechdiff_core::DriveState::accelerating(1.25, 0.05), true, true);
/// assert!((s.torque - 0.9981773363503413).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motor<T = f64> {
    /// Rotor moment of inertia `J_d` (kg·m²).
    pub rotor_inertia: T,
    /// Gear ratio `τ = φ̇ / ω_d` (drive-joint speed over motor speed; for a linear drive m/rad).
    pub ratio: T,
    /// Gearbox efficiency `η ∈ (0, 1]`.
    pub efficiency: T,
}

/// The motor at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotorState<T = f64> {
    /// Motor speed `ω_d = φ̇/τ` (rad/s).
    pub speed: T,
    /// Motor acceleration `ω̇_d = φ̈/τ` (rad/s²).
    pub acceleration: T,
    /// Motor torque `M_d` (N·m).
    pub torque: T,
    /// Power entering the gearbox, `W_e = (M_d − J_d ω̇_d)·ω_d` (W).
    pub gearbox_input: T,
    /// Power lost in the gearbox, `P_out − W_e` (W, ≤ 0).
    pub gearbox_loss: T,
    /// Rate of change of the rotor's kinetic energy, `J_d ω̇_d ω_d` (W).
    pub rotor_power: T,
    /// Whether power flows from the motor to the mechanism.
    pub direct_flow: bool,
}

impl Motor {
    /// Checks the data.
    pub(crate) fn validate(&self) -> Result<(), Error> {
        if !(self.rotor_inertia.is_finite() && self.rotor_inertia >= 0.0) {
            return Err(Error::InvalidValue {
                what: "rotor inertia of the motor (must be ≥ 0)".to_owned(),
                value: self.rotor_inertia,
            });
        }
        if !(self.ratio.is_finite() && self.ratio != 0.0) {
            return Err(Error::InvalidValue {
                what: "gear ratio of the motor (must be finite and non-zero)".to_owned(),
                value: self.ratio,
            });
        }
        super::efficiency::check_efficiency(
            || "gearbox efficiency of the motor".to_owned(),
            self.efficiency,
        )
    }

    /// The motor state for drive-joint torque `joint_torque` and drive state `drive`; the
    /// rotor inertia counts if `inertia`, the gearbox efficiency if `efficiency`.
    pub fn state(
        &self,
        joint_torque: f64,
        drive: &DriveState,
        inertia: bool,
        efficiency: bool,
    ) -> MotorState {
        self.state_of(joint_torque, drive.omega, drive.alpha, inertia, efficiency)
    }
}

impl<T: Scalar> Motor<T> {
    /// The rotor's inertia reduced to the drive joint, `J_d/τ²`.
    pub(crate) fn reduced_rotor(&self) -> T {
        self.rotor_inertia / (self.ratio * self.ratio)
    }

    /// [`Motor::state`] in any scalar, for drive speed `omega` and acceleration `alpha`. The
    /// direction of power flow is the sign of the real part (a discrete choice: a derivative
    /// is that of the branch taken).
    pub(crate) fn state_of(
        &self,
        joint_torque: T,
        omega: T,
        alpha: T,
        inertia: bool,
        efficiency: bool,
    ) -> MotorState<T> {
        let speed = omega / self.ratio;
        let acceleration = alpha / self.ratio;
        let p_out = joint_torque * omega;
        let direct_flow = p_out.re() >= 0.0;
        let eta = if efficiency {
            self.efficiency
        } else {
            T::one()
        };
        let factor = if direct_flow { eta.recip() } else { eta };
        let rotor = if inertia {
            self.rotor_inertia * acceleration
        } else {
            T::zero()
        };
        let gearbox_torque = joint_torque * self.ratio * factor;
        let gearbox_input = gearbox_torque * speed;
        MotorState {
            speed,
            acceleration,
            torque: rotor + gearbox_torque,
            gearbox_input,
            gearbox_loss: p_out - gearbox_input,
            rotor_power: rotor * speed,
            direct_flow,
        }
    }
}
