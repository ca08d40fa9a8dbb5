//! A slider-crank loop found in a mechanism: crank, rod and a slider on a guide of the
//! ground (or the rod's pin in a slot of the ground), and its metrics.

use super::four_bar::{duals, sub};
use super::grashof::{SliderCrankCriterion, SliderCrankLengths};
use super::input_range::{Band, InputFrame, InputRange, TransmissionExtremes};
use super::transmission::{TransmissionAngle, slider_crank_transmission_angle};
use crate::geometry::{Kinematics, PointOutput};
use crate::{Jet, Scalar};
use std::f64::consts::FRAC_PI_2;

/// A slider-crank loop: a crank pivoted on the ground, a rod hinged to it, and the rod's
/// other pin B moving on a straight path fixed in the ground (a slider on a prismatic guide,
/// or a pin in a slot of the ground); the crank placed before the rod (and slider).
///
/// ```text
///                 A
///          r   /      \   l
///            /          \
///          O  θ→ u        B ══ slider ══   (path of B: e from O, along u)
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct SliderCrankLoop {
    /// The frame (ground) link's name.
    pub frame: String,
    /// The crank's name.
    pub crank: String,
    /// The rod's name.
    pub rod: String,
    /// The slider's name (`None`: the rod's pin runs in a slot of the ground).
    pub slider: Option<String>,
    /// Joint names: the crank's pivot O, the crank pin A, the slider pin B (revolute rod–slider,
    /// or the pin-in-slot), and the guide (prismatic; absent with a pin in a slot).
    pub joints: Vec<String>,
    /// Crank r, rod l, offset e (m), from the sketch.
    pub lengths: SliderCrankLengths,
    /// Whether the crank is the mechanism's drive (an angle drive of its pivot).
    pub driven: bool,
    /// Lengths within this (m) are equal (see [`super::length_tolerance`]).
    pub tolerance: f64,
    /// The sign of the signed transmission angle at the sketch (±1): the loop's branch.
    pub branch: f64,
    /// The path's unit direction u (global; θ is measured from it).
    pub direction: [f64; 2],
    pub(crate) input: InputFrame,
    /// A and B on the rod.
    pub(crate) points: [PointOutput; 2],
    /// The crank pivot O (global, m).
    pub(crate) pivot: [f64; 2],
}

impl SliderCrankLoop {
    /// What the transmission angle rests on, for a report: the rod's rise over its length.
    pub const TRANSMISSION_FORMULA: &'static str = "cos μ = (r·sin θ − e)/l";

    /// The lengths as `[r, l, e]`.
    pub fn rle(&self) -> [f64; 3] {
        let l = &self.lengths;
        [l.crank, l.rod, l.offset]
    }

    /// Whether the crank turns fully: r + |e| vs l.
    pub fn criterion(&self) -> SliderCrankCriterion {
        SliderCrankCriterion::classify(&self.lengths, self.tolerance)
    }

    /// The crank angle at the sketch (rad, from the path's direction u, in (−π, π]).
    pub fn sketch_angle(&self) -> f64 {
        self.input.sketch
    }

    pub(crate) fn band(&self) -> Band {
        let [r, l, e] = self.rle();
        Band {
            centre: FRAC_PI_2,
            high: (e + l) / r,
            low: (e - l) / r,
            high_margin: e + l - r,
            low_margin: l - r - e,
            tolerance: self.tolerance,
        }
    }

    /// How far the crank turns: fully, or between the positions where the rod stands
    /// perpendicular to the path (on the sketch's side).
    pub fn input_range(&self) -> InputRange {
        self.band().range(&self.input)
    }

    /// The transmission angle's extremes over [`SliderCrankLoop::input_range`], in closed
    /// form: cos μ = (r sin θ − e)/l is greatest at θ = 90° and least at θ = −90° when the
    /// crank passes them.
    pub fn transmission_extremes(&self) -> TransmissionExtremes {
        let band = self.band();
        let rle = self.rle();
        band.extremes(&band.range(&self.input), &self.input, |theta| {
            slider_crank_transmission_angle(rle, theta)
        })
    }

    /// μ = acos((r sin θ − e)/l) at crank angle `theta` (rad, from u).
    pub fn transmission_angle<D: Scalar>(&self, theta: D) -> D {
        slider_crank_transmission_angle(self.rle(), theta)
    }

    /// The normal n of the path (u turned +90°): the slider's "follower".
    pub fn normal(&self) -> [f64; 2] {
        [-self.direction[1], self.direction[0]]
    }

    /// The transmission angle in the pose `q` (any scalar), between the rod B → A and the
    /// path's normal n.
    pub fn transmission_in<D: Scalar>(&self, q: &[D]) -> TransmissionAngle<D> {
        let [a, b] = self.points.map(|p| p.position_in(q));
        let n = self.normal().map(D::from);
        TransmissionAngle::between(sub(a, b), n)
    }

    /// The transmission angle at a solved pose with its first `N` derivatives.
    pub fn transmission_at<const N: usize>(
        &self,
        k: &Kinematics<'_, N>,
    ) -> TransmissionAngle<Jet<N>> {
        self.transmission_in(&duals(k)).jets()
    }

    /// The slider's position along the path, u·(B − O) (m), at a solved pose: its dead
    /// positions are the stroke's ends.
    pub fn slider_position<const N: usize>(&self, k: &Kinematics<'_, N>) -> Jet<N> {
        let [x, y] = k.position(&self.points[1]);
        let [u, o] = [self.direction, self.pivot];
        let value = u[0] * (x.value - o[0]) + u[1] * (y.value - o[1]);
        let derivatives =
            std::array::from_fn(|i| u[0] * x.derivatives[i] + u[1] * y.derivatives[i]);
        Jet::new(value, derivatives)
    }
}
