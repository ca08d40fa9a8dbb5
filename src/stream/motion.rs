//! The rows of the machine in motion, streamed: the table over time (start-up, coast-down)
//! and the table over the drive angle (the steady state) go to their outputs row by row as
//! the integration gives them, so memory stays flat in the simulated time and turns.

use std::io;
use std::path::PathBuf;

use crate::error::{Error, Result};
use crate::scene::Column;

use super::Sink;
use super::format::{RowFormat, Texts, Wanted};
use super::record;

/// The outputs of a run with `[simulate]`; each is optional.
#[derive(Default)]
pub struct MotionSinks<'a> {
    /// The terminal: the plan, each table with fixed-width scientific columns, and the
    /// analyses' headline numbers. A reader that goes away ends the table, not the run.
    pub table: Option<Sink<'a>>,
    /// CSV of the motion in time: the header `name [unit]` per column, then every row.
    pub time_csv: Option<Sink<'a>>,
    /// CSV of the steady state over the drive angle, as `time_csv`.
    pub steady_csv: Option<Sink<'a>>,
}

impl MotionSinks<'_> {
    /// Writes `text` to the terminal; a reader that went away ends the terminal output.
    pub(crate) fn say(&mut self, text: &str) -> Result<()> {
        let Some(sink) = &mut self.table else {
            return Ok(());
        };
        match sink.out.write_all(text.as_bytes()) {
            Err(e) if e.kind() == io::ErrorKind::BrokenPipe => {
                self.table = None;
                Ok(())
            }
            result => result.map_err(|source| Error::Write {
                path: sink.path.clone(),
                source,
            }),
        }
    }
}

/// Which table of a run with `[simulate]` rows go to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Table {
    /// Over time.
    Time,
    /// The steady state over the drive angle.
    Steady,
}

/// One table's rows written as they come: formatted once per row for the terminal and the
/// table's CSV, nothing kept.
pub struct Rows {
    format: RowFormat,
    texts: Texts,
    table: Table,
    /// Rows written so far.
    pub written: usize,
}

impl Rows {
    /// Starts `table` with `columns`: its title and header lines on the terminal, its CSV
    /// header.
    ///
    /// # Errors
    /// [`Error::Write`] naming the output that failed.
    pub fn start(
        sinks: &mut MotionSinks<'_>,
        table: Table,
        title: &str,
        columns: &[Column],
    ) -> Result<Self> {
        let format = RowFormat::new(columns);
        let mut head = format!("\n{title}\n");
        format.table_header(columns, &mut head);
        sinks.say(&head)?;
        if let Some(csv) = Self::csv(sinks, table) {
            let header = record::csv_record(columns.iter().map(Column::header));
            csv.write(header.as_bytes())?;
        }
        Ok(Rows {
            format,
            texts: Texts::default(),
            table,
            written: 0,
        })
    }

    fn csv<'s, 'a>(sinks: &'s mut MotionSinks<'a>, table: Table) -> Option<&'s mut Sink<'a>> {
        match table {
            Table::Time => sinks.time_csv.as_mut(),
            Table::Steady => sinks.steady_csv.as_mut(),
        }
    }

    /// Writes one row (SI values, in the columns' order) to the terminal and the CSV.
    ///
    /// # Errors
    /// [`Error::Write`] naming the output that failed.
    pub fn row(&mut self, sinks: &mut MotionSinks<'_>, row: &[f64]) -> Result<()> {
        let wanted = Wanted {
            table: sinks.table.is_some(),
            csv: Self::csv(sinks, self.table).is_some(),
            jsonl: false,
        };
        self.texts.clear();
        self.format.row(row, wanted, &mut self.texts);
        if wanted.table {
            let text = std::mem::take(&mut self.texts.table);
            let result = sinks.say(std::str::from_utf8(&text).unwrap_or_default());
            self.texts.table = text;
            result?;
        }
        if let Some(csv) = Self::csv(sinks, self.table) {
            csv.write(&self.texts.csv)?;
        }
        self.written += 1;
        Ok(())
    }
}

/// The CSV file of the steady state beside the time table's `path`: `run.csv` →
/// `run_steady.csv`.
pub fn steady_path(path: &std::path::Path) -> PathBuf {
    let stem = path
        .file_stem()
        .map_or_else(|| "run".to_owned(), |s| s.to_string_lossy().into_owned());
    let name = match path.extension() {
        Some(ext) => format!("{stem}_steady.{}", ext.to_string_lossy()),
        None => format!("{stem}_steady"),
    };
    path.with_file_name(name)
}
