//! Sensitivities of a scene's outputs to its `[parameters]` and a tolerance study from them.
//!
//! A scene may ask for derivative columns and ± tolerances:
//!
//! ```toml
//! [sensitivity]
//! columns = ["d(psi)/d(a)", "d(psi')/d(b)", "d(M_drive)/d(m2)"]
//!
//! [tolerances]
//! columns = ["psi"]                          # the outputs to study
//! parameters = { a = 0.0005, b = 0.0005 }    # ± half-widths, in each parameter's unit
//! ```
//!
//! `d(COLUMN)/d(PARAMETER)` is the derivative of any column of the table (a position, a
//! velocity coefficient `psi'` — so `d(psi')/d(a)` is the mixed `∂²ψ/∂φ∂a` —, a force, the
//! drive torque) with respect to a parameter, at each drive position of the sweep, per unit
//! of the parameter as `[parameters]` writes it. It is the total derivative: parameters
//! given by formulas of the one differentiated (`b = "2*a"`) follow it, as with `--set`.
//! The tolerance study adds, per studied column, the first-order worst case and
//! root-sum-square ([`tolerance`]) at every position and their largest values over the
//! sweep; `--monte-carlo N` checks them against `N` runs at random parameters.
//!
//! **How the derivatives are computed: exact where the exact route reaches, said per
//! column.** A kinematic column (a point's coordinates, an angle, a slider's displacement;
//! their position, coefficients, velocity, acceleration, jerk) is **exact** (dual numbers,
//! `exact`): the scene's tangent ([`crate::scene::tangent`]: the d/dp of every number of
//! the built mechanism — the points from their formulas, units and constructions, the joints'
//! numbers, the drive's value at the sketch, its speed and acceleration) is carried through
//! the pose's implicit differentiation (`mechdiff_core::geometry::Parametric`) and the
//! outputs' generic code; its error is rounding (measured against Norton's closed form in
//! 256-bit arithmetic in `tests/sensitivity.rs`).
//!
//! A dynamics column is exact too (`exact`'s one place for it, the dynamics' own exact
//! route): the scene's tangent carries `[masses]` (a uniform bar's mass, centre and moment
//! with its moving ends), `[gravity]`, the loads' forces and torques and `[motor]`, read by
//! the run's own code in dual numbers, so a column by a mass, a length, g or a load is
//! exact. Elsewhere — a cam-driven scene, `[sweep] of`, a number that moves and that the
//! tangent does not carry (a friction coefficient, a mesh's efficiency, a load's `active`
//! range), the equilibrium's columns of a plan with friction or mesh efficiencies, the
//! balancing columns — the column is a **Richardson extrapolation**, labelled so with the reason ([`Method::Richardson`]): the scene is run
//! again with the parameter moved by `±h`, `±h/2`, `±h/4` (as `--set` moves it: every
//! formula follows), and the three central differences are extrapolated twice, which
//! cancels the `h²` and `h⁴` terms of their error: what remains is `O(h⁶)` and the rounding
//! of the runs (about `ε·|y|/h`). With `h` = 1 % of the parameter's value that is measured at
//! 2e-13 to 2e-11 of the column. The difference between the last two extrapolations is
//! reported per column as its estimated error (it is the error of the extrapolation before
//! the last, so it overestimates the value's); a column where it exceeds 1e-6 relative (an
//! output that is not smooth within `±h`, e.g. near a limit position) is named in a
//! warning. [`write_summary`] prints each column's method.
//!
//! [`check`] reads and checks the sections against a table's columns without running
//! anything (`mechdiff check` gives it the columns a run would have).
//!
//! Cost: per parameter, one pass over the sweep in dual numbers for the exact columns, and
//! six runs of the scene only if a column falls back; one run per Monte-Carlo sample.

pub(crate) mod exact;
pub(crate) mod spec;
pub mod tolerance;

use std::io::{self, Write};

use crate::error::{Error, Result};
use crate::scene::outputs::Column;
use crate::scene::parameters::{self, Setting};
use crate::scene::run::Report;
use crate::scene::units::Units;
use crate::scene::{Scene, Source};

