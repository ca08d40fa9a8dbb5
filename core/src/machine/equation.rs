//! The reduced equation of motion of a machine with one degree of freedom, its right-hand side
//! given by the mechanism's kinetostatics.
//!
//! With `τ`, `J_d` and `η` the gearbox ratio, rotor inertia and efficiency of
//! [`crate::dynamics::Motor`], `J_f` a flywheel on the drive shaft and `M_drive(φ, φ̇, φ̈)` the
//! drive torque of [`crate::dynamics::kinetostatics`] (the torque the drive joint must apply,
//! with the effects asked for — it leaves out the rotor's own inertia torque and the
//! gearbox), the motor's torque balance on its own shaft is
//!
//! `M_motor(φ̇/τ) = J_d·φ̈/τ + τ·f·(M_drive(φ, φ̇, φ̈) + J_f·φ̈)`, `f = 1/η` for power flowing
//! to the mechanism, `f = η` for power flowing back (as [`crate::dynamics::Motor::state`]).
//!
//! Without friction the kinetostatics are linear in the inertial loads, and the coefficient
//! of `φ̈` in `M_drive` is the mechanism's reduced moment of inertia `J_m(φ)` (virtual work:
//! `M_drive·φ̇ = dT_m/dt − P_applied`), so that `M_drive(φ, φ̇, φ̈) = M_drive(φ, φ̇, 0) +
//! J_m(φ)·φ̈` and `M_drive(φ, φ̇, 0) = ½ J_m′(φ) φ̇² + M_res(φ, φ̇)` (the applied loads,
//! weights). With `η = 1` this is the classic reduced form
//!
//! `J(φ)·φ̈ + ½ J′(φ)·φ̇² = M_motor/τ − M_res(φ, φ̇)`, `J = J_d/τ² + J_m(φ) + J_f`,
//!
//! and [`Machine::state`] solves it with ONE kinetostatic solve at `φ̈ = 0`. With friction or
//! efficiencies `M_drive` is not linear in `φ̈` (friction circles, direction of power flow);
//! then the balance above is solved for `φ̈` by Newton steps with the slope
//! `J_d/τ + τ f (J_m + J_f)`, each step one kinetostatic solve at the current `φ̈`.

use super::characteristic::Characteristic;
use super::error::MotionError;
use crate::dynamics::energy::energy_of;
use crate::dynamics::{CompiledModel, Effects, kinetostatics};
use crate::geometry::{Solver, Tracker};
use crate::{DriveState, Jet};

/// How the speed of a state is given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Speed {
    /// The drive speed φ̇.
    Omega(f64),
    /// The kinetic energy `½ J φ̇²` (φ̇ > 0), as the drive-angle form integrates it.
    Energy(f64),
}

/// The most Newton steps for the acceleration with friction or efficiencies.
const MAX_ACCELERATION_STEPS: usize = 50;

/// A mechanism with its effects, a motor characteristic and a flywheel: the reduced equation
/// of motion (see the [module](self)).
#[derive(Debug, Clone)]
pub struct Machine<'m> {
    pub(crate) model: CompiledModel<'m>,
    pub(crate) effects: Effects,
    pub(crate) motor: Option<Characteristic>,
    pub(crate) flywheel: f64,
    pub(crate) solver: Solver,
}

/// The machine at one instant: the terms of its equation of motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MachineState {
    /// Drive position φ (rad, or m).
    pub phi: f64,
    /// Drive speed φ̇.
    pub omega: f64,
    /// Drive acceleration φ̈ from the equation of motion.
    pub alpha: f64,
    /// Reduced moment of inertia `J = J_d/τ² + J_m(φ) + J_f` (kg·m², or kg).
    pub reduced_inertia: f64,
    /// Its derivative `J′ = J_m′(φ)`.
    pub reduced_inertia_derivative: f64,
    /// Motor speed `φ̇/τ` (rad/s).
    pub motor_speed: f64,
    /// The characteristic's torque on the motor shaft (N·m); 0 without a motor.
    pub motor_torque: f64,
    /// The kinetostatic drive torque `M_drive(φ, φ̇, φ̈)` at the drive joint (flywheel and
    /// motor not included).
    pub drive_torque: f64,
    /// Kinetostatic solves this state took.
    pub solves: usize,
}

impl MachineState {
    /// Kinetic energy `E = ½ J φ̇²` (J).
    pub fn kinetic_energy(&self) -> f64 {
        0.5 * self.reduced_inertia * self.omega * self.omega
    }

    /// `dE/dφ = J φ̈ + ½ J′ φ̇²`: the energy form of the equation of motion.
    pub fn energy_slope(&self) -> f64 {
        self.reduced_inertia * self.alpha
            + 0.5 * self.reduced_inertia_derivative * self.omega * self.omega
    }
}

