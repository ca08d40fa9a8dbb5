//! `mechdiff run <scene.toml> [--csv out.csv]`: run a scene and print its table.

use std::io::{BufWriter, Write};
use std::path::PathBuf;

use clap::Args;
use mechdiff::scene::{self, table};
use mechdiff::{Error, files};

/// Arguments of `mechdiff run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// The scene file (TOML; see docs/scene-format.md).
    pub scene: PathBuf,
    /// Replace the value of a parameter of the scene's `[parameters]` (repeatable):
    /// `--set l1=0.16`; the value may be a formula of the other parameters.
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<scene::parameters::Setting>,
    /// Run the scene once per value of one parameter and print one long table with the
    /// parameter as its first column: `--sweep l1=0.15:0.17:5` (5 values, both ends
    /// included, either direction) or `--sweep l1=0.15,0.16,0.17`; in the parameter's unit.
    #[arg(long = "sweep", value_name = "NAME=FROM:TO:COUNT")]
    pub sweep: Option<scene::study::ParameterSweep>,
    /// Also write every column at every drive position to this CSV file (header: `name [unit]`).
    /// The file is written whole or not at all (a temporary file beside it, renamed when
    /// complete), and never onto the scene file.
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,
}

/// Reads, checks and runs the scene; prints the plan, the table and the dead positions.
pub fn run(args: &RunArgs) -> Result<(), Error> {
    if let Some(csv) = &args.csv
        && files::same_file(csv, &args.scene)
    {
        return Err(Error::OutputIsInput {
            output: csv.clone(),
            scene: args.scene.clone(),
        });
    }
    let (scene, report) = match &args.sweep {
        None => {
            let scene = scene::load_with(&args.scene, &args.set)?;
            let report = scene::run(&scene)?;
            (scene, report)
        }
        Some(sweep) => {
            let text = files::read_scene(&args.scene)?;
            let file = args.scene.display().to_string();
            scene::study::run_sweep(&file, &text, &args.set, sweep)?
        }
    };
    if let Some(path) = &args.csv {
        files::write_atomically(path, |mut out| table::write_csv(&report, &mut out))?;
    }
    let stdout = std::io::stdout();
    let mut out = BufWriter::new(stdout.lock());
    match table::write_table(&scene, &report, &mut out).and_then(|()| out.flush()) {
        // The reader went away (`mechdiff run s.toml | head`): not an error of ours.
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        result => result.map_err(|source| Error::Write {
            path: PathBuf::from("<stdout>"),
            source,
        }),
    }
}