pub use spec::{Parameter, Spec};
pub use tolerance::MonteCarlo;

/// The first step `h`, relative to the parameter's value (then `h/2`, `h/4`).
pub const RELATIVE_STEP: f64 = 1e-2;

/// The first step for a parameter whose value is 0, as a multiple of its tolerance (or, with
/// none, in the parameter's unit: [`ZERO_STEP`]).
pub const TOLERANCE_STEPS: f64 = 10.0;

/// The first step for a parameter whose value is 0 and which has no tolerance.
pub const ZERO_STEP: f64 = 1e-3;

/// How many times the step is divided by 8 when a run with the parameter moved fails
/// (the mechanism may not assemble `h` away from the parameter's value).
const RETRIES: usize = 3;

/// The relative disagreement of the last two extrapolations above which a warning names
/// the column.
pub const WARN_DISAGREEMENT: f64 = 1e-6;

/// The command line's part of a study.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Options {
    /// `--monte-carlo N`: samples of the tolerance study's check.
    pub monte_carlo: Option<usize>,
    /// `--seed S` of the Monte-Carlo generator.
    pub seed: u64,
}

/// The tolerance study of one column.
#[derive(Debug, Clone, PartialEq)]
pub struct ColumnStudy {
    /// The column studied.
    pub column: Column,
    /// The largest first-order worst case over the sweep (SI) and its row.
    pub worst_case: (f64, usize),
    /// The largest root-sum-square over the sweep (SI) and its row.
    pub rss: (f64, usize),
}

/// How a derivative column was computed.
#[derive(Debug, Clone, PartialEq)]
pub enum Method {
    /// Exact (dual numbers): the scene's tangent ([`crate::scene::tangent`]) carried through
    /// the pose's implicit differentiation (`exact`); exact in f64, to rounding.
    Exact,
    /// Richardson-extrapolated central differences of whole runs (steps `h`, `h/2`, `h/4`),
    /// where the exact route does not reach the column.
    Richardson {
        /// The first step `h` of the differences, in the parameter's unit.
        step: f64,
        /// The largest disagreement of the last two extrapolations over the sweep, relative
        /// to the column's largest value (0 for a column that is 0): the estimate of its
        /// error.
        estimated_error: f64,
        /// Why the exact route does not reach the column.
        why: String,
    },
}

/// How one derivative column was computed and how far it may be off.
#[derive(Debug, Clone, PartialEq)]
pub struct DerivativeColumn {
    /// Its name, `d(COLUMN)/d(PARAMETER)`.
    pub name: String,
    /// How it was computed.
    pub method: Method,
}

impl DerivativeColumn {
    /// Whether it is exact (dual numbers).
    pub fn is_exact(&self) -> bool {
        self.method == Method::Exact
    }

    /// The estimated error relative to the column's largest value: 0 for an exact column
    /// (its error is rounding), the extrapolations' disagreement for a Richardson one.
    pub fn estimated_error(&self) -> f64 {
        match &self.method {
            Method::Exact => 0.0,
            Method::Richardson {
                estimated_error, ..
            } => *estimated_error,
        }
    }
}

/// The study of a scene: how its derivative columns were computed, and its tolerance study.
#[derive(Debug, Clone, PartialEq)]
pub struct Study {
    /// Per derivative column of `[sensitivity]`, in order.
    pub derivatives: Vec<DerivativeColumn>,
    /// The tolerances, `(parameter, ± half-width)` in the parameter's unit; empty without
    /// `[tolerances]`.
    pub tolerances: Vec<(String, f64)>,
    /// Per studied column; empty without `[tolerances]`.
    pub columns: Vec<ColumnStudy>,
    /// The drive positions (SI) and their column, to say where the largest values are.
    pub drive: (Column, Vec<f64>),
    /// The Monte-Carlo check, with `--monte-carlo`.
    pub monte_carlo: Option<MonteCarlo>,
}

