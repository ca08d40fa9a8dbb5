//! Quick return: the time ratio of an output with two dead positions per crank turn.
//!
//! Over one turn of a crank at constant speed, an output that stops and turns back at two
//! dead positions φ₁ < φ₂ (see [`crate::dead_position`]) moves one way while the crank
//! turns φ₂ − φ₁ and back while it turns 2π − (φ₂ − φ₁). The slower stroke (the larger
//! crank angle α) is the forward, working stroke, the other (β) the return; the time
//! ratio is Q = α/β ≥ 1 (Q = (180° + δ)/(180° − δ) with δ the angle between the two
//! crank positions' lines). The output's travel between the dead positions is the stroke
//! of a slider or the swing angle of a rocker.

use super::drive::DriveMotion;
use super::error::MetricsError;
use crate::dead_position::{DeadPosition, DeadPositionSearch};
use crate::geometry::{DriveKind, Kinematics, Mechanism, Solver, Tracker};
use crate::{Error, Jet};
use std::cell::RefCell;
use std::f64::consts::{PI, TAU};

/// One stroke of the output, between its dead positions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stroke {
    /// The drive position where it starts (rad).
    pub from: f64,
    /// Where it ends (rad; `from` + `crank_angle`).
    pub to: f64,
    /// The crank angle it takes (rad).
    pub crank_angle: f64,
}

/// The time ratio of an output and its travel.
#[derive(Debug, Clone, PartialEq)]
pub struct QuickReturn {
    /// The two dead positions, in increasing φ within one turn from the sketch's drive
    /// position.
    pub dead_positions: [DeadPosition; 2],
    /// The forward (slower, working) stroke: the larger crank angle α.
    pub forward: Stroke,
    /// The return stroke: the crank angle β = 2π − α.
    pub back: Stroke,
    /// Q = α/β ≥ 1.
    pub time_ratio: f64,
    /// |x(φ₂) − x(φ₁)|: the stroke (m) of a slider, the swing angle (rad) of a rocker.
    pub travel: f64,
}

impl QuickReturn {
    /// What the time ratio rests on, for a report.
    pub const FORMULA: &'static str = "Q = α/β ≥ 1, α + β = 360°: the crank angles between \
         the output's two dead positions (x′ = 0), α for the slower (forward) stroke";

    /// The quick return of the output `output` reads from each solved pose, over one turn
    /// of `m`'s crank from the sketch, solved by `solver`. Dead positions are bracketed at
    /// 1° steps and refined by Newton on the exact x″ to full precision.
    ///
    /// # Errors
    /// [`MetricsError::NotAngleDrive`], [`MetricsError::CrankDoesNotTurn`] (the drive's
    /// motion range has an end), [`MetricsError::DeadPositions`] (not exactly two), or
    /// [`MetricsError::Geometry`] from the solver.
    pub fn find(
        m: &Mechanism,
        solver: &Solver,
        output: impl Fn(&Kinematics<'_, 3>) -> Jet<3>,
    ) -> Result<QuickReturn, MetricsError> {
        Self::over_turn(&DriveMotion::of(m, solver)?, solver.track(m)?, output)
    }

    /// [`QuickReturn::find`] with the drive's motion range already walked, from `tracker`
    /// at the sketch.
    pub(crate) fn over_turn(
        drive: &DriveMotion,
        tracker: Tracker<'_>,
        output: impl Fn(&Kinematics<'_, 3>) -> Jet<3>,
    ) -> Result<QuickReturn, MetricsError> {
        let m = tracker.mechanism();
        if drive.kind != DriveKind::Angle {
            return Err(MetricsError::NotAngleDrive {
                joint: m.joints()[m.drive_joint()].name.clone(),
            });
        }
        if let Some(limit) = (drive.range.lower.as_ref()).or(drive.range.upper.as_ref()) {
            return Err(MetricsError::CrankDoesNotTurn {
                limit: limit.clone(),
            });
        }
        let start = tracker.phi();
        let tracker = RefCell::new(tracker);
        let jet = |phi: f64| -> Result<Jet<3>, Error> {
            let mut t = tracker.borrow_mut();
            t.move_to(phi)?;
            Ok(output(&t.kinematics::<3>()?))
        };
        let step = PI / 180.0;
        // Two steps past the full turn, so that a dead position at the start is bracketed.
        let search = DeadPositionSearch::new(start..=start + TAU + 2.0 * step).with_step(step);
        let mut dead: Vec<DeadPosition> = Vec::new();
        for mut d in search.find_roots(jet)? {
            if d.phi >= start + TAU {
                d.phi -= TAU;
            }
            if !dead.iter().any(|e| (e.phi - d.phi).abs() <= 1e-9) {
                dead.push(d);
            }
        }
        dead.sort_by(|a, b| a.phi.total_cmp(&b.phi));
        let [first, second] = dead[..] else {
            return Err(MetricsError::DeadPositions { found: dead.len() });
        };
        let inner = second.phi - first.phi;
        let one = Stroke {
            from: first.phi,
            to: second.phi,
            crank_angle: inner,
        };
        let other = Stroke {
            from: second.phi,
            to: first.phi + TAU,
            crank_angle: TAU - inner,
        };
        let (forward, back) = if one.crank_angle >= other.crank_angle {
            (one, other)
        } else {
            (other, one)
        };
        Ok(QuickReturn {
            dead_positions: [first, second],
            forward,
            back,
            time_ratio: forward.crank_angle / back.crank_angle,
            travel: (second.value - first.value).abs(),
        })
    }
}
