//! The Newton path of [`Tracker::move_to`] (loops without a closed form, or
//! `Solver::with_closed_form(false)`): Taylor predictor, Newton with the block-factorised
//! Φ_q, the singularity and branch checks, step halving, and the implicit lift of q′, q″ at
//! the accepted pose (steps 1–5 of the solver's documentation).

use super::{Loops, SolveReport, Tracker, amax};
use crate::Error;
use crate::geometry::constraints::Frames;
use crate::geometry::halving::Attempt;
use crate::geometry::implicit::Factorised;
use crate::geometry::{branch, frames, mobility};
use nalgebra::DVector;

/// A polishing Newton step larger than this (relative to its loop's length) is followed by a
/// fresh factorisation of Φ_q at the polished pose before q′, q″ are solved for (see
/// `Tracker::accept`): 4 ε, the size of rounding in the coordinates.
const REFACTOR_ABOVE: f64 = 4.0 * f64::EPSILON;

/// A Newton iterate whose residual is more than this many times the previous one has left
/// the basin of the solution: the attempt fails and the step is halved. Within the basin the
/// residual falls quadratically, or by about half per iteration next to a toggle.
const DIVERGING: f64 = 4.0;

/// Newton iterations in a row without a smaller residual after which an attempt fails.
const STAGNATING: usize = 3;