/// Whether the scene `text` asks for a study (has `[sensitivity]` or `[tolerances]`).
pub fn requested(text: &str) -> bool {
    text.parse::<toml::Table>()
        .is_ok_and(|t| t.contains_key("sensitivity") || t.contains_key("tolerances"))
}

/// Reads and checks the `[sensitivity]` and `[tolerances]` of the scene `text` (named
/// `file`, with `settings`) against the table's `columns`, without running anything:
/// `mechdiff check` calls it with the columns a run would have
/// ([`crate::scene::run::columns`]), [`run`] with those of its run, so both give the same
/// located errors. `None` when the scene has neither section.
///
/// # Errors
/// As [`parameters::read_with_own_units`] and `spec::read`.
pub fn check(
    file: &str,
    text: &str,
    settings: &[Setting],
    columns: &[Column],
) -> Result<Option<Spec>> {
    let source = Source::new(file, text);
    let values = parameters::read_with_own_units(text, &source, settings)?;
    spec::read(&source, text, &values, columns)
}

/// Reads and runs the scene `text` (named `file`) with `settings` (`--set`), then its
/// `[sensitivity]` columns and `[tolerances]` study: the derivative columns
/// `d(COLUMN)/d(PARAMETER)` and, per studied column, `wc(COLUMN)` and `rss(COLUMN)` are
/// appended to the report. The study is `None` when the scene has neither section.
///
/// # Errors
/// As [`crate::scene::parse_with`] and [`crate::scene::run()`]; a malformed study
/// (`spec::read`); a run with a parameter moved that fails ([`Error::Perturbed`]) or
/// whose drive positions differ from the nominal run's ([`Error::Study`]); `--monte-carlo`
/// without `[tolerances]`.
pub fn run(
    file: &str,
    text: &str,
    settings: &[Setting],
    options: &Options,
) -> Result<(Scene, Report, Option<Study>)> {
    if let Some(samples) = options.monte_carlo
        && samples > tolerance::MAX_SAMPLES
    {
        return Err(Error::OverLimit {
            option: "--monte-carlo",
            value: samples as u64,
            limit: tolerance::MAX_SAMPLES as u64,
            what: "samples",
            advice: "a few thousand samples show the spread; run several seeds (`--seed`) for more",
        });
    }
    let scene = crate::scene::parse_with(file, text, settings)?;
    let mut report = crate::scene::run(&scene)?;
    let spec = check(file, text, settings, &report.columns)?;
    // `--monte-carlo` on a scene without any study is refused, not ignored.
    if options.monte_carlo.is_some() && !spec.as_ref().is_some_and(Spec::has_tolerances) {
        return Err(Error::Study {
            file: file.to_owned(),
            message: "`--monte-carlo` checks a tolerance study, and the scene has no \
                      `[tolerances]`; add one (`columns = [\"psi\"]`, `parameters = { a = \
                      0.0005 }`)"
                .to_owned(),
        });
    }
    let Some(spec) = spec else {
        return Ok((scene, report, None));
    };
    let nominal = report.clone();
    let runner = Runner {
        file,
        text,
        settings,
        nominal: &nominal,
    };
    let classes = ColumnClasses::of(&scene, nominal.columns.len());
    let mut derivatives = Vec::with_capacity(spec.parameters.len());
    for (i, p) in spec.parameters.iter().enumerate() {
        // The columns this parameter's derivatives are asked of: its derivative columns,
        // and with a tolerance the studied ones.
        let mut needed: Vec<usize> = (spec.derivatives.iter())
            .filter(|&&(_, q)| q == i)
            .map(|&(k, _)| k)
            .collect();
        if p.tolerance.is_some() {
            needed.extend(&spec.studied);
        }
        derivatives.push(runner.derivative(&scene, &classes, p, &needed)?);
    }
    let mut derivative_columns = Vec::with_capacity(spec.derivatives.len());
    for &(k, p) in &spec.derivatives {
        let (column, parameter) = (&nominal.columns[k], &spec.parameters[p]);
        let name = format!("d({})/d({})", column.name, parameter.name);
        let d = &derivatives[p];
        let method = d.methods[k].clone().unwrap_or(Method::Exact);
        if let Method::Richardson {
            step,
            estimated_error,
            ..
        } = &method
            && *estimated_error > WARN_DISAGREEMENT
        {
            report.warnings.push(format!(
                "{name}: the extrapolated differences agree only to {} relative (the column \
                 is not smooth in `{}` within ±{}: a limit position or a change of branch \
                 nearby?)",
                Units::tidy(*estimated_error),
                parameter.name,
                Units::tidy(*step)
            ));
        }
        derivative_columns.push(DerivativeColumn {
            name: name.clone(),
            method,
        });
        push_column(
            &mut report,
            Column {
                name,
                unit: format!("{} per {}", column.unit, parameter.name),
                factor: column.factor,
            },
            d.values.iter().map(|r| r[k]),
        );
    }
    let drive = (
        nominal.columns[0].clone(),
        nominal.rows.iter().map(|r| r[0]).collect(),
    );
    if !spec.has_tolerances() {
        let study = Study {
            derivatives: derivative_columns,
            tolerances: Vec::new(),
            columns: Vec::new(),
            drive,
            monte_carlo: None,
        };
        return Ok((scene, report, Some(study)));
    }
    let toleranced: Vec<usize> = (0..spec.parameters.len())
        .filter(|&p| spec.parameters[p].tolerance.is_some())
        .collect();
    let tolerances: Vec<f64> = toleranced
        .iter()
        .filter_map(|&p| spec.parameters[p].tolerance)
        .collect();
    let mut columns = Vec::with_capacity(spec.studied.len());
    for &k in &spec.studied {
        let per_parameter: Vec<Vec<f64>> = toleranced
            .iter()
            .map(|&p| derivatives[p].values.iter().map(|r| r[k]).collect())
            .collect();
        let (worst, rss) = tolerance::stack_up(&per_parameter, &tolerances);
        let column = nominal.columns[k].clone();
        if !worst.iter().all(|w| w.is_finite()) {
            return Err(Error::Study {
                file: file.to_owned(),
                message: format!(
                    "the worst case of `{}` overflows (is not a finite number) with the \
                     tolerances of `[tolerances]`; give smaller tolerances",
                    column.name
                ),
            });
        }
        columns.push(ColumnStudy {
            column: column.clone(),
            worst_case: largest(&worst),
            rss: largest(&rss),
        });
        for (prefix, values) in [("wc", worst), ("rss", rss)] {
            let extra = Column {
                name: format!("{prefix}({})", column.name),
                unit: column.unit.clone(),
                factor: column.factor,
            };
            push_column(&mut report, extra, values.into_iter());
        }
    }
    let monte_carlo = match options.monte_carlo {
        Some(samples) => Some(tolerance::monte_carlo(
            &spec.parameters,
            &spec.studied,
            &nominal,
            samples,
            options.seed,
            |moved, purpose| runner.run_with(moved, purpose),
        )?),
        None => None,
    };
    let study = Study {
        derivatives: derivative_columns,
        tolerances: toleranced
            .iter()
            .filter_map(|&p| {
                let p = &spec.parameters[p];
                Some((p.name.clone(), p.tolerance?))
            })
            .collect(),
        columns,
        drive,
        monte_carlo,
    };
    Ok((scene, report, Some(study)))
}

