//! A synthesis problem: a linkage, a task, bounds on every design variable, the assembly
//! branch and constraints; its residuals (generic over the scalar, so that dual numbers give
//! the exact Jacobian) and its defect checks.

use super::error::{Defect, SynthesisError};
use super::grashof::GrashofClass;
use super::linkage::{Linkage, LinkagePose};
use super::task::{Task, Timing};
use crate::Scalar;
use nalgebra::DMatrix;
use num_dual::Dual64;
use std::f64::consts::{PI, TAU};

/// The most targets a task may have.
pub const MAX_TARGETS: usize = 10_000;
/// The most checks of the assembly between two consecutive targets.
pub const MAX_CHECKS: usize = 10_000;

/// What a solution must satisfy besides the task (all checked on every candidate).
#[derive(Debug, Clone, PartialEq)]
pub struct Constraints {
    /// The crank must turn fully (Grashof crank for the four-bar loop, crank + |offset| <
    /// rod for the slider-crank; the six-bar's second dyad checked over a full turn).
    pub crank_rotates: bool,
    /// The least transmission angle of every dyad at the targets and between them (rad).
    pub min_transmission: f64,
    /// Assembly checks between two consecutive targets (equally spaced drive angles).
    pub checks_between_targets: usize,
}

impl Default for Constraints {
    fn default() -> Self {
        Constraints {
            crank_rotates: false,
            min_transmission: 0.0,
            checks_between_targets: 8,
        }
    }
}

/// A validated synthesis problem; build it with [`Problem::builder`].
#[derive(Debug, Clone, PartialEq)]
pub struct Problem {
    pub(crate) linkage: Linkage,
    pub(crate) task: Task,
    pub(crate) branch: Vec<f64>,
    pub(crate) names: Vec<String>,
    pub(crate) lower: Vec<f64>,
    pub(crate) upper: Vec<f64>,
    pub(crate) constraints: Constraints,
    /// The index of the traced point (path) or output (function).
    pub(crate) selected: usize,
    /// Each target's weight (1 unless [`ProblemBuilder::weights`] says otherwise).
    pub(crate) weights: Vec<f64>,
    /// The Grashof class the four-bar loop must have.
    pub(crate) grashof: GrashofClass,
}

/// Bounds and settings not yet validated; see [`ProblemBuilder::build`].
#[derive(Debug, Clone)]
pub struct ProblemBuilder {
    linkage: Linkage,
    task: Task,
    bounds: Vec<(String, f64, f64)>,
    branch: Vec<f64>,
    constraints: Constraints,
    weights: Option<Vec<f64>>,
    grashof: GrashofClass,
}

impl Problem {
    /// Starts a problem: `linkage` must do `task`. Every design variable needs bounds
    /// ([`ProblemBuilder::bound`]) except the task's angles (`drive0`, `drive1`, …,
    /// `pose_angle`), which default to [−π, π] (free drive angles to [−π, 3π]).
    pub fn builder(linkage: Linkage, task: Task) -> ProblemBuilder {
        ProblemBuilder {
            branch: vec![1.0; linkage.dyad_count()],
            linkage,
            task,
            bounds: Vec::new(),
            constraints: Constraints::default(),
            weights: None,
            grashof: GrashofClass::Any,
        }
    }

    /// Each target's weight wᵢ (1 unless given): the objective is Σ wᵢ·eᵢ², eᵢ² the target's
    /// squared error (a point's squared distance, a pair's squared output error, a pose's
    /// squared distance plus its squared weighted angle error), and each residual is
    /// √wᵢ times the error. A function's first pair is the reference and has no residual, so
    /// its weight has no effect.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// The Grashof class the four-bar loop must have ([`GrashofClass::Any`]: none).
    pub fn grashof(&self) -> GrashofClass {
        self.grashof
    }

    /// The names of the design variables: the linkage's, then the task's.
    pub fn variable_names(&self) -> &[String] {
        &self.names
    }

    /// The bounds of every design variable (equal for a fixed one).
    pub fn bounds(&self) -> (&[f64], &[f64]) {
        (&self.lower, &self.upper)
    }

