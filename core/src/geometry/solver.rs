//! Position solver: Newton's method in f64, warm-started along a sweep, keeping the branch.
//!
//! [`Solver`] holds the configuration (builder style); [`Solver::track`] starts a [`Tracker`]
//! at the sketch pose, and [`Tracker::move_to`] walks it to a new drive position:
//!
//! 1. **Predict** with the Taylor polynomial `q + h q′ + h²/2 q″` (q′, q″ from the last pose);
//!    the links' sines and cosines are computed there once and then turned along the Newton
//!    steps (see `frames`), so a drive position costs one `sin_cos` per link.
//! 2. **Correct** with Newton on Φ(q, φ) = 0 (analytic Φ_q, factorised loop by loop, see
//!    `block_lu`) until every loop's residual is below `tolerance × length` for its
//!    positions (m) and `tolerance` for its angles (rad), `length` the loop's own length
//!    scale (see `length`).
//! 3. **Check** at the new pose: the scaled Jacobian's condition (a toggle is reported as
//!    [`Error::Singular`]) and every loop's branch certificate (see [`super::branch`]).
//! 4. If Newton fails or a certificate flips, **halve** the step and retry from the last good
//!    pose; after `max_subdivisions` halvings report [`Error::Unassemblable`] or
//!    [`Error::BranchFlip`], naming the drive position and the loop's joints (the walk of
//!    [`super::halving`], shared with the traced trackers and the generated code).
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
pub(crate) mod interval;
mod newton_path;
mod range;
mod reading;
pub use reading::PoseJets;

pub use range::{DriveLimit, LimitKind, MotionRange};

