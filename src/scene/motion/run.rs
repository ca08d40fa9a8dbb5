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
    AngleSample, CoastDown, EventKind, FlywheelSizing, Machine, MeanSpeed, MotionError, Record,
    Sample, Start, StartUp, SteadySettings, SteadyState, coast_down, flywheel, start_up,
    steady_state,
};

use crate::error::{Error, Location, Result};
use crate::scene::error_context::ErrorContext;
use crate::scene::model::{DriveKind, Scene};
use crate::scene::outputs::Column;
use crate::scene::plan::Plan;
use crate::scene::run::{columns, sweeper};
use crate::scene::setup::{RunOptions, Setup};
use crate::scene::sweep::Sweeper;
use crate::scene::units::{Dimension, Units};
use crate::stream::motion::{MotionSinks, Rows, Table};

use super::equation;
use super::format::Find;
use super::model::SceneMotion;

/// The most points of each curve kept for the diagrams (thinned as the rows stream by).
pub const CURVE_POINTS: usize = 4096;

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
}

/// The curves of the diagrams in printed units, each thinned to at most [`CURVE_POINTS`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Curves {
    /// ω over t.
    pub omega_time: Thinned,
    /// The motor's torque over t.
    pub motor_torque: Thinned,
    /// ω over φ at the steady state.
    pub omega_angle: Thinned,
    /// x and y labels with units: time, drive angle, speed, torque.
    pub labels: [String; 4],
}

/// A curve kept with bounded memory: when it holds [`CURVE_POINTS`] points every other one
/// is dropped and from then on only every other point is taken (the stride doubles).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Thinned {
    /// The points kept.
    pub points: Vec<[f64; 2]>,
    stride: usize,
    seen: usize,
}

impl Thinned {
    /// Offers a point.
    pub fn push(&mut self, point: [f64; 2]) {
        let stride = self.stride.max(1);
        if self.seen.is_multiple_of(stride) {
            self.points.push(point);
            if self.points.len() >= CURVE_POINTS {
                let mut k = 0;
                self.points.retain(|_| {
                    k += 1;
                    k % 2 == 1
                });
                self.stride = 2 * stride;
            }
        }
        self.seen += 1;
    }
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

fn column(name: &str, unit: &str, factor: f64) -> Column {
    Column {
        name: name.to_owned(),
        unit: unit.to_owned(),
        factor,
    }
}

/// The scene's words for the machine's quantities.
struct Words<'a> {
    cx: &'a ErrorContext<'a>,
    drive: DriveKind,
}

impl Words<'_> {
    fn units(&self) -> &Units {
        &self.cx.units
    }

    fn of(&self, dimension: Dimension) -> Column {
        column(
            "",
            self.units().symbol(dimension),
            self.units().factor(dimension),
        )
    }

    fn named(&self, name: &str, dimension: Dimension) -> Column {
        Column {
            name: name.to_owned(),
            ..self.of(dimension)
        }
    }

    /// `value` (SI) of `dimension` in the scene's unit, to 7 significant digits.
    fn text(&self, value: f64, dimension: Dimension) -> String {
        let v = self.units().from_si(value, dimension);
        format!("{} {}", significant(v), self.units().symbol(dimension))
    }

    fn speed(&self, value: f64) -> String {
        self.text(value, self.drive.speed_dimension())
    }

    fn position(&self, value: f64) -> String {
        self.text(value, self.drive.dimension())
    }

    fn drive_torque(&self) -> Dimension {
        match self.drive {
            DriveKind::Angle => Dimension::Torque,
            DriveKind::Displacement => Dimension::Force,
        }
    }

    fn inertia(&self) -> Dimension {
        match self.drive {
            DriveKind::Angle => Dimension::MomentOfInertia,
            DriveKind::Displacement => Dimension::Mass,
        }
    }
}

