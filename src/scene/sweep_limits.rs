//! The ends of the drive's motion range (limit positions, change points, toggles) that a
//! run's sweep reaches: marked on the diagrams and listed after the dead positions.

use mechdiff_core::geometry::{DriveLimit, LimitKind};
use std::f64::consts::TAU;

use super::model::DriveKind;
use super::setup::Setup;

/// One end of the drive's motion range that the sweep reaches.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepLimit {
    /// The limit (drive position in SI, kind, the loop's joints).
    pub limit: DriveLimit,
    /// What the run was (empty, or the parameter setting of a parameter sweep, ` (L = 2)`).
    pub tag: String,
}

/// Whether [`in_sweep`] walks the drive's motion range for a sweep of `positions` drive
/// positions: not for a cam drive or fewer than two positions.
pub fn walks(setup: &Setup<'_>, positions: usize) -> bool {
    setup.drive().cam.is_none() && positions >= 2
}

/// The ends of the motion range walked from the sketch (`Tracker::motion_range`) that lie in
/// the sweep's range of drive positions or within one of its steps beyond either end (a step
/// further would meet them). Angle drives also try the limit a turn either way. A cam drive,
/// fewer than two positions or a range that cannot be walked give none (the run itself has
/// already solved every position it reports).
pub fn in_sweep(
    setup: &Setup<'_>,
    positions: impl ExactSizeIterator<Item = f64> + Clone,
) -> Vec<SweepLimit> {
    if !walks(setup, positions.len()) {
        return Vec::new();
    }
    let Some(range) = (setup.solver)
        .track(&setup.mechanism)
        .and_then(|t| t.motion_range())
        .ok()
    else {
        return Vec::new();
    };
    let lo = positions.clone().fold(f64::INFINITY, f64::min);
    let hi = positions.clone().fold(f64::NEG_INFINITY, f64::max);
    // The largest step between neighbours, walked without holding the positions.
    let step = positions
        .clone()
        .zip(positions.skip(1))
        .map(|(a, b)| (b - a).abs())
        .fold(0.0, f64::max);
    let turns: &[f64] = match setup.drive().kind {
        DriveKind::Angle => &[0.0, -TAU, TAU],
        DriveKind::Displacement => &[0.0],
    };
    let mut limits = Vec::new();
    for limit in [range.lower, range.upper].into_iter().flatten() {
        let reached = turns
            .iter()
            .map(|t| limit.phi + t)
            .find(|phi| (lo - step..=hi + step).contains(phi));
        if let Some(phi) = reached {
            limits.push(SweepLimit {
                limit: DriveLimit { phi, ..limit },
                tag: String::new(),
            });
        }
    }
    limits
}

/// What stops the drive, in words (`limit position`, `change point`, …).
pub fn kind_words(kind: LimitKind) -> &'static str {
    match kind {
        LimitKind::Limit => "limit position",
        LimitKind::ChangePoint => "change point",
        LimitKind::Toggle => "toggle",
        LimitKind::BranchFlip => "branch flip beyond",
    }
}
