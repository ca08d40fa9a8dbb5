//! The transmission angle μ: how well the coupler drives the follower.
//!
//! **Four-bar** (crank a = O₂A, coupler b = AB, follower c = O₄B, frame d = O₂O₄, input
//! angle θ from O₂O₄): μ is the angle at B between the coupler BA and the follower BO₄, the
//! angle of triangle A B O₄ opposite the diagonal AO₄. Two laws of cosines,
//! |AO₄|² = a² + d² − 2ad cos θ = b² + c² − 2bc cos μ, give
//!
//! ```text
//! cos μ = (b² + c² − a² − d² + 2ad cos θ) / (2bc).
//! ```
//!
//! **Slider-crank** (crank r, rod l, offset e of the slider pin's path, θ from the guide's
//! direction): the follower of a slider is the normal to its path (a rocker of infinite
//! length), so μ is the angle between the rod BA and the path's normal n (the guide's
//! direction turned +90°): cos μ = (r sin θ − e)/l; μ = 90° with the rod along the path.
//!
//! **Forms.** The *signed* μ is the oriented angle from the coupler BA to the follower BO₄
//! (resp. n), in (−180°, 180°]: its sign is the loop's assembly branch and changes only
//! where the loop toggles. The *unsigned* μ = |signed| in [0°, 180°] is what the law of
//! cosines gives. The *effective* μ = min(μ, 180° − μ) in [0°, 90°] is the form design
//! rules are written in (keep it above 40°–50°), 90° best; its *deviation* 90° − effective
//! is how far the pose is from ideal transmission.

use crate::{Jet, Scalar, atan2};
use num_dual::Dual3_64;
use std::f64::consts::FRAC_PI_2;

/// The transmission angle at one pose, in its four forms (rad); in any scalar, so a dual
/// number carries its derivatives with respect to the drive.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TransmissionAngle<D> {
    /// The oriented angle from the coupler to the follower, in (−π, π]: its sign is the
    /// loop's assembly branch.
    pub signed: D,
    /// μ = |signed|, in [0, π]: the textbooks' transmission angle.
    pub unsigned: D,
    /// min(μ, π − μ), in [0, π/2]: π/2 is ideal transmission.
    pub effective: D,
    /// π/2 − effective, in [0, π/2]: how far from ideal.
    pub deviation: D,
}

impl<D: Scalar> TransmissionAngle<D> {
    /// The transmission angle between the `coupler` vector (from the follower's joint
    /// towards the input's joint) and the `follower` vector (from the same joint towards the
    /// follower's pivot, or along the normal of a slider's path).
    ///
    /// ```
    /// use mechdiff_core::metrics::TransmissionAngle;
    /// let mu = TransmissionAngle::between([1.0, 0.0], [-1.0, 1.0]);
    /// assert!((mu.unsigned - 0.75 * std::f64::consts::PI).abs() < 1e-15);
    /// assert!((mu.effective - 0.25 * std::f64::consts::PI).abs() < 1e-15);
    /// ```
    pub fn between(coupler: [D; 2], follower: [D; 2]) -> Self {
        let cross = coupler[0] * follower[1] - coupler[1] * follower[0];
        let dot = coupler[0] * follower[0] + coupler[1] * follower[1];
        let signed = atan2(cross, dot);
        let unsigned = signed.abs();
        // Without a branch on the value, so that a traced scalar records one expression
        // for every pose: deviation = |μ − 90°|, effective = 90° − deviation.
        let deviation = (unsigned - D::from(FRAC_PI_2)).abs();
        TransmissionAngle {
            signed,
            unsigned,
            effective: -deviation + FRAC_PI_2,
            deviation,
        }
    }

    /// Each form mapped by `f` (e.g. a dual number to its [`Jet`]).
    pub fn map<T>(self, f: impl Fn(D) -> T) -> TransmissionAngle<T> {
        TransmissionAngle {
            signed: f(self.signed),
            unsigned: f(self.unsigned),
            effective: f(self.effective),
            deviation: f(self.deviation),
        }
    }
}

impl TransmissionAngle<Dual3_64> {
    /// The forms as [`Jet`]s of order `N` (≤ 3) in the drive variable.
    pub fn jets<const N: usize>(self) -> TransmissionAngle<Jet<N>> {
        self.map(|x| {
            let d = [x.v1, x.v2, x.v3];
            Jet::new(x.re, std::array::from_fn(|k| d[k]))
        })
    }
}

/// The four-bar's μ by the law of cosines (rad, in [0, π]) at input angle `theta` (rad,
/// from the frame line), for input a, coupler b, output c and frame d (m).
///
/// ```
/// use mechdiff_core::metrics::four_bar_transmission_angle;
/// // A square-ish loop at θ = 90°: cos μ = (b² + c² − a² − d²)/(2bc) = 0.
/// let mu = four_bar_transmission_angle([1.0, 1.0, 1.0, 1.0], std::f64::consts::FRAC_PI_2);
/// assert!((mu - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
/// ```
pub fn four_bar_transmission_angle<D: Scalar>([a, b, c, d]: [f64; 4], theta: D) -> D {
    let cos = (theta.cos() * (2.0 * a * d) + (b * b + c * c - a * a - d * d)) / (2.0 * b * c);
    clamped_acos(cos)
}

/// The slider-crank's μ (rad, in [0, π]) at crank angle `theta` (rad, from the guide's
/// direction) for crank r, rod l and offset e (m): cos μ = (r sin θ − e)/l.
///
/// ```
/// use mechdiff_core::metrics::slider_crank_transmission_angle;
/// // The rod along the path (r sin θ = e): μ = 90°.
/// let mu = slider_crank_transmission_angle([1.0, 4.0, 0.5], std::f64::consts::FRAC_PI_6);
/// assert!((mu - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
/// ```
pub fn slider_crank_transmission_angle<D: Scalar>([r, l, e]: [f64; 3], theta: D) -> D {
    clamped_acos((theta.sin() * r - e) / l)
}

/// acos of a cosine that rounding may have pushed just outside [−1, 1].
fn clamped_acos<D: Scalar>(cos: D) -> D {
    if cos.re() >= 1.0 {
        D::from(0.0)
    } else if cos.re() <= -1.0 {
        D::from(std::f64::consts::PI)
    } else {
        cos.acos()
    }
}
