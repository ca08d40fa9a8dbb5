//! The balancing sections as written (serde, every value with its span).

use serde::Deserialize;
use toml::Spanned;

use crate::scene::values::Name;
use crate::scene::values::Number;

/// One mass of `[rotor] masses`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RotorMassDef {
    /// Mass (kg, > 0).
    pub mass: Spanned<Number>,
    /// Radius from the shaft axis (length unit, ≥ 0).
    pub radius: Spanned<Number>,
    /// Angle in the rotor's frame (angle unit).
    pub angle: Spanned<Number>,
    /// Axial position of its plane (length unit).
    pub plane: Spanned<Number>,
}

/// `[rotor]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RotorDef {
    /// The masses.
    pub masses: Spanned<Vec<Spanned<RotorMassDef>>>,
    /// Two correction planes (length unit).
    #[serde(default, deserialize_with = "crate::scene::values::option_number_pair")]
    pub planes: Option<crate::scene::values::SpannedPair>,
    /// The plane the couple polygon is taken about (length unit; default 0).
    #[serde(default)]
    pub reference: Option<Spanned<Number>>,
    /// Radius of the correcting masses (length unit, > 0).
    #[serde(default)]
    pub correction_radius: Option<Spanned<Number>>,
    /// The mass-radius (kg·m) of one correcting mass placed to cancel the couple.
    #[serde(default)]
    pub couple_mass_radius: Option<Spanned<Number>>,
}

/// One counterweight of `[balancing]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CounterweightDef {
    /// The link (turning about a fixed pivot).
    pub link: Name,
    /// The pivot and a second point of the link; angles are measured from this line.
    pub line: Spanned<[Name; 2]>,
    /// Distance of the counterweight's centre from the pivot (length unit, > 0).
    pub radius: Spanned<Number>,
}

/// `[balancing] slider_crank`: the primary and secondary unbalance of an in-line
/// slider-crank and its partial balance.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SliderCrankDef {
    /// The crank (turning about a fixed pivot).
    pub crank: Name,
    /// The connecting rod.
    pub rod: Name,
    /// The slider, on a straight ground guide through the crank pivot.
    pub slider: Name,
    /// Fraction of the reciprocating mass to balance, in [0, 1] (default 0.5).
    pub fraction: Option<Spanned<f64>>,
}

/// `[balancing]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BalancingDef {
    /// The counterweights to size.
    pub counterweights: Option<Spanned<Vec<Spanned<CounterweightDef>>>>,
    /// A slider-crank's unbalance.
    pub slider_crank: Option<Spanned<SliderCrankDef>>,
}
