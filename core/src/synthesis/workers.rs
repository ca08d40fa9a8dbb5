//! Samples and local searches run ahead on several threads, with the answer of the search
//! run in order.
//!
//! A round's samples of the bounds are ranked, then its local searches are polished one
//! after another. The samples are independent (each one's fit and objective are a function
//! of it alone): they are evaluated in batches at once and taken in order, the budget and
//! the clock applied as the search in order applies them (a sample whose turn comes when
//! the budget no longer allows a fit is evaluated again, unfitted).
//!
//! The local searches are polished one after another: each may stop the search
//! (the objective reached) and each spends the evaluation budget the next one starts from.
//! [`Synthesis::solve_on`] runs a batch of them at once, each *ahead* of its turn from the
//! evaluation count the batch starts at, and then takes them in order as the search in order
//! would have run them. A search run ahead did exactly what it would have done in its turn
//! when it ended by itself (not by the budget) and every evaluation count it will be given
//! stays under the limit: a local search depends on the budget only through "is it spent?",
//! which then answers "no" at every count in both runs. Otherwise it is run again in its
//! turn. Its improvements of the objective are recorded in its turn at the counts they would
//! have had, so the convergence history is the one of the search in order too. Searches
//! after the one that reaches the objective are dropped, as the search in order never runs
//! them. So the report is the same for any number of threads (only the time differs, and a
//! time limit makes any search depend on the clock).
//!
//! [`Synthesis::solve_on`]: super::Synthesis::solve_on

use std::time::Instant;

use super::error::Defect;
use super::evaluator::Evaluator;
use super::history::Improvement;
use super::lm::{self, LocalStop};
use super::problem::Problem;
use super::search::Synthesis;
use super::seeding;

/// The threads a search may evaluate its samples and run its local searches on: how many
/// jobs run at once, and how a batch of independent jobs is run (a thread pool, or
/// [`InOrder`]).
pub trait Workers {
    /// How many jobs are worth running at once (1: nothing is run ahead).
    fn width(&self) -> usize;

    /// Runs `job(0)`, …, `job(count − 1)`, in any order or at once, and returns their
    /// results in order of the index.
    fn run<T: Send>(&self, count: usize, job: &(dyn Fn(usize) -> T + Sync)) -> Vec<T>;
}

/// The calling thread, one job after another ([`Synthesis::solve`](super::Synthesis::solve)).
#[derive(Debug, Clone, Copy, Default)]
pub struct InOrder;

impl Workers for InOrder {
    fn width(&self) -> usize {
        1
    }

    fn run<T: Send>(&self, count: usize, job: &(dyn Fn(usize) -> T + Sync)) -> Vec<T> {
        (0..count).map(job).collect()
    }
}

/// Samples of the bounds evaluated ahead at once, per thread: enough to keep the threads
/// busy, few enough that little is evaluated in vain when the budget ends the sampling.
pub(super) const SAMPLES_AHEAD: usize = 16;

/// A sample of the bounds as the search ranks it.
pub(super) struct Sample {
    /// The point, with its timing fitted if `fitted`.
    pub x: Vec<f64>,
    /// Whether its timing was fitted.
    pub fitted: bool,
    /// The residual evaluations the fit cost.
    pub fit_evaluations: usize,
    /// Its objective, or why it is no usable mechanism.
    pub objective: Result<f64, Defect>,
}

impl Sample {
    /// The point `x` with its timing fitted (if `fit`, see `seeding`), and its objective:
    /// a function of `x` alone, so a sample taken ahead is the sample taken in its turn
    /// when its turn fits it too.
    pub(super) fn take(problem: &Problem, mut x: Vec<f64>, fit: bool) -> Sample {
        let fit_evaluations = if fit {
            seeding::fit_timing(problem, &mut x)
        } else {
            0
        };
        let objective = problem.objective(&x);
        Sample {
            x,
            fitted: fit,
            fit_evaluations,
            objective,
        }
    }
}

/// A local search run ahead of its turn from the evaluation count `from`.
pub(super) struct RunAhead {
    /// What it found.
    local: lm::Local,
    /// The evaluation count it started from.
    from: usize,
    /// The evaluation count it ended at.
    to: usize,
    /// Candidates it rejected, by defect (as [`Evaluator::rejected`]).
    rejected: Vec<usize>,
    /// Its own improvements of the objective, at the counts of the run ahead (at most one
    /// per evaluation of one local search).
    improvements: Vec<Improvement>,
}

impl RunAhead {
    /// Polishes `x0` as the search's local phase does, from the evaluation count `from`.
    pub(super) fn run(
        problem: &Problem,
        free: &[usize],
        search: &Synthesis,
        deadline: Option<Instant>,
        from: usize,
        x0: Vec<f64>,
    ) -> RunAhead {
        let (lower, upper) = problem.bounds();
        let mut f = Evaluator::new(
            problem,
            free,
            search.derivatives,
            search.max_evaluations,
            deadline,
        );
        f.evaluations = from;
        f.ahead = Some(Vec::new());
        let local = lm::minimize(
            &mut f,
            x0,
            free,
            lower,
            upper,
            search.stop_objective,
            search.iterations,
            deadline,
        );
        RunAhead {
            local,
            from,
            to: f.evaluations,
            rejected: f.rejected,
            improvements: f.ahead.unwrap_or_default(),
        }
    }

    /// Whether the search, run in its turn from `f`'s evaluation count, does what it did
    /// ahead (see the module doc).
    pub(super) fn holds_at(&self, f: &Evaluator<'_>) -> bool {
        self.local.stop != LocalStop::Budget
            && f.evaluations + (self.to - self.from) < f.max_evaluations
    }

