//! Checks a user can see: the kinetic energy, the reduced moment of inertia `J_red(φ)` and
//! its derivative, and the power balance
//! `P_drive + P_gravity + P_loads + P_friction + P_efficiency = dT/dt`
//! which gives the drive torque a second way.

use super::inertia::Mass;
use super::kinetostatics::JointReaction;
use super::model::CompiledModel;
use super::motor::MotorState;
use super::plan::Effects;
use super::state::{self, LinkState, dot, of};
use super::{gravity, loads};
use crate::geometry::Mechanism;
use crate::{DriveState, Jet};

/// Kinetic energy and reduced moment of inertia at one drive position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Energy {
    /// Kinetic energy `T = ½ J_red ω²` (J), the motor's rotor included.
    pub kinetic: f64,
    /// Reduced moment of inertia `J_red = Σ m |r_G′|² + J θ′² (+ J_d/τ²)` (kg·m², or kg for
    /// a linear drive).
    pub reduced_inertia: f64,
    /// `dJ_red/dφ = 2 Σ (m r_G′·r_G″ + J θ′ θ″)` (kg·m²/rad); `None` from first derivatives
    /// only.
    pub reduced_inertia_derivative: Option<f64>,
    /// `dT/dt = J_red ω α + ½ J_red′ ω³` (W); `None` from first derivatives only.
    pub kinetic_rate: Option<f64>,
}

/// The kinetic energy of the links with mass (and of the motor's rotor) at the pose of
/// `coordinates` (with their first `N ≥ 1` φ-derivatives) for drive state `drive`.
pub fn energy<const N: usize>(
    model: &CompiledModel<'_>,
    coordinates: &[Jet<N>],
    drive: &DriveState,
) -> Energy {
    const { assert!(N >= 1, "the kinetic energy needs first derivatives") };
    let padded: Vec<Jet<2>> = coordinates
        .iter()
        .map(|j| {
            Jet::new(
                j.value,
                [
                    j.derivatives[0],
                    j.derivatives.get(1).copied().unwrap_or(0.0),
                ],
            )
        })
        .collect();
    // With ω = 1 and α = 0 the "velocities" are the φ-derivatives r′, θ′ and the
    // "accelerations" the second derivatives r″, θ″.
    let d = state::link_states(&padded, &DriveState::constant_speed(1.0));
    let (j, dj) = reduced(&model.masses, &d);
    let rotor = model
        .motor
        .map_or(0.0, |mo| mo.rotor_inertia / (mo.ratio * mo.ratio));
    let j = j + rotor;
    let w = drive.omega;
    Energy {
        kinetic: 0.5 * j * w * w,
        reduced_inertia: j,
        reduced_inertia_derivative: (N >= 2).then_some(dj),
        kinetic_rate: (N >= 2).then_some(j * w * drive.alpha + 0.5 * dj * w * w * w),
    }
}

fn reduced(masses: &[Mass], d: &[LinkState]) -> (f64, f64) {
    let mut j = 0.0;
    let mut dj = 0.0;
    for m in masses {
        let s = of(d, m.link);
        let g = s.position(m.center);
        let (v, a) = (s.velocity_at(g), s.acceleration_at(g));
        j += m.mass * dot(v, v) + m.moment * s.omega * s.omega;
        dj += 2.0 * (m.mass * dot(v, a) + m.moment * s.omega * s.alpha);
    }
    (j, dj)
}

