//! Running `[simulate]`: the machine built from the scene with exactly the effects it gives,
//! the analyses asked for, their rows streamed as the integration gives them
//! ([`crate::stream::motion`]) and their headline numbers.
//!
//! Every row carries the machine's state (t, φ, φ̇, φ̈, the motor's torque, the kinetostatic
//! drive torque, the reduced inertia) and then the scene's own outputs and `[[dynamics]]`
//! evaluated at that φ with that φ̇ and φ̈: the one sweep of a prescribed-speed run, its
//! drive state set row by row.

use mechdiff_core::DriveState;
use mechdiff_core::machine::{
    AngleSample, CoastDown, EventKind, FlywheelSizing, Machine, MotionError, Record, Sample, Start,
    StartUp, SteadySettings, SteadyState, coast_down, flywheel, start_up, steady_state,
};

use crate::error::{Error, Location, Result};
use crate::scene::model::Scene;
use crate::scene::outputs::Column;
use crate::scene::plan::Plan;
use crate::scene::run::{columns, sweeper};
use crate::scene::setup::{RunOptions, Setup};
use crate::scene::sweep::Sweeper;
use crate::scene::units::Dimension;
use crate::stream::motion::{MotionSinks, Rows, Table};

use super::curves::Curves;
use super::equation;
use super::format::Find;
use super::model::SceneMotion;
use super::playback::{self, Clocked, Part, Playback};
use super::words::{Words, column, flywheel_lines, motion_error, significant, steady_line};

/// What a run with `[simulate]` found (its rows went to the sinks).
#[derive(Debug, Clone, PartialEq)]
pub struct MotionReport {
    /// The start-up, if asked for.
    pub start_up: Option<StartUp>,
    /// The steady state, if asked for.
    pub steady: Option<SteadyState>,
    /// The coast-down, if asked for.
    pub coast_down: Option<CoastDown>,
    /// The flywheel sized both ways, if asked for.
    pub flywheel: Option<FlywheelSizing>,
    /// Rows of the table over time.
    pub time_rows: usize,
    /// Rows of the steady state's table over the drive angle.
    pub steady_rows: usize,
    /// The table over time's columns (SI values per printed unit).
    pub time_columns: Vec<Column>,
    /// The steady-state table's columns.
    pub steady_columns: Vec<Column>,
    /// The curves for the diagrams, in the printed units.
    pub curves: Curves,
    /// The headline numbers, one line each, in the scene's units.
    pub summary: Vec<String>,
    /// The plan: the equation's terms as printed before the tables.
    pub plan: String,
    /// The frames of a report's playback, when [`MotionOptions::playback`] asks for them.
    pub playback: Option<Playback>,
}

/// What a run with `[simulate]` produces besides its streamed tables.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct MotionOptions {
    /// The frames of a report that plays the motion in real time ([`Playback`]): states at
    /// equal steps of simulated time, at most [`playback::PLAYBACK_FRAMES`].
    pub playback: bool,
    /// Only the plan ([`MotionReport::plan`]: the equation's terms, J(φ)'s range, what the
    /// analyses find and where they stop), nothing simulated: `mechdiff check`.
    pub plan_only: bool,
}

/// The code of a row's `event` column.
fn event_code(kind: Option<EventKind>) -> f64 {
    match kind {
        None => 0.0,
        Some(EventKind::LoadSwitch) => 1.0,
        Some(EventKind::Turn) => 2.0,
        Some(EventKind::Speed) => 3.0,
        Some(EventKind::Rest) => 4.0,
    }
}

/// The machine's state columns of the table over time.
fn time_columns(w: &Words<'_>) -> Vec<Column> {
    let d = w.drive;
    vec![
        column("t", "s", 1.0),
        w.named("phi", d.dimension()),
        w.named("omega", d.speed_dimension()),
        w.named("alpha", d.acceleration_dimension()),
        w.named("M_motor", Dimension::Torque),
        w.named("M_drive", w.drive_torque()),
        w.named("J", w.inertia()),
        column("event", "-", 1.0),
    ]
}

/// The machine's state columns of the steady state's table over the drive angle.
fn steady_columns(w: &Words<'_>) -> Vec<Column> {
    let d = w.drive;
    vec![
        w.named("phi", d.dimension()),
        column("t", "s", 1.0),
        w.named("omega", d.speed_dimension()),
        w.named("alpha", d.acceleration_dimension()),
        column("E", "J", 1.0),
        w.named("M_motor", Dimension::Torque),
        w.named("M_drive", w.drive_torque()),
        w.named("J", w.inertia()),
    ]
}

