//! Position solver: Newton's method in f64, warm-started along a sweep, keeping the branch.
//!
//! [`Solver`] holds the configuration (builder style); [`Solver::track`] starts a [`Tracker`]
//! at the sketch pose, and [`Tracker::move_to`] walks it to a new drive position:
//!
//! 1. **Predict** with the Taylor polynomial `q + h q′ + h²/2 q″` (q′, q″ from the last pose);
//!    the links' sines and cosines are computed there once and then turned along the Newton
//!    steps (see `frames`), so a drive position costs one `sin_cos` per link.
//! 2. **Correct** with Newton on Φ(q, φ) = 0 (analytic Φ_q, factorised loop by loop, see
//!    `block_lu`) until the residual is below `tolerance × size` (size: the sketch's
//!    diagonal).
//! 3. **Check** at the new pose: the scaled Jacobian's condition (a toggle is reported as
//!    [`Error::Singular`]) and every loop's branch certificate (see [`super::branch`]).
//! 4. If Newton fails or a certificate flips, **halve** the step and retry from the last good
//!    pose; after `max_subdivisions` halvings report [`Error::Unassemblable`] or
//!    [`Error::BranchFlip`], naming the drive position and the loop's joints.
//! 5. **Accept**: one more Newton step with the factorisation at the new pose (the residual
//!    drops from the tolerance to rounding), then q′ = Φ_q⁻¹ e_drive and q″ (see
//!    [`super::implicit`]) with the same factorisation; they feed the next predictor and
//!    [`Tracker::kinematics`].
//!
//! **Closed forms first.** Loops that match a standard pattern (driven crank, slotted
//! rocker, translating slide, RRR and RRP dyads, …; see `closed_form`) are solved by their
//! formulas instead: when every loop matches, [`Tracker::move_to`] evaluates them once in
//! `Dual2_64` (q, q′, q″ at once; q‴ in `Dual3_64` on request) and none of the steps above
//! runs, except the halving of the step towards a position that does not assemble; Φ is
//! not evaluated either ([`SolveReport::residual`] is `None`, [`Tracker::residual`]
//! evaluates it on request). When
//! only some match, they place their links in Newton's predictor. Branches are kept the
//! same way (each formula's root is fixed at the sketch); [`Solver::with_closed_form`]
//! turns this off.
//!
//! Nothing is allocated per drive position: the tracker keeps its buffers, and the loop
//! structure is resolved to storage positions once (see `block_lu`). In a loop, read outputs
//! through handles resolved once ([`Mechanism::point_output`] and the methods next to it)
//! rather than by name, and, to second order, straight from the tracker
//! ([`Tracker::value`], [`Tracker::position`]: no [`Kinematics`] built).

mod closed_path;
mod reading;

use super::block_lu::BlockLu;
use super::branch::{self, Loop};
use super::closed_form::ClosedForm;
use super::constraints::{Equations, Frames};
use super::frames;
use super::implicit::{Factorised, SecondOrder};
use super::kinematics::Kinematics;
use super::mobility::{self, Mobility};
use super::model::Mechanism;
use crate::Error;
use nalgebra::{DMatrix, DVector};
use num_dual::Dual2_64;

/// Configuration of the position solver.
///
/// ```
/// use mechdiff_core::geometry::Solver;
/// let solver = Solver::default().with_tolerance(1e-13).with_max_iterations(30);
/// assert_eq!(solver.tolerance, 1e-13);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Solver {
    /// Newton stops when max |Φ| ≤ tolerance × (sketch size); dimensionless.
    pub tolerance: f64,
    /// Newton iterations allowed per attempt.
    pub max_iterations: usize,
    /// Step halvings allowed before a failure is reported.
    pub max_subdivisions: usize,
    /// A loop whose scaled Φ_q block has a condition number above this is singular (a
    /// toggle). `None` (the default) means `0.1 / √tolerance`: at an exact toggle Newton
    /// converges only to ~√tolerance, which leaves a condition of ~1/√tolerance (3e6 for
    /// 1e-13, measured on a slider-crank driven into its dead centre), ten times above it;
    /// a regular pose that close to a toggle has lost half the digits of q′ anyway.
    pub singular_condition: Option<f64>,
    /// Solve the loops that match a standard pattern in closed form (default `true`; see
    /// `closed_form`): when every loop matches, a drive position costs one evaluation of
    /// the formulas in `Dual2_64`, with no Newton iteration and no LU; otherwise the
    /// formulas place their loops' links as Newton's predictor. `false` forces the Newton
    /// path everywhere (the reference the closed forms are tested against).
    pub closed_form: bool,
}

