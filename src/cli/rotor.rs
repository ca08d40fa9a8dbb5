//! `mechdiff run|check <rotor.toml>`: a rotor-only scene (a title, `[units]` and `[rotor]`).

use std::io::{BufWriter, Write};
use std::path::PathBuf;

use mechdiff::scene::balancing::rotor_scene;
use mechdiff::{Error, files};

use super::check::CheckArgs;
use super::run::RunArgs;

/// Runs a rotor scene: its answers on stdout, as CSV with `--csv`, its polygons with `--plot`
/// (the options it cannot honour are refused by [`super::refuse_options`] before).
pub fn run(args: &RunArgs) -> Result<(), Error> {
    let scene = rotor_scene::load(&args.scene)?;
    let lines = scene.lines()?;
    if let Some(path) = &args.csv {
        let answers = scene.rotor.answers()?;
        files::write_atomically(path, |mut out| {
            mechdiff::report::rotor::write_csv(&scene, &answers, &mut out)
        })?;
    }
    if let Some(dir) = &args.plot {
        mechdiff::pictures::balancing::write_rotor_dir(&scene.rotor, dir)?;
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

/// Checks a rotor scene (its values and the answers it asks for) and prints a summary.
pub fn check(args: &CheckArgs) -> Result<(), Error> {
    let scene = rotor_scene::load(&args.scene)?;
    let r = &scene.rotor;
    r.answers()?;
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
