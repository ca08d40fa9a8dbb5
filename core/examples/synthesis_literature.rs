//! Classic synthesis problems from the literature (`core/tests/data/synthesis/literature.rs`:
//! Kunjur & Krishnamurty's five timed points and eighteen-point closed curve, Cabrera et
//! al.'s six-point straight line without timing, Freudenstein's log10 function generator)
//! solved over seeds 0–9, each run limited to 10 s on one core. Prints, per problem: the
//! published best, mechdiff's best and median objective, the runs reaching the published
//! best (successes of 10; an answer counts only if core's geometry solver moves it through
//! every target and its ground link is within the paper's bound), the median evaluations
//! and the median CPU time per run.
//!
//! `cargo run --release -p mechdiff-core --features synthesis --example synthesis_literature`

#[path = "../tests/data/synthesis/literature.rs"]
mod literature;

use mechdiff_core::synthesis::{MAX_ROUNDS, Synthesis, SynthesisError};
use std::time::Duration;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() -> Result<(), SynthesisError> {
    println!(
        "| problem | source | published best | by | mechdiff best | median | successes of 10 | median evaluations | median time per seed (s) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for lit in literature::problems() {
        let (mut objectives, mut evaluations, mut times, mut successes) =
            (Vec::new(), Vec::new(), Vec::new(), 0);
        for seed in 0..10 {
            let settings = Synthesis::seeded(seed)
                .with_fitted_timing(true)
                .with_rounds(MAX_ROUNDS)
                .with_stop_objective(lit.success_level)
                .with_time_limit(Duration::from_secs(10));
            let report = settings.solve(&lit.problem)?;
            let x = report.x();
            let ground = (x[2] - x[0]).hypot(x[3] - x[1]);
            let admissible = lit.max_ground.is_none_or(|g| ground <= g)
                && report
                    .certificate
                    .as_ref()
                    .is_ok_and(|c| c.deviation <= 1e-9);
            successes += usize::from(admissible && report.objective <= lit.success_level);
            objectives.push(report.objective);
            evaluations.push(report.evaluations as f64);
            times.push(report.elapsed.as_secs_f64());
        }
        println!(
            "| {} | {} | {:.4e} | {} | {:.4e} | {:.4e} | {successes} | {:.0} | {:.2} |",
            lit.name,
            lit.source,
            lit.published_best,
            lit.published_by,
            objectives.iter().copied().fold(f64::INFINITY, f64::min),
            median(objectives.clone()),
            median(evaluations),
            median(times),
        );
    }
    Ok(())
}