/// The rows of one table: the machine's state, then the scene's outputs at that state.
struct RowMaker<'s> {
    sweeper: Sweeper<'s>,
    /// The indices of the scene's columns kept in a row.
    keep: Vec<usize>,
    /// The machine's own tracker (the state's φ̈ at each row).
    tracker: mechdiff_core::geometry::Tracker<'s>,
    buffer: Vec<f64>,
    row: Vec<f64>,
    failure: Option<Error>,
}

/// Where the rows over time go, and the words of their errors.
struct TimeOut<'r, 'a> {
    rows: &'r mut Option<Rows>,
    sinks: &'r mut MotionSinks<'a>,
    curves: &'r mut Curves,
    clock: &'r mut Clocked,
    columns: &'r [Column],
    /// SI per printed unit of the speed and the torque.
    speed: f64,
    torque: f64,
    words: &'r Words<'r>,
    location: &'r Location,
}

impl<'s> RowMaker<'s> {
    /// The row of `record` of a run of `machine` in time, written to `out`.
    fn time_row(
        &mut self,
        machine: &Machine<'s>,
        record: Record,
        out: &mut TimeOut<'_, '_>,
    ) -> Result<()> {
        let (sample, kind): (Sample, Option<EventKind>) = match record {
            Record::Step(s) => (s, None),
            Record::Event(e) => (e.at, Some(e.kind)),
        };
        let state = (machine.state(&mut self.tracker, sample.phi, sample.omega))
            .map_err(|e| motion_error(out.words, "the motion", out.location, e))?;
        self.row.clear();
        self.row.extend_from_slice(&[
            sample.time,
            sample.phi,
            sample.omega,
            state.alpha,
            state.motor_torque,
            state.drive_torque,
            state.reduced_inertia,
            event_code(kind),
        ]);
        self.outputs(sample.phi, sample.omega, state.alpha)?;
        let rows = match out.rows {
            Some(r) => r,
            None => out.rows.insert(Rows::start(
                out.sinks,
                Table::Time,
                "the motion in time",
                out.columns,
            )?),
        };
        rows.row(out.sinks, &self.row)?;
        (out.clock).push([sample.time, sample.phi, sample.omega, state.alpha]);
        let t = sample.time;
        out.curves.omega_time.push([t, sample.omega / out.speed]);
        out.curves
            .motor_torque
            .push([t, state.motor_torque / out.torque]);
        Ok(())
    }

    /// A row maker like this one, from the sketch again (its trackers at the start).
    fn fresh(
        &self,
        setup: &'s Setup<'s>,
        plan: &Plan,
        machine: &Machine<'s>,
        w: &Words<'_>,
        motion: &SceneMotion,
    ) -> Result<Self> {
        Ok(RowMaker {
            keep: self.keep.clone(),
            sweeper: sweeper(setup, plan, false)?,
            tracker: (machine.tracker())
                .map_err(|e| motion_error(w, "the motion", &motion.location, e))?,
            buffer: Vec::new(),
            row: Vec::new(),
            failure: None,
        })
    }

    /// The scene's outputs at `phi` with speed `omega` and acceleration `alpha`, appended
    /// to the row.
    fn outputs(&mut self, phi: f64, omega: f64, alpha: f64) -> Result<()> {
        self.sweeper
            .set_drive(DriveState::accelerating(omega, alpha));
        self.sweeper.row(phi, &mut self.buffer)?;
        self.row.extend(self.keep.iter().map(|&k| self.buffer[k]));
        Ok(())
    }
}

/// Runs the `[simulate]` of `scene`: prints the equation's terms, streams the tables to
/// `sinks`, and returns what the analyses found.
///
/// # Errors
/// A located error: the scene's checks before solving, [`Error::Motion`] for an analysis
/// that fails (a motor that cannot start the machine, no steady state within the turns),
/// a solver error of the scene's outputs, or [`Error::Write`].
pub fn run(scene: &Scene, sinks: &mut MotionSinks<'_>) -> Result<MotionReport> {
    run_with(scene, sinks, &MotionOptions::default())
}

