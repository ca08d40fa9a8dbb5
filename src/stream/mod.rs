//! Sweeps that stream: the rows of a kinematic scene are formatted and written as they are
//! computed, so that memory stays flat in the number of drive positions.
//!
//! The sweep itself is walked in drive order on one thread: each position starts from the
//! previous pose (the branch tracking) and each angle output from its previous value (kept
//! continuous), so the numbers, the errors and the first error's position are those of a
//! sequential run by construction. Turning numbers into text — most of a run's time — is
//! done in parallel (rayon): while one batch of positions is solved, the one before is
//! formatted in chunks across the other cores, and the chunks are written in order. A run
//! with one thread gives the same bytes.
//!
//! The terminal table must know its column widths before its first row: a sweep of at most
//! [`TABLE_FROM_VALUES`] positions keeps its values (a few MB) and prints the table as
//! [`crate::scene::table::write_table`] always has, each column in the format its values
//! need; a longer one prints every column in scientific notation with 9 significant digits,
//! whose width is bounded for any `f64` (`-d.dddddddde-308`).

pub mod format;

use std::io::{self, Write};
use std::path::PathBuf;

use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::scene::run::{Report, check_dead_positions, dead_positions, streamed_positions};
use crate::scene::sweep::{Sweeper, check_row, kinematic_columns};
use crate::scene::{Plan, Positions, Scene, build, table};

use format::RowFormat;

/// The longest sweep whose table is printed as in memory (each column in the format its
/// values need, see [`crate::scene::table::write_table`]); a longer one is printed with
/// fixed-width scientific columns as it is computed.
pub const TABLE_FROM_VALUES: usize = 1 << 16;

/// An output of a streamed run: a name for its errors and where its bytes go.
pub struct Sink<'a> {
    /// The file as the user named it (`<stdout>` for the terminal).
    pub path: PathBuf,
    /// Where the bytes go.
    pub out: &'a mut (dyn Write + Send),
}

impl Sink<'_> {
    fn write(&mut self, bytes: &[u8]) -> Result<()> {
        self.out.write_all(bytes).map_err(|source| Error::Write {
            path: self.path.clone(),
            source,
        })
    }
}

/// The outputs of a streamed run; each is optional.
#[derive(Default)]
pub struct Sinks<'a> {
    /// The terminal table (title, plan, table, dead positions). A reader that goes away
    /// (`| head`) ends the table, not the run; with no other output the sweep stops there.
    pub table: Option<Sink<'a>>,
    /// CSV: the header `name [unit]` per column, then every value with all its digits.
    pub csv: Option<Sink<'a>>,
    /// JSON Lines: one object per drive position, keyed by the CSV's headers.
    pub jsonl: Option<Sink<'a>>,
}

/// How a streamed run is carried out.
#[derive(Debug, Clone)]
pub struct Options {
    /// Worker threads: 0 for rayon's default (`RAYON_NUM_THREADS`, else every core).
    pub threads: usize,
    /// Show a progress bar on stderr (the caller decides: stderr a terminal, a long run).
    pub progress: bool,
    /// Positions solved in one batch (the memory held is about two batches of rows and
    /// their text).
    pub batch: usize,
    /// Positions formatted by one task.
    pub chunk: usize,
    /// The longest sweep whose table is printed from its values ([`TABLE_FROM_VALUES`]).
    pub table_from_values: usize,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            threads: 0,
            progress: false,
            batch: 1 << 14,
            chunk: 1 << 10,
            table_from_values: TABLE_FROM_VALUES,
        }
    }
}

/// What a streamed run found besides its rows.
#[derive(Debug, Clone, Default)]
pub struct Streamed {
    /// The number of rows written.
    pub rows: usize,
    /// Warnings about the results (the most ill-conditioned position).
    pub warnings: Vec<String>,
}

/// Rows solved in one batch, flat (`columns` values per row), and the error that stopped
/// the batch, if one did: the rows before it are good and are written.
struct Batch {
    rows: Vec<f64>,
    error: Option<Error>,
}

/// Text of one chunk of rows, one buffer per output.
#[derive(Default)]
struct Text {
    table: String,
    csv: Vec<u8>,
    jsonl: Vec<u8>,
}

