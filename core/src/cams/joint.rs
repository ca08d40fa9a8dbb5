//! A cam joint: a cam program as the drive of a linkage.
//!
//! The follower's displacement s (a translating follower's travel, or an oscillating
//! follower's angle) is the drive variable of a geometry model; the true input is the cam
//! angle θ, turning at ω = θ̇ with α = θ̈. The linkage's kinematics depend on s and its time
//! derivatives only, so the geometry model runs unchanged with the follower's drive state
//!
//! - ṡ = s′ ω,
//! - s̈ = s′ α + s″ ω²,
//! - s⃛ = s′ θ⃛ + 3 s″ ω α + s‴ ω³
//!
//! (′ = d/dθ, exact from the [`CamProgram`]), which is the chain rule for every output's
//! velocity and acceleration. The derivatives of an output x with respect to θ are
//! [`CamJoint::compose`]: x′_θ = x_s s′, x″_θ = x_ss s′² + x_s s″,
//! x‴_θ = x_sss s′³ + 3 x_ss s′ s″ + x_s s‴.
//!
//! The kinetostatics gives the generalised force F_s the geometry drive needs (a force for a
//! translating follower, a torque for an oscillating one); the torque on the cam shaft is
//! T = F_s s′(θ), from the power balance T ω = F_s ṡ (a frictionless cam–follower contact:
//! the cam's own inertia and the contact's friction are not modelled).
//!
//! ```
//! use mechdiff_core::DriveState;
//! use mechdiff_core::cams::{CamJoint, CamProgram, MotionLaw, Segment};
//! use std::f64::consts::PI;
//! let program = CamProgram::new(
//!     vec![
//!         Segment::law(MotionLaw::Cycloidal, 0.02, PI),
//!         Segment::law(MotionLaw::Cycloidal, -0.02, PI),
//!     ],
//!     0.0,
//! )
//! .unwrap();
//! let joint = CamJoint::new(program);
//! let (s, follower) = joint.drive_at(0.5 * PI, &DriveState::constant_speed(10.0));
//! assert!((s - 0.01).abs() < 1e-15); // half the rise at half the segment
//! assert!((follower.omega - 10.0 * 2.0 * 0.02 / PI).abs() < 1e-15); // ω s′, s′ = 2h/β
//! ```

use super::law::Side;
use super::program::CamProgram;
use crate::dynamics::CompiledModel;
use crate::dynamics::plan::{Plan, Trace};
use crate::dynamics::run::{Step, run_moved};
use crate::error::{Error, Result};
use crate::geometry::{Solver, Tracker};
use crate::jet::Jet;
use crate::motion::DriveState;

/// A cam program driving a geometry model: its displacement is the model's drive variable.
#[derive(Clone, Debug)]
pub struct CamJoint {
    program: CamProgram,
    side: Side,
}

impl CamJoint {
    /// The cam joint of `program`; at a boundary where a derivative jumps, the right-hand
    /// limit (the segment that starts there) is used.
    pub fn new(program: CamProgram) -> Self {
        CamJoint {
            program,
            side: Side::Right,
        }
    }

    /// The same joint taking the one-sided limit `side` at boundaries and breaks.
    pub fn with_side(self, side: Side) -> Self {
        CamJoint { side, ..self }
    }

    /// The cam program.
    pub fn program(&self) -> &CamProgram {
        &self.program
    }

    /// s, s′, s″, s‴ at cam angle `theta`.
    pub fn svaj(&self, theta: f64) -> Jet<3> {
        self.program.svaj(theta, self.side)
    }

    /// The follower's displacement s(θ) and its drive state (ṡ, s̈, s⃛) for the cam's
    /// motion `cam` (ω, α, θ⃛) at cam angle `theta`.
    pub fn drive_at(&self, theta: f64, cam: &DriveState) -> (f64, DriveState) {
        let s = self.svaj(theta);
        let m = s.motion(cam);
        let follower = DriveState {
            omega: m.velocity,
            alpha: m.acceleration,
            jerk: m.jerk.unwrap_or(0.0),
        };
        (s.value, follower)
    }

    /// The derivatives with respect to the cam angle of a quantity `x` given with its
    /// derivatives with respect to the follower displacement s (N ≤ 3; Faà di Bruno).
    pub fn compose<const N: usize>(&self, theta: f64, x: &Jet<N>) -> Jet<N> {
        const { assert!(N <= 3, "the cam joint composes derivatives up to the third") };
        let s = self.svaj(theta);
        let [s1, s2, s3] = s.derivatives;
        let d = &x.derivatives;
        let mut out = [0.0; N];
        if N >= 1 {
            out[0] = d[0] * s1;
        }
        if N >= 2 {
            out[1] = d[1] * s1 * s1 + d[0] * s2;
        }
        if N >= 3 {
            out[2] = d[2] * s1 * s1 * s1 + 3.0 * d[1] * s1 * s2 + d[0] * s3;
        }
        Jet::new(x.value, out)
    }

