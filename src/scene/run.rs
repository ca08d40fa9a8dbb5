//! Running a scene's [`Setup`]: the drive positions, the sweep, the outputs at every drive
//! position, and the dead positions asked for. The scene itself is read once, at the edge
//! ([`Setup::of`], in [`super::run()`] and the other entry points): nothing here takes the
//! [`super::Scene`].

use std::cell::RefCell;
use std::convert::Infallible;
use std::ops::ControlFlow;

use mechdiff_core::geometry::{Mechanism, Mobility, MotionRange};
use mechdiff_core::num_dual::Dual2_64;
use mechdiff_core::{DeadPosition, DeadPositionSearch};

use crate::error::{Error, Result};

use super::error_context::ErrorContext;
use super::evaluate::{Resolved, evaluate, evaluate_pose};
use super::model::{DriveKind, Output};
use super::outputs::Column;
use super::plan::Plan;
use super::positions::Positions;
use super::setup::Setup;
use super::sweep::{Counts, Sweeper, check_row, kinematic_columns, not_finite, solve};
use super::units::{Dimension, Units};

// The motion range in words and the entry point, at the paths they have always had.
pub use super::describe::describe_motion_range;
pub use super::launch::run;

/// The dead positions of one output found in the sweep's range.
#[derive(Debug, Clone, PartialEq)]
pub struct DeadPositions {
    /// The output's name.
    pub output: String,
    /// The output's dimension (angle or length).
    pub dimension: Dimension,
    /// Each dead position: drive position φ (SI) and the output there (SI).
    pub positions: Vec<DeadPosition>,
}

impl DeadPositions {
    /// The stroke: the largest minus the smallest value at the dead positions (SI), if there
    /// are at least two.
    pub fn stroke(&self) -> Option<f64> {
        if self.positions.len() < 2 {
            return None;
        }
        let values = self.positions.iter().map(|d| d.value);
        let hi = values.clone().fold(f64::NEG_INFINITY, f64::max);
        let lo = values.fold(f64::INFINITY, f64::min);
        Some(hi - lo)
    }
}

/// The result of a run: every column at every drive position, in SI, and the dead positions.
#[derive(Debug, Clone)]
pub struct Report {
    /// The plan that was carried out.
    pub plan: Plan,
    /// The drive column first, then the outputs' columns.
    pub columns: Vec<Column>,
    /// One row per drive position: the drive value, then one value per output column (SI).
    pub rows: Vec<Vec<f64>>,
    /// The dead positions asked for.
    pub dead_positions: Vec<DeadPositions>,
    /// The dynamic outputs' run (their columns are also in `columns` and `rows`).
    pub dynamics: Option<super::dynamics::DynamicsReport>,
    /// Warnings about the results (ill-conditioned positions: their estimated error).
    pub warnings: Vec<String>,
    /// The balancing answers (their columns are also in `columns` and `rows`).
    pub balancing: Option<super::balancing::BalancingReport>,
    /// The limit positions, change points and toggles the sweep reaches.
    pub limits: Vec<super::sweep_limits::SweepLimit>,
    /// What the run evaluated.
    pub stats: Stats,
}

impl Report {
    /// The SI values of the column named `name` (e.g. `psi'`, `vx_C`), in row order.
    pub fn column(&self, name: &str) -> Option<Vec<f64>> {
        let k = self.columns.iter().position(|c| c.name == name)?;
        Some(self.rows.iter().map(|r| r[k]).collect())
    }
}

/// What `mechdiff check` found: the model and its mobility at the sketch pose.
#[derive(Debug, Clone)]
pub struct Checked {
    /// The geometry model built from the scene.
    pub mechanism: Mechanism,
    /// Its mobility at the sketch pose.
    pub mobility: Mobility,
    /// The loops the solver closes in turn (joint names, the drive as `drive <joint>`) and
    /// the sign of each loop's assembly branch in the sketch.
    pub loops: Vec<(Vec<String>, i8)>,
    /// Per loop, whether the solver closes it by a closed form (else by Newton).
    pub closed_form: Vec<bool>,
    /// How far the drive moves either way from the sketch (limit positions, change points,
    /// toggles), or why it could not be walked.
    pub motion_range: std::result::Result<MotionRange, String>,
    /// The plan a run would carry out.
    pub plan: Plan,
    /// The columns a run's table would have ([`columns`]).
    pub columns: Vec<Column>,
}

