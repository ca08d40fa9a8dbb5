//! The `run`, `check` and `import` subcommands of the `mechdiff` tool (scene files).

pub mod accuracy;
pub mod cam;
pub mod check;
pub mod import;
pub mod rotor;
pub mod run;

use std::path::Path;

use mechdiff::{Error, files, scene};

/// Which kind of scene the file given to `run` or `check` is (an unreadable file is left to
/// the linkage path, which reports it).
pub fn scene_kind(path: &Path) -> scene::Kind {
    files::read_scene(path).map_or(scene::Kind::Linkage, |text| scene::kind(&text))
}

/// Refuses `--set` for a scene whose kind has no `[parameters]` (cams and rotors).
///
/// # Errors
/// [`Error::OptionNotApplicable`] naming `--set` and the scene, when settings are given.
pub fn refuse_settings(
    kind: scene::Kind,
    settings: &[scene::parameters::Setting],
    path: &Path,
) -> Result<(), Error> {
    if settings.is_empty() || kind == scene::Kind::Linkage {
        return Ok(());
    }
    Err(Error::OptionNotApplicable {
        option: "--set".to_owned(),
        scene: path.to_path_buf(),
        why: "only linkage scenes have `[parameters]`; write the value into the cam or rotor \
              scene itself"
            .to_owned(),
    })
}