/// Runs a kinematic scene (no dynamics, no balancing) and streams its rows to `sinks`.
///
/// # Errors
/// The first error in drive order (a solver error, a non-finite value), after the rows
/// before it were written to every output; then an error of the dead-position search; or
/// [`Error::Write`] naming the output that failed. The caller discards partial files.
pub fn run(scene: &Scene, sinks: &mut Sinks<'_>, options: &Options) -> Result<Streamed> {
    let mechanism = build::mechanism(scene)?;
    let mut plan = Plan::of(scene);
    let columns = kinematic_columns(scene);
    let positions = streamed_positions(scene, &mechanism)?;
    let mut sweeper = Sweeper::new(scene, &mechanism, &plan)?;
    plan.loops = sweeper.loops();
    let format = RowFormat::new(&columns);
    let streamed_table = positions.len() > options.table_from_values;
    let mut kept_rows: Vec<Vec<f64>> = Vec::new();

    if let Some(sink) = &mut sinks.csv {
        let header: Vec<String> = columns.iter().map(|c| c.header()).collect();
        sink.write(format!("{}\n", header.join(",")).as_bytes())?;
    }
    if streamed_table && sinks.table.is_some() {
        let mut head = String::new();
        if let Some(title) = &scene.title {
            head.push_str(title);
            head.push('\n');
        }
        head.push_str(&plan.describe(scene));
        head.push('\n');
        format.table_header(&columns, &mut head);
        write_table(sinks, head.as_bytes())?;
    }

    let bar = progress_bar(options.progress, positions.len());
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(options.threads)
        .build()
        .map_err(|e| Error::Threads {
            threads: options.threads,
            reason: e.to_string(),
        })?;
    let wanted = Wanted {
        table: streamed_table && sinks.table.is_some(),
        csv: sinks.csv.is_some(),
        jsonl: sinks.jsonl.is_some(),
    };
    let (batch, chunk) = (options.batch.max(1), options.chunk.max(1));
    let mut written = 0;
    let mut next = 0;
    let mut pending: Option<Batch> = None;
    let stopped = pool.install(|| -> Result<Option<Error>> {
        loop {
            let solve = pending.as_ref().is_none_or(|b| b.error.is_none())
                && next < positions.len()
                && (sinks.table.is_some() || wanted.csv || wanted.jsonl);
            let range = next..(next + batch).min(positions.len());
            let (solved, text) = rayon::join(
                || solve.then(|| solve_batch(scene, &mut sweeper, &columns, &positions, range)),
                || (pending.as_ref()).map(|b| format_batch(&format, &b.rows, chunk, wanted)),
            );
            if let (Some(b), Some(text)) = (pending.take(), text) {
                let n = b.rows.len() / format.columns();
                bar.suspend(|| write_texts(sinks, &text))?;
                if sinks.table.is_some() && !streamed_table {
                    kept_rows.extend(b.rows.chunks(format.columns()).map(<[f64]>::to_vec));
                }
                written += n;
                bar.inc(n as u64);
                if b.error.is_some() {
                    return Ok(b.error);
                }
            }
            match solved {
                Some(b) => {
                    next += b.rows.len() / format.columns();
                    pending = Some(b);
                }
                None => return Ok(None),
            }
        }
    })?;
    bar.finish_and_clear();
    if let Some(error) = stopped {
        return Err(error);
    }
    let dead = dead_positions(scene, &mechanism, positions.iter())?;
    check_dead_positions(scene, &dead)?;
    let warnings = sweeper.warnings();
    if sinks.table.is_some() {
        let mut text = Vec::new();
        let report = Report {
            plan,
            columns,
            rows: kept_rows,
            dead_positions: dead,
            dynamics: None,
            warnings: warnings.clone(),
            balancing: None,
            limits: crate::scene::sweep_limits::in_sweep(scene, &mechanism, positions.iter()),
        };
        let result = if streamed_table {
            table::write_dead_positions(scene, &report, &mut text)
        } else {
            table::write_table(scene, &report, &mut text)
        };
        result.map_err(|source| Error::Write {
            path: PathBuf::from("<stdout>"),
            source,
        })?;
        write_table(sinks, &text)?;
    }
    Ok(Streamed {
        rows: written,
        warnings,
    })
}

/// Which texts the formatting makes.
#[derive(Debug, Clone, Copy)]
struct Wanted {
    table: bool,
    csv: bool,
    jsonl: bool,
}

/// Solves the positions of `range` in order; stops at the first error, keeping the rows
/// before it.
fn solve_batch(
    scene: &Scene,
    sweeper: &mut Sweeper<'_>,
    columns: &[crate::scene::outputs::Column],
    positions: &Positions,
    range: std::ops::Range<usize>,
) -> Batch {
    let mut rows = Vec::with_capacity(range.len() * columns.len());
    let mut row = Vec::with_capacity(columns.len());
    for i in range {
        let result = (sweeper.row(positions.get(i), &mut row))
            .and_then(|()| check_row(scene, columns, &row));
        if let Err(error) = result {
            return Batch {
                rows,
                error: Some(error),
            };
        }
        rows.extend_from_slice(&row);
    }
    Batch { rows, error: None }
}

/// The text of a batch's rows, chunk by chunk in parallel, chunks in row order.
fn format_batch(format: &RowFormat, rows: &[f64], chunk: usize, wanted: Wanted) -> Vec<Text> {
    let width = format.columns();
    rows.par_chunks(chunk * width)
        .map(|rows| {
            let mut text = Text::default();
            for row in rows.chunks(width) {
                if wanted.table {
                    format.table(row, &mut text.table);
                }
                if wanted.csv {
                    format.csv(row, &mut text.csv);
                }
                if wanted.jsonl {
                    format.jsonl(row, &mut text.jsonl);
                }
            }
            text
        })
        .collect()
}

/// Writes the texts of a batch to their outputs, in order.
fn write_texts(sinks: &mut Sinks<'_>, texts: &[Text]) -> Result<()> {
    for text in texts {
        if !text.table.is_empty() {
            write_table(sinks, text.table.as_bytes())?;
        }
        if let Some(sink) = &mut sinks.csv {
            sink.write(&text.csv)?;
        }
        if let Some(sink) = &mut sinks.jsonl {
            sink.write(&text.jsonl)?;
        }
    }
    Ok(())
}

/// Writes to the table; a reader that went away ends the table, not the run.
fn write_table(sinks: &mut Sinks<'_>, bytes: &[u8]) -> Result<()> {
    let Some(sink) = &mut sinks.table else {
        return Ok(());
    };
    match sink.out.write_all(bytes) {
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => {
            sinks.table = None;
            Ok(())
        }
        result => result.map_err(|source| Error::Write {
            path: sink.path.clone(),
            source,
        }),
    }
}

/// A progress bar on stderr counting drive positions, or a hidden one.
fn progress_bar(shown: bool, positions: usize) -> ProgressBar {
    if !shown {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(positions as u64);
    if let Ok(style) = ProgressStyle::with_template(
        "{bar:40} {human_pos}/{human_len} positions, {per_sec}, {eta} left",
    ) {
        bar.set_style(style);
    }
    bar
}
