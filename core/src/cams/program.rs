//! A cam program: segments over one turn of the cam, each a motion law or a formula.
//!
//! The displacement s(θ) is one function generic over the [`Scalar`] ([`CamProgram::
//! displacement`]), so s′, s″, s‴ at any cam angle come from dual numbers ([`CamProgram::
//! svaj`]), and every derivative method of [`crate::method`] applies (the program is a
//! [`PositionFunction`] of the cam angle). At a segment boundary or a break inside a law the
//! [`Side`] picks the one-sided limit.

use std::f64::consts::{PI, TAU};

use num_dual::Dual3_64;

use super::law::{MotionLaw, Side};
use crate::error::{Error, Result};
use crate::jet::Jet;
use crate::motion::{DriveState, Motion};
use crate::position::PositionFunction;
use crate::scalar::Scalar;
use crate::symbolic::{Graph, Id};

/// Relative tolerance on the sum of the extents (one turn) and on the joins in displacement.
pub const JOIN_TOLERANCE: f64 = 1e-9;

/// |θ − boundary| within this (rad) is "at the boundary".
const AT_BOUNDARY: f64 = 16.0 * f64::EPSILON * TAU;

/// A displacement given as a formula in the symbolic engine's infix syntax, of the cam angle
/// `x` (rad, from the start of the turn), or of `u` (0 to 1 over the segment); `pi` is π;
/// `if(x < a, then, otherwise)` makes it piecewise (see [`crate::symbolic::piecewise`]).
/// The continuity report looks at segment boundaries only: a jump made by an `if` inside one
/// formula segment is not located (split the segment there to have it reported).
///
/// ```
/// use mechdiff_core::cams::Formula;
/// let f = Formula::parse("160*x^2/pi^2").unwrap();
/// assert!((f.value(std::f64::consts::PI, 1.0) - 160.0).abs() < 1e-12);
/// ```
#[derive(Clone, Debug)]
pub struct Formula {
    text: String,
    graph: Graph,
    root: Id,
    scale: f64,
}

impl Formula {
    /// Parses `text` (infix syntax, see [`crate::symbolic::infix`]).
    ///
    /// # Errors
    /// [`Error::Formula`] with the position of the problem if the text does not parse.
    pub fn parse(text: &str) -> Result<Self> {
        let mut graph = Graph::new();
        let root = graph.parse_infix_piecewise(text)?;
        Ok(Formula {
            text: text.to_owned(),
            graph,
            root,
            scale: 1.0,
        })
    }

    /// The same formula with its value multiplied by `factor` (a formula written in
    /// millimetres is `scaled(1e-3)` to give metres).
    pub fn scaled(self, factor: f64) -> Self {
        Formula {
            scale: self.scale * factor,
            ..self
        }
    }

    /// The formula as written.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// The formula at cam angle `x` and segment fraction `u`, in any scalar type.
    ///
    /// # Errors
    /// [`Error::UnboundSymbol`] for a name other than `x`, `u`, `pi`.
    pub fn evaluate<D: Scalar>(&self, x: D, u: D) -> Result<D> {
        let pi = D::from(PI);
        let bindings = [("x", x), ("u", u), ("pi", pi), ("PI", pi)];
        Ok(self.graph.evaluate_dual(&[self.root], &bindings)?[0] * self.scale)
    }

    /// The value at cam angle `x`, segment fraction `u` (NaN if a name is unbound: the
    /// program checks every formula when it is built).
    pub fn value(&self, x: f64, u: f64) -> f64 {
        self.evaluate(x, u).unwrap_or(f64::NAN)
    }
}

/// What a segment does: a standard law with a lift, or a formula.
#[derive(Clone, Debug)]
pub enum SegmentMotion {
    /// s = s₀ + lift·f(u): a rise (lift > 0), a return (lift < 0) or a dwell (law
    /// [`MotionLaw::Dwell`], lift 0).
    Law {
        /// The law.
        law: MotionLaw,
        /// Signed change of displacement over the segment.
        lift: f64,
    },
    /// s given by a formula of `x` (cam angle) or `u`.
    Formula(Formula),
}

/// One segment: what the follower does over an extent of cam angle.
#[derive(Clone, Debug)]
pub struct Segment {
    /// The motion over the segment.
    pub motion: SegmentMotion,
    /// The cam angle the segment spans (rad, positive).
    pub extent: f64,
}

