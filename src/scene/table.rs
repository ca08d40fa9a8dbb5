//! Printing a [`Report`]: the aligned table, the dead positions, and CSV.

use std::io::{self, Write};

use super::model::Scene;
use super::outputs::Column;
use super::run::Report;
use super::units::Units;
use crate::stream::fixed::push_fixed;
use crate::stream::format::{RowFormat, Texts, Wanted, push_scientific_signed};

pub use crate::stream::format::DIGITS;

/// How every number of one column is printed, so that the decimal points line up.
#[derive(Clone, Copy, Debug, PartialEq)]
enum ColumnFormat {
    /// Fixed point with this many decimals.
    Fixed(usize),
    /// Scientific notation with [`DIGITS`] significant digits.
    Scientific,
}

impl ColumnFormat {
    /// The format for a column of values: fixed point with [`DIGITS`] significant digits for
    /// its largest magnitude when that lies between 1e-3 and 1e6, scientific otherwise. A
    /// column of exact multiples of a round step (the drive positions) gets only the decimals
    /// it needs.
    fn for_column(values: &[f64]) -> Self {
        let largest = values
            .iter()
            .filter(|v| v.is_finite())
            .fold(0.0_f64, |m, v| m.max(v.abs()));
        if largest == 0.0 {
            return Self::Fixed(0);
        }
        let magnitude = largest.log10().floor() as i32;
        if !(-3..6).contains(&magnitude) {
            return Self::Scientific;
        }
        let decimals = (DIGITS - 1 - magnitude).max(0) as usize;
        let exact = (0..decimals).find(|&d| {
            let scale = 10f64.powi(d as i32);
            values
                .iter()
                .all(|v| ((v * scale).round() / scale - v).abs() <= 1e-12 * largest)
        });
        Self::Fixed(exact.unwrap_or(decimals))
    }

    /// Appends `v` in this format: fixed point as [`crate::report::fixed`] prints it,
    /// scientific as `format!("{v:.8e}")` does, a non-finite value as `Display` does; each
    /// number formatted once, straight into `out`.
    fn push(self, v: f64, out: &mut Vec<u8>) {
        match self {
            _ if !v.is_finite() => out.extend_from_slice(v.to_string().as_bytes()),
            Self::Fixed(decimals) => push_fixed(v, decimals, out),
            Self::Scientific => push_scientific_signed(v, out),
        }
    }

    #[cfg(test)]
    fn format(self, v: f64) -> String {
        let mut out = Vec::new();
        self.push(v, &mut out);
        String::from_utf8(out).expect("numbers are ASCII")
    }
}

/// Writes the title, the plan and the table: a header of column names, a header of units,
/// then one line per drive position; each column has one number format, right-aligned.
pub fn write_table(scene: &Scene, report: &Report, out: &mut impl Write) -> io::Result<()> {
    if let Some(title) = &scene.title {
        writeln!(out, "{title}")?;
    }
    writeln!(out, "{}", report.plan.describe(scene))?;
    write_rows(&report.columns, &report.rows, out)?;
    write_after_rows(scene, report, out)
}

/// The table's two header lines and its rows (values in SI, printed in the columns' units):
/// each column in the format its values need ([`ColumnFormat::for_column`]), right-aligned in
/// the width of its widest cell, two spaces between columns. Every number is formatted once
/// into one buffer of cells, then laid out; the text is written in blocks of 64 KiB.
fn write_rows(columns: &[Column], rows: &[Vec<f64>], out: &mut impl Write) -> io::Result<()> {
    let mut values = Vec::with_capacity(rows.len());
    let formats: Vec<ColumnFormat> = (columns.iter().enumerate())
        .map(|(k, c)| {
            values.clear();
            values.extend(rows.iter().map(|row| row[k] / c.factor));
            ColumnFormat::for_column(&values)
        })
        .collect();
    let mut widths: Vec<usize> = (columns.iter())
        .map(|c| (c.name.chars().count()).max(c.unit.chars().count() + 2))
        .collect();
    // The cells of every row, one after the other, and where each ends (numbers are ASCII:
    // their bytes are their characters).
    let mut cells = Vec::new();
    let mut ends = Vec::with_capacity(rows.len() * columns.len());
    for row in rows {
        for (k, ((v, c), format)) in row.iter().zip(columns).zip(&formats).enumerate() {
            let start = cells.len();
            format.push(v / c.factor, &mut cells);
            ends.push(cells.len());
            widths[k] = widths[k].max(cells.len() - start);
        }
    }
    let header = |cell: &dyn Fn(&Column) -> String| {
        let cells: Vec<String> = (columns.iter().zip(&widths))
            .map(|(c, &w)| format!("{:>w$}", cell(c)))
            .collect();
        format!("{}\n", cells.join("  ").trim_end())
    };
    let mut text = header(&|c| c.name.clone()).into_bytes();
    text.extend_from_slice(header(&|c| format!("[{}]", c.unit)).as_bytes());
    let mut start = 0;
    for r in 0..rows.len() {
        let row = &ends[r * columns.len()..(r + 1) * columns.len()];
        for (k, (&end, &width)) in row.iter().zip(&widths).enumerate() {
            if k > 0 {
                text.extend_from_slice(b"  ");
            }
            text.resize(text.len() + width - (end - start), b' ');
            text.extend_from_slice(&cells[start..end]);
            start = end;
        }
        text.push(b'\n');
        if text.len() >= 1 << 16 {
            out.write_all(&text)?;
            text.clear();
        }
    }
    out.write_all(&text)
}

