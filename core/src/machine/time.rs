//! The motion in time: `(φ, φ̇)` integrated from a start state until a stop condition, the
//! load switches located as events and never stepped over.
//!
//! The drive range between two load switches is one stretch: its right-hand side is the
//! machine with the loads of that stretch acting everywhere (smooth up to and beyond the
//! stretch's ends), and the integration stops at the step where φ leaves the stretch, at the
//! time where the dense output reaches the switch (located down to adjacent floating-point
//! times), and restarts there with the other loads. Turn ends, the speed asked for and rest
//! are located the same way. Friction's and the gearbox's sign changes are left to the error
//! control (they are not events).

use super::equation::{Machine, Speed};
use super::error::MotionError;
use super::integrate::{Tolerances, crossed, failed, locate, state_at};
use crate::dynamics::CompiledModel;
use crate::geometry::Tracker;
use differential_equations::prelude::{ControlFlag, IVP, Interpolation, ODE, Solout, Solution};
use std::cell::{Cell, RefCell};
use std::f64::consts::TAU;

/// Where a run starts (default: at rest at φ = 0, time 0).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Start {
    /// Time (s).
    pub time: f64,
    /// Drive position φ.
    pub phi: f64,
    /// Drive speed φ̇.
    pub omega: f64,
}

impl Start {
    /// At rest at `phi`, time 0.
    pub fn at_rest(phi: f64) -> Self {
        Start {
            time: 0.0,
            phi,
            omega: 0.0,
        }
    }
}

/// What ends a run in time (the first that happens); at least one of time, turns and speed.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Stop {
    /// At this time (s).
    pub time: Option<f64>,
    /// After this many turns of an angle drive forward from the start (2π each).
    pub turns: Option<f64>,
    /// When the drive speed reaches this value (from either side).
    pub speed: Option<f64>,
    /// When two consecutive turns differ in duration by at most this fraction.
    pub steady: Option<f64>,
}

impl Stop {
    fn validate(&self, start: &Start) -> Result<(), MotionError> {
        if self.time.is_none() && self.turns.is_none() && self.speed.is_none() {
            return Err(MotionError::NoStopCondition);
        }
        let positive = |what, v: Option<f64>| match v {
            Some(v) if !(v.is_finite() && v > 0.0) => {
                Err(MotionError::InvalidValue { what, value: v })
            }
            _ => Ok(()),
        };
        positive("number of turns (must be > 0)", self.turns)?;
        positive("steady-state fraction (must be > 0)", self.steady)?;
        if let Some(t) = self.time
            && !(t.is_finite() && t > start.time)
        {
            return Err(MotionError::InvalidValue {
                what: "stop time (must be after the start)",
                value: t,
            });
        }
        if let Some(w) = self.speed
            && !w.is_finite()
        {
            return Err(MotionError::InvalidValue {
                what: "stop speed",
                value: w,
            });
        }
        Ok(())
    }
}

/// The machine at one output time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Time (s).
    pub time: f64,
    /// Drive position φ.
    pub phi: f64,
    /// Drive speed φ̇.
    pub omega: f64,
    /// The characteristic's torque on the motor shaft (N·m; 0 without a motor).
    pub motor_torque: f64,
}

/// What an event is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EventKind {
    /// A load switched on or off.
    LoadSwitch,
    /// A turn completed.
    Turn,
    /// The stop speed was reached.
    Speed,
    /// The drive speed reached zero.
    Rest,
}

/// A located event.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Event {
    /// What happened.
    pub kind: EventKind,
    /// The machine there (for an angle event, φ is the event's angle exactly).
    pub at: Sample,
    /// `|g|` of the event function on the dense output where it was located (rad for an
    /// angle, rad/s for a speed): how closely the located time meets the event.
    pub residual: f64,
}

/// One record of a run, in time order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Record {
    /// The state at the end of an accepted step (and at the start).
    Step(Sample),
    /// A located event.
    Event(Event),
}

/// Why a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopReason {
    /// The stop time.
    Time,
    /// The number of turns.
    Turns,
    /// The stop speed.
    Speed,
    /// Two consecutive turns of (nearly) equal duration.
    Steady,
    /// The drive speed reached zero.
    Rest,
}

/// How a run ended and what it cost; the records went to the run's sink.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Simulation {
    /// The last state.
    pub end: Sample,
    /// Why it ended.
    pub reason: StopReason,
    /// Accepted steps.
    pub steps: usize,
    /// Evaluations of the equation of motion (each one position solve and one or more
    /// kinetostatic solves).
    pub evaluations: usize,
    /// Stretches integrated (one more after each event).
    pub stretches: usize,
    /// Largest characteristic torque over the records (N·m).
    pub peak_motor_torque: f64,
    /// Largest drive speed over the records.
    pub max_speed: f64,
    /// Duration of the last complete turn, if one was completed.
    pub last_period: Option<f64>,
}

