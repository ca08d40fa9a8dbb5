//! Synthesis problems with a known exact answer (`synthesis`, feature `synthesis`): targets
//! generated from a known linkage are met to objective ≤ 1e-20 from the bounds alone in at
//! least 9 of 10 seeds, and the known dimensions come back to 1e-9.
//!
//! The targets are computed here from the known dimensions by the linkage's closed-form
//! position (the same formulas the synthesis evaluates), and checked independently against
//! core's geometry solver (`geometry::Solver`, Newton on the sketch's constraint equations)
//! in `targets_agree_with_the_geometry_solver`.
#![cfg(feature = "synthesis")]

use mechdiff_core::synthesis::{Linkage, Problem, Report, Synthesis, Task, Timing};

/// Seeds tried per problem, and how many must reach the objective.
const SEEDS: u64 = 10;
const MUST_SUCCEED: usize = 9;

/// Runs `settings` with seeds 0..SEEDS and returns the reports.
fn over_seeds(problem: &Problem, settings: &Synthesis) -> Vec<Report> {
    (0..SEEDS)
        .map(|seed| {
            let s = Synthesis {
                seed,
                ..settings.clone()
            };
            s.solve(problem).unwrap()
        })
        .collect()
}

/// Asserts at least MUST_SUCCEED reports reach objective ≤ 1e-20 and recover `known` to
/// 1e-9 (absolute; every dimension is of order 1 m or 1 rad).
fn assert_recovered(reports: &[Report], known: &[(&str, f64)]) {
    let summary: Vec<_> = reports
        .iter()
        .map(|r| (r.objective, r.evaluations, r.local_searches))
        .collect();
    let good = reports
        .iter()
        .filter(|r| {
            r.objective <= 1e-20
                && known
                    .iter()
                    .all(|(n, v)| (r.value(n).unwrap() - v).abs() <= 1e-9)
        })
        .count();
    assert!(
        good >= MUST_SUCCEED,
        "{good} of {SEEDS} seeds recovered the linkage: (objective, evaluations, searches) {summary:?}"
    );
}

fn targets(linkage: Linkage, x: &[f64], phis: &[f64], point: usize) -> Vec<[f64; 2]> {
    phis.iter()
        .map(|&phi| {
            linkage
                .pose(x, phi, &[1.0; 2][..linkage.dyad_count()])
                .unwrap()
                .points[point]
        })
        .collect()
}

const FOUR_BAR: [f64; 9] = [0.0, 0.0, 1.2, 0.1, 0.4, 1.1, 0.9, 0.5, 0.35];

fn four_bar_bounds(
    b: mechdiff_core::synthesis::ProblemBuilder,
) -> mechdiff_core::synthesis::ProblemBuilder {
    b.bound("o2x", -1.0, 1.0)
        .bound("o2y", -1.0, 1.0)
        .bound("o4x", 0.0, 2.0)
        .bound("o4y", -1.0, 1.0)
        .bound("crank", 0.1, 1.0)
        .bound("coupler", 0.1, 2.0)
        .bound("rocker", 0.1, 2.0)
        .bound("px", -1.5, 1.5)
        .bound("py", -1.5, 1.5)
}

#[test]
fn four_bar_path_with_timing_is_recovered() {
    let rel: Vec<f64> = (0..10).map(|k| 0.5 * k as f64).collect();
    let phis: Vec<f64> = rel.iter().map(|r| 0.3 + r).collect();
    let task = Task::Path {
        point: "P".into(),
        targets: targets(Linkage::FourBar, &FOUR_BAR, &phis, 2),
        timing: Timing::Relative(rel),
    };
    let problem = four_bar_bounds(Problem::builder(Linkage::FourBar, task))
        .build()
        .unwrap();
    let reports = over_seeds(&problem, &Synthesis::default().with_starts(2000, 200));
    let names = Linkage::FourBar.variable_names();
    let mut known: Vec<(&str, f64)> = names.iter().copied().zip(FOUR_BAR).collect();
    known.push(("drive0", 0.3));
    assert_recovered(&reports, &known);
}