/// Checks a scene's run without running its sweep: makes every check a run makes before
/// solving (`scene::preflight`) on the model `setup` built, checks its mobility and the
/// sketch's assembly, walks the drive's motion range and holds the sweep against it.
pub fn check(setup: Setup<'_>) -> Result<Checked> {
    super::preflight::before_solving(&setup)?;
    let cx = &setup.context;
    let (mobility, loops, closed_form, motion_range) = {
        let tracker = (setup.solver)
            .track(&setup.mechanism)
            .map_err(|e| cx.solver_error(e))?;
        (
            tracker.mobility(),
            tracker.loops(),
            tracker.closed_form_loops(),
            match cx.drive.cam {
                // The cam's follower moves within the cam program's stroke.
                Some(_) => {
                    Err("not walked for a cam drive (the cam sets the joint's travel)".into())
                }
                None => (tracker.motion_range()).map_err(|e| cx.solver_error(e).to_string()),
            },
        )
    };
    if let Ok(range) = &motion_range {
        super::preflight::sweep_within_motion_range(&setup, range)?;
    }
    let (plan, columns) = (Plan::of(&setup), columns(&setup));
    Ok(Checked {
        mobility,
        loops,
        closed_form,
        motion_range,
        plan,
        columns,
        mechanism: setup.mechanism,
    })
}

/// The columns of a run's table, known before anything is solved: the drive, the outputs'
/// columns, then those of `[[dynamics]]` and `[balancing]`, as [`collect`] fills them.
pub fn columns(setup: &Setup<'_>) -> Vec<Column> {
    let (cx, mechanism) = (&setup.context, &setup.mechanism);
    let mut all = kinematic_columns(cx, setup.outputs);
    if let Some(d) = setup.dynamics {
        all.extend(super::dynamics::columns(
            cx,
            d,
            mechanism,
            &d.plan(mechanism),
        ));
    }
    if let Some(b) = setup.balancing {
        all.extend(super::balancing::columns(cx, b));
    }
    all
}

/// Runs a scene's `setup` in memory: solves every drive position of the sweep once
/// (keeping the sketch's assembly branch) and feeds that pose to the outputs,
/// `[[dynamics]]` and `[balancing]`; then searches the dead positions asked for.
pub fn collect(setup: &Setup<'_>) -> Result<Report> {
    match collect_between(setup, |_| ControlFlow::<Infallible>::Continue(()))? {
        ControlFlow::Continue(report) => Ok(report),
        ControlFlow::Break(never) => match never {},
    }
}