impl Segment {
    /// A segment following a standard law.
    pub fn law(law: MotionLaw, lift: f64, extent: f64) -> Self {
        Segment {
            motion: SegmentMotion::Law { law, lift },
            extent,
        }
    }

    /// A segment given by a formula.
    pub fn formula(formula: Formula, extent: f64) -> Self {
        Segment {
            motion: SegmentMotion::Formula(formula),
            extent,
        }
    }

    /// The breaks inside the segment, as fractions (those of its law; none for a formula).
    pub fn breaks(&self) -> &'static [f64] {
        match &self.motion {
            SegmentMotion::Law { law, .. } => law.breaks(),
            SegmentMotion::Formula(_) => &[],
        }
    }

    /// A short description: `cycloidal rise 20` or `formula 160*x^2/pi^2`.
    pub fn describe(&self) -> String {
        match &self.motion {
            SegmentMotion::Law {
                law: MotionLaw::Dwell,
                ..
            } => "dwell".to_owned(),
            SegmentMotion::Law { law, lift } => {
                let kind = if *lift >= 0.0 { "rise" } else { "return" };
                format!("{law} {kind} {}", lift.abs())
            }
            SegmentMotion::Formula(f) => format!("formula {}", f.text()),
        }
    }
}

/// A segment placed in the turn.
#[derive(Clone, Debug)]
struct Placed {
    segment: Segment,
    start: f64,
    start_displacement: f64,
}

/// A cam program: segments covering one turn, joined in displacement.
///
/// ```
/// use mechdiff_core::cams::{CamProgram, MotionLaw, Segment, Side};
/// use std::f64::consts::PI;
/// // Rise 20 (cycloidal) over 90°, dwell 90°, return (3-4-5) over 90°, dwell 90°.
/// let program = CamProgram::new(vec![
///     Segment::law(MotionLaw::Cycloidal, 20.0, PI / 2.0),
///     Segment::law(MotionLaw::Dwell, 0.0, PI / 2.0),
///     Segment::law(MotionLaw::Polynomial345, -20.0, PI / 2.0),
///     Segment::law(MotionLaw::Dwell, 0.0, PI / 2.0),
/// ], 0.0).unwrap();
/// let svaj = program.svaj(PI / 4.0, Side::Right);
/// // Halfway up a cycloidal rise: s = h/2, s′ = 2h/β.
/// assert!((svaj.value - 10.0).abs() < 1e-13);
/// assert!((svaj.d1() - 2.0 * 20.0 / (PI / 2.0)).abs() < 1e-13);
/// ```
#[derive(Clone, Debug)]
pub struct CamProgram {
    placed: Vec<Placed>,
}

impl CamProgram {
    /// Places `segments` one after the other from cam angle 0, the first starting at
    /// displacement `start_displacement`, and checks them.
    ///
    /// # Errors
    /// [`Error::CamSegment`] for an extent that is not positive and finite, a lift that is
    /// not finite, a dwell with a lift, a formula that does not evaluate to a finite number
    /// at the ends; [`Error::CamTurn`] if the extents do not add up to 2π (to 1e-9
    /// relative); [`Error::CamJoin`] if the displacement jumps at a boundary, the end of the
    /// turn included.
    pub fn new(segments: Vec<Segment>, start_displacement: f64) -> Result<Self> {
        if segments.is_empty() {
            return Err(Error::CamTurn { total_deg: 0.0 });
        }
        let mut placed = Vec::with_capacity(segments.len());
        let mut start = 0.0_f64;
        let mut displacement = start_displacement;
        for (index, segment) in segments.into_iter().enumerate() {
            let problem = |problem: String| Error::CamSegment {
                segment: index + 1,
                start_deg: degrees(start),
                problem,
            };
            if !(segment.extent.is_finite() && segment.extent > 0.0) {
                return Err(problem(format!(
                    "the extent must be a positive angle, found {} rad",
                    segment.extent
                )));
            }
            if let SegmentMotion::Law { law, lift } = &segment.motion {
                if !lift.is_finite() {
                    return Err(problem(format!("the lift must be finite, found {lift}")));
                }
                if *law == MotionLaw::Dwell && *lift != 0.0 {
                    return Err(problem(format!(
                        "a dwell has no lift, found {lift}; use a rise or return law"
                    )));
                }
            }
            placed.push(Placed {
                segment,
                start,
                start_displacement: displacement,
            });
            let this = placed.last().expect("just pushed");
            if let SegmentMotion::Formula(f) = &this.segment.motion {
                let ends = [(start, 0.0), (start + this.segment.extent, 1.0)];
                for (x, u) in ends {
                    match f.evaluate(x, u) {
                        Ok(v) if v.is_finite() => {}
                        Ok(v) => {
                            // Where, without a unit: the segment's start angle is in
                            // the error, in the caller's unit.
                            let end = if u == 0.0 {
                                "start (u = 0)"
                            } else {
                                "end (u = 1)"
                            };
                            return Err(problem(format!(
                                "the formula `{}` is {v} at the segment's {end}",
                                f.text(),
                            )));
                        }
                        Err(e) => {
                            return Err(problem(format!(
                                "{e} in the formula `{}`; formulas may use x (cam angle, \
                                 rad), u (0 to 1 over the segment) and pi",
                                f.text()
                            )));
                        }
                    }
                }
                placed.last_mut().expect("just pushed").start_displacement = f.value(start, 0.0);
            }
            let this = placed.last().expect("just pushed");
            displacement = this.end_displacement();
            start += this.segment.extent;
        }
        if (start - TAU).abs() > JOIN_TOLERANCE * TAU {
            return Err(Error::CamTurn {
                total_deg: degrees(start),
            });
        }
        let program = CamProgram { placed };
        program.check_joins()?;
        Ok(program)
    }

