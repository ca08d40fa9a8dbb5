//! The report's SVG plot: error against time on log axes with the Pareto front labelled,
//! and error against drive angle per method (drawn with plotters).

use plotters::prelude::*;

use super::report::PARETO_ORDER;
use super::{EPSILON, Report};

/// Errors below this are drawn at it (log axes cannot show 0: an error of exactly 0).
const FLOOR: f64 = 1e-20;

fn clamp(e: f64) -> f64 {
    if e.is_finite() { e.max(FLOOR) } else { 1.0 }
}

/// The SVG text of the report's plot, `width` × `height` pixels: left, the max error of
/// value, ′, ″ against the median time per position (log-log), Pareto front joined and its
/// methods named; right, each method's error (max over orders ≤ ″) against the drive angle.
pub fn svg(report: &Report, width: u32, height: u32) -> Result<String, String> {
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let (left, right) = root.split_horizontally(width / 2);
        pareto(report, &left).map_err(|e| e.to_string())?;
        along_sweep(report, &right).map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(text)
}

type Area<'a> = DrawingArea<SVGBackend<'a>, plotters::coord::Shift>;

fn pareto<'a>(report: &Report, area: &Area<'a>) -> Result<(), Box<dyn std::error::Error + 'a>> {
    let points: Vec<(f64, f64, &str, bool)> = report
        .measurements
        .iter()
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
        .caption("max scaled error (value, ′, ″) vs time", ("sans-serif", 16))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d((t0..t1).log_scale(), (e0..e1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("time per drive position [s]")
        .y_desc("scaled error")
        .draw()?;
    chart.draw_series(points.iter().map(|&(t, e, _, full)| {
        let color = if full { BLUE } else { RED };
        Circle::new((t, e), 4, color.filled())
    }))?;
    let mut front: Vec<(f64, f64, &str)> = report
        .pareto_front()
        .into_iter()
        .map(|i| (points[i].0, points[i].1, points[i].2))
        .collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    chart.draw_series(LineSeries::new(front.iter().map(|p| (p.0, p.1)), &GREEN))?;
    chart.draw_series(front.iter().map(|&(t, e, name)| {
        Text::new(name.to_string(), (t, e), ("sans-serif", 11).into_font())
    }))?;
    Ok(())
}

fn along_sweep<'a>(
    report: &Report,
    area: &Area<'a>,
) -> Result<(), Box<dyn std::error::Error + 'a>> {
    let degrees: Vec<f64> = report.positions.iter().map(|p| p.to_degrees()).collect();
    let (x0, x1) = (
        degrees.first().copied().unwrap_or(0.0),
        degrees
            .last()
            .copied()
            .unwrap_or(1.0)
            .max(degrees.first().copied().unwrap_or(0.0) + 1.0),
    );
    let error_at = |m: &super::Measurement, i: usize| {
        clamp(
            m.errors[i][..=m.order.min(PARETO_ORDER)]
                .iter()
                .fold(0.0, |a: f64, &b| a.max(b)),
        )
    };
    let (e0, e1) = bounds(
        report
            .measurements
            .iter()
            .flat_map(|m| (0..m.errors.len()).map(move |i| error_at(m, i)))
            .chain([EPSILON]),
    );
    let mut chart = ChartBuilder::on(area)
        .caption(
            "scaled error (max of value, ′, ″) vs drive",
            ("sans-serif", 16),
        )
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(x0..x1, (e0..e1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("drive position φ [°]")
        .y_desc("scaled error")
        .draw()?;
    for (k, m) in report.measurements.iter().enumerate() {
        let color = Palette99::pick(k);
        chart
            .draw_series(LineSeries::new(
                degrees
                    .iter()
                    .enumerate()
                    .map(|(i, &d)| (d, error_at(m, i))),
                &color,
            ))?
            .label(m.name.clone())
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 15, y)], Palette99::pick(k)));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .label_font(("sans-serif", 9))
        .draw()?;
    Ok(())
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