/// [`collect`], asking `between(done)` before each drive position (`done` positions solved
/// so far) whether to go on: `ControlFlow::Break(b)` stops the run there and is returned
/// as it is (a caller that must stay interruptible, such as the Python package on Ctrl-C).
///
/// # Errors
/// As [`collect`], for the positions solved before a break.
pub fn collect_between<B>(
    setup: &Setup<'_>,
    mut between: impl FnMut(usize) -> ControlFlow<B>,
) -> Result<ControlFlow<B, Report>> {
    super::preflight::before_solving(setup)?;
    let (cx, mechanism) = (&setup.context, &setup.mechanism);
    let mut plan = Plan::of(setup);
    let mut all = columns(setup);
    let mut stats = Stats::default();
    let positions = drive_positions(setup, &mut stats)?;
    let mut sweeper = sweeper(setup, &plan, true)?;
    plan.evaluated_by(sweeper.loops(), sweeper.backend());
    let width = all.len() - (setup.balancing).map_or(0, |b| super::balancing::columns(cx, b).len());
    let mut rows = Vec::with_capacity(positions.len());
    for &phi in &positions {
        if let ControlFlow::Break(b) = between(rows.len()) {
            return Ok(ControlFlow::Break(b));
        }
        let mut row = Vec::with_capacity(all.len());
        sweeper.row(phi, &mut row)?;
        // The first error in drive order, as a streamed run reports it.
        check_row(cx, &all[..width], &row)?;
        rows.push(row);
    }
    let warnings = sweeper.warnings();
    stats.sweep = sweeper.counts();
    let dead_positions = dead_positions(setup, positions.iter().copied(), &mut stats)?;
    // The dynamic columns follow the drive's and the outputs'.
    let first = kinematic_columns(cx, setup.outputs).len();
    let dynamics = (sweeper.dynamics())
        .map(|d| d.report(cx, rows.iter().map(|r| r[first..width].to_vec()).collect()))
        .transpose()?;
    let linkage = (sweeper.take_balancing())
        .map(|b| b.finish(cx))
        .transpose()?;
    drop(sweeper);
    let balancing = match setup.balancing {
        Some(b) => Some(super::balancing::report(cx, b, mechanism, linkage)?),
        None => None,
    };
    if let Some(b) = balancing.as_ref().filter(|b| !b.columns.is_empty()) {
        for (row, extra) in rows.iter_mut().zip(&b.rows) {
            row.extend_from_slice(extra);
        }
    } else {
        all.truncate(width);
    }
    stats.limit_walks = usize::from(super::sweep_limits::walks(setup, positions.len()));
    let report = Report {
        plan,
        columns: all,
        rows,
        dead_positions,
        dynamics,
        warnings,
        balancing,
        limits: super::sweep_limits::in_sweep(setup, positions.iter().copied()),
        stats,
    };
    all_finite(cx, &report)?;
    Ok(ControlFlow::Continue(report))
}

/// The sweep of `setup` with its `[[dynamics]]` and `[balancing]` fed from the one walk;
/// `keep_steps` keeps every dynamics step for the report (a run in memory).
pub(crate) fn sweeper<'s>(
    setup: &'s Setup<'s>,
    plan: &Plan,
    keep_steps: bool,
) -> Result<Sweeper<'s>> {
    let (cx, mechanism) = (&setup.context, &setup.mechanism);
    let dynamics = match setup.dynamics {
        Some(d) => super::dynamics::DynamicsSweep::new(cx, d, mechanism, keep_steps)?,
        None => None,
    };
    let balancing = match setup.balancing {
        Some(b) => super::balancing::BalancingSweep::new(cx, setup.dynamics, b, mechanism)?,
        None => None,
    };
    Ok(Sweeper::new(setup, plan)?.with_effects(dynamics, balancing))
}

/// What a run evaluated: the sweep's own solves (each drive position once) and the
/// searches beside it, each counted on its own.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Stats {
    /// The sweep: rows, the tracker's moves, the run-time evaluator's steps.
    pub sweep: Counts,
    /// Positions solved by the search for the drive positions of `[sweep] of` (Newton on
    /// the output, with its halved steps).
    pub sweep_of: usize,
    /// Positions solved by the dead-position searches.
    pub dead_positions: usize,
    /// Walks of the drive's motion range (from the sketch both ways) to find the limits the
    /// sweep reaches.
    pub limit_walks: usize,
}

/// Checks that every number of a report is finite before it is printed or written: an
/// overflow for some combination of inputs is an error naming the quantity and the drive
/// position, never an `inf` or `NaN` in the table.
fn all_finite(cx: &ErrorContext<'_>, report: &Report) -> Result<()> {
    for row in &report.rows {
        check_row(cx, &report.columns, row)?;
    }
    check_dead_positions(cx, &report.dead_positions)
}

/// Checks that the dead positions found and their strokes are finite.
pub(crate) fn check_dead_positions(
    cx: &ErrorContext<'_>,
    dead_positions: &[DeadPositions],
) -> Result<()> {
    let not_finite = |quantity, value, phi| not_finite(cx, quantity, value, phi);
    for dead in dead_positions {
        for d in &dead.positions {
            if !(d.value.is_finite() && d.phi.is_finite()) {
                let quantity = format!("the dead position of {}", dead.output);
                return Err(not_finite(quantity, d.value, d.phi));
            }
        }
        if let Some(stroke) = dead.stroke().filter(|s| !s.is_finite()) {
            let quantity = format!("the stroke of {}", dead.output);
            return Err(not_finite(quantity, stroke, dead.positions[0].phi));
        }
    }
    Ok(())
}