/// The largest value and its index (the first, if several).
fn largest(values: &[f64]) -> (f64, usize) {
    values.iter().enumerate().fold(
        (0.0, 0),
        |(m, at), (i, &v)| if v > m { (v, i) } else { (m, at) },
    )
}

/// Appends a column with its values, one per row.
fn push_column(report: &mut Report, column: Column, values: impl Iterator<Item = f64>) {
    report.columns.push(column);
    for (row, v) in report.rows.iter_mut().zip(values) {
        row.push(v);
    }
}

/// The derivatives of the columns asked of one parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct Derivative {
    /// `values[row][column]` (SI per unit of the parameter; 0 in the columns not asked).
    pub values: Vec<Vec<f64>>,
    /// Per column, how it was computed (`None`: not asked).
    pub methods: Vec<Option<Method>>,
}

/// Which columns of a scene's table the exact routes reach: the kinematic columns (the
/// drive's first), the dynamics columns, then the balancing columns.
struct ColumnClasses {
    kinematic: usize,
    dynamics_end: usize,
}

impl ColumnClasses {
    fn of(scene: &Scene, columns: usize) -> Self {
        let cx = scene.error_context();
        let balancing = scene
            .balancing
            .as_ref()
            .map_or(0, |b| crate::scene::balancing::columns(&cx, b).len());
        ColumnClasses {
            kinematic: crate::scene::sweep::kinematic_columns(&cx, &scene.outputs).len(),
            dynamics_end: columns - balancing,
        }
    }
}

