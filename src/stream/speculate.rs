//! The drive positions of a batch solved on several cores with the results of a walk in
//! order, bit for bit: speculative pieces.
//!
//! A sweep carries state from one position to the next: the tracker's branches and pose
//! (the turn of every angle; on Newton, the warm start) and each angle output's previous
//! value. The batch is split into pieces. The first starts from the true state; each other
//! from a guess — the batch's start state moved straight to the position before the piece
//! (one move, in the solver's own checked steps). The pieces are solved in parallel; then,
//! in order, a piece is kept when its guessed start is the true state at the end of the
//! piece before, bit for bit ([`Sweeper::same_state`]), and solved again from that state
//! otherwise. What is kept is therefore the walk in order by construction: rows, errors
//! and the first error's position.
//!
//! With every loop in closed form the state after a position depends on the position and
//! the turns alone, so the guesses hold (a guess fails where its move meets a blocked range
//! the walk stops at anyway). On Newton the pose carries the route's last bits, so almost
//! every guess fails: such sweeps are walked in order ([`Speculation::Auto`]).

use crate::error::Error;
use crate::parallel::prelude::*;
use crate::scene::Positions;
use crate::scene::error_context::ErrorContext;
use crate::scene::outputs::Column;
use crate::scene::sweep::{Sweeper, check_row};

/// When a batch is solved in speculative pieces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Speculation {
    /// With more than one thread, when the sweep's state does not depend on the route
    /// ([`Sweeper::is_route_independent`]: every loop in closed form).
    #[default]
    Auto,
    /// Always, even on Newton (where most pieces are solved twice): for tests of the
    /// re-solving path.
    Always,
    /// Never: every batch is walked in order on one thread.
    Never,
}

/// Rows solved in order, flat (`columns` values per row), and the error that stopped them,
/// if one did: the rows before it are good.
pub(crate) struct Batch {
    pub rows: Vec<f64>,
    pub error: Option<Error>,
}

/// How the pieces of the batches went.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Pieces {
    /// Pieces solved from a guessed start state.
    pub guessed: usize,
    /// Of those, the pieces whose guess was not the true state: solved again.
    pub solved_again: usize,
}

/// The drive positions and outputs of a sweep, for solving pieces of it.
pub(crate) struct Sweep<'a> {
    pub context: &'a ErrorContext<'a>,
    pub columns: &'a [Column],
    pub positions: &'a Positions,
}

/// A piece solved from a start state: its rows, the state after them, the guessed start.
struct Piece<'s> {
    /// `None` for the batch's first piece (the true state) or a guess that failed.
    guess: Option<Sweeper<'s>>,
    end: Sweeper<'s>,
    batch: Batch,
}

impl Sweep<'_> {
    /// Walks the positions of `range` in order from `sweeper`'s state; stops at the first
    /// error, keeping the rows before it.
    pub fn walk(&self, sweeper: &mut Sweeper<'_>, range: std::ops::Range<usize>) -> Batch {
        let mut rows = Vec::with_capacity(range.len() * self.columns.len());
        let mut row = Vec::with_capacity(self.columns.len());
        for i in range {
            let result = (sweeper.row(self.positions.get(i), &mut row))
                .and_then(|()| check_row(self.context, self.columns, &row));
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

    /// Solves the positions of `range` in pieces of `piece` positions in parallel (on the
    /// current rayon pool), `sweeper` then at the state after the last row kept; the same
    /// rows, error and state as [`Sweep::walk`]. Counts the pieces in `pieces`.
    pub fn solve<'s>(
        &self,
        sweeper: &mut Sweeper<'s>,
        range: std::ops::Range<usize>,
        piece: usize,
        pieces: &mut Pieces,
    ) -> Batch {
        let piece = piece.max(1);
        if range.len() <= piece {
            return self.walk(sweeper, range);
        }
        let starts: Vec<usize> = range.clone().step_by(piece).collect();
        let base = &*sweeper;
        let solved: Vec<Piece<'s>> = (starts.par_iter())
            .map(|&start| {
                let mut state = base.clone();
                let guess = if start == range.start {
                    None
                } else {
                    let mut row = Vec::new();
                    let before = self.positions.get(start - 1);
                    state.row(before, &mut row).ok().map(|()| state.clone())
                };
                state.restart_worst();
                let end = (start + piece).min(range.end);
                let batch = if start == range.start || guess.is_some() {
                    self.walk(&mut state, start..end)
                } else {
                    Batch {
                        rows: Vec::new(),
                        error: None,
                    }
                };
                Piece {
                    guess,
                    end: state,
                    batch,
                }
            })
            .collect();
        let mut rows = Vec::with_capacity(range.len() * self.columns.len());
        for (piece_solved, &start) in solved.into_iter().zip(&starts) {
            let Piece { guess, end, batch } = piece_solved;
            let (end, batch) = if start == range.start {
                (end, batch)
            } else {
                pieces.guessed += 1;
                if guess.is_some_and(|g| g.same_state(sweeper)) {
                    (end, batch)
                } else {
                    pieces.solved_again += 1;
                    let mut state = sweeper.clone();
                    state.restart_worst();
                    let batch = self.walk(&mut state, start..(start + piece).min(range.end));
                    (state, batch)
                }
            };
            sweeper.follow(end);
            rows.extend_from_slice(&batch.rows);
            if batch.error.is_some() {
                return Batch {
                    rows,
                    error: batch.error,
                };
            }
        }
        Batch { rows, error: None }
    }
}
