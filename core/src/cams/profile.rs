//! The cam's geometry over a turn: pitch curve, profile with exact normals, pressure angle,
//! radius of curvature, undercutting.
//!
//! Everything is computed from one generic function, [`CamMechanism::contact`]: s and s′
//! come from the program evaluated with a nested dual number, so the normal of the pitch
//! curve is exact, and evaluating `contact` itself with a dual number gives the derivatives
//! of the profile, hence its tangent and curvature, exactly too.
//!
//! - Roller (and knife-edge, r = 0): the pitch curve P(θ) = R(−θ)B(s(θ)) is the path of the
//!   roller centre B in the cam frame; its outward normal n is the tangent turned by +90°
//!   (P runs clockwise); the profile is P − r n. The pressure angle is the signed angle from
//!   the direction in which B moves to the normal (for a translating roller:
//!   tan φ = (s′ − e)/(y₀ + s)).
//! - Flat face: the contact point is (s′, R_b + s) in the fixed frame (the envelope of the
//!   face lines), the pressure angle is 0, the profile's radius of curvature is the rate of
//!   the contact point along the face (R_b + s + s″).
//!
//! Curvature κ is counted positive where the curve is convex; a roller profile is undercut
//! where the pitch curve is convex with a radius below the roller's (κ r > 1), a flat-faced
//! profile where its radius of curvature is not positive (a cusp).

use std::f64::consts::TAU;

use num_dual::{Dual, Dual2_64};

use super::extrema::maximize;
use super::follower::{Dimensions, Follower};
use super::law::Side;
use super::program::CamProgram;
use crate::error::Result;
use crate::scalar::{Scalar, atan2};

/// A cam program with the cam's base circle and its follower.
#[derive(Clone, Debug)]
pub struct CamMechanism {
    /// The motion program.
    pub program: CamProgram,
    /// The checked dimensions.
    pub dimensions: Dimensions,
}

/// The contact geometry at one cam angle, in the cam's frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact<D> {
    /// The follower's reference point (roller centre, knife-edge, foot of the face).
    pub pitch: [D; 2],
    /// The point of contact on the cam profile.
    pub profile: [D; 2],
    /// The outward unit normal of the profile at the contact.
    pub normal: [D; 2],
    /// The pressure angle (rad, signed).
    pub pressure_angle: D,
}

/// A value and the cam angle where it is taken.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Extreme {
    /// The value.
    pub value: f64,
    /// The cam angle (rad).
    pub angle: f64,
}

/// The geometry of a cam over the turn.
#[derive(Clone, Debug, PartialEq)]
pub struct CamAnalysis {
    /// The largest |pressure angle| (rad) and where (0 for a flat face).
    pub max_pressure_angle: Extreme,
    /// The smallest radius of curvature of the pitch curve where it is convex (the roller
    /// centre's path; the face's foot for a flat face: `None`).
    pub min_pitch_radius: Option<Extreme>,
    /// The smallest radius of curvature of the profile where the pitch curve is convex
    /// (negative: the profile is undercut or has a cusp).
    pub min_profile_radius: Extreme,
    /// Cam angle ranges (rad, start and end) where the profile is undercut (roller) or has
    /// a cusp (flat face).
    pub undercut: Vec<(f64, f64)>,
    /// Flat face: the smallest and largest distance of the contact from the follower's axis
    /// (s′ at its minimum and maximum); the face must span at least this.
    pub face_extent: Option<(f64, f64)>,
}

/// Samples per piece of the program for the searches (then golden-section refinement).
const SAMPLES: usize = 64;

/// The nested-dual evaluation of s and s′ as scalars of type `D`.
fn s_and_slope<D: Scalar>(program: &CamProgram, theta: D, side: Side) -> (D, D)
where
    Dual<D>: Scalar,
{
    let s = program.displacement(Dual::new(theta, D::one()), side);
    (s.re, s.eps)
}

impl CamMechanism {
    /// Checks the dimensions against the program (see [`Dimensions::new`]).
    ///
    /// # Errors
    /// [`crate::Error::CamDimension`] as [`Dimensions::new`].
    pub fn new(program: CamProgram, base_radius: f64, follower: Follower) -> Result<Self> {
        let (s_min, _) = program.displacement_range();
        let dimensions = Dimensions::new(base_radius, follower, s_min)?;
        Ok(CamMechanism {
            program,
            dimensions,
        })
    }

