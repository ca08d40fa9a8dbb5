//! The options of `mechdiff run`, which the runs of cam, rotor and formula scenes read too.

use std::path::PathBuf;

use clap::Args;
use mechdiff::evaluator::Evaluator;
use mechdiff::{scene, sensitivity, stream};

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
    /// the same values bit for bit), or `auto`: the default (the solver, or the program
    /// compiled where a cost model of set-up and rows says it pays: a long sweep of closed
    /// forms). Results agree to 1e-13; errors are the solver's. The plan line says which
    /// path evaluates each loop.
    #[arg(long, value_enum, value_name = "HOW", default_value_t = Evaluator::Auto)]
    pub evaluator: Evaluator,
}