    /// The linkage.
    pub fn linkage(&self) -> Linkage {
        self.linkage
    }

    /// The task.
    pub fn task(&self) -> &Task {
        &self.task
    }

    /// The branch sign of each dyad.
    pub fn branch(&self) -> &[f64] {
        &self.branch
    }

    /// The drive angle of each target for the variables `x`.
    pub fn drive_angles<D: Scalar>(&self, x: &[D]) -> Vec<D> {
        let base = self.linkage.variable_names().len();
        let offset = usize::from(matches!(self.task, Task::Motion { .. }));
        match self.task.timing() {
            Timing::Absolute(angles) => angles.iter().map(|&a| D::from(a)).collect(),
            Timing::Relative(angles) => angles.iter().map(|&a| x[base + offset] + a).collect(),
            Timing::Free => x[base + offset..].to_vec(),
        }
    }

    /// The residuals at `x` (m, rad or the slider's m; a motion's angle errors times its
    /// weight), or the target where the linkage does not assemble. Their sum of squares is
    /// the objective. Evaluated with `Dual64` numbers, their ε parts are one column of the
    /// exact Jacobian.
    pub fn residuals<D: Scalar>(&self, x: &[D]) -> Result<Vec<D>, Defect> {
        let phis = self.drive_angles(x);
        let poses = phis
            .iter()
            .map(|&phi| self.linkage.pose(x, phi, &self.branch))
            .collect::<Result<Vec<LinkagePose<D>>, _>>()
            .map_err(|_| Defect::NoAssemblyAtTarget)?;
        let mut r = Vec::with_capacity(self.task.residual_count());
        match &self.task {
            Task::Path { targets, .. } => {
                for (pose, t) in poses.iter().zip(targets) {
                    let p = pose.points[self.selected];
                    r.extend([p[0] - t[0], p[1] - t[1]]);
                }
            }
            Task::Function { pairs, .. } => {
                let is_angle = self.linkage.output_is_angle(self.selected);
                let mut change = D::from(0.0);
                for (i, pair) in pairs.iter().enumerate().skip(1) {
                    let step =
                        poses[i].outputs[self.selected] - poses[i - 1].outputs[self.selected];
                    change += if is_angle { wrap(step) } else { step };
                    r.push(change - (pair[1] - pairs[0][1]));
                }
            }
            Task::Motion {
                poses: targets,
                angle_weight,
                ..
            } => {
                let beta = x[self.linkage.variable_names().len()];
                let traced = self.linkage.point_names().len() - 1;
                for (pose, t) in poses.iter().zip(targets) {
                    let p = pose.points[traced];
                    let angle = wrap(pose.traced_link_angle + beta - t[2]);
                    r.extend([p[0] - t[0], p[1] - t[1], angle * *angle_weight]);
                }
            }
        }
        self.weigh(&mut r);
        Ok(r)
    }

    /// Multiplies each target's residuals by the square root of its weight (weights of 1 left
    /// alone, so an unweighted problem's numbers are exactly as before).
    fn weigh<D: Scalar>(&self, r: &mut [D]) {
        let per_target = match self.task {
            Task::Path { .. } => 2,
            Task::Function { .. } => 1,
            Task::Motion { .. } => 3,
        };
        // A function's residual k belongs to pair k + 1 (pair 0 is the reference).
        let first = usize::from(matches!(self.task, Task::Function { .. }));
        for (k, chunk) in r.chunks_mut(per_target).enumerate() {
            let w = self.weights[k + first];
            if w != 1.0 {
                let scale = w.sqrt();
                for v in chunk {
                    *v *= scale;
                }
            }
        }
    }

    /// The exact Jacobian of the residuals at `x` with respect to the variables `columns`
    /// (indices into [`Problem::variable_names`]): one evaluation of
    /// [`Problem::residuals`] in `Dual64` numbers per column, no difference quotient. The
    /// objective's gradient is 2·Jᵀr.
    pub fn jacobian(&self, x: &[f64], columns: &[usize]) -> Result<DMatrix<f64>, Defect> {
        let mut jac = DMatrix::zeros(self.task.residual_count(), columns.len());
        for (k, &i) in columns.iter().enumerate() {
            let mut xd: Vec<Dual64> = x.iter().map(|&v| Dual64::from(v)).collect();
            xd[i].eps = 1.0;
            for (row, v) in self.residuals(&xd)?.iter().enumerate() {
                jac[(row, k)] = v.eps;
            }
        }
        Ok(jac)
    }

