//! The search: space-filling starts from the bounds alone (a seeded Latin hypercube), ranked
//! by their objective, each polished by Levenberg–Marquardt with the exact Jacobian.

use super::error::{Defect, SynthesisError};
use super::evaluator::{Derivatives, Evaluator};
use super::history::History;
use super::lm::{self, LeastSquares, LocalStop};
use super::problem::Problem;
use super::seeding;
use super::task::Timing;
use super::workers::{InOrder, RunAhead, SAMPLES_AHEAD, Sample, Workers};
use std::time::{Duration, Instant};

/// The most starts a search may sample.
pub const MAX_STARTS: usize = 100_000;
/// The most sampling rounds of a search.
pub const MAX_ROUNDS: usize = 1_000_000;

/// Search settings, with builder methods; [`Synthesis::solve`] runs it.
#[derive(Debug, Clone, PartialEq)]
pub struct Synthesis {
    /// Seed of the starts: the same seed gives the same result.
    pub seed: u64,
    /// Samples of the bounds (Latin hypercube).
    pub starts: usize,
    /// The most local searches (the best-ranked feasible samples first).
    pub local_searches: usize,
    /// Iterations of one local search.
    pub iterations: usize,
    /// Stop as soon as the objective is at most this.
    pub stop_objective: f64,
    /// The most residual evaluations in all (a Jacobian counts as its passes).
    pub max_evaluations: usize,
    /// Wall-clock limit of the whole search.
    pub time_limit: Option<Duration>,
    /// Exact or difference Jacobians.
    pub derivatives: Derivatives,
    /// Rounds of sampling: each round samples `starts` fresh points of the box and polishes
    /// its best `local_searches`; the next round starts while the objective is not reached
    /// and the time and evaluation limits allow (default 1).
    pub rounds: usize,
    /// Give each sample the timing that suits its dimensions before ranking it (the best
    /// `drive0` of relative timing; free drive angles matched in order to the nearest
    /// points of its path; a path task's sample also moved, turned and scaled onto the
    /// targets), see `seeding` (default off: it costs up to a hundred evaluations a sample,
    /// which pays where random samples are poor, as on the literature's problems).
    pub fit_timing: bool,
}

impl Default for Synthesis {
    fn default() -> Self {
        Synthesis {
            seed: 0,
            starts: 1000,
            local_searches: 100,
            iterations: 200,
            stop_objective: 1e-24,
            max_evaluations: 10_000_000,
            time_limit: None,
            derivatives: Derivatives::Exact,
            rounds: 1,
            fit_timing: false,
        }
    }
}

/// How the whole search ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum StopReason {
    /// The objective reached [`Synthesis::stop_objective`].
    Objective,
    /// Every local search asked for was run.
    Starts,
    /// The evaluation limit.
    Evaluations,
    /// The time limit.
    Time,
}

/// What the search found, and what it cost.
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    /// The design variables' names and values (fixed ones included), in the problem's order.
    pub variables: Vec<(String, f64)>,
    /// The sum of squared residuals.
    pub objective: f64,
    /// The residuals (per target: x, y; the function's error; x, y, weighted angle).
    pub residuals: Vec<f64>,
    /// The norm of the objective's half-gradient Jᵀr at the answer.
    pub gradient_norm: f64,
    /// Variables at a bound at the answer (name, and whether the upper one).
    pub at_bounds: Vec<(String, bool)>,
    /// Residual evaluations (a dual Jacobian counts one per free variable, a difference one
    /// two per free variable).
    pub evaluations: usize,
    /// Samples of the bounds.
    pub samples: usize,
    /// Samples that were usable mechanisms.
    pub feasible_samples: usize,
    /// Local searches run.
    pub local_searches: usize,
    /// Local searches that reached [`Synthesis::stop_objective`].
    pub successes: usize,
    /// Samples and trial points rejected, by defect.
    pub defects: Vec<(Defect, usize)>,
    /// How the search ended.
    pub stop: StopReason,
    /// How the best local search ended.
    pub local_stop: LocalStop,
    /// Wall-clock time.
    pub elapsed: Duration,
    /// The answer moved through the targets by core's geometry solver
    /// ([`Problem::certify`]): the largest deviation from the closed forms, or why it
    /// cannot move (never expected: every candidate was checked between the targets).
    pub certificate: Result<super::certify::Certificate, crate::Error>,
    /// The best objective against the evaluations spent, one point per improvement (bounded,
    /// see [`History`]).
    pub history: History,
}

