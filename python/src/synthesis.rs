//! Dimensional synthesis from Python: the core engine's [`Problem`] built from plain values,
//! and one search of it ([`Synthesis::solve`]) per call, without the GIL. `mechdiff.synthesis`
//! wraps it (and pickles it by its arguments); `mechdiff.study.synthesis` runs many seeds of
//! it on a Dask cluster, one row per start.

use std::time::Duration;

use mechdiff::core::synthesis::{
    Constraints, Derivatives, GrashofClass, Linkage, Problem, Report, Synthesis, SynthesisError,
    Task, Timing,
};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::argument;

/// The longest time limit of one search (s): a day.
const MAX_SECONDS: f64 = 86_400.0;

/// A synthesis problem: a linkage, a task, bounds on every design variable, the branch and
/// the constraints, validated by the core engine.
#[pyclass(module = "mechdiff._mechdiff", name = "SynthesisProblem", frozen)]
pub struct SynthesisProblem {
    /// The validated problem.
    problem: Problem,
}

/// The linkage a name stands for.
fn linkage(py: Python<'_>, name: &str) -> PyResult<Linkage> {
    match name {
        "four_bar" => Ok(Linkage::FourBar),
        "slider_crank" => Ok(Linkage::SliderCrank),
        "stephenson_six" => Ok(Linkage::StephensonSix),
        other => Err(argument(
            py,
            format!(
                "linkage={other:?} is not one synthesis sizes; expected \"four_bar\", \
                 \"slider_crank\" or \"stephenson_six\""
            ),
        )),
    }
}

/// The Grashof class a name stands for (`"any"`: none required).
fn grashof(py: Python<'_>, name: &str) -> PyResult<GrashofClass> {
    GrashofClass::named(name).ok_or_else(|| {
        let names: Vec<String> = (GrashofClass::NAMES.iter())
            .map(|(n, _)| format!("{n:?}"))
            .collect();
        argument(
            py,
            format!(
                "grashof={name:?} is not a Grashof class; expected one of {}",
                names.join(", ")
            ),
        )
    })
}

/// The targets as rows of `width` numbers, or which row has another width.
fn rows<const N: usize>(
    py: Python<'_>,
    task: &str,
    targets: &[Vec<f64>],
) -> PyResult<Vec<[f64; N]>> {
    (targets.iter().enumerate())
        .map(|(i, row)| {
            <[f64; N]>::try_from(row.as_slice()).map_err(|_| {
                argument(
                    py,
                    format!(
                        "{task} target {i} has {} numbers; a {task} target has {N}",
                        row.len()
                    ),
                )
            })
        })
        .collect()
}

/// A synthesis error as a Python exception: a problem that cannot be set up is an
/// `ArgumentError` (`LimitError` for a count over its limit), a search that finds no usable
/// mechanism a `StudyError`; `kind` is the core variant's name.
fn to_py(py: Python<'_>, error: &SynthesisError) -> PyErr {
    let (class, kind) = match error {
        SynthesisError::TargetCount { .. } => ("LimitError", "TargetCount"),
        SynthesisError::NoAssembly { .. } => ("StudyError", "NoAssembly"),
        SynthesisError::TimeLimit { .. } => ("StudyError", "TimeLimit"),
        SynthesisError::UnknownName { .. } => ("ArgumentError", "UnknownName"),
        SynthesisError::MissingBound { .. } => ("ArgumentError", "MissingBound"),
        SynthesisError::InvalidBound { .. } => ("ArgumentError", "InvalidBound"),
        SynthesisError::NonFiniteTarget { .. } => ("ArgumentError", "NonFiniteTarget"),
        SynthesisError::InvalidConstraint { .. } => ("ArgumentError", "InvalidConstraint"),
        _ => ("ArgumentError", "InvalidSetting"),
    };
    let message = format!("synthesis: {error}");
    let made = py
        .import("mechdiff.errors")
        .and_then(|m| m.getattr(class))
        .and_then(|c| c.call1((message.clone(),)))
        .and_then(|e| e.setattr("kind", kind).map(|()| e));
    match made {
        Ok(exception) => PyErr::from_value(exception),
        Err(_) => argument(py, message),
    }
}

