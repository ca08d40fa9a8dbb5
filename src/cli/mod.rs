//! The `run` and `check` subcommands of the `mechdiff` tool (scene files).

pub mod cam;
pub mod check;
pub mod rotor;
pub mod run;

use std::path::Path;

use mechdiff::{files, scene};

/// Which kind of scene the file given to `run` or `check` is (an unreadable file is left to
/// the linkage path, which reports it).
pub fn scene_kind(path: &Path) -> scene::Kind {
    files::read_scene(path).map_or(scene::Kind::Linkage, |text| scene::kind(&text))
}
