//! The energy form: with `φ̇ > 0` the kinetic energy `E = ½ J(φ) φ̇²` and the time are
//! integrated over the drive angle, `dE/dφ = J φ̈ + ½ J′ φ̇²` (the equation of motion times
//! `1/φ̇`) and `dt/dφ = 1/φ̇`. Load switches at drive angles are then the ends of the
//! integration's stretches, exactly; a turn ends at φ₀ + 2π exactly.

use super::equation::{Machine, Speed};
use super::error::MotionError;
use super::integrate::{Tolerances, crossed, failed, locate, state_at};
use super::time::at_time;
use crate::dynamics::CompiledModel;
use crate::geometry::Tracker;
use differential_equations::prelude::{ControlFlag, IVP, Interpolation, ODE, Solout, Solution};
use std::cell::{Cell, RefCell};

/// The machine at one drive angle of an energy-form run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AngleSample {
    /// Drive angle φ (rad).
    pub phi: f64,
    /// Time (s).
    pub time: f64,
    /// Drive speed φ̇ (rad/s).
    pub omega: f64,
    /// Kinetic energy `½ J φ̇²` (J).
    pub energy: f64,
}

/// The equation of motion over the drive angle for one stretch: `y = (E, t)`.
struct InAngle<'a, 'm> {
    machine: &'a Machine<'m>,
    model: CompiledModel<'m>,
    tracker: RefCell<Tracker<'m>>,
    failure: RefCell<Option<MotionError>>,
    evaluations: Cell<usize>,
}

impl InAngle<'_, '_> {
    /// `(φ̇, φ̈)` at `phi` with energy `energy`.
    fn speed(&self, phi: f64, energy: f64) -> Result<(f64, f64), MotionError> {
        self.evaluations.set(self.evaluations.get() + 1);
        let s = self.machine.state_in(
            &self.model,
            &mut self.tracker.borrow_mut(),
            phi,
            Speed::Energy(energy),
        )?;
        Ok((s.omega, s.alpha))
    }
}

impl ODE<f64, [f64; 2]> for InAngle<'_, '_> {
    fn diff(&self, phi: f64, y: &[f64; 2], dydphi: &mut [f64; 2]) {
        self.evaluations.set(self.evaluations.get() + 1);
        let state = self.machine.state_in(
            &self.model,
            &mut self.tracker.borrow_mut(),
            phi,
            Speed::Energy(y[0]),
        );
        match state {
            Ok(s) => *dydphi = [s.energy_slope(), 1.0 / s.omega],
            Err(e) => {
                let mut failure = self.failure.borrow_mut();
                if failure.is_none() {
                    *failure = Some(at_time(e, y[1]));
                }
                *dydphi = [f64::NAN; 2];
            }
        }
    }
}

/// The lowest and highest drive speed of a run and where.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extremes {
    /// Lowest speed (rad/s) and its angle.
    pub min: (f64, f64),
    /// Highest speed (rad/s) and its angle.
    pub max: (f64, f64),
}

impl Extremes {
    fn none() -> Self {
        Extremes {
            min: (f64::INFINITY, f64::NAN),
            max: (f64::NEG_INFINITY, f64::NAN),
        }
    }

    fn add(&mut self, omega: f64, phi: f64) {
        if omega < self.min.0 {
            self.min = (omega, phi);
        }
        if omega > self.max.0 {
            self.max = (omega, phi);
        }
    }
}

/// An energy-form run from one angle to another.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AngleRun {
    /// The end.
    pub end: AngleSample,
    /// Extreme speeds: at the step ends and the stretch ends, and, if asked for, where φ̈
    /// changes sign inside a step (located on the dense output, the speed there integrated
    /// from the step's start).
    pub extremes: Extremes,
    /// Accepted steps.
    pub steps: usize,
    /// Evaluations of the equation of motion.
    pub evaluations: usize,
}

struct Watch<'s, 'a, 'm> {
    system: &'s InAngle<'a, 'm>,
    sink: &'s mut dyn FnMut(AngleSample),
    extremes: Extremes,
    /// Whether φ̈ = 0 is located inside the steps.
    locate_extremes: bool,
    /// φ̈ at the start of the step.
    alpha: f64,
    steps: usize,
    max_steps: usize,
    /// Where φ̈ = 0 inside a step: the step's start and the angle.
    candidates: Vec<(f64, [f64; 2], f64)>,
    /// The last accepted step's end.
    last: Option<(f64, [f64; 2])>,
    failure: Option<MotionError>,
}

