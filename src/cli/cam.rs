//! `mechdiff run <cam.toml>`: the report of a cam scene (a file with a `[cam]` section).

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use mechdiff::Error;
use mechdiff::report::cam;
use mechdiff::scene;

use super::run::RunArgs;

/// Whether the file given to `run` is a cam scene (unreadable files are left to the usual
/// path, which reports them).
pub fn is_cam_scene(path: &Path) -> bool {
    std::fs::read_to_string(path).is_ok_and(|text| scene::cam::is_cam_scene(&text))
}

/// Runs a cam scene: the report on stdout, the SVAJ table and the profile as CSV if asked.
pub fn run(args: &RunArgs) -> Result<(), Error> {
    let scene = scene::cam::load(&args.scene)?;
    let write = |path: &PathBuf, what: &dyn Fn(&mut BufWriter<File>) -> std::io::Result<()>| {
        let result = File::create(path).and_then(|file| {
            let mut out = BufWriter::new(file);
            what(&mut out)?;
            out.flush()
        });
        result.map_err(|source| Error::Write {
            path: path.clone(),
            source,
        })
    };
    if let Some(path) = &args.csv {
        write(path, &|out| cam::write_svaj_csv(&scene, out))?;
    }
    if let Some(path) = &args.profile_csv {
        write(path, &|out| cam::write_profile_csv(&scene, out))?;
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