/// The power balance at one drive position (W); the loss terms are ≤ 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PowerBalance {
    /// Power of the drive: the motor's `M_d ω_d` with a motor, else the drive joint's `M φ̇`.
    pub drive: f64,
    /// Rate of change of the kinetic energy, `Σ (m a_G·v_G + J θ̈ θ̇)` (+ `J_d ω̇_d ω_d`);
    /// 0 when inertia is not in the plan.
    pub kinetic_rate: f64,
    /// Power of the weights.
    pub gravity: f64,
    /// Power of the external loads.
    pub loads: f64,
    /// Power lost by friction.
    pub friction: f64,
    /// Power lost in meshes and in the motor's gearbox.
    pub efficiency: f64,
    /// The drive torque from the balance, `(dT/dt − P_gravity − P_loads − P_friction −
    /// P_efficiency)/ω` (the motor's torque with a motor); `None` at rest.
    pub torque: Option<f64>,
    /// The drive torque from the equilibrium equations (the motor's with a motor).
    pub kinetostatic_torque: f64,
    /// `drive + gravity + loads + friction + efficiency − kinetic_rate` (0 up to rounding).
    pub residual: f64,
}

impl PowerBalance {
    /// The largest magnitude among the power terms (the scale of the residual).
    pub fn scale(&self) -> f64 {
        [
            self.drive,
            self.kinetic_rate,
            self.gravity,
            self.loads,
            self.friction,
            self.efficiency,
        ]
        .iter()
        .fold(0.0, |a: f64, v| a.max(v.abs()))
    }

    /// Difference of the two drive torques, `None` at rest.
    pub fn torque_difference(&self) -> Option<f64> {
        self.torque.map(|t| self.kinetostatic_torque - t)
    }
}

#[allow(clippy::too_many_arguments)]
pub(crate) fn balance(
    model: &CompiledModel<'_>,
    effects: &Effects,
    phi: f64,
    drive: &DriveState,
    states: &[LinkState],
    drive_torque: f64,
    reactions: &[JointReaction],
    motor: Option<&MotorState>,
) -> PowerBalance {
    let mut kinetic_rate = 0.0;
    if effects.inertia {
        for m in &model.masses {
            let s = of(states, m.link);
            let g = s.position(m.center);
            kinetic_rate +=
                m.mass * dot(s.acceleration_at(g), s.velocity_at(g)) + m.moment * s.alpha * s.omega;
        }
    }
    let gravity = match (&model.gravity, effects.gravity) {
        (Some(g), true) => gravity::power(g, &model.masses, states),
        _ => 0.0,
    };
    let loads = if effects.loads {
        loads::power(&model.loads, phi, states)
    } else {
        0.0
    };
    let friction: f64 = reactions
        .iter()
        .zip(&model.mechanism.joints)
        .filter(|(_, j)| {
            !matches!(
                j.kind,
                crate::geometry::JointKind::RackPinion { .. }
                    | crate::geometry::JointKind::Gear { .. }
            )
        })
        .map(|(r, _)| r.power_loss)
        .sum();
    let mut efficiency: f64 = reactions
        .iter()
        .zip(&model.mechanism.joints)
        .filter(|(_, j)| {
            matches!(
                j.kind,
                crate::geometry::JointKind::RackPinion { .. }
                    | crate::geometry::JointKind::Gear { .. }
            )
        })
        .map(|(r, _)| r.power_loss)
        .sum();
    let (power, speed, torque) = match motor {
        Some(ms) => {
            efficiency += ms.gearbox_loss;
            kinetic_rate += ms.rotor_power;
            (ms.torque * ms.speed, ms.speed, ms.torque)
        }
        None => (drive_torque * drive.omega, drive.omega, drive_torque),
    };
    let others = gravity + loads + friction + efficiency;
    PowerBalance {
        drive: power,
        kinetic_rate,
        gravity,
        loads,
        friction,
        efficiency,
        torque: (speed != 0.0).then(|| (kinetic_rate - others) / speed),
        kinetostatic_torque: torque,
        residual: power + others - kinetic_rate,
    }
}

/// The diagonal of the sketch's bounding box (m), at least 1e-3: a length scale.
pub(crate) fn size(m: &Mechanism) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in &m.points {
        for i in 0..2 {
            lo[i] = lo[i].min(p.sketch[i]);
            hi[i] = hi[i].max(p.sketch[i]);
        }
    }
    let d = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
    if d.is_finite() { d.max(1e-3) } else { 1.0 }
}
