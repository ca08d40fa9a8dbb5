//! `mechdiff run <scene.toml> [--csv out.csv] [--json out.json] [--plot DIR] [--report
//! out.html]`: run a scene, print its table, and write the outputs asked for.

use std::io::{BufWriter, IsTerminal, Write};
use std::path::PathBuf;

use clap::Args;
use mechdiff::RunOptions;
use mechdiff::evaluator::Evaluator;
use mechdiff::scene::any::AnyScene;
use mechdiff::scene::{self, table};
use mechdiff::{Error, escape, files, pictures, sensitivity, stream};

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
    /// Also write every column at every drive position to this CSV file (header: `name [unit]`;
    /// rotor scenes: the rotor's answers, one row each).
    /// The file is written whole or not at all (a temporary file beside it, renamed when
    /// complete), and never onto the scene file.
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,
    /// Also write every column at every drive position to this JSON Lines file, one object
    /// per drive position keyed by the CSV's headers (pandas: `read_json(path, lines=True)`,
    /// polars: `read_ndjson`). Written whole or not at all, like `--csv`.
    #[arg(long, value_name = "FILE")]
    pub jsonl: Option<PathBuf>,
    /// Worker threads solving and formatting the rows (0: `RAYON_NUM_THREADS`, else one per
    /// core). The output is the same, byte for byte, for any number; at most 1024.
    #[arg(long, value_name = "N", default_value_t = 0,
          value_parser = clap::value_parser!(u64).range(0..=stream::MAX_THREADS as u64))]
    pub threads: u64,
    /// Also write the columns, rows and dead positions to this JSON file (held in memory:
    /// at most a million drive positions).
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// Draw the run into this folder: diagram.svg/png, mechanism_*.svg/png, report.html.
    #[arg(long, value_name = "DIR")]
    pub plot: Option<PathBuf>,
    /// Write the animated HTML report of the run to this file (self-contained).
    #[arg(long, value_name = "FILE")]
    pub report: Option<PathBuf>,
    /// Check the scene's `[tolerances]` study by N runs at parameters drawn uniformly from
    /// their ± tolerances; prints the largest deviation sampled beside the worst case (at
    /// most a million samples).
    #[arg(long = "monte-carlo", value_name = "N",
          value_parser = clap::value_parser!(u64)
              .range(0..=sensitivity::tolerance::MAX_SAMPLES as u64))]
    pub monte_carlo: Option<u64>,
    /// The seed of `--monte-carlo`'s generator (the same seed gives the same samples).
    #[arg(long, value_name = "S", default_value_t = 1)]
    pub seed: u64,
    /// Cam scenes: write the cam profile (pitch and profile points, normals) to this CSV.
    #[arg(long, value_name = "FILE")]
    pub profile_csv: Option<PathBuf>,
    /// How positions are evaluated: `solver` (the geometry solver in dual numbers),
    /// `program` (the run-time evaluator of the scene's traced closed forms: every loop
    /// must have one; compiled to native code from 2500 positions on, interpreted below),
    /// `interpreter` or `jit` (the same evaluator always interpreted, or always compiled:
    /// the same values bit for bit), or `auto`: the default (today the solver, whose digits
    /// existing runs print; the program's rows are faster: BENCHMARKS.md). Results agree to
    /// 1e-13; errors are the solver's. The plan line says which path evaluates each loop.
    #[arg(long, value_enum, value_name = "HOW", default_value_t = Evaluator::Auto)]
    pub evaluator: Evaluator,
}