/// A report of a search of `problem` as a dict of plain values (see
/// `SynthesisProblem.solve`).
fn report_dict<'py>(
    py: Python<'py>,
    problem: &Problem,
    report: &Report,
    settings: &Synthesis,
) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    dict.set_item("variables", report.variables.clone())?;
    let class = problem.linkage().grashof_class(&report.x());
    dict.set_item("grashof_class", class.map(GrashofClass::name))?;
    dict.set_item("objective", report.objective)?;
    dict.set_item("residuals", report.residuals.clone())?;
    dict.set_item("gradient_norm", report.gradient_norm)?;
    dict.set_item("at_bounds", report.at_bounds.clone())?;
    dict.set_item("evaluations", report.evaluations)?;
    dict.set_item("samples", report.samples)?;
    dict.set_item("feasible_samples", report.feasible_samples)?;
    dict.set_item("local_searches", report.local_searches)?;
    dict.set_item("successes", report.successes)?;
    let defects: Vec<(String, usize)> = (report.defects.iter())
        .map(|(d, n)| (d.describe().to_owned(), *n))
        .collect();
    dict.set_item("defects", defects)?;
    dict.set_item("stop", format!("{:?}", report.stop))?;
    dict.set_item("local_stop", format!("{:?}", report.local_stop))?;
    dict.set_item("seconds", report.elapsed.as_secs_f64())?;
    match &report.certificate {
        Ok(c) => {
            dict.set_item("certificate_deviation", c.deviation)?;
            dict.set_item("certificate_error", py.None())?;
        }
        Err(e) => {
            dict.set_item("certificate_deviation", f64::NAN)?;
            dict.set_item("certificate_error", e.to_string())?;
        }
    }
    dict.set_item("why_not_better", report.why_not_better(settings))?;
    Ok(dict)
}