    /// The contact geometry at cam angle `theta`, in any scalar type.
    pub fn contact<D: Scalar>(&self, theta: D, side: Side) -> Contact<D>
    where
        Dual<D>: Scalar,
    {
        let (s, slope) = s_and_slope(&self.program, theta, side);
        let dims = &self.dimensions;
        let (b, dir) = dims.reference_point(s);
        let zero = D::from(0.0);
        let (contact, normal, pressure_angle) = match dims.follower {
            Follower::FlatFaced => ([slope, b[1]], [zero, D::one()], zero),
            _ => {
                // The pitch curve's tangent in the fixed frame: dB/dθ − J B.
                let tangent = [dir[0] * slope + b[1], dir[1] * slope - b[0]];
                let length = (tangent[0] * tangent[0] + tangent[1] * tangent[1]).sqrt();
                let n = [-tangent[1] / length, tangent[0] / length];
                let r = dims.follower.roller_radius();
                let contact = [b[0] - n[0] * r, b[1] - n[1] * r];
                let cross = dir[0] * n[1] - dir[1] * n[0];
                let dot = dir[0] * n[0] + dir[1] * n[1];
                (contact, n, atan2(cross, dot))
            }
        };
        let (sin, cos) = (theta.sin(), theta.cos());
        let to_cam = |p: [D; 2]| [p[0] * cos + p[1] * sin, -p[0] * sin + p[1] * cos];
        Contact {
            pitch: to_cam(b),
            profile: to_cam(contact),
            normal: to_cam(normal),
            pressure_angle,
        }
    }

    /// The pressure angle (rad) at cam angle `theta`.
    pub fn pressure_angle(&self, theta: f64, side: Side) -> f64 {
        self.contact(theta, side).pressure_angle
    }

    /// The curvature (1/length, positive where convex) of the pitch curve at `theta`, from
    /// its first and second derivatives.
    pub fn pitch_curvature(&self, theta: f64, side: Side) -> f64 {
        let c = self.contact(Dual2_64::from(theta).derivative(), side);
        curvature(c.pitch)
    }

    /// The curvature (1/length, positive where convex) of the profile at `theta`, from the
    /// profile's own first and second derivatives (infinite at a cusp).
    pub fn profile_curvature(&self, theta: f64, side: Side) -> f64 {
        let c = self.contact(Dual2_64::from(theta).derivative(), side);
        curvature(c.profile)
    }

    /// The profile's signed radius of curvature for a flat face: the rate at which the
    /// contact moves along the face, d(profile)/dθ · (face direction) (R_b + s + s″);
    /// negative where the profile has a cusp (the face cannot follow the program there).
    pub fn flat_face_radius(&self, theta: f64, side: Side) -> f64 {
        let c = self.contact(Dual2_64::from(theta).derivative(), side);
        let (sin, cos) = theta.sin_cos();
        c.profile[0].v1 * cos - c.profile[1].v1 * sin
    }

    /// The pieces of the turn on which everything is smooth: segments split at the breaks
    /// of their laws, as (start, end) cam angles.
    pub fn pieces(&self) -> Vec<(f64, f64)> {
        let program = &self.program;
        let mut pieces = Vec::new();
        for (index, segment) in program.segments().enumerate() {
            let (a, b) = (program.start(index), program.end(index));
            let mut cuts = vec![a];
            cuts.extend(segment.breaks().iter().map(|f| a + f * (b - a)));
            cuts.push(b);
            pieces.extend(cuts.windows(2).map(|w| (w[0], w[1])));
        }
        pieces
    }

    /// The largest `f` over the turn, each piece searched separately with the one-sided
    /// values at its ends.
    pub fn maximum(&self, f: impl Fn(f64, Side) -> f64) -> Extreme {
        let mut best = Extreme {
            value: f64::NEG_INFINITY,
            angle: 0.0,
        };
        for (lo, hi) in self.pieces() {
            let mid = 0.5 * (lo + hi);
            let side = |t: f64| if t < mid { Side::Right } else { Side::Left };
            let (angle, value) = maximize(|t| f(t, side(t)), lo, hi, SAMPLES);
            if value > best.value {
                best = Extreme { value, angle };
            }
        }
        best
    }

