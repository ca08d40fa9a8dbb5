//! `mechdiff run <cam.toml>`: the report of a cam scene (a file with a `[cam]` section).

use std::io::{BufWriter, Write};
use std::path::PathBuf;

use mechdiff::report::cam;
use mechdiff::scene;
use mechdiff::{Error, files};

use super::run::RunArgs;

/// Runs a cam scene: the report on stdout, the SVAJ table and the profile as CSV if asked.
pub fn run(args: &RunArgs) -> Result<(), Error> {
    let not_here = [
        ("--json", args.json.is_some()),
        ("--jsonl", args.jsonl.is_some()),
        ("--report", args.report.is_some()),
    ];
    if let Some((option, _)) = not_here.iter().find(|(_, given)| *given) {
        return Err(Error::OptionNotApplicable {
            option: (*option).to_owned(),
            scene: args.scene.clone(),
            why: "a cam scene writes its SVAJ table with --csv, its profile with --profile-csv \
                  and its pictures with --plot"
                .to_owned(),
        });
    }
    let scene = scene::cam::load(&args.scene)?;
    if let Some(path) = &args.csv {
        files::write_atomically(path, |mut out| cam::write_svaj_csv(&scene, &mut out))?;
    }
    if let Some(path) = &args.profile_csv {
        files::write_atomically(path, |mut out| cam::write_profile_csv(&scene, &mut out))?;
    }
    if let Some(dir) = &args.plot {
        mechdiff::pictures::cam::write_dir(&scene, dir)?;
    }
    let stdout = std::io::stdout();
    let mut out = BufWriter::new(stdout.lock());
    match cam::write_report(&scene, &mut out).and_then(|()| out.flush()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        result => result.map_err(|source| Error::Write {
            path: PathBuf::from("<stdout>"),
            source,
        }),
    }
}
