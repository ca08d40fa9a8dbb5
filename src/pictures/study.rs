//! The pictures of a parameter study (`mechdiff run scene.toml --sweep l1=… --plot DIR`):
//! the diagram as families of curves against the drive position, one curve per parameter
//! value with a legend of the values; a summary of headline numbers (stroke or swing, the
//! largest drive torque, the smallest transmission angle) against the parameter; and the
//! drawings, coupler-curve plots and report of the first value's run.

use std::path::{Path, PathBuf};

use mechdiff_core::metrics::Loops;

use super::diagram::{Diagram, Panel};
use super::run::{Animation, curve, selected};
use super::symbols::symbol;
use crate::error::Result;
use crate::scene::build::mechanism;
use crate::scene::model::OutputKind;
use crate::scene::study::{ParameterSweep, StudyRun};
use crate::scene::units::{Dimension, Units};

/// The most curves one panel of a family draws (one colour each): with more values, this
/// many spread evenly over them, both ends included, and the title says so. The summary
/// draws every value.
pub const MAX_CURVES: usize = 6;

/// The indices of the runs a family draws (see [`MAX_CURVES`]).
pub fn drawn(runs: usize) -> Vec<usize> {
    if runs <= MAX_CURVES {
        return (0..runs).collect();
    }
    let last = (runs - 1) as f64;
    let mut picks: Vec<usize> = (0..MAX_CURVES)
        .map(|i| (last * i as f64 / (MAX_CURVES - 1) as f64).round() as usize)
        .collect();
    picks.dedup();
    picks
}

/// `NAME = V`: a value's name in legends and titles.
fn value_name(sweep: &ParameterSweep, value: f64) -> String {
    format!("{} = {}", sweep.name, Units::tidy(value))
}

/// The diagram of a study: per column chosen as [`selected`] chooses them for the first
/// value's run, a panel with one curve per drawn value ([`drawn`]) against the drive
/// position, labelled with that column's own symbol and unit.
///
/// # Errors
/// A `[plot] panels` name that is neither an output nor a column.
pub fn family(sweep: &ParameterSweep, runs: &[StudyRun]) -> Result<Option<Diagram>> {
    let Some(first) = runs.first() else {
        return Ok(None);
    };
    let (scene, report) = (&first.scene, &first.report);
    let picks = drawn(runs.len());
    let name = scene.title.clone().unwrap_or_else(|| scene.file.clone());
    let title = format!(
        "{name} — {} ({} of {} values drawn)",
        sweep.name,
        picks.len(),
        runs.len()
    );
    let mut d = Diagram::new(&title, &format!("φ [{}]", report.columns[0].unit));
    for g in &selected(scene, report)? {
        for &c in &g.columns {
            let column = &report.columns[c];
            let mut panel = Panel::new(&format!("{} [{}]", symbol(&column.name), column.unit));
            for &k in &picks {
                let r = &runs[k].report;
                if let Some(kc) = r.columns.iter().position(|x| x.name == column.name) {
                    panel = panel.series(&value_name(sweep, runs[k].value), curve(r, kc).0);
                }
            }
            d = d.panel(panel);
        }
    }
    Ok(Some(d))
}

