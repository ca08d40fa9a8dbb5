//! The edge between a read scene and its run: the library's entry points. Each resolves
//! the [`Scene`] once into its [`Setup`] and hands it to the runner ([`super::run`],
//! [`crate::stream`]); the scene itself words the terminal table ([`TableWords`]).

use std::io;
use std::ops::ControlFlow;

use crate::error::Result;
use crate::stream::{self, Sinks, Streamed, TableWords};

use super::model::Scene;
use super::plan::Plan;
use super::run::{self, Checked, Report};
use super::setup::{RunOptions, Setup};
use super::table;

/// Checks a scene without running its sweep: builds the model, makes every check a run
/// makes before solving, checks its mobility and the sketch's assembly, walks the drive's
/// motion range and holds the sweep against it ([`run::check`]).
///
/// # Errors
/// The located error a run would give before solving, or for a sweep past a limit
/// position.
pub fn check(scene: &Scene) -> Result<Checked> {
    run::check(Setup::of(scene, &RunOptions::default())?)
}

/// Runs a scene in memory on the solver: solves every drive position of the sweep once
/// (keeping the sketch's assembly branch) and feeds that pose to the outputs,
/// `[[dynamics]]` and `[balancing]`; then searches the dead positions asked for.
///
/// # Errors
/// The first error in drive order, located in the scene's file and units.
pub fn run(scene: &Scene) -> Result<Report> {
    run_with(scene, &RunOptions::default())
}

/// [`run()`] with `options`: how the positions are evaluated ([`RunOptions::evaluator`]).
///
/// ```
/// use mechdiff::{RunOptions, evaluator::Evaluator};
///
/// let scene = mechdiff::load("scenes/slider_crank.toml")?;
/// let solver = mechdiff::run(&scene)?;
/// let options = RunOptions { evaluator: Evaluator::Interpreter };
/// let program = mechdiff::run_with(&scene, &options)?;
/// assert!(solver.plan.backend.is_none() && program.plan.backend.is_some());
/// assert_eq!(solver.rows.len(), program.rows.len());
/// for (c, column) in solver.columns.iter().enumerate() {
///     // The same closed forms, differentiated differently, agree to rounding: 1e-13 of
///     // the column's largest magnitude (the bound tests/run_evaluator.rs holds every scene to).
///     let largest = solver.rows.iter().fold(0.0f64, |m, r| m.max(r[c].abs()));
///     for (a, b) in solver.rows.iter().zip(&program.rows) {
///         assert!((a[c] - b[c]).abs() <= 1e-13 * largest, "{}", column.name);
///     }
/// }
/// # Ok::<(), mechdiff::Error>(())
/// ```
///
/// # Errors
/// As [`run()`]; [`crate::Error::NoEvaluator`] when the run-time evaluator asked for cannot
/// evaluate the scene.
pub fn run_with(scene: &Scene, options: &RunOptions) -> Result<Report> {
    run::collect(&Setup::of(scene, options)?)
}

/// [`run_with`], asking `between(done)` before each drive position (`done` positions
/// solved so far) whether to go on: `ControlFlow::Break(b)` stops the run there and is
/// returned as it is. The Python package checks for Ctrl-C this way.
///
/// ```
/// use std::ops::ControlFlow;
///
/// let scene = mechdiff::load("scenes/norton_four_bar.toml")?;
/// let options = mechdiff::RunOptions::default();
/// // Stopped before the fourth of the 11 positions.
/// let stopped = mechdiff::run_between(&scene, &options, |done| {
///     if done == 3 { ControlFlow::Break(done) } else { ControlFlow::Continue(()) }
/// })?;
/// assert!(matches!(stopped, ControlFlow::Break(3)));
/// let whole = mechdiff::run_between(&scene, &options, |_| ControlFlow::<()>::Continue(()))?;
/// assert!(matches!(whole, ControlFlow::Continue(r) if r.rows.len() == 11));
/// # Ok::<(), mechdiff::Error>(())
/// ```
///
/// # Errors
/// As [`run_with`], for the positions solved before a break.
pub fn run_between<B>(
    scene: &Scene,
    options: &RunOptions,
    between: impl FnMut(usize) -> ControlFlow<B>,
) -> Result<ControlFlow<B, Report>> {
    run::collect_between(&Setup::of(scene, options)?, between)
}

/// Runs a scene and streams its rows to `sinks` ([`crate::stream::sweep`], the positions
/// evaluated as `options.evaluator` says), its terminal table worded by the scene.
///
/// # Errors
/// See [`crate::stream::sweep`].
pub fn stream(scene: &Scene, sinks: &mut Sinks<'_>, options: &stream::Options) -> Result<Streamed> {
    let run = RunOptions {
        evaluator: options.evaluator,
    };
    stream::sweep(&Setup::of(scene, &run)?, scene, sinks, options)
}

/// A scene words its table: its title, the plan line and what follows the rows, in its
/// units ([`table`]).
impl TableWords for Scene {
    fn head(&self, plan: &Plan) -> String {
        let mut head = String::new();
        if let Some(title) = &self.title {
            head.push_str(title);
            head.push('\n');
        }
        head.push_str(&plan.describe(self));
        head.push('\n');
        head
    }

    fn table(&self, report: &Report, out: &mut Vec<u8>) -> io::Result<()> {
        table::write_table(self, report, out)
    }

    fn after_rows(&self, report: &Report, out: &mut Vec<u8>) -> io::Result<()> {
        table::write_after_rows(self, report, out)
    }
}