#[pymethods]
impl SynthesisProblem {
    /// A problem: `linkage` (`"four_bar"`, `"slider_crank"`, `"stephenson_six"`) must do
    /// `task` (`"path"`: `targets` are points x, y in m; `"function"`: (drive angle rad,
    /// output rad or m) pairs; `"motion"`: poses x, y m, angle rad) with `name` the traced
    /// point, the output or the guided link (default: the linkage's traced point, its
    /// first output, its traced link). `timing` (path and motion): `"absolute"` (`drive`
    /// gives each target's drive angle, rad), `"relative"` (`drive` relative to an unknown
    /// `drive0`) or `"free"`. `bounds`: `[(variable, lower, upper), ...]`, equal bounds fix
    /// a variable. `weights`: one per target (each finite and ≥ 0, default 1), multiplying
    /// its squared error in the objective. `grashof`: the Grashof class the four-bar loop
    /// must have (`"crank-rocker"`, `"double-crank"`, `"rocker-crank"`, `"double-rocker"`,
    /// `"triple-rocker"`; `"any"`: none).
    #[new]
    #[allow(clippy::too_many_arguments)]
    #[pyo3(signature = (linkage, task, targets, *, name = None, timing = "absolute", drive = None,
        bounds = Vec::new(), branch = None, crank_rotates = false, min_transmission = 0.0,
        checks_between_targets = 8, angle_weight = 1.0, weights = None, grashof = "any"))]
    fn new(
        py: Python<'_>,
        linkage: &str,
        task: &str,
        targets: Vec<Vec<f64>>,
        name: Option<String>,
        timing: &str,
        drive: Option<Vec<f64>>,
        bounds: Vec<(String, f64, f64)>,
        branch: Option<Vec<f64>>,
        crank_rotates: bool,
        min_transmission: f64,
        checks_between_targets: usize,
        angle_weight: f64,
        weights: Option<Vec<f64>>,
        grashof: &str,
    ) -> PyResult<Self> {
        let linkage = self::linkage(py, linkage)?;
        let grashof = self::grashof(py, grashof)?;
        let timing = match (timing, drive) {
            ("absolute", Some(d)) => Timing::Absolute(d),
            ("relative", Some(d)) => Timing::Relative(d),
            ("free", None) => Timing::Free,
            ("absolute" | "relative", None) => {
                return Err(argument(
                    py,
                    format!("timing={timing:?} needs `drive`: one drive angle (rad) per target"),
                ));
            }
            ("free", Some(_)) => {
                return Err(argument(
                    py,
                    "timing=\"free\" solves each target's drive angle; give no `drive`".into(),
                ));
            }
            (other, _) => {
                return Err(argument(
                    py,
                    format!(
                        "timing={other:?} is not one; expected \"absolute\", \"relative\" or \
                         \"free\""
                    ),
                ));
            }
        };
        let task = match task {
            "path" => Task::Path {
                point: name.unwrap_or_else(|| linkage.traced_point().to_owned()),
                targets: rows::<2>(py, "path", &targets)?,
                timing,
            },
            "function" => {
                if !matches!(timing, Timing::Absolute(_)) {
                    return Err(argument(
                        py,
                        "function generation takes its drive angles from its pairs; give no \
                         `timing` or `drive`"
                            .into(),
                    ));
                }
                Task::Function {
                    output: name.unwrap_or_else(|| linkage.output_names()[0].to_owned()),
                    pairs: rows::<2>(py, "function", &targets)?,
                }
            }
            "motion" => Task::Motion {
                link: name.unwrap_or_else(|| linkage.traced_link().to_owned()),
                poses: rows::<3>(py, "motion", &targets)?,
                timing,
                angle_weight,
            },
            other => {
                return Err(argument(
                    py,
                    format!(
                        "task={other:?} is not one; expected \"path\", \"function\" or \
                         \"motion\""
                    ),
                ));
            }
        };
        let mut builder = Problem::builder(linkage, task).constraints(Constraints {
            crank_rotates,
            min_transmission,
            checks_between_targets,
        });
        for (variable, lower, upper) in &bounds {
            builder = builder.bound(variable, *lower, *upper);
        }
        if let Some(branch) = branch {
            builder = builder.branch(&branch);
        }
        if let Some(weights) = weights {
            builder = builder.weights(weights);
        }
        builder = builder.grashof(grashof);
        let problem = builder.build().map_err(|e| to_py(py, &e))?;
        Ok(SynthesisProblem { problem })
    }

    /// The names of the design variables, in order: the linkage's, then the task's
    /// (`pose_angle`, `drive0`, `drive1`, …).
    #[getter]
    fn variable_names(&self) -> Vec<String> {
        self.problem.variable_names().to_vec()
    }

    /// The bounds of every design variable, `[(lower, upper), ...]` in order.
    #[getter]
    fn bounds(&self) -> Vec<(f64, f64)> {
        let (lower, upper) = self.problem.bounds();
        lower.iter().copied().zip(upper.iter().copied()).collect()
    }

    /// Each target's weight, in order (1 where none was given).
    #[getter]
    fn weights(&self) -> Vec<f64> {
        self.problem.weights().to_vec()
    }

    /// The Grashof class the four-bar loop must have (`"any"`: none required).
    #[getter]
    fn grashof(&self) -> &'static str {
        self.problem.grashof().name()
    }

    /// The residuals at the design variables `x` (in order), or `None` where the linkage
    /// does not assemble at a target.
    fn residuals(&self, py: Python<'_>, x: Vec<f64>) -> PyResult<Option<Vec<f64>>> {
        let n = self.problem.variable_names().len();
        if x.len() != n {
            return Err(argument(
                py,
                format!(
                    "x has {} values; the problem has {n} design variables",
                    x.len()
                ),
            ));
        }
        Ok(self.problem.residuals(&x).ok())
    }

    /// One search (core's `Synthesis::solve`, without the GIL): `samples` points of a
    /// Latin hypercube of the bounds drawn from `seed`, the best `local_searches` of them
    /// polished by Levenberg–Marquardt with the exact Jacobian (`exact=False`: central
    /// differences), each of at most `iterations`; stopped at `stop_objective`,
    /// `max_evaluations` or `time_limit` (s). A dict: `variables` `[(name, value)]`,
    /// `grashof_class` (the answer's four-bar loop, `None` for the slider-crank),
    /// `objective`, `residuals`, `gradient_norm`, `at_bounds`, `evaluations`, `samples`,
    /// `feasible_samples`, `local_searches`, `successes`, `defects` `[(what, count)]`,
    /// `stop`, `local_stop`, `seconds`, `certificate_deviation` (m; NaN with
    /// `certificate_error` when core's solver cannot move the answer), `why_not_better`.
    #[allow(clippy::too_many_arguments)]
    #[pyo3(signature = (seed = 0, samples = 1000, local_searches = 100, iterations = 200,
        stop_objective = 1e-24, max_evaluations = 10_000_000, time_limit = None, exact = true))]
    fn solve<'py>(
        &self,
        py: Python<'py>,
        seed: u64,
        samples: usize,
        local_searches: usize,
        iterations: usize,
        stop_objective: f64,
        max_evaluations: usize,
        time_limit: Option<f64>,
        exact: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        let mut settings = Synthesis::seeded(seed)
            .with_starts(samples, local_searches)
            .with_stop_objective(stop_objective)
            .with_max_evaluations(max_evaluations)
            .with_derivatives(if exact {
                Derivatives::Exact
            } else {
                Derivatives::CentralDifferences
            });
        settings.iterations = iterations;
        if let Some(seconds) = time_limit {
            if !(seconds > 0.0 && seconds <= MAX_SECONDS) {
                return Err(argument(
                    py,
                    format!(
                        "time_limit={seconds} s: expected more than 0 and at most {MAX_SECONDS} s"
                    ),
                ));
            }
            settings = settings.with_time_limit(Duration::from_secs_f64(seconds));
        }
        let report = py
            .detach(|| settings.solve(&self.problem))
            .map_err(|e| to_py(py, &e))?;
        report_dict(py, &self.problem, &report, &settings)
    }
}
