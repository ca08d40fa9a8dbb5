//! `[rotor]` and `[balancing]` checked, in SI (see `resolve`).

use mechdiff_core::balancing::{Counterweight, Rotor};

use crate::error::Location;

/// A checked `[rotor]` (SI).
#[derive(Debug, Clone, PartialEq)]
pub struct SceneRotor {
    /// The rotor.
    pub rotor: Rotor,
    /// Two correction planes (m).
    pub planes: Option<[f64; 2]>,
    /// The couple polygon's plane (m).
    pub reference: f64,
    /// Radius of the correcting masses (m).
    pub correction_radius: Option<f64>,
    /// Mass-radius of one correcting mass that cancels the couple (kg·m).
    pub couple_mass_radius: Option<f64>,
    /// Where `[rotor]` is.
    pub location: Location,
    /// Where `planes` is written, if it is.
    pub planes_at: Option<Location>,
}

/// The checked balancing sections of a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneBalancing {
    /// `[rotor]`.
    pub rotor: Option<SceneRotor>,
    /// `[balancing]` counterweights (SI), each with its place in the file, and the section's
    /// place.
    pub counterweights: Option<(Vec<(Counterweight, Location)>, Location)>,
    /// `[balancing] slider_crank`: crank, rod and slider links, the fraction, and its place.
    pub slider_crank: Option<SceneSliderCrank>,
}

/// A checked `[balancing] slider_crank`.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneSliderCrank {
    /// Crank, rod and slider links.
    pub links: [String; 3],
    /// Fraction of the reciprocating mass balanced, in [0, 1].
    pub fraction: f64,
    /// Where it is.
    pub location: Location,
}
