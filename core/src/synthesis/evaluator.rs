//! The problem as the search's phases see it: residuals and Jacobians (exact or by
//! central differences) of the free variables, counted against the search's budget, and
//! the candidates rejected by defect.

use std::time::Instant;

use nalgebra::{DMatrix, DVector};

use super::error::Defect;
use super::history::{History, Improvement};
use super::lm::LeastSquares;
use super::problem::Problem;

/// How the local phase gets its Jacobian.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Derivatives {
    /// Exact: one evaluation of the residuals in `Dual64` numbers per free variable.
    Exact,
    /// Central differences, step h = ε^(1/3)·max(|x|, 1) (one-sided where a side is
    /// infeasible): two evaluations per free variable; the baseline exact derivatives are
    /// compared with.
    CentralDifferences,
}

/// The problem's residuals and Jacobians for the local phase, counting evaluations and
/// rejected trial points.
pub(super) struct Evaluator<'p> {
    pub(super) problem: &'p Problem,
    pub(super) free: &'p [usize],
    pub(super) derivatives: Derivatives,
    pub(super) evaluations: usize,
    pub(super) max_evaluations: usize,
    pub(super) deadline: Option<Instant>,
    pub(super) rejected: Vec<usize>,
    pub(super) history: History,
    /// A local search run ahead of its turn (`workers`) records its own improvements here,
    /// at its own counts, instead of in `history`.
    pub(super) ahead: Option<Vec<Improvement>>,
}

impl<'p> Evaluator<'p> {
    /// An evaluator of `problem` over its `free` variables within the search's limits: no
    /// evaluation yet, no candidate rejected.
    pub(super) fn new(
        problem: &'p Problem,
        free: &'p [usize],
        derivatives: Derivatives,
        max_evaluations: usize,
        deadline: Option<Instant>,
    ) -> Self {
        Evaluator {
            problem,
            free,
            derivatives,
            evaluations: 0,
            max_evaluations,
            deadline,
            rejected: vec![0; Defect::ALL.len()],
            history: History::default(),
            ahead: None,
        }
    }

    pub(super) fn feasible(&mut self, x: &[f64]) -> Option<Vec<f64>> {
        self.evaluations += 1;
        match self
            .problem
            .check(x)
            .and_then(|()| self.problem.residuals(x))
        {
            Ok(r) if r.iter().all(|v| v.is_finite()) => {
                let objective: f64 = r.iter().map(|v| v * v).sum();
                match &mut self.ahead {
                    None => self.history.record(self.evaluations, objective),
                    Some(own) => {
                        if objective.is_finite()
                            && own.last().is_none_or(|best| objective < best.objective)
                        {
                            own.push(Improvement {
                                evaluations: self.evaluations,
                                objective,
                            });
                        }
                    }
                }
                Some(r)
            }
            Ok(_) => None,
            Err(d) => {
                self.rejected[Defect::ALL.iter().position(|&k| k == d).unwrap_or(0)] += 1;
                None
            }
        }
    }
}

impl LeastSquares for Evaluator<'_> {
    fn residuals(&mut self, x: &[f64]) -> Option<Vec<f64>> {
        self.feasible(x)
    }

    fn jacobian(&mut self, x: &[f64]) -> Option<DMatrix<f64>> {
        let rows = self.problem.task.residual_count();
        let mut jac = DMatrix::zeros(rows, self.free.len());
        match self.derivatives {
            Derivatives::Exact => {
                self.evaluations += self.free.len();
                jac = self.problem.jacobian(x, self.free).ok()?;
            }
            Derivatives::CentralDifferences => {
                let (lower, upper) = self.problem.bounds();
                for (k, &i) in self.free.iter().enumerate() {
                    let h = f64::EPSILON.cbrt() * x[i].abs().max(1.0);
                    let side = |s: f64, me: &mut Self| {
                        let mut xs = x.to_vec();
                        xs[i] = (x[i] + s * h).clamp(lower[i], upper[i]);
                        let step = xs[i] - x[i];
                        me.evaluations += 1;
                        let r = me.problem.residuals(&xs).ok()?;
                        (step != 0.0).then_some((r, step))
                    };
                    let plus = side(1.0, self);
                    let minus = side(-1.0, self);
                    let r0 = || self.problem.residuals(x).ok();
                    let column: Vec<f64> = match (plus, minus) {
                        (Some((rp, hp)), Some((rm, hm))) => rp
                            .iter()
                            .zip(&rm)
                            .map(|(p, m)| (p - m) / (hp - hm))
                            .collect(),
                        (Some((rp, hp)), None) => {
                            rp.iter().zip(r0()?).map(|(p, c)| (p - c) / hp).collect()
                        }
                        (None, Some((rm, hm))) => {
                            rm.iter().zip(r0()?).map(|(m, c)| (m - c) / hm).collect()
                        }
                        (None, None) => return None,
                    };
                    for (row, v) in column.iter().enumerate() {
                        jac[(row, k)] = *v;
                    }
                }
            }
        }
        Some(jac)
    }

    fn inequalities(&self, x: &[f64]) -> Vec<(f64, DVector<f64>)> {
        self.problem
            .inequalities(x)
            .into_iter()
            .map(|c| {
                let gradient = self.free.iter().map(|&i| c.gradient[i]);
                (c.value, DVector::from_iterator(self.free.len(), gradient))
            })
            .collect()
    }

    fn exhausted(&self) -> bool {
        self.evaluations >= self.max_evaluations
            || self.deadline.is_some_and(|d| Instant::now() >= d)
    }
}