/// Reads, checks and runs the scene; prints the plan, the table and the dead positions.
pub fn run(args: &RunArgs) -> Result<(), Error> {
    // Reading the scene makes it one of the run's inputs, which no output may be.
    let text = files::read_scene(&args.scene)?;
    files::refuse_inputs(outputs(args))?;
    let kind = scene::kind(&text);
    let given = [
        ("--set", !args.set.is_empty()),
        ("--sweep", args.sweep.is_some()),
        ("--json", args.json.is_some()),
        ("--jsonl", args.jsonl.is_some()),
        ("--plot", args.plot.is_some()),
        ("--report", args.report.is_some()),
        ("--profile-csv", args.profile_csv.is_some()),
        ("--monte-carlo", args.monte_carlo.is_some()),
        ("--evaluator", args.evaluator != Evaluator::Auto),
    ];
    super::refuse_options(kind, &given, &args.scene)?;
    let file = args.scene.display().to_string();
    // The reader `check` uses: the same verdict on everything up to solving.
    let read = match scene::any::read(&file, &text, &args.set)? {
        AnyScene::Cam(cam) => return super::cam::run(args, &cam),
        AnyScene::Rotor(rotor) => return super::rotor::run(args, &rotor),
        AnyScene::Formula(formulas, _) => return super::formula::run(args, &formulas),
        AnyScene::Linkage(scene) => scene,
    };
    // The scene's cam files are inputs now too: refused before the run.
    files::refuse_inputs(outputs(args))?;
    let study_asked = sensitivity::requested(&text) || args.monte_carlo.is_some();
    let mut study = None;
    let (scene, report) = match &args.sweep {
        Some(_) if study_asked => {
            return Err(Error::OptionNotApplicable {
                option: "--sweep".to_owned(),
                scene: args.scene.clone(),
                why: "the scene has a sensitivity or tolerance study (`[sensitivity]`, \
                      `[tolerances]`, `--monte-carlo`), which runs at one set of parameter \
                      values; run it once per value with `--set`"
                    .to_owned(),
            });
        }
        None if study_asked && args.evaluator != Evaluator::Auto => {
            return Err(Error::OptionNotApplicable {
                option: "--evaluator".to_owned(),
                scene: args.scene.clone(),
                why: "a sensitivity or tolerance study runs the scene many times on the solver; \
                      leave `--evaluator` out"
                    .to_owned(),
            });
        }
        None if study_asked => {
            let options = sensitivity::Options {
                monte_carlo: args.monte_carlo.map(|n| n as usize),
                seed: args.seed,
            };
            let (scene, report, found) = sensitivity::run(&file, &text, &args.set, &options)?;
            study = found;
            (scene, report)
        }
        None => {
            let scene = *read;
            let options = RunOptions {
                evaluator: args.evaluator,
            };
            let in_memory = scene.balancing.is_some()
                || args.json.is_some()
                || args.plot.is_some()
                || args.report.is_some();
            if !in_memory {
                return stream(&scene, args, &options);
            }
            let report = scene::run_with(&scene, &options)?;
            (scene, report)
        }
        Some(sweep) => scene::study::run_sweep(&file, &text, &args.set, sweep)?,
    };
    for warning in &report.warnings {
        eprintln!(
            "{}",
            escape::terminal(&format!("warning: {}: {warning}", scene.file))
        );
    }
    files::refuse_inputs(outputs(args))?;
    if let Some(path) = &args.csv {
        files::write_atomically(path, |mut out| table::write_csv(&report, &mut out))?;
    }
    if let Some(path) = &args.jsonl {
        files::write_atomically(path, |mut out| table::write_jsonl(&report, &mut out))?;
    }
    if let Some(path) = &args.json {
        files::write_atomically(path, |mut out| table::write_json(&scene, &report, &mut out))?;
    }
    if let Some(dir) = &args.plot {
        pictures::run::write_dir(&scene, &report, dir)?;
    }
    if let Some(path) = &args.report {
        pictures::report::write(&scene, &report, path)?;
    }
    let stdout = std::io::stdout();
    let mut out = BufWriter::new(escape::Terminal::new(stdout.lock()));
    let written = table::write_table(&scene, &report, &mut out).and_then(|()| match &study {
        Some(study) => sensitivity::write_summary(study, &mut out),
        None => Ok(()),
    });
    match written.and_then(|()| out.flush()) {
        // The reader went away (`mechdiff run s.toml | head`): not an error of ours.
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        result => result.map_err(|source| Error::Write {
            path: PathBuf::from("<stdout>"),
            source,
        }),
    }
}

/// The output files asked for (`--plot`'s are checked by the picture writers).
fn outputs(args: &RunArgs) -> impl Iterator<Item = &std::path::Path> {
    [
        &args.csv,
        &args.jsonl,
        &args.json,
        &args.report,
        &args.profile_csv,
    ]
    .into_iter()
    .flatten()
    .map(PathBuf::as_path)
}

/// Runs a kinematic scene streaming its rows: the table to stdout, `--csv` and `--jsonl`
/// into temporary files renamed over the user's only when the run succeeded.
fn stream(scene: &scene::Scene, args: &RunArgs, run: &RunOptions) -> Result<(), Error> {
    let mut csv = args
        .csv
        .as_deref()
        .map(files::AtomicFile::create)
        .transpose()?;
    let mut jsonl = args
        .jsonl
        .as_deref()
        .map(files::AtomicFile::create)
        .transpose()?;
    let mut stdout = BufWriter::with_capacity(1 << 16, escape::Terminal::new(std::io::stdout()));
    fn sink(file: &mut files::AtomicFile) -> stream::Sink<'_> {
        let path = file.path().to_owned();
        stream::Sink {
            path,
            out: file.writer(),
        }
    }
    let mut sinks = stream::Sinks {
        table: Some(stream::Sink {
            path: PathBuf::from("<stdout>"),
            out: &mut stdout,
        }),
        csv: csv.as_mut().map(sink),
        jsonl: jsonl.as_mut().map(sink),
    };
    let options = stream::Options {
        threads: args.threads as usize,
        progress: std::io::stderr().is_terminal()
            && scene.positions.len() > stream::TABLE_FROM_VALUES,
        evaluator: run.evaluator,
        ..stream::Options::default()
    };
    let streamed = stream::run(scene, &mut sinks, &options)?;
    drop(sinks);
    for warning in &streamed.warnings {
        eprintln!(
            "{}",
            escape::terminal(&format!("warning: {}: {warning}", scene.file))
        );
    }
    for file in [csv, jsonl].into_iter().flatten() {
        file.commit()?;
    }
    match stdout.flush() {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        result => result.map_err(|source| Error::Write {
            path: PathBuf::from("<stdout>"),
            source,
        }),
    }
}
