//! The `mechdiff` command-line tool.

mod cli;

use clap::{Parser, Subcommand};
use mechdiff::escape;
use std::process::ExitCode;

/// mechdiff: kinematics and dynamics of planar mechanisms with exact, automatic derivatives.
///
/// Without a command, prints the Whitworth shaping machine report: accelerations of the centres
/// of gravity and inertial forces at φ = 0°, 180° and at both dead positions (found
/// numerically), then the dead positions and the ram's stroke.
#[derive(Debug, Parser)]
#[command(name = "mechdiff", version, about, long_about)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// Let a scene name files (`[drive] cam`) under DIR too, besides its own folder
    /// (repeatable; links and `..` are resolved before the check).
    #[arg(long = "allow-path", value_name = "DIR", global = true)]
    allow_path: Vec<std::path::PathBuf>,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// The Whitworth shaping machine report (the default command).
    Whitworth,
    /// Run a scene file: print the plan and a table of the outputs (optionally write CSV).
    Run(cli::run::RunArgs),
    /// Check a scene file (syntax, names, units, sketch, mobility) without running it.
    Check(cli::check::CheckArgs),
    /// Every derivative method against an extended-precision reference: error per order and
    /// time per drive position, side by side (`whitworth` or any scene file: mechanism, formula,
    /// cam or rotor).
    Accuracy(cli::accuracy::AccuracyArgs),
    /// Convert a Pyslvs expression or a PMKS text file into a scene (printed, or --out FILE).
    Import(cli::import::ImportArgs),
    /// Size a scene's parameters from what it must do (its `[synthesize]` section: path,
    /// function or motion generation), by least squares with the exact Jacobian.
    Synthesize(cli::synthesize::SynthesizeArgs),
    /// Generate Rust code: a formula's function and its derivatives, or a scene's whole pose
    /// (symbolic, with CSE)
    Codegen(mechdiff::codegen::Args),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    // Ctrl-C or SIGTERM: the temporary files being written are removed before the exit.
    if let Err(error) = mechdiff::files::remove_temporaries_on_signal() {
        eprintln!("warning: temporary files will not be removed on Ctrl-C: {error}");
    }
    for dir in &cli.allow_path {
        if let Err(error) = mechdiff::files::allow_folder(dir) {
            eprintln!(
                "error: --allow-path: {}",
                escape::terminal(&error.to_string())
            );
            return ExitCode::FAILURE;
        }
    }
    let result: Result<(), Box<dyn std::error::Error>> = match cli.command {
        None | Some(Command::Whitworth) => whitworth(),
        Some(Command::Run(args)) => cli::run::run(&args).map_err(Into::into),
        Some(Command::Check(args)) => cli::check::check(&args).map_err(Into::into),
        Some(Command::Accuracy(args)) => cli::accuracy::accuracy(&args).map_err(Into::into),
        Some(Command::Import(args)) => cli::import::import(&args).map_err(Into::into),
        Some(Command::Synthesize(args)) => cli::synthesize::synthesize(&args).map_err(Into::into),
        Some(Command::Codegen(args)) => mechdiff::codegen::run(&args).map_err(Into::into),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {}", escape::terminal(&error.to_string()));
            ExitCode::FAILURE
        }
    }
}

/// Prints the report for the reference Whitworth shaping machine.
fn whitworth() -> Result<(), Box<dyn std::error::Error>> {
    let shaper = mechdiff::mechanisms::Whitworth::reference();
    print!("{}", mechdiff::report::whitworth::report(&shaper)?);
    Ok(())
}
