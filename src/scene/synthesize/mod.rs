//! Dimensional synthesis of a scene's `[parameters]`: the `[synthesize]` section (read in a
//! pass of its own: the scene's reader skips it) names a linkage the synthesis engine sizes
//! (`mechdiff_core::synthesis`), the scene's parameters that are its dimensions, their
//! bounds, one task (path, function or motion generation), constraints and the search's
//! limits. [`read`] checks it all before any work (every error at `file:line:column`),
//! [`Setup::solve`] runs the search, [`Setup::found_scene`] writes the scene with the
//! parameters found, and [`Setup::margins`] measures the constraints at the answer.
//!
//! ```
//! let text = std::fs::read_to_string("scenes/synthesis_four_bar_path.toml")?;
//! let setup = mechdiff::scene::synthesize::read("synthesis_four_bar_path.toml", &text)?;
//! assert_eq!(setup.problem.task().target_count(), 10);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod margins;
mod read;
mod scene_check;
mod section;
mod summary;

use std::ops::Range;

use mechdiff_core::synthesis::{Derivatives, Problem, Report, Synthesis, SynthesisError, Workers};

use crate::error::{Error, Result};
use crate::scene::Source;
use crate::scene::units::{Dimension, Units};

pub use margins::{Margin, Margins};
pub use read::{
    DEFAULT_TIME_LIMIT, MAX_EVALUATIONS, MAX_TIME_LIMIT, check_time_limit, read, read_if_present,
};
pub use scene_check::SceneCheck;
pub use summary::{describe, summary};

/// A design variable of the linkage or the task, and where it lives in the scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Variable {
    /// The engine's name (`crank`, `o4x`, `drive0`, …).
    pub name: String,
    /// The scene parameter it is (`None` for the task's angles: `drive0`, `pose_angle`, …).
    pub parameter: Option<String>,
    /// Its unit's dimension (length or angle).
    pub dimension: Dimension,
    /// Its bounds (SI; equal when fixed at the scene's value); `None` for a task angle left
    /// to the engine's default.
    pub bounds: Option<(f64, f64)>,
    /// The span of its value in `[parameters]`, where the value found is written (a free
    /// design variable only).
    pub value_span: Option<Range<usize>>,
}

/// How the search minimises the objective.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// `lm`: samples of the bounds polished by Levenberg–Marquardt with the exact Jacobian
    /// (dual numbers).
    Exact,
    /// `differences`: the same with central-difference Jacobians (a baseline).
    Differences,
    /// `evolution`: differential evolution alone, no derivatives (a baseline).
    Evolution,
}

impl Method {
    /// Every method by the name a scene or the command line writes.
    pub const NAMES: [(&'static str, Method); 3] = [
        ("lm", Method::Exact),
        ("differences", Method::Differences),
        ("evolution", Method::Evolution),
    ];

    /// The method named `name`, if any.
    pub fn named(name: &str) -> Option<Method> {
        Self::NAMES.iter().find(|(n, _)| *n == name).map(|m| m.1)
    }

    /// In words, as the report prints it.
    pub fn describe(self) -> &'static str {
        match self {
            Method::Exact => "LM, exact Jacobian (dual numbers)",
            Method::Differences => "LM, central differences",
            Method::Evolution => "differential evolution alone",
        }
    }
}

/// A scene's synthesis, read and checked.
#[derive(Debug, Clone)]
pub struct Setup {
    /// The engine's problem (SI).
    pub problem: Problem,
    /// The search's settings from the section (the command line may change them).
    pub settings: Synthesis,
    /// The design variables, in the problem's order.
    pub variables: Vec<Variable>,
    /// The file's units.
    pub units: Units,
    /// The scene's text, for messages and for writing the scene found.
    pub source: Source,
    /// The linkage as the section names it (`four_bar`, …).
    pub linkage_name: String,
    /// The section's method (`lm` unless it says otherwise; the command line may change it).
    pub method: Method,
    /// Whether the crank must turn fully.
    pub crank_rotates: bool,
    /// The least transmission angle required (rad; 0 when none).
    pub min_transmission: f64,
    /// The span of the value of the parameter `sketch` names, if any.
    sketch_span: Option<Range<usize>>,
    bounds_span: Range<usize>,
    time_span: Range<usize>,
}

impl Setup {
    /// Runs the search with `settings` (the section's, or changed by the command line).
    ///
    /// # Errors
    /// [`Error::Synthesis`]: no sample of the bounds is a usable mechanism (at
    /// `[synthesize.bounds]`, with the defects counted), or the time limit ran out before
    /// one was found (at `time_limit`).
    pub fn solve(&self, settings: &Synthesis) -> Result<Report> {
        settings
            .solve(&self.problem)
            .map_err(|source| self.located(source))
    }