impl<'m> Machine<'m> {
    /// The machine of `model` with the effects `effects` (inertia must be among them, or a
    /// rotor or a flywheel must give inertia), no motor torque and no flywheel. The gearbox
    /// of the model's [`crate::dynamics::Motor`] counts when `effects.motor`.
    pub fn new(model: &CompiledModel<'m>, effects: Effects) -> Self {
        Machine {
            model: model.clone(),
            effects,
            motor: None,
            flywheel: 0.0,
            solver: Solver::default(),
        }
    }

    /// Sets the motor characteristic (on the motor shaft behind the gearbox; at the drive
    /// joint without a motor in the model or the effects).
    pub fn with_motor(mut self, motor: Characteristic) -> Self {
        self.motor = Some(motor);
        self
    }

    /// Removes the motor torque (coasting).
    pub fn without_motor(mut self) -> Self {
        self.motor = None;
        self
    }

    /// Sets a flywheel of moment of inertia `inertia` (kg·m², ≥ 0) on the drive shaft.
    pub fn with_flywheel(mut self, inertia: f64) -> Self {
        self.flywheel = inertia;
        self
    }

    /// Sets the geometry solver's settings.
    pub fn with_solver(mut self, solver: Solver) -> Self {
        self.solver = solver;
        self
    }

    /// The flywheel's moment of inertia.
    pub fn flywheel(&self) -> f64 {
        self.flywheel
    }

    /// The motor characteristic, if any.
    pub fn motor(&self) -> Option<&Characteristic> {
        self.motor.as_ref()
    }

    /// The gear ratio `τ` (1 without a motor in the effects).
    pub fn ratio(&self) -> f64 {
        self.gear().map_or(1.0, |g| g.ratio)
    }

    fn gear(&self) -> Option<crate::dynamics::Motor> {
        self.model.motor.filter(|_| self.effects.motor)
    }

    /// Checks the data: the flywheel and the characteristic.
    ///
    /// # Errors
    /// [`MotionError::InvalidValue`] naming the number.
    pub fn validate(&self) -> Result<(), MotionError> {
        if !(self.flywheel.is_finite() && self.flywheel >= 0.0) {
            return Err(MotionError::InvalidValue {
                what: "flywheel inertia (must be ≥ 0)",
                value: self.flywheel,
            });
        }
        self.motor.as_ref().map_or(Ok(()), Characteristic::validate)
    }

