//! Executing a [`Plan`] over a sweep of drive positions: positions only, derivatives of the
//! order asked, and only the dynamic outputs and effects in the plan.

use super::energy::{Energy, energy};
use super::kinetostatics;
use super::model::CompiledModel;
use super::plan::{Plan, Trace};
use super::shaking::{ShakingForce, shaking_into};
use super::solution::Solution;
use super::state::{self, LinkState};
use crate::geometry::{Solver, Tracker};
use crate::sweep::{Consumer, Sweep};
use crate::{DriveState, Error, Jet};

/// The results at one drive position; what the plan did not ask for is `None`.
#[derive(Debug, Clone, PartialEq)]
pub struct Step {
    /// Drive position.
    pub phi: f64,
    /// Drive state.
    pub drive: DriveState,
    /// Reactions, drive torque, power balance.
    pub solution: Option<Solution>,
    /// Kinetic energy and reduced inertia.
    pub energy: Option<Energy>,
    /// Shaking force.
    pub shaking: Option<ShakingForce>,
}

impl Step {
    /// The step at drive position `phi` with drive state `drive`, before anything is
    /// evaluated: the results the plan asks for are filled in by the runner.
    pub(crate) fn at(phi: f64, drive: DriveState) -> Self {
        Step {
            phi,
            drive,
            solution: None,
            energy: None,
            shaking: None,
        }
    }
}

/// The results of a planned sweep and what it evaluated.
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    /// One step per drive position.
    pub steps: Vec<Step>,
    /// Everything evaluated, summed over the sweep.
    pub trace: Trace,
}

/// Runs `plan` for `model` at the drive positions `phis` (in order, from the sketch pose),
/// with the drive state `drive(φ)` at each.
///
/// ```
/// use mechdiff_core::dynamics::{Dynamics, Plan, Request, run::run};
/// use mechdiff_core::geometry::{Drive, Inertia, Mechanism, Solver};
/// use mechdiff_core::DriveState;
/// let m = Mechanism::builder()
///     .point("O", [0.0, 0.0]).point("A", [1.0, 0.0])
///     .ground(["O"]).link("crank", ["O", "A"])
///     .inertia("crank", Inertia { mass: 2.0, center: [0.5, 0.0], moment: 0.0 })
///     .revolute("O", "ground", "crank", "O")
///     .drive(Drive::angle("O"))
///     .build().unwrap();
/// let d = Dynamics::new();
/// let model = d.compile(&m).unwrap();
/// let plan = Plan::for_requests(&[Request::Positions], d.available(&m));
/// let r = run(&plan, &model, &Solver::default(), &[0.0, 0.5], |_| DriveState::constant_speed(1.0)).unwrap();
/// assert_eq!((r.trace.positions, r.trace.derivatives, r.trace.inertia), (2, 0, 0));
/// ```
pub fn run(
    plan: &Plan,
    model: &CompiledModel<'_>,
    solver: &Solver,
    phis: &[f64],
    drive: impl Fn(f64) -> DriveState,
) -> Result<Run, Error> {
    let states: Vec<(f64, DriveState)> = phis.iter().map(|&phi| (phi, drive(phi))).collect();
    run_states(plan, model, solver, &states)
}

/// [`run`] with the drive state given with each drive position (a drive whose speed is not
/// a function of its position, e.g. one moved by a cam: see [`crate::cams::joint`]).
pub fn run_states(
    plan: &Plan,
    model: &CompiledModel<'_>,
    solver: &Solver,
    states: &[(f64, DriveState)],
) -> Result<Run, Error> {
    run_moved(plan, model, solver, states, |tracker, k| {
        tracker.move_to(states[k].0).map(drop)
    })
}

