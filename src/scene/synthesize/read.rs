//! `[synthesize]` given meaning: the scene's parameters matched to the linkage's design
//! variables, bounds, targets and drive positions converted to SI, limits checked, and the
//! engine's [`Problem`] and [`Synthesis`] built. Every error names `file:line:column`.

use std::collections::HashMap;
use std::ops::Range;
use std::time::Duration;

use mechdiff_core::synthesis::{
    Constraints, Derivatives, GrashofClass, Linkage, MAX_ROUNDS, MAX_STARTS, MAX_TARGETS, Problem,
    Synthesis, SynthesisError, Task, Timing,
};
use toml::Spanned;

use super::section::{FunctionDef, MotionDef, Numbers, PathDef, SynthesisOnly, SynthesizeDef};
use super::{Method, Setup, Variable};
use crate::error::{Error, Result};
use crate::scene::Source;
use crate::scene::bindings::Bindings;
use crate::scene::parameters::{self, ParameterValue, Plain};
use crate::scene::units::{Dimension, Units};
use crate::scene::values::{Number, formula};

/// The most residual evaluations a search may be given.
pub const MAX_EVALUATIONS: i64 = 1_000_000_000;
/// The longest time limit (s): one day.
pub const MAX_TIME_LIMIT: f64 = 86_400.0;
/// The time limit when the section gives none (s).
pub const DEFAULT_TIME_LIMIT: f64 = 60.0;

/// The linkages by the names a scene writes.
const LINKAGES: [(&str, Linkage); 3] = [
    ("four_bar", Linkage::FourBar),
    ("slider_crank", Linkage::SliderCrank),
    ("stephenson_six", Linkage::StephensonSix),
];

/// Reads and checks the `[synthesize]` section of the scene `text` (`file` names it).
///
/// # Errors
/// A TOML error at its place; no `[synthesize]` section, or not exactly one task; an
/// unknown linkage, branch side, variable, parameter, point, output or link; a design
/// variable that is not a plain number in `[parameters]`; bounds, targets or drive
/// positions of the wrong shape or count; a limit out of its range. Each at
/// `file:line:column`, saying what to write.
pub fn read(file: &str, text: &str) -> Result<Setup> {
    let source = Source::new(file, text);
    let only: SynthesisOnly = toml::from_str(text).map_err(|e| source.syntax_error(&e))?;
    let Some(section) = &only.synthesize else {
        return Err(Error::Invalid {
            location: source.location(0..0),
            message: "the scene has no `[synthesize]` section; add one with the linkage, \
                      the bounds of its parameters and a task (docs/scene-format.md, \
                      \"Synthesis\")"
                .into(),
        });
    };
    let values = parameters::read_with_own_units(text, &source, &[])?;
    let bindings = Bindings::new(values.iter().map(|(n, v, _)| (n.clone(), *v)).collect());
    let units = Units::declared(&only.units);
    let reader = Reader {
        source: &source,
        bindings: &bindings,
        units: &units,
    };
    reader.setup(&only, section, &values)
}

/// As [`read`], `None` when the scene has no `[synthesize]` section (`mechdiff check`).
///
/// # Errors
/// As [`read`].
pub fn read_if_present(file: &str, text: &str) -> Result<Option<Setup>> {
    let present = text
        .parse::<toml::Table>()
        .is_ok_and(|t| t.contains_key("synthesize"));
    present.then(|| read(file, text)).transpose()
}

struct Reader<'a> {
    source: &'a Source,
    bindings: &'a Bindings,
    units: &'a Units,
}