    /// Pressure angle, curvature, undercutting and face width over the turn.
    pub fn analyse(&self) -> CamAnalysis {
        let flat = self.dimensions.follower == Follower::FlatFaced;
        let r = self.dimensions.follower.roller_radius();
        let max_pressure_angle = if flat {
            Extreme {
                value: 0.0,
                angle: 0.0,
            }
        } else {
            self.maximum(|t, side| self.pressure_angle(t, side).abs())
        };
        let (min_pitch_radius, min_profile_radius, undercut_when): (
            _,
            _,
            Box<dyn Fn(f64, Side) -> f64>,
        ) = if flat {
            let least = self.maximum(|t, side| -self.flat_face_radius(t, side));
            let least = Extreme {
                value: -least.value,
                ..least
            };
            (
                None,
                least,
                Box::new(|t, side| -self.flat_face_radius(t, side)),
            )
        } else {
            let sharpest = self.maximum(|t, side| self.pitch_curvature(t, side));
            let pitch = Extreme {
                value: 1.0 / sharpest.value,
                angle: sharpest.angle,
            };
            let profile = Extreme {
                value: pitch.value - r,
                angle: pitch.angle,
            };
            (
                Some(pitch),
                profile,
                Box::new(move |t, side| self.pitch_curvature(t, side) * r - 1.0),
            )
        };
        let undercut = if flat || r > 0.0 {
            self.ranges_where(&*undercut_when)
        } else {
            Vec::new()
        };
        let face_extent = flat.then(|| {
            let slope = |t: f64, side| self.program.svaj(t, side).d1();
            let high = self.maximum(slope);
            let low = self.maximum(|t, side| -slope(t, side));
            (-low.value, high.value)
        });
        CamAnalysis {
            max_pressure_angle,
            min_pitch_radius,
            min_profile_radius,
            undercut,
            face_extent,
        }
    }

    /// The cam-angle ranges where `g > 0`, from samples on each piece, the ends refined by
    /// bisection.
    fn ranges_where(&self, g: &dyn Fn(f64, Side) -> f64) -> Vec<(f64, f64)> {
        let mut ranges: Vec<(f64, f64)> = Vec::new();
        for (lo, hi) in self.pieces() {
            let mid = 0.5 * (lo + hi);
            let at = |t: f64| g(t, if t < mid { Side::Right } else { Side::Left });
            let refine = |mut inside: f64, mut outside: f64| {
                for _ in 0..60 {
                    let m = 0.5 * (inside + outside);
                    if at(m) > 0.0 {
                        inside = m;
                    } else {
                        outside = m;
                    }
                }
                inside
            };
            let ts: Vec<f64> = (0..=SAMPLES)
                .map(|k| lo + (hi - lo) * k as f64 / SAMPLES as f64)
                .collect();
            let mut start: Option<f64> = None;
            for (k, &t) in ts.iter().enumerate() {
                let inside = at(t) > 0.0;
                match (inside, start) {
                    (true, None) => {
                        start = Some(if k == 0 { t } else { refine(t, ts[k - 1]) });
                    }
                    (false, Some(s)) => {
                        ranges.push((s, refine(ts[k - 1], t)));
                        start = None;
                    }
                    _ => {}
                }
            }
            if let Some(s) = start {
                ranges.push((s, hi));
            }
        }
        // Ranges that meet across a piece boundary are one range.
        let mut merged: Vec<(f64, f64)> = Vec::new();
        for range in ranges {
            match merged.last_mut() {
                Some(last) if (range.0 - last.1).abs() <= 1e-12 * TAU => last.1 = range.1,
                _ => merged.push(range),
            }
        }
        merged
    }

    /// `count` points of the turn, equally spaced from θ = 0: (θ, pitch point, profile
    /// point), in the cam frame.
    pub fn outline(&self, count: usize) -> Vec<(f64, [f64; 2], [f64; 2])> {
        (0..count)
            .map(|k| {
                let theta = TAU * k as f64 / count as f64;
                let c = self.contact(theta, Side::Right);
                (theta, c.pitch, c.profile)
            })
            .collect()
    }
}

/// κ = −(X′ × X″)/|X′|³ of a clockwise curve X(θ) given with its derivatives.
fn curvature(x: [Dual2_64; 2]) -> f64 {
    let (d1, d2) = ([x[0].v1, x[1].v1], [x[0].v2, x[1].v2]);
    let speed = d1[0].hypot(d1[1]);
    -(d1[0] * d2[1] - d1[1] * d2[0]) / (speed * speed * speed)
}