/// The equation of motion in time for one stretch: `y = (φ, φ̇)`.
pub(crate) struct InTime<'a, 'm> {
    pub machine: &'a Machine<'m>,
    pub model: CompiledModel<'m>,
    pub tracker: RefCell<Tracker<'m>>,
    pub failure: RefCell<Option<MotionError>>,
    pub evaluations: Cell<usize>,
}

impl ODE<f64, [f64; 2]> for InTime<'_, '_> {
    fn diff(&self, t: f64, y: &[f64; 2], dydt: &mut [f64; 2]) {
        self.evaluations.set(self.evaluations.get() + 1);
        let state = self.machine.state_in(
            &self.model,
            &mut self.tracker.borrow_mut(),
            y[0],
            Speed::Omega(y[1]),
        );
        match state {
            Ok(s) => *dydt = [y[1], s.alpha],
            Err(e) => {
                let mut failure = self.failure.borrow_mut();
                if failure.is_none() {
                    *failure = Some(at_time(e, t));
                }
                *dydt = [f64::NAN; 2];
            }
        }
    }
}

/// `e` with time `t` where it has a time.
pub(crate) fn at_time(e: MotionError, t: f64) -> MotionError {
    match e {
        MotionError::Mechanism { phi, source, .. } => MotionError::Mechanism {
            phi,
            time: t,
            source,
        },
        other => other,
    }
}

/// An event met on a step, located on the dense output.
#[derive(Clone, Copy)]
struct Met {
    event: Event,
    /// The event's angle, for an angle event.
    angle: Option<f64>,
    /// The step's start `(t, y)`.
    from: (f64, [f64; 2]),
}

/// The event functions of one stretch and what the stretch met.
struct Watch<'s, 'a, 'm> {
    system: &'s InTime<'a, 'm>,
    /// Angles that end the stretch: the load switches below and above, the next turn's end,
    /// the stop angle.
    angles: [(f64, EventKind); 4],
    speed: Option<f64>,
    sink: &'s mut dyn FnMut(Record),
    steps: usize,
    max_steps: usize,
    /// The last accepted step's end.
    last: Option<(f64, [f64; 2])>,
    /// The event met on the last step (located on the dense output), its angle if it is
    /// one, and the step's start.
    met: Option<Met>,
    peak: f64,
    max_speed: f64,
}

impl Watch<'_, '_, '_> {
    fn sample(&self, time: f64, y: [f64; 2]) -> Sample {
        let machine = self.system.machine;
        let motor_torque = machine
            .motor
            .as_ref()
            .map_or(0.0, |c| c.torque(y[1] / machine.ratio()));
        Sample {
            time,
            phi: y[0],
            omega: y[1],
            motor_torque,
        }
    }

    fn record(&mut self, r: Record) {
        let s = match r {
            Record::Step(s) => s,
            Record::Event(e) => e.at,
        };
        self.peak = self.peak.max(s.motor_torque);
        self.max_speed = self.max_speed.max(s.omega);
        (self.sink)(r);
    }
}

impl Solout<f64, [f64; 2]> for &mut Watch<'_, '_, '_> {
    fn solout<I>(
        &mut self,
        t_curr: f64,
        t_prev: f64,
        y_curr: &[f64; 2],
        y_prev: &[f64; 2],
        interpolator: &mut I,
        _: &mut Solution<f64, [f64; 2]>,
    ) -> ControlFlag<f64, [f64; 2]>
    where
        I: Interpolation<f64, [f64; 2]> + ?Sized,
    {
        if self.system.failure.borrow().is_some()
            || !(y_curr[0].is_finite() && y_curr[1].is_finite())
        {
            return ControlFlag::Terminate;
        }
        if t_curr == t_prev {
            return ControlFlag::Continue;
        }
        self.steps += 1;
        self.last = Some((t_curr, *y_curr));
        // The earliest event on this step.
        let mut first: Option<Met> = None;
        let mut consider = |g: &dyn Fn(&[f64; 2]) -> f64, kind, exact: Option<f64>| {
            let (g0, g1) = (g(y_prev), g(y_curr));
            if crossed(g0, g1) {
                let (t, y, r) =
                    locate(interpolator, (t_prev, g0), (t_curr, g1), *y_curr, |_, y| {
                        g(y)
                    });
                if first.is_none_or(|f| t < f.event.at.time) {
                    let at = Sample {
                        time: t,
                        phi: y[0],
                        omega: y[1],
                        motor_torque: f64::NAN,
                    };
                    first = Some(Met {
                        event: Event {
                            kind,
                            at,
                            residual: r,
                        },
                        angle: exact,
                        from: (t_prev, *y_prev),
                    });
                }
            }
        };
        for (angle, kind) in self.angles {
            if angle.is_finite() {
                consider(&|y: &[f64; 2]| y[0] - angle, kind, Some(angle));
            }
        }
        if let Some(w) = self.speed {
            consider(&|y: &[f64; 2]| y[1] - w, EventKind::Speed, None);
        }
        consider(&|y: &[f64; 2]| y[1], EventKind::Rest, None);
        if first.is_some() {
            self.met = first;
            return ControlFlag::Terminate;
        }
        let s = self.sample(t_curr, *y_curr);
        self.record(Record::Step(s));
        if self.steps >= self.max_steps {
            return ControlFlag::Terminate;
        }
        ControlFlag::Continue
    }
}

