//! Inertia: d'Alembert's inertial force `−m·a_G` at the centre of gravity and couple `−J·θ̈`
//! of every link with mass properties.

use super::state::{Generalized, LinkState, of};
use crate::Scalar;

/// Mass properties of one link, compiled: the centre of gravity in link-local coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Mass<T = f64> {
    /// Link index in the mechanism.
    pub link: usize,
    /// Mass (kg).
    pub mass: T,
    /// Centre of gravity relative to the link's reference point, unrotated (m).
    pub center: [T; 2],
    /// Moment of inertia about the centre of gravity (kg·m²).
    pub moment: T,
}

/// The inertial (d'Alembert) load of one link at an instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InertialLoad<T = f64> {
    /// Link index in the mechanism.
    pub link: usize,
    /// Centre of gravity, global (m).
    pub center: [T; 2],
    /// Velocity of the centre of gravity (m/s).
    pub velocity: [T; 2],
    /// Acceleration of the centre of gravity (m/s²).
    pub acceleration: [T; 2],
    /// Inertial force `−m·a_G` (N).
    pub force: [T; 2],
    /// Inertial couple `−J_G·θ̈` (N·m).
    pub couple: T,
}

/// The inertial loads of every link with mass.
pub(crate) fn loads<T: Scalar>(
    masses: &[Mass<T>],
    states: &[LinkState<T>],
) -> Vec<InertialLoad<T>> {
    let mut loads = Vec::with_capacity(masses.len());
    loads_into(masses, states, &mut loads);
    loads
}

/// [`loads`] into `loads` (cleared first; nothing allocated once it has the capacity).
pub(crate) fn loads_into<T: Scalar>(
    masses: &[Mass<T>],
    states: &[LinkState<T>],
    loads: &mut Vec<InertialLoad<T>>,
) {
    loads.clear();
    loads.extend(masses.iter().map(|m| {
        let s = of(states, m.link);
        let center = s.position(m.center);
        let acceleration = s.acceleration_at(center);
        InertialLoad {
            link: m.link,
            center,
            velocity: s.velocity_at(center),
            acceleration,
            force: [-(m.mass * acceleration[0]), -(m.mass * acceleration[1])],
            couple: -(m.moment * s.alpha),
        }
    }));
}

/// Adds the inertial loads to the generalized loads.
pub(crate) fn load<T: Scalar>(
    inertial: &[InertialLoad<T>],
    states: &[LinkState<T>],
    q: &mut Generalized<T>,
) {
    for l in inertial {
        q.force(states, l.link, l.center, l.force);
        q.couple(l.link, l.couple);
    }
}
