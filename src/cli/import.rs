//! `mechdiff import FILE [--out scene.toml] [--force]`: a Pyslvs expression or PMKS text
//! file as a scene.

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use mechdiff::scene::Source;
use mechdiff::{Error, files, import};

/// Arguments of `mechdiff import`.
#[derive(Debug, Args)]
pub struct ImportArgs {
    /// The linkage: a Pyslvs expression (`M[J[R, ...], ...]`) or a PMKS text file
    /// (`ground,input,R,0,0,tfft` a line).
    pub file: PathBuf,
    /// Write the scene to this file (whole or not at all) instead of printing it.
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Replace `--out` if it exists.
    #[arg(long)]
    pub force: bool,
}

/// Reads the file, converts it and prints or writes the scene.
pub fn import(args: &ImportArgs) -> Result<(), Error> {
    let text = files::read_input(&args.file, "the imported file")?;
    if let Some(out) = &args.out {
        files::refuse_inputs([out.as_path()])?;
        if !args.force && out.exists() {
            return Err(Error::Write {
                path: out.clone(),
                source: std::io::Error::new(
                    std::io::ErrorKind::AlreadyExists,
                    "the file exists; give --force to replace it",
                ),
            });
        }
    }
    let source = Source::new(args.file.display().to_string(), text);
    let scene = import::read(&source)?.to_scene(&source)?;
    match &args.out {
        Some(out) => files::write_atomically(out, |w| w.write_all(scene.as_bytes())),
        None => std::io::stdout()
            .write_all(scene.as_bytes())
            .map_err(|source| Error::Write {
                path: PathBuf::from("<stdout>"),
                source,
            }),
    }
}
