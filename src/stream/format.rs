//! Rows as text, fast: CSV and JSON Lines with the shortest digits that read back to the
//! same `f64` (the Żmij algorithm of the `zmij` crate), and the streamed table's fixed-width
//! scientific columns.

use super::scientific::scientific;
use super::shortest::display_then;
use crate::scene::outputs::Column;

pub use super::scientific::{DIGITS, SCIENTIFIC_WIDTH, push_scientific, push_scientific_signed};
pub use super::shortest::push_display;

/// Which texts rows are written into.
#[derive(Debug, Clone, Copy)]
pub struct Wanted {
    /// The streamed table.
    pub table: bool,
    /// CSV.
    pub csv: bool,
    /// JSON Lines.
    pub jsonl: bool,
}

/// The text of some rows, one buffer per output (kept and reused from batch to batch).
#[derive(Debug, Default)]
pub struct Texts {
    /// The streamed table's lines.
    pub table: Vec<u8>,
    /// CSV lines.
    pub csv: Vec<u8>,
    /// JSON Lines records.
    pub jsonl: Vec<u8>,
}

impl Texts {
    /// Empties every buffer, keeping its memory.
    pub fn clear(&mut self) {
        self.table.clear();
        self.csv.clear();
        self.jsonl.clear();
    }
}

/// How rows become text, one writer per output; the values of a row are in SI and printed
/// in the columns' units.
#[derive(Debug, Clone)]
pub struct RowFormat {
    /// Per column: the SI value per printed unit.
    factors: Vec<f64>,
    /// Per column: `"name [unit]":` as a JSON key, the first with its `{`.
    keys: Vec<String>,
    /// Per column: the streamed table's width.
    widths: Vec<usize>,
}

impl RowFormat {
    /// The format of rows with these columns.
    pub fn new(columns: &[Column]) -> Self {
        let keys = (columns.iter().enumerate())
            .map(|(k, c)| {
                let key = serde_json::Value::String(c.header()).to_string();
                format!("{}{key}:", if k == 0 { "{" } else { "," })
            })
            .collect();
        let widths = (columns.iter())
            .map(|c| {
                let unit = c.unit.chars().count() + 2;
                SCIENTIFIC_WIDTH.max(c.name.chars().count()).max(unit)
            })
            .collect();
        Self {
            factors: columns.iter().map(|c| c.factor).collect(),
            keys,
            widths,
        }
    }

    /// The number of columns.
    pub fn columns(&self) -> usize {
        self.factors.len()
    }

    /// The lines of a row in every text `wanted`, appended to `texts`: the CSV line (every
    /// value with the digits of [`push_display`]), the JSON Lines record
    /// (`{"name [unit]":value,...}`, Żmij's shortest digits) and the streamed table's line
    /// (every value as [`push_scientific`] writes it, right-aligned in its column's fixed
    /// width). Each value is formatted by Żmij at most once, for CSV and JSON Lines both;
    /// which texts are written is decided once per row, not per value.
    pub fn row(&self, row: &[f64], wanted: Wanted, texts: &mut Texts) {
        match (wanted.csv, wanted.jsonl) {
            (true, false) => self.csv_line(row, &mut texts.csv),
            (false, false) => {}
            (csv, jsonl) => self.shortest_lines(row, csv, jsonl, texts),
        }
        if wanted.table {
            self.table_line(row, &mut texts.table);
        }
    }

    /// A row's CSV line alone (the usual case): per value Żmij's text, laid out by
    /// [`display_then`] with the comma that follows it.
    fn csv_line(&self, row: &[f64], out: &mut Vec<u8>) {
        let mut buffer = zmij::Buffer::new();
        for (v, factor) in row.iter().zip(&self.factors) {
            let value = v / factor + 0.0;
            display_then(value, buffer.format_finite(value).as_bytes(), b',', out);
        }
        end_csv_line(row.is_empty(), out);
    }