    /// Every boundary joins in displacement (formulas may not; laws join by construction).
    fn check_joins(&self) -> Result<()> {
        let ends: Vec<f64> = self.placed.iter().map(Placed::end_displacement).collect();
        let scale = self
            .placed
            .iter()
            .map(|p| p.start_displacement.abs())
            .chain(ends.iter().map(|e| e.abs()))
            .fold(0.0, f64::max);
        let n = self.placed.len();
        for after in (1..n).chain([0]) {
            let before = (after + n - 1) % n;
            let (left, right) = (ends[before], self.placed[after].start_displacement);
            if (left - right).abs() > JOIN_TOLERANCE * scale.max(f64::MIN_POSITIVE) {
                return Err(Error::CamJoin {
                    angle_deg: if after == 0 {
                        360.0
                    } else {
                        degrees(self.placed[after].start)
                    },
                    before: before + 1,
                    after: after + 1,
                    left,
                    right,
                });
            }
        }
        Ok(())
    }

    /// The segments in order.
    pub fn segments(&self) -> impl Iterator<Item = &Segment> {
        self.placed.iter().map(|p| &p.segment)
    }

    /// Segment `index` (from 0).
    ///
    /// # Panics
    /// If `index` is not below [`CamProgram::len`].
    pub fn segment(&self, index: usize) -> &Segment {
        &self.placed[index].segment
    }

    /// Number of segments.
    pub fn len(&self) -> usize {
        self.placed.len()
    }

    /// Whether there are no segments (never: a program has at least one).
    pub fn is_empty(&self) -> bool {
        self.placed.is_empty()
    }

    /// The cam angle (rad) where segment `index` starts (0 for the first).
    pub fn start(&self, index: usize) -> f64 {
        self.placed[index].start
    }

    /// The cam angle (rad) where segment `index` ends (2π for the last).
    pub fn end(&self, index: usize) -> f64 {
        if index + 1 == self.placed.len() {
            TAU
        } else {
            self.placed[index + 1].start
        }
    }

    /// The segment that holds cam angle `theta` (any real angle, taken modulo 2π), the one
    /// chosen by `side` at a boundary, and the cam angle in [0, 2π] it corresponds to on
    /// that segment.
    pub fn locate(&self, theta: f64, side: Side) -> (usize, f64) {
        let n = self.placed.len();
        let mut t = theta.rem_euclid(TAU);
        if TAU - t <= AT_BOUNDARY {
            t = 0.0;
        }
        let index = self
            .placed
            .iter()
            .rposition(|p| p.start <= t + AT_BOUNDARY)
            .unwrap_or(0);
        let at_start = (t - self.placed[index].start).abs() <= AT_BOUNDARY;
        if side == Side::Left && at_start {
            let before = (index + n - 1) % n;
            let local = if index == 0 { TAU } else { t };
            (before, local)
        } else {
            (index, t)
        }
    }

