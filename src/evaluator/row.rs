//! A row of `mechdiff run` from the run-time evaluator's values: where each output's value
//! rows `[x, x′, …]` lie in the program's outputs, which quantities its columns report and
//! where they go in the row, fixed once before the sweep, so that a row reads each value
//! row once and writes each column once (the row grown once).
//!
//! The arithmetic is the solver path's own ([`quantity_in`]: ω x′, α x′ + ω² x″, …, a
//! derivative beyond the plan's order or the program's read as zero; an angle kept
//! continuous by whole turns as the solver path keeps it, [`to_turn`]), so a row holds the
//! same values, bit for bit, as one read through jets.

use mechdiff_core::DriveState;

use crate::scene::evaluate::{Resolved, quantity_in, to_turn};
use crate::scene::format::Quantity;
use crate::scene::model::OutputKind;

/// How one output's columns are read from the program's values.
#[derive(Debug, Clone)]
struct OutputColumns {
    /// Index of the output's first value row `[x, x′, …]` in the program's values (a
    /// point's y follows its x).
    at: usize,
    /// Whether the output is a point: two value rows (x, y), the columns of each quantity
    /// x then y.
    point: bool,
    /// An angle output's value at the sketch pose, where its continuity starts; `None` for
    /// the other outputs.
    angle: Option<f64>,
    /// The quantities reported, in column order.
    quantities: Vec<Quantity>,
}

/// The columns of a row from the program's values (see the module documentation).
#[derive(Debug, Clone)]
pub(crate) struct CodeRow {
    outputs: Vec<OutputColumns>,
    /// Values per value row of the program (a value and its derivatives).
    width: usize,
    /// Derivatives read from the program (the plan's order, at most the program's): one
    /// beyond reads as zero.
    known: usize,
    /// Columns per row.
    columns: usize,
}

impl CodeRow {
    /// The row of `outputs` (in the order their values follow one another in the program,
    /// `width` values per value row) at derivative order `order` (1 to 3).
    pub fn new(outputs: &[Resolved<'_>], width: usize, order: usize) -> Self {
        let (mut at, mut columns) = (0, 0);
        let outputs = (outputs.iter())
            .map(|resolved| {
                let output = resolved.output;
                let point = matches!(output.kind, OutputKind::Point(_));
                let rows = if point { 2 } else { 1 };
                let of = OutputColumns {
                    at,
                    point,
                    angle: matches!(output.kind, OutputKind::Angle { .. })
                        .then(|| resolved.sketch()),
                    quantities: output.quantities.clone(),
                };
                at += rows * width;
                columns += rows * output.quantities.len();
                of
            })
            .collect();
        CodeRow {
            outputs,
            width,
            known: order.clamp(1, 3).min(width.saturating_sub(1)),
            columns,
        }
    }

    /// Pushes every output's columns from the program's `values` onto `row`, at the drive
    /// state `drive`; `previous` holds each output's angle at the previous position (read
    /// and updated for angle outputs).
    pub fn push(
        &self,
        values: &[f64],
        previous: &mut [Option<f64>],
        drive: &DriveState,
        row: &mut Vec<f64>,
    ) {
        // The derivatives read, known when compiled: no test per value.
        match self.known {
            1 => self.push_known::<1>(values, previous, drive, row),
            2 => self.push_known::<2>(values, previous, drive, row),
            _ => self.push_known::<3>(values, previous, drive, row),
        }
    }

    /// [`CodeRow::push`] reading `K` derivatives of each value row.
    fn push_known<const K: usize>(
        &self,
        values: &[f64],
        previous: &mut [Option<f64>],
        drive: &DriveState,
        row: &mut Vec<f64>,
    ) {
        let start = row.len();
        row.resize(start + self.columns, 0.0);
        let mut column = &mut row[start..];
        // `[x, x′, x″, x‴]` of the value row at `at`, zero beyond the `K` known.
        let jet = |at: usize| {
            let v = &values[at..=at + K];
            std::array::from_fn(|k| if k <= K { v[k] } else { 0.0 })
        };
        for (o, previous) in self.outputs.iter().zip(previous) {
            let mut x: [f64; 4] = jet(o.at);
            if let Some(sketch) = o.angle {
                to_turn(&mut x[0], previous.unwrap_or(sketch));
                *previous = Some(x[0]);
            }
            let rows = if o.point { 2 } else { 1 };
            let (these, rest) = std::mem::take(&mut column).split_at_mut(rows * o.quantities.len());
            column = rest;
            if o.point {
                let y = jet(o.at + self.width);
                for (&q, pair) in o.quantities.iter().zip(these.chunks_exact_mut(2)) {
                    pair[0] = quantity_in(x, q, drive);
                    pair[1] = quantity_in(y, q, drive);
                }
            } else {
                for (&q, slot) in o.quantities.iter().zip(these) {
                    *slot = quantity_in(x, q, drive);
                }
            }
        }
    }
}
