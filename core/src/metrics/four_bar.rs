//! A four-bar loop found in a mechanism: its links, lengths and input, and the metrics that
//! follow from them (Grashof class, input range, transmission angle).

use super::grashof::{FourBarLengths, Grashof};
use super::input_range::{Band, InputFrame, InputRange, TransmissionExtremes, wrap};
use super::transmission::{TransmissionAngle, four_bar_transmission_angle};
use crate::geometry::{Kinematics, PointOutput, ScalarOutput};
use crate::{Jet, Scalar};
use num_dual::Dual3_64;

/// A four-bar loop: four links in a cycle joined by four revolute joints, the frame being
/// the ground, the input pivoted on it and placed before the coupler and the output (which
/// the solver places together, as a dyad).
///
/// ```text
///            A ─────── coupler b ─────── B
///           /                             \
///      input a                          output c
///         /  θ                              \
///       O_in ────────── frame d ─────────── O_out
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct FourBarLoop {
    /// Link names: frame, input, coupler, output.
    pub links: [String; 4],
    /// Joint names: the input's pivot O_in, input–coupler A, coupler–output B, the output's
    /// pivot O_out.
    pub joints: [String; 4],
    /// The lengths d, a, b, c (m), from the sketch.
    pub lengths: FourBarLengths,
    /// Whether the input is the mechanism's drive (an angle drive of its pivot).
    pub driven: bool,
    /// Sums of lengths within this (m) are equal (see [`super::length_tolerance`]).
    pub tolerance: f64,
    /// The sign of the signed transmission angle at the sketch (±1): the loop's branch.
    pub branch: f64,
    pub(crate) input: InputFrame,
    /// A and B on the coupler, O_out on the output.
    pub(crate) points: [PointOutput; 3],
    pub(crate) output_rotation: ScalarOutput,
}

impl FourBarLoop {
    /// What the transmission angle rests on, for a report: the law of cosines in the two
    /// triangles O_in A O_out and A B O_out.
    pub const TRANSMISSION_FORMULA: &'static str = "cos μ = (b² + c² − a² − d² + 2ad·cos θ)/(2bc)";

    /// The lengths as `[a, b, c, d]` (input, coupler, output, frame).
    pub fn abcd(&self) -> [f64; 4] {
        let l = &self.lengths;
        [l.input, l.coupler, l.output, l.frame]
    }

    /// Grashof's class with the inequality it rests on.
    pub fn grashof(&self) -> Grashof {
        let names = self.links.each_ref().map(String::as_str);
        Grashof::classify(&self.lengths, names, self.tolerance)
    }

    /// The input angle at the sketch (rad, from the frame line O_in → O_out, in (−π, π]).
    pub fn sketch_angle(&self) -> f64 {
        self.input.sketch
    }

    pub(crate) fn band(&self) -> Band {
        let [a, b, c, d] = self.abcd();
        Band {
            centre: 0.0,
            high: (a * a + d * d - (b - c) * (b - c)) / (2.0 * a * d),
            low: (a * a + d * d - (b + c) * (b + c)) / (2.0 * a * d),
            high_margin: (a - d).abs() - (b - c).abs(),
            low_margin: b + c - a - d,
            tolerance: self.tolerance,
        }
    }

    /// How far the input turns, from the loop's lengths: fully, or between the toggle
    /// positions where coupler and output fold or stretch in line (on the sketch's side).
    /// When the input is not the drive (a second four-bar driven by the first's rocker),
    /// the other loops may hold it to a narrower range: read μ along the sweep with
    /// [`FourBarLoop::transmission_at`] for the extremes the mechanism reaches.
    pub fn input_range(&self) -> InputRange {
        self.band().range(&self.input)
    }

    /// The transmission angle's extremes over [`FourBarLoop::input_range`], in closed
    /// form: cos μ grows with cos θ, so μ is least at θ = 0 and greatest at θ = π when the
    /// input passes them, else at a toggle end (μ = 0 or π there).
    pub fn transmission_extremes(&self) -> TransmissionExtremes {
        let band = self.band();
        let abcd = self.abcd();
        band.extremes(&band.range(&self.input), &self.input, |theta| {
            four_bar_transmission_angle(abcd, theta)
        })
    }

    /// μ by the law of cosines at input angle `theta` (rad, from the frame line).
    pub fn transmission_angle<D: Scalar>(&self, theta: D) -> D {
        four_bar_transmission_angle(self.abcd(), theta)
    }

    /// The transmission angle in the pose `q` (`(x, y, θ)` per moving link, in any scalar:
    /// e.g. from [`crate::geometry::Tracker::closed_form_pose`]), from the positions of A,
    /// B and O_out.
    pub fn transmission_in<D: Scalar>(&self, q: &[D]) -> TransmissionAngle<D> {
        let [a, b, pivot] = self.points.map(|p| p.position_in(q));
        TransmissionAngle::between(sub(a, b), sub(pivot, b))
    }

    /// The transmission angle at a solved pose with its first `N` derivatives with respect
    /// to the drive.
    pub fn transmission_at<const N: usize>(
        &self,
        k: &Kinematics<'_, N>,
    ) -> TransmissionAngle<Jet<N>> {
        self.transmission_in(&duals(k)).jets()
    }

    /// The output link's rotation since the sketch (its dead positions are the rocker's
    /// ends).
    pub fn output_rotation(&self) -> ScalarOutput {
        self.output_rotation
    }
}

/// The input angle of `arm` about `pivot`, from the direction `zero` (rad, in (−π, π]).
pub(crate) fn angle_from(zero: [f64; 2], pivot: [f64; 2], arm: [f64; 2]) -> f64 {
    let v = sub(arm, pivot);
    wrap(v[1].atan2(v[0]) - zero[1].atan2(zero[0]))
}

pub(crate) fn sub<D: Scalar>(a: [D; 2], b: [D; 2]) -> [D; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

/// The pose of `k` as third-order duals (derivatives above `N` zero).
pub(crate) fn duals<const N: usize>(k: &Kinematics<'_, N>) -> Vec<Dual3_64> {
    (k.coordinates.iter())
        .map(|j| {
            let d = |i: usize| j.derivatives.get(i).copied().unwrap_or(0.0);
            Dual3_64::new(j.value, d(0), d(1), d(2))
        })
        .collect()
}
