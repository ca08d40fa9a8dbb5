//! What a kinetostatic solve gives at one drive position: the reaction in every joint, the
//! drive torque and the power balance ([`Solution`]); the types the equilibrium, energy and
//! tangent modules compute and read.

use super::inertia::InertialLoad;
use super::motor::MotorState;
use super::plan::Trace;
use crate::{DriveState, Scalar};

/// The reaction in one joint.
///
/// `force` and `couple` are what link a of the joint (the first link of a revolute or rigid
/// joint, the guide of a prismatic joint, the slot link of a pin in slot, the pinion's link of
/// a rack-and-pinion) exerts on link b (the second link, the slider, the pin's link, the rack),
/// friction included; the force acts at the joint's point (revolute), measuring point
/// (prismatic) or pin (pin in slot).
///
/// Tooth forces: the tangential tooth force of a rack-and-pinion or gear mesh (pressure
/// angle 0) is included in the reactions of the wheels' bearings (and in their friction
/// circles) when the meshing members turn on a common link, a frame or one carrier (see the
/// `teeth` module); otherwise the mesh acts on the wheels as couples only.
#[derive(Debug, Clone, PartialEq)]
pub struct JointReaction<T = f64> {
    /// Joint name.
    pub joint: String,
    /// Force on link b (N, global components).
    pub force: [T; 2],
    /// Couple on link b (N·m): the prismatic joint's reaction couple, a rigid joint's couple,
    /// a revolute joint's friction torque, the torque on a gear's second link.
    pub couple: T,
    /// Normal force on link b along the guide's normal `n` (prismatic, pin in slot), the
    /// magnitude `|R|` (revolute; its derivative with respect to a parameter is not defined
    /// where `R = 0`), the tooth force on the rack along its guide (rack-and-pinion)
    /// or the torque on the second gear's link (gear) (N or N·m).
    pub normal: T,
    /// Friction force on link b along the guide direction `u` (sliding joints, N) or friction
    /// torque on link b (revolute, N·m); 0 without friction.
    pub friction: T,
    /// Power lost in the joint by friction or imperfect efficiency (W, ≤ 0).
    pub power_loss: T,
}

/// The equilibrium at one drive position.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    /// Drive position.
    pub phi: f64,
    /// Drive state used.
    pub drive: DriveState,
    /// The multipliers λ, one per constraint row (joints in order, the drive last).
    pub multipliers: Vec<f64>,
    /// Torque (N·m) or force (N) the drive joint must apply, positive in the sense of φ.
    pub drive_torque: f64,
    /// The reaction in every joint, in the model's joint order.
    pub reactions: Vec<JointReaction>,
    /// The motor, if the model has one and the plan includes it.
    pub motor: Option<MotorState>,
    /// Inertial loads of the links with mass (empty when inertia is not evaluated).
    pub inertial: Vec<InertialLoad>,
    /// The power balance of this solution.
    pub balance: PowerBalance,
    /// Solves of the equilibrium system (1 without friction and efficiency).
    pub iterations: usize,
    /// What was evaluated.
    pub trace: Trace,
}

/// The power balance at one drive position (W); the loss terms are ≤ 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PowerBalance<T = f64> {
    /// Power of the drive: the motor's `M_d ω_d` with a motor, else the drive joint's `M φ̇`.
    pub drive: T,
    /// Rate of change of the kinetic energy, `Σ (m a_G·v_G + J θ̈ θ̇)` (+ `J_d ω̇_d ω_d`);
    /// 0 when inertia is not in the plan.
    pub kinetic_rate: T,
    /// Power of the weights.
    pub gravity: T,
    /// Power of the external loads.
    pub loads: T,
    /// Power lost by friction.
    pub friction: T,
    /// Power lost in meshes and in the motor's gearbox.
    pub efficiency: T,
    /// The drive torque from the balance, `(dT/dt − P_gravity − P_loads − P_friction −
    /// P_efficiency)/ω` (the motor's torque with a motor); `None` at rest.
    pub torque: Option<T>,
    /// The drive torque from the equilibrium equations (the motor's with a motor).
    pub kinetostatic_torque: T,
    /// `drive + gravity + loads + friction + efficiency − kinetic_rate` (0 up to rounding).
    pub residual: T,
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
}

impl<T: Scalar> PowerBalance<T> {
    /// Difference of the two drive torques, `None` at rest.
    pub fn torque_difference(&self) -> Option<T> {
        self.torque.map(|t| self.kinetostatic_torque - t)
    }
}
