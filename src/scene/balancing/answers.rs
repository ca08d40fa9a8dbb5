//! A rotor's answers, computed once for the printed report, the CSV file and the pictures.

use mechdiff_core::balancing::{Correction, CouplePlane, Polygons, TwoPlaneBalance};

use crate::error::{Error, Result};

use super::model::SceneRotor;

/// Everything asked of a `[rotor]` (SI: kg·m, kg·m², m, rad).
#[derive(Debug, Clone, PartialEq)]
pub struct RotorAnswers {
    /// The force (m r) and couple (m r d, about the reference plane) polygons.
    pub polygons: Polygons,
    /// Their gaps: `Σ Uᵢ` (kg·m) and `Σ Uᵢ (zᵢ − z₀)` (kg·m²).
    pub resultant: [[f64; 2]; 2],
    /// The largest term of each polygon: the scale of its rounding noise.
    pub scale: [f64; 2],
    /// The static correction, in the reference plane.
    pub static_balance: Correction,
    /// The two-plane corrections, if `planes` is given.
    pub two_plane: Option<TwoPlaneBalance>,
    /// The one correcting mass of `couple_mass_radius` that cancels the couple, if given.
    pub couple_plane: Option<CouplePlane>,
}

impl SceneRotor {
    /// Computes the rotor's answers; an engine error (coincident planes, no couple to
    /// cancel) is located at `[rotor]`.
    pub fn answers(&self) -> Result<RotorAnswers> {
        let rotor = &self.rotor;
        let located = |e: mechdiff_core::Error| Error::Invalid {
            location: self.location.clone(),
            message: e.to_string(),
        };
        let two_plane = match self.planes {
            Some([left, right]) => Some(rotor.two_plane_balance(left, right).map_err(|e| {
                match (e, &self.planes_at) {
                    (mechdiff_core::Error::CoincidentPlanes { .. }, Some(at)) => Error::Invalid {
                        location: at.clone(),
                        message: "the two correction planes coincide to rounding (closer than \
                                  1e-12 of the rotor's axial extent): two-plane balancing \
                                  needs two distinct planes; move one of them along the shaft"
                            .to_owned(),
                    },
                    (e, _) => located(e),
                }
            })?),
            None => None,
        };
        let couple_plane = match self.couple_mass_radius {
            Some(mr) => Some(rotor.couple_plane(mr, self.reference).map_err(located)?),
            None => None,
        };
        let answers = RotorAnswers {
            polygons: rotor.polygons(self.reference),
            resultant: [
                rotor.resultant_force(),
                rotor.resultant_couple(self.reference),
            ],
            scale: rotor.largest_terms(self.reference),
            static_balance: rotor.static_balance(self.reference),
            two_plane,
            couple_plane,
        };
        answers.check_finite(self)?;
        Ok(answers)
    }
}

impl RotorAnswers {
    /// Every answer is a finite number: each input is bounded where it is written, but two
    /// planes a hair apart, or a tiny `correction_radius` or `couple_mass_radius`, still
    /// divide a finite m·r·d into an overflow. Such a rotor is refused at `[rotor]` rather
    /// than printed as `inf`.
    fn check_finite(&self, rotor: &SceneRotor) -> Result<()> {
        let corrections = std::iter::once(&self.static_balance)
            .chain(self.two_plane.iter().flat_map(|t| [&t.left, &t.right]))
            .chain(self.couple_plane.iter().map(|c| &c.correction));
        let mut numbers: Vec<f64> = self.resultant.iter().flatten().copied().collect();
        numbers.extend(self.scale);
        numbers.extend(self.polygons.force.iter().flatten());
        numbers.extend(self.polygons.couple.iter().flatten());
        for c in corrections {
            numbers.extend([c.axial, c.mass_radius, c.angle, c.vector[0], c.vector[1]]);
            if let Some(radius) = rotor.correction_radius {
                numbers.push(c.mass_radius / radius);
            }
        }
        if let Some(c) = &self.couple_plane {
            numbers.extend([c.distance, c.force_after[0], c.force_after[1]]);
        }
        if numbers.iter().all(|x| x.is_finite()) {
            return Ok(());
        }
        Err(Error::Invalid {
            location: rotor.location.clone(),
            message: "the rotor's corrections overflow (are not finite numbers): the correction \
                      planes are too close together, or `correction_radius` or \
                      `couple_mass_radius` too small for these masses; move the planes apart \
                      or enlarge those values"
                .to_owned(),
        })
    }
}
