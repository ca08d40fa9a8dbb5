//! The report's pictures: error against time on log axes with the Pareto front labelled
//! (plotters, in the bundled font of [`crate::pictures`]), and error against the drive angle
//! per method and order (a [`Diagram`] of [`crate::pictures`]).

use std::sync::OnceLock;

use plotters::prelude::*;
use plotters::style::FontStyle;

use super::report::PARETO_ORDER;
use super::{EPSILON, MAX_ORDER, Report};
use crate::pictures::{Diagram, FONT, FONT_FAMILY, Panel};
use crate::{Error, Result};

/// Errors below this are drawn at it (log axes cannot show 0: an error of exactly 0).
const FLOOR: f64 = 1e-20;

fn clamp(e: f64) -> f64 {
    if e.is_finite() { e.max(FLOOR) } else { 1.0 }
}

fn picture_error(e: impl std::fmt::Display) -> Error {
    Error::Picture {
        message: format!("accuracy plot: {e}"),
    }
}

/// Registers the bundled font with plotters (as the diagrams of [`crate::pictures`] do).
fn font() -> Result<()> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| {
        plotters::style::register_font(FONT_FAMILY, FontStyle::Normal, FONT).is_ok()
    });
    if ok {
        Ok(())
    } else {
        Err(picture_error("the bundled font could not be read"))
    }
}

/// The SVG of the max error of value, ′, ″ against the median time per drive position, on
/// log axes, `width` × `height` pixels: one dot per method (blue: computes ″, red: fewer
/// orders, not compared), the Pareto front joined in green and its methods named. Methods
/// that were not timed (they failed) are left out.
///
/// # Errors
/// [`Error::Picture`] if plotters cannot draw it.
pub fn pareto_svg(report: &Report, width: u32, height: u32) -> Result<String> {
    font()?;
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(picture_error)?;
        pareto(report, &root).map_err(picture_error)?;
        root.present().map_err(picture_error)?;
    }
    Ok(text)
}

type Area<'a> = DrawingArea<SVGBackend<'a>, plotters::coord::Shift>;

fn pareto<'a>(
    report: &Report,
    area: &Area<'a>,
) -> std::result::Result<(), Box<dyn std::error::Error + 'a>> {
    let points: Vec<(f64, f64, &str, bool)> = report
        .measurements
        .iter()
        .filter(|m| m.time[0].is_finite())
        .map(|m| {
            (
                m.time[0].max(1e-12),
                clamp(m.max_error_to(PARETO_ORDER)),
                m.name.as_str(),
                m.order >= PARETO_ORDER,
            )
        })
        .collect();
    let (t0, t1) = bounds(points.iter().map(|p| p.0));
    let (e0, e1) = bounds(points.iter().map(|p| p.1).chain([EPSILON]));
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!(
                "{}: max scaled error of value, ′, ″ against time",
                short(&report.title)
            ),
            (FONT_FAMILY, 14),
        )
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(80)
        .build_cartesian_2d((t0..t1).log_scale(), (e0..e1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("time per drive position [s]")
        .y_desc("max scaled error")
        .x_label_formatter(&|x| format!("{x:.0e}"))
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .label_style((FONT_FAMILY, 11))
        .draw()?;
    chart.draw_series(points.iter().map(|&(t, e, _, full)| {
        let color = if full { BLUE } else { RED };
        Circle::new((t, e), 4, color.filled())
    }))?;
    // Every method named in small grey type; the front's names again in black below.
    chart.draw_series(points.iter().map(|&(t, e, name, _)| {
        Text::new(
            format!(" {name}"),
            (t, e),
            (FONT_FAMILY, 9).into_font().color(&RGBColor(120, 120, 120)),
        )
    }))?;
    let mut front: Vec<(f64, f64, &str)> = report
        .pareto_front()
        .into_iter()
        .map(|i| {
            let m = &report.measurements[i];
            (
                m.time[0],
                clamp(m.max_error_to(PARETO_ORDER)),
                m.name.as_str(),
            )
        })
        .collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    chart.draw_series(LineSeries::new(front.iter().map(|p| (p.0, p.1)), &GREEN))?;
    chart.draw_series(front.iter().map(|&(t, e, name)| {
        Text::new(format!(" {name}"), (t, e), (FONT_FAMILY, 11).into_font())
    }))?;
    Ok(())
}

/// The title's first clause (before the first colon), for captions.
fn short(title: &str) -> &str {
    title.split(':').next().unwrap_or(title)
}

/// A log axis range holding every value, padded by a factor 2 each side.
fn bounds(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    if lo.is_finite() && hi > 0.0 {
        (lo / 2.0, hi * 2.0)
    } else {
        (FLOOR, 1.0)
    }
}

/// Where each method loses digits: one panel per order (value, ′, ″, ‴), log₁₀ of the scaled
/// error (max over the outputs) against the drive position in degrees, one curve per exact
/// method and per finite-difference scheme at its best step for that order.
/// An error of exactly 0 is drawn at 1e-20; a failure (∞) breaks the curve.
pub fn along_sweep(report: &Report) -> Diagram {
    let degrees: Vec<f64> = report.positions.iter().map(|p| p.to_degrees()).collect();
    let mut diagram = Diagram::new(short(&report.title), "drive position φ [deg]");
    for (k, name) in ["value", "′", "″", "‴"]
        .iter()
        .enumerate()
        .take(MAX_ORDER + 1)
    {
        let mut panel = Panel::new(&format!("log10 scaled error {name}"));
        // Exact methods, and each finite-difference scheme at its best step for this order.
        let prime = ["", "′", "″", "‴"][k];
        let shown = report.measurements.iter().filter(|m| {
            m.order >= k
                && (m.is_exact() || (k > 0 && m.name.contains("best") && m.name.contains(prime)))
        });
        for m in shown {
            let points = degrees
                .iter()
                .zip(&m.errors)
                .map(|(&d, e)| {
                    [
                        d,
                        if e[k].is_finite() {
                            e[k].max(FLOOR).log10()
                        } else {
                            f64::NAN
                        },
                    ]
                })
                .collect();
            panel = panel.series(&m.name, points);
        }
        diagram = diagram.panel(panel);
    }
    diagram
}
