//! Velocity and acceleration arrows of the `[plot] vectors` points in the drawings at the
//! `[plot] positions`, each kind to one round scale stated in the legend.

use super::drawing::{Drawing, VectorKind};
use super::scene::point_motions;
use crate::error::{Error, Result};
use crate::scene::Scene;

/// The velocity and acceleration arrows of the `[plot] vectors` points at the `[plot]
/// positions`, each kind to one scale for all drawings (so that arrows compare).
pub(crate) struct Vectors {
    /// Indices of the points (into the scene's points).
    points: Vec<usize>,
    /// Per position, per scene point: `[v, a]` (m/s, m/s²).
    motions: Vec<Vec<[[f64; 2]; 2]>>,
    /// Model length (m) per m/s and per m/s².
    scales: [f64; 2],
}

/// The longest arrow, as a fraction of the larger side of the drawings' extent.
const ARROW_SHARE: f64 = 0.25;

impl Vectors {
    /// The arrows at the drive positions `phi` (in sweep order), scaled so that the longest
    /// of each kind is at most [`ARROW_SHARE`] of `extent`'s larger side, at a round scale
    /// (1, 2 or 5 × 10ⁿ model units per unit of the quantity); `None` without
    /// `[plot] vectors`. Without a drive speed, or with a velocity or acceleration that is not
    /// finite (a singular position), an error at `[plot] vectors`.
    pub(crate) fn of(
        scene: &Scene,
        m: &mechdiff_core::geometry::Mechanism,
        phi: &[f64],
        extent: &[[f64; 2]],
    ) -> Result<Option<Vectors>> {
        let Some((names, location)) = &scene.plot.vectors else {
            return Ok(None);
        };
        let invalid = |message: String| Error::Invalid {
            location: location.clone(),
            message,
        };
        let Some(omega) = scene.drive.speed else {
            return Err(invalid(
                "`[plot] vectors` needs the drive speed: give `[drive] speed` (a point's \
                 velocity is ω times its velocity coefficient)"
                    .to_owned(),
            ));
        };
        let points: Vec<usize> = (names.iter())
            .filter_map(|n| scene.points.iter().position(|p| p.name == *n))
            .collect();
        let motions = point_motions(scene, m, phi, omega, scene.drive.acceleration)?;
        let mut longest = [0.0_f64; 2];
        for (pose, &at) in motions.iter().zip(phi) {
            for &p in &points {
                for (kind, value) in pose[p].iter().enumerate() {
                    let length = value[0].hypot(value[1]);
                    if !length.is_finite() {
                        return Err(invalid(format!(
                            "the {} of point `{}` at drive position {} is not defined (a \
                             singular position); choose another `[plot] position`",
                            ["velocity", "acceleration"][kind],
                            scene.points[p].name,
                            scene.drive_text(at)
                        )));
                    }
                    longest[kind] = longest[kind].max(length);
                }
            }
        }
        let (lo, hi) = extent.iter().fold(
            ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
            |(lo, hi), p| {
                (
                    [lo[0].min(p[0]), lo[1].min(p[1])],
                    [hi[0].max(p[0]), hi[1].max(p[1])],
                )
            },
        );
        let size = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        let size = if size.is_finite() && size > 0.0 {
            size
        } else {
            1.0
        };
        let scales =
            longest.map(|l| round_down(ARROW_SHARE * size / if l > 0.0 { l } else { 1.0 }));
        Ok(Some(Vectors {
            points,
            motions,
            scales,
        }))
    }

    /// `drawing` (at position `k`, pose `pose`) with its arrows.
    pub(crate) fn drawn(&self, drawing: Drawing, k: usize, pose: &[[f64; 2]]) -> Drawing {
        let kinds = [VectorKind::Velocity, VectorKind::Acceleration];
        self.points.iter().fold(drawing, |d, &p| {
            (0..2).fold(d, |d, kind| {
                d.vector(
                    kinds[kind],
                    pose[p],
                    self.motions[k][p][kind],
                    self.scales[kind],
                )
            })
        })
    }
}

/// The largest 1, 2 or 5 × 10ⁿ not above `v` (> 0).
fn round_down(v: f64) -> f64 {
    let decade = 10f64.powf(v.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * decade)
        .find(|&r| r <= v * (1.0 + 1e-12))
        .unwrap_or(decade)
}

#[cfg(test)]
mod tests {
    use super::round_down;

    /// Scales are the largest 1, 2 or 5 × 10ⁿ not above the value (exact ones kept).
    #[test]
    fn scales_round_down_to_one_two_five() {
        for (v, want) in [
            (0.37, 0.2),
            (5.0, 5.0),
            (0.099, 0.05),
            (1234.0, 1000.0),
            (2.0e-7, 2.0e-7),
        ] {
            let got = round_down(v);
            assert!((got - want).abs() <= 1e-12 * want, "{v}: {got} vs {want}");
        }
    }
}