impl Reader<'_> {
    fn invalid(&self, span: Range<usize>, message: impl Into<String>) -> Error {
        Error::Invalid {
            location: self.source.location(span),
            message: message.into(),
        }
    }

    /// A number in SI (the file's unit of `dimension` converted).
    fn number(&self, n: &Spanned<Number>, dimension: Dimension) -> Result<f64> {
        let value: f64 = n
            .get_ref()
            .value_in(self.bindings)
            .map_err(|e| self.invalid(n.span(), e))?;
        if !value.is_finite() {
            return Err(self.invalid(n.span(), "the number must be finite"));
        }
        Ok(self.units.to_si(value, dimension))
    }

    /// A list of `width` numbers of the given dimensions.
    fn row(&self, row: &Numbers, dimensions: &[Dimension], what: &str) -> Result<Vec<f64>> {
        if row.get_ref().len() != dimensions.len() {
            return Err(self.invalid(
                row.span(),
                format!(
                    "{what} has {} numbers; write {} ({})",
                    row.get_ref().len(),
                    dimensions.len(),
                    dimensions
                        .iter()
                        .map(|d| self.units.symbol(*d))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            ));
        }
        row.get_ref()
            .iter()
            .zip(dimensions)
            .map(|(n, d)| self.number(n, *d))
            .collect()
    }

    /// A count between `least` and `most`, or `default`.
    fn count(
        &self,
        value: Option<&Spanned<i64>>,
        key: &str,
        least: i64,
        most: i64,
        default: i64,
    ) -> Result<usize> {
        let Some(v) = value else {
            return Ok(default as usize);
        };
        if !(least..=most).contains(v.get_ref()) {
            return Err(self.invalid(
                v.span(),
                format!(
                    "`{key}` = {} is out of range; write a whole number from {least} to {most}",
                    v.get_ref()
                ),
            ));
        }
        Ok(*v.get_ref() as usize)
    }

    fn setup(
        &self,
        only: &SynthesisOnly,
        section: &Spanned<SynthesizeDef>,
        values: &[(String, f64, f64)],
    ) -> Result<Setup> {
        let def = section.get_ref();
        let Some(&(_, linkage)) = LINKAGES.iter().find(|(n, _)| n == def.linkage.get_ref()) else {
            return Err(self.invalid(
                def.linkage.span(),
                format!(
                    "unknown linkage `{}`; synthesis sizes: four_bar, slider_crank, \
                     stephenson_six",
                    def.linkage.get_ref()
                ),
            ));
        };
        let (task, task_span, task_angles) = self.task(def, section.span())?;
        let branch = self.branch(def, linkage)?;
        // Engine variable → scene parameter.
        let mut renamed: HashMap<&str, &Spanned<String>> = HashMap::new();
        if let Some(names) = &def.names {
            for (variable, parameter) in names.get_ref() {
                if !linkage
                    .variable_names()
                    .contains(&variable.get_ref().as_str())
                {
                    return Err(self.invalid(
                        variable.span(),
                        format!(
                            "`{}` is not a variable of the {}; its variables are {}",
                            variable.get_ref(),
                            def.linkage.get_ref(),
                            linkage.variable_names().join(", ")
                        ),
                    ));
                }
                renamed.insert(variable.get_ref().as_str(), parameter);
            }
        }
        let table = only.parameters.as_ref().map(Spanned::get_ref);
        let mut variables = Vec::new();
        for &name in linkage.variable_names() {
            let parameter = renamed.get(name).map_or(name, |p| p.get_ref().as_str());
            variables.push(Variable {
                name: name.to_owned(),
                parameter: Some(parameter.to_owned()),
                dimension: variable_dimension(linkage, name),
                bounds: None,
                value_span: None,
            });
        }
        for name in &task_angles {
            variables.push(Variable {
                name: name.clone(),
                parameter: None,
                dimension: Dimension::Angle,
                bounds: None,
                value_span: None,
            });
        }
        // Bounds, by parameter name (or task angle).
        let mut bound_spans = HashMap::new();
        for (key, pair) in def.bounds.get_ref() {
            let Some(v) = variables.iter_mut().find(|v| {
                v.parameter.as_deref() == Some(key.get_ref().as_str())
                    || (v.parameter.is_none() && v.name == *key.get_ref())
            }) else {
                let known: Vec<String> = variables
                    .iter()
                    .map(|v| v.parameter.clone().unwrap_or_else(|| v.name.clone()))
                    .collect();
                return Err(self.invalid(
                    key.span(),
                    format!(
                        "`{}` is not a design variable of this synthesis; bound one of: {}",
                        key.get_ref(),
                        known.join(", ")
                    ),
                ));
            };
            let [lower, upper] = self.row(pair, &[v.dimension; 2], "a bound")?[..] else {
                unreachable!("row checks the length")
            };
            if lower > upper {
                return Err(self.invalid(
                    pair.span(),
                    "the lower bound exceeds the upper; write `[lower, upper]`",
                ));
            }
            v.bounds = Some((lower, upper));
            bound_spans.insert(v.name.clone(), pair.span());
        }
        // Every linkage variable: a parameter of the scene, fixed or bounded.
        for v in variables.iter_mut().filter(|v| v.parameter.is_some()) {
            let parameter = v.parameter.clone().unwrap_or_default();
            let entry = table.and_then(|t| t.iter().find(|(n, _)| *n.get_ref() == parameter));
            let value = values.iter().find(|(n, _, _)| *n == parameter);
            let (Some((_, written)), Some((_, value, _))) = (entry, value) else {
                let at = bound_spans
                    .get(&v.name)
                    .cloned()
                    .unwrap_or(section.span().start..section.span().start);
                return Err(self.invalid(
                    at,
                    format!(
                        "the {}'s variable `{}` is not a parameter of the scene; add `{parameter} \
                         = …` to `[parameters]` and build the sketch from it (or name the \
                         parameter that plays its part in `[synthesize.names]`)",
                        def.linkage.get_ref(),
                        v.name
                    ),
                ));
            };
            match v.bounds {
                Some((lower, upper)) if lower < upper => {
                    if !matches!(written.get_ref(), ParameterValue::Plain(Plain::Number(_))) {
                        return Err(self.invalid(
                            written.span(),
                            format!(
                                "the design variable `{parameter}` must be a plain number in \
                                 the file's unit here, so that the value found can be written \
                                 in its place; write it as a number"
                            ),
                        ));
                    }
                    v.value_span = Some(written.span());
                }
                Some(_) => {}
                None => {
                    let si = self.units.to_si(*value, v.dimension);
                    v.bounds = Some((si, si));
                }
            }
        }
        let sketch_span = match &def.sketch {
            None => None,
            Some(name) => {
                let entry =
                    table.and_then(|t| t.iter().find(|(n, _)| n.get_ref() == name.get_ref()));
                match entry {
                    Some((_, written))
                        if matches!(written.get_ref(), ParameterValue::Plain(Plain::Number(_)))
                            && !variables.iter().any(|v| {
                                v.parameter.as_deref() == Some(name.get_ref().as_str())
                            }) =>
                    {
                        Some(written.span())
                    }
                    _ => {
                        return Err(self.invalid(
                            name.span(),
                            format!(
                                "`sketch` names the parameter holding the sketch's drive \
                                 position (a plain number in the file's angle unit, used in \
                                 the crank's `angle`, and not a dimension of the linkage); \
                                 `{}` is not such a parameter",
                                name.get_ref()
                            ),
                        ));
                    }
                }
            }
        };
        let mut builder = Problem::builder(linkage, task).branch(&branch);
        for v in &variables {
            if let Some((lower, upper)) = v.bounds {
                builder = builder.bound(&v.name, lower, upper);
            }
        }
        let constraints = Constraints {
            crank_rotates: def.crank_rotates.as_ref().is_some_and(|c| *c.get_ref()),
            min_transmission: match &def.min_transmission {
                Some(n) => self.number(n, Dimension::Angle)?,
                None => 0.0,
            },
            checks_between_targets: self.count(
                def.checks_between_targets.as_ref(),
                "checks_between_targets",
                1,
                mechdiff_core::synthesis::MAX_CHECKS as i64,
                8,
            )?,
        };
        let (crank_rotates, min_transmission) =
            (constraints.crank_rotates, constraints.min_transmission);
        let weights = self.task_weights(def)?;
        if let Some(weights) = &weights {
            builder = builder.weights(weights.clone());
        }
        builder = builder.grashof(self.grashof(def, linkage, crank_rotates)?);
        let problem = builder.constraints(constraints).build().map_err(|source| {
            let span = match &source {
                SynthesisError::InvalidBound { variable, .. } => bound_spans.get(variable).cloned(),
                SynthesisError::InvalidSetting { setting, .. } => match *setting {
                    "min_transmission" => def.min_transmission.as_ref().map(Spanned::span),
                    "angle_weight" => def.motion.as_ref().map(|m| m.get_ref().angle_weight.span()),
                    _ => None,
                },
                SynthesisError::InvalidConstraint { constraint, .. } => match *constraint {
                    "grashof" => def.grashof.as_ref().map(Spanned::span),
                    _ => weights_def(def).map(Spanned::span),
                },
                _ => None,
            };
            Error::Synthesis {
                location: self.source.location(span.unwrap_or(task_span.clone())),
                source,
            }
        })?;
        let settings = self.settings(def)?;
        let method = match &def.method {
            None => Method::Exact,
            Some(m) => Method::named(m.get_ref()).ok_or_else(|| {
                self.invalid(
                    m.span(),
                    format!(
                        "unknown method `{}`; write `lm` (Levenberg–Marquardt, exact \
                         Jacobian), `differences` (the same with central differences) or \
                         `evolution` (differential evolution, no derivatives)",
                        m.get_ref()
                    ),
                )
            })?,
        };
        Ok(Setup {
            problem,
            settings,
            variables,
            units: *self.units,
            source: self.source.clone(),
            linkage_name: def.linkage.get_ref().clone(),
            method,
            crank_rotates,
            min_transmission,
            sketch_span,
            bounds_span: def.bounds.span(),
            time_span: def
                .time_limit
                .as_ref()
                .map_or(section.span(), Spanned::span),
        })
    }

    /// The task, its span and the names of its angles among the design variables.
    fn task(
        &self,
        def: &SynthesizeDef,
        section: Range<usize>,
    ) -> Result<(Task, Range<usize>, Vec<String>)> {
        let given = [
            def.path.as_ref().map(Spanned::span),
            def.function.as_ref().map(Spanned::span),
            def.motion.as_ref().map(Spanned::span),
        ];
        if given.iter().flatten().count() != 1 {
            let at = given.iter().flatten().nth(1).cloned().unwrap_or(section);
            return Err(self.invalid(
                at,
                "a synthesis has exactly one task: `[synthesize.path]`, \
                 `[synthesize.function]` or `[synthesize.motion]`",
            ));
        }
        if let Some(path) = &def.path {
            let (task, angles) = self.path(path.get_ref())?;
            return Ok((task, path.get_ref().point.span(), angles));
        }
        if let Some(function) = &def.function {
            let task = self.function(function)?;
            return Ok((
                task,
                function.get_ref().output.span(),
                vec!["drive0".into()],
            ));
        }
        let motion = def.motion.as_ref().expect("one task is given");
        let (task, mut angles) = self.motion(motion.get_ref())?;
        angles.insert(0, "pose_angle".into());
        Ok((task, motion.get_ref().link.span(), angles))
    }

    /// The targets' rows, bounded before they are converted.
    fn rows(
        &self,
        rows: &Spanned<Vec<Numbers>>,
        dimensions: &[Dimension],
        what: &str,
    ) -> Result<Vec<Vec<f64>>> {
        if rows.get_ref().is_empty() || rows.get_ref().len() > MAX_TARGETS {
            return Err(self.invalid(
                rows.span(),
                format!(
                    "{} {what}s; write from 1 to {MAX_TARGETS}",
                    rows.get_ref().len()
                ),
            ));
        }
        rows.get_ref()
            .iter()
            .map(|r| self.row(r, dimensions, what))
            .collect()
    }

    /// The timing of `count` targets from `drive` and `timing`, and the names of its angles.
    fn timing(
        &self,
        drive: Option<&Numbers>,
        timing: Option<&Spanned<String>>,
        count: usize,
        at: Range<usize>,
    ) -> Result<(Timing, Vec<String>)> {
        let kind = timing.map(|t| t.get_ref().as_str());
        let angles = |drive: Option<&Numbers>| -> Result<Vec<f64>> {
            let Some(drive) = drive else {
                return Err(self.invalid(
                    timing.map_or(at.clone(), Spanned::span),
                    "this timing needs `drive = [...]`, the drive position of each target in \
                     the file's angle unit; or write `timing = \"free\"`",
                ));
            };
            if drive.get_ref().len() != count {
                return Err(self.invalid(
                    drive.span(),
                    format!(
                        "{} drive positions for {count} targets; give one per target",
                        drive.get_ref().len()
                    ),
                ));
            }
            let dimensions = vec![Dimension::Angle; count];
            self.row(drive, &dimensions, "`drive`")
        };
        match (kind, drive) {
            (None, Some(_)) | (Some("absolute"), _) => {
                Ok((Timing::Absolute(angles(drive)?), vec![]))
            }
            (Some("relative"), _) => Ok((Timing::Relative(angles(drive)?), vec!["drive0".into()])),
            (None, None) | (Some("free"), None) => Ok((
                Timing::Free,
                (1..=count).map(|i| format!("drive{i}")).collect(),
            )),
            (Some("free"), Some(d)) => Err(self.invalid(
                d.span(),
                "free timing finds each target's drive position; remove `drive`, or write \
                 `timing = \"absolute\"` or `\"relative\"`",
            )),
            (Some(other), _) => Err(self.invalid(
                timing.map_or(at, Spanned::span),
                format!("unknown timing `{other}`; write `absolute`, `relative` or `free`"),
            )),
        }
    }

    fn path(&self, def: &PathDef) -> Result<(Task, Vec<String>)> {
        let targets = self.rows(&def.targets, &[Dimension::Length; 2], "target")?;
        let (timing, angles) = self.timing(
            def.drive.as_ref(),
            def.timing.as_ref(),
            targets.len(),
            def.point.span(),
        )?;
        Ok((
            Task::Path {
                point: def.point.get_ref().clone(),
                targets: targets.iter().map(|t| [t[0], t[1]]).collect(),
                timing,
            },
            angles,
        ))
    }

    fn motion(&self, def: &MotionDef) -> Result<(Task, Vec<String>)> {
        use Dimension::{Angle, Length};
        let poses = self.rows(&def.poses, &[Length, Length, Angle], "pose")?;
        let (timing, angles) = self.timing(
            def.drive.as_ref(),
            def.timing.as_ref(),
            poses.len(),
            def.link.span(),
        )?;
        Ok((
            Task::Motion {
                link: def.link.get_ref().clone(),
                poses: poses.iter().map(|p| [p[0], p[1], p[2]]).collect(),
                timing,
                angle_weight: self.number(&def.angle_weight, Length)?,
            },
            angles,
        ))
    }

    fn function(&self, spanned: &Spanned<FunctionDef>) -> Result<Task> {
        let def = spanned.get_ref();
        let output = def.output.get_ref().clone();
        // The output's unit: a length for the slider, an angle otherwise.
        let dimension = if output == "slider" {
            Dimension::Length
        } else {
            Dimension::Angle
        };
        let pairs = match (&def.pairs, &def.formula) {
            (Some(pairs), None) => self.rows(pairs, &[Dimension::Angle, dimension], "pair")?,
            (None, Some(text)) => self.sampled(def, text, dimension)?,
            _ => {
                return Err(self.invalid(
                    spanned.span(),
                    "give either `pairs = [[drive, output], …]` or `formula`, `from`, `to` \
                     and `count`",
                ));
            }
        };
        if pairs.len() < 2 {
            return Err(self.invalid(
                spanned.span(),
                "function generation needs at least 2 pairs (only changes from the first \
                 count)",
            ));
        }
        Ok(Task::Function {
            output,
            pairs: pairs.iter().map(|p| [p[0], p[1]]).collect(),
        })
    }

    /// `count` pairs of a formula of `phi` over `from`..`to`.
    fn sampled(
        &self,
        def: &FunctionDef,
        text: &Spanned<String>,
        dimension: Dimension,
    ) -> Result<Vec<Vec<f64>>> {
        let (Some(from), Some(to), Some(count)) = (&def.from, &def.to, &def.count) else {
            return Err(self.invalid(
                text.span(),
                "a formula needs `from`, `to` (the drive range, in the file's angle unit) and \
                 `count` (positions, both ends included)",
            ));
        };
        let count = self.count(Some(count), "count", 2, MAX_TARGETS as i64, 0)?;
        let (from_si, to_si) = (
            self.number(from, Dimension::Angle)?,
            self.number(to, Dimension::Angle)?,
        );
        let mut context: HashMap<String, f64> = self.bindings.values().clone();
        (0..count)
            .map(|k| {
                let phi = from_si + (to_si - from_si) * k as f64 / (count - 1) as f64;
                let written = self.units.from_si(phi, Dimension::Angle);
                context.insert("phi".into(), written);
                let value =
                    formula(text.get_ref(), &context).map_err(|e| self.invalid(text.span(), e))?;
                if !value.is_finite() {
                    return Err(self.invalid(
                        text.span(),
                        format!("the formula is not finite at phi = {written}"),
                    ));
                }
                Ok(vec![phi, self.units.to_si(value, dimension)])
            })
            .collect()
    }

    fn branch(&self, def: &SynthesizeDef, linkage: Linkage) -> Result<Vec<f64>> {
        let Some(sides) = &def.branch else {
            return Ok(vec![1.0; linkage.dyad_count()]);
        };
        if sides.get_ref().len() != linkage.dyad_count() {
            return Err(self.invalid(
                sides.span(),
                format!(
                    "the {} has {} dyads; give one side each (`left` or `right`)",
                    def.linkage.get_ref(),
                    linkage.dyad_count()
                ),
            ));
        }
        sides
            .get_ref()
            .iter()
            .map(|s| match s.get_ref().as_str() {
                "left" => Ok(1.0),
                "right" => Ok(-1.0),
                other => Err(self.invalid(
                    s.span(),
                    format!("unknown side `{other}`; write `left` or `right`"),
                )),
            })
            .collect()
    }

    /// The task's weights, one per target, each finite and ≥ 0 (checked here with their
    /// place; the engine checks that not all are 0).
    fn task_weights(&self, def: &SynthesizeDef) -> Result<Option<Vec<f64>>> {
        let Some(weights) = weights_def(def) else {
            return Ok(None);
        };
        let count = [
            def.path
                .as_ref()
                .map(|p| p.get_ref().targets.get_ref().len()),
            def.function.as_ref().map(|f| {
                let f = f.get_ref();
                match (&f.pairs, &f.count) {
                    (Some(pairs), _) => pairs.get_ref().len(),
                    (None, Some(count)) => (*count.get_ref()).max(0) as usize,
                    (None, None) => 0,
                }
            }),
            def.motion
                .as_ref()
                .map(|m| m.get_ref().poses.get_ref().len()),
        ]
        .into_iter()
        .flatten()
        .next()
        .unwrap_or(0);
        if weights.get_ref().len() != count {
            return Err(self.invalid(
                weights.span(),
                format!(
                    "{} weights for {count} targets; give one per target (default 1 each)",
                    weights.get_ref().len()
                ),
            ));
        }
        weights
            .get_ref()
            .iter()
            .map(|w| {
                let value: f64 = w
                    .get_ref()
                    .value_in(self.bindings)
                    .map_err(|e| self.invalid(w.span(), e))?;
                if value.is_finite() && value >= 0.0 {
                    Ok(value)
                } else {
                    Err(self.invalid(
                        w.span(),
                        format!("the weight {value} is not a finite number ≥ 0"),
                    ))
                }
            })
            .collect::<Result<Vec<f64>>>()
            .map(Some)
    }

    /// The Grashof class asked for (`any` when none), checked against the linkage and
    /// `crank_rotates`.
    fn grashof(
        &self,
        def: &SynthesizeDef,
        linkage: Linkage,
        crank_rotates: bool,
    ) -> Result<GrashofClass> {
        let Some(name) = &def.grashof else {
            return Ok(GrashofClass::Any);
        };
        let Some(class) = GrashofClass::named(name.get_ref()) else {
            return Err(self.invalid(
                name.span(),
                format!(
                    "unknown Grashof class `{}`; write one of {}",
                    name.get_ref(),
                    GrashofClass::NAMES
                        .iter()
                        .map(|(n, _)| format!("`{n}`"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            ));
        };
        if class != GrashofClass::Any && linkage == Linkage::SliderCrank {
            return Err(self.invalid(
                name.span(),
                "a slider-crank has no Grashof class; ask its crank to turn fully with \
                 `crank_rotates = true`, or write `grashof = \"any\"`",
            ));
        }
        if crank_rotates && !matches!(class, GrashofClass::Any | GrashofClass::CrankRocker) {
            return Err(self.invalid(
                name.span(),
                format!(
                    "`crank_rotates = true` asks a crank-rocker (the crank shortest), which \
                     contradicts `grashof = \"{}\"`; drop one of them",
                    name.get_ref()
                ),
            ));
        }
        Ok(class)
    }

    /// The search settings, each limit checked before any work.
    fn settings(&self, def: &SynthesizeDef) -> Result<Synthesis> {
        let mut s = Synthesis::seeded(match &def.seed {
            Some(seed) if *seed.get_ref() < 0 => {
                return Err(self.invalid(seed.span(), "the seed is a whole number ≥ 0"));
            }
            Some(seed) => *seed.get_ref() as u64,
            None => 1,
        });
        s.starts = self.count(def.starts.as_ref(), "starts", 1, MAX_STARTS as i64, 1000)?;
        s.local_searches = self.count(
            def.local_searches.as_ref(),
            "local_searches",
            1,
            s.starts as i64,
            s.local_searches.min(s.starts) as i64,
        )?;
        s.max_evaluations = self.count(
            def.evaluations.as_ref(),
            "evaluations",
            1,
            MAX_EVALUATIONS,
            s.max_evaluations as i64,
        )?;
        let time = match &def.time_limit {
            Some(t) => {
                let value: f64 = t
                    .get_ref()
                    .value_in(self.bindings)
                    .map_err(|e| self.invalid(t.span(), e))?;
                check_time_limit(value).map_err(|m| self.invalid(t.span(), m))?
            }
            None => DEFAULT_TIME_LIMIT,
        };
        s.time_limit = Some(Duration::from_secs_f64(time));
        if let Some(objective) = &def.objective {
            let value: f64 = objective
                .get_ref()
                .value_in(self.bindings)
                .map_err(|e| self.invalid(objective.span(), e))?;
            if !(value.is_finite() && value >= 0.0) {
                return Err(self.invalid(
                    objective.span(),
                    "the objective to stop at is a finite number ≥ 0 (m²)",
                ));
            }
            s.stop_objective = value;
        }
        s.rounds = self.count(def.rounds.as_ref(), "rounds", 1, MAX_ROUNDS as i64, 1)?;
        s.fit_timing = def.fit_timing.as_ref().is_some_and(|f| *f.get_ref());
        s.derivatives = match def.method.as_ref().map(|m| m.get_ref().as_str()) {
            Some("differences") => Derivatives::CentralDifferences,
            _ => Derivatives::Exact,
        };
        Ok(s)
    }
}

/// The task's `weights`, if given.
fn weights_def(def: &SynthesizeDef) -> Option<&Numbers> {
    (def.path.as_ref().and_then(|p| p.get_ref().weights.as_ref()))
        .or_else(|| (def.function.as_ref()).and_then(|f| f.get_ref().weights.as_ref()))
        .or_else(|| (def.motion.as_ref()).and_then(|m| m.get_ref().weights.as_ref()))
}

/// A time limit in seconds, checked: positive, finite, at most [`MAX_TIME_LIMIT`].
///
/// # Errors
/// What is wrong and what to write.
pub fn check_time_limit(seconds: f64) -> std::result::Result<f64, String> {
    if seconds > 0.0 && seconds <= MAX_TIME_LIMIT {
        Ok(seconds)
    } else {
        Err(format!(
            "the time limit {seconds} s is out of range; give more than 0 and at most \
             {MAX_TIME_LIMIT} s (one day)"
        ))
    }
}

/// The unit of a linkage's variable: an angle for the slider-crank's `guide`, a length
/// otherwise.
fn variable_dimension(linkage: Linkage, name: &str) -> Dimension {
    if linkage == Linkage::SliderCrank && name == "guide" {
        Dimension::Angle
    } else {
        Dimension::Length
    }
}