/// [`run_states`] with the tracker brought to state `k`'s drive position by
/// `move_to(tracker, k)` (in order, from the sketch pose): a drive that reaches its next
/// position along a path of its own, e.g. a cam's follower through every displacement it
/// passes ([`crate::cams::CamJoint::move_tracker`]).
pub fn run_moved(
    plan: &Plan,
    model: &CompiledModel<'_>,
    solver: &Solver,
    states: &[(f64, DriveState)],
    mut move_to: impl FnMut(&mut Tracker<'_>, usize) -> Result<(), Error>,
) -> Result<Run, Error> {
    check(plan, model)?;
    let mut steps = Steps {
        plan,
        model,
        states,
        trace: Trace::default(),
        steps: Vec::with_capacity(states.len()),
    };
    Sweep::new(model.mechanism, solver)?
        .with(&mut steps)
        .run_moved(states.iter().map(|s| s.0), &mut (), |tracker, k, _| {
            move_to(tracker, k)
        })?;
    Ok(Run {
        steps: steps.steps,
        trace: steps.trace,
    })
}

/// The steps of a planned run at drive states `states`, one per pose the sweep solves.
struct Steps<'a, 'm> {
    plan: &'a Plan,
    model: &'a CompiledModel<'m>,
    states: &'a [(f64, DriveState)],
    trace: Trace,
    steps: Vec<Step>,
}

impl Consumer for Steps<'_, '_> {
    fn at(&mut self, tracker: &Tracker<'_>, phi: f64, _: &mut Vec<f64>) -> Result<(), Error> {
        let d = self.states[self.steps.len()].1;
        let step = step_at(self.plan, self.model, tracker, phi, d, &mut self.trace)?;
        self.steps.push(step);
        Ok(())
    }
}

/// What a planned sweep checks before solving any position: a shaking force needs a link
/// with mass.
///
/// # Errors
/// [`Error::MissingData`] when the plan asks for the shaking force of a model without mass.
pub fn check(plan: &Plan, model: &CompiledModel<'_>) -> Result<(), Error> {
    if plan.shaking && model.masses.is_empty() {
        return Err(Error::MissingData {
            what: "the shaking force".to_owned(),
            missing: "mass properties of at least one link".to_owned(),
        });
    }
    Ok(())
}

/// The results of `plan` at the pose `tracker` stands at (moved to drive position `phi`
/// by the caller, nothing solved here), with drive state `d`: the pose lifted to the
/// derivative order the plan needs and every effect the plan asks for, each counted in
/// `trace`. [`run_moved`] calls it at every position of its sweep; a sweep that solves each
/// position once for several consumers calls it with its own tracker.
///
/// # Errors
/// The lift's or the equilibrium's error at `phi`, or [`Error::NonFinite`] naming the
/// quantity that overflowed.
pub fn step_at(
    plan: &Plan,
    model: &CompiledModel<'_>,
    tracker: &Tracker<'_>,
    phi: f64,
    d: DriveState,
    trace: &mut Trace,
) -> Result<Step, Error> {
    trace.positions += 1;
    let mut step = Step::at(phi, d);
    match plan.order {
        0 => {}
        1 => {
            let k = tracker.kinematics::<1>()?;
            trace.derivatives += 1;
            if plan.energy {
                step.energy = Some(energy(model, &k.coordinates, &d));
                trace.energy += 1;
            }
            if plan.kinetostatics {
                // Forces at order 1 are planned only without inertia: the accelerations
                // (q″ padded with 0) are then never read.
                debug_assert!(!plan.effects.inertia);
                let padded: Vec<Jet<2>> = k
                    .coordinates
                    .iter()
                    .map(|j| Jet::new(j.value, [j.derivatives[0], 0.0]))
                    .collect();
                let s = kinetostatics::solve_at(model, &plan.effects, phi, &padded, &d)?;
                trace.add(&s.trace);
                step.solution = Some(s);
            }
        }
        _ => {
            let mut coordinates = Vec::new();
            tracker.coordinates_into(&mut coordinates);
            return step_from(plan, model, phi, d, &coordinates, trace);
        }
    }
    all_finite(&step)?;
    Ok(step)
}

/// What [`step_reusing`] keeps from one position to the next: the pose's coordinates, the
/// links' states and the last step, so that a plan of order 2 or more allocates nothing per
/// position for its shaking force and kinetic energy (the equilibrium's solve still does).
#[derive(Debug, Clone, Default)]
pub struct StepBuffers {
    coordinates: Vec<Jet<2>>,
    states: Vec<LinkState>,
    step: Option<Step>,
}

/// [`step_at`] with buffers kept by the caller from one position to the next: the same
/// results, bit for bit, and a reference to them (valid until the next call).
///
/// # Errors
/// As [`step_at`].
pub fn step_reusing<'b>(
    plan: &Plan,
    model: &CompiledModel<'_>,
    tracker: &Tracker<'_>,
    phi: f64,
    d: DriveState,
    trace: &mut Trace,
    buffers: &'b mut StepBuffers,
) -> Result<&'b Step, Error> {
    if plan.order < 2 {
        return Ok(buffers
            .step
            .insert(step_at(plan, model, tracker, phi, d, trace)?));
    }
    let StepBuffers {
        coordinates,
        states,
        step,
    } = buffers;
    trace.positions += 1;
    tracker.coordinates_into(coordinates);
    let step = step.get_or_insert_with(|| Step::at(phi, d));
    fill(plan, model, phi, d, coordinates, trace, step, states)?;
    Ok(step)
}

