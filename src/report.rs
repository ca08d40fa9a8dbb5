//! Plain-text reports the `mechdiff` command prints: tables with units and aligned columns.

pub mod cam;
pub mod rotor;
pub mod whitworth;

/// A text table: a header row and data rows, the first `labels` columns left-aligned (names,
/// units), the others right-aligned (numbers), columns separated by two spaces.
#[derive(Clone, Debug, Default)]
pub struct Table {
    labels: usize,
    rows: Vec<Vec<String>>,
}

impl Table {
    /// A table whose first `labels` columns are labels; `header` is its first row.
    pub fn new(labels: usize, header: Vec<String>) -> Self {
        Self {
            labels,
            rows: vec![header],
        }
    }

    /// Appends a row.
    pub fn row(&mut self, cells: Vec<String>) {
        self.rows.push(cells);
    }

    /// The table as lines of text, each ending in a newline.
    pub fn render(&self) -> String {
        let columns = self.rows.iter().map(Vec::len).max().unwrap_or(0);
        let width: Vec<usize> = (0..columns)
            .map(|c| {
                let cells = self.rows.iter().filter_map(|r| r.get(c));
                cells.map(|s| s.chars().count()).max().unwrap_or(0)
            })
            .collect();
        let mut out = String::new();
        for row in &self.rows {
            let cells: Vec<String> = row
                .iter()
                .enumerate()
                .map(|(c, cell)| {
                    if c < self.labels {
                        format!("{cell:<w$}", w = width[c])
                    } else {
                        format!("{cell:>w$}", w = width[c])
                    }
                })
                .collect();
            out.push_str(cells.join("  ").trim_end());
            out.push('\n');
        }
        out
    }
}

/// `value` with `decimals` decimals, without a minus sign on a value that rounds to zero.
pub fn fixed(value: f64, decimals: usize) -> String {
    let text = format!("{value:.decimals$}");
    match text.strip_prefix('-') {
        Some(digits) if digits.chars().all(|c| c == '0' || c == '.') => digits.to_string(),
        _ => text,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Labels left, numbers right, widths from the widest cell (counted in characters, so
    /// "ẍ_S1" is 4 wide).
    #[test]
    fn columns_are_aligned() {
        let mut table = Table::new(1, vec!["q".into(), "value".into()]);
        table.row(vec!["ẍ_S1".into(), "1.5".into()]);
        assert_eq!(table.render(), "q     value\nẍ_S1    1.5\n");
    }

    /// −0.0001 to three decimals prints as 0.000, not −0.000.
    #[test]
    fn negative_zero_is_printed_without_sign() {
        assert_eq!(fixed(-0.0001, 3), "0.000");
        assert_eq!(fixed(-0.0006, 3), "-0.001");
    }
}
