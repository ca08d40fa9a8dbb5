//! `[parameters]`: named values a scene's formulas use (`l1 = 0.16`, `b = "2*l1"`), and
//! `--set name=value` on the command line to override them.
//!
//! Parameters are read first (a pass over the file that looks at `[parameters]` only) and
//! evaluated in the order of their dependencies into [`Bindings`], the explicit context in
//! which the resolver evaluates every quoted formula of the file. A parameter is a
//! plain number in the unit of the field that uses it, like any number of the file, unless
//! it is given with a unit of its own (`{ value = 6, unit = "in" }`): then it is converted
//! to the file's unit of that dimension. A `--set` value is in the parameter's unit.

use std::cmp::Reverse;
use std::collections::{BTreeMap, BinaryHeap, HashMap};
use std::str::FromStr;

use serde::Deserialize;
use toml::Spanned;

use crate::error::{Error, Result};

use super::dimension::{ParameterDimensions, Quantity, infer};
use super::scalar::Carried;
use super::source::Source;
use super::units::{Dimension, Units, UnitsSection, unit_factor};
use super::values::{Name, formula_in, formula_names, parameters_used, parse_formula};
use mechdiff_core::num_dual::Dual64;

pub use super::bindings::Bindings;

/// Reads and evaluates the `[parameters]` of `text` (as [`read`]) into the context a scene's
/// formulas are resolved in; with `seed`, the dual values carry the derivative with respect
/// to that parameter (per unit of it in its own unit, as `--set` moves it: `seed` itself is
/// then independent, its own formula set aside as `--set` sets it aside).
///
/// # Errors
/// As [`read`].
pub fn bindings(
    text: &str,
    source: &Source,
    settings: &[Setting],
    seed: Option<&str>,
) -> Result<Bindings> {
    let first: ParametersOnly = toml::from_str(text).map_err(|e| source.syntax_error(&e))?;
    bindings_of(
        first.parameters.as_ref(),
        &first.units,
        source,
        settings,
        seed,
    )
}

/// A parameter's value as written: a number or a quoted formula, in the unit of the
/// fields that use it, or either with its own unit (`{ value = 6, unit = "in" }`).
#[derive(Debug, Clone)]
pub enum ParameterValue {
    /// A number or a formula of numbers, constants and other parameters (`"2*l1"`).
    Plain(Plain),
    /// A value with its unit, converted to the file's unit of that dimension.
    WithUnit {
        /// The value.
        value: Plain,
        /// A unit as `[units]` writes it (`"mm"`, `"in"`, `"deg"`, `"lb"`, `"lbf"`, …).
        unit: Spanned<String>,
    },
}

/// A number or a formula.
#[derive(Debug, Clone)]
pub enum Plain {
    /// A number.
    Number(f64),
    /// A formula.
    Formula(String),
}

impl Plain {
    fn text(&self) -> String {
        match self {
            Plain::Number(v) => format!("{v:e}"),
            Plain::Formula(f) => f.clone(),
        }
    }
}

const EXPECTED: &str =
    "a number, a formula in quotes (`\"2*a\"`), or `{ value = 6, unit = \"in\" }`";

impl<'de> Deserialize<'de> for Plain {
    fn deserialize<D: serde::Deserializer<'de>>(
        deserializer: D,
    ) -> std::result::Result<Self, D::Error> {
        match ParameterValue::deserialize(deserializer)? {
            ParameterValue::Plain(p) => Ok(p),
            ParameterValue::WithUnit { .. } => Err(serde::de::Error::custom(
                "`value` is a number or a formula in quotes, without a unit of its own",
            )),
        }
    }
}

impl<'de> Deserialize<'de> for ParameterValue {
    fn deserialize<D: serde::Deserializer<'de>>(
        deserializer: D,
    ) -> std::result::Result<Self, D::Error> {
        deserializer.deserialize_any(ValueVisitor)
    }
}

struct ValueVisitor;