    /// The sum of squared residuals at `x`, or the first defect found there.
    pub fn objective(&self, x: &[f64]) -> Result<f64, Defect> {
        self.check(x)?;
        Ok(self.residuals(x)?.iter().map(|r| r * r).sum())
    }

    /// The first defect of the mechanism `x`, if any: order of free drive angles, crank
    /// rotation, assembly and transmission at and between the targets.
    pub fn check(&self, x: &[f64]) -> Result<(), Defect> {
        let phis = self.drive_angles(x);
        if matches!(self.task.timing(), Timing::Free)
            && (phis.windows(2).any(|w| w[1] <= w[0]) || phis[phis.len() - 1] - phis[0] >= TAU)
        {
            return Err(Defect::OutOfOrder);
        }
        if self.grashof != GrashofClass::Any && self.linkage.grashof_class(x) != Some(self.grashof)
        {
            return Err(Defect::WrongGrashofClass);
        }
        let least = self.constraints.min_transmission.sin().powi(2);
        let margin = |phi: f64, defect: Defect| -> Result<(), Defect> {
            let pose = self
                .linkage
                .pose(x, phi, &self.branch)
                .map_err(|_| defect)?;
            if pose.margins.iter().any(|&m| m < least) {
                return Err(Defect::TransmissionBelowMinimum);
            }
            Ok(())
        };
        if self.constraints.crank_rotates {
            self.crank_rotates(x)?;
            for k in 0..72 {
                margin(f64::from(k) * TAU / 72.0, Defect::CrankDoesNotRotate)?;
            }
        }
        for &phi in &phis {
            margin(phi, Defect::NoAssemblyAtTarget)?;
        }
        let checks = self.constraints.checks_between_targets;
        for w in phis.windows(2) {
            for k in 1..checks {
                let t = k as f64 / checks as f64;
                margin(w[0] + (w[1] - w[0]) * t, Defect::BlockedBetweenTargets)?;
            }
        }
        Ok(())
    }

    /// Grashof's condition with the crank shortest (four-bar loop), or crank + |offset| < rod.
    fn crank_rotates(&self, x: &[f64]) -> Result<(), Defect> {
        let ok = match self.linkage {
            Linkage::SliderCrank => x[2] + x[4].abs() < x[3],
            _ => {
                let ground = (x[2] - x[0]).hypot(x[3] - x[1]);
                let [crank, coupler, rocker] = [x[4], x[5], x[6]];
                let longest = ground.max(coupler).max(rocker);
                crank < ground.min(coupler).min(rocker)
                    && crank + longest < ground + coupler + rocker - longest
            }
        };
        if ok {
            Ok(())
        } else {
            Err(Defect::CrankDoesNotRotate)
        }
    }
}

/// An angle difference brought into (−π, π] by whole turns (a constant: derivatives kept).
fn wrap<D: Scalar>(angle: D) -> D {
    let turns = ((angle.re() + PI) / TAU).floor();
    angle - turns * TAU
}

impl ProblemBuilder {
    /// Bounds of design variable `name` (lower ≤ upper; equal bounds fix it).
    pub fn bound(mut self, name: &str, lower: f64, upper: f64) -> Self {
        self.bounds.push((name.to_owned(), lower, upper));
        self
    }

    /// Fixes design variable `name` at `value`.
    pub fn fix(self, name: &str, value: f64) -> Self {
        self.bound(name, value, value)
    }

    /// The branch sign (+1 or −1) of each dyad (default +1: B left of A→O4, E left of C→O6;
    /// the slider-crank's B ahead of A along the guide).
    pub fn branch(mut self, branch: &[f64]) -> Self {
        self.branch = branch.to_vec();
        self
    }

    /// The constraints every candidate must satisfy.
    pub fn constraints(mut self, constraints: Constraints) -> Self {
        self.constraints = constraints;
        self
    }