    /// Moves `tracker` (the linkage whose drive variable is the follower's position
    /// `offset + s`) along the cam from cam angle `from` to `to`: through the follower's
    /// position at every reversal of s between them ([`CamProgram::reversals`]), then to
    /// `offset + s(to)`. Each stretch is a move of the linkage's own tracker, so every
    /// displacement the follower passes is proven assemblable on the tracker's branch (the
    /// linkage's checked, halved steps), and a limit position, change point, toggle or
    /// branch flip inside the step is found and refined as for any drive.
    ///
    /// # Errors
    /// The tracker's errors with every drive position a cam angle: [`Error::Blocked`] from
    /// `from` to `to` with the cam angle where the follower reaches the linkage's limit
    /// position ([`CamProgram::reaching`] on the stretch, to adjacent floating-point
    /// numbers), [`Error::ChangePoint`], [`Error::Singular`], [`Error::BranchFlip`],
    /// [`Error::Unassemblable`] likewise; [`Error::MoveTooLong`] from the reversals' search
    /// or the tracker.
    ///
    /// ```
    /// use mechdiff_core::cams::{CamJoint, CamProgram, MotionLaw, Segment};
    /// use mechdiff_core::geometry::{Drive, Mechanism, Solver};
    /// use mechdiff_core::Error;
    /// use std::f64::consts::PI;
    /// // A slider (the follower) at x = 1.6 pulls a rocker of 1 through a rod of 1: the rod
    /// // reaches no further than x = 2. The cam lifts the follower 0.5 and back (cycloidal
    /// // rise over a half turn, return over the other).
    /// let (a, b) = (0.8, 0.6); // rocker pin (0.8, 0.6): the rod from it to (1.6, 0) is 1 long
    /// let m = Mechanism::builder()
    ///     .point("O", [0.0, 0.0]).point("A", [a, b]).point("B", [1.6, 0.0])
    ///     .point("X", [3.0, 0.0])
    ///     .ground(["O", "X"]).link("rocker", ["O", "A"]).link("rod", ["A", "B"])
    ///     .link("follower", ["B"])
    ///     .revolute("O", "ground", "rocker", "O").revolute("A", "rocker", "rod", "A")
    ///     .revolute("B", "rod", "follower", "B")
    ///     .prismatic("guide", "ground", ["O", "X"], "follower", "B")
    ///     .drive(Drive::displacement("guide"))
    ///     .build().unwrap();
    /// let program = CamProgram::new(vec![
    ///     Segment::law(MotionLaw::Cycloidal, 0.5, PI),
    ///     Segment::law(MotionLaw::Cycloidal, -0.5, PI),
    /// ], 0.0).unwrap();
    /// let joint = CamJoint::new(program);
    /// let offset = 1.6; // the follower's position at s = 0
    /// let mut tracker = Solver::default().track(&m).unwrap();
    /// tracker.move_to(offset + joint.svaj(1.9).value).unwrap(); // s = 0.35
    /// // Between 1.9 and 4.4 (s = 0.35 again) the follower passes s = 0.4 (x = 2, the rod's
    /// // reach) before its peak (π): the step is refused, with the cam angle where s first
    /// // reaches 0.4.
    /// let Err(Error::Blocked { limit, .. }) = joint.move_tracker(&mut tracker, offset, 1.9, 4.4)
    /// else { panic!("the blocked range is jumped") };
    /// let u = joint.program().reaching(0.0, PI, 0.4, mechdiff_core::cams::Side::Right);
    /// assert!((limit - u).abs() < 1e-12);
    /// ```
    pub fn move_tracker(
        &self,
        tracker: &mut Tracker<'_>,
        offset: f64,
        from: f64,
        to: f64,
    ) -> Result<()> {
        let mut stops = self.program.reversals(from, to, self.side)?;
        stops.push(to);
        let mut start = from;
        for stop in stops {
            if let Err(e) = tracker.move_to(offset + self.svaj(stop).value) {
                // The stretch from `start` to `stop` is monotone: each follower position
                // the tracker names is reached at one cam angle of it.
                let theta = |x: f64| (self.program).reaching(start, stop, x - offset, self.side);
                return Err(match e {
                    Error::Blocked { limit, joints, .. } => Error::Blocked {
                        from,
                        to,
                        limit: theta(limit),
                        joints,
                    },
                    Error::ChangePoint { phi, joints } => Error::ChangePoint {
                        phi: theta(phi),
                        joints,
                    },
                    Error::Singular {
                        phi,
                        condition,
                        joints,
                    } => Error::Singular {
                        phi: theta(phi),
                        condition,
                        joints,
                    },
                    Error::Unassemblable {
                        phi,
                        last_assembled,
                        joints,
                        residual,
                    } => Error::Unassemblable {
                        phi: theta(phi),
                        last_assembled: theta(last_assembled),
                        joints,
                        residual,
                    },
                    Error::BranchFlip {
                        from: before,
                        to: after,
                        joints,
                    } => Error::BranchFlip {
                        from: theta(before),
                        to: theta(after),
                        joints,
                    },
                    Error::NonFinite { phi, quantity } => Error::NonFinite {
                        phi: theta(phi),
                        quantity,
                    },
                    Error::MoveTooLong { steps, longest, .. } => Error::MoveTooLong {
                        from,
                        to,
                        steps,
                        longest,
                    },
                    other => other,
                });
            }
            start = stop;
        }
        Ok(())
    }

