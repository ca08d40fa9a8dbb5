//! `[sensitivity]` and `[tolerances]` as written, read in a pass of their own (the scene's
//! reader skips them), and checked against the scene's parameters and the table's columns:
//! every error names `file:line:column` and what to write instead.

use std::collections::BTreeMap;

use serde::Deserialize;
use toml::Spanned;

use crate::error::{Error, Result};
use crate::scene::Source;
use crate::scene::bindings::Bindings;
use crate::scene::outputs::Column;
use crate::scene::values::Number;

/// The two sections; the rest of the file is skipped.
#[derive(Deserialize)]
struct StudyOnly {
    sensitivity: Option<Spanned<SensitivityDef>>,
    tolerances: Option<Spanned<TolerancesDef>>,
}

/// `[sensitivity]`: `columns = ["d(psi)/d(a)", …]`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SensitivityDef {
    columns: Spanned<Vec<Spanned<String>>>,
}

/// The largest tolerance (± half-width, in the parameter's unit): the largest bound of the
/// scene's numbers ([`crate::scene::limits`]), so that a worst case (sum of |∂y/∂p|·t) stays
/// finite; a worst case that still overflows is refused when it is computed.
pub const MAX_TOLERANCE: f64 = 1e12;

/// `[tolerances]`: the columns to study and `parameters = { a = 0.0005, … }`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TolerancesDef {
    columns: Spanned<Vec<Spanned<String>>>,
    parameters: Spanned<BTreeMap<Spanned<String>, Spanned<Number>>>,
}

/// A parameter the study differentiates by.
#[derive(Debug, Clone, PartialEq)]
pub struct Parameter {
    /// Its name in `[parameters]`.
    pub name: String,
    /// Its value in its own unit (the unit a `--set` value is in).
    pub value: f64,
    /// Its ± tolerance (half-width) in the same unit, if `[tolerances]` gives one.
    pub tolerance: Option<f64>,
}

/// What a scene asks of the study, checked.
#[derive(Debug, Clone, PartialEq)]
pub struct Spec {
    /// The parameters to differentiate by, in the order first named.
    pub parameters: Vec<Parameter>,
    /// Derivative columns: (index of the column in the table, index into `parameters`).
    pub derivatives: Vec<(usize, usize)>,
    /// The columns of the tolerance study (indices in the table); empty without
    /// `[tolerances]`.
    pub studied: Vec<usize>,
}

impl Spec {
    /// Whether the scene has a `[tolerances]` section.
    pub fn has_tolerances(&self) -> bool {
        !self.studied.is_empty()
    }

    /// One line saying what the study computes, with the table's `columns` (as
    /// `mechdiff check` prints it).
    pub fn describe(&self, columns: &[Column]) -> String {
        let derivatives: Vec<String> = (self.derivatives.iter())
            .map(|&(k, p)| format!("d({})/d({})", columns[k].name, self.parameters[p].name))
            .collect();
        let mut line = if derivatives.is_empty() {
            "study: no derivative columns".to_owned()
        } else {
            format!("study: derivative columns {}", derivatives.join(", "))
        };
        if self.has_tolerances() {
            let tolerances: Vec<String> = (self.parameters.iter())
                .filter_map(|p| Some(format!("{} ± {}", p.name, p.tolerance?)))
                .collect();
            let studied: Vec<&str> = (self.studied.iter())
                .map(|&k| columns[k].name.as_str())
                .collect();
            line.push_str(&format!(
                "; tolerance study of {} with {}",
                studied.join(", "),
                tolerances.join(", ")
            ));
        }
        line
    }
}

/// Splits `d(COLUMN)/d(PARAMETER)` into its column and parameter.
pub fn split_derivative(text: &str) -> Option<(&str, &str)> {
    let inner = text.trim().strip_prefix("d(")?.strip_suffix(')')?;
    let (column, parameter) = inner.rsplit_once(")/d(")?;
    let (column, parameter) = (column.trim(), parameter.trim());
    (!column.is_empty() && !parameter.is_empty()).then_some((column, parameter))
}

