//! Base-circle sizing: the smallest base circle that keeps the pressure angle under a limit
//! (translating roller or knife-edge) or the profile convex (flat face).
//!
//! For a translating roller, tan φ = (s′ − e)/(√(R_p² − e²) + s) shrinks at every cam angle
//! as the prime circle R_p = R_b + r grows, so the largest |φ| over the turn decreases with
//! R_b and the radius where it equals the limit is found by bisection (to a few ulp of R_b).
//! For a flat face the profile's radius of curvature is R_b + s + s″, so the smallest base
//! radius with a radius of curvature of at least ρ_min everywhere is ρ_min − min(s + s″).

use super::follower::Follower;
use super::law::Side;
use super::profile::CamMechanism;
use super::program::CamProgram;
use crate::error::{Error, Result};

/// Bisection steps on the base radius (each halves the bracket; stops at a few ulp).
const BISECTIONS: usize = 200;

/// The smallest base radius for which the largest |pressure angle| of a translating roller
/// or knife-edge follower is at most `limit` (rad). Where the geometry alone (the offset, the
/// smallest displacement) needs a larger radius than the limit does, that radius is
/// returned: the limit is then not reached.
///
/// ```
/// use mechdiff_core::cams::{CamProgram, Follower, MotionLaw, Segment, sizing};
/// use std::f64::consts::PI;
/// let program = CamProgram::new(vec![
///     Segment::law(MotionLaw::Cycloidal, 0.02, PI / 2.0),
///     Segment::law(MotionLaw::Dwell, 0.0, PI / 2.0),
///     Segment::law(MotionLaw::Cycloidal, -0.02, PI / 2.0),
///     Segment::law(MotionLaw::Dwell, 0.0, PI / 2.0),
/// ], 0.0).unwrap();
/// let roller = Follower::Roller { offset: 0.0, radius: 0.005 };
/// let base = sizing::base_radius_for_pressure_angle(&program, roller, 30f64.to_radians()).unwrap();
/// assert!(base > 0.0 && base < 0.1);
/// ```
///
/// # Errors
/// [`Error::CamDimension`] for a follower that is not a translating roller or knife-edge, a
/// limit outside (0°, 90°), or a roller radius that is not positive.
pub fn base_radius_for_pressure_angle(
    program: &CamProgram,
    follower: Follower,
    limit: f64,
) -> Result<f64> {
    let offset = match follower {
        Follower::KnifeEdge { offset } | Follower::Roller { offset, .. } => offset,
        _ => {
            return Err(Error::CamDimension {
                what: "follower".to_owned(),
                value: f64::NAN,
                problem: format!(
                    "base-circle sizing by pressure angle is for translating roller and \
                     knife-edge followers, not {}",
                    follower.describe()
                ),
            });
        }
    };
    if !(limit > 0.0 && limit < std::f64::consts::FRAC_PI_2) {
        return Err(Error::CamDimension {
            what: "pressure angle limit".to_owned(),
            value: limit.to_degrees(),
            problem: "must be between 0° and 90°".to_owned(),
        });
    }
    let (s_min, s_max) = program.displacement_range();
    let r = follower.roller_radius();
    let scale = (s_max - s_min)
        .abs()
        .max(offset.abs())
        .max(r)
        .max(f64::MIN_POSITIVE);
    let excess = |base: f64| -> Option<f64> {
        let cam = CamMechanism::new(program.clone(), base, follower).ok()?;
        Some(
            cam.maximum(|t, side: Side| cam.pressure_angle(t, side).abs())
                .value
                - limit,
        )
    };
    // The smallest radius the geometry allows (prime circle beyond the offset, the follower
    // kept off the cam centre), found by bisection on feasibility.
    let (mut infeasible, mut feasible) = (0.0, scale);
    while excess(feasible).is_none() {
        (infeasible, feasible) = (feasible, 2.0 * feasible);
    }
    for _ in 0..BISECTIONS {
        let mid = 0.5 * (infeasible + feasible);
        if mid <= infeasible || mid >= feasible {
            break;
        }
        if excess(mid).is_some() {
            feasible = mid;
        } else {
            infeasible = mid;
        }
    }
    let smallest = feasible;
    if excess(smallest).is_some_and(|e| e <= 0.0) {
        return Ok(smallest);
    }
    // Bracket the limit: too small (pressure angle above the limit) … large enough.
    let (mut small, mut large) = (smallest, 2.0 * smallest.max(scale));
    while excess(large).is_some_and(|e| e > 0.0) {
        (small, large) = (large, 2.0 * large);
    }
    for _ in 0..BISECTIONS {
        let mid = 0.5 * (small + large);
        if mid <= small || mid >= large {
            break;
        }
        if excess(mid).is_some_and(|e| e > 0.0) {
            small = mid;
        } else {
            large = mid;
        }
    }
    Ok(large)
}

/// The smallest base radius for which a flat-faced follower's profile has a radius of
/// curvature of at least `min_radius` everywhere (0: just convex, no cusp), and the face
/// stays off the cam centre.
///
/// # Errors
/// [`Error::CamDimension`] for a negative or non-finite `min_radius`.
pub fn base_radius_for_flat_face(program: &CamProgram, min_radius: f64) -> Result<f64> {
    if !(min_radius.is_finite() && min_radius >= 0.0) {
        return Err(Error::CamDimension {
            what: "smallest radius of curvature".to_owned(),
            value: min_radius,
            problem: "must be zero or positive".to_owned(),
        });
    }
    // s + s″ over the turn, with a unit base circle only to get the pieces.
    let (s_min, _) = program.displacement_range();
    let probe = CamMechanism::new(program.clone(), 1.0 + s_min.abs(), Follower::FlatFaced)?;
    let least = -probe
        .maximum(|t, side| {
            let j = program.svaj(t, side);
            -(j.value + j.d2())
        })
        .value;
    let convex = min_radius - least;
    // Off the cam centre: R_b + s_min > 0.
    Ok(convex.max(-s_min).max(f64::MIN_POSITIVE))
}
