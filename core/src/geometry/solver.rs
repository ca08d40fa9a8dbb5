//! Position solver: Newton's method in f64, warm-started along a sweep, keeping the branch.
//!
//! [`Solver`] holds the configuration (builder style); [`Solver::track`] starts a [`Tracker`]
//! at the sketch pose, and [`Tracker::move_to`] walks it to a new drive position:
//!
//! 1. **Predict** with the Taylor polynomial `q + h q′ + h²/2 q″` (q′, q″ from the last pose).
//! 2. **Correct** with Newton on Φ(q, φ) = 0 (analytic Φ_q, LU) until the residual is below
//!    `tolerance × size` (size: the sketch's diagonal).
//! 3. **Check** at the new pose: the scaled Jacobian's condition (a toggle is reported as
//!    [`Error::Singular`]) and every loop's branch certificate (see [`super::branch`]).
//! 4. If Newton fails or a certificate flips, **halve** the step and retry from the last good
//!    pose; after `max_subdivisions` halvings report [`Error::Unassemblable`] or
//!    [`Error::BranchFlip`], naming the drive position and the loop's joints.

use super::branch::{self, Loop};
use super::constraints::Equations;
use super::mobility::{self, Mobility};
use super::model::Mechanism;
use super::implicit;
use super::kinematics::Kinematics;
use crate::{Error, Jet};
use nalgebra::{DMatrix, DVector, LU};

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
}

impl Default for Solver {
    fn default() -> Self {
        Solver { tolerance: 1e-13, max_iterations: 50, max_subdivisions: 24, singular_condition: None }
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
        self.singular_condition.unwrap_or(0.1 / self.tolerance.sqrt())
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
        let mut t = Tracker {
            mechanism: m,
            solver: *self,
            mobility,
            jac: DMatrix::zeros(n, n),
            work: DMatrix::zeros(n, n),
            residual: DVector::zeros(n),
            q: DVector::from_vec(m.sketch_coordinates()),
            phi: m.drive_at_sketch,
            lu: None,
            dq: DVector::zeros(n),
            ddq: DVector::zeros(n),
            certificates: Vec::new(),
            loops,
            size,
            eq,
        };
        t.certificates = t.refresh(t.phi)?;
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
    /// Sub-steps taken (1 if the whole step was accepted at once).
    pub steps: usize,
    /// Final max |Φ| (m or rad).
    pub residual: f64,
    /// Sub-steps rejected because Newton landed on another assembly branch.
    pub branch_rejections: usize,
    /// Sub-steps rejected because Newton did not converge.
    pub newton_failures: usize,
}

/// A mechanism being walked along its drive, one assembly branch kept.
#[derive(Debug, Clone)]
pub struct Tracker<'m> {
    mechanism: &'m Mechanism,
    solver: Solver,
    mobility: Mobility,
    pub(crate) eq: Equations,
    loops: Vec<Loop>,
    size: f64,
    jac: DMatrix<f64>,
    /// Scratch Jacobian for Newton iterations.
    work: DMatrix<f64>,
    residual: DVector<f64>,
    pub(crate) q: DVector<f64>,
    pub(crate) phi: f64,
    /// LU of Φ_q at (q, φ), reused for q′, q″, q‴.
    pub(crate) lu: Option<LU<f64, nalgebra::Dyn, nalgebra::Dyn>>,
    pub(crate) dq: DVector<f64>,
    ddq: DVector<f64>,
    certificates: Vec<i8>,
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

    /// The loops (joint names per loop, in solving order) and their branch certificates.
    pub fn loops(&self) -> Vec<(Vec<String>, i8)> {
        self.loops
            .iter()
            .zip(&self.certificates)
            .map(|(l, &c)| (self.loop_joints(l), c))
            .collect()
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

    /// The pose at the current drive position with its first `N` (1 ≤ N ≤ 3) exact
    /// derivatives with respect to φ, by implicit differentiation with the LU already
    /// computed for the pose (see [`super::implicit`]).
    pub fn kinematics<const N: usize>(&self) -> Result<Kinematics<'m, N>, Error> {
        const { assert!(N >= 1 && N <= 3, "the geometry solver lifts derivatives of order 1 to 3") };
        let singular = || Error::Singular {
            phi: self.phi,
            condition: f64::INFINITY,
            joints: self.mechanism.joints.iter().map(|j| j.name.clone()).collect(),
        };
        let lu = self.lu.as_ref().ok_or_else(singular)?;
        let dddq = if N == 3 {
            implicit::third_derivative(&self.eq, lu, &self.q, &self.dq, &self.ddq, self.phi)
                .ok_or_else(singular)?
        } else {
            DVector::zeros(0)
        };
        let coordinates = (0..self.q.len())
            .map(|i| {
                let d = [self.dq[i], self.ddq[i], dddq.get(i).copied().unwrap_or(0.0)];
                Jet::new(self.q[i], std::array::from_fn(|k| d[k]))
            })
            .collect();
        Ok(Kinematics::new(self.mechanism, self.phi, coordinates))
    }