impl<'de> serde::de::Visitor<'de> for ValueVisitor {
    type Value = ParameterValue;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str(EXPECTED)
    }

    fn visit_f64<E: serde::de::Error>(self, v: f64) -> std::result::Result<ParameterValue, E> {
        Ok(ParameterValue::Plain(Plain::Number(v)))
    }

    fn visit_i64<E: serde::de::Error>(self, v: i64) -> std::result::Result<ParameterValue, E> {
        Ok(ParameterValue::Plain(Plain::Number(v as f64)))
    }

    fn visit_u64<E: serde::de::Error>(self, v: u64) -> std::result::Result<ParameterValue, E> {
        Ok(ParameterValue::Plain(Plain::Number(v as f64)))
    }

    fn visit_str<E: serde::de::Error>(self, v: &str) -> std::result::Result<ParameterValue, E> {
        Ok(ParameterValue::Plain(Plain::Formula(v.to_owned())))
    }

    fn visit_map<A: serde::de::MapAccess<'de>>(
        self,
        mut map: A,
    ) -> std::result::Result<ParameterValue, A::Error> {
        let (mut value, mut unit) = (None, None);
        while let Some(key) = map.next_key::<String>()? {
            match key.as_str() {
                "value" => value = Some(map.next_value::<Plain>()?),
                "unit" => unit = Some(map.next_value::<Spanned<String>>()?),
                other => return Err(serde::de::Error::unknown_field(other, &["value", "unit"])),
            }
        }
        Ok(ParameterValue::WithUnit {
            value: value.ok_or_else(|| serde::de::Error::missing_field("value"))?,
            unit: unit.ok_or_else(|| serde::de::Error::missing_field("unit"))?,
        })
    }
}

/// `[parameters]` as written.
pub type ParameterTable = Spanned<BTreeMap<Name, Spanned<ParameterValue>>>;

/// The first pass over a scene: `[parameters]` only (other sections are skipped).
#[derive(Deserialize)]
struct ParametersOnly {
    parameters: Option<ParameterTable>,
    #[serde(default)]
    units: UnitsSection,
}

/// `--set name=value`: a parameter's value from the command line (a number or a formula of
/// the other parameters).
#[derive(Debug, Clone, PartialEq)]
pub struct Setting {
    /// The parameter.
    pub name: String,
    /// Its value, as a formula.
    pub value: String,
}

impl FromStr for Setting {
    type Err = String;

    fn from_str(text: &str) -> std::result::Result<Self, String> {
        match text.split_once('=') {
            Some((name, value)) if !name.trim().is_empty() && !value.trim().is_empty() => {
                Ok(Setting {
                    name: name.trim().to_owned(),
                    value: value.trim().to_owned(),
                })
            }
            _ => Err(format!(
                "`{text}` is not a setting; write `NAME=VALUE`, e.g. `--set l1=0.16`"
            )),
        }
    }
}

/// A parameter to evaluate: its formula and where it comes from.
struct Pending<'a> {
    name: &'a str,
    text: String,
    /// The value's span in the file; `None` for a `--set` value.
    span: Option<std::ops::Range<usize>>,
    /// The file's units per unit of the value (1 without a unit of its own).
    scale: f64,
    /// Its unit, when it has one of its own, and that unit's dimension.
    unit: Option<(String, Dimension)>,
}

/// Reads and evaluates the `[parameters]` of `text`, with `settings` replacing the values
/// of the file; the result is in the order of evaluation: every parameter after those it
/// uses, otherwise in the file's order.
///
/// # Errors
/// A TOML syntax error; a parameter name that is not a plain name or is a constant; a
/// formula that cannot be read or uses an unknown name (with its column); a cycle of
/// parameters; a `--set` naming no parameter of the file.
pub fn read(text: &str, source: &Source, settings: &[Setting]) -> Result<Vec<(String, f64)>> {
    Ok(read_with_own_units(text, source, settings)?
        .into_iter()
        .map(|(name, value, _)| (name, value))
        .collect())
}

/// As [`read`], each parameter also with its value in its own unit (the unit of
/// `{ value = 6, unit = "in" }`, the unit a `--set` value is in): `(name, value in the
/// file's unit, value in its own unit)`; the two are equal for a parameter without a unit of
/// its own.
///
/// # Errors
/// As [`read`].
pub fn read_with_own_units(
    text: &str,
    source: &Source,
    settings: &[Setting],
) -> Result<Vec<(String, f64, f64)>> {
    read_in::<f64>(text, source, settings, None)
}

