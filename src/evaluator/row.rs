//! A row of `mechdiff run` from the run-time evaluator's values: where each column's value
//! and derivatives lie in the program's outputs and which quantity it reports, fixed once
//! before the sweep, so that a row is one pass over its columns (a few loads, products and
//! one store each, the row grown once).
//!
//! The arithmetic is the solver path's own ([`quantity_in`]: ω x′, α x′ + ω² x″, …, a
//! derivative beyond the plan's order or the program's read as zero; an angle kept
//! continuous by whole turns as the solver path keeps it, [`to_turn`]), so a row holds the
//! same values, bit for bit, as one read through jets.

use mechdiff_core::DriveState;

use crate::scene::evaluate::{Resolved, quantity_in, to_turn};
use crate::scene::format::Quantity;
use crate::scene::model::OutputKind;

/// One column: a quantity of the value row at `at`.
#[derive(Debug, Clone, Copy)]
struct Column {
    /// Index of the value `x` of the column's value row `[x, x′, …]` in the program's values.
    at: usize,
    /// The quantity reported.
    quantity: Quantity,
    /// For an angle output, its index in [`CodeRow::angles`]: the value is the angle kept
    /// continuous, not the program's.
    angle: Option<usize>,
}

/// An angle output, kept continuous along the sweep.
#[derive(Debug, Clone, Copy)]
struct Angle {
    /// Index of its value in the program's values.
    at: usize,
    /// Index of the output (in `previous`, see [`CodeRow::push`]).
    output: usize,
    /// Its value at the sketch pose, where its continuity starts.
    sketch: f64,
}

/// The columns of a row from the program's values (see the module documentation).
#[derive(Debug, Clone)]
pub(crate) struct CodeRow {
    columns: Vec<Column>,
    angles: Vec<Angle>,
    /// Each angle's value at the current row (in the order of `angles`).
    turned: Vec<f64>,
    /// Derivatives read from the program (the plan's order, at most the program's): one
    /// beyond reads as zero.
    known: usize,
}

impl CodeRow {
    /// The row of `outputs` (in the order their values follow one another in the program,
    /// `width` values per value row: a value and its derivatives) at derivative order
    /// `order` (1 to 3).
    pub fn new(outputs: &[Resolved<'_>], width: usize, order: usize) -> Self {
        let (mut at, mut columns, mut angles) = (0, Vec::new(), Vec::new());
        for (index, resolved) in outputs.iter().enumerate() {
            let output = resolved.output;
            let rows = match output.kind {
                OutputKind::Point(_) => 2,
                _ => 1,
            };
            let angle = matches!(output.kind, OutputKind::Angle { .. }).then(|| {
                angles.push(Angle {
                    at,
                    output: index,
                    sketch: resolved.sketch(),
                });
                angles.len() - 1
            });
            for &quantity in &output.quantities {
                columns.extend((0..rows).map(|r| Column {
                    at: at + r * width,
                    quantity,
                    angle,
                }));
            }
            at += rows * width;
        }
        CodeRow {
            columns,
            turned: vec![0.0; angles.len()],
            angles,
            known: order.clamp(1, 3).min(width.saturating_sub(1)),
        }
    }

    /// Pushes every output's columns from the program's `values` onto `row`, at the drive
    /// state `drive`; `previous` holds each output's angle at the previous position (read
    /// and updated for angle outputs).
    pub fn push(
        &mut self,
        values: &[f64],
        previous: &mut [Option<f64>],
        drive: &DriveState,
        row: &mut Vec<f64>,
    ) {
        for (a, turned) in self.angles.iter().zip(&mut self.turned) {
            let previous = &mut previous[a.output];
            *turned = values[a.at];
            to_turn(turned, previous.unwrap_or(a.sketch));
            *previous = Some(*turned);
        }
        let (known, turned) = (self.known, &self.turned);
        row.extend(self.columns.iter().map(|c| {
            let d = |k: usize| if k <= known { values[c.at + k] } else { 0.0 };
            let x = match c.angle {
                Some(a) => turned[a],
                None => values[c.at],
            };
            quantity_in([x, d(1), d(2), d(3)], c.quantity, drive)
        }));
    }
}
