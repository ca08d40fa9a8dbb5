//! Coupler curves: the x–y path of each traced point over the sweep (`[plot] trace`), drawn
//! to scale — equal axes, grid and scale bar of [`Drawing`] — with the drive position
//! marked along it at round values, and the dead positions and limits the sweep reaches
//! marked; and the path as CSV (`x, y` at each drawn drive position).

use std::f64::consts::TAU;
use std::fmt::Write as _;

use super::axis;
use super::drawing::{Drawing, Style};
use super::scene::{Poses, poses};
use crate::error::Result;
use crate::scene::Scene;
use crate::scene::build::mechanism;
use crate::scene::run::Report;
use crate::scene::units::Dimension;

/// Colour of the drive-position ticks along a path.
const TICK: &str = "#333333";
/// Colour of a dead position's mark.
const DEAD: &str = "#1b9e77";
/// Colour of a limit's mark.
const LIMIT: &str = "#d62728";

/// One traced point's path: its file stem, the picture and the CSV.
#[derive(Debug, Clone)]
pub struct PathPlot {
    /// `path_<point>`.
    pub name: String,
    /// The x–y plot.
    pub drawing: Drawing,
    /// `phi [unit],x_P [unit],y_P [unit]` then one line per drawn drive position.
    pub csv: String,
}