    /// Takes the search into `f` as if it had run there: its evaluations, rejected
    /// candidates and improvements (those that improve on `f`'s history).
    pub(super) fn take_into(self, f: &mut Evaluator<'_>) -> lm::Local {
        let start = f.evaluations;
        for i in self.improvements {
            f.history
                .record(start + (i.evaluations - self.from), i.objective);
        }
        f.evaluations = start + (self.to - self.from);
        for (total, n) in f.rejected.iter_mut().zip(&self.rejected) {
            *total += n;
        }
        self.local
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synthesis::{Linkage, Report, StopReason, Task, Timing};

    /// `width` jobs at once, each on a thread of its own, started last first (a job's place
    /// in the results must come from its index, not from when it ran).
    struct Threads(usize);

    impl Workers for Threads {
        fn width(&self) -> usize {
            self.0
        }

        fn run<T: Send>(&self, count: usize, job: &(dyn Fn(usize) -> T + Sync)) -> Vec<T> {
            std::thread::scope(|s| {
                let mut handles: Vec<_> =
                    (0..count).rev().map(|j| s.spawn(move || job(j))).collect();
                handles.reverse();
                handles.into_iter().map(|h| h.join().unwrap()).collect()
            })
        }
    }

    /// The four-bar O2 = (0, 0), O4 = (1.2, 0.1), crank 0.4, coupler 1.1, rocker 0.9 with
    /// coupler point (0.5, 0.35): its point P at ten crank angles 0.5 rad apart, every
    /// second one moved by `offset` (m) in x (out of reach of a four-bar unless 0), with the
    /// drive angles known up to a common start.
    fn problem(offset: f64) -> Problem {
        let known = [0.0, 0.0, 1.2, 0.1, 0.4, 1.1, 0.9, 0.5, 0.35];
        let rel: Vec<f64> = (0..10).map(|k| 0.5 * f64::from(k)).collect();
        let targets = rel
            .iter()
            .enumerate()
            .map(|(k, r)| {
                let p = Linkage::FourBar
                    .pose(&known, 0.3 + r, &[1.0])
                    .unwrap()
                    .points[2];
                [p[0] + offset * (k % 2) as f64, p[1]]
            })
            .collect();
        let task = Task::Path {
            point: "P".into(),
            targets,
            timing: Timing::Relative(rel),
        };
        Problem::builder(Linkage::FourBar, task)
            .bound("o2x", -1.0, 1.0)
            .bound("o2y", -1.0, 1.0)
            .bound("o4x", 0.0, 2.0)
            .bound("o4y", -1.0, 1.0)
            .bound("crank", 0.1, 1.0)
            .bound("coupler", 0.1, 2.0)
            .bound("rocker", 0.1, 2.0)
            .bound("px", -1.5, 1.5)
            .bound("py", -1.5, 1.5)
            .build()
            .unwrap()
    }

    /// The report of `settings` on `problem` in order, and the same on 2 and 3 threads: equal
    /// in every field but the time taken, every number to the bit (compared as printed by
    /// `Debug`, which prints the shortest digits that read back to the same bits, so that a
    /// NaN, as the gradient norm of an answer no local search polished, equals itself).
    fn same_on_threads(problem: &Problem, settings: &Synthesis) -> Report {
        let alone = settings.solve(problem).unwrap();
        for width in [2, 3] {
            let mut threaded = settings.solve_on(problem, &Threads(width)).unwrap();
            threaded.elapsed = alone.elapsed;
            assert_eq!(
                format!("{threaded:?}"),
                format!("{alone:?}"),
                "{width} threads"
            );
        }
        alone
    }

    #[test]
    fn every_sample_and_local_search_run_on_threads_gives_the_report_of_the_search_in_order() {
        // Targets out of reach (every second moved 0.05 m): every local search of both rounds
        // runs; with the timing of each sample fitted or not.
        for fit in [false, true] {
            let settings = Synthesis::seeded(2)
                .with_starts(40, 5)
                .with_rounds(2)
                .with_fitted_timing(fit);
            let report = same_on_threads(&problem(0.05), &settings);
            assert_eq!(
                (report.local_searches, report.stop),
                (10, StopReason::Starts)
            );
            assert!(report.history.improvements().len() > 1);
        }
    }

    #[test]
    fn a_budget_that_ends_inside_a_batch_gives_the_report_of_the_search_in_order() {
        // The evaluation limit falls within the sampling (it ends once a usable sample is
        // in hand; fits stop where the limit no longer allows a whole one) or within the
        // local searches: what was run ahead beyond it is run again in its turn, cut by the
        // budget as in order.
        let out_of_reach = problem(0.05);
        for fit in [false, true] {
            let full = Synthesis::seeded(2)
                .with_starts(40, 5)
                .with_fitted_timing(fit);
            let spent = full.solve(&out_of_reach).unwrap().evaluations;
            for limit in [10, spent / 10, spent / 3, spent / 2, spent - 1] {
                let limited = full.clone().with_max_evaluations(limit);
                let report = same_on_threads(&out_of_reach, &limited);
                assert_eq!(report.stop, StopReason::Evaluations, "limit {limit}");
            }
        }
    }

    #[test]
    fn a_local_search_that_reaches_the_objective_ends_the_search_on_threads_too() {
        // The targets of the known four-bar: a search reaches the objective, and the
        // searches after it, run ahead, are dropped. With these seeds the first search
        // succeeds, then the second (the cases this test is for: a search run ahead taken,
        // and one dropped, in the same batch).
        for (seed, starts, searches) in [(1, 200, 1), (0, 20, 2)] {
            let settings = Synthesis::seeded(seed).with_starts(starts, 10);
            let report = same_on_threads(&problem(0.0), &settings);
            assert_eq!(report.stop, StopReason::Objective);
            assert_eq!(report.local_searches, searches, "seed {seed}");
        }
    }
}
