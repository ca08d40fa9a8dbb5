//! `mechdiff run <scene.toml> [--csv out.csv] [--json out.json] [--plot DIR] [--report
//! out.html]`: run a scene, print its table, and write the outputs asked for.

mod args;

pub use args::RunArgs;

use std::io::{BufWriter, IsTerminal, Write};
use std::path::PathBuf;

use mechdiff::RunOptions;
use mechdiff::evaluator::Evaluator;
use mechdiff::scene::any::AnyScene;
use mechdiff::scene::{self, table};
use mechdiff::{Error, escape, files, pictures, sensitivity, stream};

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
    if read.motion.is_some() {
        return super::motion::run(args, &read);
    }
    let study_asked = sensitivity::requested(&text) || args.monte_carlo.is_some();
    let mut study = None;
    // A parameter study's runs, kept apart for its pictures (one curve per value).
    let mut study_runs = None;
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
        Some(sweep) => {
            let runs = scene::study::run_each(&file, &text, &args.set, sweep)?;
            if args.plot.is_some() || args.report.is_some() {
                let joined = scene::study::join(sweep, runs.clone())?;
                study_runs = Some(runs);
                joined
            } else {
                scene::study::join(sweep, runs)?
            }
        }
    };
    for warning in &report.warnings {
        eprintln!(
            "{}",
            escape::terminal(&format!("warning: {}: {warning}", scene.file))
        );
    }
    files::refuse_inputs(outputs(args))?;
    // A parameter study's rows are of many linkages: their metrics are not one block.
    let metrics = match &args.sweep {
        None => metrics_of(&scene),
        Some(_) => None,
    };
    if let Some(path) = &args.csv {
        files::write_atomically(path, |mut out| table::write_csv(&report, &mut out))?;
    }
    if let Some(path) = &args.jsonl {
        files::write_atomically(path, |mut out| table::write_jsonl(&report, &mut out))?;
    }
    if let Some(path) = &args.json {
        files::write_atomically(path, |mut out| {
            table::write_json_with(&scene, &report, metrics.as_ref(), &mut out)
        })?;
    }
    let study_pictures = args.sweep.as_ref().zip(study_runs.as_deref());
    if let Some(dir) = &args.plot {
        match study_pictures {
            Some((sweep, runs)) => pictures::study::write_dir(sweep, runs, dir)?,
            None => pictures::run::write_dir(&scene, &report, dir)?,
        };
    }
    if let Some(path) = &args.report {
        match study_pictures {
            Some((sweep, runs)) => pictures::study::write_report(sweep, runs, path)?,
            None => pictures::report::write(&scene, &report, path)?,
        }
    }
    let stdout = std::io::stdout();
    let mut out = BufWriter::new(escape::Terminal::new(stdout.lock()));
    let written = table::write_table(&scene, &report, &mut out)
        .and_then(|()| match &study {
            Some(study) => sensitivity::write_summary(study, &mut out),
            None => Ok(()),
        })
        .and_then(|()| write_metrics(&scene, metrics.as_ref(), &mut out));
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
    // A table that goes nowhere is not formatted, nor the metrics after it (their sweep of
    // the transmission angle costs ~200 instructions per slider-crank position).
    let discard_table = stdout_is_null();
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
        discard_table,
        ..stream::Options::default()
    };
    let streamed = stream::run(scene, &mut sinks, &options)?;
    drop(sinks);
    let metrics = metrics_of(scene);
    let written = match discard_table {
        true => Ok(()),
        false => write_metrics(scene, metrics.as_ref(), &mut stdout),
    };
    for warning in &streamed.warnings {
        eprintln!(
            "{}",
            escape::terminal(&format!("warning: {}: {warning}", scene.file))
        );
    }
    for file in [csv, jsonl].into_iter().flatten() {
        file.commit()?;
    }
    match written.and_then(|()| stdout.flush()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        result => result.map_err(|source| Error::Write {
            path: PathBuf::from("<stdout>"),
            source,
        }),
    }
}

/// Whether standard output is `/dev/null` (the same file: device and inode), where a table
/// goes nowhere: `mechdiff run big.toml --csv out.csv > /dev/null` formats no table.
fn stdout_is_null() -> bool {
    #[cfg(unix)]
    {
        use std::os::fd::AsFd;
        use std::os::unix::fs::MetadataExt;
        let stdout = std::io::stdout().as_fd().try_clone_to_owned();
        let (Ok(stdout), Ok(null)) = (stdout, std::fs::metadata("/dev/null")) else {
            return false;
        };
        std::fs::File::from(stdout)
            .metadata()
            .is_ok_and(|m| m.dev() == null.dev() && m.ino() == null.ino())
    }
    #[cfg(not(unix))]
    false
}

/// The scene's linkage metrics; a failure to compute them is a warning, not the run's
/// failure (the run's results are complete without them).
fn metrics_of(scene: &scene::Scene) -> Option<scene::metrics::SceneMetrics> {
    scene::metrics::SceneMetrics::of(scene).unwrap_or_else(|e| {
        let line = format!("warning: {}: no linkage metrics: {e}", scene.file);
        eprintln!("{}", escape::terminal(&line));
        None
    })
}

/// Writes the scene's linkage metrics after its table, a blank line before them.
fn write_metrics(
    scene: &scene::Scene,
    metrics: Option<&scene::metrics::SceneMetrics>,
    out: &mut impl Write,
) -> std::io::Result<()> {
    let Some(metrics) = metrics else {
        return Ok(());
    };
    writeln!(out)?;
    for line in metrics.lines(scene) {
        writeln!(out, "{line}")?;
    }
    Ok(())
}