/// The headline numbers of a study against the parameter: per angle or slider output, its
/// range Δ over the sweep (max − min: the stroke or swing when the sweep holds both dead
/// positions); per transmission-angle output, its smallest value; the largest |drive
/// torque| (or force); per four-bar or slider-crank loop (named by its follower), its worst
/// effective transmission angle μ_eff = min(μ, 180° − μ) over the input's range (from its
/// lengths). `None` without any.
pub fn summary(sweep: &ParameterSweep, runs: &[StudyRun]) -> Option<Diagram> {
    let first = runs.first()?;
    let scene = &first.scene;
    // (label with unit, per run: [value, headline number in the printed unit])
    let mut panels: Vec<(String, Vec<[f64; 2]>)> = Vec::new();
    let mut add = |label: String, value: &dyn Fn(&StudyRun) -> Option<f64>| {
        let points: Vec<[f64; 2]> = (runs.iter())
            .filter_map(|r| value(r).map(|v| [r.value, v]))
            .filter(|p| p[1].is_finite())
            .collect();
        if !points.is_empty() {
            panels.push((label, points));
        }
    };
    let column_values = |r: &StudyRun, name: &str| -> Option<(Vec<f64>, String)> {
        let k = r.report.columns.iter().position(|c| c.name == name)?;
        let c = &r.report.columns[k];
        let values = r.report.rows.iter().map(|row| row[k] / c.factor).collect();
        Some((values, c.unit.clone()))
    };
    for output in &scene.outputs {
        let Some((_, unit)) = column_values(first, &output.name) else {
            continue;
        };
        let n = &output.name;
        match output.kind {
            OutputKind::Point(_) => {}
            OutputKind::Transmission { .. } => add(format!("min {} [{unit}]", symbol(n)), &|r| {
                column_values(r, n).map(|(v, _)| v.into_iter().fold(f64::INFINITY, f64::min))
            }),
            OutputKind::Angle { .. } | OutputKind::Slider { .. } => {
                add(format!("Δ{} [{unit}]", symbol(n)), &|r| {
                    column_values(r, n).map(|(v, _)| {
                        let (lo, hi) = (v.iter())
                            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| {
                                (lo.min(x), hi.max(x))
                            });
                        hi - lo
                    })
                })
            }
        }
    }
    for torque in ["M_drive", "F_drive"] {
        if let Some((_, unit)) = column_values(first, torque) {
            add(format!("max |{}| [{unit}]", symbol(torque)), &|r| {
                column_values(r, torque).map(|(v, _)| v.iter().fold(0.0f64, |m, x| m.max(x.abs())))
            });
        }
    }
    let units = scene.units.for_outputs();
    let angle = units.symbol(Dimension::Angle);
    let worst = |r: &StudyRun| -> Vec<(String, f64)> {
        let Some(loops) = (mechanism(&r.scene).ok()).and_then(|m| Loops::find(&m).ok()) else {
            return Vec::new();
        };
        let effective =
            |mu: f64| units.from_si(mu.min(std::f64::consts::PI - mu), Dimension::Angle);
        // Each loop named by its follower (a four-bar's output, a slider-crank's slider).
        let mut out: Vec<(String, f64)> = (loops.four_bars.iter())
            .map(|l| {
                let name = l.links[3].clone();
                (name, effective(l.transmission_extremes().worst.angle))
            })
            .collect();
        out.extend(loops.slider_cranks.iter().map(|l| {
            let name = l.slider.clone().unwrap_or_else(|| l.rod.clone());
            (name, effective(l.transmission_extremes().worst.angle))
        }));
        out
    };
    for (name, _) in worst(first) {
        add(format!("min μ_eff {name} [{angle}]"), &|r| {
            worst(r)
                .into_iter()
                .find(|(n, _)| *n == name)
                .map(|(_, v)| v)
        });
    }
    if panels.is_empty() {
        return None;
    }
    let title = scene.title.clone().unwrap_or_else(|| scene.file.clone());
    let mut d = Diagram::new(
        &format!(
            "{title} — against {} (Δ: max − min over the sweep)",
            sweep.name
        ),
        &format!("{} [as set]", sweep.name),
    );
    for (label, points) in panels {
        d = d.panel(Panel::new(&label).series(&label, points));
    }
    Some(d)
}

/// Writes the pictures of a study into `dir` (created if missing): `diagram.svg/png` (the
/// families; `diagram_2`, … when it is taller than a page), `sweep_summary.svg/png`, the
/// first value's drawings and coupler-curve plots (as [`super::run::write_dir`] names
/// them), and `report.html` (the first value's run, with the families as its diagram).
/// Returns the files written; if any is one of the run's inputs, nothing is written.
///
/// # Errors
/// A `[plot]` entry the first value's run cannot honour; a file that cannot be written.
pub fn write_dir(sweep: &ParameterSweep, runs: &[StudyRun], dir: &Path) -> Result<Vec<PathBuf>> {
    let Some(first) = runs.first() else {
        return Ok(Vec::new());
    };
    let (scene, report) = (&first.scene, &first.report);
    let mut pictures: Vec<(String, String)> = Vec::new();
    let mut whole = String::new();
    if let Some(diagram) = family(sweep, runs)? {
        whole = diagram.to_svg()?;
        let pages = diagram.pages();
        for (k, page) in pages.iter().enumerate() {
            let svg = if pages.len() == 1 {
                whole.clone()
            } else {
                page.to_svg()?
            };
            let name = match k {
                0 => "diagram".to_owned(),
                _ => format!("diagram_{}", k + 1),
            };
            pictures.push((name, svg));
        }
    }
    if let Some(summary) = summary(sweep, runs) {
        pictures.push(("sweep_summary".to_owned(), summary.to_svg()?));
    }
    let animation = Animation::of(scene, report)?;
    let tag = value_name(sweep, first.value);
    for (name, drawing) in super::run::drawings(scene, report, &animation)? {
        let mut drawing = drawing;
        drawing.title = format!("{} ({tag})", drawing.title);
        pictures.push((name, drawing.to_svg()));
    }
    let paths = super::path::plots(scene, report, &animation.poses, &animation.traced)?;
    for p in &paths {
        let mut drawing = p.drawing.clone();
        drawing.title = format!("{} ({tag})", drawing.title);
        pictures.push((p.name.clone(), drawing.to_svg()));
    }
    let html = super::report::html(scene, report, &animation, &whole)?;
    super::run::write_folder(dir, &pictures, &html, &paths)
}

/// Writes the HTML report of a study to `path`: the first value's run, with the families of
/// curves ([`family`]) as its diagram.
///
/// # Errors
/// As [`super::report::write`].
pub fn write_report(sweep: &ParameterSweep, runs: &[StudyRun], path: &Path) -> Result<()> {
    let Some(first) = runs.first() else {
        return Ok(());
    };
    let diagram = match family(sweep, runs)? {
        Some(d) => d.to_svg()?,
        None => String::new(),
    };
    let animation = Animation::of(&first.scene, &first.report)?;
    let html = super::report::html(&first.scene, &first.report, &animation, &diagram)?;
    super::write_file(path, html.as_bytes())
}
