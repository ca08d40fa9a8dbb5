//! Rows as text, fast: CSV and JSON Lines with the shortest digits that read back to the
//! same `f64` (the Żmij algorithm of the `zmij` crate), and the streamed table's fixed-width
//! scientific columns.

use std::fmt::Write as _;

use crate::scene::outputs::Column;
use crate::scene::table::DIGITS;

/// The width of a number in the streamed table: `-d.dddddddde-308`, the longest an `f64`
/// prints in scientific notation with [`DIGITS`] significant digits.
pub const SCIENTIFIC_WIDTH: usize = DIGITS as usize + 7;

/// Appends `value` as Rust's `Display` prints it (`1`, `0.5`, `0.0000001`, never an
/// exponent), the digits being the shortest that read back to the same number. `-0` is
/// written `0`. `value` must be finite.
pub fn push_display(value: f64, out: &mut Vec<u8>) {
    let mut buffer = zmij::Buffer::new();
    let text = buffer.format_finite(value + 0.0);
    let (negative, text) = match text.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, text),
    };
    let (mantissa, exponent) = match text.split_once(['e', 'E']) {
        Some((m, e)) => (m, e.parse::<i32>().unwrap_or(0)),
        None => (text, 0),
    };
    // The significant digits and where the decimal point falls among them.
    let (whole, fraction) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let mut point = whole.len() as i32 + exponent;
    let mut digits: Vec<u8> = whole.bytes().chain(fraction.bytes()).collect();
    let leading = digits.iter().take_while(|&&d| d == b'0').count();
    digits.drain(..leading);
    point -= leading as i32;
    while digits.last() == Some(&b'0') {
        digits.pop();
    }
    if digits.is_empty() {
        out.push(b'0');
        return;
    }
    if negative {
        out.push(b'-');
    }
    let n = digits.len() as i32;
    if point <= 0 {
        out.extend_from_slice(b"0.");
        out.extend(std::iter::repeat_n(b'0', (-point) as usize));
        out.extend_from_slice(&digits);
    } else if point >= n {
        out.extend_from_slice(&digits);
        out.extend(std::iter::repeat_n(b'0', (point - n) as usize));
    } else {
        out.extend_from_slice(&digits[..point as usize]);
        out.push(b'.');
        out.extend_from_slice(&digits[point as usize..]);
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

    /// The CSV line of a row: every value with the digits of [`push_display`].
    pub fn csv(&self, row: &[f64], out: &mut Vec<u8>) {
        for (k, (v, factor)) in row.iter().zip(&self.factors).enumerate() {
            if k > 0 {
                out.push(b',');
            }
            push_display(v / factor, out);
        }
        out.push(b'\n');
    }

    /// The JSON Lines record of a row: `{"name [unit]":value,...}`, the shortest digits.
    pub fn jsonl(&self, row: &[f64], out: &mut Vec<u8>) {
        let mut buffer = zmij::Buffer::new();
        for ((v, factor), key) in row.iter().zip(&self.factors).zip(&self.keys) {
            out.extend_from_slice(key.as_bytes());
            out.extend_from_slice(buffer.format_finite(v / factor + 0.0).as_bytes());
        }
        out.extend_from_slice(b"}\n");
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

    /// The streamed table's line of a row: every value in scientific notation with
    /// [`DIGITS`] significant digits, right-aligned in its column's fixed width.
    pub fn table(&self, row: &[f64], out: &mut String) {
        for (k, ((v, factor), &w)) in row.iter().zip(&self.factors).zip(&self.widths).enumerate()
        {
            if k > 0 {
                out.push_str("  ");
            }
            let _ = write!(out, "{:>w$.*e}", (DIGITS - 1) as usize, v / factor + 0.0);
        }
        out.push('\n');
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn display(v: f64) -> String {
        let mut out = Vec::new();
        push_display(v, &mut out);
        String::from_utf8(out).unwrap()
    }

    /// The edges of the layout: integers, exponents far out either way, negative zero.
    #[test]
    fn display_digits_match_the_standard_library_at_the_edges() {
        for v in [
            0.0,
            -0.0,
            1.0,
            -1.5,
            100.0,
            0.1,
            1e-7,
            -2.5e-8,
            123_456_789.125,
            1e15,
            1e16,
            1.7976931348623157e308,
            5e-324,
            f64::MIN_POSITIVE,
            0.30000000000000004,
        ] {
            assert_eq!(display(v), (v + 0.0).to_string(), "{v:e}");
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4096))]
        /// Any finite `f64` prints as `Display` prints it: same shortest digits, same layout.
        #[test]
        fn display_digits_match_the_standard_library(bits in any::<u64>()) {
            let v = f64::from_bits(bits);
            prop_assume!(v.is_finite());
            prop_assert_eq!(display(v), (v + 0.0).to_string());
        }
    }
}