/// The path plots of a run: one per `traced` point (indices into the scene's points: the
/// `[plot] trace` points, or the `[[output]] point` points), over the `drawn` poses (those
/// of the run's animation: at most [`super::run::FRAMES`], spread over the sweep).
///
/// # Errors
/// The solver's errors at a marked drive position (the run solved them already, so none is
/// expected).
pub fn plots(
    scene: &Scene,
    report: &Report,
    drawn: &Poses,
    traced: &[usize],
) -> Result<Vec<PathPlot>> {
    if traced.is_empty() || drawn.phi.is_empty() {
        return Ok(Vec::new());
    }
    let m = mechanism(scene)?;
    let units = scene.units.for_outputs();
    let (length, length_si) = (
        units.symbol(Dimension::Length),
        units.to_si(1.0, Dimension::Length),
    );
    let drive = &report.columns[0];
    let angle_drive = scene.drive.kind.dimension() == Dimension::Angle;
    // The round drive values marked along the path, in the drive's printed unit.
    let (lo, hi) = (drawn.phi.iter()).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &p| {
        (lo.min(p), hi.max(p))
    });
    let range = lo / drive.factor..hi / drive.factor;
    let mut ticks = if angle_drive && drive.unit == "deg" {
        axis::angle_ticks(&range)
    } else {
        axis::ticks(&range, 9)
    };
    ticks.retain(|v| range.contains(v) || *v == range.end);
    let tick_phi: Vec<f64> = ticks.iter().map(|v| v * drive.factor).collect();
    let tick_poses = poses(scene, &m, &tick_phi)?;
    let mut dead: Vec<(f64, String)> = (report.dead_positions.iter())
        .flat_map(|d| {
            d.positions.iter().map(move |p| {
                let kind = if p.d2 < 0.0 { "max" } else { "min" };
                (p.phi, format!("dead: {} {kind}", d.output))
            })
        })
        .collect();
    dead.sort_by(|a, b| a.0.total_cmp(&b.0));
    let dead_poses = poses(scene, &m, &dead.iter().map(|d| d.0).collect::<Vec<_>>())?;
    let limits: Vec<(f64, String)> = (report.limits.iter())
        .map(|l| {
            let words = crate::scene::sweep_limits::kind_words(l.limit.kind);
            (l.limit.phi, words.to_owned())
        })
        .collect();
    // A limit is a toggle of the loop that stops there: its pose may not solve with the
    // derivatives the drawings carry (the velocity coefficients are infinite). Such a limit is
    // marked at the drawn pose nearest to it (the curve's end next to it), and says so.
    let mut limit_poses = Poses {
        phi: Vec::new(),
        xy: Vec::new(),
    };
    let mut limits = limits;
    for (phi, words) in &mut limits {
        let pose = match poses(scene, &m, &[*phi]) {
            Ok(p) => p.xy.into_iter().next().expect("one pose asked"),
            Err(_) => {
                let nearest = (0..drawn.phi.len())
                    .min_by(|&a, &b| {
                        (drawn.phi[a] - *phi)
                            .abs()
                            .total_cmp(&(drawn.phi[b] - *phi).abs())
                    })
                    .expect("drawn poses are not empty");
                let at = format!("φ = {} {}", short(*phi / drive.factor), drive.unit);
                words.push_str(&format!(" at {at} (marked at the nearest drawn position)"));
                drawn.xy[nearest].clone()
            }
        };
        limit_poses.phi.push(*phi);
        limit_poses.xy.push(pose);
    }
    let title = scene.title.clone().unwrap_or_else(|| scene.file.clone());
    let mut out = Vec::new();
    for &k in traced {
        let point = &scene.points[k].name;
        let path = drawn.path(k);
        let centre = centroid(&path);
        let away = |p: [f64; 2]| [p[0] - centre[0], p[1] - centre[1]];
        let mut d = Drawing::new(&format!(
            "{title} — path of {point} (coupler curve), φ marked along it"
        ))
        .unit(length, length_si)
        .include(&path)
        .path(point, &path);
        let size = extent(&path) * 0.006;
        // Drive values a whole number of turns apart mark one place: one label for them.
        let mut marks: Vec<(usize, Vec<f64>)> = Vec::new();
        for (i, (&v, &phi)) in ticks.iter().zip(&tick_phi).enumerate() {
            let same = |&(j, _): &(usize, Vec<f64>)| {
                angle_drive
                    && ((phi - tick_phi[j]) / TAU - ((phi - tick_phi[j]) / TAU).round()).abs()
                        < 1e-9
            };
            match marks.iter_mut().find(|m| same(m)) {
                Some((_, values)) => values.push(v),
                None => marks.push((i, vec![v])),
            }
        }
        for (i, values) in &marks {
            let at = tick_poses.xy[*i][k];
            let values: Vec<String> = values.iter().map(|v| short(*v)).collect();
            let text = format!("φ = {} {}", values.join(", "), drive.unit);
            d = d
                .circle(at, size, Style::stroke(TICK, 1.0).filled(TICK))
                .label_toward(at, &text, away(at));
        }
        // Dead positions and limits are labelled on the other side of the curve, clear of
        // the drive's marks.
        let inward = |p: [f64; 2]| {
            let a = away(p);
            [-a[0], -a[1]]
        };
        for (pose, (_, words)) in dead_poses.xy.iter().zip(&dead) {
            let at = pose[k];
            d = d
                .circle(at, 2.0 * size, Style::stroke(DEAD, 2.0))
                .label_toward(at, words, inward(at));
        }
        for (pose, (_, words)) in limit_poses.xy.iter().zip(&limits) {
            let at = pose[k];
            d = d
                .circle(at, 2.0 * size, Style::stroke(LIMIT, 2.0))
                .label_toward(at, words, inward(at));
        }
        let mut csv = format!(
            "phi [{}],x_{point} [{length}],y_{point} [{length}]\n",
            drive.unit
        );
        for (phi, xy) in drawn.phi.iter().zip(&path) {
            let _ = writeln!(
                csv,
                "{},{},{}",
                phi / drive.factor + 0.0,
                xy[0] / length_si + 0.0,
                xy[1] / length_si + 0.0
            );
        }
        out.push(PathPlot {
            name: format!("path_{}", file_safe(point)),
            drawing: d,
            csv,
        });
    }
    Ok(out)
}

/// A point name as part of a file name: letters, digits, `-` and `_` kept, others `_`.
fn file_safe(name: &str) -> String {
    name.chars()
        .map(|c| match c {
            'a'..='z' | 'A'..='Z' | '0'..='9' | '-' | '_' => c,
            _ => '_',
        })
        .collect()
}

/// A tick value without trailing zeros (at most six decimals).
fn short(v: f64) -> String {
    let text = format!("{v:.6}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" {
        "0".to_owned()
    } else {
        text.to_owned()
    }
}

/// The mean of `points`.
fn centroid(points: &[[f64; 2]]) -> [f64; 2] {
    let n = points.len().max(1) as f64;
    let sum = (points.iter()).fold([0.0, 0.0], |s, p| [s[0] + p[0], s[1] + p[1]]);
    [sum[0] / n, sum[1] / n]
}

/// The larger side of `points`' bounding box (a unit when it is empty or a point).
fn extent(points: &[[f64; 2]]) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in points {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let size = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    if size.is_finite() && size > 0.0 {
        size
    } else {
        1.0
    }
}