impl Solout<f64, [f64; 2]> for &mut Watch<'_, '_, '_> {
    fn solout<I>(
        &mut self,
        phi: f64,
        phi_prev: f64,
        y: &[f64; 2],
        y_prev: &[f64; 2],
        interpolator: &mut I,
        _: &mut Solution<f64, [f64; 2]>,
    ) -> ControlFlag<f64, [f64; 2]>
    where
        I: Interpolation<f64, [f64; 2]> + ?Sized,
    {
        if self.system.failure.borrow().is_some() || !(y[0].is_finite() && y[1].is_finite()) {
            return ControlFlag::Terminate;
        }
        if phi == phi_prev {
            return ControlFlag::Continue;
        }
        self.steps += 1;
        self.last = Some((phi, *y));
        let (omega, alpha) = match self.system.speed(phi, y[0]) {
            Ok(s) => s,
            Err(e) => {
                self.failure = Some(at_time(e, y[1]));
                return ControlFlag::Terminate;
            }
        };
        self.extremes.add(omega, phi);
        if self.locate_extremes && crossed(self.alpha, alpha) {
            // φ̈ = 0 on the dense output, located in φ (the independent variable).
            let system = self.system;
            let (p, _, _) = locate(
                interpolator,
                (phi_prev, self.alpha),
                (phi, alpha),
                *y,
                |p, s| system.speed(p, s[0]).map_or(f64::NAN, |v| v.1),
            );
            // The speed there is integrated from the step's start after the stretch:
            // the dense output is less accurate than the steps.
            self.candidates.push((phi_prev, *y_prev, p));
        }
        self.alpha = alpha;
        (self.sink)(AngleSample {
            phi,
            time: y[1],
            omega,
            energy: y[0],
        });
        if self.steps >= self.max_steps {
            return ControlFlag::Terminate;
        }
        ControlFlag::Continue
    }
}

/// Integrates the energy form of `machine` from angle `from` with energy `energy` and time
/// `time` to angle `to > from`, stretch by stretch between load switches; every accepted step
/// goes to `sink`; the extreme speeds inside the steps are located if `extremes`. `tracker` is
/// moved along.
///
/// # Errors
/// [`MotionError::Stalled`] when the energy reaches zero (the energy form needs φ̇ > 0), the
/// equation of motion's errors, [`MotionError::TooManySteps`], [`MotionError::Integrator`].
#[allow(clippy::too_many_arguments)]
pub(crate) fn integrate<'m>(
    machine: &Machine<'m>,
    tracker: &mut Option<Tracker<'m>>,
    from: f64,
    energy: f64,
    time: f64,
    to: f64,
    tolerances: &Tolerances,
    extremes: bool,
    sink: &mut dyn FnMut(AngleSample),
) -> Result<AngleRun, MotionError> {
    let mut run = AngleRun {
        end: AngleSample {
            phi: from,
            time,
            omega: f64::NAN,
            energy,
        },
        extremes: Extremes::none(),
        steps: 0,
        evaluations: 0,
    };
    let mut phi = from;
    let mut y = [energy, time];
    while phi < to {
        let (lower, upper) = machine.switches_around(phi);
        let end = upper.min(to);
        let Some(t) = tracker.take() else {
            return Err(MotionError::Integrator {
                time: phi,
                message: "no geometry tracker".to_owned(),
            });
        };
        let system = InAngle {
            machine,
            model: machine.loads_between(phi, (lower, upper), true),
            tracker: RefCell::new(t),
            failure: RefCell::new(None),
            evaluations: Cell::new(0),
        };
        let start = system.speed(phi, y[0]);
        let (omega0, alpha0) = match start {
            Ok(s) => s,
            Err(e) => {
                *tracker = Some(system.tracker.into_inner());
                return Err(at_time(e, y[1]));
            }
        };
        run.extremes.add(omega0, phi);
        if run.steps == 0 {
            sink(AngleSample {
                phi,
                time: y[1],
                omega: omega0,
                energy: y[0],
            });
        }
        let mut watch = Watch {
            system: &system,
            sink,
            extremes: run.extremes,
            locate_extremes: extremes,
            alpha: alpha0,
            steps: run.steps,
            max_steps: tolerances.max_steps,
            failure: None,
            candidates: Vec::new(),
            last: None,
        };
        let left = tolerances.max_steps - run.steps;
        // Steps of at most half a radian: the geometry tracker follows every stage.
        let result = IVP::ode(&system, phi, end, y)
            .method(tolerances.method(left + 1).h_max(0.5))
            .solout(&mut watch)
            .solve();
        run.steps = watch.steps;
        run.extremes = watch.extremes;
        let failure = watch.failure.take();
        let last = watch.last;
        let candidates = std::mem::take(&mut watch.candidates);
        if failure.is_none() && system.failure.borrow().is_none() {
            for (from, y_from, p) in candidates {
                let at = state_at(&system, (from, y_from), p, tolerances)
                    .and_then(|s| system.speed(p, s[0]));
                match at {
                    Ok((w, _)) => run.extremes.add(w, p),
                    Err(e) => {
                        *tracker = Some(system.tracker.into_inner());
                        return Err(e);
                    }
                }
            }
        }
        run.evaluations += system.evaluations.get();
        *tracker = Some(system.tracker.into_inner());
        if let Some(e) = system.failure.into_inner().or(failure) {
            return Err(e);
        }
        result.map_err(failed)?;
        let Some((p, ye)) = last else {
            return Err(MotionError::Integrator {
                time: phi,
                message: "no step was taken".to_owned(),
            });
        };
        if p != end {
            return Err(MotionError::TooManySteps {
                steps: run.steps,
                time: ye[1],
                phi: p,
            });
        }
        (phi, y) = (end, ye);
    }
    let t = tracker.as_mut().ok_or(MotionError::Integrator {
        time: phi,
        message: "no geometry tracker".to_owned(),
    })?;
    let omega = machine
        .state_in(&machine.model, t, phi, Speed::Energy(y[0]))
        .map(|s| s.omega)
        .unwrap_or(f64::NAN);
    run.end = AngleSample {
        phi,
        time: y[1],
        omega,
        energy: y[0],
    };
    Ok(run)
}