    /// Runs the search by `method` with `settings`: [`Setup::solve`] with the exact or the
    /// central-difference Jacobian, or differential evolution alone.
    ///
    /// # Errors
    /// As [`Setup::solve`].
    pub fn solve_by(&self, settings: &Synthesis, method: Method) -> Result<Report> {
        self.solve_threaded(settings, method, 1)
    }

    /// [`Setup::solve_by`] with the samples and the local searches of Levenberg–Marquardt
    /// run on `threads` worker threads (0: `RAYON_NUM_THREADS`, else one per core; one without the
    /// `parallel` feature): the same report for any number, but for the time taken
    /// ([`Synthesis::solve_on`]). Differential evolution runs on the calling thread.
    ///
    /// # Errors
    /// As [`Setup::solve`]; [`Error::OverLimit`] for more than
    /// [`MAX_THREADS`](crate::stream::MAX_THREADS) threads, [`Error::Threads`] when the
    /// threads cannot be started.
    pub fn solve_threaded(
        &self,
        settings: &Synthesis,
        method: Method,
        threads: usize,
    ) -> Result<Report> {
        if threads > crate::stream::MAX_THREADS {
            return Err(Error::OverLimit {
                option: "--threads",
                value: threads as u64,
                limit: crate::stream::MAX_THREADS as u64,
                what: "worker threads",
                advice: "give at most one or two per core, or 0 for one per core",
            });
        }
        let pool = crate::parallel::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| Error::Threads {
                threads,
                reason: e.to_string(),
            })?;
        let settings = Synthesis {
            derivatives: match method {
                Method::Differences => Derivatives::CentralDifferences,
                _ => Derivatives::Exact,
            },
            ..settings.clone()
        };
        let result = match method {
            Method::Evolution => settings.evolve(&self.problem),
            _ => settings.solve_on(&self.problem, &Pool(pool)),
        };
        result.map_err(|source| self.located(source))
    }

    /// A search error at its place: the time limit, or the bounds.
    fn located(&self, source: SynthesisError) -> Error {
        let span = match &source {
            SynthesisError::TimeLimit { .. } | SynthesisError::InvalidSetting { .. } => {
                self.time_span.clone()
            }
            _ => self.bounds_span.clone(),
        };
        Error::Synthesis {
            location: self.source.location(span),
            source,
        }
    }

    /// The deviation below which the scene found draws the linkage the engine sized (m):
    /// 1e-9 of the largest bound (at least 1 m), far above the solvers' tolerances.
    pub fn scene_tolerance(&self) -> f64 {
        let (lower, upper) = self.problem.bounds();
        1e-9 * lower
            .iter()
            .chain(upper)
            .map(|v| v.abs())
            .fold(1.0, f64::max)
    }

    /// The value of variable `k` of `report` in the file's unit.
    pub fn in_file_units(&self, report: &Report, k: usize) -> f64 {
        self.units
            .from_si(report.variables[k].1, self.variables[k].dimension)
    }

    /// The scene's text with each free design variable's value in `[parameters]` replaced
    /// by the value found (in the file's unit, shortest form that reads back exactly), and
    /// the parameter `sketch` names (if any) by the first target's drive position; the rest
    /// of the file, comments and `[synthesize]` included, as it was.
    pub fn found_scene(&self, report: &Report) -> String {
        let mut edits: Vec<(Range<usize>, String)> = self
            .variables
            .iter()
            .enumerate()
            .filter_map(|(k, v)| {
                let span = v.value_span.clone()?;
                Some((span, format!("{}", self.in_file_units(report, k))))
            })
            .collect();
        if let Some(span) = &self.sketch_span {
            let first = self.problem.drive_angles(&report.x())[0];
            let first = self.units.from_si(first, Dimension::Angle);
            edits.push((span.clone(), format!("{first}")));
        }
        edits.sort_by_key(|(span, _)| std::cmp::Reverse(span.start));
        let mut text = self.source.text.clone();
        for (span, value) in edits {
            text.replace_range(span, &value);
        }
        text
    }
}

/// A search's local searches on a pool of worker threads ([`Workers`]).
struct Pool(crate::parallel::ThreadPool);

impl Workers for Pool {
    fn width(&self) -> usize {
        self.0.current_num_threads()
    }

    fn run<T: Send>(&self, count: usize, job: &(dyn Fn(usize) -> T + Sync)) -> Vec<T> {
        use crate::parallel::prelude::*;
        let jobs: Vec<usize> = (0..count).collect();
        self.0
            .install(|| jobs.par_iter().map(|&j| job(j)).collect())
    }
}