impl Default for Solver {
    fn default() -> Self {
        Solver {
            tolerance: 1e-13,
            max_iterations: 50,
            max_subdivisions: 24,
            singular_condition: None,
            closed_form: true,
        }
    }
}

impl Solver {
    /// Sets the residual tolerance (relative to the sketch size).
    pub fn with_tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = tolerance;
        self
    }

    /// Sets the Newton iterations allowed per attempt.
    pub fn with_max_iterations(mut self, max_iterations: usize) -> Self {
        self.max_iterations = max_iterations;
        self
    }

    /// Sets how often a failing step may be halved.
    pub fn with_max_subdivisions(mut self, max_subdivisions: usize) -> Self {
        self.max_subdivisions = max_subdivisions;
        self
    }

    /// Sets the condition number above which a pose is reported singular.
    pub fn with_singular_condition(mut self, condition: f64) -> Self {
        self.singular_condition = Some(condition);
        self
    }

    /// Enables (default) or disables the closed-form solution of standard loops.
    pub fn with_closed_form(mut self, closed_form: bool) -> Self {
        self.closed_form = closed_form;
        self
    }

    /// Solves `m` at every drive position of `phis` in order, starting from the sketch pose,
    /// and lifts each pose to `N` derivatives.
    pub fn sweep<'m, const N: usize>(
        &self,
        m: &'m Mechanism,
        phis: &[f64],
    ) -> Result<Vec<Kinematics<'m, N>>, Error> {
        let mut tracker = self.track(m)?;
        phis.iter()
            .map(|&phi| {
                tracker.move_to(phi)?;
                tracker.kinematics::<N>()
            })
            .collect()
    }

    /// The condition number above which a loop is singular (see [`Solver::singular_condition`]).
    pub fn singular_threshold(&self) -> f64 {
        self.singular_condition
            .unwrap_or(0.1 / self.tolerance.sqrt())
    }

    /// Checks mobility and starts tracking `m` at its sketch pose.
    pub fn track<'m>(&self, m: &'m Mechanism) -> Result<Tracker<'m>, Error> {
        let mobility = mobility::check_mobility(m)?;
        let eq = Equations::new(m);
        let loops = branch::loops(&eq).ok_or_else(|| Error::Underconstrained {
            free: 0,
            links: Vec::new(),
            joints: m.joints.iter().map(|j| j.name.clone()).collect(),
        })?;
        let n = eq.coordinates();
        let size = super::validate::sketch_size(m);
        let row_columns = branch::structure(&eq);
        let mut unit_drive = DVector::zeros(n);
        unit_drive[n - 1] = 1.0;
        // The Hadamard screen's constants per loop (see `Tracker::check_trial`).
        let screens = loops
            .iter()
            .map(|l| {
                let k = l.rows.len() as f64;
                let angular = l.rows.iter().filter(|&&r| eq.angular[r]).count();
                let weight = |r: usize| if eq.angular[r] { size } else { 1.0 };
                Screen {
                    bound: k.powf(0.5 * k),
                    row_scale: size.powi(angular as i32),
                    entries: l
                        .columns
                        .iter()
                        .flat_map(|&c| l.rows.iter().map(move |&r| (c * n + r, weight(r))))
                        .collect(),
                }
            })
            .collect();
        let q = DVector::from_vec(m.sketch_coordinates());
        let closed = ClosedForm::new(
            &eq,
            &loops,
            q.as_slice(),
            m.drive_at_sketch,
            size,
            self.singular_threshold(),
        );
        let frames: Vec<(f64, f64)> = (0..n / 3).map(|k| q[3 * k + 2].sin_cos()).collect();
        let mut t = Tracker {
            unit_drive,
            mechanism: m,
            solver: *self,
            mobility,
            jac: DMatrix::zeros(n, n),
            lu: BlockLu::new(&loops, &row_columns),
            work: DMatrix::zeros(n, n),
            work_lu: BlockLu::new(&loops, &row_columns),
            residual: DVector::zeros(n),
            trial: DVector::zeros(n),
            trial_frames: frames.clone(),
            trial_residual: DVector::zeros(n),
            step: DVector::zeros(n),
            q,
            frames,
            phi: m.drive_at_sketch,
            dq: DVector::zeros(n),
            ddq: DVector::zeros(n),
            second_order: SecondOrder::new(n),
            certificates: vec![0; loops.len()],
            trial_certificates: vec![0; loops.len()],
            screens,
            closed_only: self.closed_form && closed.complete(),
            seeding: self.closed_form && !closed.complete() && closed.count() > 0,
            closed,
            closed_q: vec![Dual2_64::from(0.0); n],
            closed_frames: vec![(Dual2_64::from(0.0), Dual2_64::from(0.0)); n / 3],
            loops,
            size,
            eq,
        };
        t.trial.copy_from(&t.q);
        let phi = t.phi;
        t.evaluate_trial(phi);
        t.check_trial(phi)?;
        t.accept(phi)?;
        Ok(t)
    }
}