    /// Each target's weight (finite, ≥ 0, one per target, not all 0; default 1 each), see
    /// [`Problem::weights`].
    pub fn weights(mut self, weights: Vec<f64>) -> Self {
        self.weights = Some(weights);
        self
    }

    /// The Grashof class the four-bar loop (the four-bar's, or the six-bar's first loop) must
    /// have; a candidate of another class is rejected ([`Defect::WrongGrashofClass`]). With
    /// [`Constraints::crank_rotates`] (the crank shortest) only `CrankRocker` and `Any` are
    /// consistent; a slider-crank has no Grashof class (its crank's rotation is
    /// `crank_rotates`).
    pub fn grashof(mut self, class: GrashofClass) -> Self {
        self.grashof = class;
        self
    }

    /// Validates names, bounds, targets and settings.
    pub fn build(self) -> Result<Problem, SynthesisError> {
        let linkage = self.linkage;
        let task = self.task;
        let count = task.target_count();
        let need = match task {
            Task::Function { .. } => 2,
            _ => 1,
        };
        if count < need || count > MAX_TARGETS {
            return Err(SynthesisError::TargetCount {
                what: "targets",
                count,
                reason: format!("a task needs between {need} and {MAX_TARGETS}"),
            });
        }
        let selected = select(linkage, &task)?;
        check_targets(&task)?;
        let mut names: Vec<String> = linkage
            .variable_names()
            .iter()
            .map(|s| s.to_string())
            .collect();
        let mut defaults = vec![None; names.len()];
        if matches!(task, Task::Motion { .. }) {
            names.push("pose_angle".into());
            defaults.push(Some((-PI, PI)));
        }
        match task.timing() {
            Timing::Absolute(_) => {}
            Timing::Relative(_) => {
                names.push("drive0".into());
                defaults.push(Some((-PI, PI)));
            }
            Timing::Free => {
                for i in 1..=count {
                    names.push(format!("drive{i}"));
                    defaults.push(Some((-PI, 3.0 * PI)));
                }
            }
        }
        let mut lower: Vec<f64> = defaults
            .iter()
            .map(|d| d.map_or(f64::NAN, |d| d.0))
            .collect();
        let mut upper: Vec<f64> = defaults
            .iter()
            .map(|d| d.map_or(f64::NAN, |d| d.1))
            .collect();
        for (name, lo, hi) in self.bounds {
            let Some(i) = names.iter().position(|n| *n == name) else {
                return Err(SynthesisError::UnknownName {
                    what: "variable",
                    name,
                    known: names,
                });
            };
            let reason = if !lo.is_finite() || !hi.is_finite() {
                Some("bounds must be finite")
            } else if lo > hi {
                Some("the lower bound must not exceed the upper")
            } else {
                None
            };
            if let Some(reason) = reason {
                return Err(SynthesisError::InvalidBound {
                    variable: name,
                    lower: lo,
                    upper: hi,
                    reason,
                });
            }
            (lower[i], upper[i]) = (lo, hi);
        }
        if let Some(i) = lower.iter().position(|l| l.is_nan()) {
            return Err(SynthesisError::MissingBound {
                variable: names[i].clone(),
            });
        }
        if self.branch.len() != linkage.dyad_count() || self.branch.iter().any(|b| b.abs() != 1.0) {
            return Err(SynthesisError::TargetCount {
                what: "branch signs",
                count: self.branch.len(),
                reason: format!(
                    "the linkage needs {} signs, each +1 or −1",
                    linkage.dyad_count()
                ),
            });
        }
        let c = &self.constraints;
        if !(0.0..=PI / 2.0).contains(&c.min_transmission) {
            return Err(SynthesisError::InvalidSetting {
                setting: "min_transmission",
                value: c.min_transmission,
                reason: "a transmission angle between 0 and π/2 rad",
            });
        }
        if c.checks_between_targets == 0 || c.checks_between_targets > MAX_CHECKS {
            return Err(SynthesisError::InvalidSetting {
                setting: "checks_between_targets",
                value: c.checks_between_targets as f64,
                reason: "between 1 and 10 000",
            });
        }
        let weights = match self.weights {
            Some(w) => check_weights(w, count, usize::from(matches!(task, Task::Function { .. })))?,
            None => vec![1.0; count],
        };
        let grashof = self.grashof;
        if grashof != GrashofClass::Any {
            if linkage == Linkage::SliderCrank {
                return Err(SynthesisError::InvalidConstraint {
                    constraint: "grashof",
                    reason: format!(
                        "a slider-crank has no Grashof class (`{}` asked); its crank turns \
                         fully with `crank_rotates`",
                        grashof.name()
                    ),
                });
            }
            if self.constraints.crank_rotates && grashof != GrashofClass::CrankRocker {
                return Err(SynthesisError::InvalidConstraint {
                    constraint: "grashof",
                    reason: format!(
                        "`crank_rotates` asks a crank-rocker (the crank shortest), which \
                         contradicts the class `{}`; drop one of them",
                        grashof.name()
                    ),
                });
            }
        }
        Ok(Problem {
            linkage,
            task,
            branch: self.branch,
            names,
            lower,
            upper,
            constraints: self.constraints,
            selected,
            weights,
            grashof,
        })
    }
}