/// As [`read_with_own_units`], in the scalar `D`, with the parameter `seed` (if any) the
/// independent variable of `D`'s dual part.
fn read_in<D: Carried>(
    text: &str,
    source: &Source,
    settings: &[Setting],
    seed: Option<&str>,
) -> Result<Vec<(String, D, f64)>> {
    let first: ParametersOnly = toml::from_str(text).map_err(|e| source.syntax_error(&e))?;
    evaluate_in(
        first.parameters.as_ref(),
        &first.units,
        source,
        settings,
        seed,
    )
}

/// The context of a scene's formulas from its `[parameters]` and `[units]` as read (the
/// scene's one reading: see [`bindings`] for the same from the text).
///
/// # Errors
/// As [`read`].
pub fn bindings_of(
    parameters: Option<&ParameterTable>,
    units: &UnitsSection,
    source: &Source,
    settings: &[Setting],
    seed: Option<&str>,
) -> Result<Bindings> {
    let values = evaluate_in::<f64>(parameters, units, source, settings, None)?;
    let values = values.into_iter().map(|(n, v, _)| (n, v)).collect();
    Ok(match seed {
        Some(seed) => {
            let duals = evaluate_in::<Dual64>(parameters, units, source, settings, Some(seed))?;
            let duals = duals.into_iter().map(|(n, v, _)| (n, v)).collect();
            Bindings::seeded(values, duals, seed)
        }
        None => Bindings::new(values),
    })
}

/// As [`read_in`], of `[parameters]` (`parameters`) and `[units]` (`units`) as read.
fn evaluate_in<D: Carried>(
    parameters: Option<&ParameterTable>,
    units: &UnitsSection,
    source: &Source,
    settings: &[Setting],
    seed: Option<&str>,
) -> Result<Vec<(String, D, f64)>> {
    let file_units = Units::declared(units);
    let empty = BTreeMap::new();
    let table = parameters.map_or(&empty, Spanned::get_ref);
    let mut pending: Vec<Pending> = Vec::with_capacity(table.len());
    for (name, value) in table {
        let plain = formula_names(name.get_ref()).is_ok_and(|n| n == [name.get_ref().clone()]);
        if !plain || matches!(name.get_ref().as_str(), "pi" | "tau") {
            return Err(Error::Invalid {
                location: source.location(name.span()),
                message: format!(
                    "`{}` cannot name a parameter; a parameter's name is a letter followed by \
                     letters, digits or `_`, and is not `pi`, `tau` or a function's name",
                    name.get_ref()
                ),
            });
        }
        let (text, scale, unit) = match value.get_ref() {
            ParameterValue::Plain(value) => (value.text(), 1.0, None),
            ParameterValue::WithUnit { value, unit } => {
                let Some((dimension, factor)) = unit_factor(unit.get_ref()) else {
                    return Err(Error::Invalid {
                        location: source.location(unit.span()),
                        message: format!(
                            "`{}` is not a unit; a parameter's unit is one that `[units]` \
                             accepts: m, mm, in, ft, rad, deg, rad/s, deg/s, rpm, rad/s^2, \
                             deg/s^2, kg, lb, slug, N, lbf, N*m, N*mm, lbf*in, lbf*ft, kg*m^2, \
                             kg*mm^2, lb*in^2, slug*ft^2",
                            unit.get_ref()
                        ),
                    });
                };
                (
                    value.text(),
                    factor / file_units.factor(dimension),
                    Some((unit.get_ref().clone(), dimension)),
                )
            }
        };
        pending.push(Pending {
            name: name.get_ref(),
            text,
            span: Some(value.span()),
            scale,
            unit,
        });
    }
    // In the file's order, so that the evaluation order follows it where the dependencies
    // allow (`mechdiff check` lists the parameters in that order).
    pending.sort_by_key(|p| p.span.as_ref().map_or(0, |s| s.start));
    for setting in settings {
        let Some(p) = pending.iter_mut().find(|p| p.name == setting.name) else {
            let known: Vec<&str> = pending.iter().map(|p| p.name).collect();
            return Err(Error::Setting {
                option: "--set",
                setting: format!("{}={}", setting.name, setting.value),
                message: if known.is_empty() {
                    "the scene has no `[parameters]`".to_owned()
                } else {
                    format!(
                        "the scene has no parameter `{}`; its parameters are: {}",
                        setting.name,
                        known.join(", ")
                    )
                },
            });
        };
        p.text.clone_from(&setting.value);
        p.span = None;
    }
    let values = evaluate(&pending, source, seed)?;
    if pending.iter().any(|p| p.unit.is_some()) {
        let order: Vec<&str> = values.iter().map(|(name, ..)| name.as_str()).collect();
        source.set_parameter_dimensions(dimensions(&pending, &order, source, &file_units)?);
    }
    Ok(values)
}