    /// The torque on the cam shaft, T = F_s s′(θ), for the generalised force `drive_force`
    /// the geometry drive needs (N for a translating follower, N·m for an oscillating one).
    pub fn torque(&self, theta: f64, drive_force: f64) -> f64 {
        drive_force * self.svaj(theta).derivatives[0]
    }
}

/// The results of a cam-driven linkage at one cam angle.
#[derive(Debug, Clone, PartialEq)]
pub struct CamStep {
    /// Cam angle θ (rad).
    pub theta: f64,
    /// The cam's motion (ω, α, θ⃛).
    pub cam: DriveState,
    /// s, s′, s″, s‴ at θ.
    pub svaj: Jet<3>,
    /// The linkage's results at drive position s(θ) with the follower's drive state.
    pub step: Step,
    /// Torque on the cam shaft `F_s s′` (N·m) where the plan solved the equilibrium.
    pub torque: Option<f64>,
}

impl CamStep {
    /// The power the cam puts in, `T ω` (W), where the plan solved the equilibrium.
    pub fn power(&self) -> Option<f64> {
        self.torque.map(|t| t * self.cam.omega)
    }
}

/// The results of a cam-driven linkage over a sweep of cam angles.
#[derive(Debug, Clone, PartialEq)]
pub struct CamRun {
    /// One step per cam angle.
    pub steps: Vec<CamStep>,
    /// Everything evaluated, summed over the sweep.
    pub trace: Trace,
}

/// Runs `plan` for the linkage `model` driven by the cam joint `joint` at the cam angles
/// `thetas` (in order), the cam moving as `cam(θ)`.
///
/// The linkage moves from one cam angle to the next through every displacement the
/// follower passes ([`CamJoint::move_tracker`]; from the sketch to the first, straight).
///
/// # Errors
/// [`Error::MissingData`] if the model has a motor (the motor belongs on the cam shaft, which
/// the geometry model does not contain); the errors of the geometry solver, at cam angles
/// between two positions (see [`CamJoint::move_tracker`]), at the follower's drive position
/// on the way to the first; and those of the kinetostatics at the follower's drive
/// position.
pub fn run(
    joint: &CamJoint,
    plan: &Plan,
    model: &CompiledModel<'_>,
    solver: &Solver,
    thetas: &[f64],
    cam: impl Fn(f64) -> DriveState,
) -> Result<CamRun> {
    if model.motor.is_some() {
        return Err(Error::MissingData {
            what: "a motor on a cam-driven linkage".to_owned(),
            missing: "a drive joint that is not the follower (the cam joint supports no motor)"
                .to_owned(),
        });
    }
    let cams: Vec<DriveState> = thetas.iter().map(|&t| cam(t)).collect();
    let states: Vec<(f64, DriveState)> = (thetas.iter().zip(&cams))
        .map(|(&t, c)| joint.drive_at(t, c))
        .collect();
    // From the sketch straight to the first position, then along the cam.
    let run = run_moved(plan, model, solver, &states, |tracker, k| match k {
        0 => tracker.move_to(states[0].0).map(drop),
        _ => joint.move_tracker(tracker, 0.0, thetas[k - 1], thetas[k]),
    })?;
    let steps = (run.steps.into_iter().zip(thetas).zip(cams))
        .map(|((step, &theta), cam)| {
            let torque = (step.solution.as_ref()).map(|s| joint.torque(theta, s.drive_torque));
            CamStep {
                theta,
                cam,
                svaj: joint.svaj(theta),
                step,
                torque,
            }
        })
        .collect();
    Ok(CamRun {
        steps,
        trace: run.trace,
    })
}