/// [`run`], with the frames of a report's playback when `options` asks for them.
///
/// # Errors
/// As [`run`].
pub fn run_with(
    scene: &Scene,
    sinks: &mut MotionSinks<'_>,
    options: &MotionOptions,
) -> Result<MotionReport> {
    let Some(motion) = &scene.motion else {
        return Err(Error::Invalid {
            location: scene.drive.location.clone(),
            message: "the scene has no `[simulate]` section".to_owned(),
        });
    };
    // The outputs are evaluated at each row's simulated speed and acceleration; the
    // prescribed speed the checks before solving ask for is a placeholder.
    let mut moving = scene.clone();
    moving.drive.speed.get_or_insert(1.0);
    let setup = Setup::of(&moving, &RunOptions::default())?;
    crate::scene::preflight::before_solving(&setup)?;
    let cx = &setup.context;
    let w = Words {
        cx,
        drive: scene.drive.kind,
    };
    let dynamics = scene.dynamics.as_ref().ok_or_else(|| Error::Invalid {
        location: motion.location.clone(),
        message: "`[simulate]` needs the machine's masses and motor (`[masses]`, `[motor]`)"
            .to_owned(),
    })?;
    let model = (dynamics.data.compile(&setup.mechanism)).map_err(|source| Error::Model {
        file: cx.file.to_owned(),
        source,
    })?;
    let effects = dynamics.data.available(&setup.mechanism);
    let machine = Machine::new(&model, effects)
        .with_motor(motion.characteristic.clone())
        .with_flywheel(motion.flywheel)
        .with_solver(setup.solver);
    let mut head = String::new();
    if let Some(title) = &scene.title {
        head.push_str(title);
        head.push('\n');
    }
    let range = inertia_range(&machine, motion, &w)?;
    let described = equation::describe(scene, motion, &effects, &range);
    head.push_str(&described);
    sinks.say(&head)?;

    let plan = Plan::of(&setup);
    // The scene's columns after its drive column; a `[[dynamics]] drive_torque`'s M_drive
    // and M_motor are the machine's own state columns (the same numbers, once each).
    let state_names = ["M_motor", "M_drive"];
    let (keep, extra): (Vec<usize>, Vec<Column>) = (columns(&setup).into_iter().enumerate())
        .skip(1)
        .filter(|(_, c)| !state_names.contains(&c.name.as_str()))
        .unzip();
    let mut make = RowMaker {
        keep,
        sweeper: sweeper(&setup, &plan, false)?,
        tracker: (machine.tracker())
            .map_err(|e| motion_error(&w, "the motion", &motion.location, e))?,
        buffer: Vec::new(),
        row: Vec::new(),
        failure: None,
    };
    let mut time_columns = time_columns(&w);
    time_columns.extend(extra.iter().cloned());
    let mut steady_columns = steady_columns(&w);
    steady_columns.extend(extra.iter().cloned());
    let speed_unit = w.of(w.drive.speed_dimension());
    let torque_unit = w.of(Dimension::Torque);
    let angle_unit = w.of(w.drive.dimension());
    let mut report = MotionReport {
        start_up: None,
        steady: None,
        coast_down: None,
        flywheel: None,
        time_rows: 0,
        steady_rows: 0,
        time_columns: time_columns.clone(),
        steady_columns: steady_columns.clone(),
        curves: Curves {
            labels: [
                "t [s]".to_owned(),
                format!("phi [{}]", angle_unit.unit),
                format!("omega [{}]", speed_unit.unit),
                format!("M_motor [{}]", torque_unit.unit),
            ],
            ..Curves::default()
        },
        summary: Vec::new(),
        plan: described,
        playback: None,
    };
    if options.plan_only {
        return Ok(report);
    }
    let mut time_clock = Clocked::default();
    let mut steady_clock = Clocked::default();
    let mut coast_from: Option<f64> = None;
    let tolerances = motion.tolerances;
    let coasting = machine.clone().without_motor();

    // The table over time: the start-up, then the coast-down from where it ended.
    let mut time_rows: Option<Rows> = None;
    let mut end: Option<Start> = None;
    if motion.finds(Find::StartUp) {
        let speed = match motion.speed {
            Some(s) => s,
            None => equation::start_up_speed(motion, machine.ratio()).unwrap_or(0.0),
        };
        let mut sink = |r: Record| {
            if make.failure.is_none()
                && let Err(e) = make.time_row(
                    &machine,
                    r,
                    &mut TimeOut {
                        rows: &mut time_rows,
                        sinks,
                        curves: &mut report.curves,
                        clock: &mut time_clock,
                        columns: &time_columns,
                        speed: speed_unit.factor,
                        torque: torque_unit.factor,
                        words: &w,
                        location: &motion.location,
                    },
                )
            {
                make.failure = Some(e);
            }
        };
        let found = start_up(
            &machine,
            motion.start,
            speed,
            motion.time,
            &tolerances,
            &mut sink,
        );
        if let Some(e) = make.failure.take() {
            return Err(e);
        }
        let s = found.map_err(|e| {
            let at = match e {
                MotionError::CannotStart { .. } | MotionError::Stalled { .. } => {
                    &motion.characteristic_at
                }
                MotionError::NotReached { .. } | MotionError::TooManySteps { .. } => {
                    &motion.time_at
                }
                _ => &motion.location,
            };
            motion_error(&w, "start-up", at, e)
        })?;
        report.summary.push(format!(
            "start-up from rest at {}: {} reached after {} s and {} turns; peak motor torque {} \
             ({} steps, {} evaluations of the equation of motion)",
            w.position(motion.start),
            w.speed(speed),
            significant(s.time_to_speed),
            significant(s.travel / std::f64::consts::TAU),
            w.text(s.peak_motor_torque, Dimension::Torque),
            s.simulation.steps,
            s.simulation.evaluations,
        ));
        end = Some(Start {
            time: s.simulation.end.time,
            phi: s.simulation.end.phi,
            omega: s.simulation.end.omega,
        });
        report.start_up = Some(s);
    }

    if motion.finds(Find::SteadyState) || (motion.finds(Find::CoastDown) && end.is_none()) {
        let settings = steady_settings(motion, &motion.tolerances);
        let mut steady_rows: Option<Rows> = None;
        let mut sink = |a: AngleSample| {
            if make.failure.is_some() {
                return;
            }
            let result = (|| -> Result<()> {
                let state = (machine.state(&mut make.tracker, a.phi, a.omega))
                    .map_err(|e| motion_error(&w, "steady state", &motion.location, e))?;
                make.row.clear();
                make.row.extend_from_slice(&[
                    a.phi,
                    a.time,
                    a.omega,
                    state.alpha,
                    a.energy,
                    state.motor_torque,
                    state.drive_torque,
                    state.reduced_inertia,
                ]);
                make.outputs(a.phi, a.omega, state.alpha)?;
                let rows = match &mut steady_rows {
                    Some(r) => r,
                    None => steady_rows.insert(Rows::start(
                        sinks,
                        Table::Steady,
                        "the steady state over one turn",
                        &steady_columns,
                    )?),
                };
                rows.row(sinks, &make.row)?;
                steady_clock.push([a.time, a.phi, a.omega, state.alpha]);
                report
                    .curves
                    .omega_angle
                    .push([a.phi / angle_unit.factor, a.omega / speed_unit.factor]);
                Ok(())
            })();
            if let Err(e) = result {
                make.failure = Some(e);
            }
        };
        let found = steady_state(&machine, &settings, &mut sink);
        if let Some(e) = make.failure.take() {
            return Err(e);
        }
        let s = found.map_err(|e| {
            let at = match e {
                MotionError::NoSteadyState { .. } => &motion.turns_at,
                _ => &motion.location,
            };
            motion_error(&w, "steady state", at, e)
        })?;
        report.steady_rows = steady_rows.map_or(0, |r| r.written);
        report.summary.push(steady_line(&w, &s));
        if end.is_none() {
            end = Some(Start {
                time: 0.0,
                phi: s.phi,
                omega: s.omega,
            });
        }
        report.steady = Some(s);
    }

    if motion.finds(Find::CoastDown)
        && let Some(start) = end
    {
        coast_from = Some(start.time);
        let mut sink = |r: Record| {
            if make.failure.is_none()
                && let Err(e) = make.time_row(
                    &coasting,
                    r,
                    &mut TimeOut {
                        rows: &mut time_rows,
                        sinks,
                        curves: &mut report.curves,
                        clock: &mut time_clock,
                        columns: &time_columns,
                        speed: speed_unit.factor,
                        torque: torque_unit.factor,
                        words: &w,
                        location: &motion.location,
                    },
                )
            {
                make.failure = Some(e);
            }
        };
        let found = coast_down(&machine, start, None, motion.time, &tolerances, &mut sink);
        if let Some(e) = make.failure.take() {
            return Err(e);
        }
        let c = found.map_err(|e| {
            let at = match e {
                MotionError::NotReached { .. } | MotionError::TooManySteps { .. } => {
                    &motion.time_at
                }
                _ => &motion.location,
            };
            motion_error(&w, "coast-down", at, e)
        })?;
        report.summary.push(format!(
            "coast-down (motor off) from {} at {}: at rest after {} s and {} turns",
            w.speed(start.omega),
            w.position(start.phi),
            significant(c.time),
            significant(c.turns),
        ));
        report.coast_down = Some(c);
    }
    report.time_rows = time_rows.map_or(0, |r| r.written);

    if motion.finds(Find::Flywheel) {
        let delta = motion.delta.unwrap_or(0.02);
        let settings = steady_settings(motion, &motion.tolerances);
        let f = flywheel(&machine, delta, motion.mean, &settings).map_err(|e| {
            let at = match e {
                MotionError::NoSteadyState { .. } => &motion.turns_at,
                _ => &motion.location,
            };
            motion_error(&w, "flywheel", at, e)
        })?;
        report.summary.extend(flywheel_lines(&w, motion, &f));
        report.flywheel = Some(f);
    }
    if options.playback {
        let mut parts = Vec::new();
        if !time_clock.states.is_empty() {
            let name = match (report.start_up.is_some(), report.coast_down.is_some()) {
                (true, true) => "the start-up, then the coast-down",
                (false, true) => "the coast-down",
                _ => "the start-up",
            };
            parts.push((name.to_owned(), time_clock));
        }
        parts.push(("one period of the steady state".to_owned(), steady_clock));
        let (step, joined) = playback::join(parts);
        let mut columns = vec![column("clock", "s", 1.0)];
        columns.extend(time_columns.iter().filter(|c| c.name != "event").cloned());
        let mut out = Playback {
            columns,
            rows: Vec::new(),
            step,
            parts: Vec::new(),
        };
        for (name, clocked) in joined {
            let first = out.rows.len();
            let mut make = make.fresh(&setup, &plan, &machine, &w, motion)?;
            for (k, [t, phi, omega]) in clocked.states.iter().copied().enumerate() {
                let which = match coast_from {
                    Some(c) if first == 0 && t > c => &coasting,
                    _ => &machine,
                };
                let state = (which.state(&mut make.tracker, phi, omega))
                    .map_err(|e| motion_error(&w, "the motion", &motion.location, e))?;
                make.row.clear();
                make.row.extend_from_slice(&[
                    (first + k) as f64 * step,
                    t,
                    phi,
                    omega,
                    state.alpha,
                    state.motor_torque,
                    state.drive_torque,
                    state.reduced_inertia,
                ]);
                make.outputs(phi, omega, state.alpha)?;
                out.rows.push(make.row.clone());
            }
            out.parts.push(Part {
                name,
                frames: first..out.rows.len(),
            });
        }
        report.playback = Some(out);
    }
    let mut text = String::from("\n");
    for line in &report.summary {
        text.push_str(line);
        text.push('\n');
    }
    sinks.say(&text)?;
    Ok(report)
}

