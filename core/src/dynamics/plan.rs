//! What to compute: the derivative order and the effects the requested outputs need, and a
//! trace of what was evaluated.

use std::fmt;

/// A set of effects.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Effects {
    /// d'Alembert inertial forces and couples.
    pub inertia: bool,
    /// Weights.
    pub gravity: bool,
    /// External forces and torques.
    pub loads: bool,
    /// Coulomb friction.
    pub friction: bool,
    /// Efficiencies of meshes and of the motor's gearbox.
    pub efficiency: bool,
    /// Motor behind a gearbox (rotor inertia, ratio).
    pub motor: bool,
}

impl Effects {
    /// No effect.
    pub const fn none() -> Self {
        Effects {
            inertia: false,
            gravity: false,
            loads: false,
            friction: false,
            efficiency: false,
            motor: false,
        }
    }

    /// Every effect.
    pub const fn all() -> Self {
        Effects {
            inertia: true,
            gravity: true,
            loads: true,
            friction: true,
            efficiency: true,
            motor: true,
        }
    }

    /// The effects in both sets.
    pub fn and(self, other: Effects) -> Effects {
        Effects {
            inertia: self.inertia && other.inertia,
            gravity: self.gravity && other.gravity,
            loads: self.loads && other.loads,
            friction: self.friction && other.friction,
            efficiency: self.efficiency && other.efficiency,
            motor: self.motor && other.motor,
        }
    }

    /// `(name, on)` for every effect, in a fixed order.
    pub fn list(&self) -> [(&'static str, bool); 6] {
        [
            ("inertia", self.inertia),
            ("gravity", self.gravity),
            ("loads", self.loads),
            ("friction", self.friction),
            ("efficiency", self.efficiency),
            ("motor", self.motor),
        ]
    }
}

/// An output a user can ask for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Request {
    /// Positions only.
    Positions,
    /// Velocities.
    Velocities,
    /// Accelerations.
    Accelerations,
    /// Jerks.
    Jerk,
    /// Joint reactions.
    Reactions,
    /// Drive torque (or force), and the motor torque with a motor.
    DriveTorque,
    /// Kinetic energy.
    KineticEnergy,
    /// Reduced moment of inertia and its derivative.
    ReducedInertia,
    /// Power balance (drive torque both ways, and their difference).
    PowerBalance,
    /// Shaking force and moment on the frame.
    ShakingForce,
}

/// What to evaluate: the derivative order and the effects.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Plan {
    /// Highest φ-derivative needed: 0 positions, 1 velocities, 2 accelerations and forces,
    /// 3 jerk.
    pub order: usize,
    /// Effects to evaluate.
    pub effects: Effects,
    /// Whether the equilibrium (reactions, drive torque) is solved.
    pub kinetostatics: bool,
    /// Whether the kinetic energy and reduced inertia are computed.
    pub energy: bool,
    /// Whether the shaking force is computed.
    pub shaking: bool,
}

impl Plan {
    /// The plan for `requests`, with the effects `available` (those the data provides).
    ///
    /// Forces (reactions, drive torque, power balance) need every available effect, and
    /// accelerations if inertia is among them (else velocities, for friction directions and
    /// powers). The shaking force needs inertia only. Energy needs velocities, the reduced
    /// inertia's derivative accelerations.
    ///
    /// ```
    /// use mechdiff_core::dynamics::{Effects, Plan, Request};
    /// let available = Effects { inertia: true, gravity: true, ..Effects::none() };
    /// let plan = Plan::for_requests(&[Request::ShakingForce], available);
    /// assert_eq!(plan.to_string(), "order 2; effects: inertia; not computed: gravity, loads, friction, efficiency, motor");
    /// ```
    pub fn for_requests(requests: &[Request], available: Effects) -> Plan {
        let mut plan = Plan {
            order: 0,
            effects: Effects::none(),
            kinetostatics: false,
            energy: false,
            shaking: false,
        };
        for r in requests {
            let order = match r {
                Request::Positions => 0,
                Request::Velocities | Request::KineticEnergy => 1,
                Request::Accelerations | Request::ReducedInertia => 2,
                Request::Jerk => 3,
                Request::ShakingForce => {
                    plan.effects.inertia = available.inertia;
                    plan.shaking = true;
                    2
                }
                Request::Reactions | Request::DriveTorque | Request::PowerBalance => {
                    plan.effects = available;
                    plan.kinetostatics = true;
                    if available.inertia { 2 } else { 1 }
                }
            };
            if matches!(r, Request::KineticEnergy | Request::ReducedInertia) {
                plan.energy = true;
            }
            plan.order = plan.order.max(order);
        }
        plan
    }
}

impl fmt::Display for Plan {
    /// `order 2; effects: inertia; not computed: gravity, friction, efficiency`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let list = self.effects.list();
        let on: Vec<&str> = list.iter().filter(|e| e.1).map(|e| e.0).collect();
        let off: Vec<&str> = list.iter().filter(|e| !e.1).map(|e| e.0).collect();
        write!(
            f,
            "order {}; effects: {}",
            self.order,
            if on.is_empty() {
                "none".to_owned()
            } else {
                on.join(", ")
            }
        )?;
        if !off.is_empty() {
            write!(f, "; not computed: {}", off.join(", "))?;
        }
        Ok(())
    }
}

/// How often each effect and each stage was evaluated: the proof that an effect not in the
/// plan costs nothing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Trace {
    /// Positions solved.
    pub positions: usize,
    /// Poses lifted to derivatives (velocities or more).
    pub derivatives: usize,
    /// Kinetic energies evaluated.
    pub energy: usize,
    /// Shaking forces evaluated.
    pub shaking: usize,
    /// Inertial loads evaluated.
    pub inertia: usize,
    /// Weights evaluated.
    pub gravity: usize,
    /// External loads evaluated.
    pub loads: usize,
    /// Friction forces evaluated (once per iteration that uses them).
    pub friction: usize,
    /// Efficiency factors evaluated (once per iteration that uses them).
    pub efficiency: usize,
    /// Motor states evaluated.
    pub motor: usize,
    /// LU factorizations of the equilibrium equations.
    pub equilibrium_solves: usize,
}

impl Trace {
    /// Adds another trace's counts.
    pub fn add(&mut self, o: &Trace) {
        self.positions += o.positions;
        self.derivatives += o.derivatives;
        self.energy += o.energy;
        self.shaking += o.shaking;
        self.inertia += o.inertia;
        self.gravity += o.gravity;
        self.loads += o.loads;
        self.friction += o.friction;
        self.efficiency += o.efficiency;
        self.motor += o.motor;
        self.equilibrium_solves += o.equilibrium_solves;
    }
}
