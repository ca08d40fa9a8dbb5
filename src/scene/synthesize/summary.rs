//! What `mechdiff synthesize` prints: the parameters found, the objective and each residual,
//! the constraints' margins, and what the search cost.

use std::fmt::Write;

use mechdiff_core::synthesis::{GrashofClass, Report, StopReason, Synthesis, Task, Timing};

use super::{Method, Setup};
use crate::scene::units::Dimension;

/// The most weights [`describe`] lists; a longer list is cut after them.
const LISTED_WEIGHTS: usize = 12;

/// One line saying what the section asks (as `mechdiff check` prints it): the linkage, the
/// task, the targets with their weights (where one is not 1), the design variables free,
/// and the Grashof class required (where the section names one).
pub fn describe(setup: &Setup) -> String {
    let problem = &setup.problem;
    let (lower, upper) = problem.bounds();
    let free = lower.iter().zip(upper).filter(|(l, u)| l < u).count();
    let task = match problem.task() {
        Task::Path { point, .. } => format!("path generation of point {point}"),
        Task::Function { output, .. } => format!("function generation of output {output}"),
        Task::Motion { link, .. } => format!("motion generation of link {link}"),
    };
    let weights = problem.weights();
    let weighted = if weights.iter().any(|w| *w != 1.0) {
        let listed: Vec<String> = (weights.iter().take(LISTED_WEIGHTS))
            .map(|w| w.to_string())
            .collect();
        let rest = if weights.len() > LISTED_WEIGHTS {
            format!(", … ({} in all)", weights.len())
        } else {
            String::new()
        };
        format!(" (weights {}{rest})", listed.join(", "))
    } else {
        String::new()
    };
    let grashof = match problem.grashof() {
        GrashofClass::Any => String::new(),
        class => format!(", Grashof class {} required", class.name()),
    };
    format!(
        "synthesis: {}, {task}, {} targets{weighted}, {free} of {} design variables \
         free{grashof}; `mechdiff synthesize` sizes them",
        setup.linkage_name,
        problem.task().target_count(),
        lower.len()
    )
}

/// The text report of `report`, found by `method` with `settings`.
pub fn summary(setup: &Setup, settings: &Synthesis, report: &Report, method: Method) -> String {
    let mut out = String::new();
    let units = &setup.units;
    let task = setup.problem.task();
    let (what, timing) = match task {
        Task::Path { point, timing, .. } => (format!("path generation of point {point}"), timing),
        Task::Function { output, .. } => (
            format!("function generation of output {output}"),
            &Timing::Free,
        ),
        Task::Motion { link, timing, .. } => (format!("motion generation of link {link}"), timing),
    };
    let timing = match (task, timing) {
        (Task::Function { .. }, _) => "drive relative to drive0",
        (_, Timing::Absolute(_)) => "drive positions given",
        (_, Timing::Relative(_)) => "drive positions given up to drive0",
        (_, Timing::Free) => "drive positions free, in order",
    };
    let derivatives = match method {
        Method::Exact => "exact Jacobian (dual numbers)",
        Method::Differences => "central-difference Jacobian",
        Method::Evolution => "differential evolution (no derivatives)",
    };
    let _ = writeln!(
        out,
        "synthesis: {}, {what}, {} targets ({timing}); {derivatives}; seed {}",
        setup.linkage_name,
        task.target_count(),
        settings.seed
    );
    let _ = writeln!(out, "\nparameters found:");
    let (lower, upper) = setup.problem.bounds();
    for (k, v) in setup.variables.iter().enumerate() {
        let shown = v.parameter.as_deref().unwrap_or(&v.name);
        let symbol = units.symbol(v.dimension);
        let value = setup.in_file_units(report, k);
        let note = if lower[k] == upper[k] {
            "fixed".to_owned()
        } else {
            let at = report
                .at_bounds
                .iter()
                .find(|(n, _)| *n == v.name)
                .map_or("", |(_, up)| {
                    if *up {
                        ", at the upper bound"
                    } else {
                        ", at the lower bound"
                    }
                });
            format!(
                "bounds [{}, {}]{at}",
                units.from_si(lower[k], v.dimension),
                units.from_si(upper[k], v.dimension)
            )
        };
        let _ = writeln!(out, "  {shown:<12} = {value:>22.15} {symbol:<4} {note}");
    }
    let _ = writeln!(
        out,
        "\nobjective: {:.6e} (sum of the squared residuals below)",
        report.objective
    );
    let weighted = setup.problem.weights().iter().any(|w| *w != 1.0);
    let _ = writeln!(
        out,
        "residuals (SI: m, rad; a pose's angle error times its weight, m{}):",
        if weighted {
            "; each times the square root of its target's weight"
        } else {
            ""
        }
    );
    let labels: &[&str] = match task {
        Task::Path { .. } => &["x", "y"],
        Task::Function { .. } => &["output"],
        Task::Motion { .. } => &["x", "y", "angle"],
    };
    let header: Vec<String> = labels.iter().map(|l| format!("{l:>14}")).collect();
    let _ = writeln!(out, "  {:>6} {}", "target", header.join(" "));
    let first = usize::from(matches!(task, Task::Function { .. }));
    for (i, row) in report.residuals.chunks(labels.len()).enumerate() {
        let cells: Vec<String> = row.iter().map(|r| format!("{r:>14.6e}")).collect();
        let _ = writeln!(out, "  {:>6} {}", i + 1 + first, cells.join(" "));
    }
    let _ = writeln!(out, "\nconstraints at the answer (margin ≥ 0: satisfied):");
    for m in setup.margins(report).margins {
        let symbol = units.symbol(m.dimension);
        let value = units.from_si(m.value, m.dimension);
        let need = match (m.required, m.least) {
            (true, Some(least)) => format!(
                "required ≥ {} {symbol}, margin {:.6} {symbol}",
                units.from_si(least, m.dimension),
                units.from_si(m.value - least, m.dimension)
            ),
            (true, None) => "required".into(),
            _ => "not required".into(),
        };
        let _ = writeln!(out, "  {}: {value:.6} {symbol} ({need})", m.what);
    }
    let stop = match report.stop {
        StopReason::Objective => format!("the objective reached {:e}", settings.stop_objective),
        StopReason::Starts => "every local search asked for was run".into(),
        StopReason::Evaluations => "the evaluation limit".into(),
        StopReason::Time => "the time limit".into(),
        _ => "another reason".into(),
    };
    let _ = writeln!(
        out,
        "\nsearch: {} evaluations, {} samples of the bounds ({} usable), {} local searches \
         ({} reached the objective), {:.3} s; stopped by {stop}",
        report.evaluations,
        report.samples,
        report.feasible_samples,
        report.local_searches,
        report.successes,
        report.elapsed.as_secs_f64()
    );
    if !report.defects.is_empty() {
        let counted: Vec<String> = (report.defects.iter())
            .map(|(d, n)| format!("{n}× {}", d.describe()))
            .collect();
        let _ = writeln!(out, "rejected candidates: {}", counted.join(", "));
    }
    match &report.certificate {
        Ok(c) => {
            let _ = writeln!(
                out,
                "checked: core's geometry solver moves the answer through every target, its \
                 points within {:.3e} {} of the synthesis's",
                units.from_si(c.deviation, Dimension::Length),
                units.symbol(Dimension::Length)
            );
        }
        Err(e) => {
            let _ = writeln!(
                out,
                "warning: core's geometry solver cannot move the answer: {e}"
            );
        }
    }
    if let Some(why) = report.why_not_better(settings) {
        let _ = writeln!(out, "not better because: {why}");
    }
    out
}
