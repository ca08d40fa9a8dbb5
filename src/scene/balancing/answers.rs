//! A rotor's answers, computed once for the printed report, the CSV file and the pictures.

use mechdiff_core::balancing::{Correction, CouplePlane, Polygons, TwoPlaneBalance};

use crate::error::{Error, Result};

use super::resolve::SceneRotor;

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
            Some([left, right]) => Some(rotor.two_plane_balance(left, right).map_err(located)?),
            None => None,
        };
        let couple_plane = match self.couple_mass_radius {
            Some(mr) => Some(rotor.couple_plane(mr, self.reference).map_err(located)?),
            None => None,
        };
        Ok(RotorAnswers {
            polygons: rotor.polygons(self.reference),
            resultant: [
                rotor.resultant_force(),
                rotor.resultant_couple(self.reference),
            ],
            scale: rotor.largest_terms(self.reference),
            static_balance: rotor.static_balance(self.reference),
            two_plane,
            couple_plane,
        })
    }
}
