//! Pictures of a synthesis (`mechdiff synthesize --plot DIR`): the targets and what the
//! answer does — the path of the traced point (path and motion generation, with the
//! linkage drawn at the first target and the poses' directions), or the output's change
//! against the drive (function generation) —, and the search's convergence: the best
//! objective (log scale) against the evaluations spent.

use std::f64::consts::TAU;
use std::path::{Path, PathBuf};

use std::fmt::Write as _;

use mechdiff_core::synthesis::{History, Linkage, Report, Task};

use super::diagram::{Diagram, Panel};
use super::drawing::{Drawing, Style};
use crate::error::Result;
use crate::scene::synthesize::Setup;
use crate::scene::units::Dimension;

/// Drive positions drawn along the answer's path or function.
const SAMPLES: usize = 361;
/// Colour of the targets.
const TARGET: &str = "#d62728";

/// Draws the pictures of `report` into `dir` (created if missing) and returns their paths.
///
/// # Errors
/// [`crate::Error::Write`] if the folder or a file cannot be written;
/// [`crate::Error::OutputIsInput`] for a file that is an input of the run.
pub fn write(setup: &Setup, report: &Report, dir: &Path) -> Result<Vec<PathBuf>> {
    crate::files::create_output_folder(dir)?;
    let problem = &setup.problem;
    let linkage = problem.linkage();
    let x = report.x();
    let phis = problem.drive_angles(&x);
    let units = &setup.units;
    let length = |v: f64| units.from_si(v, Dimension::Length);
    // The drive from the first target to the last (a full turn for one target).
    let (first, last) = match phis.len() {
        1 => (phis[0], phis[0] + TAU),
        _ => (phis[0], phis[phis.len() - 1]),
    };
    let drive: Vec<f64> = (0..SAMPLES)
        .map(|k| first + (last - first) * k as f64 / (SAMPLES - 1) as f64)
        .collect();
    let poses: Vec<_> = drive
        .iter()
        .map(|&phi| linkage.pose(&x, phi, problem.branch()).ok())
        .collect();
    let mut written = Vec::new();
    let path = dir.join("synthesis_convergence.svg");
    crate::pictures::write_file(
        &path,
        convergence(&report.history, report.evaluations)?.as_bytes(),
    )?;
    written.push(path);
    match problem.task() {
        Task::Function { output, pairs } => {
            let k = linkage
                .output_names()
                .iter()
                .position(|n| n == output)
                .unwrap_or(0);
            let dimension = if linkage.output_is_angle(k) {
                Dimension::Angle
            } else {
                Dimension::Length
            };
            let shown = |v: f64| units.from_si(v, dimension);
            let angle = |v: f64| units.from_si(v, Dimension::Angle);
            let start = linkage.pose(&x, phis[0], problem.branch()).ok();
            let found: Vec<[f64; 2]> = drive
                .iter()
                .zip(&poses)
                .map(|(&phi, pose)| match (pose, &start) {
                    (Some(p), Some(s)) => {
                        let mut change = p.outputs[k] - s.outputs[k];
                        if dimension == Dimension::Angle {
                            change -= TAU * ((change + std::f64::consts::PI) / TAU).floor();
                        }
                        [angle(phi - phis[0]), shown(change)]
                    }
                    _ => [angle(phi - phis[0]), f64::NAN],
                })
                .collect();
            let targets: Vec<[f64; 2]> = pairs
                .iter()
                .map(|p| [angle(p[0] - pairs[0][0]), shown(p[1] - pairs[0][1])])
                .collect();
            let unit = units.symbol(dimension);
            let diagram = Diagram::new(
                &format!("function generation: change of {output} against the drive"),
                &format!(
                    "drive from the first pair [{}]",
                    units.symbol(Dimension::Angle)
                ),
            )
            .panel(
                Panel::new(&format!("change of {output} [{unit}]"))
                    .series("targets", targets)
                    .series("found", found),
            );
            let path = dir.join("synthesis_function.svg");
            diagram.write_svg(&path)?;
            written.push(path);
        }
        Task::Path { point, targets, .. } => {
            let k = linkage
                .point_names()
                .iter()
                .position(|n| n == point)
                .unwrap_or(0);
            let title = format!("path generation: {point} through the targets (red)");
            let (mut drawing, size) = scene_drawing(setup, report, &poses, k, &phis, &title);
            for t in targets {
                drawing = drawing.circle(
                    [length(t[0]), length(t[1])],
                    size / 6.0,
                    Style::stroke(TARGET, 2.0).filled(TARGET),
                );
            }
            let path = dir.join("synthesis_path.svg");
            drawing.write_svg(&path)?;
            written.push(path);
        }
        Task::Motion { poses: wanted, .. } => {
            let k = linkage.point_names().len() - 1;
            let title = "motion generation: the poses wanted (red) and found (blue)";
            let (mut drawing, size) = scene_drawing(setup, report, &poses, k, &phis, title);
            let beta = x[linkage.variable_names().len()];
            for (t, &phi) in wanted.iter().zip(&phis) {
                let at = [length(t[0]), length(t[1])];
                let tip = [at[0] + size * t[2].cos(), at[1] + size * t[2].sin()];
                drawing = drawing.polyline(&[at, tip], Style::stroke(TARGET, 2.0));
                if let Ok(pose) = linkage.pose(&x, phi, problem.branch()) {
                    let p = pose.points[k];
                    let a = pose.traced_link_angle + beta;
                    let from = [length(p[0]), length(p[1])];
                    let to = [from[0] + size * a.cos(), from[1] + size * a.sin()];
                    drawing = drawing.polyline(&[from, to], Style::link());
                }
            }
            let path = dir.join("synthesis_poses.svg");
            drawing.write_svg(&path)?;
            written.push(path);
        }
    }
    Ok(written)
}

