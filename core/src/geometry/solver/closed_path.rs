//! The all-closed-form path of [`Tracker::move_to`]: one evaluation of the loops' formulas
//! in `Dual2_64` per drive position, written into the tracker's q, q′, q″.

use super::{SolveReport, Tracker};
use crate::Error;
use crate::geometry::closed_form::Failure;
use num_dual::Dual2_64;

impl Tracker<'_> {
    /// Moves to `phi` with every loop in closed form: q, q′, q″ from one evaluation of the
    /// formulas in `Dual2_64`. Where a loop cannot assemble at `phi`, the step is halved
    /// (as on the Newton path) so that the tracker ends at the last position that
    /// assembles, reported in the error.
    pub(super) fn move_closed(&mut self, phi: f64) -> Result<SolveReport, Error> {
        let mut report = SolveReport::starting(phi);
        let mut halvings: usize = 0;
        while self.phi != phi || report.steps == 0 {
            let target = if halvings == 0 {
                phi
            } else {
                self.phi + (phi - self.phi) / f64::powi(2.0, halvings.min(1074) as i32)
            };
            let x = Dual2_64::new(target, 1.0, 0.0);
            let (q, frames) = (&mut self.closed_q, &mut self.closed_frames);
            match self.closed.solve_all(x, self.q.as_slice(), q, frames) {
                Ok(()) => {
                    self.accept_closed(target);
                    report.steps += 1;
                    halvings = halvings.saturating_sub(1);
                }
                Err((l, failure @ Failure::Unassemblable { .. })) => {
                    report.newton_failures += 1;
                    halvings += 1;
                    let next =
                        self.phi + (phi - self.phi) / f64::powi(2.0, halvings.min(1074) as i32);
                    if halvings > self.solver.max_subdivisions || next == self.phi {
                        return Err(self.closed_failure(phi, l, failure));
                    }
                }
                Err((l, failure)) => return Err(self.closed_failure(target, l, failure)),
            }
        }
        Ok(report)
    }

    /// Makes the closed forms' pose (in `closed_q`, `closed_frames`) current at `phi`.
    fn accept_closed(&mut self, phi: f64) {
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
        // Φ is not evaluated: the formulas close the loops by construction (see
        // `SolveReport::residual`, and `Tracker::residual` to check it).
        self.phi = phi;
    }

    /// The error for loop `l`'s closed form failing at `phi`.
    pub(super) fn closed_failure(&self, phi: f64, l: usize, failure: Failure) -> Error {
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