/// Positions of one turn at which the plan gives J(φ)'s range.
const INERTIA_POSITIONS: usize = 360;

/// The plan's line of J(φ)'s range: over one turn from the start for an angle drive that
/// turns one (at [`INERTIA_POSITIONS`] positions), else J at the start.
///
/// # Errors
/// The machine's error at the start (it does not assemble there).
fn inertia_range(machine: &Machine<'_>, motion: &SceneMotion, w: &Words<'_>) -> Result<String> {
    let fail = |e| motion_error(w, "the motion", &motion.location, e);
    let mut tracker = machine.tracker().map_err(fail)?;
    let at_start = (machine.state(&mut tracker, motion.start, 0.0))
        .map_err(fail)?
        .reduced_inertia;
    let j = |v: f64| w.text(v, w.inertia());
    let start = w.position(motion.start);
    if w.drive == crate::scene::model::DriveKind::Angle {
        let mut range = (at_start, at_start);
        let turn = (1..=INERTIA_POSITIONS).try_for_each(|k| {
            let phi = motion.start + std::f64::consts::TAU * k as f64 / INERTIA_POSITIONS as f64;
            let v = machine.state(&mut tracker, phi, 0.0)?.reduced_inertia;
            range = (range.0.min(v), range.1.max(v));
            Ok::<(), MotionError>(())
        });
        if turn.is_ok() {
            return Ok(format!(
                "  J(φ) over one turn from {start}: {} to {} ({INERTIA_POSITIONS} positions)\n",
                j(range.0),
                j(range.1)
            ));
        }
    }
    let why = match w.drive {
        crate::scene::model::DriveKind::Angle => " (the drive does not turn a whole turn)",
        crate::scene::model::DriveKind::Displacement => "",
    };
    Ok(format!(
        "  J(φ) at the start {start}: {}{why}\n",
        j(at_start)
    ))
}

/// The steady-state search's settings from `[simulate]`.
fn steady_settings(
    motion: &SceneMotion,
    tolerances: &mechdiff_core::machine::Tolerances,
) -> SteadySettings {
    SteadySettings {
        phi: motion.start,
        guess: motion.speed,
        max_turns: motion.turns,
        tolerances: *tolerances,
        ..SteadySettings::default()
    }
}