/// The linkage at the first target and the path of point `k` (file units), and a length of
/// a tenth of the path's extent (for the poses' direction strokes).
fn scene_drawing(
    setup: &Setup,
    report: &Report,
    poses: &[Option<mechdiff_core::synthesis::LinkagePose<f64>>],
    k: usize,
    phis: &[f64],
    title: &str,
) -> (Drawing, f64) {
    let units = &setup.units;
    let length = |p: [f64; 2]| {
        [
            units.from_si(p[0], Dimension::Length),
            units.from_si(p[1], Dimension::Length),
        ]
    };
    let problem = &setup.problem;
    let linkage = problem.linkage();
    let x = report.x();
    let path: Vec<[f64; 2]> = poses
        .iter()
        .map(|p| p.as_ref().map_or([f64::NAN; 2], |p| length(p.points[k])))
        .collect();
    let finite: Vec<[f64; 2]> = path.iter().copied().filter(|p| p[0].is_finite()).collect();
    let extent = finite
        .iter()
        .flat_map(|a| finite.iter().map(move |b| (a[0] - b[0]).hypot(a[1] - b[1])))
        .step_by(97)
        .fold(0.0f64, f64::max);
    let mut drawing = Drawing::new(title).unit(units.symbol(Dimension::Length), 1.0);
    drawing = drawing.path(linkage.point_names()[k], &finite);
    if let Ok(pose) = linkage.pose(&x, phis[0], problem.branch()) {
        let o2 = length([x[0], x[1]]);
        let [a, b] = [length(pose.points[0]), length(pose.points[1])];
        let p = length(pose.points[2]);
        drawing = drawing
            .polyline(&[o2, a], Style::link())
            .polygon(&[a, b, p], Style::link());
        if linkage == Linkage::SliderCrank {
            drawing = drawing.block(b, x[5]);
        } else {
            let o4 = length([x[2], x[3]]);
            drawing = drawing
                .polyline(&[b, o4], Style::link())
                .ground(o4)
                .joint("O4", o4);
        }
        if linkage == Linkage::StephensonSix {
            let [e, q] = [length(pose.points[3]), length(pose.points[4])];
            let o6 = length([x[9], x[10]]);
            drawing = drawing
                .polygon(&[p, e, q], Style::link())
                .polyline(&[e, o6], Style::link())
                .ground(o6)
                .joint("O6", o6)
                .joint("E", e);
        }
        drawing = drawing
            .ground(o2)
            .joint("O2", o2)
            .joint("A", a)
            .joint("B", b);
    }
    (drawing, (extent / 10.0).max(f64::MIN_POSITIVE))
}