/// The drive positions of a streamed sweep: as given (counted on demand), or solved for
/// `[sweep] of` (a list from the file, held in memory).
pub(crate) fn streamed_positions(setup: &Setup<'_>, stats: &mut Stats) -> Result<Positions> {
    match setup.sweep_of {
        None => Ok(setup.positions.clone()),
        Some(_) => drive_positions(setup, stats).map(Positions::List),
    }
}

/// The drive positions of the sweep: as given, or, for `[sweep] of = "output"`, solved so
/// that the output takes each given value (Newton on the output's exact velocity
/// coefficient, from the sketch or the previous position; steps limited to a quarter turn or
/// a quarter of the sketch's size).
fn drive_positions(setup: &Setup<'_>, stats: &mut Stats) -> Result<Vec<f64>> {
    let Some(k) = setup.sweep_of else {
        return setup.positions.to_vec();
    };
    let cx = &setup.context;
    let resolved = Resolved::new(setup, &setup.outputs[k])?;
    let output = resolved.output;
    let mut tracker = (setup.solver)
        .track(&setup.mechanism)
        .map_err(|e| cx.solver_error(e))?;
    let max_step = match cx.drive.kind {
        DriveKind::Angle => std::f64::consts::FRAC_PI_4,
        DriveKind::Displacement => 0.25 * tracker.length_scale(),
    };
    let dimension = output.kind.dimension();
    let text = |v: f64| {
        format!(
            "{} {}",
            Units::tidy(cx.units.from_si(v, dimension)),
            cx.units.symbol(dimension)
        )
    };
    let mut previous = None;
    let mut drive = Vec::with_capacity(setup.positions.len());
    for target in setup.positions.iter() {
        let mut phi = tracker.phi();
        let mut reached = false;
        // Why the last trial position failed, if it did: a step that leaves the positions
        // where the mechanism assembles (or lands on a toggle) is halved back towards the
        // last position that assembled.
        let mut beyond: Option<Error> = None;
        for _ in 0..60 {
            stats.sweep_of += 1;
            let k = match solve::<1>(cx, &mut tracker, phi) {
                Ok(k) => k,
                Err(e) => {
                    let good = tracker.phi();
                    let half = good + 0.5 * (phi - good);
                    beyond = Some(e);
                    if half == good || half == phi {
                        break;
                    }
                    phi = half;
                    continue;
                }
            };
            beyond = None;
            let jet = evaluate(&k, &resolved, &mut previous)[0];
            let (miss, slope) = (jet.value - target, jet.d1());
            if miss.abs() <= 4.0 * f64::EPSILON * target.abs().max(jet.value.abs()) {
                reached = true;
                break;
            }
            if slope == 0.0 || !slope.is_finite() {
                break;
            }
            let step = (miss / slope).clamp(-max_step, max_step);
            if step.abs() <= 2.0 * f64::EPSILON * phi.abs().max(1.0) {
                reached = true;
                break;
            }
            phi -= step;
        }
        if !reached {
            return Err(Error::NotReached {
                file: cx.file.to_owned(),
                output: output.name.clone(),
                value: text(target),
                last: cx.drive_text(tracker.phi()),
                beyond: beyond
                    .map_or_else(String::new, |e| {
                        let e = e.to_string();
                        let file = format!("{}: ", cx.file);
                        format!("; beyond it: {}", e.strip_prefix(&file).unwrap_or(&e))
                    })
                    .into(),
            });
        }
        drive.push(tracker.phi());
    }
    Ok(drive)
}