impl Report {
    /// The value of design variable `name`.
    pub fn value(&self, name: &str) -> Option<f64> {
        self.variables.iter().find(|(n, _)| n == name).map(|v| v.1)
    }

    /// The values in the problem's order.
    pub fn x(&self) -> Vec<f64> {
        self.variables.iter().map(|v| v.1).collect()
    }

    /// `None` when the objective reached the level asked for; otherwise why the answer is
    /// not better, in words: the budget ran out, or the best search ended at a stationary
    /// point (a local or the global minimum of targets out of reach) or against bounds.
    pub fn why_not_better(&self, settings: &Synthesis) -> Option<String> {
        if self.objective <= settings.stop_objective {
            return None;
        }
        let budget = match self.stop {
            StopReason::Evaluations => "the evaluation limit was reached; ",
            StopReason::Time => "the time limit was reached; ",
            _ => "",
        };
        let end = match self.local_stop {
            LocalStop::Step | LocalStop::Damping => format!(
                "the best of {} local searches ended where no step lowers the objective \
                 (|Jᵀr| = {:.3e}): a minimum of the squared errors, so the targets are out \
                 of reach of this linkage within the bounds and constraints, or another \
                 minimum is better (more starts may find it)",
                self.local_searches, self.gradient_norm
            ),
            LocalStop::Iterations => format!(
                "the best local search ran out of iterations while still descending \
                 (|Jᵀr| = {:.3e}); allow more iterations",
                self.gradient_norm
            ),
            LocalStop::Budget => "the best local search was stopped by the budget".into(),
            LocalStop::Objective => "it reached the level asked for".into(),
        };
        let bounds = if self.at_bounds.is_empty() {
            String::new()
        } else {
            format!(
                "; at a bound: {}",
                self.at_bounds
                    .iter()
                    .map(|(n, up)| format!("{n} ({})", if *up { "upper" } else { "lower" }))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        };
        Some(format!("{budget}{end}{bounds}"))
    }
}

impl Synthesis {
    /// Default settings with seed `seed`.
    pub fn seeded(seed: u64) -> Self {
        Synthesis {
            seed,
            ..Synthesis::default()
        }
    }

    /// Sets the number of samples and of local searches.
    pub fn with_starts(mut self, samples: usize, local_searches: usize) -> Self {
        self.starts = samples;
        self.local_searches = local_searches;
        self
    }

    /// Sets the derivatives of the local phase.
    pub fn with_derivatives(mut self, derivatives: Derivatives) -> Self {
        self.derivatives = derivatives;
        self
    }

    /// Sets the wall-clock limit.
    pub fn with_time_limit(mut self, limit: Duration) -> Self {
        self.time_limit = Some(limit);
        self
    }

    /// Sets the evaluation limit.
    pub fn with_max_evaluations(mut self, evaluations: usize) -> Self {
        self.max_evaluations = evaluations;
        self
    }

    /// Sets the number of sampling rounds (see [`Synthesis::rounds`]).
    pub fn with_rounds(mut self, rounds: usize) -> Self {
        self.rounds = rounds;
        self
    }

    /// Sets whether samples get the timing that suits them (see [`Synthesis::fit_timing`]).
    pub fn with_fitted_timing(mut self, fit: bool) -> Self {
        self.fit_timing = fit;
        self
    }

    /// Sets the objective at which the search stops.
    pub fn with_stop_objective(mut self, objective: f64) -> Self {
        self.stop_objective = objective;
        self
    }

    /// Runs the search on `problem`, on the calling thread.
    pub fn solve(&self, problem: &Problem) -> Result<Report, SynthesisError> {
        self.solve_on(problem, &InOrder)
    }