    /// A row's JSON Lines record, and its CSV line if `csv`, from one Żmij text per value.
    fn shortest_lines(&self, row: &[f64], csv: bool, jsonl: bool, texts: &mut Texts) {
        let mut buffer = zmij::Buffer::new();
        for ((v, factor), key) in row.iter().zip(&self.factors).zip(&self.keys) {
            let value = v / factor + 0.0;
            let text = buffer.format_finite(value).as_bytes();
            if csv {
                display_then(value, text, b',', &mut texts.csv);
            }
            if jsonl {
                texts.jsonl.extend_from_slice(key.as_bytes());
                texts.jsonl.extend_from_slice(text);
            }
        }
        if csv {
            end_csv_line(row.is_empty(), &mut texts.csv);
        }
        if jsonl {
            texts.jsonl.extend_from_slice(b"}\n");
        }
    }

    /// A row's line of the streamed table: every value in scientific notation, right-aligned
    /// in its column, two spaces between columns.
    fn table_line(&self, row: &[f64], out: &mut Vec<u8>) {
        let columns = row.iter().zip(&self.factors).zip(&self.widths);
        for (k, ((v, factor), &width)) in columns.enumerate() {
            if k > 0 {
                out.extend_from_slice(b"  ");
            }
            scientific(v / factor + 0.0, width, out);
        }
        out.push(b'\n');
    }

    /// The two header lines of the streamed table: names, then units in brackets, each
    /// right-aligned in its column.
    pub fn table_header(&self, columns: &[Column], out: &mut String) {
        let line = |out: &mut String, cell: &dyn Fn(&Column) -> String| {
            let cells: Vec<String> = (columns.iter().zip(&self.widths))
                .map(|(c, &w)| format!("{:>w$}", cell(c)))
                .collect();
            out.push_str(cells.join("  ").trim_end());
            out.push('\n');
        };
        line(out, &|c| c.name.clone());
        line(out, &|c| format!("[{}]", c.unit));
    }
}

/// Ends a CSV line whose every cell was written with its comma: the last comma becomes
/// the line's end (a row of no columns, `empty`, is an empty line).
fn end_csv_line(empty: bool, out: &mut Vec<u8>) {
    match out.last_mut() {
        Some(last) if !empty => *last = b'\n',
        _ => out.push(b'\n'),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4096))]
        /// A row's three texts, against the standard library cell by cell: CSV as `Display`
        /// prints each value, the streamed table as `{:.8e}` right-aligned in its width, and
        /// JSON Lines reading back as the same numbers under the CSV's headers.
        #[test]
        fn a_row_is_written_as_the_standard_library_writes_each_value(
            row in proptest::collection::vec(-1e7f64..1e7, 3),
            scale in -12i32..12,
            wanted in (any::<bool>(), any::<bool>(), any::<bool>()),
        ) {
            let columns = [("phi", "deg", 0.017453292519943295), ("s", "mm", 1e-3), ("F,x", "N", 1.0)]
                .map(|(name, unit, factor)| Column { name: name.into(), unit: unit.into(), factor });
            let row: Vec<f64> = row.iter().map(|v| v * 10f64.powi(scale)).collect();
            let (table, csv, jsonl) = wanted;
            let mut texts = Texts::default();
            RowFormat::new(&columns).row(&row, Wanted { table, csv, jsonl }, &mut texts);
            let values: Vec<f64> = (row.iter().zip(&columns)).map(|(v, c)| v / c.factor + 0.0).collect();
            let csv_line = values.iter().map(f64::to_string).collect::<Vec<_>>().join(",") + "\n";
            prop_assert_eq!(String::from_utf8(texts.csv).unwrap(), if csv { csv_line } else { String::new() });
            let table_line = (values.iter())
                .map(|v| format!("{v:>SCIENTIFIC_WIDTH$.8e}"))
                .collect::<Vec<_>>()
                .join("  ")
                + "\n";
            prop_assert_eq!(String::from_utf8(texts.table).unwrap(), if table { table_line } else { String::new() });
            if jsonl {
                let record: serde_json::Map<String, serde_json::Value> =
                    serde_json::from_slice(&texts.jsonl).unwrap();
                for (c, v) in columns.iter().zip(&values) {
                    prop_assert_eq!(record[&c.header()].as_f64(), Some(*v));
                }
            } else {
                prop_assert!(texts.jsonl.is_empty());
            }
        }
    }
}
