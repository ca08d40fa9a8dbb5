//! Differential evolution: the derivative-free baseline exact derivatives are compared with
//! (Storn & Price's DE/rand/1/bin, the mutation factor dithered in [0.5, 1) per trial,
//! crossover 0.9), on the same problems, defect checks, budgets and starts as the search.
//!
//! The population is the first `min(starts, 15 × free variables)` points of the search's
//! Latin hypercube (with the same timing fit when [`Synthesis::fit_timing`] is on); a
//! mutant coordinate beyond a bound is put halfway between its parent's and the bound; a
//! candidate that is not a usable mechanism (any [`super::Defect`]) loses every
//! comparison. It stops at the objective, the time or the evaluation limit.

use super::error::{Defect, SynthesisError};
use super::evaluator::Evaluator;
use super::lm::{LeastSquares, Local, LocalStop};
use super::problem::Problem;
use super::search::{Report, StopReason, Synthesis, at_bounds};
use super::seeding;
use std::time::Instant;

/// Crossover probability.
const CROSSOVER: f64 = 0.9;
/// Population size per free variable.
const PER_VARIABLE: usize = 15;

impl Synthesis {
    /// Minimises the problem's objective by differential evolution alone (no derivatives,
    /// no local phase): the baseline of [`Synthesis::solve`]. Uses `seed`, `starts` (the
    /// population is at most 15 per free variable), `fit_timing`, `stop_objective`,
    /// `max_evaluations` and `time_limit`; the report's `local_searches` is 0 and its
    /// `gradient_norm` NaN.
    pub fn evolve(&self, problem: &Problem) -> Result<Report, SynthesisError> {
        self.validate()?;
        let started = Instant::now();
        let deadline = self.time_limit.map(|t| started + t);
        let (lower, upper) = problem.bounds();
        let free: Vec<usize> = (0..lower.len()).filter(|&i| lower[i] < upper[i]).collect();
        let mut f = Evaluator::new(
            problem,
            &free,
            self.derivatives,
            self.max_evaluations,
            deadline,
        );
        let size = self.starts.min(PER_VARIABLE * free.len().max(1)).max(4);
        let mut population: Vec<(f64, Vec<f64>)> = Vec::with_capacity(size);
        for mut x in self
            .latin_hypercube(problem, &free, 0)
            .into_iter()
            .take(size)
        {
            if self.fit_timing {
                f.evaluations += seeding::fit_timing(problem, &mut x);
            }
            let value = f
                .feasible(&x)
                .map_or(f64::INFINITY, |r| r.iter().map(|v| v * v).sum());
            population.push((value, x));
        }
        let samples = population.len();
        let feasible_samples = population.iter().filter(|p| p.0.is_finite()).count();
        if feasible_samples == 0 {
            return Err(SynthesisError::NoAssembly {
                samples,
                defects: tally(&f.rejected),
            });
        }
        let mut rng = fastrand::Rng::with_seed(self.seed ^ 0xD1FF_E4E0_1F0E_5EED);
        let best_of = |p: &[(f64, Vec<f64>)]| {
            p.iter()
                .enumerate()
                .min_by(|a, b| a.1.0.total_cmp(&b.1.0))
                .map_or(0, |(i, _)| i)
        };
        let mut stop = StopReason::Objective;
        'generations: while population[best_of(&population)].0 > self.stop_objective {
            for i in 0..size {
                if f.exhausted() {
                    stop = if deadline.is_some_and(|d| Instant::now() >= d) {
                        StopReason::Time
                    } else {
                        StopReason::Evaluations
                    };
                    break 'generations;
                }
                let pick = |rng: &mut fastrand::Rng, not: &[usize]| loop {
                    let k = rng.usize(..size);
                    if !not.contains(&k) {
                        return k;
                    }
                };
                let r1 = pick(&mut rng, &[i]);
                let r2 = pick(&mut rng, &[i, r1]);
                let r3 = pick(&mut rng, &[i, r1, r2]);
                let scale = 0.5 + 0.5 * rng.f64();
                let forced = rng.usize(..free.len());
                let mut trial = population[i].1.clone();
                for (k, &j) in free.iter().enumerate() {
                    if k == forced || rng.f64() < CROSSOVER {
                        let v = population[r1].1[j]
                            + scale * (population[r2].1[j] - population[r3].1[j]);
                        let parent = population[i].1[j];
                        trial[j] = if v < lower[j] {
                            0.5 * (parent + lower[j])
                        } else if v > upper[j] {
                            0.5 * (parent + upper[j])
                        } else {
                            v
                        };
                    }
                }
                let value = f
                    .feasible(&trial)
                    .map_or(f64::INFINITY, |r| r.iter().map(|v| v * v).sum());
                if value <= population[i].0 {
                    population[i] = (value, trial);
                    if value <= self.stop_objective {
                        break 'generations;
                    }
                }
            }
        }
        let best = population.swap_remove(best_of(&population));
        let reached = best.0 <= self.stop_objective;
        if reached {
            stop = StopReason::Objective;
        }
        let local = Local {
            x: best.1,
            objective: best.0,
            gradient_norm: f64::NAN,
            stop: if reached {
                LocalStop::Objective
            } else {
                LocalStop::Budget
            },
        };
        let names = problem.variable_names();
        Ok(Report {
            variables: names.iter().cloned().zip(local.x.iter().copied()).collect(),
            objective: local.objective,
            residuals: problem.residuals(&local.x).unwrap_or_default(),
            gradient_norm: local.gradient_norm,
            at_bounds: at_bounds(problem, &free, &local.x),
            evaluations: f.evaluations,
            samples,
            feasible_samples,
            local_searches: 0,
            successes: usize::from(reached),
            defects: tally(&f.rejected),
            stop,
            local_stop: local.stop,
            elapsed: started.elapsed(),
            certificate: problem.certify(&local.x),
            history: f.history,
        })
    }
}

/// The defects counted, as the report lists them.
fn tally(counts: &[usize]) -> Vec<(Defect, usize)> {
    Defect::ALL
        .iter()
        .zip(counts)
        .filter(|(_, n)| **n > 0)
        .map(|(d, n)| (*d, *n))
        .collect()
}
