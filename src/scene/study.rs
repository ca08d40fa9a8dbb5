//! Parameter studies: the same scene run over several values of one of its `[parameters]`
//! (`mechdiff run scene.toml --sweep l1=0.15:0.17:5`), as one long table with the
//! parameter as its first column.
//!
//! Each value is applied as a `--set` would apply it (after the other settings), so every
//! formula that uses the parameter follows it; the scene is read, checked and run anew for
//! each value, and an error names the value it happened at.

use std::str::FromStr;

use crate::error::{Error, Result};

use super::model::Scene;
use super::outputs::Column;
use super::parameters::Setting;
use super::run::Report;

/// The most values a parameter sweep may have (each is a whole run of the scene).
pub const MAX_VALUES: usize = 10_000;

/// `--sweep NAME=FROM:TO:COUNT` (COUNT evenly spaced values, both ends included, in either
/// direction) or `--sweep NAME=V1,V2,...` (a list): the values of one parameter, in the
/// parameter's unit.
#[derive(Debug, Clone, PartialEq)]
pub struct ParameterSweep {
    /// The parameter.
    pub name: String,
    /// Its values, in order.
    pub values: Vec<f64>,
}

impl FromStr for ParameterSweep {
    type Err = String;

    fn from_str(text: &str) -> std::result::Result<Self, String> {
        let usage = "write `NAME=FROM:TO:COUNT` (e.g. `l1=0.15:0.17:5`, both ends included) \
                     or `NAME=V1,V2,...` (e.g. `l1=0.15,0.16,0.17`)";
        let Some((name, values)) = text.split_once('=') else {
            return Err(format!("`{text}` is not a parameter sweep; {usage}"));
        };
        let (name, values) = (name.trim(), values.trim());
        if name.is_empty() || values.is_empty() {
            return Err(format!("`{text}` is not a parameter sweep; {usage}"));
        }
        let number = |v: &str| {
            v.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    format!("`{}` in `{text}` is not a finite number; {usage}", v.trim())
                })
        };
        let values = match values.split(':').collect::<Vec<_>>()[..] {
            [from, to, count] => {
                let (from, to) = (number(from)?, number(to)?);
                let count: usize = count.trim().parse().map_err(|_| {
                    format!(
                        "`{}` in `{text}` is not a count of values (a whole number ≥ 2); {usage}",
                        count.trim()
                    )
                })?;
                if !(2..=MAX_VALUES).contains(&count) {
                    return Err(format!(
                        "`{text}` asks for {count} values; a range gives 2 to {MAX_VALUES} \
                         values (a single value is `--set {name}=V`)"
                    ));
                }
                let last = (count - 1) as f64;
                // The ends exactly as written; between them, from + (to - from)·i/(n-1).
                (0..count)
                    .map(|i| match i {
                        0 => from,
                        i if i == count - 1 => to,
                        i => from + (to - from) * (i as f64 / last),
                    })
                    .collect()
            }
            [list] => {
                let values = list
                    .split(',')
                    .map(number)
                    .collect::<std::result::Result<Vec<_>, _>>()?;
                if values.len() > MAX_VALUES {
                    return Err(format!(
                        "`--sweep {name}` has more than {MAX_VALUES} values"
                    ));
                }
                values
            }
            _ => return Err(format!("`{text}` is not a parameter sweep; {usage}")),
        };
        Ok(ParameterSweep {
            name: name.to_owned(),
            values,
        })
    }
}

/// One run of a parameter study: the value, the scene read with it, and its report.
#[derive(Debug, Clone)]
pub struct StudyRun {
    /// The parameter's value (as set).
    pub value: f64,
    /// The scene read with that value.
    pub scene: Scene,
    /// Its run.
    pub report: Report,
}

/// Runs the scene `text` (named `file` in messages) once per value of `sweep`, with
/// `settings` applied first, and joins the reports into one: the parameter's column first
/// (unit `as set`: the value as given on the command line), then the columns of a run,
/// with the rows of every value one after the other. Dead positions and dynamics summaries
/// are kept per value, their names followed by `(NAME = V)`.
///
/// Returns the scene read with the first value (for its title, plan and units) and the
/// joined report.
///
/// # Errors
/// The first error of a run, prefixed with the value it happened at
/// ([`Error::AtParameter`]); a sweep of a parameter the scene does not have, or that is
/// also `--set` ([`Error::Setting`]).
pub fn run_sweep(
    file: &str,
    text: &str,
    settings: &[Setting],
    sweep: &ParameterSweep,
) -> Result<(Scene, Report)> {
    join(sweep, run_each(file, text, settings, sweep)?)
}