/// The error for the parameter `p`: at its value in the file, or for its `--set`.
fn failure(p: &Pending, source: &Source, message: String) -> Error {
    match &p.span {
        Some(span) => Error::Invalid {
            location: source.location(source.inside_formula(span.clone(), &message)),
            message: format!("parameter `{}`: {message}", p.name),
        },
        None => Error::Setting {
            option: "--set",
            setting: format!("{}={}", p.name, p.text),
            message,
        },
    }
}

/// The dimensions of the parameters (see [`super::dimension`]), inferred in the `order` of
/// evaluation: a parameter with a unit of its own has that unit's, one defined by a formula
/// the formula's.
///
/// # Errors
/// A formula that adds, or takes a function of, numbers of the wrong dimensions; a
/// parameter with a unit of its own whose formula is not free (its parameters would be
/// converted twice).
fn dimensions(
    pending: &[Pending],
    order: &[&str],
    source: &Source,
    file_units: &Units,
) -> Result<ParameterDimensions> {
    let by_name: HashMap<&str, &Pending> = pending.iter().map(|p| (p.name, p)).collect();
    let mut dimensions = ParameterDimensions::default();
    for name in order {
        let p = by_name[name];
        let (graph, root) = parse_formula(&p.text).map_err(|e| failure(p, source, e))?;
        let found = infer(&p.text, &graph, root, &dimensions).map_err(|e| failure(p, source, e))?;
        match (&p.unit, found) {
            (Some((unit, dimension)), found) => {
                if let Some(q) = found {
                    return Err(failure(
                        p,
                        source,
                        format!(
                            "the formula \"{}\" is {}, and a parameter with a unit of its own \
                             (`{unit}`) takes a number in that unit or a formula of parameters \
                             without units; write the formula as a parameter without a unit",
                            p.text,
                            q.words()
                        ),
                    ));
                }
                dimensions.with_unit(p.name, unit, Quantity::of(*dimension, file_units));
            }
            (None, found) => dimensions.with_formula(p.name, &p.text, found),
        }
    }
    Ok(dimensions)
}