/// `v` to 7 significant digits, without trailing zeros.
pub(crate) fn significant(v: f64) -> String {
    match format!("{v:.6e}").parse::<f64>() {
        Ok(r) => Units::tidy(r),
        Err(_) => v.to_string(),
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

/// The engine's `error` in `analysis`, placed at `location`, with its drive position in the
/// scene's units.
fn motion_error(
    w: &Words<'_>,
    analysis: &'static str,
    location: &Location,
    error: MotionError,
) -> Error {
    let (phi, time) = match &error {
        MotionError::Mechanism { phi, time, .. } | MotionError::Stalled { phi, time } => {
            (Some(*phi), Some(*time))
        }
        MotionError::NoInertia { phi, .. }
        | MotionError::NoConsistentAcceleration { phi, .. }
        | MotionError::NonFinite { phi, .. }
        | MotionError::CannotStart { phi, .. } => (Some(*phi), None),
        MotionError::TooManySteps { phi, time, .. } => (Some(*phi), Some(*time)),
        _ => (None, None),
    };
    let mut position = String::new();
    if let Some(phi) = phi.filter(|p| p.is_finite()) {
        position = format!(" at drive position {}", w.position(phi));
        if let Some(t) = time.filter(|t| t.is_finite()) {
            position.push_str(&format!(", t = {} s", significant(t)));
        }
    }
    Error::Motion {
        location: location.clone(),
        analysis,
        position,
        source: error,
    }
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
        let t = sample.time;
        out.curves.omega_time.push([t, sample.omega / out.speed]);
        out.curves
            .motor_torque
            .push([t, state.motor_torque / out.torque]);
        Ok(())
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
    head.push_str(&equation::describe(scene, motion, &effects));
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
    };
    let tolerances = motion.tolerances;
    let coasting = machine.clone().without_motor();

    // The table over time: the start-up, then the coast-down from where it ended.
    let mut time_rows: Option<Rows> = None;
    let mut end: Option<Start> = None;
    if motion.finds(Find::StartUp) {
        let speed = match motion.speed {
            Some(s) => s,
            None => {
                0.95 * motion.characteristic.no_load_speed().unwrap_or(0.0) * machine.ratio().abs()
            }
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
        let mut sink = |r: Record| {
            if make.failure.is_none()
                && let Err(e) = make.time_row(
                    &coasting,
                    r,
                    &mut TimeOut {
                        rows: &mut time_rows,
                        sinks,
                        curves: &mut report.curves,
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
    let mut text = String::from("\n");
    for line in &report.summary {
        text.push_str(line);
        text.push('\n');
    }
    sinks.say(&text)?;
    Ok(report)
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

/// The steady state's headline numbers.
fn steady_line(w: &Words<'_>, s: &SteadyState) -> String {
    format!(
        "steady state (from {} at {}): period {} s; ω_min {} at {}, ω_max {} at {}; mean speed \
         {} as the time mean 2π/T and {} as the mid-range (ω_max + ω_min)/2; δ = \
         (ω_max − ω_min)/ω_mean = {} against the time mean, {} against the mid-range \
         ({} turns integrated)",
        w.speed(s.omega),
        w.position(s.phi),
        significant(s.period),
        w.speed(s.min.0),
        w.position(s.min.1),
        w.speed(s.max.0),
        w.position(s.max.1),
        w.speed(s.mean_time),
        w.speed(s.mean_mid),
        significant(s.delta_time),
        significant(s.delta_mid),
        s.turns,
    )
}

/// The flywheel's headline numbers: exact and classic, and why they differ.
fn flywheel_lines(w: &Words<'_>, motion: &SceneMotion, f: &FlywheelSizing) -> Vec<String> {
    let mean = match motion.mean {
        MeanSpeed::Time => "the time mean",
        MeanSpeed::MidRange => "the mid-range speed",
    };
    let inertia = w.inertia();
    let difference = if f.exact > 0.0 {
        format!("{} %", significant(100.0 * (f.classic - f.exact) / f.exact))
    } else {
        "— (no flywheel needed)".to_owned()
    };
    vec![
        format!(
            "flywheel for δ = {} against {} ({}): {} exact (the periodic solution with the \
             motor's characteristic and the varying J(φ), iterated {} times; simulated δ = {}), \
             {} by the classic energy method (ΔE_max = {} J over ω_m² δ, less the rotor and the \
             mean J_m); classic − exact = {}",
            significant(f.target),
            mean,
            w.speed(f.mean_speed),
            w.text(f.exact, inertia),
            f.iterations,
            significant(match motion.mean {
                MeanSpeed::Time => f.steady.delta_time,
                MeanSpeed::MidRange => f.steady.delta_mid,
            }),
            w.text(f.classic, inertia),
            significant(f.energy_swing),
            difference,
        ),
        "  the classic method holds the speed constant where it computes the torques, the \
         motor's torque constant at its mean (a torque that falls with speed damps the \
         fluctuation) and the inertia constant (the varying J_m(φ) exchanges energy with the \
         flywheel); the exact value keeps all three"
            .to_owned(),
    ]
}