/// The dead positions asked for, searched in the range of the sweep's drive positions.
pub(crate) fn dead_positions(
    setup: &Setup<'_>,
    positions: impl Iterator<Item = f64> + Clone,
    stats: &mut Stats,
) -> Result<Vec<DeadPositions>> {
    let mut dead_positions = Vec::new();
    for output in setup.outputs.iter().filter(|o| o.dead_positions) {
        let (found, solved) = search_dead_positions(setup, output, positions.clone())?;
        stats.dead_positions += solved;
        dead_positions.push(DeadPositions {
            output: output.name.clone(),
            dimension: output.kind.dimension(),
            positions: found,
        });
    }
    Ok(dead_positions)
}

/// The most intervals of the grid on which dead positions are searched.
const DEAD_POSITION_INTERVALS: f64 = 65_536.0;

/// Every dead position of an angle or slider output in the sweep's range, and the number of
/// positions the search solved.
fn search_dead_positions(
    setup: &Setup<'_>,
    output: &Output,
    positions: impl Iterator<Item = f64> + Clone,
) -> Result<(Vec<DeadPosition>, usize)> {
    let (lo, hi) = (positions.clone()).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
        (lo.min(p), hi.max(p))
    });
    // Sample at least as finely as the sweep, and at least 360 intervals over the range.
    let sweep_step = (positions.clone().zip(positions.skip(1)))
        .map(|(a, b)| (b - a).abs())
        .fold(f64::INFINITY, f64::min);
    // At most 2^16 intervals, so that a streamed sweep of 10^8 positions does not hold 10^8
    // samples: the grid only brackets the sign changes of the output's derivative, refined
    // to full precision after; dead positions closer together than (hi - lo)/2^16 would be
    // missed (the sweep's own resolution is then finer than any plot of it).
    let step = sweep_step
        .min((hi - lo) / 360.0)
        .max((hi - lo) / DEAD_POSITION_INTERVALS);
    let cx = &setup.context;
    let tracker = RefCell::new(
        (setup.solver)
            .track(&setup.mechanism)
            .map_err(|e| cx.solver_error(e))?,
    );
    let resolved = Resolved::new(setup, output)?;
    let previous = RefCell::new(None);
    let solved = std::cell::Cell::new(0);
    // x′ and x″ read from each solved pose (the search reads no third derivative), nothing
    // allocated per evaluation.
    let found = DeadPositionSearch::new(lo..=hi)
        .with_step(step)
        .find_roots(|phi| {
            solved.set(solved.get() + 1);
            let mut t = tracker.borrow_mut();
            t.move_to(phi)?;
            let previous = &mut previous.borrow_mut();
            Ok(evaluate_pose::<Dual2_64, 2>(&t.pose_jets(), &resolved, previous)[0])
        })
        .map_err(|e| cx.solver_error(e))?;
    Ok((found, solved.get()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A report with an overflowed value is refused, naming the column (with its unit) and
    /// the drive position in the scene's units.
    #[test]
    fn a_non_finite_result_is_an_error_naming_the_quantity_and_the_position() {
        let scene = super::super::parse(
            "s.toml",
            r#"
            [units]
            angle = "deg"
            [points]
            O = [0.0, 0.0]
            A = [0.1, 0.0]
            [links]
            ground = ["O"]
            crank = ["O", "A"]
            [joints]
            O = { type = "revolute", at = "O", links = ["ground", "crank"] }
            [drive]
            joint = "O"
            line = ["O", "A"]
            [sweep]
            positions = [0, 90]
            [[output]]
            point = "A"
            quantities = ["position"]
            "#,
        )
        .unwrap();
        let setup = Setup::of(&scene, &Default::default()).unwrap();
        let mut report = collect(&setup).unwrap();
        report.rows[1][2] = f64::INFINITY;
        let e = all_finite(&setup.context, &report).unwrap_err();
        assert!(matches!(e, Error::NotFinite { .. }), "{e:?}");
        let message = e.to_string();
        assert!(
            message.starts_with("s.toml: y_A [m] is inf at drive position 90 deg"),
            "{message}"
        );
        report.rows[1][2] = f64::NAN;
        assert!(
            all_finite(&setup.context, &report)
                .unwrap_err()
                .to_string()
                .contains("is NaN")
        );
    }
}
