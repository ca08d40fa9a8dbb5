//! Scene files: a mechanism described by geometry alone, in TOML.
//!
//! A scene names points at the sketch pose, links (rigid bodies carrying points), joints, one
//! drive, the drive positions to compute and the outputs to print. The format is documented
//! in `docs/scene-format.md`; this module reads it in three stages:
//!
//! 1. [`format`](mod@format): the TOML as written (serde, every value with its byte span);
//! 2. `resolve`: units applied, names resolved, the sketch checked —
//!    a [`Scene`], where every error names `file:line:column` and what was expected;
//! 3. [`build`](mod@build): the geometry model of mechdiff-core, and [`run`](fn@run): the
//!    sweep, evaluated.
//!
//! ```
//! let scene = mechdiff::scene::parse("<doc>", r#"
//!     [points]
//!     O = [0.0, 0.0]
//!     A = [0.1, 0.0]
//!     [links]
//!     ground = ["O"]
//!     crank = ["O", "A"]
//!     [joints]
//!     O = { type = "revolute", at = "O", links = ["ground", "crank"] }
//!     [drive]
//!     joint = "O"
//!     line = ["O", "A"]
//!     [sweep]
//!     positions = [0.0, 1.0]
//!     [[output]]
//!     point = "A"
//!     quantities = ["position"]
//! "#).unwrap();
//! assert_eq!(scene.positions.to_vec().unwrap(), vec![0.0, 1.0]);
//! assert_eq!(scene.order(), 0);
//! ```

pub mod any;
pub mod balancing;
pub mod build;
pub mod cam;
pub(crate) mod context;
mod describe;
mod dimension;
mod drive;
pub mod dynamics;
pub mod error_context;
pub(crate) mod evaluate;
pub mod format;
mod joints;
pub(crate) mod launch;
pub mod metrics;
pub mod model;
pub mod motion;
pub(crate) mod outputs;
pub mod parameters;
mod placement;
pub(crate) mod plan;
pub mod plot;
pub(crate) mod positions;
pub(crate) mod preflight;
mod resample;
pub(crate) mod resolve;
pub mod run;
pub mod setup;
pub mod solver;
pub(crate) mod source;
pub mod study;
pub(crate) mod sweep;
pub(crate) mod sweep_limits;
pub mod synthesize;
pub mod table;
pub mod tangent;

// The lower layers of reading, in the `mechdiff-scene` crate, under their old paths.
pub use mechdiff_scene::{bindings, scalar, units, values};
pub(crate) use mechdiff_scene::{construct, limits, quantity};

use std::path::Path;

use crate::error::Result;

pub use launch::{check, run, run_with};
pub use model::Scene;
pub use outputs::Column;
pub use plan::Plan;
pub use positions::Positions;
pub use run::{Checked, Report};
pub use setup::{RunOptions, Setup};
pub use source::Source;
pub use sweep::Sweeper;
pub use sweep_limits::SweepLimit;
pub use sweep_limits::kind_words;

/// The most list entries (commas) a scene's text may hold: a `positions` list of
/// `values::MAX_POSITIONS` ([`Positions::to_vec`]) and room for the rest. TOML is parsed
/// whole before a list is read, at about 150 bytes an entry, so a longer list is refused
/// before parsing.
pub const MAX_LIST_ENTRIES: usize = values::MAX_POSITIONS + 100_000;

/// What a scene file describes, from its top-level sections.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A linkage (`[points]`, `[links]`, …; the default, which reports what is missing).
    Linkage,
    /// A cam (a `[cam]` section; see [`cam`]).
    Cam,
    /// A rotor alone (a `[rotor]` section and no `[points]`; see [`balancing::RotorScene`]).
    Rotor,
    /// Formulas of the drive (an `[outputs]` table of formulas; see
    /// `crate::accuracy::formula`).
    Formula,
}

/// Which kind of scene `text` is. Text that is not TOML is a [`Kind::Linkage`], whose
/// reader reports the syntax error at its place.
pub fn kind(text: &str) -> Kind {
    match text.parse::<toml::Table>() {
        Ok(table) if table.get("outputs").is_some_and(toml::Value::is_table) => Kind::Formula,
        Ok(table) if table.contains_key("cam") => Kind::Cam,
        Ok(table) if table.contains_key("rotor") && !table.contains_key("points") => Kind::Rotor,
        _ => Kind::Linkage,
    }
}

/// Parses and checks a scene given as text; `file` names it in messages.
pub fn parse(file: &str, text: &str) -> Result<Scene> {
    parse_with(file, text, &[])
}

/// Parses and checks a scene given as text, with `settings` (`--set`) replacing values of
/// its `[parameters]`.
pub fn parse_with(file: &str, text: &str, settings: &[parameters::Setting]) -> Result<Scene> {
    let source = Source::new(file, text);
    if let Some((at, _)) = text.match_indices(',').nth(MAX_LIST_ENTRIES) {
        return Err(crate::error::Error::Invalid {
            location: source.location(at..at + 1),
            message: format!(
                "the file has more than {MAX_LIST_ENTRIES} list entries (commas) before this \
                 one; a `positions` list holds at most {} drive positions: use `from`, `to` \
                 and `step`, or split the sweep into several scenes",
                values::MAX_POSITIONS
            ),
        });
    }
    let raw: format::SceneFile = toml::from_str(text).map_err(|e| source.syntax_error(&e))?;
    let bindings =
        parameters::bindings_of(raw.parameters.as_ref(), &raw.units, &source, settings, None)?;
    resolve::resolve(&raw, &source, &bindings)
}

/// Reads, parses and checks a scene file (at most [`crate::files::MAX_SCENE_BYTES`], UTF-8).
pub fn load(path: impl AsRef<Path>) -> Result<Scene> {
    load_with(path, &[])
}

/// Reads, parses and checks a scene file with `settings` (`--set`) replacing values of its
/// `[parameters]`.
pub fn load_with(path: impl AsRef<Path>, settings: &[parameters::Setting]) -> Result<Scene> {
    let path = path.as_ref();
    let text = crate::files::read_scene(path)?;
    parse_with(&path.display().to_string(), &text, settings)
}