/// The index of the task's point or output, checking the names.
fn select(linkage: Linkage, task: &Task) -> Result<usize, SynthesisError> {
    let find = |what: &'static str, name: &str, known: &[&str]| {
        known
            .iter()
            .position(|k| *k == name)
            .ok_or_else(|| SynthesisError::UnknownName {
                what,
                name: name.to_owned(),
                known: known.iter().map(|k| k.to_string()).collect(),
            })
    };
    match task {
        Task::Path { point, .. } => find("point", point, linkage.point_names()),
        Task::Function { output, .. } => find("output", output, linkage.output_names()),
        Task::Motion { link, .. } => find("link", link, &[linkage.traced_link()]),
    }
}

/// One finite weight ≥ 0 per target, not all 0.
/// The first `reference` targets have no residual (a function's first pair), so their
/// weights do not count towards "not all 0".
fn check_weights(
    weights: Vec<f64>,
    count: usize,
    reference: usize,
) -> Result<Vec<f64>, SynthesisError> {
    if weights.len() != count {
        return Err(SynthesisError::TargetCount {
            what: "weights",
            count: weights.len(),
            reason: format!("one per target: {count}"),
        });
    }
    if let Some((index, &value)) = weights
        .iter()
        .enumerate()
        .find(|(_, w)| !(w.is_finite() && **w >= 0.0))
    {
        return Err(SynthesisError::InvalidConstraint {
            constraint: "weights",
            reason: format!("weight {index} is {value}; every weight is a finite number ≥ 0"),
        });
    }
    if weights.iter().skip(reference).all(|w| *w == 0.0) {
        return Err(SynthesisError::InvalidConstraint {
            constraint: "weights",
            reason: "every weight is 0, so every mechanism would be an answer; give at least \
                     one a positive weight"
                .into(),
        });
    }
    Ok(weights)
}

