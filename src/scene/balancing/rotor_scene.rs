//! Rotor-only scene files: a title, `[units]` and `[rotor]`, no linkage. A rotor is balanced
//! on its own (its masses, planes and corrections), so it needs no drawn mechanism.

use serde::Deserialize;
use toml::Spanned;

use crate::error::Result;
use crate::scene::context::Context;
use crate::scene::source::Source;
use crate::scene::units::{Units, UnitsSection};

use super::format::RotorDef;
use super::model::SceneRotor;
use super::resolve::resolve_rotor;

/// A rotor-only scene file as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RotorFile {
    /// A one-line title.
    pub title: Option<String>,
    /// Units of every number in the file.
    #[serde(default)]
    pub units: UnitsSection,
    /// The rotor.
    pub rotor: Spanned<RotorDef>,
}

/// A checked rotor-only scene.
#[derive(Debug, Clone, PartialEq)]
pub struct RotorScene {
    /// The file as named in messages.
    pub file: String,
    /// The title.
    pub title: Option<String>,
    /// The units of printed and written numbers.
    pub units: Units,
    /// The rotor (SI).
    pub rotor: SceneRotor,
}

impl RotorScene {
    /// The printed report: the title, then the polygons and the corrections asked for.
    pub fn lines(&self) -> Result<Vec<String>> {
        let mut lines = super::rotor_lines(&self.units, &self.rotor)?;
        // The answers start with a blank line (after the table of a linkage scene).
        match &self.title {
            Some(title) => lines[0].clone_from(title),
            None => {
                lines.remove(0);
            }
        }
        Ok(lines)
    }
}

/// Parses and checks a rotor-only scene given as text; `file` names it in messages.
pub fn parse(file: &str, text: &str) -> Result<RotorScene> {
    let source = Source::new(file, text);
    let raw: RotorFile = toml::from_str(text).map_err(|e| source.syntax_error(&e))?;
    let units = Units::declared(&raw.units);
    // A rotor scene has no `[parameters]`: its formulas are constant.
    let parameters = crate::scene::bindings::Bindings::default();
    let cx = Context::new(&source, units, &parameters);
    Ok(RotorScene {
        file: file.to_owned(),
        title: raw.title,
        units: units.for_outputs(),
        rotor: resolve_rotor(&cx, &raw.rotor)?,
    })
}

/// Reads and checks a rotor-only scene file (at most [`crate::files::MAX_SCENE_BYTES`]).
pub fn load(path: &std::path::Path) -> Result<RotorScene> {
    let text = crate::files::read_scene(path)?;
    parse(&path.display().to_string(), &text)
}
