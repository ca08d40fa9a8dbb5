//! Sweeps that stream: the rows of a scene (its outputs and `[[dynamics]]`) are formatted and
//! written as they are computed, so that memory stays flat in the number of drive positions.
//!
//! Each position of a sweep starts from the previous pose (the branch tracking) and each
//! angle output from its previous value (kept continuous). A batch of positions is solved in
//! parallel by speculative pieces (`speculate`), each piece checked against the state
//! the walk in order reaches at its start and solved again where it differs, so the
//! numbers, the errors and the first error's position are those of a sequential run by
//! construction. Turning numbers into text is done in parallel too (rayon): while one batch
//! of positions is solved, the one before is formatted in chunks, and the chunks are
//! written in order. A run with one thread gives the same bytes.
//!
//! The terminal table must know its column widths before its first row: a sweep of at most
//! [`TABLE_FROM_VALUES`] positions keeps its values (a few MB) and prints the table as
//! [`crate::scene::table::write_table`] always has, each column in the format its values
//! need; a longer one prints every column in scientific notation with 9 significant digits,
//! whose width is bounded for any `f64` (`-d.dddddddde-308`).

pub mod fixed;
pub mod format;
pub mod motion;
pub mod record;
mod scientific;
mod shortest;
pub(crate) mod speculate;

use std::io::{self, Write};
use std::path::PathBuf;

use crate::error::{Error, Result};
use crate::evaluator::Evaluator;
use crate::parallel::prelude::*;
use crate::scene::run::{
    Report, Stats, check_dead_positions, collect, columns, dead_positions, streamed_positions,
    sweeper,
};
use crate::scene::setup::Setup;
use crate::scene::{Plan, table};

use format::{RowFormat, Texts, Wanted};
use speculate::{Batch, Sweep};
pub use speculate::{Pieces, Speculation};

/// Runs a scene and streams its rows to sinks (see [`sweep`]); the scene is resolved once
/// into its [`Setup`] with [`Options::evaluator`], and its table worded by the scene itself.
pub use crate::scene::launch::stream as run;

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

/// The most worker threads a run starts (`--threads`): far more than any machine's cores
/// (each thread costs a stack and the work is split among them).
pub const MAX_THREADS: usize = 1024;

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
    /// Positions solved by one task of the parallel solve (see [`Speculation`]).
    pub piece: usize,
    /// When batches are solved in parallel pieces.
    pub speculation: Speculation,
    /// The longest sweep whose table is printed from its values ([`TABLE_FROM_VALUES`]).
    pub table_from_values: usize,
    /// How the run evaluates its positions (`--evaluator`, [`crate::RunOptions::evaluator`]).
    pub evaluator: Evaluator,
    /// The table's bytes go nowhere (the terminal is `/dev/null`): the sweep is solved and
    /// checked to its end as for a table, with the same errors, but the table is neither
    /// formatted nor written. Set by the caller, which knows where its table goes.
    pub discard_table: bool,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            threads: 0,
            progress: false,
            batch: 1 << 14,
            chunk: 1 << 10,
            piece: 1 << 12,
            speculation: Speculation::Auto,
            table_from_values: TABLE_FROM_VALUES,
            evaluator: Evaluator::default(),
            discard_table: false,
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
    /// How the parallel solve's pieces went.
    pub pieces: Pieces,
    /// What the run evaluated (of a sweep solved in pieces: the pieces kept).
    pub stats: Stats,
}

/// The terminal table's words besides its rows, in the scene's terms: a presenter the edge
/// hands the runner (a [`crate::Scene`] words its own table), so that the runner never
/// reads the scene.
pub trait TableWords {
    /// The lines before the table's header: the title, if any, and the plan line, each
    /// ending in a newline.
    fn head(&self, plan: &Plan) -> String;
    /// The whole table of a run held in memory
    /// ([`crate::scene::table::write_table`]).
    ///
    /// # Errors
    /// The writer's.
    fn table(&self, report: &Report, out: &mut Vec<u8>) -> io::Result<()>;
    /// What follows the rows of a table printed as they were computed: the dead positions
    /// and the limits ([`crate::scene::table::write_after_rows`]).
    ///
    /// # Errors
    /// The writer's.
    fn after_rows(&self, report: &Report, out: &mut Vec<u8>) -> io::Result<()>;
}

