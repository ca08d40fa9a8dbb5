//! Scene files: a mechanism described by geometry alone, in TOML.
//!
//! A scene names points at the sketch pose, links (rigid bodies carrying points), joints, one
//! drive, the drive positions to compute and the outputs to print. The format is documented
//! in `docs/scene-format.md`; this module reads it in three stages:
//!
//! 1. [`format`](mod@format): the TOML as written (serde, every value with its byte span);
//! 2. [`resolve`](resolve::resolve): units applied, names resolved, the sketch checked —
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
//! assert_eq!(scene.positions, vec![0.0, 1.0]);
//! assert_eq!(scene.order(), 0);
//! ```

pub mod build;
mod drive;
pub mod dynamics;
mod evaluate;
pub mod format;
mod joints;
pub mod model;
pub mod outputs;
pub mod plan;
pub mod plot;
pub mod resolve;
pub mod run;
pub mod source;
pub mod table;
pub mod units;

use std::path::Path;

use crate::error::{Error, Result};

pub use model::Scene;
pub use plan::Plan;
pub use run::{Checked, Report, check, run};
pub use source::Source;

/// Parses and checks a scene given as text; `file` names it in messages.
pub fn parse(file: &str, text: &str) -> Result<Scene> {
    let source = Source::new(file, text);
    let raw: format::SceneFile = toml::from_str(text).map_err(|e| source.syntax_error(&e))?;
    resolve::resolve(raw, &source)
}

/// Reads, parses and checks a scene file.
pub fn load(path: impl AsRef<Path>) -> Result<Scene> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path).map_err(|source| Error::Read {
        path: path.to_owned(),
        source,
    })?;
    parse(&path.display().to_string(), &text)
}
