//! Many variants of one scene in one call: the inner loop of a tolerance study or a design
//! grid (`mechdiff.study`), run in Rust without the GIL. Each variant is the scene read with
//! some parameters moved, as `--set` moves them (every formula follows), and run over the
//! scene's sweep; one that fails becomes a row of NaN and a reason, never a lost batch.

use mechdiff::Setting;
use numpy::{PyArray1, PyArray3, PyArrayMethods, PyReadonlyArray2};
use pyo3::prelude::*;

use crate::errors::{argument, kind, to_py};
use crate::scene::Scene;

/// The most variants of one call (the caller splits a larger study into calls, as
/// `mechdiff.study` does into chunks).
pub const MAX_VARIANTS: usize = 10_000_000;

/// The most numbers (variants × positions × columns) one call returns: 400 MB.
pub const MAX_VALUES: usize = 50_000_000;

/// Variants run between two checks for Ctrl-C (a block of the Norton four-bar takes about
/// a millisecond).
const BLOCK: usize = 64;

/// The failures of a batch: `(variant, kind, message)`.
type Failures = Vec<(usize, String, String)>;

/// See `Scene.run_variants`.
pub fn run<'py>(
    py: Python<'py>,
    scene: &Scene,
    names: &[String],
    values: PyReadonlyArray2<'py, f64>,
    columns: Option<Vec<String>>,
) -> PyResult<(Bound<'py, PyArray3<f64>>, Vec<String>, Failures)> {
    let values = values.as_array();
    let (variants, parameters) = values.dim();
    if parameters != names.len() {
        return Err(argument(
            py,
            format!(
                "values has {parameters} columns and names {} parameters; expected one column \
                 per name",
                names.len()
            ),
        ));
    }
    if variants > MAX_VARIANTS {
        return Err(argument(
            py,
            format!(
                "{variants} variants in one call is over the limit of {MAX_VARIANTS}; split the \
                 study into chunks (mechdiff.study does)"
            ),
        ));
    }
    // The nominal run names the columns and counts the rows every variant must have.
    let nominal = py
        .detach(|| mechdiff::run(scene.scene()))
        .map_err(|e| to_py(py, &e))?;
    let picked: Vec<(usize, f64)> = match &columns {
        None => (nominal.columns.iter().enumerate())
            .map(|(k, c)| (k, c.factor))
            .collect(),
        Some(names) => {
            let mut picked = Vec::with_capacity(names.len());
            for name in names {
                let Some(k) = nominal.columns.iter().position(|c| &c.name == name) else {
                    let known: Vec<&str> =
                        nominal.columns.iter().map(|c| c.name.as_str()).collect();
                    return Err(argument(
                        py,
                        format!(
                            "the scene has no column `{name}`; its columns are: {}",
                            known.join(", ")
                        ),
                    ));
                };
                picked.push((k, nominal.columns[k].factor));
            }
            picked
        }
    };
    let rows = nominal.rows.len();
    let per_variant = rows * picked.len();
    if variants.saturating_mul(per_variant) > MAX_VALUES {
        return Err(argument(
            py,
            format!(
                "{variants} variants × {rows} positions × {} columns is over the limit of \
                 {MAX_VALUES} numbers in one call; ask for fewer variants per call (chunks) or \
                 fewer columns",
                picked.len()
            ),
        ));
    }
    let (file, text, own) = scene.source();
    let mut out = vec![f64::NAN; variants * per_variant];
    let mut failures = Failures::new();
    for start in (0..variants).step_by(BLOCK) {
        let end = (start + BLOCK).min(variants);
        let block = &mut out[start * per_variant..end * per_variant];
        let found = py.detach(|| {
            let mut found = Failures::new();
            for (i, slot) in (start..end).zip(block.chunks_mut(per_variant.max(1))) {
                let mut settings: Vec<Setting> = own.to_vec();
                for (name, &value) in names.iter().zip(values.row(i)) {
                    settings.retain(|s| &s.name != name);
                    settings.push(Setting {
                        name: name.clone(),
                        // The shortest text that reads back as the same f64.
                        value: format!("{value:e}"),
                    });
                }
                let run = mechdiff::parse_with(file, text, &settings)
                    .and_then(|variant| mechdiff::run(&variant));
                match run {
                    Ok(report) if report.rows.len() == rows => {
                        for (r, row) in report.rows.iter().enumerate() {
                            for (c, &(k, factor)) in picked.iter().enumerate() {
                                slot[r * picked.len() + c] = row[k] / factor;
                            }
                        }
                    }
                    Ok(report) => found.push((
                        i,
                        "Rows".to_owned(),
                        format!(
                            "{file}: the variant has {} drive positions and the nominal \
                             scene {rows}; a study compares runs position by position",
                            report.rows.len()
                        ),
                    )),
                    Err(e) => found.push((i, kind(&e), e.to_string())),
                }
            }
            found
        });
        failures.extend(found);
        py.check_signals()?;
    }
    let array = PyArray1::from_vec(py, out).reshape([variants, rows, picked.len()])?;
    let names = (picked.iter())
        .map(|&(k, _)| nominal.columns[k].name.clone())
        .collect();
    Ok((array, names, failures))
}
