//! The shaking force and moment on the frame: the sum of the links' inertial forces
//! `Σ −m a_G` and of their moments about the origin, `Σ (r_G × (−m a_G) − J θ̈)` — what the
//! foundation must carry (reference 000: ΣF_x, ΣF_y).

use super::inertia::{self, InertialLoad, Mass};
use super::model::CompiledModel;
use super::state::{self, LinkState, cross};
use crate::{DriveState, Jet, Scalar};

/// The shaking force at one drive position.
#[derive(Debug, Clone, PartialEq)]
pub struct ShakingForce<T = f64> {
    /// Drive position.
    pub phi: f64,
    /// `Σ −m a_G` (N).
    pub force: [T; 2],
    /// Moment of the inertial loads about the global origin (N·m).
    pub moment: T,
    /// The inertial load of each link with mass.
    pub links: Vec<InertialLoad<T>>,
}

/// The shaking force of `model` at the pose of `coordinates` for drive state `drive`.
pub fn shaking_force(
    model: &CompiledModel<'_>,
    phi: f64,
    coordinates: &[Jet<2>],
    drive: &DriveState,
) -> ShakingForce {
    shaking_of(&model.masses, phi, &state::link_states(coordinates, drive))
}

/// [`shaking_force`] in any scalar, from the links' states.
pub(crate) fn shaking_of<T: Scalar>(
    masses: &[Mass<T>],
    phi: f64,
    states: &[LinkState<T>],
) -> ShakingForce<T> {
    let mut shaking = ShakingForce {
        phi,
        force: [T::zero(); 2],
        moment: T::zero(),
        links: Vec::with_capacity(masses.len()),
    };
    shaking_into(masses, phi, states, &mut shaking);
    shaking
}

/// [`shaking_of`] written into `shaking` (its links' buffer reused: nothing allocated once
/// it has the capacity).
pub(crate) fn shaking_into<T: Scalar>(
    masses: &[Mass<T>],
    phi: f64,
    states: &[LinkState<T>],
    shaking: &mut ShakingForce<T>,
) {
    inertia::loads_into(masses, states, &mut shaking.links);
    let mut force = [T::zero(); 2];
    let mut moment = T::zero();
    for l in &shaking.links {
        force[0] += l.force[0];
        force[1] += l.force[1];
        moment += cross(l.center, l.force) + l.couple;
    }
    (shaking.phi, shaking.force, shaking.moment) = (phi, force, moment);
}

/// An extreme value over a sweep and where it occurs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extreme {
    /// The value.
    pub value: f64,
    /// The drive position where it occurs.
    pub phi: f64,
}

/// The extremes of the shaking force over a sweep (over the sampled positions).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShakingSummary {
    /// Smallest and largest `ΣF_x`.
    pub force_x: [Extreme; 2],
    /// Smallest and largest `ΣF_y`.
    pub force_y: [Extreme; 2],
    /// Largest magnitude `|ΣF|`.
    pub magnitude: Extreme,
    /// Smallest and largest moment.
    pub moment: [Extreme; 2],
}

impl ShakingSummary {
    /// The extremes over `sweep`; `None` if it is empty.
    pub fn of(sweep: &[ShakingForce]) -> Option<Self> {
        let mut summary: Option<Self> = None;
        for f in sweep {
            Self::add(&mut summary, f);
        }
        summary
    }

    /// The extremes of one position alone.
    pub fn at(f: &ShakingForce) -> Self {
        let at = |value: f64| Extreme { value, phi: f.phi };
        ShakingSummary {
            force_x: [at(f.force[0]); 2],
            force_y: [at(f.force[1]); 2],
            magnitude: at(f.force[0].hypot(f.force[1])),
            moment: [at(f.moment); 2],
        }
    }

    /// Takes position `f` into the extremes so far (`None` before the first position): a
    /// sweep summarised one position at a time, as it is solved.
    pub fn add(summary: &mut Option<Self>, f: &ShakingForce) {
        let one = Self::at(f);
        *summary = Some(match summary.take() {
            Some(s) => s.then(&one),
            None => one,
        });
    }

    /// The extremes of this part of a sweep followed by `later`: the first of equal extremes
    /// is kept (only a strictly smaller or larger value replaces one), so summarising pieces
    /// and joining them in order gives the summary of the whole sweep.
    pub fn then(&self, later: &Self) -> Self {
        let low = |a: Extreme, b: Extreme| if b.value < a.value { b } else { a };
        let high = |a: Extreme, b: Extreme| if b.value > a.value { b } else { a };
        let pair = |a: [Extreme; 2], b: [Extreme; 2]| [low(a[0], b[0]), high(a[1], b[1])];
        ShakingSummary {
            force_x: pair(self.force_x, later.force_x),
            force_y: pair(self.force_y, later.force_y),
            magnitude: high(self.magnitude, later.magnitude),
            moment: pair(self.moment, later.moment),
        }
    }
}
