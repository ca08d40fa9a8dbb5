//! The all-closed-form path of [`Tracker::move_to`]: one evaluation of the loops' formulas
//! in `Dual2_64` per drive position, written into the tracker's q, q′, q″, with every step
//! between two positions checked by the loops' margins (see [`super::interval`]).

use super::interval;
use super::{SolveReport, Tracker};
use crate::Error;
use crate::geometry::closed_form::Failure;
use crate::geometry::halving::{Attempt, StepHalving, Stop};
use num_dual::Dual2_64;

impl Tracker<'_> {
    /// Moves to `phi` with every loop in closed form: q, q′, q″ from one evaluation of the
    /// formulas in `Dual2_64`. A step is accepted only when every loop's margin is shown
    /// positive over the whole step ([`interval::passes`]); otherwise it is halved, and
    /// once the halvings are used up the end of the branch is located and reported
    /// ([`Error::Blocked`], [`Error::ChangePoint`], [`Error::Singular`]); the tracker is
    /// left at the last position accepted.
    pub(super) fn move_closed(&mut self, phi: f64) -> Result<SolveReport, Error> {
        let start = self.phi;
        // The tracker and the condition at `phi` itself, if its formula found it a toggle.
        let mut state = (self, None);
        let walked = state.0.halving().walk(
            &mut state,
            start,
            phi,
            |(t, toggle_at_phi), target, _| {
                Ok(Attempt::Failed(match t.evaluate_closed(target) {
                    Ok(()) => match t.unproven(target) {
                        None => {
                            t.accept_closed(target);
                            return Ok(Attempt::Accepted);
                        }
                        Some(l) => (l, None),
                    },
                    Err((l, failure)) => {
                        if let (true, Failure::Singular { condition }) = (target == phi, failure) {
                            *toggle_at_phi = Some(condition);
                        }
                        (l, Some(failure))
                    }
                }))
            },
            |(t, toggle_at_phi), target, failed| {
                match t.end_of_branch(start, phi, target, failed, *toggle_at_phi) {
                    // The margin stayed clear of zero: rounding, not the branch's end.
                    None => {
                        t.evaluate_closed(target)
                            .map_err(|(l, f)| t.closed_failure(target, l, f))?;
                        t.accept_closed(target);
                        Ok(())
                    }
                    Some(e) => Err(e),
                }
            },
        );
        let walked = walked.map_err(|stop| state.0.stopped(start, phi, stop))?;
        Ok(SolveReport {
            steps: walked.steps,
            newton_failures: walked.failures,
            ..SolveReport::starting(phi)
        })
    }

    /// The limits of a move's walk: steps of at most [`Tracker::longest_step`], halved at
    /// most [`Solver::max_subdivisions`] times, at most [`interval::MAX_SUBSTEPS`] in all.
    ///
    /// [`Solver::max_subdivisions`]: crate::geometry::Solver::max_subdivisions
    pub(super) fn halving(&self) -> StepHalving {
        StepHalving {
            longest: self.longest_step(),
            max_subdivisions: self.solver.max_subdivisions,
            max_substeps: interval::MAX_SUBSTEPS,
        }
    }

    /// The error of a move from `start` to `phi` that stopped short: its walk's error, or
    /// [`Error::MoveTooLong`] once it would take more than [`interval::MAX_SUBSTEPS`]
    /// sub-steps.
    pub(super) fn stopped(&self, start: f64, phi: f64, stop: Stop<Error>) -> Error {
        match stop {
            Stop::Failed(e) => e,
            Stop::TooLong => Error::MoveTooLong {
                from: start,
                to: phi,
                steps: interval::MAX_SUBSTEPS,
                longest: self.longest_step(),
            },
        }
    }

    /// The formulas at `target`, into `closed_q`, `closed_frames`, `closed_margins`.
    pub(super) fn evaluate_closed(&mut self, target: f64) -> Result<(), (usize, Failure)> {
        let x = Dual2_64::new(target, 1.0, 0.0);
        let (q, frames) = (&mut self.closed_q, &mut self.closed_frames);
        self.closed
            .solve_all(x, self.q.as_slice(), q, frames, &mut self.closed_margins)
    }

    /// The first loop whose margin is not shown positive between the current position and
    /// `target` (evaluated into `closed_margins`).
    fn unproven(&self, target: f64) -> Option<usize> {
        let h = target - self.phi;
        (0..self.margins.len()).find(|&l| {
            self.closed.has_margin(l)
                && !interval::passes(self.margins[l], self.closed_margins[l], h)
        })
    }

    /// The longest step checked at once: 1/8 rad for an angle, 1/8 of the sketch for a
    /// displacement (see [`interval::passes`]).
    pub(crate) fn longest_step(&self) -> f64 {
        match self.mechanism.drive_kind() {
            crate::geometry::DriveKind::Angle => interval::LONGEST_TURN,
            crate::geometry::DriveKind::Displacement => {
                interval::LONGEST_TURN * self.lengths.linkage
            }
        }
    }

    /// Makes the closed forms' pose (in `closed_q`, `closed_frames`) current at `phi`.
    // Inlined into the step that accepts, as before the walk was shared: called from two
    // places (a step accepted, or taken after all at the end of its halvings), it was not.
    #[inline(always)]
    pub(super) fn accept_closed(&mut self, phi: f64) {
        let poses = self.q.as_mut_slice().iter_mut();
        let derivatives = self
            .dq
            .as_mut_slice()
            .iter_mut()
            .zip(self.ddq.as_mut_slice());
        for ((x, (dx, ddx)), v) in poses.zip(derivatives).zip(&self.closed_q) {
            (*x, *dx, *ddx) = (v.re, v.v1, v.v2);
        }
        for (f, (s, c)) in self.frames.iter_mut().zip(&self.closed_frames) {
            *f = (s.re, c.re);
        }
        self.margins.copy_from_slice(&self.closed_margins);
        // Φ is not evaluated: the formulas close the loops by construction (see
        // `SolveReport::residual`, and `Tracker::residual` to check it).
        self.phi = phi;
    }

    /// The error for loop `l`'s closed form failing at `phi`.
    pub(crate) fn closed_failure(&self, phi: f64, l: usize, failure: Failure) -> Error {
        let joints = self.loop_joints(&self.loops[l]);
        match failure {
            Failure::Unassemblable { residual } => Error::Unassemblable {
                phi,
                last_assembled: self.phi,
                joints,
                residual,
            },
            Failure::Singular { condition } => Error::Singular {
                phi,
                condition,
                joints,
            },
        }
    }
}
