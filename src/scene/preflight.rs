//! What a run checks before it solves any position, written once: `mechdiff check` and every
//! `mechdiff run` call [`before_solving`], so the two give the same verdict on every error a
//! run can give before solving. `check` also holds the sweep against the drive's motion range
//! it walked ([`sweep_within_motion_range`]), which a run finds when it reaches the limit.

use mechdiff_core::geometry::{DriveLimit, LimitKind, MotionRange};

use crate::error::{Error, Result};

use super::positions::{MAX_IN_MEMORY, Positions};
use super::setup::Setup;

/// Every check of a scene's dynamics and balancing that needs no solved position: the
/// dynamic model compiles, the drive has the speed the outputs need (a power balance or
/// counterweights need a non-zero one), the rotor's answers are finite, and a sweep held in
/// memory (counterweights) is not longer than [`MAX_IN_MEMORY`] positions.
///
/// # Errors
/// The located error a run would give for the first of these that fails.
pub fn before_solving(setup: &Setup<'_>) -> Result<()> {
    let (cx, mechanism) = (&setup.context, &setup.mechanism);
    if let Some(d) = setup.dynamics.filter(|d| !d.outputs.is_empty()) {
        super::dynamics::before_solving(cx, d, mechanism, cx.drive.speed)?;
    }
    if let Some(b) = setup.balancing {
        super::balancing::before_solving(cx, b, mechanism)?;
    }
    // Counterweights are sized from every position before a row is known: held in memory.
    let in_memory = (setup.balancing).is_some_and(|b| b.counterweights.is_some());
    if in_memory && setup.positions.len() > MAX_IN_MEMORY {
        // The error names `step` and what to do instead; nothing is allocated.
        setup.positions.to_vec()?;
    }
    Ok(())
}

/// How far (relative) a sweep's position may lie past a limit position, found by bisection
/// to about this precision, before `check` refuses it: a sweep written to end at the printed
/// limit is not refused for its last digit.
const LIMIT_SLACK: f64 = 1e-9;

/// Refuses a sweep that reaches past a limit position of the drive's motion range (walked
/// from the sketch by `check`): the run would stop there with [`Error::Blocked`], so `check`
/// gives the same error, naming the first position past the limit. Change points and
/// toggles are left to the run, which may pass them; a sweep given as values of an output
/// (`[sweep] of`) is solved for its drive positions by the run.
///
/// # Errors
/// [`Error::Blocked`] with the last position of the sweep inside the range (or the sketch's),
/// the first one past it, and the limit.
pub fn sweep_within_motion_range(setup: &Setup<'_>, range: &MotionRange) -> Result<()> {
    if setup.sweep_of.is_some() {
        return Ok(());
    }
    fn limit(end: Option<&DriveLimit>) -> Option<&DriveLimit> {
        end.filter(|l| l.kind == LimitKind::Limit)
    }
    let (lower, upper) = (limit(range.lower.as_ref()), limit(range.upper.as_ref()));
    if lower.is_none() && upper.is_none() {
        return Ok(());
    }
    let past = |phi: f64| {
        lower
            .filter(|l| phi < l.phi - LIMIT_SLACK * (1.0 + l.phi.abs()))
            .or_else(|| upper.filter(|u| phi > u.phi + LIMIT_SLACK * (1.0 + u.phi.abs())))
    };
    let (positions, cx) = (setup.positions, &setup.context);
    let Some(first_past) = first_past(positions, |phi| past(phi).is_some()) else {
        return Ok(());
    };
    let phi = positions.get(first_past);
    let inside = match first_past {
        0 => cx.drive.at_sketch,
        k => positions.get(k - 1),
    };
    let l = past(phi).expect("past the limit");
    Err(Error::Blocked {
        file: cx.file.to_owned(),
        from: cx.joint_text(inside).into(),
        to: cx.joint_text(phi).into(),
        limit: cx.joint_text(l.phi).into(),
        loop_joints: l.joints.join(", ").into(),
    })
}

/// The index of the first position for which `past` holds. A list (bounded by the file's
/// size) is walked; a range `from + i·step` is monotone, so once its first position is
/// inside the motion range, the positions past a limit are a suffix, found by bisection in
/// O(log count) — a sweep of 10¹⁰ positions is checked at once.
fn first_past(positions: &Positions, past: impl Fn(f64) -> bool) -> Option<usize> {
    match positions {
        Positions::List(list) => list.iter().position(|&phi| past(phi)),
        Positions::Steps { count, .. } => {
            if past(positions.get(0)) {
                return Some(0);
            }
            // Invariant: positions below `inside_up_to` are inside, `count` is past or the end.
            let (mut inside_up_to, mut end) = (1, *count);
            while inside_up_to < end {
                let middle = inside_up_to + (end - inside_up_to) / 2;
                if past(positions.get(middle)) {
                    end = middle;
                } else {
                    inside_up_to = middle + 1;
                }
            }
            (end < *count).then_some(end)
        }
    }
}
