//! The follower and the cam's base circle: the dimensions of a disc cam mechanism.
//!
//! Frames: the cam turns counter-clockwise about the origin; θ is its angle. In the fixed
//! frame a translating follower moves along the line x = e (the offset) in the +y
//! direction; an oscillating follower's arm turns about the pivot (a, 0) (a = pivot
//! distance), the roller centre at A + l(−cos ψ, −sin ψ), ψ measured from the line pivot →
//! cam centre, so that ψ grows as the roller moves out. The cam's own frame turns with it:
//! a point X of the fixed frame is R(−θ)X in the cam frame.
//!
//! The prime circle has radius R_p = R_b + r (base radius plus roller radius); at s = 0 the
//! roller centre is on it: y₀ = √(R_p² − e²) for a translating follower, ψ₀ with
//! a² + l² − 2al cos ψ₀ = R_p² for an oscillating one.

use crate::error::{Error, Result};
use crate::scalar::Scalar;

/// The kind and dimensions of the follower.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Follower {
    /// Translating knife-edge (a roller of radius 0) on the line x = `offset`.
    KnifeEdge {
        /// Offset e of the follower's axis from the cam centre.
        offset: f64,
    },
    /// Translating roller on the line x = `offset`.
    Roller {
        /// Offset e of the follower's axis from the cam centre.
        offset: f64,
        /// Roller radius r (positive).
        radius: f64,
    },
    /// Translating flat face perpendicular to the follower's axis.
    FlatFaced,
    /// Oscillating arm with a roller; the displacement of the program is the arm's angle
    /// (rad).
    OscillatingRoller {
        /// Distance a from the cam centre to the arm's pivot.
        pivot_distance: f64,
        /// Arm length l from the pivot to the roller centre.
        arm_length: f64,
        /// Roller radius r (positive).
        radius: f64,
    },
}

impl Follower {
    /// The roller radius (0 for a knife-edge or a flat face).
    pub fn roller_radius(&self) -> f64 {
        match *self {
            Follower::Roller { radius, .. } | Follower::OscillatingRoller { radius, .. } => radius,
            _ => 0.0,
        }
    }

    /// A short name: `translating roller`, …
    pub fn describe(&self) -> &'static str {
        match self {
            Follower::KnifeEdge { .. } => "translating knife-edge",
            Follower::Roller { .. } => "translating roller",
            Follower::FlatFaced => "translating flat-faced",
            Follower::OscillatingRoller { .. } => "oscillating roller",
        }
    }
}

/// The follower's dimensions, checked, with the base radius and the follower's place at
/// s = 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dimensions {
    /// Base circle radius R_b.
    pub base_radius: f64,
    /// The follower.
    pub follower: Follower,
    /// y₀ (translating) or ψ₀ (oscillating): the follower's place at s = 0.
    pub rest: f64,
}

impl Dimensions {
    /// Checks the dimensions against each other and against the displacement range
    /// `[s_min, s_max]` of the program.
    ///
    /// # Errors
    /// [`Error::CamDimension`] for a base radius or roller radius that is not positive, an
    /// offset not smaller than the prime circle radius, an arm that cannot reach the prime
    /// circle, or a program that would pull the follower through the cam centre.
    pub fn new(base_radius: f64, follower: Follower, s_min: f64) -> Result<Self> {
        let bad = |what: &str, value: f64, problem: &str| Error::CamDimension {
            what: what.to_owned(),
            value,
            problem: problem.to_owned(),
        };
        if !(base_radius.is_finite() && base_radius > 0.0) {
            return Err(bad("base radius", base_radius, "must be positive"));
        }
        let roller = follower.roller_radius();
        if !(roller.is_finite() && roller >= 0.0)
            || (roller == 0.0
                && matches!(
                    follower,
                    Follower::Roller { .. } | Follower::OscillatingRoller { .. }
                ))
        {
            return Err(bad(
                "roller radius",
                roller,
                "must be positive (use a knife-edge follower for radius 0)",
            ));
        }
        let prime = base_radius + roller;
        let rest = match follower {
            Follower::KnifeEdge { offset } | Follower::Roller { offset, .. } => {
                if !offset.is_finite() || offset.abs() >= prime {
                    return Err(bad(
                        "offset",
                        offset,
                        "must be smaller in size than the prime circle radius (base + \
                         roller); enlarge the base circle or reduce the offset",
                    ));
                }
                let y0 = (prime * prime - offset * offset).sqrt();
                if y0 + s_min <= 0.0 {
                    return Err(bad(
                        "smallest displacement",
                        s_min,
                        "would pull the follower through the cam centre; enlarge the base \
                         circle or raise the program's smallest displacement",
                    ));
                }
                y0
            }
            Follower::FlatFaced => {
                if base_radius + s_min <= 0.0 {
                    return Err(bad(
                        "smallest displacement",
                        s_min,
                        "would pull the face through the cam centre; enlarge the base circle \
                         or raise the program's smallest displacement",
                    ));
                }
                base_radius
            }
            Follower::OscillatingRoller {
                pivot_distance: a,
                arm_length: l,
                ..
            } => {
                for (what, v) in [("pivot distance", a), ("arm length", l)] {
                    if !(v.is_finite() && v > 0.0) {
                        return Err(bad(what, v, "must be positive"));
                    }
                }
                let cos = (a * a + l * l - prime * prime) / (2.0 * a * l);
                if !(-1.0 < cos && cos < 1.0) {
                    return Err(bad(
                        "arm length",
                        l,
                        "the roller cannot touch the prime circle (radius R_p = base + \
                         roller) from the pivot at distance a: need |a − l| < R_p < a + l",
                    ));
                }
                cos.acos()
            }
        };
        Ok(Dimensions {
            base_radius,
            follower,
            rest,
        })
    }

    /// The follower's reference point in the fixed frame for displacement `s` — the roller
    /// centre, the knife-edge, or the foot of the flat face on its axis — and its derivative
    /// with respect to s (the direction in which it moves as s grows; unit for a
    /// translating follower, of length l for an oscillating one).
    pub fn reference_point<D: Scalar>(&self, s: D) -> ([D; 2], [D; 2]) {
        match self.follower {
            Follower::KnifeEdge { offset } | Follower::Roller { offset, .. } => (
                [D::from(offset), s + self.rest],
                [D::from(0.0), D::from(1.0)],
            ),
            Follower::FlatFaced => ([D::from(0.0), s + self.rest], [D::from(0.0), D::from(1.0)]),
            Follower::OscillatingRoller {
                pivot_distance: a,
                arm_length: l,
                ..
            } => {
                let psi = s + self.rest;
                let (sin, cos) = (psi.sin(), psi.cos());
                ([-cos * l + a, -sin * l], [sin * l, -cos * l])
            }
        }
    }
}