/// How a move ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolveReport {
    /// Drive position reached.
    pub phi: f64,
    /// Newton iterations used in total (all sub-steps).
    pub iterations: usize,
    /// Sub-steps accepted (1 if the whole step was accepted at once).
    pub steps: usize,
    /// Final max |Φ| (m or rad) on the Newton path. `None` when every loop is solved in
    /// closed form: the formulas close the loops by construction (up to rounding), so Φ is
    /// not evaluated per position; [`Tracker::residual`] computes it on request.
    pub residual: Option<f64>,
    /// Sub-steps rejected because Newton landed on another assembly branch.
    pub branch_rejections: usize,
    /// Sub-steps rejected because Newton did not converge (on the closed-form path:
    /// because a loop could not assemble).
    pub newton_failures: usize,
}

/// A mechanism being walked along its drive, one assembly branch kept.
#[derive(Debug, Clone)]
pub struct Tracker<'m> {
    mechanism: &'m Mechanism,
    solver: Solver,
    mobility: Mobility,
    eq: Equations,
    loops: Vec<Loop>,
    size: f64,
    /// Φ_q at the current pose and its factorisation (reused for q′, q″, q‴).
    jac: DMatrix<f64>,
    lu: BlockLu,
    /// Scratch Jacobian and factorisation for trial poses.
    work: DMatrix<f64>,
    work_lu: BlockLu,
    residual: DVector<f64>,
    trial: DVector<f64>,
    /// `(sin θ, cos θ)` of every body of `trial`.
    trial_frames: Vec<(f64, f64)>,
    trial_residual: DVector<f64>,
    step: DVector<f64>,
    /// e_drive = −Φ_φ.
    unit_drive: DVector<f64>,
    q: DVector<f64>,
    /// `(sin θ, cos θ)` of every body of `q`.
    frames: Vec<(f64, f64)>,
    phi: f64,
    dq: DVector<f64>,
    ddq: DVector<f64>,
    second_order: SecondOrder,
    certificates: Vec<i8>,
    trial_certificates: Vec<i8>,
    screens: Vec<Screen>,
    /// The loops' closed forms (see `closed_form`).
    closed: ClosedForm,
    /// Every loop is solved in closed form (no Newton, no LU).
    closed_only: bool,
    /// Some loops are: their formulas seed Newton's predictor.
    seeding: bool,
    /// The closed forms' pose and `(sin θ, cos θ)` in `Dual2_64` (buffers).
    closed_q: Vec<Dual2_64>,
    closed_frames: Vec<(Dual2_64, Dual2_64)>,
}

/// Constants of one loop's singularity screen.
#[derive(Debug, Clone, PartialEq)]
struct Screen {
    /// The block's entries column by column: (position in Φ_q's storage, row scale).
    entries: Vec<(usize, f64)>,
    /// k^(k/2) for a k×k block: the condition bound is this over the normalised determinant.
    bound: f64,
    /// size^(angular rows of the loop): the row scaling's factor in the determinant.
    row_scale: f64,
}

