//! A motor driving the drive joint through a gearbox: rotor inertia `J_d` behind the gear
//! ratio `τ = φ̇ / ω_d`, and the gearbox efficiency `η` (by direction of power flow).
//!
//! With `M′` the torque the kinetostatics need at the drive joint and `P_out = M′·φ̇`, the
//! power entering the gearbox is `W_e = P_out/η` for direct flow (`P_out ≥ 0`) and
//! `W_e = η·P_out` for reverse flow; the motor torque is `M_d = W_e/ω_d + J_d·ω̇_d`
//! (equivalently `M_d = J_d ω̇_d + M′ τ/η` or `+ M′ τ η`).

use crate::{DriveState, Error};

/// Motor data.
///
/// ```
/// use mechdiff_core::dynamics::Motor;
/// let m = Motor { rotor_inertia: 0.002, ratio: 1.0 / 30.0, efficiency: 0.9 };
/// let s = m.state(26.869788081459216, &mechdiff_core::DriveState::accelerating(1.25, 0.05), true, true);
/// assert!((s.torque - 0.9981773363503413).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motor {
    /// Rotor moment of inertia `J_d` (kg·m²).
    pub rotor_inertia: f64,
    /// Gear ratio `τ = φ̇ / ω_d` (drive-joint speed over motor speed; for a linear drive m/rad).
    pub ratio: f64,
    /// Gearbox efficiency `η ∈ (0, 1]`.
    pub efficiency: f64,
}

/// The motor at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotorState {
    /// Motor speed `ω_d = φ̇/τ` (rad/s).
    pub speed: f64,
    /// Motor acceleration `ω̇_d = φ̈/τ` (rad/s²).
    pub acceleration: f64,
    /// Motor torque `M_d` (N·m).
    pub torque: f64,
    /// Power entering the gearbox, `W_e = (M_d − J_d ω̇_d)·ω_d` (W).
    pub gearbox_input: f64,
    /// Power lost in the gearbox, `P_out − W_e` (W, ≤ 0).
    pub gearbox_loss: f64,
    /// Rate of change of the rotor's kinetic energy, `J_d ω̇_d ω_d` (W).
    pub rotor_power: f64,
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
        let speed = drive.omega / self.ratio;
        let acceleration = drive.alpha / self.ratio;
        let p_out = joint_torque * drive.omega;
        let direct_flow = p_out >= 0.0;
        let eta = if efficiency { self.efficiency } else { 1.0 };
        let factor = if direct_flow { 1.0 / eta } else { eta };
        let rotor = if inertia {
            self.rotor_inertia * acceleration
        } else {
            0.0
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