    /// Moves to drive position `phi`, keeping every loop on its branch.
    pub fn move_to(&mut self, phi: f64) -> Result<SolveReport, Error> {
        if !phi.is_finite() {
            return Err(Error::NonFinite { phi, quantity: "drive position" });
        }
        let mut report = SolveReport {
            phi: self.phi,
            iterations: 0,
            steps: 0,
            residual: 0.0,
            branch_rejections: 0,
            newton_failures: 0,
        };
        let mut halvings: usize = 0;
        while self.phi != phi {
            let h = (phi - self.phi) / f64::powi(2.0, halvings as i32);
            let target = if halvings == 0 { phi } else { self.phi + h };
            let start = &self.q + &self.dq * h + &self.ddq * (0.5 * h * h);
            let failure = match self.newton(start, target) {
                Ok((q, iterations)) => {
                    report.iterations += iterations;
                    let saved = self.save();
                    self.q = q;
                    let certificates = self.refresh(target)?;
                    match certificates.iter().zip(&self.certificates).position(|(a, b)| a != b) {
                        None => {
                            report.steps += 1;
                            halvings = halvings.saturating_sub(1);
                            continue;
                        }
                        Some(l) => {
                            let joints = self.loop_joints(&self.loops[l]);
                            self.restore(saved);
                            report.branch_rejections += 1;
                            Error::BranchFlip { from: self.phi, to: target, joints }
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
            if halvings > self.solver.max_subdivisions {
                return Err(failure);
            }
        }
        report.phi = self.phi;
        report.residual = self.residual.amax();
        Ok(report)
    }

    fn save(&self) -> Saved {
        Saved {
            q: self.q.clone(),
            phi: self.phi,
            jac: self.jac.clone(),
            residual: self.residual.clone(),
            lu: self.lu.clone(),
            dq: self.dq.clone(),
            ddq: self.ddq.clone(),
        }
    }

    fn restore(&mut self, s: Saved) {
        (self.q, self.phi, self.jac, self.residual) = (s.q, s.phi, s.jac, s.residual);
        (self.lu, self.dq, self.ddq) = (s.lu, s.dq, s.ddq);
    }

    /// Newton from `start` at drive position `phi`: the converged q and the iterations, or
    /// the final residual and the loop with the largest residual.
    fn newton(&mut self, start: DVector<f64>, phi: f64) -> Result<(DVector<f64>, usize), (f64, usize)> {
        let mut q = start;
        let mut r = DVector::zeros(self.residual.len());
        let limit = self.solver.tolerance * self.size;
        for iteration in 0..=self.solver.max_iterations {
            self.eq.evaluate(q.as_slice(), phi, r.as_mut_slice());
            let norm = r.amax();
            if norm <= limit {
                return Ok((q, iteration));
            }
            if !norm.is_finite() || iteration == self.solver.max_iterations {
                break;
            }
            self.eq.jacobian(q.as_slice(), &mut self.work);
            match self.work.clone().lu().solve(&r) {
                Some(step) if step.iter().all(|s| s.is_finite()) => q -= step,
                _ => break,
            }
        }
        Err((r.amax(), self.worst_loop(&r)))
    }

    /// Accepts the pose `q` at `phi`: Jacobian, LU, q′, q″; returns the loops' branch
    /// certificates, or [`Error::Singular`].
    fn refresh(&mut self, phi: f64) -> Result<Vec<i8>, Error> {
        self.phi = phi;
        self.eq.evaluate(self.q.as_slice(), phi, self.residual.as_mut_slice());
        self.eq.jacobian(self.q.as_slice(), &mut self.jac);
        let mut scaled = self.jac.clone();
        mobility::scale(&self.eq, &mut scaled, self.size);
        let mut certificates = Vec::with_capacity(self.loops.len());
        for l in &self.loops {
            let limit = self.solver.singular_threshold();
            let (sign, condition) = branch::certificate(&scaled, l, limit);
            if !(condition <= limit) {
                return Err(Error::Singular { phi, condition, joints: self.loop_joints(l) });
            }
            certificates.push(sign);
        }
        let lu = self.jac.clone().lu();
        // Polish: one more Newton step with this LU takes the converged pose from the
        // tolerance down to rounding (the Jacobian, ~1e-13 away, is still the right one for
        // the derivatives to that order).
        if let Some(step) = lu.solve(&self.residual) {
            if step.iter().all(|s| s.is_finite()) {
                self.q -= step;
                self.eq.evaluate(self.q.as_slice(), phi, self.residual.as_mut_slice());
            }
        }
        let singular = || Error::Singular {
            phi,
            condition: f64::INFINITY,
            joints: self.mechanism.joints.iter().map(|j| j.name.clone()).collect(),
        };
        let mut e = DVector::zeros(self.q.len());
        e[self.q.len() - 1] = 1.0;
        // Φ_q q′ = −Φ_φ = e_drive (the drive row is the only one that depends on φ).
        self.dq = lu.solve(&e).ok_or_else(singular)?;
        self.ddq = implicit::second_derivative(&self.eq, &lu, &self.q, &self.dq, phi)
            .ok_or_else(singular)?;
        self.lu = Some(lu);
        Ok(certificates)
    }

    /// The loop whose equations are furthest from being satisfied by residual `r`.
    fn worst_loop(&self, r: &DVector<f64>) -> usize {
        let mut worst = (0.0, 0);
        for (i, l) in self.loops.iter().enumerate() {
            let x = l.rows.iter().map(|&row| r[row].abs()).fold(0.0, f64::max);
            if !(x <= worst.0) {
                worst = (x, i);
            }
        }
        worst.1
    }
}

/// A tracker's state, kept to undo a rejected step.
struct Saved {
    q: DVector<f64>,
    phi: f64,
    jac: DMatrix<f64>,
    residual: DVector<f64>,
    lu: Option<LU<f64, nalgebra::Dyn, nalgebra::Dyn>>,
    dq: DVector<f64>,
    ddq: DVector<f64>,
}