impl Tracker<'_> {
    /// Moves to `phi` by predictor, Newton and the checks, halving the step on failure.
    pub(super) fn move_newton(&mut self, phi: f64) -> Result<SolveReport, Error> {
        let start = self.phi;
        let mut state = (self, SolveReport::starting(start));
        if start != phi {
            // Steps of at most 1/8 rad (or 1/8 of the sketch), as on the closed-form path:
            // Newton's landing is checked (branch certificates) at least that often.
            let walked = state.0.halving().walk(
                &mut state,
                start,
                phi,
                |(t, report), target, h| t.attempt_newton(phi, target, h, report),
                // Given up after the allowed halvings, or once a halved step no longer
                // moves φ.
                |_, _, failure| Err(failure),
            );
            walked.map_err(|stop| state.0.stopped(start, phi, stop))?;
        }
        let (t, mut report) = state;
        report.phi = t.phi;
        report.residual = Some(amax(t.residual.as_slice()));
        Ok(report)
    }

    /// One step of a move to `phi`: to `target`, `h` from the current position, by the
    /// Taylor predictor, Newton and the checks. A failure of Newton (counted in `report`
    /// with the iterations) or a branch flip fails the step; a toggle ends the move.
    fn attempt_newton(
        &mut self,
        phi: f64,
        target: f64,
        h: f64,
        report: &mut SolveReport,
    ) -> Result<Attempt<Error>, Error> {
        // Taylor predictor q + h q′ + h²/2 q″.
        let derivatives = self.dq.as_slice().iter().zip(self.ddq.as_slice());
        let poses = self.trial.as_mut_slice().iter_mut().zip(self.q.as_slice());
        for ((x, &q), (&dq, &ddq)) in poses.zip(derivatives) {
            *x = q + h * (dq + 0.5 * h * ddq);
        }
        for (f, pose) in self
            .trial_frames
            .iter_mut()
            .zip(self.trial.as_slice().chunks_exact(3))
        {
            *f = pose[2].sin_cos();
        }
        if self.seeding {
            let (q, frames) = (self.q.as_slice(), &mut self.trial_frames);
            self.closed
                .seed(target, q, self.trial.as_mut_slice(), frames);
        }
        match self.newton(target) {
            Ok(iterations) => {
                report.iterations += iterations;
                self.check_trial(target)?;
                match self
                    .trial_certificates
                    .iter()
                    .zip(&self.certificates)
                    .position(|(a, b)| a != b)
                {
                    None => {
                        self.accept(target)?;
                        report.steps += 1;
                        Ok(Attempt::Accepted)
                    }
                    Some(l) => {
                        report.branch_rejections += 1;
                        Ok(Attempt::Failed(Error::BranchFlip {
                            from: self.phi,
                            to: target,
                            joints: self.loop_joints(&self.loops[l]),
                        }))
                    }
                }
            }
            Err((residual, l)) => {
                report.newton_failures += 1;
                Ok(Attempt::Failed(Error::Unassemblable {
                    phi,
                    last_assembled: self.phi,
                    joints: self.loop_joints(&self.loops[l]),
                    residual,
                }))
            }
        }
    }

    /// Newton on `trial` at drive position `phi`: the iterations, or the final residual and
    /// the loop with the largest residual. Leaves Φ(trial) in `trial_residual`.
    ///
    /// An attempt is given up early, so that the caller halves the step instead of
    /// following Newton elsewhere: when the residual grows past [`DIVERGING`] times the
    /// previous one (Newton has left the solution's basin and may wander, winding the
    /// angles by many turns, to another assembly), or when it has not decreased for
    /// [`STAGNATING`] iterations in a row (it sits at its rounding floor above the
    /// tolerance and more iterations cannot help).
    fn newton(&mut self, phi: f64) -> Result<usize, (f64, usize)> {
        let mut previous = f64::INFINITY;
        let mut stalled = 0;
        for iteration in 0..=self.solver.max_iterations {
            self.evaluate_trial(phi);
            let norm = amax(self.trial_residual.as_slice());
            if self.converged() {
                return Ok(iteration);
            }
            stalled = if norm >= previous { stalled + 1 } else { 0 };
            if !norm.is_finite()
                || iteration == self.solver.max_iterations
                || norm > DIVERGING * previous
                || stalled >= STAGNATING
            {
                break;
            }
            previous = norm;
            self.jacobian_trial();
            let solved = self.work_lu.factor(&self.work)
                && self.work_lu.solve(
                    &self.work,
                    self.trial_residual.as_slice(),
                    self.step.as_mut_slice(),
                );
            if !solved {
                break;
            }
            step_pose(&mut self.trial, &mut self.trial_frames, &self.step);
        }
        Err((amax(self.trial_residual.as_slice()), self.worst_loop()))
    }

    /// Whether `trial_residual` is within the tolerance: every position row within
    /// `tolerance × length` of its loop, every angle row within `tolerance` (NaN is not).
    fn converged(&self) -> bool {
        let tolerance = self.solver.tolerance;
        let rows = self.trial_residual.iter().zip(&self.eq.angular);
        rows.zip(&self.lengths.rows)
            .all(|((&r, &angular), &length)| {
                r.abs()
                    <= if angular {
                        tolerance
                    } else {
                        tolerance * length
                    }
            })
    }

    /// Φ(trial, φ) into `trial_residual`.
    pub(super) fn evaluate_trial(&mut self, phi: f64) {
        let f = Frames {
            q: self.trial.as_slice(),
            frames: &self.trial_frames,
        };
        self.eq
            .evaluate_with(&f, phi, self.trial_residual.as_mut_slice());
    }

    /// Φ_q(trial) into `work`.
    fn jacobian_trial(&mut self) {
        let f = Frames {
            q: self.trial.as_slice(),
            frames: &self.trial_frames,
        };
        self.eq.jacobian_with(&f, &mut self.work);
    }

    /// Φ_q at the converged trial pose: factorises it into `work_lu` and sets every loop's
    /// branch certificate in `trial_certificates`, or returns [`Error::Singular`] if a loop's
    /// condition exceeds the limit.
    pub(super) fn check_trial(&mut self, phi: f64) -> Result<(), Error> {
        self.jacobian_trial();
        let factored = self.work_lu.factor(&self.work);
        let limit = self.solver.singular_threshold();
        for (i, l) in self.loops.iter().enumerate() {
            let det = if factored {
                self.work_lu.determinant(i)
            } else {
                0.0
            };
            // Hadamard screen on the scaled block with unit columns (see branch::condition):
            // its determinant is det · Π(row scales) / Π(column norms), the column scales
            // cancelling.
            let screen = &self.screens[i];
            let jac = self.work.as_slice();
            let mut normalized = det * screen.row_scale;
            for column in screen.entries.chunks_exact(l.rows.len()) {
                let norm = column
                    .iter()
                    .map(|&(at, scale)| (jac[at] * scale).powi(2))
                    .sum::<f64>()
                    .sqrt();
                normalized /= norm;
            }
            let bound = screen.bound / normalized.abs();
            if bound.is_nan() || bound > limit {
                let mut scaled = self.work.clone();
                mobility::scale(&self.eq, &mut scaled, &self.lengths);
                let condition = branch::condition(&scaled, l, limit);
                if condition.is_nan() || condition > limit {
                    return Err(Error::Singular {
                        phi,
                        condition,
                        joints: self.loop_joints(l),
                    });
                }
            }
            self.trial_certificates[i] = if det > 0.0 { 1 } else { -1 };
        }
        Ok(())
    }

    /// Makes the checked trial pose current: polishes it with one more Newton step (the
    /// factorisation is at the pose itself, so this takes the residual from the tolerance
    /// down to rounding), then q′ and q″.
    pub(super) fn accept(&mut self, phi: f64) -> Result<(), Error> {
        std::mem::swap(&mut self.jac, &mut self.work);
        std::mem::swap(&mut self.lu, &mut self.work_lu);
        std::mem::swap(&mut self.q, &mut self.trial);
        std::mem::swap(&mut self.frames, &mut self.trial_frames);
        self.phi = phi;
        let polished = Loops {
            jac: &self.jac,
            lu: &self.lu,
        }
        .solve_into(self.trial_residual.as_slice(), self.step.as_mut_slice());
        if polished {
            step_pose(&mut self.q, &mut self.frames, &self.step);
            // Φ_q was factorised at the pose before the polish: where the polish moved it by
            // more than rounding, q′ and q″ from that factorisation would carry the move's
            // relative size (up to the tolerance, 1e-13) instead of rounding. Newton often
            // stops one iteration short of rounding (short steps: a close predictor), so
            // factorise again at the polished pose.
            if self.moved_beyond_rounding() {
                let f = Frames {
                    q: self.q.as_slice(),
                    frames: &self.frames,
                };
                self.eq.jacobian_with(&f, &mut self.jac);
                if !self.lu.factor(&self.jac) {
                    return Err(self.singular(phi));
                }
            }
        }
        let lu = Loops {
            jac: &self.jac,
            lu: &self.lu,
        };
        // Φ_q q′ = −Φ_φ = e_drive (the drive row, last, is the only one that depends on φ);
        // q″ comes with Φ at the polished pose (the reported residual).
        let ok = lu.solve_into(self.unit_drive.as_slice(), self.dq.as_mut_slice())
            && self.second_order.solve(
                &self.eq,
                &lu,
                self.q.as_slice(),
                &self.frames,
                self.dq.as_slice(),
                phi,
                self.ddq.as_mut_slice(),
                self.residual.as_mut_slice(),
            );
        if !ok {
            return Err(self.singular(phi));
        }
        // The certificates of the factorisation just made current (`check_trial`'s).
        self.certificates.copy_from_slice(&self.trial_certificates);
        Ok(())
    }

    /// Whether the polishing step (in `step`) moved a coordinate by more than rounding:
    /// [`REFACTOR_ABOVE`] times its loop's length for a position, times 1 for an angle.
    fn moved_beyond_rounding(&self) -> bool {
        let steps = self.step.iter().enumerate().zip(&self.lengths.columns);
        steps.into_iter().any(|((c, &step), &length)| {
            let scale = if c % 3 == 2 { 1.0 } else { length };
            step.abs() > REFACTOR_ABOVE * scale
        })
    }

    /// The loop whose equations are furthest from being satisfied by the trial residual.
    fn worst_loop(&self) -> usize {
        let mut worst = (0.0, 0);
        for (i, l) in self.loops.iter().enumerate() {
            let x = l
                .rows
                .iter()
                .map(|&row| self.trial_residual[row].abs())
                .fold(0.0, f64::max);
            if x.is_nan() || x > worst.0 {
                worst = (x, i);
            }
        }
        worst.1
    }
}

/// `q −= step`, keeping the bodies' `(sin θ, cos θ)` in `frames` up to date.
fn step_pose(q: &mut DVector<f64>, frames: &mut [(f64, f64)], step: &DVector<f64>) {
    let poses = q.as_mut_slice().chunks_exact_mut(3);
    for ((f, pose), step) in frames
        .iter_mut()
        .zip(poses)
        .zip(step.as_slice().chunks_exact(3))
    {
        let from = pose[2];
        for (x, s) in pose.iter_mut().zip(step) {
            *x -= s;
        }
        *f = frames::turn(*f, from, pose[2]);
    }
}
