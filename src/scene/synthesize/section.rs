//! `[synthesize]` as written: serde structures that mirror the TOML one to one, every value
//! with its span (the scene's reader skips the section; [`super::read`] gives it meaning).

use std::collections::BTreeMap;

use serde::Deserialize;
use toml::Spanned;

use crate::scene::parameters::ParameterTable;
use crate::scene::units::UnitsSection;
use crate::scene::values::Number;

/// The parts of the file synthesis reads; the rest is skipped.
#[derive(Deserialize)]
pub(super) struct SynthesisOnly {
    pub parameters: Option<ParameterTable>,
    #[serde(default)]
    pub units: UnitsSection,
    pub synthesize: Option<Spanned<SynthesizeDef>>,
}

/// A list of numbers, each with its span.
pub(super) type Numbers = Spanned<Vec<Spanned<Number>>>;

/// `[synthesize]`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SynthesizeDef {
    /// `four_bar`, `slider_crank` or `stephenson_six`.
    pub linkage: Spanned<String>,
    /// Per dyad, `left` or `right` (the side a scene's `circles` construction names).
    pub branch: Option<Spanned<Vec<Spanned<String>>>>,
    /// The engine's variable → the scene's parameter, where the names differ.
    pub names: Option<Spanned<BTreeMap<Spanned<String>, Spanned<String>>>>,
    /// The parameter holding the sketch's drive position: the scene found is drawn at the
    /// first target's.
    pub sketch: Option<Spanned<String>>,
    /// Design variables: a parameter (or a task angle) → `[lower, upper]`.
    pub bounds: Spanned<BTreeMap<Spanned<String>, Numbers>>,
    /// The seed of the starts.
    pub seed: Option<Spanned<i64>>,
    /// Samples of the bounds.
    pub starts: Option<Spanned<i64>>,
    /// Local searches (the best samples polished).
    pub local_searches: Option<Spanned<i64>>,
    /// Residual evaluations in all.
    pub evaluations: Option<Spanned<i64>>,
    /// Wall-clock limit (s).
    pub time_limit: Option<Spanned<Number>>,
    /// The objective at which the search stops (m²).
    pub objective: Option<Spanned<Number>>,
    /// The crank must turn fully.
    pub crank_rotates: Option<Spanned<bool>>,
    /// The least transmission angle (the file's angle unit).
    pub min_transmission: Option<Spanned<Number>>,
    /// Assembly checks between two consecutive targets.
    pub checks_between_targets: Option<Spanned<i64>>,
    /// The Grashof class of the four-bar loop (`crank-rocker`, …, `any`).
    pub grashof: Option<Spanned<String>>,
    /// Rounds of sampling.
    pub rounds: Option<Spanned<i64>>,
    /// Give each sample the timing that suits it before ranking.
    pub fit_timing: Option<Spanned<bool>>,
    /// `lm`, `differences` or `evolution`.
    pub method: Option<Spanned<String>>,
    /// Path generation.
    pub path: Option<Spanned<PathDef>>,
    /// Function generation.
    pub function: Option<Spanned<FunctionDef>>,
    /// Motion generation.
    pub motion: Option<Spanned<MotionDef>>,
}

/// `[synthesize.path]`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct PathDef {
    /// The traced point.
    pub point: Spanned<String>,
    /// `[[x, y], …]` in the file's length unit.
    pub targets: Spanned<Vec<Numbers>>,
    /// The drive position of each target (the file's angle unit).
    pub drive: Option<Numbers>,
    /// `absolute`, `relative` or `free`.
    pub timing: Option<Spanned<String>>,
    /// One weight per target (default 1).
    pub weights: Option<Numbers>,
}

/// `[synthesize.function]`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FunctionDef {
    /// The output: a link's angle, or the slider.
    pub output: Spanned<String>,
    /// `[[drive, output], …]`.
    pub pairs: Option<Spanned<Vec<Numbers>>>,
    /// The output as a formula of the drive `phi` (both in the file's units).
    pub formula: Option<Spanned<String>>,
    /// The drive range of the formula: first position.
    pub from: Option<Spanned<Number>>,
    /// Last position.
    pub to: Option<Spanned<Number>>,
    /// Number of positions (both ends included).
    pub count: Option<Spanned<i64>>,
    /// One weight per pair (default 1; the first pair's has no effect).
    pub weights: Option<Numbers>,
}

/// `[synthesize.motion]`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MotionDef {
    /// The guided link.
    pub link: Spanned<String>,
    /// `[[x, y, angle], …]`.
    pub poses: Spanned<Vec<Numbers>>,
    /// The drive position of each pose.
    pub drive: Option<Numbers>,
    /// `absolute`, `relative` or `free`.
    pub timing: Option<Spanned<String>>,
    /// The length an angle error of one radian weighs as (file's length unit).
    pub angle_weight: Spanned<Number>,
    /// One weight per pose (default 1).
    pub weights: Option<Numbers>,
}
