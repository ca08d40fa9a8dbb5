//! The `run`, `check` and `import` subcommands of the `mechdiff` tool (scene files).

pub mod accuracy;
pub mod cam;
pub mod check;
pub mod formula;
pub mod import;
pub mod motion;
pub mod rotor;
pub mod run;
pub mod synthesize;

use std::path::Path;

use mechdiff::{Error, scene};

/// Refuses the options a scene of this kind cannot honour, instead of ignoring them:
/// `given` pairs each option with whether it was given. Cam and rotor scenes have no
/// `[parameters]` (`--set`, `--sweep`) nor a drive-position table (`--jsonl`; their `--json`
/// is their summary, their `--report` their own page); only cam scenes have a profile
/// (`--profile-csv`).
///
/// # Errors
/// [`Error::OptionNotApplicable`] naming the first such option and the scene.
pub fn refuse_options(
    kind: scene::Kind,
    given: &[(&'static str, bool)],
    path: &Path,
) -> Result<(), Error> {
    let (refused, why): (&[&str], &str) = match kind {
        scene::Kind::Linkage => (
            &["--profile-csv"],
            "only cam scenes have a profile; a linkage writes --csv, --jsonl, --json, --plot \
             and --report",
        ),
        scene::Kind::Cam => (
            &[
                "--set",
                "--sweep",
                "--jsonl",
                "--monte-carlo",
                "--evaluator",
            ],
            "a cam scene has no `[parameters]` and no linkage to evaluate, and writes its SVAJ \
             table with --csv, its profile with --profile-csv, its summary with --json, its \
             pictures with --plot and its animated report with --report",
        ),
        scene::Kind::Formula => (
            &[
                "--set",
                "--sweep",
                "--json",
                "--jsonl",
                "--plot",
                "--report",
                "--profile-csv",
                "--monte-carlo",
                "--evaluator",
            ],
            "a formula scene (an `[outputs]` table of formulas) prints its table and writes \
             --csv; `mechdiff accuracy` measures it",
        ),
        scene::Kind::Rotor => (
            &[
                "--set",
                "--sweep",
                "--jsonl",
                "--profile-csv",
                "--monte-carlo",
                "--evaluator",
            ],
            "a rotor scene has no `[parameters]` and no drive positions to tabulate; use --csv \
             or --json for its answers, --plot for its polygons and --report for its page",
        ),
    };
    match given
        .iter()
        .find(|(option, is_given)| *is_given && refused.contains(option))
    {
        Some((option, _)) => Err(Error::OptionNotApplicable {
            option: (*option).to_owned(),
            scene: path.to_path_buf(),
            why: why.to_owned(),
        }),
        None => Ok(()),
    }
}