/// Evaluates the parameters in the order of their dependencies (Kahn's algorithm), in the
/// scalar `D`, `seed` (if any) the independent variable: `(name, value in the file's unit,
/// value in its own unit)`.
fn evaluate<D: Carried>(
    pending: &[Pending],
    source: &Source,
    seed: Option<&str>,
) -> Result<Vec<(String, D, f64)>> {
    let fail = |p: &Pending, message: String| failure(p, source, message);
    let index: HashMap<&str, usize> = pending
        .iter()
        .enumerate()
        .map(|(i, p)| (p.name, i))
        .collect();
    let mut uses: Vec<Vec<usize>> = Vec::with_capacity(pending.len());
    let mut names_in_scene: Vec<&str> = pending.iter().map(|p| p.name).collect();
    names_in_scene.sort_unstable();
    for p in pending {
        // An unknown name is reported here, with its column and every parameter's name.
        let names = parameters_used(&p.text, &names_in_scene).map_err(|e| fail(p, e))?;
        uses.push(
            names
                .iter()
                .filter_map(|n| index.get(n.as_str()).copied())
                .collect(),
        );
    }
    let mut waiting: Vec<usize> = uses.iter().map(Vec::len).collect();
    let mut used_by: Vec<Vec<usize>> = vec![Vec::new(); pending.len()];
    for (i, u) in uses.iter().enumerate() {
        for &j in u {
            used_by[j].push(i);
        }
    }
    // The first ready parameter in the file's order next (Kahn's algorithm with a heap).
    let mut ready: BinaryHeap<Reverse<usize>> = (0..pending.len())
        .filter(|&i| waiting[i] == 0)
        .map(Reverse)
        .collect();
    let mut values: Vec<(String, D, f64)> = Vec::with_capacity(pending.len());
    let mut known: HashMap<String, D> = HashMap::with_capacity(pending.len());
    while let Some(Reverse(i)) = ready.pop() {
        let p = &pending[i];
        let mut own: D = formula_in(&p.text, &known).map_err(|e| fail(p, e))?;
        if seed == Some(p.name) {
            own = D::with_tangent(own.re(), 1.0);
        }
        let value = own * p.scale;
        known.insert(p.name.to_owned(), value);
        values.push((p.name.to_owned(), value, own.re()));
        for &k in &used_by[i] {
            waiting[k] -= 1;
            if waiting[k] == 0 {
                ready.push(Reverse(k));
            }
        }
    }
    if let Some(p) = pending
        .iter()
        .enumerate()
        .find(|(i, _)| waiting[*i] > 0)
        .map(|(_, p)| p)
    {
        let cycle: Vec<&str> = pending
            .iter()
            .enumerate()
            .filter(|(i, _)| waiting[*i] > 0)
            .map(|(_, p)| p.name)
            .collect();
        return Err(fail(
            p,
            format!(
                "the parameters {} use each other in a cycle; give one of them a number",
                cycle.join(", ")
            ),
        ));
    }
    Ok(values)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read_str(text: &str, settings: &[Setting]) -> Result<Vec<(String, f64)>> {
        read(text, &Source::new("t.toml", text), settings)
    }

    #[test]
    fn parameters_are_evaluated_after_those_they_use() {
        let values = read_str("[parameters]\nb = \"2*a\"\na = 0.5\n", &[]).unwrap();
        // 2*0.5 is exact in f64.
        assert_eq!(values, [("a".to_owned(), 0.5), ("b".to_owned(), 1.0)]);
        // Without dependencies, the file's order (not the alphabet's, nor its reverse).
        let values = read_str("[parameters]\nz = 1\nm = 2\na = 3\n", &[]).unwrap();
        let names: Vec<&str> = values.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["z", "m", "a"]);
        let set = [Setting::from_str("a=0.25").unwrap()];
        let values = read_str("[parameters]\nb = \"2*a\"\na = 0.5\n", &set).unwrap();
        assert_eq!(values[1], ("b".to_owned(), 0.5));
    }

    #[test]
    fn a_parameter_with_a_unit_is_converted_to_the_files_unit() {
        let text = "[units]\nlength = \"mm\"\n[parameters]\nl = { value = 2, unit = \"in\" }\n\
                    m = \"l/2\"\n";
        let values = read_str(text, &[]).unwrap();
        // 2 in = 50.8 mm: 2 × (0.0254 / 0.001), one rounding in the quotient, one in the
        // product: 1e-13 relative.
        assert!((values[0].1 - 50.8).abs() < 50.8e-13, "{values:?}");
        let e = read_str("[parameters]\nl = { value = 2, unit = \"furlong\" }\n", &[]);
        assert!(
            e.unwrap_err()
                .to_string()
                .contains("`furlong` is not a unit")
        );
    }

    #[test]
    fn cycles_unknown_names_and_bad_settings_are_refused() {
        let e = read_str("[parameters]\na = \"b\"\nb = \"a+1\"\n", &[]).unwrap_err();
        assert!(e.to_string().contains("cycle"), "{e}");
        let e = read_str("[parameters]\na = \"1 + bb\"\n", &[]).unwrap_err();
        assert!(e.to_string().contains("`bb` (column 5"), "{e}");
        // At `bb` itself: column 5 is the quote, `bb` is the 5th character inside it.
        assert!(e.to_string().starts_with("t.toml:2:10"), "{e}");
        // The names a formula could use are every parameter of the scene, whether or not
        // it has been evaluated yet (a `--set` value is evaluated before the others).
        assert!(e.to_string().contains("the parameters are: a;"), "{e}");
        let set = [Setting::from_str("a=nan").unwrap()];
        let e = read_str(
            "[parameters]
a = 1
b = 2
",
            &set,
        )
        .unwrap_err();
        assert!(e.to_string().contains("the parameters are: a, b;"), "{e}");
        assert!(!e.to_string().contains("has no `[parameters]`"), "{e}");
        let e = read_str(
            "[parameters]\na = 1\n",
            &[Setting::from_str("z=1").unwrap()],
        );
        assert!(e.unwrap_err().to_string().contains("no parameter `z`"));
        assert!(Setting::from_str("a").is_err());
        let e = read_str("[parameters]\npi = 3\n", &[]).unwrap_err();
        assert!(e.to_string().contains("cannot name a parameter"), "{e}");
    }
}
