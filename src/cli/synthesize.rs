//! `mechdiff synthesize scene.toml`: the scene's parameters sized by its `[synthesize]`
//! section; prints the answer, writes the scene found (`--out`) and its pictures (`--plot`).

use std::io::Write;
use std::path::PathBuf;
use std::time::Duration;

use clap::{Args, ValueEnum};
use mechdiff::scene::synthesize::{self, Method, Setup};
use mechdiff::{Error, files};
use mechdiff_core::synthesis::{MAX_ROUNDS, MAX_STARTS, Report, Synthesis};

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
    /// Rounds of sampling: each samples `starts` fresh points and polishes the best, while
    /// the objective is not reached and the limits allow (replaces the section's `rounds`).
    #[arg(long)]
    pub rounds: Option<usize>,
    /// Give each sample the timing that suits it before ranking (replaces the section's
    /// `fit_timing`).
    #[arg(long)]
    pub fit_timing: bool,
    /// How to search (replaces the section's `method`): `lm` (Levenberg–Marquardt, exact
    /// Jacobian), `differences` (central-difference Jacobian) or `evolution` (differential
    /// evolution alone).
    #[arg(long, value_enum, conflicts_with_all = ["exact", "differences"])]
    pub method: Option<MethodArg>,
    /// Exact Jacobian by dual numbers (the default; `--method lm`).
    #[arg(long, conflicts_with = "differences")]
    pub exact: bool,
    /// Central-difference Jacobian instead of the exact one (`--method differences`).
    #[arg(long)]
    pub differences: bool,
    /// Worker threads evaluating the samples and polishing the local searches (0:
    /// `RAYON_NUM_THREADS`, else one per core). The answer is the same, digit for digit, for
    /// any number; at most 1024. Differential evolution runs on one thread.
    #[arg(long, value_name = "N", default_value_t = 0,
          value_parser = clap::value_parser!(u64).range(0..=mechdiff::stream::MAX_THREADS as u64))]
    pub threads: u64,
    /// Run the search by each method (exact Jacobian, central differences, differential
    /// evolution) with the same seed, starts and limits, and print them side by side
    /// (objective, evaluations, local searches, time); the answer shown is the method's
    /// asked for.
    #[arg(long)]
    pub compare: bool,
}

/// `--method`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum MethodArg {
    /// Levenberg–Marquardt with the exact Jacobian (dual numbers).
    Lm,
    /// Levenberg–Marquardt with central-difference Jacobians.
    Differences,
    /// Differential evolution alone, no derivatives.
    Evolution,
}

impl From<MethodArg> for Method {
    fn from(m: MethodArg) -> Method {
        match m {
            MethodArg::Lm => Method::Exact,
            MethodArg::Differences => Method::Differences,
            MethodArg::Evolution => Method::Evolution,
        }
    }
}

/// Reads the section, runs the search, prints and writes what was asked.
pub fn synthesize(args: &SynthesizeArgs) -> Result<(), Error> {
    let text = files::read_scene(&args.scene)?;
    let setup = synthesize::read(&args.scene.display().to_string(), &text)?;
    let settings = settings(&setup, args)?;
    let method = match (args.method, args.exact, args.differences) {
        (Some(m), _, _) => m.into(),
        (None, true, _) => Method::Exact,
        (None, _, true) => Method::Differences,
        (None, false, false) => setup.method,
    };
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
    let threads = args.threads as usize;
    let report = setup.solve_threaded(&settings, method, threads)?;
    let mut printed = synthesize::summary(&setup, &settings, &report, method);
    if args.compare {
        let mut rows = Vec::new();
        for (_, other) in Method::NAMES {
            if other == method {
                rows.push((other, report.clone()));
            } else {
                rows.push((other, setup.solve_threaded(&settings, other, threads)?));
            }
        }
        printed.push_str(&compare(&rows, settings.stop_objective));
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
    if let Some(rounds) = args.rounds {
        if rounds == 0 || rounds > MAX_ROUNDS {
            return Err(Error::Setting {
                option: "--rounds",
                setting: rounds.to_string(),
                message: format!("give from 1 to {MAX_ROUNDS} rounds of sampling"),
            });
        }
        s.rounds = rounds;
    }
    if args.fit_timing {
        s.fit_timing = true;
    }
    Ok(s)
}

/// The searches side by side.
fn compare(rows: &[(Method, Report)], stop_objective: f64) -> String {
    let mut out = format!(
        "\nthe same search by each method (same seed, starts and limits; success: objective \
         ≤ {stop_objective:e}):\n  {:<34} {:>12} {:>12} {:>8} {:>10}\n",
        "method", "objective", "evaluations", "searches", "time (s)"
    );
    for (method, r) in rows {
        out.push_str(&format!(
            "  {:<34} {:>12.3e} {:>12} {:>8} {:>10.3}\n",
            method.describe(),
            r.objective,
            r.evaluations,
            r.local_searches,
            r.elapsed.as_secs_f64()
        ));
    }
    out
}
