//! `mechdiff synthesize scene.toml`: the scene's parameters sized by its `[synthesize]`
//! section; prints the answer, writes the scene found (`--out`) and its pictures (`--plot`).

use std::io::Write;
use std::path::PathBuf;
use std::time::Duration;

use clap::Args;
use mechdiff::scene::synthesize::{self, Setup};
use mechdiff::{Error, files};
use mechdiff_core::synthesis::{Derivatives, MAX_STARTS, Report, Synthesis};

/// Arguments of `mechdiff synthesize`.
#[derive(Debug, Args)]
pub struct SynthesizeArgs {
    /// The scene file, with `[parameters]` and a `[synthesize]` section.
    pub scene: PathBuf,
    /// Write the scene with the parameters found to FILE (whole or not at all); `mechdiff
    /// run` runs it as is.
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Replace `--out` if it exists (never an input of the run).
    #[arg(long)]
    pub force: bool,
    /// Draw the targets and what the answer does (path, function or poses) into DIR.
    #[arg(long, value_name = "DIR")]
    pub plot: Option<PathBuf>,
    /// The seed of the starts (replaces the section's `seed`).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Wall-clock limit in seconds (replaces the section's `time_limit`).
    #[arg(long, value_name = "SECONDS")]
    pub time_limit: Option<f64>,
    /// Samples of the bounds (replaces the section's `starts`).
    #[arg(long)]
    pub starts: Option<usize>,
    /// Exact Jacobian by dual numbers (the default).
    #[arg(long, conflicts_with = "differences")]
    pub exact: bool,
    /// Central-difference Jacobian instead of the exact one (the baseline).
    #[arg(long)]
    pub differences: bool,
    /// Run the search with the exact and with the central-difference Jacobian, and print
    /// both side by side (evaluations, time, objective).
    #[arg(long, conflicts_with_all = ["exact", "differences"])]
    pub compare: bool,
}

/// Reads the section, runs the search, prints and writes what was asked.
pub fn synthesize(args: &SynthesizeArgs) -> Result<(), Error> {
    let text = files::read_scene(&args.scene)?;
    let setup = synthesize::read(&args.scene.display().to_string(), &text)?;
    let settings = settings(&setup, args)?;
    let outputs: Vec<&std::path::Path> = args
        .out
        .iter()
        .chain(&args.plot)
        .map(|p| p.as_path())
        .collect();
    files::refuse_inputs(outputs)?;
    if let Some(out) = &args.out
        && !args.force
        && out.exists()
    {
        return Err(Error::Write {
            path: out.clone(),
            source: std::io::Error::new(
                std::io::ErrorKind::AlreadyExists,
                "the file exists; give --force to replace it",
            ),
        });
    }
    let report = setup.solve(&settings)?;
    let mut printed = synthesize::summary(&setup, &settings, &report);
    if args.compare {
        let differences = Synthesis {
            derivatives: Derivatives::CentralDifferences,
            ..settings.clone()
        };
        let other = setup.solve(&differences)?;
        printed.push_str(&compare(&report, &other));
    }
    let found = setup.found_scene(&report);
    printed.push_str(&scene_check(&setup, &report, &found));
    if let Some(out) = &args.out {
        // The scene found must read back as a scene `mechdiff run` accepts.
        mechdiff::scene::parse(&out.display().to_string(), &found)?;
        files::write_atomically(out, |w| w.write_all(found.as_bytes()))?;
        printed.push_str(&format!("wrote {}\n", out.display()));
    }
    if let Some(dir) = &args.plot {
        let written = mechdiff::pictures::synthesis::write(&setup, &report, dir)?;
        for path in written {
            printed.push_str(&format!("wrote {}\n", path.display()));
        }
    }
    std::io::stdout()
        .write_all(mechdiff::escape::terminal(&printed).as_bytes())
        .map_err(|source| Error::Write {
            path: PathBuf::from("<stdout>"),
            source,
        })
}

/// What the scene's own solver says of the scene found.
fn scene_check(setup: &Setup, report: &Report, found: &str) -> String {
    let length = mechdiff::scene::units::Dimension::Length;
    let unit = setup.units.symbol(length);
    match setup.check_scene(report, found) {
        Ok(c) if c.compared.is_empty() => format!(
            "warning: the scene has none of the points {} on a moving link, so it cannot be \
             compared with the linkage sized\n",
            setup.problem.linkage().point_names().join(", ")
        ),
        Ok(c) if c.deviation <= setup.scene_tolerance() => format!(
            "the scene with these parameters, moved through the targets by its own solver, \
             places {} within {:.3e} {unit} of the linkage sized\n",
            c.compared.join(", "),
            setup.units.from_si(c.deviation, length)
        ),
        Ok(c) => format!(
            "warning: the scene does not draw the linkage sized: its points {} lie up to \
             {:.6e} {unit} from the engine's; build them from the parameters as \
             docs/scene-format.md shows (the dyad's side = `branch`, the coupler point's side \
             = the sign of py)\n",
            c.compared.join(", "),
            setup.units.from_si(c.deviation, length)
        ),
        Err(e) => format!(
            "warning: the scene with these parameters cannot be moved through the targets \
             by its own solver: {e}\n"
        ),
    }
}

/// The section's settings with the command line's changes, checked.
fn settings(setup: &Setup, args: &SynthesizeArgs) -> Result<Synthesis, Error> {
    let mut s = setup.settings.clone();
    if let Some(seed) = args.seed {
        s.seed = seed;
    }
    if let Some(t) = args.time_limit {
        let t = synthesize::check_time_limit(t).map_err(|message| Error::Setting {
            option: "--time-limit",
            setting: t.to_string(),
            message,
        })?;
        s.time_limit = Some(Duration::from_secs_f64(t));
    }
    if let Some(starts) = args.starts {
        if starts == 0 || starts > MAX_STARTS {
            return Err(Error::Setting {
                option: "--starts",
                setting: starts.to_string(),
                message: format!("give from 1 to {MAX_STARTS} samples of the bounds"),
            });
        }
        s.starts = starts;
        s.local_searches = s.local_searches.min(starts);
    }
    if args.differences {
        s.derivatives = Derivatives::CentralDifferences;
    }
    Ok(s)
}

/// The two searches side by side.
fn compare(exact: &Report, differences: &Report) -> String {
    let row = |name: &str, r: &Report| {
        format!(
            "  {name:<20} {:>12.3e} {:>12} {:>8} {:>10.3}\n",
            r.objective,
            r.evaluations,
            r.local_searches,
            r.elapsed.as_secs_f64()
        )
    };
    format!(
        "\nexact against differences (same seed, same starts):\n  {:<20} {:>12} {:>12} {:>8} \
         {:>10}\n{}{}",
        "Jacobian",
        "objective",
        "evaluations",
        "searches",
        "time (s)",
        row("exact (dual numbers)", exact),
        row("central differences", differences)
    )
}
