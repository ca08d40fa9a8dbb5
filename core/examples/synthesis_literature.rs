//! Classic synthesis problems from the literature (`core/tests/data/synthesis/literature.rs`:
//! Kunjur & Krishnamurty's five timed points and eighteen-point closed curve, Cabrera et
//! al.'s six-point straight line without timing, Freudenstein's log10 function generator)
//! solved over seeds 0–9, each run limited to 10 s. Prints, per problem: the published
//! best, mechdiff's best and median objective, the runs reaching the published best
//! (successes of 10; an answer counts only if core's geometry solver moves it through every
//! target and its ground link is within the paper's bound), the median evaluations and the
//! median time per run (wall clock, one thread).
//!
//! With `--compare [seconds]` it runs the same problems with the exact Jacobian, with
//! central differences and by differential evolution alone (no derivatives), each run
//! limited to `seconds` (default 3), and prints successes, median objective, evaluations
//! and time per method.
//!
//! `--only PREFIX` runs only the problems whose name starts with PREFIX (e.g. `--only 6-point`);
//! `--seeds N` runs seeds 0..N (default 10); `--each` prints every run on standard error.
//!
//! `cargo run --release -p mechdiff-core --features synthesis --example synthesis_literature [-- --compare 3] [--only 6-point] [--seeds 10]`

#[path = "../tests/data/synthesis/literature.rs"]
mod literature;

use literature::Literature;
use mechdiff_core::synthesis::{Derivatives, MAX_ROUNDS, Report, Synthesis, SynthesisError};
use std::time::Duration;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The methods compared.
#[derive(Clone, Copy)]
enum Method {
    Exact,
    Differences,
    Evolution,
}

fn run(
    lit: &Literature,
    seed: u64,
    method: Method,
    limit: Duration,
) -> Result<Report, SynthesisError> {
    let settings = Synthesis::seeded(seed)
        .with_fitted_timing(true)
        .with_rounds(MAX_ROUNDS)
        .with_stop_objective(lit.success_level)
        .with_time_limit(limit);
    match method {
        Method::Exact => settings.solve(&lit.problem),
        Method::Differences => settings
            .with_derivatives(Derivatives::CentralDifferences)
            .solve(&lit.problem),
        Method::Evolution => settings.evolve(&lit.problem),
    }
}

/// Whether a run reached the published best with an admissible, defect-free mechanism.
fn success(lit: &Literature, report: &Report) -> bool {
    let x = report.x();
    let ground = (x[2] - x[0]).hypot(x[3] - x[1]);
    report.objective <= lit.success_level
        && lit.max_ground.is_none_or(|g| ground <= g)
        && report
            .certificate
            .as_ref()
            .is_ok_and(|c| c.deviation <= 1e-9)
}

/// One problem's runs over the selection's seeds by one method.
struct Tally {
    objectives: Vec<f64>,
    evaluations: Vec<f64>,
    times: Vec<f64>,
    successes: usize,
}

impl Tally {
    /// Runs `lit` for each seed (a line per run on stderr with `--each`).
    fn over_seeds(
        selection: &Selection,
        lit: &Literature,
        method: Method,
        limit: Duration,
    ) -> Result<Tally, SynthesisError> {
        let mut t = Tally {
            objectives: Vec::new(),
            evaluations: Vec::new(),
            times: Vec::new(),
            successes: 0,
        };
        for seed in 0..selection.seeds {
            let report = run(lit, seed, method, limit)?;
            if selection.each {
                each(lit, seed, &report);
            }
            t.successes += usize::from(success(lit, &report));
            t.objectives.push(report.objective);
            t.evaluations.push(report.evaluations as f64);
            t.times.push(report.elapsed.as_secs_f64());
        }
        Ok(t)
    }

    /// The least objective of the runs.
    fn best(&self) -> f64 {
        self.objectives
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min)
    }
}

/// One run's line (with `--each`, on standard error).
fn each(lit: &Literature, seed: u64, report: &Report) {
    eprintln!(
        "{} seed {seed}: {:.3e}{} after {} evaluations, {} local searches ({} samples), {:.2} s",
        lit.name,
        report.objective,
        if success(lit, report) {
            " (reached)"
        } else {
            ""
        },
        report.evaluations,
        report.local_searches,
        report.samples,
        report.elapsed.as_secs_f64(),
    );
}

/// The command line: which problems, how many seeds.
struct Selection {
    only: Option<String>,
    seeds: u64,
    each: bool,
}

impl Selection {
    fn problems(&self) -> Vec<Literature> {
        literature::problems()
            .into_iter()
            .filter(|l| {
                self.only
                    .as_ref()
                    .is_none_or(|p| l.name.starts_with(p.as_str()))
            })
            .collect()
    }
}

fn main() -> Result<(), SynthesisError> {
    let args: Vec<String> = std::env::args().collect();
    let after = |flag: &str| {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1))
            .cloned()
    };
    let selection = Selection {
        only: after("--only"),
        seeds: after("--seeds").and_then(|s| s.parse().ok()).unwrap_or(10),
        each: args.iter().any(|a| a == "--each"),
    };
    if args.iter().any(|a| a == "--compare") {
        let seconds: f64 = after("--compare")
            .and_then(|s| s.parse().ok())
            .unwrap_or(3.0);
        return compare(&selection, Duration::from_secs_f64(seconds));
    }
    println!(
        "| problem | source | published best | by | mechdiff best | median | successes | median evaluations | median time per seed (s) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for lit in selection.problems() {
        let t = Tally::over_seeds(&selection, &lit, Method::Exact, Duration::from_secs(10))?;
        println!(
            "| {} | {} | {:.4e} | {} | {:.4e} | {:.4e} | {} | {:.0} | {:.2} |",
            lit.name,
            lit.source,
            lit.published_best,
            lit.published_by,
            t.best(),
            median(t.objectives.clone()),
            t.successes,
            median(t.evaluations),
            median(t.times),
        );
    }
    Ok(())
}

fn compare(selection: &Selection, limit: Duration) -> Result<(), SynthesisError> {
    println!(
        "Each run limited to {:.1} s; seeds 0–{}.",
        limit.as_secs_f64(),
        selection.seeds.saturating_sub(1)
    );
    println!(
        "| problem | method | successes | best | median objective | median evaluations | median time (s) |"
    );
    println!("|---|---|---|---|---|---|---|");
    for lit in selection.problems() {
        for (label, method) in [
            ("LM, exact Jacobian (dual numbers)", Method::Exact),
            ("LM, central differences", Method::Differences),
            ("differential evolution alone", Method::Evolution),
        ] {
            let t = Tally::over_seeds(selection, &lit, method, limit)?;
            println!(
                "| {} | {label} | {} | {:.4e} | {:.4e} | {:.0} | {:.2} |",
                lit.name,
                t.successes,
                t.best(),
                median(t.objectives.clone()),
                median(t.evaluations),
                median(t.times),
            );
        }
    }
    Ok(())
}