/// The convergence diagram of `history`: log₁₀ of the best objective against the evaluations
/// spent, as a staircase (the best holds until the next improvement, the last one until
/// `evaluations`, the search's total), and each recorded
/// improvement as a `<circle class="improvement">` with its exact `data-evaluations` and
/// `data-objective` (an objective of exactly 0 is drawn at the panel's bottom).
///
/// # Errors
/// [`crate::Error::Picture`] if the diagram cannot be drawn.
pub fn convergence(history: &History, evaluations: usize) -> Result<String> {
    let points = history.improvements();
    // log₁₀ of 0 is drawn 2 decades below the least positive objective.
    let least = points
        .iter()
        .map(|p| p.objective)
        .filter(|v| *v > 0.0)
        .fold(f64::INFINITY, f64::min);
    let floor = if least.is_finite() {
        least.log10() - 2.0
    } else {
        -30.0
    };
    let log = |v: f64| if v > 0.0 { v.log10() } else { floor };
    let mut steps: Vec<[f64; 2]> = Vec::with_capacity(2 * points.len());
    for (k, p) in points.iter().enumerate() {
        if k > 0 {
            steps.push([p.evaluations as f64, log(points[k - 1].objective)]);
        }
        steps.push([p.evaluations as f64, log(p.objective)]);
    }
    if let Some(last) = points.last()
        && evaluations > last.evaluations
    {
        steps.push([evaluations as f64, log(last.objective)]);
    }
    let diagram = Diagram::new(
        &format!(
            "convergence: best objective against evaluations ({} improvements)",
            points.len()
        ),
        "residual evaluations",
    )
    .panel(Panel::new("log₁₀ of the best objective [m², rad²]").series("best", steps));
    let mut svg = diagram.to_svg()?;
    // The plotting rectangle and its data range, as the diagram writes them.
    let frame = svg
        .find(r#"class="plot-frame""#)
        .and_then(|at| svg[at..].find("/>").map(|end| svg[at..at + end].to_owned()))
        .unwrap_or_default();
    let attribute = |name: &str| -> f64 {
        let key = format!(r#" {name}=""#);
        frame
            .find(&key)
            .and_then(|at| {
                let rest = &frame[at + key.len()..];
                rest[..rest.find('"')?].parse().ok()
            })
            .unwrap_or(f64::NAN)
    };
    let [x0, x1, y0, y1] = ["data-x0", "data-x1", "data-y0", "data-y1"].map(attribute);
    let [left, top, width, height] = ["x", "y", "width", "height"].map(attribute);
    let mut marks = String::from("<g class=\"improvements\">\n");
    for p in points {
        let (x, y) = (p.evaluations as f64, log(p.objective));
        let px = left + (x - x0) / (x1 - x0) * width;
        let py = top + height - (y - y0) / (y1 - y0) * height;
        // A degenerate range (one improvement) puts the point in the middle.
        let px = if px.is_finite() {
            px
        } else {
            left + width / 2.0
        };
        let py = if py.is_finite() {
            py
        } else {
            top + height / 2.0
        };
        let _ = writeln!(
            marks,
            r#"<circle class="improvement" data-evaluations="{}" data-objective="{:e}" cx="{px:.2}" cy="{py:.2}" r="3" fill="{TARGET}"/>"#,
            p.evaluations, p.objective
        );
    }
    marks.push_str("</g>\n</svg>");
    if let Some(end) = svg.rfind("</svg>") {
        svg.replace_range(end.., &marks);
    }
    Ok(svg)
}