/// The results of a plan of order 2 or more (see [`step_at`]) from the pose's coordinates
/// with their first two derivatives: the same numbers at a pose solved before (the
/// counterweights' balanced linkage moves as the linkage does, see
/// [`crate::balancing::LinkageBalancing`]).
///
/// # Errors
/// As [`step_at`].
pub fn step_from(
    plan: &Plan,
    model: &CompiledModel<'_>,
    phi: f64,
    d: DriveState,
    coordinates: &[Jet<2>],
    trace: &mut Trace,
) -> Result<Step, Error> {
    let mut step = Step::at(phi, d);
    fill(
        plan,
        model,
        phi,
        d,
        coordinates,
        trace,
        &mut step,
        &mut Vec::new(),
    )?;
    Ok(step)
}

/// Fills `step` (its buffers reused) with the results of a plan of order 2 or more at the
/// pose `coordinates` (see [`step_from`]); `states` is the links' states' buffer.
#[allow(clippy::too_many_arguments)]
fn fill(
    plan: &Plan,
    model: &CompiledModel<'_>,
    phi: f64,
    d: DriveState,
    coordinates: &[Jet<2>],
    trace: &mut Trace,
    step: &mut Step,
    states: &mut Vec<LinkState>,
) -> Result<(), Error> {
    debug_assert!(plan.order >= 2, "a plan of order {} lifts less", plan.order);
    (step.phi, step.drive) = (phi, d);
    trace.derivatives += 1;
    step.energy = plan.energy.then(|| energy(model, coordinates, &d));
    trace.energy += usize::from(plan.energy);
    if plan.shaking {
        state::link_states_into(coordinates, &d, states);
        let shaking = step.shaking.get_or_insert_with(|| ShakingForce {
            phi,
            force: [0.0; 2],
            moment: 0.0,
            links: Vec::new(),
        });
        shaking_into(&model.masses, phi, states, shaking);
        trace.shaking += 1;
        trace.inertia += 1;
    } else {
        step.shaking = None;
    }
    step.solution = None;
    if plan.kinetostatics {
        let s = kinetostatics::solve_at(model, &plan.effects, phi, coordinates, &d)?;
        trace.add(&s.trace);
        step.solution = Some(s);
    }
    all_finite(step)
}

/// Checks every number of a step: an overflow (or 0/0) for some combination of inputs is
/// [`Error::NonFinite`] naming the quantity and the drive position, never a NaN passed on.
fn all_finite(step: &Step) -> Result<(), Error> {
    let check = |quantity: &'static str, values: &[f64]| {
        if values.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err(Error::NonFinite {
                phi: step.phi,
                quantity,
            })
        }
    };
    if let Some(e) = &step.energy {
        check("the kinetic energy", &[e.kinetic])?;
        check("the reduced moment of inertia", &[e.reduced_inertia])?;
        let derivative = e.reduced_inertia_derivative.unwrap_or(0.0);
        check(
            "the derivative of the reduced moment of inertia",
            &[derivative],
        )?;
        check(
            "the rate of the kinetic energy",
            &[e.kinetic_rate.unwrap_or(0.0)],
        )?;
    }
    if let Some(s) = &step.shaking {
        check("the shaking force", &s.force)?;
        check("the moment of the shaking force", &[s.moment])?;
    }
    if let Some(s) = &step.solution {
        check("the drive torque", &[s.drive_torque])?;
        check("the joint reactions (Lagrange multipliers)", &s.multipliers)?;
        let b = &s.balance;
        let terms = [
            b.drive,
            b.kinetic_rate,
            b.gravity,
            b.loads,
            b.friction,
            b.efficiency,
        ];
        check("a term of the power balance", &terms)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A step whose kinetic energy overflowed is an error naming it and the drive position.
    #[test]
    fn a_non_finite_step_is_an_error_naming_the_quantity() {
        let mut step = Step {
            phi: 0.5,
            drive: DriveState::constant_speed(1.0),
            solution: None,
            energy: Some(Energy {
                kinetic: 1.0,
                reduced_inertia: 2.0,
                reduced_inertia_derivative: None,
                kinetic_rate: Some(0.0),
            }),
            shaking: None,
        };
        assert!(all_finite(&step).is_ok());
        if let Some(e) = step.energy.as_mut() {
            e.kinetic = f64::INFINITY;
        }
        let error = all_finite(&step).unwrap_err();
        assert!(
            matches!(
                error,
                Error::NonFinite {
                    phi: 0.5,
                    quantity: "the kinetic energy"
                }
            ),
            "{error:?}"
        );
    }
}
