//! Synthesis given what it cannot do (`synthesis`, feature `synthesis`): targets out of reach
//! get the best found and why it is not better; bounds that exclude every assembly, unknown
//! names, non-finite targets and wrong counts get typed errors; limits are honoured. Never a
//! panic, a hang or a NaN.
#![cfg(feature = "synthesis")]

use mechdiff_core::synthesis::{
    Defect, Linkage, Problem, ProblemBuilder, StopReason, Synthesis, SynthesisError, Task, Timing,
};
use std::time::{Duration, Instant};

fn path(targets: Vec<[f64; 2]>) -> Task {
    let n = targets.len();
    Task::Path {
        point: "P".into(),
        targets,
        timing: Timing::Relative((0..n).map(|k| 0.5 * k as f64).collect()),
    }
}

fn bounded(b: ProblemBuilder) -> ProblemBuilder {
    b.bound("o2x", -1.0, 1.0)
        .bound("o2y", -1.0, 1.0)
        .bound("o4x", 0.0, 2.0)
        .bound("o4y", -1.0, 1.0)
        .bound("crank", 0.1, 1.0)
        .bound("coupler", 0.1, 2.0)
        .bound("rocker", 0.1, 2.0)
        .bound("px", -1.0, 1.0)
        .bound("py", -1.0, 1.0)
}

/// Six points on a circle of radius 8 m about the origin.
fn far_targets() -> Vec<[f64; 2]> {
    (0..6)
        .map(|k| {
            let t = 0.5 * k as f64;
            [8.0 * t.cos(), 8.0 * t.sin()]
        })
        .collect()
}

#[test]
fn targets_out_of_reach_get_the_best_found_and_why() {
    // Within the bounds P stays within |O2| + crank + |AP| ≤ √2 + 1 + √2 < 4 m of the
    // origin, so every target is at least 4 m away: the objective is at least 6·4² = 96.
    let problem = bounded(Problem::builder(Linkage::FourBar, path(far_targets())))
        .build()
        .unwrap();
    let settings = Synthesis::seeded(3).with_starts(300, 10);
    let report = settings.solve(&problem).unwrap();
    assert!(report.objective.is_finite() && report.objective >= 96.0);
    assert!(report.residuals.iter().all(|r| r.is_finite()));
    assert!(report.variables.iter().all(|(_, v)| v.is_finite()));
    let why = report.why_not_better(&settings).unwrap();
    assert!(why.contains("out of reach"), "{why}");
    // Reaching out, the best answer presses against bounds, and says which.
    assert!(!report.at_bounds.is_empty(), "{report:?}");
    assert!(why.contains("at a bound"), "{why}");
    assert_eq!(report.successes, 0);
}

#[test]
fn bounds_that_exclude_every_assembly_are_an_error() {
    // O4 five metres from O2, coupler + rocker at most 2 m, crank at most 1 m: the loop
    // never closes.
    let problem = Problem::builder(Linkage::FourBar, path(far_targets()))
        .fix("o2x", 0.0)
        .fix("o2y", 0.0)
        .fix("o4x", 5.0)
        .fix("o4y", 0.0)
        .bound("crank", 0.1, 1.0)
        .bound("coupler", 0.1, 1.0)
        .bound("rocker", 0.1, 1.0)
        .bound("px", -1.0, 1.0)
        .bound("py", -1.0, 1.0)
        .build()
        .unwrap();
    let err = Synthesis::seeded(1)
        .with_starts(200, 10)
        .solve(&problem)
        .unwrap_err();
    assert_eq!(
        err,
        SynthesisError::NoAssembly {
            samples: 200,
            defects: vec![(Defect::NoAssemblyAtTarget, 200)],
        }
    );
    assert!(err.to_string().contains("widen the bounds"), "{err}");
}