    /// A geometry tracker at the sketch pose.
    ///
    /// # Errors
    /// The geometry's error when the sketch does not assemble.
    pub fn tracker(&self) -> Result<Tracker<'m>, MotionError> {
        self.solver
            .track(self.model.mechanism)
            .map_err(|source| MotionError::Mechanism {
                phi: f64::NAN,
                time: f64::NAN,
                source,
            })
    }

    /// The state at drive position `phi` and speed `omega`: `φ̈` from the equation of
    /// motion, with `tracker` moved to `phi`.
    ///
    /// # Errors
    /// The geometry's or the kinetostatics' error at `phi`, [`MotionError::NoInertia`],
    /// [`MotionError::NoConsistentAcceleration`], [`MotionError::NonFinite`].
    pub fn state(
        &self,
        tracker: &mut Tracker<'m>,
        phi: f64,
        omega: f64,
    ) -> Result<MachineState, MotionError> {
        self.state_in(&self.model, tracker, phi, Speed::Omega(omega))
    }

    /// [`Machine::state`] with the loads of `model` (the machine's model with the loads of
    /// one stretch between switches, see `loads_between`).
    pub(crate) fn state_in(
        &self,
        model: &CompiledModel<'m>,
        tracker: &mut Tracker<'m>,
        phi: f64,
        speed: Speed,
    ) -> Result<MachineState, MotionError> {
        let at = |source| MotionError::Mechanism {
            phi,
            time: f64::NAN,
            source,
        };
        tracker.move_to(phi).map_err(at)?;
        let coordinates: Vec<Jet<2>> = tracker.kinematics::<2>().map_err(at)?.coordinates;
        let mut data = model.data();
        data.motor = None;
        let e = energy_of(
            &data,
            &coordinates,
            |j| [j.value, j.derivatives[0], j.derivatives[1]],
            0.0,
            0.0,
        );
        let (jm, djm) = if self.effects.inertia {
            (
                e.reduced_inertia,
                e.reduced_inertia_derivative.unwrap_or(0.0),
            )
        } else {
            (0.0, 0.0)
        };
        let gear = self.gear();
        let (ratio, rotor) = gear.map_or((1.0, 0.0), |g| (g.ratio, g.rotor_inertia));
        let j = rotor / (ratio * ratio) + jm + self.flywheel;
        if !(j > 0.0 && j.is_finite()) {
            return Err(MotionError::NoInertia { phi, inertia: j });
        }
        let omega = match speed {
            Speed::Omega(omega) => omega,
            Speed::Energy(energy) if energy > 0.0 => (2.0 * energy / j).sqrt(),
            Speed::Energy(_) => {
                return Err(MotionError::Stalled {
                    phi,
                    time: f64::NAN,
                });
            }
        };
        let motor_speed = omega / ratio;
        let motor_torque = self.motor.as_ref().map_or(0.0, |c| c.torque(motor_speed));
        let joint_effects = Effects {
            motor: false,
            ..self.effects
        };
        let drive_torque = |alpha: f64| {
            let d = DriveState {
                omega,
                alpha,
                jerk: 0.0,
            };
            kinetostatics::solve_at(model, &joint_effects, phi, &coordinates, &d)
                .map(|s| s.drive_torque)
                .map_err(at)
        };
        // The torque the motor must give for acceleration `alpha` and drive torque `m`.
        let needed = |alpha: f64, m: f64| match gear {
            Some(g) => {
                g.state_of(
                    m + self.flywheel * alpha,
                    omega,
                    alpha,
                    true,
                    self.effects.efficiency,
                )
                .torque
            }
            None => m + self.flywheel * alpha,
        };
        let m0 = drive_torque(0.0)?;
        let mut solves = 1;
        // Exact without friction and efficiency: M_drive(α) = M_drive(0) + J_m α.
        let mut alpha = (motor_torque / ratio - m0) / j;
        let mut m = m0 + jm * alpha;
        if self.effects.friction || self.effects.efficiency {
            let mut settled = false;
            for _ in 0..MAX_ACCELERATION_STEPS {
                m = drive_torque(alpha)?;
                solves += 1;
                let residual = motor_torque - needed(alpha, m);
                let direct = (m + self.flywheel * alpha) * omega >= 0.0;
                let eta = match gear {
                    Some(g) if self.effects.efficiency => g.efficiency,
                    _ => 1.0,
                };
                let f = if direct { 1.0 / eta } else { eta };
                let slope = rotor / ratio + ratio * f * (jm + self.flywheel);
                let step = residual / slope;
                alpha += step;
                if step.abs()
                    <= 1e-13
                        * alpha
                            .abs()
                            .max(motor_torque.abs().max(m0.abs()) / (ratio * j))
                {
                    settled = true;
                    break;
                }
            }
            if !settled {
                return Err(MotionError::NoConsistentAcceleration { phi, omega });
            }
        }
        if !alpha.is_finite() {
            return Err(MotionError::NonFinite {
                phi,
                quantity: "the drive acceleration",
            });
        }
        Ok(MachineState {
            phi,
            omega,
            alpha,
            reduced_inertia: j,
            reduced_inertia_derivative: djm,
            motor_speed,
            motor_torque,
            drive_torque: m,
            solves,
        })
    }

    /// The machine's model with only the loads acting between `from` and the next switch
    /// in the direction of motion (`forward`: up to `upper`, else down to `lower`), each
    /// made to act everywhere: the right-hand side of one stretch between two load switches,
    /// smooth up to and beyond its ends.
    pub(crate) fn loads_between(
        &self,
        from: f64,
        (lower, upper): (f64, f64),
        forward: bool,
    ) -> CompiledModel<'m> {
        let to = if forward { upper } else { lower };
        let mid = if to.is_finite() {
            0.5 * (from + to)
        } else if forward {
            from + 1.0
        } else {
            from - 1.0
        };
        let mut model = self.model.clone();
        model.loads.retain(|l| l.acts_at(mid));
        for l in &mut model.loads {
            l.active = None;
        }
        model
    }

    /// The nearest drive positions below and above `phi` where a load switches on or off
    /// (±∞ for none); a switch at `phi` itself (within 1e-12 relative) is neither.
    pub(crate) fn switches_around(&self, phi: f64) -> (f64, f64) {
        let tau = std::f64::consts::TAU;
        let margin = 1e-12 * phi.abs().max(1.0);
        let mut lower = f64::NEG_INFINITY;
        let mut upper = f64::INFINITY;
        if !self.effects.loads {
            return (lower, upper);
        }
        for l in &self.model.loads {
            let Some([from, to]) = l.active else { continue };
            for edge in [from, to] {
                let candidates = if l.periodic {
                    if to - from >= tau {
                        continue;
                    }
                    let below = edge + ((phi - edge) / tau).floor() * tau;
                    vec![below - tau, below, below + tau, below + 2.0 * tau]
                } else {
                    vec![edge]
                };
                for candidate in candidates {
                    if candidate < phi - margin && candidate > lower {
                        lower = candidate;
                    }
                    if candidate > phi + margin && candidate < upper {
                        upper = candidate;
                    }
                }
            }
        }
        (lower, upper)
    }
}