/// Richardson-extrapolated central differences of whole runs with respect to one
/// parameter: every column's, with their error estimate.
#[derive(Debug, Clone, PartialEq)]
pub struct Extrapolated {
    /// `values[row][column]` (SI per unit of the parameter).
    pub values: Vec<Vec<f64>>,
    /// `|last extrapolation − the one before|` per entry: an estimate of the error.
    pub disagreement: Vec<Vec<f64>>,
    /// The first step used, in the parameter's unit.
    pub step: f64,
}

/// The Richardson-extrapolated differences of every column of the scene `text` (named
/// `file`, with `settings`) with respect to `parameter`: the fallback of the exact route,
/// also for comparing the two.
///
/// # Errors
/// As [`run`].
pub fn extrapolated(
    file: &str,
    text: &str,
    settings: &[Setting],
    parameter: &Parameter,
) -> Result<Extrapolated> {
    let scene = crate::scene::parse_with(file, text, settings)?;
    let nominal = crate::scene::run(&scene)?;
    Runner {
        file,
        text,
        settings,
        nominal: &nominal,
    }
    .richardson(parameter)
}

/// Runs the scene with parameters moved, checked against the nominal run.
pub(crate) struct Runner<'a> {
    file: &'a str,
    text: &'a str,
    settings: &'a [Setting],
    nominal: &'a Report,
}