/// Writes what follows the table's rows: the dead positions ([`write_dead_positions`]),
/// the dynamics' summary lines and the balancing answers.
pub fn write_after_rows(scene: &Scene, report: &Report, out: &mut impl Write) -> io::Result<()> {
    write_dead_positions(scene, report, out)?;
    for line in report.dynamics.iter().flat_map(|d| &d.summary) {
        writeln!(out, "{line}")?;
    }
    for line in report.balancing.iter().flat_map(|b| &b.lines) {
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
    if !report.limits.is_empty() {
        writeln!(out)?;
        writeln!(
            out,
            "the sweep reaches the end of the drive's motion range (walked from the sketch):"
        )?;
        for line in super::describe::limit_lines(scene, &report.limits) {
            writeln!(out, "{line}")?;
        }
    }
    Ok(())
}

/// Writes the report as CSV: a header `name [unit]` per column, then every value in the
/// scene's units with all the digits of an `f64` (shortest representation that reads back
/// to the same number).
pub fn write_csv(report: &Report, out: &mut impl Write) -> io::Result<()> {
    let header = crate::stream::record::csv_record(report.columns.iter().map(|c| c.header()));
    out.write_all(header.as_bytes())?;
    let format = RowFormat::new(&report.columns);
    let wanted = Wanted {
        table: false,
        csv: true,
        jsonl: false,
    };
    let mut texts = Texts::default();
    for row in &report.rows {
        texts.clear();
        format.row(row, wanted, &mut texts);
        out.write_all(&texts.csv)?;
    }
    Ok(())
}

/// Writes the report's rows as JSON Lines: one object per drive position keyed by the CSV's
/// headers, every value in the scene's units with the shortest digits that read back.
pub fn write_jsonl(report: &Report, out: &mut impl Write) -> io::Result<()> {
    let format = RowFormat::new(&report.columns);
    let wanted = Wanted {
        table: false,
        csv: false,
        jsonl: true,
    };
    let mut texts = Texts::default();
    for row in &report.rows {
        texts.clear();
        format.row(row, wanted, &mut texts);
        out.write_all(&texts.jsonl)?;
    }
    Ok(())
}

/// Writes the report as JSON: `{"columns": [{"name", "unit"}], "rows": [[...]], "dead_positions":
/// [{"output", "phi", "value"}], "limits": [{"phi", "kind", "joints"}]}`, every value in the scene's units with all the digits of an
/// `f64`; a non-finite value is written as `null`.
pub fn write_json(scene: &Scene, report: &Report, out: &mut impl Write) -> io::Result<()> {
    write_json_with(scene, report, None, out)
}

/// [`write_json`] with the scene's linkage metrics under `"metrics"` (see
/// [`super::metrics::SceneMetrics::json`]) when it has some.
pub fn write_json_with(
    scene: &Scene,
    report: &Report,
    metrics: Option<&super::metrics::SceneMetrics>,
    out: &mut impl Write,
) -> io::Result<()> {
    let columns: Vec<_> = (report.columns.iter())
        .map(|c| serde_json::json!({"name": c.name, "unit": c.unit}))
        .collect();
    let rows: Vec<Vec<f64>> = (report.rows.iter())
        .map(|row| {
            row.iter()
                .zip(&report.columns)
                .map(|(v, c)| v / c.factor + 0.0)
                .collect()
        })
        .collect();
    let u = scene.units.for_outputs();
    let drive = scene.drive.kind.dimension();
    let dead: Vec<_> = (report.dead_positions.iter())
        .flat_map(|d| d.positions.iter().map(move |p| (d, p)))
        .map(|(d, p)| {
            serde_json::json!({
                "output": d.output,
                "phi": scene.units.from_si(p.phi, drive),
                "value": u.from_si(p.value, d.dimension),
                "unit": u.symbol(d.dimension),
            })
        })
        .collect();
    let limits: Vec<_> = (report.limits.iter())
        .map(|l| {
            serde_json::json!({
                "phi": scene.units.from_si(l.limit.phi, drive),
                "kind": super::sweep_limits::kind_words(l.limit.kind),
                "joints": l.limit.joints,
            })
        })
        .collect();
    let mut value = serde_json::json!({
        "columns": columns, "rows": rows, "dead_positions": dead, "limits": limits
    });
    if let Some(metrics) = metrics {
        value["metrics"] = metrics.json(scene);
    }
    serde_json::to_writer(&mut *out, &value)?;
    writeln!(out)
}

#[cfg(test)]
mod tests {
    use super::{Column, ColumnFormat, write_rows};
    use crate::report::Table;
    use proptest::prelude::*;

    /// Nine significant digits for the column's largest value, the same decimals in every row.
    #[test]
    fn a_column_shares_one_format() {
        let f = ColumnFormat::for_column(&[67.975_687_162_957_8, -0.5, 0.0]);
        assert_eq!(f, ColumnFormat::Fixed(7));
        assert_eq!(f.format(-0.5), "-0.5000000");
        assert_eq!(f.format(-1e-9), "0.0000000");
    }

    /// Drive positions at a round step print without trailing zeros.
    #[test]
    fn round_steps_need_no_decimals() {
        assert_eq!(
            ColumnFormat::for_column(&[0.0, 5.0, 360.0]),
            ColumnFormat::Fixed(0)
        );
        assert_eq!(
            ColumnFormat::for_column(&[0.0, 0.5, 1.0]),
            ColumnFormat::Fixed(1)
        );
    }

    /// Magnitudes of 1e6 and more (or below 1e-3) are printed in scientific notation.
    #[test]
    fn large_columns_are_scientific() {
        let f = ColumnFormat::for_column(&[3.085e6, -1.0]);
        assert_eq!(f, ColumnFormat::Scientific);
        assert_eq!(f.format(3.085e6), "3.08500000e6");
    }

    /// The table as it was printed before its cells were written straight into one buffer:
    /// one `String` per cell from the standard library's formatting
    /// (`{:.N}` less the sign of a zero, `{:.8e}`, `Display`), aligned by [`Table`].
    fn reference(columns: &[Column], rows: &[Vec<f64>]) -> Vec<u8> {
        let scaled: Vec<Vec<f64>> = (rows.iter())
            .map(|row| row.iter().zip(columns).map(|(v, c)| v / c.factor).collect())
            .collect();
        let formats: Vec<ColumnFormat> = (0..columns.len())
            .map(|k| ColumnFormat::for_column(&scaled.iter().map(|r| r[k]).collect::<Vec<_>>()))
            .collect();
        let mut table = Table::new(0, columns.iter().map(|c| c.name.clone()).collect());
        table.row(columns.iter().map(|c| format!("[{}]", c.unit)).collect());
        for row in &scaled {
            table.row(
                (row.iter().zip(&formats))
                    .map(|(&v, f)| match f {
                        _ if !v.is_finite() => v.to_string(),
                        ColumnFormat::Fixed(d) => crate::report::fixed(v, *d),
                        ColumnFormat::Scientific => format!("{v:.8e}"),
                    })
                    .collect(),
            );
        }
        table.render().into_bytes()
    }

    /// A column's value of kind `kind` from random `bits`: round steps (fixed point with few
    /// decimals), magnitudes 1e-6…1e8 (fixed point or scientific), any finite `f64`
    /// (mostly scientific), or zero of either sign.
    fn value(kind: u8, bits: u64, exponent: i32) -> f64 {
        match kind {
            0 => (bits % 4001) as f64 * 0.25 - 500.0,
            1 => {
                let unit = (bits >> 11) as f64 / (1u64 << 53) as f64;
                (2.0 * unit - 1.0) * 10f64.powi(exponent)
            }
            2 => Some(f64::from_bits(bits))
                .filter(|v| v.is_finite())
                .unwrap_or(1.0),
            _ if bits.is_multiple_of(2) => -0.0,
            _ => 0.0,
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]
        /// Random tables (up to 5 columns of mixed kinds, units with factors, up to 40 rows,
        /// names wider or narrower than the numbers, non-ASCII units): the same bytes as
        /// the table of `String` cells.
        #[test]
        fn rows_print_as_the_table_of_string_cells(
            kinds in prop::collection::vec((0u8..4, 0usize..3, -6i32..9), 1..6),
            cells in prop::collection::vec(any::<u64>(), 0..200),
        ) {
            let factors = [1.0, std::f64::consts::PI / 180.0, 1e-3];
            let columns: Vec<Column> = (kinds.iter().enumerate())
                .map(|(k, &(_, f, _))| Column {
                    name: ["phi", "a_very_long_column_name", "ẍ"][k % 3].to_owned(),
                    unit: ["deg", "mm/s²", "m"][f].to_owned(),
                    factor: factors[f],
                })
                .collect();
            let rows: Vec<Vec<f64>> = (cells.chunks_exact(columns.len()))
                .map(|row| {
                    (row.iter().zip(&kinds))
                        .map(|(&bits, &(kind, f, e))| value(kind, bits, e) * factors[f])
                        .collect()
                })
                .collect();
            let mut out = Vec::new();
            write_rows(&columns, &rows, &mut out).unwrap();
            prop_assert_eq!(String::from_utf8(out).unwrap(),
                String::from_utf8(reference(&columns, &rows)).unwrap());
        }
    }
}
