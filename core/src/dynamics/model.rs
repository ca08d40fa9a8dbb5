//! The data of the effects ([`Dynamics`]) and its compiled, validated form ([`CompiledModel`]).

use super::efficiency::{self, CompiledEfficiency, Efficiency};
use super::friction::{self, CompiledFriction, Friction};
use super::gravity::Gravity;
use super::inertia::Mass;
use super::loads::{self, CompiledLoad, Load};
use super::motor::Motor;
use super::plan::Effects;
use crate::Error;
use crate::geometry::{Equations, Mechanism};

/// The effects' data of a mechanism, by name: gravity, external loads, friction, efficiencies
/// and a motor. Masses, centres of gravity and moments of inertia are part of the geometry
/// model ([`crate::geometry::MechanismBuilder::inertia`]).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Dynamics {
    /// Gravity, if it acts.
    pub gravity: Option<Gravity>,
    /// External loads.
    pub loads: Vec<Load>,
    /// Friction per joint.
    pub friction: Vec<Friction>,
    /// Efficiency per rack-and-pinion or gear joint.
    pub efficiency: Vec<Efficiency>,
    /// A motor behind a gearbox at the drive joint.
    pub motor: Option<Motor>,
}

impl Dynamics {
    /// No effect data.
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets gravity.
    pub fn with_gravity(mut self, gravity: Gravity) -> Self {
        self.gravity = Some(gravity);
        self
    }

    /// Adds an external load.
    pub fn with_load(mut self, load: Load) -> Self {
        self.loads.push(load);
        self
    }

    /// Adds friction in a joint.
    pub fn with_friction(mut self, friction: Friction) -> Self {
        self.friction.push(friction);
        self
    }

    /// Adds the efficiency of a mesh.
    pub fn with_efficiency(mut self, efficiency: Efficiency) -> Self {
        self.efficiency.push(efficiency);
        self
    }

    /// Sets the motor.
    pub fn with_motor(mut self, motor: Motor) -> Self {
        self.motor = Some(motor);
        self
    }

    /// The effects this data (and the mechanism's mass properties) can evaluate.
    pub fn available(&self, m: &Mechanism) -> Effects {
        Effects {
            inertia: m.links.iter().any(|l| l.inertia.is_some()),
            gravity: self.gravity.is_some(),
            loads: !self.loads.is_empty(),
            friction: !self.friction.is_empty(),
            efficiency: !self.efficiency.is_empty()
                || self.motor.is_some_and(|mo| mo.efficiency < 1.0),
            motor: self.motor.is_some(),
        }
    }

    /// Validates the data against `m` and resolves names to indices.
    pub fn compile<'m>(&self, m: &'m Mechanism) -> Result<CompiledModel<'m>, Error> {
        let mut rows = Vec::with_capacity(m.joints.len());
        let mut row = 0;
        for j in &m.joints {
            rows.push(row);
            row += j.kind.equation_count();
        }
        let masses = m
            .links
            .iter()
            .enumerate()
            .filter_map(|(k, l)| l.inertia.map(|i| (k, l, i)))
            .map(|(k, l, i)| {
                if !(i.mass >= 0.0 && i.moment >= 0.0) {
                    return Err(Error::InvalidValue {
                        what: format!(
                            "mass or moment of inertia of link `{}` (must be ≥ 0)",
                            l.name
                        ),
                        value: if i.mass < 0.0 { i.mass } else { i.moment },
                    });
                }
                Ok(Mass {
                    link: k,
                    mass: i.mass,
                    center: m.local(k, i.center),
                    moment: i.moment,
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        if let Some(g) = &self.gravity {
            g.validate()?;
        }
        if let Some(mo) = &self.motor {
            mo.validate()?;
        }
        let loads = self
            .loads
            .iter()
            .enumerate()
            .map(|(i, l)| loads::compile(m, l, i))
            .collect::<Result<_, _>>()?;
        let friction = self
            .friction
            .iter()
            .map(|f| friction::compile(m, f, &rows))
            .collect::<Result<_, _>>()?;
        let efficiency = self
            .efficiency
            .iter()
            .map(|e| efficiency::compile(m, e, &rows))
            .collect::<Result<_, _>>()?;
        Ok(CompiledModel {
            mechanism: m,
            equations: Equations::new(m),
            rows,
            drive_row: row,
            masses,
            gravity: self.gravity,
            loads,
            friction,
            efficiency,
            motor: self.motor,
        })
    }
}

/// Effect data resolved against a mechanism, ready to evaluate (see [`Dynamics::compile`]).
#[derive(Debug, Clone)]
pub struct CompiledModel<'m> {
    pub(crate) mechanism: &'m Mechanism,
    pub(crate) equations: Equations,
    /// First constraint row of each joint.
    pub(crate) rows: Vec<usize>,
    /// Row of the drive equation (the last).
    pub(crate) drive_row: usize,
    pub(crate) masses: Vec<Mass>,
    pub(crate) gravity: Option<Gravity>,
    pub(crate) loads: Vec<CompiledLoad>,
    pub(crate) friction: Vec<CompiledFriction>,
    pub(crate) efficiency: Vec<CompiledEfficiency>,
    pub(crate) motor: Option<Motor>,
}

/// The numbers of the effects in scalar `T`, borrowed: what the generic effect code reads
/// (`f64` from a [`CompiledModel`], `Dual64` from a [`super::ModelTangent`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Data<'a, T> {
    pub masses: &'a [Mass<T>],
    /// Gravity vector (m/s²), if given.
    pub gravity: Option<[T; 2]>,
    pub loads: &'a [CompiledLoad<T>],
    pub motor: Option<Motor<T>>,
}

impl<'m> CompiledModel<'m> {
    /// The effects' numbers in `f64`.
    pub(crate) fn data(&self) -> Data<'_, f64> {
        Data {
            masses: &self.masses,
            gravity: self.gravity.map(|g| g.g),
            loads: &self.loads,
            motor: self.motor,
        }
    }

    /// The mechanism.
    pub fn mechanism(&self) -> &'m Mechanism {
        self.mechanism
    }

    /// The motor, if any.
    pub fn motor(&self) -> Option<&Motor> {
        self.motor.as_ref()
    }
}
