//! `mechdiff run` of a scene with `[simulate]`: the machine moving under its motor. The
//! plan (the equation's terms), the table over time and the steady state's table over the
//! drive angle stream to the terminal and to `--csv FILE` (over time) and `FILE_steady.csv`
//! (over the angle) as they are computed; `--plot DIR` draws ω(t), the motor's torque and
//! ω(φ); `--report FILE.html` plays the motion on the simulated clock beside them.

use std::io::{BufWriter, Write};
use std::path::PathBuf;

use mechdiff::scene::Scene;
use mechdiff::stream::Sink;
use mechdiff::stream::motion::{MotionSinks, steady_path};
use mechdiff::{Error, escape, files, pictures};

use super::run::RunArgs;

/// Runs the `[simulate]` of `scene` with the options `args` (refusing those that do not
/// apply).
pub fn run(args: &RunArgs, scene: &Scene) -> Result<(), Error> {
    let refused = [
        ("--sweep", args.sweep.is_some()),
        ("--json", args.json.is_some()),
        ("--jsonl", args.jsonl.is_some()),
        ("--monte-carlo", args.monte_carlo.is_some()),
        (
            "--evaluator",
            args.evaluator != mechdiff::evaluator::Evaluator::Auto,
        ),
    ];
    if let Some((option, _)) = refused.iter().find(|(_, given)| *given) {
        return Err(Error::OptionNotApplicable {
            option: (*option).to_owned(),
            scene: args.scene.clone(),
            why: "a scene with `[simulate]` runs its machine under the motor: it prints the \
                  tables over time and over the drive angle, writes them with --csv (FILE and \
                  FILE_steady), draws them with --plot and plays the motion with --report"
                .to_owned(),
        });
    }
    let steady = args.csv.as_deref().map(steady_path);
    files::refuse_inputs(args.csv.iter().chain(&steady).map(PathBuf::as_path))?;
    let mut time_csv = args
        .csv
        .as_deref()
        .map(files::AtomicFile::create)
        .transpose()?;
    let mut steady_csv = steady
        .as_deref()
        .map(files::AtomicFile::create)
        .transpose()?;
    let mut stdout = BufWriter::with_capacity(1 << 16, escape::Terminal::new(std::io::stdout()));
    fn sink(file: &mut files::AtomicFile) -> Sink<'_> {
        let path = file.path().to_owned();
        Sink {
            path,
            out: file.writer(),
        }
    }
    let mut sinks = MotionSinks {
        table: Some(Sink {
            path: PathBuf::from("<stdout>"),
            out: &mut stdout,
        }),
        time_csv: time_csv.as_mut().map(sink),
        steady_csv: steady_csv.as_mut().map(sink),
    };
    let options = mechdiff::scene::motion::MotionOptions {
        playback: args.report.is_some(),
        ..Default::default()
    };
    let report = mechdiff::scene::motion::run_with(scene, &mut sinks, &options)?;
    drop(sinks);
    if let Some(file) = time_csv {
        file.commit()?;
    }
    if let Some(file) = steady_csv
        && report.steady_rows > 0
    {
        file.commit()?;
    }
    if let Some(dir) = &args.plot {
        let title = scene.title.as_deref().unwrap_or("the machine in motion");
        pictures::motion::write_dir(title, &report, dir)?;
    }
    if let Some(path) = &args.report {
        pictures::report::motion::write(scene, &report, path)?;
    }
    match stdout.flush() {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        result => result.map_err(|source| Error::Write {
            path: PathBuf::from("<stdout>"),
            source,
        }),
    }
}