/// Runs a scene's `setup` and streams its rows to `sinks`, the table worded by `words`:
/// the kinematic outputs and `[[dynamics]]` from the one walk of the sweep, in constant
/// memory. Counterweights (`[balancing]`) are sized from every position before their
/// columns are known: such a run is carried out in memory ([`crate::scene::run::collect`])
/// and written by the same writers.
///
/// # Errors
/// The first error in drive order (a solver error, a non-finite value), after the rows
/// before it were written to every output; then an error of the dead-position search; or
/// [`Error::Write`] naming the output that failed. The caller discards partial files.
pub fn sweep(
    setup: &Setup<'_>,
    words: &dyn TableWords,
    sinks: &mut Sinks<'_>,
    options: &Options,
) -> Result<Streamed> {
    if (setup.balancing).is_some_and(|b| b.counterweights.is_some()) {
        return in_memory(setup, words, sinks);
    }
    let cx = &setup.context;
    crate::scene::preflight::before_solving(setup)?;
    let mut plan = Plan::of(setup);
    let columns = columns(setup);
    let mut stats = Stats::default();
    let positions = streamed_positions(setup, &mut stats)?;
    let mut sweeper = sweeper(setup, &plan, false)?;
    plan.evaluated_by(sweeper.loops(), sweeper.backend());
    let format = RowFormat::new(&columns);
    let streamed_table = positions.len() > options.table_from_values;
    // A table that goes nowhere is not formatted; the sweep still runs as for a table.
    let table_text = sinks.table.is_some() && !options.discard_table;
    let mut kept_rows: Vec<Vec<f64>> = Vec::new();

    if let Some(sink) = &mut sinks.csv {
        let header = record::csv_record(columns.iter().map(|c| c.header()));
        sink.write(header.as_bytes())?;
    }
    if streamed_table && table_text {
        let mut head = words.head(&plan);
        format.table_header(&columns, &mut head);
        write_table(sinks, head.as_bytes())?;
    }

    let bar = crate::progress::bar(options.progress, positions.len());
    if options.threads > MAX_THREADS {
        return Err(Error::OverLimit {
            option: "--threads",
            value: options.threads as u64,
            limit: MAX_THREADS as u64,
            what: "worker threads",
            advice: "give at most one or two per core, or 0 for one per core",
        });
    }
    let pool = crate::parallel::ThreadPoolBuilder::new()
        .num_threads(options.threads)
        .build()
        .map_err(|e| Error::Threads {
            threads: options.threads,
            reason: e.to_string(),
        })?;
    let wanted = Wanted {
        table: streamed_table && table_text,
        csv: sinks.csv.is_some(),
        jsonl: sinks.jsonl.is_some(),
    };
    let (batch, chunk) = (options.batch.max(1), options.chunk.max(1));
    let sweep = Sweep {
        context: cx,
        columns: &columns,
        positions: &positions,
    };
    let speculate = match options.speculation {
        Speculation::Auto => pool.current_num_threads() > 1 && sweeper.is_route_independent(),
        Speculation::Always => true,
        Speculation::Never => false,
    };
    let mut pieces = Pieces::default();
    // Chunks formatted at once (one per thread), then written before the next ones.
    let round = pool.current_num_threads().max(1);
    let mut texts: Vec<Texts> = Vec::new();
    let mut written = 0;
    let mut next = 0;
    let mut pending: Option<Batch> = None;
    let stopped = pool.install(|| -> Result<Option<Error>> {
        loop {
            let solve = pending.as_ref().is_none_or(|b| b.error.is_none())
                && next < positions.len()
                && (sinks.table.is_some() || wanted.csv || wanted.jsonl);
            let range = next..(next + batch).min(positions.len());
            let (solved, text) = crate::parallel::join(
                || {
                    solve.then(|| match speculate {
                        true => sweep.solve(&mut sweeper, range, options.piece, &mut pieces),
                        false => sweep.walk(&mut sweeper, range),
                    })
                },
                || {
                    let mut out = Output {
                        sinks: &mut *sinks,
                        texts: &mut texts,
                        bar: &bar,
                    };
                    (pending.as_ref()).map(|b| out.batch(&format, &b.rows, chunk, round, wanted))
                },
            );
            if let (Some(b), Some(text)) = (pending.take(), text) {
                text?;
                let n = b.rows.len() / format.columns();
                if table_text && sinks.table.is_some() && !streamed_table {
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
    let dead = dead_positions(setup, positions.iter(), &mut stats)?;
    check_dead_positions(cx, &dead)?;
    let warnings = sweeper.warnings();
    stats.sweep = sweeper.counts();
    let dynamics = (sweeper.dynamics())
        .map(|d| d.report(cx, Vec::new()))
        .transpose()?;
    let balancing = (setup.balancing)
        .map(|b| crate::scene::balancing::report(cx, b, &setup.mechanism, None))
        .transpose()?;
    if table_text && sinks.table.is_some() {
        let mut text = Vec::new();
        stats.limit_walks = usize::from(crate::scene::sweep_limits::walks(setup, positions.len()));
        let report = Report {
            plan,
            columns,
            rows: kept_rows,
            dead_positions: dead,
            dynamics,
            warnings: warnings.clone(),
            balancing,
            limits: crate::scene::sweep_limits::in_sweep(setup, positions.iter()),
            stats,
        };
        let result = if streamed_table {
            words.after_rows(&report, &mut text)
        } else {
            words.table(&report, &mut text)
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
        pieces,
        stats,
    })
}

/// [`sweep`] for a scene whose rows are known only at the end (counterweights): run in
/// memory, then written by the writers of a run in memory.
fn in_memory(setup: &Setup<'_>, words: &dyn TableWords, sinks: &mut Sinks<'_>) -> Result<Streamed> {
    let report = collect(setup)?;
    let write = |sink: &mut Sink<'_>, f: &dyn Fn(&mut Vec<u8>) -> io::Result<()>| {
        let mut bytes = Vec::new();
        f(&mut bytes).map_err(|source| Error::Write {
            path: sink.path.clone(),
            source,
        })?;
        sink.write(&bytes)
    };
    if let Some(sink) = &mut sinks.csv {
        write(sink, &|out| table::write_csv(&report, out))?;
    }
    if let Some(sink) = &mut sinks.jsonl {
        write(sink, &|out| table::write_jsonl(&report, out))?;
    }
    if sinks.table.is_some() {
        let mut text = Vec::new();
        (words.table(&report, &mut text)).map_err(|source| Error::Write {
            path: PathBuf::from("<stdout>"),
            source,
        })?;
        write_table(sinks, &text)?;
    }
    Ok(Streamed {
        rows: report.rows.len(),
        warnings: report.warnings,
        pieces: Pieces::default(),
        stats: report.stats,
    })
}

/// Where a batch's text goes, and the buffers it is made in.
struct Output<'s, 'a> {
    sinks: &'s mut Sinks<'a>,
    /// One per chunk formatted at once, reused from round to round and batch to batch.
    texts: &'s mut Vec<Texts>,
    bar: &'s crate::progress::ProgressBar,
}

impl Output<'_, '_> {
    /// Formats a batch's rows and writes them, in order: `round` chunks of `chunk` rows
    /// formatted in parallel, then written, then the next `round`. The text held is a few
    /// chunks, whatever the batch, so it stays in cache from formatting to writing.
    fn batch(
        &mut self,
        format: &RowFormat,
        rows: &[f64],
        chunk: usize,
        round: usize,
        wanted: Wanted,
    ) -> Result<()> {
        let width = format.columns();
        if self.texts.len() < round {
            self.texts.resize_with(round, Texts::default);
        }
        for group in rows.chunks(chunk * width * round) {
            let chunks = group.len().div_ceil(chunk * width);
            (self.texts[..chunks].par_iter_mut())
                .zip(group.par_chunks(chunk * width))
                .for_each(|(text, rows)| {
                    text.clear();
                    for row in rows.chunks(width) {
                        format.row(row, wanted, text);
                    }
                });
            let texts = &self.texts[..chunks];
            self.bar.suspend(|| write_texts(self.sinks, texts))?;
        }
        Ok(())
    }
}

/// Writes the texts of a batch to their outputs, in order.
fn write_texts(sinks: &mut Sinks<'_>, texts: &[Texts]) -> Result<()> {
    for text in texts {
        if !text.table.is_empty() {
            write_table(sinks, &text.table)?;
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