/// Finite targets, timing lists as long as the targets, a positive angle weight.
fn check_targets(task: &Task) -> Result<(), SynthesisError> {
    let finite = |what: &'static str, values: &mut dyn Iterator<Item = f64>, width: usize| {
        for (k, value) in values.enumerate() {
            if !value.is_finite() {
                return Err(SynthesisError::NonFiniteTarget {
                    what,
                    index: k / width,
                    value,
                });
            }
        }
        Ok(())
    };
    match task {
        Task::Path { targets, .. } => finite("target", &mut targets.iter().flatten().copied(), 2)?,
        Task::Function { pairs, .. } => finite("pair", &mut pairs.iter().flatten().copied(), 2)?,
        Task::Motion {
            poses,
            angle_weight,
            ..
        } => {
            finite("pose", &mut poses.iter().flatten().copied(), 3)?;
            if !(angle_weight.is_finite() && *angle_weight > 0.0) {
                return Err(SynthesisError::InvalidSetting {
                    setting: "angle_weight",
                    value: *angle_weight,
                    reason: "a positive length (m per rad)",
                });
            }
        }
    }
    if let Timing::Absolute(a) | Timing::Relative(a) = task.timing() {
        if a.len() != task.target_count() {
            return Err(SynthesisError::TargetCount {
                what: "drive angles",
                count: a.len(),
                reason: format!("one per target: {}", task.target_count()),
            });
        }
        finite("drive angle", &mut a.iter().copied(), 1)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The function task of a four-bar with the ground 1 m along +x and only its three links
    /// free, with `weights` if given.
    fn function(weights: Option<Vec<f64>>) -> Result<Problem, SynthesisError> {
        let pairs = vec![[0.0, 0.0], [0.2, 0.1], [0.4, 0.3], [0.6, 0.4]];
        let mut b = Problem::builder(
            Linkage::FourBar,
            Task::Function {
                output: "rocker".into(),
                pairs,
            },
        )
        .fix("o2x", 0.0)
        .fix("o2y", 0.0)
        .fix("o4x", 1.0)
        .fix("o4y", 0.0)
        .bound("crank", 0.1, 1.0)
        .bound("coupler", 0.1, 2.0)
        .bound("rocker", 0.1, 2.0)
        .fix("px", 0.0)
        .fix("py", 0.0);
        if let Some(w) = weights {
            b = b.weights(w);
        }
        b.build()
    }

    #[test]
    fn a_weight_scales_its_targets_squared_error_and_the_reference_pairs_has_none() {
        let x = [0.0, 0.0, 1.0, 0.0, 0.3, 1.0, 0.8, 0.0, 0.0, 0.7];
        let plain = function(None).unwrap().residuals(&x).unwrap();
        // Pair 0 is the reference: its weight changes nothing; pair k's weight multiplies
        // residual k − 1 by its square root (√4 = 2, √0.25 = 0.5, both exact).
        let weighted = function(Some(vec![9.0, 4.0, 1.0, 0.25]))
            .unwrap()
            .residuals(&x)
            .unwrap();
        assert_eq!(weighted, [2.0 * plain[0], plain[1], 0.5 * plain[2]]);
    }

    #[test]
    fn weights_and_grashof_classes_that_cannot_hold_are_errors() {
        assert!(matches!(
            function(Some(vec![1.0; 3])),
            Err(SynthesisError::TargetCount {
                what: "weights",
                count: 3,
                ..
            })
        ));
        for bad in [f64::NAN, -1.0, f64::INFINITY] {
            assert!(matches!(
                function(Some(vec![1.0, bad, 1.0, 1.0])),
                Err(SynthesisError::InvalidConstraint {
                    constraint: "weights",
                    ..
                })
            ));
        }
        // Only the reference pair weighed: every mechanism would be an answer.
        assert!(matches!(
            function(Some(vec![1.0, 0.0, 0.0, 0.0])),
            Err(SynthesisError::InvalidConstraint { .. })
        ));
        let slider = Problem::builder(
            Linkage::SliderCrank,
            Task::Path {
                point: "P".into(),
                targets: vec![[0.0, 0.0]],
                timing: Timing::Absolute(vec![0.0]),
            },
        )
        .grashof(GrashofClass::CrankRocker);
        let slider = ["o2x", "o2y", "crank", "rod", "offset", "guide", "px", "py"]
            .iter()
            .fold(slider, |b, n| b.fix(n, 0.5))
            .build();
        assert!(matches!(
            slider,
            Err(SynthesisError::InvalidConstraint {
                constraint: "grashof",
                ..
            })
        ));
        let Task::Function { pairs, .. } = function(None).unwrap().task else {
            unreachable!()
        };
        let rotating = Problem::builder(
            Linkage::FourBar,
            Task::Function {
                output: "rocker".into(),
                pairs,
            },
        )
        .constraints(Constraints {
            crank_rotates: true,
            ..Constraints::default()
        })
        .grashof(GrashofClass::DoubleCrank);
        let rotating = Linkage::FourBar
            .variable_names()
            .iter()
            .fold(rotating, |b, n| b.fix(n, 0.5))
            .build();
        assert!(matches!(
            rotating,
            Err(SynthesisError::InvalidConstraint {
                constraint: "grashof",
                ..
            })
        ));
    }
}
