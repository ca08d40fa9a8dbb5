//! Checks a user can see: the kinetic energy, the reduced moment of inertia `J_red(φ)` and
//! its derivative, and the power balance
//! `P_drive + P_gravity + P_loads + P_friction + P_efficiency = dT/dt`
//! which gives the drive torque a second way.

use super::inertia::Mass;
use super::model::{CompiledModel, Data};
use super::motor::MotorState;
use super::plan::Effects;
use super::solution::{JointReaction, PowerBalance};
use super::state::{self, LinkState, dot, of};
use super::{gravity, loads};
use crate::geometry::{JointKind, Mechanism};
use crate::{DriveState, Jet, Scalar};

/// Kinetic energy and reduced moment of inertia at one drive position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Energy<T = f64> {
    /// Kinetic energy `T = ½ J_red ω²` (J), the motor's rotor included.
    pub kinetic: T,
    /// Reduced moment of inertia `J_red = Σ m |r_G′|² + J θ′² (+ J_d/τ²)` (kg·m², or kg for
    /// a linear drive).
    pub reduced_inertia: T,
    /// `dJ_red/dφ = 2 Σ (m r_G′·r_G″ + J θ′ θ″)` (kg·m²/rad); `None` from first derivatives
    /// only.
    pub reduced_inertia_derivative: Option<T>,
    /// `dT/dt = J_red ω α + ½ J_red′ ω³` (W); `None` from first derivatives only.
    pub kinetic_rate: Option<T>,
}

/// The kinetic energy of the links with mass (and of the motor's rotor) at the pose of
/// `coordinates` (with their first `N ≥ 1` φ-derivatives) for drive state `drive`.
pub fn energy<const N: usize>(
    model: &CompiledModel<'_>,
    coordinates: &[Jet<N>],
    drive: &DriveState,
) -> Energy {
    const { assert!(N >= 1, "the kinetic energy needs first derivatives") };
    // q″ read as 0 from first derivatives only.
    let jet = |j: &Jet<N>| {
        let second = j.derivatives.get(1).copied().unwrap_or(0.0);
        [j.value, j.derivatives[0], second]
    };
    let e = energy_of(&model.data(), coordinates, jet, drive.omega, drive.alpha);
    Energy {
        reduced_inertia_derivative: e.reduced_inertia_derivative.filter(|_| N >= 2),
        kinetic_rate: e.kinetic_rate.filter(|_| N >= 2),
        ..e
    }
}

/// [`energy`] in any scalar, from `(q, q′, q″)` of every coordinate (`jet`) and the drive's
/// speed and acceleration.
pub(crate) fn energy_of<C, T: Scalar>(
    data: &Data<'_, T>,
    coordinates: &[C],
    jet: impl Fn(&C) -> [T; 3],
    omega: T,
    alpha: T,
) -> Energy<T> {
    // With ω = 1 and α = 0 the "velocities" are the φ-derivatives r′, θ′ and the
    // "accelerations" the second derivatives r″, θ″.
    let d = state::states_of(coordinates, jet, T::one(), T::zero());
    let (j, dj) = reduced(data.masses, &d);
    let j = j + data.motor.map_or(T::zero(), |mo| mo.reduced_rotor());
    let w = omega;
    Energy {
        kinetic: j * w * w * 0.5,
        reduced_inertia: j,
        reduced_inertia_derivative: Some(dj),
        kinetic_rate: Some(j * w * alpha + dj * w * w * w * 0.5),
    }
}

fn reduced<T: Scalar>(masses: &[Mass<T>], d: &[LinkState<T>]) -> (T, T) {
    let mut j = T::zero();
    let mut dj = T::zero();
    for m in masses {
        let s = of(d, m.link);
        let g = s.position(m.center);
        let (v, a) = (s.velocity_at(g), s.acceleration_at(g));
        j += m.mass * dot(v, v) + m.moment * s.omega * s.omega;
        dj += (m.mass * dot(v, a) + m.moment * s.omega * s.alpha) * 2.0;
    }
    (j, dj)
}

/// The power balance from the data `data` of `m`, in any scalar; `omega` is the drive speed.
#[allow(clippy::too_many_arguments)]
pub(crate) fn balance<T: Scalar>(
    m: &Mechanism,
    data: &Data<'_, T>,
    effects: &Effects,
    phi: f64,
    omega: T,
    states: &[LinkState<T>],
    drive_torque: T,
    reactions: &[JointReaction<T>],
    motor: Option<&MotorState<T>>,
) -> PowerBalance<T> {
    let mut kinetic_rate = T::zero();
    if effects.inertia {
        for m in data.masses {
            let s = of(states, m.link);
            let g = s.position(m.center);
            kinetic_rate +=
                m.mass * dot(s.acceleration_at(g), s.velocity_at(g)) + m.moment * s.alpha * s.omega;
        }
    }
    let gravity = match (data.gravity, effects.gravity) {
        (Some(g), true) => gravity::power(g, data.masses, states),
        _ => T::zero(),
    };
    let loads = if effects.loads {
        loads::power(data.loads, phi, states)
    } else {
        T::zero()
    };
    let mesh = |j: &&crate::geometry::Joint| {
        matches!(
            j.kind,
            JointKind::RackPinion { .. } | JointKind::Gear { .. }
        )
    };
    let friction: T = reactions
        .iter()
        .zip(&m.joints)
        .filter(|(_, j)| !mesh(j))
        .map(|(r, _)| r.power_loss)
        .sum();
    let mut efficiency: T = reactions
        .iter()
        .zip(&m.joints)
        .filter(|(_, j)| mesh(j))
        .map(|(r, _)| r.power_loss)
        .sum();
    let (power, speed, torque) = match motor {
        Some(ms) => {
            efficiency += ms.gearbox_loss;
            kinetic_rate += ms.rotor_power;
            (ms.torque * ms.speed, ms.speed, ms.torque)
        }
        None => (drive_torque * omega, omega, drive_torque),
    };
    let others = gravity + loads + friction + efficiency;
    PowerBalance {
        drive: power,
        kinetic_rate,
        gravity,
        loads,
        friction,
        efficiency,
        torque: (speed.re() != 0.0).then(|| (kinetic_rate - others) / speed),
        kinetostatic_torque: torque,
        residual: power + others - kinetic_rate,
    }
}

/// The diagonal of the sketch's bounding box (m), at least 1e-3: a length scale.
pub(crate) fn size(m: &Mechanism) -> f64 {
    let d = crate::geometry::length::extent(m.points.iter().map(|p| p.sketch));
    if d.is_finite() { d.max(1e-3) } else { 1.0 }
}