impl Runner<'_> {
    /// The report with `moved` applied after the command line's settings.
    fn run_with(&self, moved: &[Setting], purpose: &str) -> Result<Report> {
        let mut with = self.settings.to_vec();
        with.extend_from_slice(moved);
        let wrap = |source: Error| Error::Perturbed {
            settings: moved
                .iter()
                .map(|s| format!("{}={}", s.name, s.value))
                .collect::<Vec<_>>()
                .join(", "),
            purpose: purpose.to_owned(),
            source: Box::new(source),
        };
        let scene = crate::scene::parse_with(self.file, self.text, &with).map_err(wrap)?;
        let report = crate::scene::run(&scene).map_err(wrap)?;
        let same = report.rows.len() == self.nominal.rows.len()
            && report.columns.len() == self.nominal.columns.len()
            && report
                .rows
                .iter()
                .zip(&self.nominal.rows)
                .all(|(a, b)| a[0] == b[0]);
        if !same {
            let names: Vec<&str> = moved.iter().map(|s| s.name.as_str()).collect();
            return Err(Error::Study {
                file: self.file.to_owned(),
                message: format!(
                    "with {} moved ({purpose}) the table has other drive positions or \
                     columns than with the parameters' values; a sensitivity is taken at \
                     fixed drive positions: write `[sweep]` and the outputs without {}",
                    names.join(", "),
                    names.join(", ")
                ),
            });
        }
        Ok(report)
    }

    /// The derivatives of the columns `needed` with respect to `p`: exact where the exact
    /// routes reach, Richardson-extrapolated differences elsewhere (see the module's doc).
    fn derivative(
        &self,
        scene: &Scene,
        classes: &ColumnClasses,
        p: &Parameter,
        needed: &[usize],
    ) -> Result<Derivative> {
        let (rows, width) = (self.nominal.rows.len(), self.nominal.columns.len());
        let mut values = vec![vec![0.0; width]; rows];
        let mut methods: Vec<Option<Method>> = vec![None; width];
        let tangent = exact::tangent(self, &p.name);
        // The kinematic columns, by the scene's tangent and the pose's.
        let kinematic = if needed.iter().any(|&k| k < classes.kinematic) {
            Some(exact::kinematic(self, scene, &tangent))
        } else {
            None
        };
        // The single place where the dynamics columns' exact derivatives plug in.
        let dynamics =
            if (needed.iter()).any(|&k| (classes.kinematic..classes.dynamics_end).contains(&k)) {
                Some(exact::dynamics(self, scene, &tangent, classes.kinematic))
            } else {
                None
            };
        let mut fallback: Vec<(usize, String)> = Vec::new();
        for &k in needed {
            let class = if k == 0 {
                // The drive's column: fixed positions, whatever the parameter (0).
                None
            } else if k < classes.kinematic {
                kinematic.as_ref()
            } else if k < classes.dynamics_end {
                dynamics.as_ref()
            } else {
                fallback.push((k, "balancing columns have no exact route".to_owned()));
                continue;
            };
            match class.map(|c| c.as_ref().map(|c| (c.not_reached.get(&k), c))) {
                None => methods[k] = Some(Method::Exact),
                Some(Ok((None, columns))) => {
                    for (r, c) in values.iter_mut().zip(&columns.values) {
                        r[k] = c[k];
                    }
                    methods[k] = Some(Method::Exact);
                }
                Some(Ok((Some(why), _))) | Some(Err(why)) => fallback.push((k, why.clone())),
            }
        }
        if !fallback.is_empty() {
            let d = self.richardson(p)?;
            for (k, why) in fallback {
                let scale = d.values.iter().map(|r| r[k].abs()).fold(0.0, f64::max);
                let disagreement = d.disagreement.iter().map(|r| r[k]).fold(0.0, f64::max);
                for (r, dr) in values.iter_mut().zip(&d.values) {
                    r[k] = dr[k];
                }
                methods[k] = Some(Method::Richardson {
                    step: d.step,
                    estimated_error: if scale > 0.0 {
                        disagreement / scale
                    } else {
                        0.0
                    },
                    why,
                });
            }
        }
        Ok(Derivative { values, methods })
    }

    /// Richardson-extrapolated differences of every column with respect to `p`.
    fn richardson(&self, p: &Parameter) -> Result<Extrapolated> {
        let mut step = if p.value != 0.0 {
            RELATIVE_STEP * p.value.abs()
        } else {
            p.tolerance.map_or(ZERO_STEP, |t| TOLERANCE_STEPS * t)
        };
        let mut attempt = 0;
        loop {
            match self.extrapolated(p, step) {
                Ok(d) => return Ok(d),
                Err(Error::Perturbed { .. }) if attempt < RETRIES => {
                    attempt += 1;
                    step /= 8.0;
                }
                Err(e) => return Err(e),
            }
        }
    }

    /// Central differences with steps `h`, `h/2`, `h/4`, extrapolated twice.
    fn extrapolated(&self, p: &Parameter, h: f64) -> Result<Extrapolated> {
        let purpose = format!("for the derivative with respect to `{}`", p.name);
        let mut differences: Vec<Vec<Vec<f64>>> = Vec::with_capacity(3);
        for level in 0..3 {
            let h = h / f64::from(1 << level);
            let (up, down) = (p.value + h, p.value - h);
            let at = |v: f64| {
                [Setting {
                    name: p.name.clone(),
                    value: format!("{v:e}"),
                }]
            };
            let high = self.run_with(&at(up), &purpose)?;
            let low = self.run_with(&at(down), &purpose)?;
            // The steps actually taken (p ± h rounded), so the quotient is the slope of the
            // two runs.
            let width = up - down;
            differences.push(
                high.rows
                    .iter()
                    .zip(&low.rows)
                    .map(|(a, b)| a.iter().zip(b).map(|(x, y)| (x - y) / width).collect())
                    .collect(),
            );
        }
        let combine = |a: &Vec<Vec<f64>>, b: &Vec<Vec<f64>>, weight: f64| -> Vec<Vec<f64>> {
            a.iter()
                .zip(b)
                .map(|(ra, rb)| {
                    ra.iter()
                        .zip(rb)
                        .map(|(&coarse, &fine)| fine + (fine - coarse) / (weight - 1.0))
                        .collect()
                })
                .collect()
        };
        // h² cancelled (weight 4), then h⁴ (weight 16).
        let first = combine(&differences[0], &differences[1], 4.0);
        let second = combine(&differences[1], &differences[2], 4.0);
        let values = combine(&first, &second, 16.0);
        let disagreement = values
            .iter()
            .zip(&second)
            .map(|(a, b)| a.iter().zip(b).map(|(x, y)| (x - y).abs()).collect())
            .collect();
        Ok(Extrapolated {
            values,
            disagreement,
            step: h,
        })
    }
}