/// Reads and checks `[sensitivity]` and `[tolerances]` of `text`. `parameters` are the
/// scene's `(name, value in the file's unit, value in its own unit)`, `columns` the table's.
/// `None` when the file has neither section.
///
/// # Errors
/// A malformed section (TOML error at its place); a derivative column not written
/// `d(COLUMN)/d(PARAMETER)`, or naming a column the table does not have or a parameter the
/// scene does not have; a tolerance on a name that is not a parameter; a tolerance that is
/// negative, zero or not finite; a studied column the table does not have.
pub fn read(
    source: &Source,
    text: &str,
    parameters: &[(String, f64, f64)],
    columns: &[Column],
) -> Result<Option<Spec>> {
    let bindings = Bindings::new(parameters.iter().map(|(n, v, _)| (n.clone(), *v)).collect());
    let only: StudyOnly = toml::from_str(text).map_err(|e| source.syntax_error(&e))?;
    if only.sensitivity.is_none() && only.tolerances.is_none() {
        return Ok(None);
    }
    let invalid = |span: std::ops::Range<usize>, message: String| Error::Invalid {
        location: source.location(span),
        message,
    };
    let known_parameters = || {
        if parameters.is_empty() {
            "the scene has no `[parameters]`; add the value there and use its name where the \
             number was"
                .to_owned()
        } else {
            let mut names: Vec<&str> = parameters.iter().map(|(n, _, _)| n.as_str()).collect();
            names.sort_unstable();
            format!("its parameters are: {}", names.join(", "))
        }
    };
    let known_columns = || {
        let names: Vec<&str> = columns.iter().map(|c| c.name.as_str()).collect();
        format!("the table's columns are: {}", names.join(", "))
    };
    let column_index = |name: &Spanned<String>, shown: &str, what: &str| {
        columns
            .iter()
            .position(|c| c.name == *name.get_ref().trim() || c.name == shown)
            .ok_or_else(|| {
                invalid(
                    name.span(),
                    format!(
                        "{what}: the table has no column `{shown}`; {}",
                        known_columns()
                    ),
                )
            })
    };
    let mut spec = Spec {
        parameters: Vec::new(),
        derivatives: Vec::new(),
        studied: Vec::new(),
    };
    let mut derivatives = Vec::new();
    if let Some(section) = &only.sensitivity {
        let list = &section.get_ref().columns;
        if list.get_ref().is_empty() {
            return Err(invalid(
                list.span(),
                "`[sensitivity] columns` is empty; list derivative columns such as \
                 \"d(psi)/d(a)\", or remove the section"
                    .to_owned(),
            ));
        }
        for entry in list.get_ref() {
            let what = format!("`[sensitivity]` column \"{}\"", entry.get_ref());
            let Some((column, parameter)) = split_derivative(entry.get_ref()) else {
                return Err(invalid(
                    entry.span(),
                    format!(
                        "{what} is not a derivative; write \"d(COLUMN)/d(PARAMETER)\", e.g. \
                         \"d(psi)/d(a)\" or \"d(psi')/d(a)\" (a column of the table, a name \
                         of `[parameters]`)"
                    ),
                ));
            };
            let spanned = Spanned::new(entry.span(), column.to_owned());
            let k = column_index(&spanned, column, &what)?;
            let Some(p) = parameter_index(&mut spec.parameters, parameters, parameter) else {
                return Err(invalid(
                    entry.span(),
                    format!(
                        "{what}: the scene has no parameter `{parameter}`; {}",
                        known_parameters()
                    ),
                ));
            };
            if derivatives.contains(&(k, p)) {
                return Err(invalid(
                    entry.span(),
                    format!("{what} is listed twice; remove one"),
                ));
            }
            derivatives.push((k, p));
        }
    }
    let mut studied = Vec::new();
    if let Some(section) = &only.tolerances {
        let section = section.get_ref();
        let table = section.parameters.get_ref();
        if table.is_empty() {
            return Err(invalid(
                section.parameters.span(),
                "`[tolerances] parameters` is empty; give ± tolerances such as \
                 `parameters = { a = 0.0005 }`"
                    .to_owned(),
            ));
        }
        let mut entries: Vec<_> = table.iter().collect();
        entries.sort_by_key(|(name, _)| name.span().start);
        for (name, tolerance) in entries {
            let what = format!("`[tolerances]` of `{}`", name.get_ref());
            let Some(p) = parameter_index(&mut spec.parameters, parameters, name.get_ref()) else {
                return Err(invalid(
                    name.span(),
                    format!(
                        "{what}: `{}` is not a parameter of the scene; a tolerance belongs \
                         to a name of `[parameters]` (write the value there and use the name \
                         where the number was); {}",
                        name.get_ref(),
                        known_parameters()
                    ),
                ));
            };
            let t: f64 = (tolerance.get_ref().value_in(&bindings))
                .map_err(|message| source.formula_error(tolerance.span(), &message))?;
            if t.is_finite() && t > MAX_TOLERANCE {
                return Err(invalid(
                    tolerance.span(),
                    format!(
                        "{what} is {t:e}, over the limit of {MAX_TOLERANCE:e}; a tolerance is \
                         the half-width of ± in the parameter's unit, far smaller than the \
                         largest number of a scene (1e9 m, 1e12 N)"
                    ),
                ));
            }
            if !(t.is_finite() && t > 0.0) {
                let fix = if t.is_finite() && t < 0.0 {
                    format!(" (write {})", -t)
                } else {
                    String::new()
                };
                return Err(invalid(
                    tolerance.span(),
                    format!(
                        "{what} is {t}; a tolerance is the half-width of ± in the \
                         parameter's unit: a positive finite number{fix}"
                    ),
                ));
            }
            spec.parameters[p].tolerance = Some(t);
        }
        if section.columns.get_ref().is_empty() {
            return Err(invalid(
                section.columns.span(),
                "`[tolerances] columns` is empty; name the columns to study, e.g. \
                 `columns = [\"psi\"]`"
                    .to_owned(),
            ));
        }
        for name in section.columns.get_ref() {
            let what = "`[tolerances] columns`";
            let k = column_index(name, name.get_ref().trim(), what)?;
            if k == 0 {
                return Err(invalid(
                    name.span(),
                    format!(
                        "{what}: `{}` is the drive position, which the study holds fixed; \
                         name an output column",
                        name.get_ref()
                    ),
                ));
            }
            if !studied.contains(&k) {
                studied.push(k);
            }
        }
    }
    spec.derivatives = derivatives;
    spec.studied = studied;
    Ok(Some(spec))
}

/// The index in `list` of the scene's parameter `name`, added on first use; `None` if the
/// scene has no such parameter.
fn parameter_index(
    list: &mut Vec<Parameter>,
    parameters: &[(String, f64, f64)],
    name: &str,
) -> Option<usize> {
    if let Some(k) = list.iter().position(|p| p.name == name) {
        return Some(k);
    }
    let (_, _, own) = parameters.iter().find(|(n, _, _)| n == name)?;
    list.push(Parameter {
        name: name.to_owned(),
        value: *own,
        tolerance: None,
    });
    Some(list.len() - 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivative_columns_split_at_their_last_divider() {
        assert_eq!(split_derivative("d(psi)/d(a)"), Some(("psi", "a")));
        assert_eq!(split_derivative(" d(psi')/d( l1 ) "), Some(("psi'", "l1")));
        assert_eq!(split_derivative("d(F(x))/d(m2)"), Some(("F(x)", "m2")));
        for bad in ["psi", "d(psi)/da", "d()/d(a)", "d(psi)/d()", "dpsi/d(a)"] {
            assert_eq!(split_derivative(bad), None, "{bad}");
        }
    }
}
