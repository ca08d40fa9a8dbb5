//! Peak coefficients of a motion law: the largest |f′|, |f″|, |f‴| of its normalised
//! displacement f(u) over 0 ≤ u ≤ 1.
//!
//! For a rise h over a cam angle β the peaks of the program are C_v h/β, C_a h/β²,
//! C_j h/β³ (per radian of cam angle). They are found by search (samples and golden
//! section on each piece of the law, ends included as one-sided values), not copied from a
//! table, so a test can check them against the textbooks.

use num_dual::Dual3_64;

use super::extrema::maximize;
use super::law::{MotionLaw, Side};

/// The peak coefficients of a law.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PeakCoefficients {
    /// max |f′| (velocity).
    pub velocity: f64,
    /// max |f″| (acceleration), one-sided values at breaks and ends included.
    pub acceleration: f64,
    /// max |f‴| (jerk), one-sided values at breaks and ends included.
    pub jerk: f64,
}

impl MotionLaw {
    /// The law's peak coefficients C_v, C_a, C_j.
    ///
    /// ```
    /// use mechdiff_core::cams::MotionLaw;
    /// let c = MotionLaw::Cycloidal.peak_coefficients();
    /// assert!((c.velocity - 2.0).abs() < 1e-12);
    /// ```
    pub fn peak_coefficients(self) -> PeakCoefficients {
        let mut cuts = vec![0.0];
        cuts.extend_from_slice(self.breaks());
        cuts.push(1.0);
        let mut peaks = [0.0f64; 3];
        for piece in cuts.windows(2) {
            let (lo, hi) = (piece[0], piece[1]);
            let mid = 0.5 * (lo + hi);
            let derivative = |u: f64, k: usize| {
                let side = if u < mid { Side::Right } else { Side::Left };
                let f = self.rise(Dual3_64::from(u).derivative(), side);
                [f.v1, f.v2, f.v3][k].abs()
            };
            for (k, peak) in peaks.iter_mut().enumerate() {
                let (_, value) = maximize(|u| derivative(u, k), lo, hi, 64);
                *peak = peak.max(value);
            }
        }
        PeakCoefficients {
            velocity: peaks[0],
            acceleration: peaks[1],
            jerk: peaks[2],
        }
    }
}