/// `v` to six significant digits.
fn significant(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let decimals = 5 - v.abs().log10().floor() as i32;
    if (0..=12).contains(&decimals) {
        format!("{v:.*}", decimals as usize)
    } else {
        format!("{v:.5e}")
    }
}

/// Writes the study's summary: how each derivative column was computed and its estimated
/// error; then, with `[tolerances]`, per studied column the largest worst case and
/// root-sum-square over the sweep, where they are, and the Monte-Carlo check.
pub fn write_summary(study: &Study, out: &mut impl Write) -> io::Result<()> {
    if !study.derivatives.is_empty() {
        writeln!(out, "derivative columns:")?;
        for d in &study.derivatives {
            match &d.method {
                Method::Exact => writeln!(
                    out,
                    "  {}: exact (dual numbers: the scene's tangent through the pose's \
                     implicit differentiation)",
                    d.name
                )?,
                Method::Richardson {
                    step,
                    estimated_error,
                    why,
                } => writeln!(
                    out,
                    "  {}: Richardson-extrapolated central differences of whole runs (steps \
                     h, h/2, h/4, h = {}), not exact, estimated error {estimated_error:.0e} \
                     (the last two extrapolations' largest disagreement, relative to the \
                     column's largest value); not exact because {why}",
                    d.name,
                    Units::tidy(*step)
                )?,
            }
        }
    }
    if study.columns.is_empty() {
        return Ok(());
    }
    let tolerances: Vec<String> = study
        .tolerances
        .iter()
        .map(|(name, t)| format!("{name} ± {}", Units::tidy(*t)))
        .collect();
    writeln!(
        out,
        "tolerance study (first order, {}):",
        tolerances.join(", ")
    )?;
    let (drive, positions) = &study.drive;
    let at = |row: usize| {
        format!(
            "{} = {} {}",
            drive.name,
            Units::tidy(positions[row] / drive.factor),
            drive.unit
        )
    };
    for (i, c) in study.columns.iter().enumerate() {
        let shown = |v: f64| match c.column.unit.as_str() {
            "1" | "" => significant(v / c.column.factor),
            unit => format!("{} {unit}", significant(v / c.column.factor)),
        };
        write!(
            out,
            "  {}: worst case ±{} at {}, root-sum-square ±{} at {}",
            c.column.name,
            shown(c.worst_case.0),
            at(c.worst_case.1),
            shown(c.rss.0),
            at(c.rss.1)
        )?;
        if let Some(mc) = &study.monte_carlo {
            let sampled = mc.max_deviation[i];
            let share = if c.worst_case.0 > 0.0 {
                format!(
                    "{:.1} % of the worst case",
                    100.0 * sampled / c.worst_case.0
                )
            } else {
                "the worst case is 0".to_owned()
            };
            write!(
                out,
                "; Monte Carlo ({} samples, seed {}): largest deviation {} ({share})",
                mc.samples,
                mc.seed,
                shown(sampled)
            )?;
        }
        writeln!(out)?;
    }
    if study.monte_carlo.is_some() {
        writeln!(
            out,
            "  (the worst case is first order: a sample may exceed it by the second-order \
             remainder ½·δᵀ(∂²y/∂p²)δ, of the order of the tolerances squared)"
        )?;
    }
    Ok(())
}