/// Runs `machine` from `start` until `stop`, with error control `tolerances`; every accepted
/// step and every event goes to `sink` in time order (nothing is kept: memory is flat in the
/// length of the run).
///
/// # Errors
/// Bad settings ([`MotionError::NoStopCondition`], [`MotionError::InvalidValue`]), the
/// equation of motion's errors at the time and position they happen,
/// [`MotionError::TooManySteps`], [`MotionError::Integrator`].
pub fn simulate(
    machine: &Machine<'_>,
    start: Start,
    stop: &Stop,
    tolerances: &Tolerances,
    sink: &mut dyn FnMut(Record),
) -> Result<Simulation, MotionError> {
    machine.validate()?;
    tolerances.validate()?;
    stop.validate(&start)?;
    for (what, v) in [
        ("start time", start.time),
        ("start position", start.phi),
        ("start speed", start.omega),
    ] {
        if !v.is_finite() {
            return Err(MotionError::InvalidValue { what, value: v });
        }
    }
    let mut tracker = machine.tracker()?;
    let (mut t, mut y) = (start.time, [start.phi, start.omega]);
    let end_time = stop.time.unwrap_or(start.time + 1e12);
    let stop_angle = stop.turns.map_or(f64::NAN, |n| start.phi + n * TAU);
    let turn_events = stop.turns.is_some() || stop.steady.is_some();
    let mut turns_done = 0usize;
    let mut turn_started = start.time;
    let mut periods: [Option<f64>; 2] = [None, None];
    let mut simulation = Simulation {
        end: Sample {
            time: t,
            phi: y[0],
            omega: y[1],
            motor_torque: 0.0,
        },
        reason: StopReason::Time,
        steps: 0,
        evaluations: 0,
        stretches: 0,
        peak_motor_torque: f64::NEG_INFINITY,
        max_speed: f64::NEG_INFINITY,
        last_period: None,
    };
    let mut first_record = true;
    loop {
        let (lower, upper) = machine.switches_around(y[0]);
        let system = InTime {
            machine,
            model: machine.loads_between(y[0], (lower, upper), y[1] >= 0.0),
            tracker: RefCell::new(tracker),
            failure: RefCell::new(None),
            evaluations: Cell::new(0),
        };
        let next_turn = if turn_events {
            start.phi + (turns_done + 1) as f64 * TAU
        } else {
            f64::NAN
        };
        let mut watch = Watch {
            system: &system,
            angles: [
                (lower, EventKind::LoadSwitch),
                (upper, EventKind::LoadSwitch),
                (next_turn, EventKind::Turn),
                (stop_angle, EventKind::Turn),
            ],
            speed: stop.speed,
            sink,
            steps: simulation.steps,
            max_steps: tolerances.max_steps,
            met: None,
            last: None,
            peak: simulation.peak_motor_torque,
            max_speed: simulation.max_speed,
        };
        if first_record {
            let s = watch.sample(t, y);
            watch.record(Record::Step(s));
            first_record = false;
        }
        let left = tolerances.max_steps - simulation.steps;
        let result = IVP::ode(&system, t, end_time, y)
            .method(tolerances.method(left + 1))
            .solout(&mut watch)
            .solve();
        let (steps, met, last) = (watch.steps, watch.met, watch.last);
        simulation.stretches += 1;
        if let Some(e) = system.failure.borrow_mut().take() {
            return Err(e);
        }
        let result = result.map_err(failed);
        let met = match met {
            Some(Met { event, angle, from }) => {
                let speed = match event.kind {
                    EventKind::Speed => stop.speed.unwrap_or(0.0),
                    _ => 0.0,
                };
                let e = refine(&system, tolerances, from, event, angle, speed)?;
                watch.record(Record::Event(e));
                Some(e)
            }
            None => None,
        };
        simulation.steps = steps;
        simulation.peak_motor_torque = watch.peak;
        simulation.max_speed = watch.max_speed;
        simulation.evaluations += system.evaluations.get();
        tracker = system.tracker.into_inner();
        result?;
        let Some(event) = met else {
            let Some((te, ye)) = last else {
                return Err(MotionError::Integrator {
                    time: t,
                    message: "no step was taken".to_owned(),
                });
            };
            if simulation.steps >= tolerances.max_steps {
                return Err(MotionError::TooManySteps {
                    steps: simulation.steps,
                    time: te,
                    phi: ye[0],
                });
            }
            // The integration reached the stop time.
            simulation.end = Sample {
                time: te,
                phi: ye[0],
                omega: ye[1],
                motor_torque: machine
                    .motor
                    .as_ref()
                    .map_or(0.0, |c| c.torque(ye[1] / machine.ratio())),
            };
            simulation.reason = StopReason::Time;
            return Ok(simulation);
        };
        (t, y) = (event.at.time, [event.at.phi, event.at.omega]);
        simulation.end = event.at;
        match event.kind {
            EventKind::Speed => {
                simulation.reason = StopReason::Speed;
                return Ok(simulation);
            }
            EventKind::Rest => {
                simulation.reason = StopReason::Rest;
                return Ok(simulation);
            }
            EventKind::LoadSwitch | EventKind::Turn => {}
        }
        // Angle events that fall together are handled together.
        let at_angle = |a: f64| a.is_finite() && (y[0] - a).abs() <= 1e-12 * a.abs().max(1.0);
        if at_angle(next_turn) {
            turns_done += 1;
            let period = t - turn_started;
            turn_started = t;
            periods = [periods[1], Some(period)];
            simulation.last_period = Some(period);
            if let (Some(fraction), [Some(a), Some(b)]) = (stop.steady, periods)
                && (a - b).abs() <= fraction * b
            {
                simulation.reason = StopReason::Steady;
                return Ok(simulation);
            }
        }
        if at_angle(stop_angle) {
            simulation.reason = StopReason::Turns;
            return Ok(simulation);
        }
    }
}

