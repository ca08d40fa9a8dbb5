//! `mechdiff run <cam.toml>`: the report of a cam scene (a file with a `[cam]` section).

use std::io::{BufWriter, Write};
use std::path::PathBuf;

use mechdiff::report::cam;

use mechdiff::scene::cam::CamScene;
use mechdiff::{Error, files};

use super::run::RunArgs;

/// Runs a cam scene (read by `scene::any::read`): the report on stdout, its warnings on
/// stderr, the SVAJ table and the profile as CSV, the summary as JSON and the animated report as HTML
/// if asked (the
/// options it cannot honour are refused by [`super::refuse_options`] before).
pub fn run(args: &RunArgs, scene: &CamScene) -> Result<(), Error> {
    for warning in scene.warnings(&scene.mechanism.analyse()) {
        eprintln!("warning: {}: {warning}", scene.file);
    }
    if let Some(path) = &args.json {
        files::write_atomically(path, |mut out| cam::write_json(scene, &mut out))?;
    }
    if let Some(path) = &args.csv {
        files::write_atomically(path, |mut out| cam::write_svaj_csv(scene, &mut out))?;
    }
    if let Some(path) = &args.profile_csv {
        files::write_atomically(path, |mut out| cam::write_profile_csv(scene, &mut out))?;
    }
    if let Some(dir) = &args.plot {
        mechdiff::pictures::cam::write_dir(scene, dir)?;
    }
    if let Some(path) = &args.report {
        mechdiff::pictures::report::cam::write(scene, path)?;
    }
    let stdout = std::io::stdout();
    let mut out = BufWriter::new(mechdiff::escape::Terminal::new(stdout.lock()));
    match cam::write_report(scene, &mut out).and_then(|()| out.flush()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        result => result.map_err(|source| Error::Write {
            path: PathBuf::from("<stdout>"),
            source,
        }),
    }
}