    /// The follower displacement s(θ) at cam angle `theta`, in any scalar type; `side` picks
    /// the one-sided limit at a boundary or a break.
    pub fn displacement<D: Scalar>(&self, theta: D, side: Side) -> D {
        let (index, local) = self.locate(theta.re(), side);
        let p = &self.placed[index];
        // x: the cam angle on this segment's turn, with theta's derivative parts.
        let x = theta - (theta.re() - local);
        let u = (x - p.start) / p.segment.extent;
        match &p.segment.motion {
            SegmentMotion::Law { law, lift } => law.rise(u, side) * *lift + p.start_displacement,
            SegmentMotion::Formula(f) => f.evaluate(x, u).unwrap_or(x * f64::NAN),
        }
    }

    /// s, s′, s″, s‴ at cam angle `theta` (′ = d/dθ).
    pub fn svaj(&self, theta: f64, side: Side) -> Jet<3> {
        let s = self.displacement(Dual3_64::from(theta).derivative(), side);
        Jet::new(s.re, [s.v1, s.v2, s.v3])
    }

    /// The follower's position, velocity ω s′, acceleration α s′ + ω² s″ and jerk
    /// φ⃛ s′ + 3ωα s″ + ω³ s‴ for the cam's motion `drive`.
    pub fn follower_motion(&self, theta: f64, side: Side, drive: &DriveState) -> Motion {
        self.svaj(theta, side).motion(drive)
    }

    /// The smallest and largest displacement over the turn (from the segments' ends and
    /// 64 samples each, refined), and the stroke between them.
    pub fn displacement_range(&self) -> (f64, f64) {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for index in 0..self.len() {
            let (a, b) = (self.start(index), self.end(index));
            let at = |t: f64| self.value_on(index, t);
            let (_, max) = super::extrema::maximize(at, a, b, 64);
            let (_, min) = super::extrema::maximize(|t| -at(t), a, b, 64);
            (lo, hi) = (lo.min(-min), hi.max(max));
        }
        (lo, hi)
    }

    /// s at `t` on segment `index` (one-sided at the segment's own ends).
    pub(crate) fn value_on(&self, index: usize, t: f64) -> f64 {
        self.svaj_on(index, t).value
    }

    /// s, s′, s″, s‴ at `t` on segment `index`, even at its ends (one-sided limits from
    /// inside the segment) and at the breaks of its law (the side nearer the middle).
    pub fn svaj_on(&self, index: usize, t: f64) -> Jet<3> {
        let mid = 0.5 * (self.start(index) + self.end(index));
        let side = if t < mid { Side::Right } else { Side::Left };
        let (found, _) = self.locate(t, side);
        if found == index {
            return self.svaj(t, side);
        }
        // t is at the far end of the turn for the last segment, or just outside by
        // rounding: evaluate the segment's own formula there.
        let p = &self.placed[index];
        let theta = Dual3_64::from(t).derivative();
        let u = (theta - p.start) / p.segment.extent;
        let s = match &p.segment.motion {
            SegmentMotion::Law { law, lift } => law.rise(u, side) * *lift + p.start_displacement,
            SegmentMotion::Formula(f) => f.evaluate(theta, u).unwrap_or(theta * f64::NAN),
        };
        Jet::new(s.re, [s.v1, s.v2, s.v3])
    }
}

/// An angle in degrees for messages, rounded to 1e-9° so that the rounding of a conversion
/// from the user's unit does not show (120°, not 119.99999999999999°).
fn degrees(radians: f64) -> f64 {
    (radians.to_degrees() * 1e9).round() / 1e9
}

impl Placed {
    fn end_displacement(&self) -> f64 {
        match &self.segment.motion {
            SegmentMotion::Law { lift, .. } => self.start_displacement + lift,
            SegmentMotion::Formula(f) => f.value(self.start + self.segment.extent, 1.0),
        }
    }
}

impl PositionFunction for CamProgram {
    type Output<T> = T;

    /// The displacement at cam angle `phi` (the right-hand limit at a boundary).
    fn evaluate<D: Scalar>(&self, phi: D) -> D {
        self.displacement(phi, Side::Right)
    }

    fn map<A, B>(s: A, mut f: impl FnMut(A) -> B) -> B {
        f(s)
    }
}