/// The event `e`, located on the dense output on the step from `from`, moved to where the
/// integration itself meets it: the state at the located time integrated from the step's
/// start, and Newton steps in time on `φ − angle` (rate φ̇) or `φ̇ − speed` (rate φ̈); the
/// event's angle or speed is then set exactly, the residual kept.
fn refine(
    system: &InTime<'_, '_>,
    tolerances: &Tolerances,
    from: (f64, [f64; 2]),
    mut e: Event,
    angle: Option<f64>,
    speed: f64,
) -> Result<Event, MotionError> {
    let mut t = e.at.time;
    let mut y = [e.at.phi, e.at.omega];
    let mut residual = f64::INFINITY;
    for _ in 0..8 {
        y = state_at(system, from, t, tolerances)?;
        if let Some(e) = system.failure.borrow_mut().take() {
            return Err(e);
        }
        let (g, rate, scale) = match angle {
            Some(a) => (y[0] - a, y[1], a.abs().max(1.0)),
            None => {
                let s = system.machine.state_in(
                    &system.model,
                    &mut system.tracker.borrow_mut(),
                    y[0],
                    Speed::Omega(y[1]),
                );
                (
                    y[1] - speed,
                    s.map_err(|e| at_time(e, t))?.alpha,
                    speed.abs().max(1.0),
                )
            }
        };
        residual = g.abs();
        if residual <= 4.0 * f64::EPSILON * scale || rate == 0.0 || !rate.is_finite() {
            break;
        }
        t -= g / rate;
    }
    match angle {
        Some(a) => y[0] = a,
        None => y[1] = speed,
    }
    let motor_torque = system
        .machine
        .motor
        .as_ref()
        .map_or(0.0, |c| c.torque(y[1] / system.machine.ratio()));
    e.at = Sample {
        time: t,
        phi: y[0],
        omega: y[1],
        motor_torque,
    };
    e.residual = residual;
    Ok(e)
}

/// [`simulate`] keeping every record.
///
/// # Errors
/// As [`simulate`].
pub fn simulate_collect(
    machine: &Machine<'_>,
    start: Start,
    stop: &Stop,
    tolerances: &Tolerances,
) -> Result<(Simulation, Vec<Record>), MotionError> {
    let mut records = Vec::new();
    let s = simulate(machine, start, stop, tolerances, &mut |r| records.push(r))?;
    Ok((s, records))
}