#[test]
fn a_task_naming_an_unknown_point_is_an_error() {
    let task = Task::Path {
        point: "Z".into(),
        targets: far_targets(),
        timing: Timing::Free,
    };
    let err = bounded(Problem::builder(Linkage::FourBar, task))
        .build()
        .unwrap_err();
    assert_eq!(
        err,
        SynthesisError::UnknownName {
            what: "point",
            name: "Z".into(),
            known: vec!["A".into(), "B".into(), "P".into()],
        }
    );
    let task = Task::Function {
        output: "slider".into(),
        pairs: vec![[0.0, 0.0], [1.0, 1.0]],
    };
    let err = bounded(Problem::builder(Linkage::FourBar, task))
        .build()
        .unwrap_err();
    assert!(
        matches!(err, SynthesisError::UnknownName { what: "output", .. }),
        "{err}"
    );
}

#[test]
fn non_finite_targets_and_wrong_counts_are_located_errors() {
    let mut targets = far_targets();
    targets[4][1] = f64::NAN;
    let err = bounded(Problem::builder(Linkage::FourBar, path(targets)))
        .build()
        .unwrap_err();
    assert!(matches!(
        err,
        SynthesisError::NonFiniteTarget {
            what: "target",
            index: 4,
            ..
        }
    ));
    let task = Task::Path {
        point: "P".into(),
        targets: far_targets(),
        timing: Timing::Absolute(vec![0.0; 5]),
    };
    let err = bounded(Problem::builder(Linkage::FourBar, task))
        .build()
        .unwrap_err();
    assert!(
        matches!(err, SynthesisError::TargetCount { count: 5, .. }),
        "{err}"
    );
    let err = Problem::builder(Linkage::FourBar, path(vec![]))
        .build()
        .unwrap_err();
    assert!(
        matches!(err, SynthesisError::TargetCount { count: 0, .. }),
        "{err}"
    );
}

#[test]
fn missing_and_invalid_bounds_are_errors() {
    let err = Problem::builder(Linkage::FourBar, path(far_targets()))
        .bound("crank", 0.1, 1.0)
        .build()
        .unwrap_err();
    assert_eq!(
        err,
        SynthesisError::MissingBound {
            variable: "o2x".into()
        }
    );
    let err = bounded(Problem::builder(Linkage::FourBar, path(far_targets())))
        .bound("rocker", 2.0, 1.0)
        .build()
        .unwrap_err();
    assert!(matches!(err, SynthesisError::InvalidBound { .. }), "{err}");
    let err = bounded(Problem::builder(Linkage::FourBar, path(far_targets())))
        .bound("length", 0.0, 1.0)
        .build()
        .unwrap_err();
    assert!(
        matches!(
            err,
            SynthesisError::UnknownName {
                what: "variable",
                ..
            }
        ),
        "{err}"
    );
}

#[test]
fn limits_are_honoured() {
    let problem = bounded(Problem::builder(Linkage::FourBar, path(far_targets())))
        .build()
        .unwrap();
    // The evaluation limit: the search stops within one local iteration of it (a dual
    // Jacobian of 9 free variables plus one trial point: 10 evaluations).
    let report = Synthesis::seeded(0)
        .with_starts(100, 100)
        .with_max_evaluations(500)
        .solve(&problem)
        .unwrap();
    assert_eq!(report.stop, StopReason::Evaluations);
    assert!(report.evaluations <= 510, "{}", report.evaluations);
    // The time limit: 0.3 s, honoured to within one local iteration (a few ms even in a
    // debug build; 1 s allowed for a loaded machine).
    let start = Instant::now();
    let report = Synthesis::seeded(0)
        .with_starts(20_000, 20_000)
        .with_time_limit(Duration::from_millis(300))
        .solve(&problem);
    assert!(
        start.elapsed() < Duration::from_millis(1300),
        "{:?}",
        start.elapsed()
    );
    match report {
        Ok(r) => assert_eq!(r.stop, StopReason::Time),
        Err(e) => assert!(matches!(e, SynthesisError::TimeLimit { .. }), "{e}"),
    }
    // Counts a user can write are bounded before work starts.
    let err = Synthesis::seeded(0)
        .with_starts(10_000_000, 1)
        .solve(&problem)
        .unwrap_err();
    assert!(
        matches!(
            err,
            SynthesisError::InvalidSetting {
                setting: "starts",
                ..
            }
        ),
        "{err}"
    );
}
