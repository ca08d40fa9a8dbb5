//! `mechdiff run|check <rotor.toml>`: a rotor-only scene (a title, `[units]` and `[rotor]`).

use std::io::{BufWriter, Write};
use std::path::PathBuf;

use mechdiff::scene::balancing::RotorScene;
use mechdiff::{Error, files};

use super::run::RunArgs;

/// Runs a rotor scene (read by `scene::any::read`): its answers on stdout, as CSV with
/// `--csv` and JSON with `--json`, its polygons with `--plot` and on a page with `--report` (the options it cannot honour
/// are refused by [`super::refuse_options`] before).
pub fn run(args: &RunArgs, scene: &RotorScene) -> Result<(), Error> {
    let lines = scene.lines()?;
    let answers = scene.rotor.answers()?;
    if let Some(path) = &args.csv {
        files::write_atomically(path, |mut out| {
            mechdiff::report::rotor::write_csv(scene, &answers, &mut out)
        })?;
    }
    if let Some(path) = &args.json {
        files::write_atomically(path, |mut out| {
            mechdiff::report::rotor::write_json(scene, &answers, &mut out)
        })?;
    }
    if let Some(dir) = &args.plot {
        mechdiff::pictures::balancing::write_rotor_dir(&scene.rotor, dir)?;
    }
    if let Some(path) = &args.report {
        mechdiff::pictures::report::rotor::write(scene, path)?;
    }
    let stdout = std::io::stdout();
    let mut out = BufWriter::new(mechdiff::escape::Terminal::new(stdout.lock()));
    let written = lines
        .iter()
        .try_for_each(|line| writeln!(out, "{line}"))
        .and_then(|()| out.flush());
    match written {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        result => result.map_err(|source| Error::Write {
            path: PathBuf::from("<stdout>"),
            source,
        }),
    }
}

/// Prints the summary of a rotor scene read by `scene::any::read` (which checked its values
/// and the answers it asks for).
pub fn check(scene: &RotorScene) -> Result<(), Error> {
    let r = &scene.rotor;
    let mut asked = vec!["static balance"];
    if r.planes.is_some() {
        asked.push("two-plane balance");
    }
    if r.couple_mass_radius.is_some() {
        asked.push("couple-plane mass");
    }
    println!(
        "{}",
        mechdiff::escape::terminal(&format!(
            "{}: ok: rotor of {} mass(es), no linkage; {}",
            scene.file,
            r.rotor.masses().len(),
            asked.join(", ")
        ))
    );
    Ok(())
}
