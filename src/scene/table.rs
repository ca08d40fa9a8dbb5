//! Printing a [`Report`]: the aligned table, the dead positions, and CSV.

use std::io::{self, Write};

use super::model::Scene;
use super::run::Report;
use super::units::Units;

/// Significant digits in the printed table (the CSV carries every digit).
const DIGITS: usize = 9;

/// A number with 9 significant digits: fixed-point for magnitudes from 1e-3 to 1e6,
/// scientific otherwise.
pub fn format_number(v: f64) -> String {
    if v == 0.0 {
        return "0".to_owned();
    }
    if !v.is_finite() {
        return v.to_string();
    }
    let magnitude = v.abs().log10().floor() as i32;
    if (-3..6).contains(&magnitude) {
        let decimals = (DIGITS as i32 - 1 - magnitude).max(0) as usize;
        format!("{v:.decimals$}")
    } else {
        format!("{v:.*e}", DIGITS - 1)
    }
}

/// Writes the title, the plan and the table: a header of column names, a header of units,
/// then one line per drive position, every column right-aligned.
pub fn write_table(scene: &Scene, report: &Report, out: &mut impl Write) -> io::Result<()> {
    if let Some(title) = &scene.title {
        writeln!(out, "{title}")?;
    }
    writeln!(out, "{}", report.plan.describe(scene))?;
    let cells: Vec<Vec<String>> = report
        .rows
        .iter()
        .map(|row| {
            row.iter()
                .zip(&report.columns)
                .map(|(v, c)| format_number(v / c.factor))
                .collect()
        })
        .collect();
    let widths: Vec<usize> = report
        .columns
        .iter()
        .enumerate()
        .map(|(k, c)| {
            let header = c.name.chars().count().max(c.unit.chars().count() + 2);
            cells.iter().map(|r| r[k].len()).fold(header, usize::max)
        })
        .collect();
    let line = |items: Vec<String>| -> String {
        items
            .iter()
            .zip(&widths)
            .map(|(s, w)| format!("{s:>w$}"))
            .collect::<Vec<_>>()
            .join("  ")
    };
    writeln!(
        out,
        "{}",
        line(report.columns.iter().map(|c| c.name.clone()).collect())
    )?;
    writeln!(
        out,
        "{}",
        line(
            report
                .columns
                .iter()
                .map(|c| format!("[{}]", c.unit))
                .collect()
        )
    )?;
    for row in cells {
        writeln!(out, "{}", line(row))?;
    }
    write_dead_positions(scene, report, out)?;
    for line in report.dynamics.iter().flat_map(|d| &d.summary) {
        writeln!(out, "{line}")?;
    }
    Ok(())
}

/// Writes the dead positions found and the stroke between them, to 15 significant digits.
pub fn write_dead_positions(
    scene: &Scene,
    report: &Report,
    out: &mut impl Write,
) -> io::Result<()> {
    let u = &scene.units.for_outputs();
    for dead in &report.dead_positions {
        let unit = u.symbol(dead.dimension);
        writeln!(out)?;
        if dead.positions.is_empty() {
            writeln!(
                out,
                "{}: no dead position in the sweep's range ({}' keeps its sign)",
                dead.output, dead.output
            )?;
            continue;
        }
        writeln!(
            out,
            "dead positions of {} (where {}' changes sign, found numerically):",
            dead.output, dead.output
        )?;
        for d in &dead.positions {
            let kind = if d.d2 < 0.0 { "maximum" } else { "minimum" };
            writeln!(
                out,
                "  phi = {}: {} = {} {unit} ({kind})",
                scene.drive_text(d.phi),
                dead.output,
                Units::tidy(u.from_si(d.value, dead.dimension)),
            )?;
        }
        if let Some(stroke) = dead.stroke() {
            let stroke = Units::tidy(u.from_si(stroke, dead.dimension));
            writeln!(out, "stroke of {}: {stroke} {unit}", dead.output)?;
        }
    }
    Ok(())
}

/// Writes the report as CSV: a header `name [unit]` per column, then every value in the
/// scene's units with all the digits of an `f64` (shortest representation that reads back
/// to the same number).
pub fn write_csv(report: &Report, out: &mut impl Write) -> io::Result<()> {
    let header: Vec<String> = report.columns.iter().map(|c| c.header()).collect();
    writeln!(out, "{}", header.join(","))?;
    for row in &report.rows {
        let cells: Vec<String> = row
            .iter()
            .zip(&report.columns)
            .map(|(v, c)| (v / c.factor + 0.0).to_string())
            .collect();
        writeln!(out, "{}", cells.join(","))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::format_number;

    #[test]
    fn numbers_keep_nine_significant_digits() {
        assert_eq!(format_number(0.0), "0");
        assert_eq!(format_number(67.975_687_162_957_8), "67.9756872");
        assert_eq!(format_number(-0.000123456789123), "-1.23456789e-4");
        assert_eq!(format_number(0.00123456789123), "0.00123456789");
        assert_eq!(format_number(123456.789), "123456.789");
        assert_eq!(format_number(1234567.89), "1.23456789e6");
    }
}