    /// Runs the search on `problem` with its samples and local searches on `workers`,
    /// [`Workers::width`] at once: the report is [`Synthesis::solve`]'s, whatever the number
    /// of threads (but for the time taken, and unless a time limit cuts the search short;
    /// see `workers`).
    ///
    /// ```
    /// use mechdiff_core::synthesis::{InOrder, Linkage, Problem, Synthesis, Task, Timing, Workers};
    /// /// Two jobs at once, each on a thread of its own.
    /// struct Two;
    /// impl Workers for Two {
    ///     fn width(&self) -> usize { 2 }
    ///     fn run<T: Send>(&self, count: usize, job: &(dyn Fn(usize) -> T + Sync)) -> Vec<T> {
    ///         std::thread::scope(|s| {
    ///             let handles: Vec<_> = (0..count).map(|j| s.spawn(move || job(j))).collect();
    ///             handles.into_iter().map(|h| h.join().unwrap()).collect()
    ///         })
    ///     }
    /// }
    /// let targets = vec![[0.5, 0.1], [0.2, 0.6], [-0.4, 0.3]];
    /// let task = Task::Path { point: "A".into(), targets, timing: Timing::Free };
    /// let problem = Problem::builder(Linkage::FourBar, task)
    ///     .fix("o2x", 0.0).fix("o2y", 0.0).fix("o4x", 1.0).fix("o4y", 0.0)
    ///     .bound("crank", 0.1, 0.9).fix("coupler", 1.0).fix("rocker", 1.0)
    ///     .fix("px", 0.0).fix("py", 0.0)
    ///     .build()
    ///     .unwrap();
    /// let settings = Synthesis::seeded(3).with_starts(40, 6);
    /// let mut alone = settings.solve_on(&problem, &InOrder).unwrap();
    /// let two = settings.solve_on(&problem, &Two).unwrap();
    /// alone.elapsed = two.elapsed;
    /// assert_eq!(alone, two);
    /// ```
    pub fn solve_on<W: Workers>(
        &self,
        problem: &Problem,
        workers: &W,
    ) -> Result<Report, SynthesisError> {
        self.validate()?;
        let started = Instant::now();
        let deadline = self.time_limit.map(|t| started + t);
        let (lower, upper) = problem.bounds();
        let free: Vec<usize> = (0..lower.len()).filter(|&i| lower[i] < upper[i]).collect();
        let mut defects = vec![0usize; Defect::ALL.len()];
        let count = |d: Defect, defects: &mut Vec<usize>| {
            defects[Defect::ALL.iter().position(|&k| k == d).unwrap_or(0)] += 1;
        };
        let tally = |defects: &[usize]| {
            Defect::ALL
                .iter()
                .zip(defects)
                .filter(|(_, n)| **n > 0)
                .map(|(d, n)| (*d, *n))
                .collect::<Vec<_>>()
        };
        let mut f = Evaluator::new(
            problem,
            &free,
            self.derivatives,
            self.max_evaluations,
            deadline,
        );
        let (mut samples, mut feasible_samples) = (0, 0);
        let fit_cost = seeding::fit_cost(problem);
        // The best sample stands as the answer if the budget allows no local search.
        let mut fallback: Option<lm::Local> = None;
        let mut best: Option<lm::Local> = None;
        let (mut searches, mut successes) = (0, 0);
        let mut stop = StopReason::Starts;
        'rounds: for round in 0..self.rounds {
            let mut ranked = Vec::new();
            let points = self.latin_hypercube(problem, &free, round);
            let width = workers.width().max(1);
            let batch = if width > 1 {
                SAMPLES_AHEAD * width
            } else {
                points.len()
            };
            // Batches of samples evaluated ahead at once, then taken in order (`workers`).
            'samples: for batch in points.chunks(batch.max(1)) {
                let mut ahead = if width > 1 {
                    // Fitted if the budget allows a fit now (it allows none later if not).
                    let fit = self.fit_timing && f.evaluations + fit_cost < f.max_evaluations;
                    let take = |j: usize| Sample::take(problem, batch[j].clone(), fit);
                    workers.run(batch.len(), &take)
                } else {
                    Vec::new()
                }
                .into_iter();
                for x in batch {
                    // The evaluation limit ends the sampling once a usable sample is in hand.
                    if (round > 0 || !ranked.is_empty()) && f.exhausted() {
                        break 'samples;
                    }
                    // Fitted only while the evaluation limit allows a whole fit.
                    let fit = self.fit_timing && f.evaluations + fit_cost < f.max_evaluations;
                    let sample = match ahead.next() {
                        Some(sample) if sample.fitted == fit => sample,
                        _ => Sample::take(problem, x.clone(), fit),
                    };
                    f.evaluations += sample.fit_evaluations + 1;
                    samples += 1;
                    match sample.objective {
                        Ok(value) if value.is_finite() => {
                            f.history.record(f.evaluations, value);
                            ranked.push((value, sample.x));
                        }
                        Ok(_) => count(Defect::NoAssemblyAtTarget, &mut defects),
                        Err(d) => count(d, &mut defects),
                    }
                    if deadline.is_some_and(|d| Instant::now() >= d) {
                        break 'samples;
                    }
                }
            }
            if round == 0 && ranked.is_empty() {
                if deadline.is_some_and(|d| Instant::now() >= d) {
                    return Err(SynthesisError::TimeLimit {
                        samples,
                        limit: self.time_limit.unwrap_or_default(),
                    });
                }
                return Err(SynthesisError::NoAssembly {
                    samples,
                    defects: tally(&defects),
                });
            }
            ranked.sort_by(|a, b| a.0.total_cmp(&b.0));
            feasible_samples += ranked.len();
            if let Some((value, x)) = ranked.first()
                && fallback.as_ref().is_none_or(|b| *value < b.objective)
            {
                fallback = Some(lm::Local {
                    x: x.clone(),
                    objective: *value,
                    gradient_norm: f64::NAN,
                    stop: LocalStop::Budget,
                });
            }
            let starts: Vec<Vec<f64>> = (ranked.into_iter().take(self.local_searches))
                .map(|(_, x0)| x0)
                .collect();
            // Batches of local searches run ahead at once, then taken in order (`workers`).
            for batch in starts.chunks(workers.width().max(1)) {
                let mut ahead = if batch.len() > 1 {
                    let from = f.evaluations;
                    let run = |j: usize| {
                        RunAhead::run(problem, &free, self, deadline, from, batch[j].clone())
                    };
                    workers.run(batch.len(), &run)
                } else {
                    Vec::new()
                }
                .into_iter();
                for x0 in batch {
                    if f.exhausted() {
                        stop = if deadline.is_some_and(|d| Instant::now() >= d) {
                            StopReason::Time
                        } else {
                            StopReason::Evaluations
                        };
                        break 'rounds;
                    }
                    let local = match ahead.next() {
                        Some(run) if run.holds_at(&f) => run.take_into(&mut f),
                        _ => lm::minimize(
                            &mut f,
                            x0.clone(),
                            &free,
                            lower,
                            upper,
                            self.stop_objective,
                            self.iterations,
                            deadline,
                        ),
                    };
                    searches += 1;
                    successes += usize::from(local.objective <= self.stop_objective);
                    if best.as_ref().is_none_or(|b| local.objective < b.objective) {
                        best = Some(local);
                    }
                    if best
                        .as_ref()
                        .is_some_and(|b| b.objective <= self.stop_objective)
                    {
                        stop = StopReason::Objective;
                        break 'rounds;
                    }
                }
            }
            if f.exhausted() {
                break;
            }
        }
        if stop != StopReason::Objective {
            if deadline.is_some_and(|d| Instant::now() >= d) {
                stop = StopReason::Time;
            } else if f.evaluations >= self.max_evaluations {
                stop = StopReason::Evaluations;
            }
        }
        for (d, n) in defects.iter_mut().zip(&f.rejected) {
            *d += n;
        }
        // Round 0 returned an error without a usable sample, so there is one.
        let Some(best) = best.or(fallback) else {
            return Err(SynthesisError::NoAssembly {
                samples,
                defects: tally(&defects),
            });
        };
        let residuals = problem.residuals(&best.x).unwrap_or_default();
        let names = problem.variable_names();
        let at_bounds = at_bounds(problem, &free, &best.x);
        Ok(Report {
            variables: names.iter().cloned().zip(best.x.iter().copied()).collect(),
            objective: best.objective,
            residuals,
            gradient_norm: best.gradient_norm,
            at_bounds,
            evaluations: f.evaluations,
            samples,
            feasible_samples,
            local_searches: searches,
            successes,
            defects: tally(&defects),
            stop,
            local_stop: best.stop,
            elapsed: started.elapsed(),
            certificate: problem.certify(&best.x),
            history: f.history,
        })
    }

    pub(super) fn validate(&self) -> Result<(), SynthesisError> {
        let bad = |setting, value: f64, reason| {
            Err(SynthesisError::InvalidSetting {
                setting,
                value,
                reason,
            })
        };
        if self.starts == 0 || self.starts > MAX_STARTS {
            return bad(
                "starts",
                self.starts as f64,
                "between 1 and 100 000 samples",
            );
        }
        if self.local_searches == 0 || self.iterations == 0 || self.iterations > 100_000 {
            return bad(
                "local_searches / iterations",
                self.iterations.min(self.local_searches) as f64,
                "at least one local search of 1 to 100 000 iterations",
            );
        }
        if self.rounds == 0 || self.rounds > MAX_ROUNDS {
            return bad(
                "rounds",
                self.rounds as f64,
                "between 1 and 1 000 000 rounds of sampling",
            );
        }
        if !(self.stop_objective >= 0.0 && self.stop_objective.is_finite()) {
            return bad(
                "stop_objective",
                self.stop_objective,
                "a finite objective ≥ 0",
            );
        }
        Ok(())
    }

    /// `starts` points of the box, one in each of `starts` slices of every free variable
    /// (slices matched at random, the point uniform in its cell); fixed variables at their
    /// value; free drive angles sorted (the order the targets are met in) and brought within
    /// one turn of the first.
    /// Round `round` draws from its own stream: round 0 from `seed` itself (the sampling
    /// of a single-round search), round r from `seed` mixed with r.
    pub(super) fn latin_hypercube(
        &self,
        problem: &Problem,
        free: &[usize],
        round: usize,
    ) -> Vec<Vec<f64>> {
        let (lower, upper) = problem.bounds();
        let stream = (round as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        let mut rng = fastrand::Rng::with_seed(self.seed ^ stream);
        let n = self.starts;
        let mut points = vec![lower.to_vec(); n];
        for &i in free {
            let mut slices: Vec<usize> = (0..n).collect();
            rng.shuffle(&mut slices);
            for (point, slice) in points.iter_mut().zip(slices) {
                let t = (slice as f64 + rng.f64()) / n as f64;
                point[i] = lower[i] + (upper[i] - lower[i]) * t;
            }
        }
        if matches!(problem.task.timing(), Timing::Free) {
            let first = problem.variable_names().len() - problem.task.target_count();
            for point in &mut points {
                let drive = &mut point[first..];
                drive.sort_by(f64::total_cmp);
                // Within one turn: offsets from the first angle shrunk towards it (inside
                // the bounds still, as they only move towards a value within them).
                let span = drive[drive.len() - 1] - drive[0];
                let most = 0.999 * std::f64::consts::TAU;
                if span >= most {
                    let start = drive[0];
                    for phi in drive.iter_mut() {
                        *phi = start + (*phi - start) * (most / span);
                    }
                }
            }
        }
        points
    }
}

/// The free variables of `x` at a bound (name, and whether the upper one).
pub(super) fn at_bounds(problem: &Problem, free: &[usize], x: &[f64]) -> Vec<(String, bool)> {
    let (lower, upper) = problem.bounds();
    let names = problem.variable_names();
    free.iter()
        .filter_map(|&i| {
            let touch = |b: f64| (x[i] - b).abs() <= 1e-12 * b.abs().max(1.0);
            (touch(lower[i]) || touch(upper[i])).then(|| (names[i].clone(), touch(upper[i])))
        })
        .collect()
}