/// Runs the scene `text` once per value of `sweep` (see [`run_sweep`]), each run kept on
/// its own: what the pictures of a study draw (one curve per value).
///
/// # Errors
/// As [`run_sweep`].
pub fn run_each(
    file: &str,
    text: &str,
    settings: &[Setting],
    sweep: &ParameterSweep,
) -> Result<Vec<StudyRun>> {
    if settings.iter().any(|s| s.name == sweep.name) {
        return Err(Error::Setting {
            option: "--sweep",
            setting: format!("{}=…", sweep.name),
            message: format!(
                "`{}` is both set and swept; drop the `--set` or the `--sweep`",
                sweep.name
            ),
        });
    }
    let mut runs = Vec::with_capacity(sweep.values.len());
    for &value in &sweep.values {
        let mut with = settings.to_vec();
        with.push(Setting {
            name: sweep.name.clone(),
            value: value.to_string(),
        });
        let at = |source: Error| match source {
            // The swept parameter is not in the scene: the same error for every value, named
            // by the option that asked for it.
            Error::Setting {
                setting, message, ..
            } if setting.starts_with(&format!("{}=", sweep.name)) => Error::Setting {
                option: "--sweep",
                setting: sweep.name.clone(),
                message,
            },
            // A `--set` the scene does not have.
            e @ Error::Setting { .. } => e,
            e => Error::AtParameter {
                setting: format!("{}={value}", sweep.name),
                source: Box::new(e),
            },
        };
        let scene = super::parse_with(file, text, &with).map_err(at)?;
        let report = super::run(&scene).map_err(at)?;
        runs.push(StudyRun {
            value,
            scene,
            report,
        });
    }
    Ok(runs)
}

/// The runs of a study joined into one report (see [`run_sweep`]), with the scene of the
/// first value.
///
/// # Errors
/// [`Error::Setting`] when there is no run.
pub fn join(sweep: &ParameterSweep, runs: Vec<StudyRun>) -> Result<(Scene, Report)> {
    let mut joined: Option<(Scene, Report)> = None;
    for StudyRun {
        value,
        scene,
        mut report,
    } in runs
    {
        let tag = format!(" ({} = {value})", sweep.name);
        for row in &mut report.rows {
            row.insert(0, value);
        }
        for dead in &mut report.dead_positions {
            dead.output.push_str(&tag);
        }
        for limit in &mut report.limits {
            limit.tag.push_str(&tag);
        }
        if let Some(dynamics) = &mut report.dynamics {
            for line in &mut dynamics.summary {
                line.push_str(&tag);
            }
        }
        match &mut joined {
            None => {
                report.columns.insert(
                    0,
                    Column {
                        name: sweep.name.clone(),
                        unit: "as set".to_owned(),
                        factor: 1.0,
                    },
                );
                joined = Some((scene, report));
            }
            Some((_, all)) => {
                all.rows.append(&mut report.rows);
                all.dead_positions.append(&mut report.dead_positions);
                all.limits.append(&mut report.limits);
                if let (Some(all), Some(more)) = (&mut all.dynamics, report.dynamics) {
                    all.summary.extend(more.summary);
                }
            }
        }
    }
    // `ParameterSweep` always holds at least one value (a list of one or a range of two).
    joined.ok_or_else(|| Error::Setting {
        option: "--sweep",
        setting: format!("{}=", sweep.name),
        message: "the sweep has no values".to_owned(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_range_includes_both_ends_in_either_direction() {
        let s: ParameterSweep = "l1=0.15:0.17:5".parse().unwrap();
        assert_eq!(s.name, "l1");
        assert_eq!(s.values.len(), 5);
        // The ends exactly as written; the middle 0.15 + 0.02·2/4 to one rounding each.
        assert_eq!((s.values[0], s.values[4]), (0.15, 0.17));
        assert!((s.values[2] - 0.16).abs() < 1e-16);
        let down: ParameterSweep = "l1 = 2:1:3".parse().unwrap();
        // 2 + (1 - 2)·0.5 = 1.5 exactly.
        assert_eq!(down.values, [2.0, 1.5, 1.0]);
        let list: ParameterSweep = "m=1,2.5,-3".parse().unwrap();
        assert_eq!(list.values, [1.0, 2.5, -3.0]);
    }

    #[test]
    fn malformed_sweeps_say_how_to_write_one() {
        for bad in [
            "l1",
            "l1=",
            "=1,2",
            "l1=1:2",
            "l1=1:2:x",
            "l1=a,b",
            "l1=1:2:1",
            "l1=1:2:3:4",
        ] {
            let e = bad.parse::<ParameterSweep>().unwrap_err();
            assert!(
                e.contains("NAME=FROM:TO:COUNT") || e.contains("2 to"),
                "{bad}: {e}"
            );
        }
        let e = "l1=1:inf:3".parse::<ParameterSweep>().unwrap_err();
        assert!(
            e.contains("`inf` in `l1=1:inf:3` is not a finite number"),
            "{e}"
        );
    }
}