use super::block_lu::BlockLu;
use super::branch::{self, Loop};
use super::closed_form::ClosedForm;
use super::constraints::Equations;
use super::implicit::{Factorised, SecondOrder};
use super::kinematics::Kinematics;
use super::length::LoopLengths;
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
    /// Newton stops when every loop's |Φ| ≤ tolerance × (the loop's length scale) for its
    /// positions, ≤ tolerance for its angles; dimensionless.
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
    /// Sets the residual tolerance (relative to each loop's length scale).
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
        let lengths = LoopLengths::new(m, &eq, &loops);
        let row_columns = branch::structure(&eq);
        let mut unit_drive = DVector::zeros(n);
        unit_drive[n - 1] = 1.0;
        // The Hadamard screen's constants per loop (see `Tracker::check_trial`).
        let screens = loops
            .iter()
            .zip(&lengths.loops)
            .map(|(l, &length)| {
                let k = l.rows.len() as f64;
                let angular = l.rows.iter().filter(|&&r| eq.angular[r]).count();
                let weight = |r: usize| if eq.angular[r] { length } else { 1.0 };
                Screen {
                    bound: k.powf(0.5 * k),
                    row_scale: length.powi(angular as i32),
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
            &lengths.loops,
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
            margins: vec![Dual2_64::from(1.0); loops.len()],
            closed_margins: vec![Dual2_64::from(1.0); loops.len()],
            loops,
            lengths,
            eq,
        };
        t.trial.copy_from(&t.q);
        let phi = t.phi;
        t.evaluate_trial(phi);
        t.check_trial(phi)?;
        t.accept(phi)?;
        if t.closed_only {
            // The margins (and their derivatives) at the sketch, for the first step's check.
            t.evaluate_closed(phi)
                .map_err(|(l, failure)| t.closed_failure(phi, l, failure))?;
            t.margins.copy_from_slice(&t.closed_margins);
        }
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

impl SolveReport {
    /// A move to `phi` before any sub-step: nothing counted yet.
    fn starting(phi: f64) -> Self {
        SolveReport {
            phi,
            iterations: 0,
            steps: 0,
            residual: None,
            branch_rejections: 0,
            newton_failures: 0,
        }
    }
}

/// A mechanism being walked along its drive, one assembly branch kept.
#[derive(Debug, Clone)]
pub struct Tracker<'m> {
    mechanism: &'m Mechanism,
    solver: Solver,
    mobility: Mobility,
    eq: Equations,
    loops: Vec<Loop>,
    /// Each loop's own length scale: what every threshold is measured in (see `length`).
    lengths: LoopLengths,
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
    /// Every closed-form loop's margin (see `closed_form`) at the current pose, with its
    /// derivatives in φ, and at the trial position (buffer).
    margins: Vec<Dual2_64>,
    closed_margins: Vec<Dual2_64>,
}

/// Constants of one loop's singularity screen.
#[derive(Debug, Clone, PartialEq)]
struct Screen {
    /// The block's entries column by column: (position in Φ_q's storage, row scale).
    entries: Vec<(usize, f64)>,
    /// k^(k/2) for a k×k block: the condition bound is this over the normalised determinant.
    bound: f64,
    /// length^(angular rows of the loop), its loop's length: the row scaling's factor in the
    /// determinant.
    row_scale: f64,
}

impl<'m> Tracker<'m> {
    /// The mechanism tracked.
    pub fn mechanism(&self) -> &'m Mechanism {
        self.mechanism
    }

    /// The linkage's length scale (m): the extent of the points its loops' equations involve
    /// (a point that takes part in no loop's closure does not count). What the solver
    /// measures a displacement drive's steps in.
    pub fn length_scale(&self) -> f64 {
        self.lengths.linkage
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

    /// How much the current pose amplifies rounding, and in which loop (its joints): for
    /// each closed-form loop, its lever's length in the sketch over its length now (see
    /// `closed_form`: `1/√margin`, 1 in the sketch's shape). A pose is
    /// ill-conditioned when this is large: its coordinates and coefficients carry a
    /// relative error of about `amplification × f64::EPSILON` (e.g. a slotted lever whose
    /// pin passes 1e-6 of its length from the hinge: ψ′ ≈ 1e6, amplification 1e6, error
    /// ~2e-10). Loops on the Newton path count 1 (their conditioning is checked against
    /// [`Solver::singular_threshold`] instead).
    pub fn amplification(&self) -> (f64, Vec<String>) {
        let (amplification, l) = self.amplification_loop();
        (amplification, self.joints_of_loop(l))
    }

    /// [`Tracker::amplification`] with its loop as an index (in the order of
    /// [`Tracker::loops`], named by [`Tracker::joints_of_loop`]): nothing allocated, for a
    /// check at every position of a sweep.
    pub fn amplification_loop(&self) -> (f64, usize) {
        let mut worst = (1.0, 0);
        if self.closed_only {
            for (l, m) in self.margins.iter().enumerate() {
                let k = self.closed.amplification(l, m.re);
                if k > worst.0 || k.is_nan() {
                    worst = (k, l);
                }
            }
        }
        worst
    }

    /// [`Tracker::amplification_loop`] where it exceeds `limit` (≥ 1) or is NaN, `None`
    /// where every loop's amplification is at most `limit`: cheap checks first (each
    /// margin against the limit, no square root or division), for a sweep that reports only
    /// the positions that amplify rounding by more than a limit.
    pub fn amplification_over(&self, limit: f64) -> Option<(f64, usize)> {
        let within = |(l, m): (usize, &Dual2_64)| self.closed.surely_within(l, m.re, limit);
        if !self.closed_only || self.margins.iter().enumerate().all(within) {
            return None;
        }
        Some(self.amplification_loop()).filter(|(k, _)| *k > limit || k.is_nan())
    }

    /// Whether `other` (a tracker of the same mechanism and solver) is in the same state as
    /// this one, bit for bit: drive position, pose, `(sin θ, cos θ)`, q′, q″, branch
    /// certificates, the closed-form loops' margins and buffers, Φ_q (its factorisation is
    /// always made from it) and the last residual. Every move reads only these (its other
    /// buffers are written before they are read), so two trackers in the same state give
    /// the same results, bit for bit, for the same moves: a sweep split into pieces solved
    /// from states found another way is the sequential sweep exactly where the states
    /// agree at the pieces' joins.
    pub fn same_state(&self, other: &Tracker<'_>) -> bool {
        fn same<T>(a: &[T], b: &[T], bits: impl Fn(&T) -> [u64; 6]) -> bool {
            a.len() == b.len() && a.iter().zip(b).all(|(x, y)| bits(x) == bits(y))
        }
        let real = |x: &f64| [x.to_bits(), 0, 0, 0, 0, 0];
        let dual = |x: &Dual2_64| [x.re, x.v1, x.v2, 0.0, 0.0, 0.0].map(f64::to_bits);
        let frame = |(s, c): &(f64, f64)| [*s, *c, 0.0, 0.0, 0.0, 0.0].map(f64::to_bits);
        let dual_frame =
            |(s, c): &(Dual2_64, Dual2_64)| [s.re, s.v1, s.v2, c.re, c.v1, c.v2].map(f64::to_bits);
        std::ptr::eq(self.mechanism, other.mechanism)
            && self.solver == other.solver
            && self.closed_only == other.closed_only
            && self.seeding == other.seeding
            && self.phi.to_bits() == other.phi.to_bits()
            && same(self.q.as_slice(), other.q.as_slice(), real)
            && same(self.dq.as_slice(), other.dq.as_slice(), real)
            && same(self.ddq.as_slice(), other.ddq.as_slice(), real)
            && same(&self.frames, &other.frames, frame)
            && self.certificates == other.certificates
            && same(&self.margins, &other.margins, dual)
            && same(&self.closed_q, &other.closed_q, dual)
            && same(&self.closed_frames, &other.closed_frames, dual_frame)
            && same(&self.closed_margins, &other.closed_margins, dual)
            && same(self.jac.as_slice(), other.jac.as_slice(), real)
            && same(self.residual.as_slice(), other.residual.as_slice(), real)
    }

    /// The loops' closed forms, when every loop has one (see `trace`).
    pub(crate) fn closed_forms(&self) -> Option<&ClosedForm> {
        self.closed_only.then_some(&self.closed)
    }

    /// The loops' closed forms, every loop's (`None` steps are solved by Newton), for a
    /// trace of a mixed plan (see `trace`).
    pub(crate) fn closed_form_table(&self) -> &ClosedForm {
        &self.closed
    }

    /// The equations, the loops' rows and columns, and their length scales (the solver's
    /// scales, for a trace of a Newton loop).
    pub(crate) fn structure(&self) -> (&Equations, &[Loop], &LoopLengths) {
        (&self.eq, &self.loops, &self.lengths)
    }

    /// The solver's configuration.
    pub(crate) fn solver(&self) -> Solver {
        self.solver
    }

    /// The singular threshold of the solver tracking (see [`Solver::singular_threshold`]).
    pub(crate) fn solver_singular_threshold(&self) -> f64 {
        self.solver.singular_threshold()
    }

    /// The joints of loop `l` (in the order of [`Tracker::loops`]).
    pub fn joints_of_loop(&self, l: usize) -> Vec<String> {
        self.loop_joints(&self.loops[l])
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
        if self.closed_only {
            self.move_closed(phi)
        } else {
            self.move_newton(phi)
        }
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
