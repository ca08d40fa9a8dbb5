//! `mechdiff accuracy <scene.toml | whitworth>`: every derivative method against an
//! extended-precision reference, timed side by side.

use std::path::{Path, PathBuf};

use clap::Args;
use mechdiff::accuracy::{self, Timing, formula, whitworth};
use mechdiff::mechanisms::Whitworth;
use mechdiff::mechanisms::whitworth::Parameters;
use mechdiff::scene::Kind;
use mechdiff::{Error, files};

/// Arguments of `mechdiff accuracy`.
#[derive(Debug, Args)]
pub struct AccuracyArgs {
    /// `whitworth` (the reference machine), a formula scene (see scenes/hard/), a mechanism
    /// scene (scenes/four_bar.toml, a cam-driven one too), a cam scene (scenes/cams/) or a
    /// rotor scene (scenes/rotor_balancing.toml).
    pub subject: String,
    /// For `whitworth`: the crank ratio λ = l1/l0 (l0 kept at 0.4 m), in (0, 1).
    #[arg(long)]
    pub lambda: Option<f64>,
    /// Write the report as CSV to this file instead of printing the table.
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,
    /// Write the SVG plot of error against time (Pareto front labelled) to this file, and
    /// the error against the drive angle per method to the same name ending `-angle.svg`.
    #[arg(long, value_name = "FILE")]
    pub svg: Option<PathBuf>,
    /// Timed repeats per method (the median and spread are over these; at most 1000).
    #[arg(long, default_value_t = 15,
          value_parser = clap::value_parser!(u64).range(0..=accuracy::MAX_REPEATS as u64))]
    pub repeats: u64,
    /// Measure at most this many drive positions of the sweep, evenly spread (every k-th,
    /// the last kept): a quick check of a long sweep.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub positions: Option<u32>,
}

/// Measures and prints (or writes) the report.
pub fn accuracy(args: &AccuracyArgs) -> Result<(), Error> {
    let timing = Timing {
        repeats: args.repeats as usize,
        ..Timing::default()
    };
    let positions = args.positions.map(|n| n as usize);
    let report = if args.subject == "whitworth" {
        let mut parameters = Parameters::reference();
        if let Some(lambda) = args.lambda {
            parameters.l1 = lambda * parameters.l0;
        }
        let shaper = Whitworth::new(parameters).map_err(|e| Error::Reference {
            what: "the Whitworth machine".into(),
            reason: e.to_string(),
        })?;
        let linkage = whitworth::linkage(&shaper)?;
        thin(positions, whitworth::case(&shaper, &linkage)?)?.measure(&timing)?
    } else {
        let path = PathBuf::from(&args.subject);
        let text = files::read_scene(&path)?;
        // Refused before the measurement (cam files a scene names are checked once read).
        files::refuse_inputs(outputs(args).iter().map(PathBuf::as_path))?;
        match mechdiff::scene::kind(&text) {
            Kind::Formula => {
                let scene = formula::parse(&text, &args.subject)?;
                thin(positions, formula::case(&scene, &args.subject)?)?.measure(&timing)?
            }
            Kind::Cam => {
                let scene = mechdiff::scene::cam::parse(&args.subject, &text)?;
                accuracy::cam::case(&scene, positions)?.measure(&timing)?
            }
            Kind::Rotor => {
                let scene = mechdiff::scene::balancing::rotor_scene::load(&path)?;
                return write_rotor(args, &accuracy::rotor::report(&scene)?);
            }
            Kind::Linkage => {
                let mut scene = mechdiff::scene::parse(&args.subject, &text)?;
                let defaulted = accuracy::scene::default_outputs(&mut scene);
                let mechanism = mechdiff::scene::build::mechanism(&scene)?;
                let mut case = accuracy::scene::case_at(&scene, &mechanism, positions)?;
                case.notes.extend(defaulted);
                case.measure(&timing)?
            }
        }
    };
    write(args, &report)
}

/// Writes `text` to `path` whole or not at all, never onto an input.
fn save(path: &Path, text: &str) -> Result<(), Error> {
    files::write_atomically(path, |out| out.write_all(text.as_bytes()))
}

fn write(args: &AccuracyArgs, report: &accuracy::Report) -> Result<(), Error> {
    // Every output checked before the first is written.
    files::refuse_inputs(outputs(args).iter().map(PathBuf::as_path))?;
    if let Some(path) = &args.svg {
        save(path, &accuracy::plot::pareto_svg(report, 900, 600)?)?;
        accuracy::plot::along_sweep(report).write_svg(&angle_path(path))?;
    }
    match &args.csv {
        Some(path) => save(path, &report.csv()),
        None => {
            print!("{}", mechdiff::escape::terminal(&report.table()));
            Ok(())
        }
    }
}

/// A rotor's report: the table, or `--csv`. `--svg` and `--positions` are refused (no
/// sweep to plot or thin).
fn write_rotor(args: &AccuracyArgs, report: &accuracy::rotor::RotorReport) -> Result<(), Error> {
    if args.svg.is_some() || args.positions.is_some() {
        return Err(Error::Reference {
            what: args.subject.clone(),
            reason: "a rotor scene has no drive sweep: --svg (error against time and angle) \
                     and --positions do not apply; its report is the table or --csv"
                .into(),
        });
    }
    match &args.csv {
        Some(path) => save(path, &report.csv()),
        None => {
            print!("{}", mechdiff::escape::terminal(&report.table()));
            Ok(())
        }
    }
}

/// The files `accuracy` writes: `--svg` and its `-angle.svg`, `--csv`.
fn outputs(args: &AccuracyArgs) -> Vec<PathBuf> {
    let svgs = args.svg.iter().flat_map(|p| [p.clone(), angle_path(p)]);
    svgs.chain(args.csv.iter().cloned()).collect()
}

/// `out.svg` → `out-angle.svg`: where the error-against-angle diagram goes.
fn angle_path(path: &std::path::Path) -> PathBuf {
    let stem = path
        .file_stem()
        .map_or_else(|| "accuracy".into(), |s| s.to_string_lossy().into_owned());
    path.with_file_name(format!("{stem}-angle.svg"))
}

/// `case` thinned to `positions` drive positions (`--positions`), or whole.
fn thin(positions: Option<usize>, case: accuracy::Case<'_>) -> Result<accuracy::Case<'_>, Error> {
    match positions {
        Some(n) => case.thinned(n),
        None => Ok(case),
    }
}