impl<'m> Tracker<'m> {
    /// The mechanism tracked.
    pub fn mechanism(&self) -> &'m Mechanism {
        self.mechanism
    }

    /// The mobility found when tracking started.
    pub fn mobility(&self) -> Mobility {
        self.mobility
    }

    /// Current drive position.
    pub fn phi(&self) -> f64 {
        self.phi
    }

    /// Current pose coordinates `(x, y, θ)` per moving link.
    pub fn coordinates(&self) -> &[f64] {
        self.q.as_slice()
    }

    /// The loops (joint names per loop, in solving order) and their branch certificates
    /// (when every loop is in closed form, those of the sketch: the formulas keep its
    /// branches).
    pub fn loops(&self) -> Vec<(Vec<String>, i8)> {
        self.loops
            .iter()
            .zip(&self.certificates)
            .map(|(l, &c)| (self.loop_joints(l), c))
            .collect()
    }

    /// Per loop (in the order of [`Tracker::loops`]), whether it is solved in closed form
    /// (see [`Solver::closed_form`]); with some loops not, the others only seed Newton.
    pub fn closed_form_loops(&self) -> Vec<bool> {
        let on = self.closed_only || self.seeding;
        self.closed.matched().map(|m| m && on).collect()
    }

    fn loop_joints(&self, l: &Loop) -> Vec<String> {
        let m = self.mechanism;
        let mut names: Vec<String> = Vec::new();
        for &r in &l.rows {
            let j = self.eq.row_joint[r];
            let name = if j == m.joints.len() {
                format!("drive `{}`", m.joints[m.drive_joint].name)
            } else {
                m.joints[j].name.clone()
            };
            if !names.contains(&name) {
                names.push(name);
            }
        }
        names
    }

    fn singular(&self, phi: f64) -> Error {
        Error::Singular {
            phi,
            condition: f64::INFINITY,
            joints: self
                .mechanism
                .joints
                .iter()
                .map(|j| j.name.clone())
                .collect(),
        }
    }

    /// Moves to drive position `phi`, keeping every loop on its branch.
    pub fn move_to(&mut self, phi: f64) -> Result<SolveReport, Error> {
        if !phi.is_finite() {
            return Err(Error::NonFinite {
                phi,
                quantity: "drive position",
            });
        }
        let mut report = SolveReport {
            phi: self.phi,
            iterations: 0,
            steps: 0,
            residual: None,
            branch_rejections: 0,
            newton_failures: 0,
        };
        if self.closed_only {
            return self.move_closed(phi);
        }
        let mut halvings: usize = 0;
        while self.phi != phi {
            let h = (phi - self.phi) / f64::powi(2.0, halvings.min(1074) as i32);
            let target = if halvings == 0 { phi } else { self.phi + h };
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
            let failure = match self.newton(target) {
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
                            halvings = halvings.saturating_sub(1);
                            continue;
                        }
                        Some(l) => {
                            report.branch_rejections += 1;
                            Error::BranchFlip {
                                from: self.phi,
                                to: target,
                                joints: self.loop_joints(&self.loops[l]),
                            }
                        }
                    }
                }
                Err((residual, l)) => {
                    report.newton_failures += 1;
                    Error::Unassemblable {
                        phi,
                        last_assembled: self.phi,
                        joints: self.loop_joints(&self.loops[l]),
                        residual,
                    }
                }
            };
            halvings += 1;
            // Give up after the allowed halvings, or once a halved step no longer moves φ.
            let next = self.phi + (phi - self.phi) / f64::powi(2.0, halvings.min(1074) as i32);
            if halvings > self.solver.max_subdivisions || next == self.phi {
                return Err(failure);
            }
        }
        report.phi = self.phi;
        report.residual = Some(amax(self.residual.as_slice()));
        Ok(report)
    }

    /// Newton on `trial` at drive position `phi`: the iterations, or the final residual and
    /// the loop with the largest residual. Leaves Φ(trial) in `trial_residual`.
    fn newton(&mut self, phi: f64) -> Result<usize, (f64, usize)> {
        let limit = self.solver.tolerance * self.size;
        for iteration in 0..=self.solver.max_iterations {
            self.evaluate_trial(phi);
            let norm = amax(self.trial_residual.as_slice());
            if norm <= limit {
                return Ok(iteration);
            }
            if !norm.is_finite() || iteration == self.solver.max_iterations {
                break;
            }
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

    /// Φ(trial, φ) into `trial_residual`.
    fn evaluate_trial(&mut self, phi: f64) {
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
    fn check_trial(&mut self, phi: f64) -> Result<(), Error> {
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
                mobility::scale(&self.eq, &mut scaled, self.size);
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
    fn accept(&mut self, phi: f64) -> Result<(), Error> {
        std::mem::swap(&mut self.jac, &mut self.work);
        std::mem::swap(&mut self.lu, &mut self.work_lu);
        std::mem::swap(&mut self.q, &mut self.trial);
        std::mem::swap(&mut self.frames, &mut self.trial_frames);
        self.phi = phi;
        let lu = Loops {
            jac: &self.jac,
            lu: &self.lu,
        };
        if lu.solve_into(self.trial_residual.as_slice(), self.step.as_mut_slice()) {
            step_pose(&mut self.q, &mut self.frames, &self.step);
        }
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

/// max |x_i|, NaN if any x_i is NaN.
fn amax(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |m, &v| {
        if v.abs() > m || v.is_nan() {
            v.abs()
        } else {
            m
        }
    })
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

/// A factorised Φ_q with the matrix it came from, as a linear solver.
struct Loops<'a> {
    jac: &'a DMatrix<f64>,
    lu: &'a BlockLu,
}

impl Factorised for Loops<'_> {
    fn solve_into(&self, b: &[f64], x: &mut [f64]) -> bool {
        self.lu.solve(self.jac, b, x)
    }
}
