//! The values of a scene file as serde reads them: numbers (or quoted constant formulas),
//! pairs that must have exactly two entries, and lists with a length limit.
//!
//! These are `deserialize_with` helpers for the file's format; every error they raise gets
//! the value's span from toml, so the message is printed at `file:line:column`.

use std::collections::HashMap;
use std::fmt;

use mechdiff_core::Scalar;
use mechdiff_core::symbolic::Graph;
use mechdiff_core::symbolic::constants::is_named_constant;
use serde::Deserialize;
use serde::de::{self, Deserializer, SeqAccess, Visitor};
use toml::Spanned;

use crate::bindings::Bindings;
use crate::scalar::Carried;

/// The most drive positions a `positions = [...]` list may have (the file is parsed whole).
pub const MAX_POSITIONS: usize = 1_000_000;

/// The longest formula a scene may quote (characters).
pub const MAX_FORMULA_LENGTH: usize = 200;

/// The deepest nesting of parentheses in a quoted formula.
pub const MAX_FORMULA_DEPTH: usize = 16;

/// A number as written in a scene: a TOML integer or float, or a quoted formula such as
/// `"23.4791*0.86"`, `"180/7"` or `"2*l1"` kept as its text. Serde only reads it; the
/// resolver evaluates it ([`Number::value_in`]) with the scene's parameters, in the scalar it
/// resolves in. Its span (a `Spanned<Number>`) places its errors at `file:line:column`.
#[derive(Debug, Clone, PartialEq)]
pub enum Number {
    /// A number written as a number.
    Literal(f64),
    /// A quoted formula, as written (see [`formula_in`]).
    Formula(String),
}

impl Number {
    /// Its value in the scalar `D` with the scene's `parameters` (for a dual number, with
    /// the derivative with respect to the seeded parameter; a literal has none).
    ///
    /// # Errors
    /// As [`constant_formula`], for a formula.
    pub fn value_in<D: Carried>(&self, parameters: &Bindings) -> Result<D, String> {
        match self {
            Number::Literal(v) => Ok(D::constant(*v)),
            Number::Formula(text) => formula_in(text, D::parameters(parameters)),
        }
    }
}

impl<'de> Deserialize<'de> for Number {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(NumberVisitor)
    }
}

struct NumberVisitor;

impl Visitor<'_> for NumberVisitor {
    type Value = Number;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a number, or a constant formula in quotes (`\"23.4791*0.86\"`)")
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Number, E> {
        Ok(Number::Literal(v))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Number, E> {
        Ok(Number::Literal(v as f64))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Number, E> {
        Ok(Number::Literal(v as f64))
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<Number, E> {
        Ok(Number::Formula(v.to_owned()))
    }
}

/// The value of a constant formula (no parameters): numbers, `+ - * / ^`, parentheses, the
/// functions of the symbolic engine (`sqrt`, `sin`, `atan2`, …, angles in radians) and the
/// constants `pi` and `tau`. It is parsed by the symbolic engine's infix parser. A scene's
/// formulas may also use its `[parameters]` ([`Number::value_in`]).
///
/// ```
/// use mechdiff_scene::values::constant_formula;
///
/// assert_eq!(constant_formula("23.4791*0.86").unwrap(), 23.4791 * 0.86);
/// assert_eq!(constant_formula("2*pi").unwrap(), std::f64::consts::TAU);
/// assert!(constant_formula("2*x").unwrap_err().contains("`x` (column 3"));
/// ```
///
/// # Errors
/// A message saying what is wrong with the formula (syntax, an unknown name and its column,
/// a result that is not a finite number) and what a formula may contain.
pub fn constant_formula(text: &str) -> Result<f64, String> {
    formula(text, &HashMap::new())
}

/// The value of a formula whose names are `pi`, `tau` and the given `bindings` (see
/// [`constant_formula`]).
///
/// # Errors
/// As [`constant_formula`].
pub fn formula(text: &str, bindings: &HashMap<String, f64>) -> Result<f64, String> {
    formula_in(text, bindings)
}

/// The value of a formula in any scalar `D` (see [`constant_formula`]), its names `pi`,
/// `tau` and the given `bindings`: with dual numbers for the `bindings`, the formula's
/// derivative with respect to what they carry (the tangent of a scene).
///
/// # Errors
/// As [`constant_formula`].
pub fn formula_in<D: Scalar>(text: &str, bindings: &HashMap<String, D>) -> Result<D, String> {
    let quoted = format!("the formula \"{text}\"");
    let (graph, id) = parse_formula(text)?;
    let constants = [
        ("pi", D::constant(std::f64::consts::PI)),
        ("tau", D::constant(std::f64::consts::TAU)),
    ];
    let symbols = graph.symbols(&[id]);
    // The sorted list of parameters only for the message: a scene may have many formulas
    // and many parameters.
    let known =
        |s: &str| is_named_constant(s) || matches!(s, "pi" | "tau") || bindings.contains_key(s);
    if !symbols.iter().all(|s| known(s)) {
        let mut parameters: Vec<&str> = bindings.keys().map(String::as_str).collect();
        parameters.sort_unstable();
        unknown_name(text, &symbols, &parameters)?;
    }
    // Only the names the formula uses are bound (a scene may have many parameters).
    let mut all: Vec<(&str, D)> = constants.to_vec();
    all.extend(
        symbols
            .iter()
            .filter_map(|s| bindings.get(*s).map(|v| (*s, *v))),
    );
    let value = graph
        .evaluate_dual(&[id], &all)
        .map_err(|e| format!("{quoted} cannot be evaluated: {e}"))?[0];
    if !value.re().is_finite() {
        return Err(format!(
            "{quoted} evaluates to {}; expected a finite number (check for a division \
             by zero, a square root or logarithm of a negative number, or an overflow)",
            value.re()
        ));
    }
    // + 0 turns a −0 into 0.
    Ok(value + 0.0)
}

/// The error for the first name `text` uses (of its `symbols`) that is neither a constant
/// nor one of the scene's `parameters`, with its column and the names it could be.
fn unknown_name(text: &str, symbols: &[&str], parameters: &[&str]) -> Result<(), String> {
    let known =
        |s: &str| is_named_constant(s) || matches!(s, "pi" | "tau") || parameters.contains(&s);
    let Some(name) = symbols.iter().copied().find(|s| !known(s)) else {
        return Ok(());
    };
    let column = name_column(text, name);
    let listed = if parameters.is_empty() {
        "the scene has no `[parameters]`".to_owned()
    } else {
        format!("the parameters are: {}", parameters.join(", "))
    };
    Err(format!(
        "the formula \"{text}\" uses `{name}` (column {column} of the formula), which is \
         neither a parameter nor a constant; {listed}; {ALLOWED}"
    ))
}

/// The parameters `text` uses, once every name it uses is checked to be a constant or one
/// of the scene's `parameters` (all of them, evaluated or not: a formula's error lists what
/// it could use).
///
/// # Errors
/// As [`constant_formula`], for a formula that cannot be read or an unknown name.
pub fn parameters_used(text: &str, parameters: &[&str]) -> Result<Vec<String>, String> {
    let (graph, id) = parse_formula(text)?;
    let symbols = graph.symbols(&[id]);
    unknown_name(text, &symbols, parameters)?;
    Ok(symbols
        .into_iter()
        .filter(|s| parameters.contains(s))
        .map(str::to_owned)
        .collect())
}

/// What a formula may contain, for messages.
const ALLOWED: &str = "a formula may use numbers, + - * / ^, parentheses, functions such as \
                       sqrt, sin, cos, atan2 (radians), the constants pi and tau, and the \
                       names of `[parameters]`";

/// The names a formula uses (other than `pi` and `tau`), in the order of the engine.
///
/// # Errors
/// As [`constant_formula`], for a formula that cannot be read.
pub fn formula_names(text: &str) -> Result<Vec<String>, String> {
    let (graph, id) = parse_formula(text)?;
    Ok(graph
        .symbols(&[id])
        .into_iter()
        .filter(|s| !matches!(*s, "pi" | "tau") && !is_named_constant(s))
        .map(str::to_owned)
        .collect())
}

/// The column (1-based, in characters) of the first whole-word `name` in `text`.
fn name_column(text: &str, name: &str) -> usize {
    let word = |c: char| c.is_alphanumeric() || c == '_';
    let at = text
        .match_indices(name)
        .find(|(i, _)| {
            let before = text[..*i].chars().next_back();
            let after = text[i + name.len()..].chars().next();
            !before.is_some_and(word) && !after.is_some_and(word)
        })
        .map_or(0, |(i, _)| i);
    text[..at].chars().count() + 1
}

/// A formula checked for size and parsed by the symbolic engine.
pub fn parse_formula(text: &str) -> Result<(Graph, mechdiff_core::symbolic::Id), String> {
    let quoted = format!("the formula \"{text}\"");
    if text.chars().count() > MAX_FORMULA_LENGTH {
        return Err(format!(
            "{quoted} is longer than {MAX_FORMULA_LENGTH} characters; write the number itself"
        ));
    }
    let mut depth = 0usize;
    for c in text.chars() {
        match c {
            '(' => depth += 1,
            ')' => depth = depth.saturating_sub(1),
            _ => {}
        }
        if depth > MAX_FORMULA_DEPTH {
            return Err(format!(
                "{quoted} nests parentheses deeper than {MAX_FORMULA_DEPTH}; simplify it"
            ));
        }
    }
    // Literals that are not finite f64 (`1e999`) are refused here, before the parser sees
    // them.
    if let Some(literal) = literals(text).find(|l| l.parse::<f64>().is_ok_and(|v| !v.is_finite())) {
        return Err(format!(
            "{quoted}: the number {literal} is beyond the range of f64 (about 1.8e308)"
        ));
    }
    let mut graph = Graph::new();
    let id = graph.parse_infix(text).map_err(|e| {
        // The scene's error is located at the string; of the engine's message keep the
        // first line (its column in the formula), not the caret drawn under it.
        let e = e.to_string();
        let first = e.lines().next().unwrap_or_default();
        format!("{quoted} cannot be read: {first}; {ALLOWED}")
    })?;
    Ok((graph, id))
}

/// The number literals of a formula (digits, `.`, and an exponent).
fn literals(text: &str) -> impl Iterator<Item = &str> {
    let bytes = text.as_bytes();
    let mut i = 0;
    std::iter::from_fn(move || {
        while i < bytes.len() && !(bytes[i].is_ascii_digit() || bytes[i] == b'.') {
            // Skip names (`atan2`) whole, so their digits are not read as numbers.
            if bytes[i].is_ascii_alphabetic() || bytes[i] == b'_' {
                while i < bytes.len() && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'_') {
                    i += 1;
                }
            } else {
                i += 1;
            }
        }
        if i >= bytes.len() {
            return None;
        }
        let start = i;
        while i < bytes.len() && (bytes[i].is_ascii_digit() || bytes[i] == b'.') {
            i += 1;
        }
        if i < bytes.len() && matches!(bytes[i], b'e' | b'E') {
            let sign = usize::from(matches!(bytes.get(i + 1), Some(b'+' | b'-')));
            if bytes.get(i + 1 + sign).is_some_and(u8::is_ascii_digit) {
                i += 1 + sign;
                while i < bytes.len() && bytes[i].is_ascii_digit() {
                    i += 1;
                }
            }
        }
        Some(&text[start..i])
    })
}

fn exactly_two<T, E: de::Error>(list: Spanned<Vec<T>>, what: &str) -> Result<Spanned<[T; 2]>, E> {
    let span = list.span();
    let list = list.into_inner();
    let n = list.len();
    let pair: [T; 2] = list.try_into().map_err(|_| {
        E::custom(format!(
            "expected exactly two {what}, found {n}; a pair is written `[first, second]`"
        ))
    })?;
    Ok(Spanned::new(span, pair))
}

/// A name with the place where it is written.
pub type Name = Spanned<String>;

/// An optional pair of names (a line, the links of a slide, two gears): exactly two entries,
/// never silently the first two of a longer list (use with `#[serde(default)]`).
pub fn option_name_pair<'de, D: Deserializer<'de>>(
    deserializer: D,
) -> Result<Option<Spanned<[Name; 2]>>, D::Error> {
    Option::<Spanned<Vec<Name>>>::deserialize(deserializer)?
        .map(|list| exactly_two(list, "names"))
        .transpose()
}

/// A required pair of names.
pub fn name_pair<'de, D: Deserializer<'de>>(
    deserializer: D,
) -> Result<Spanned<[Name; 2]>, D::Error> {
    exactly_two(Spanned::<Vec<Name>>::deserialize(deserializer)?, "names")
}

/// Two numbers as written, each with its span, and the pair's span.
pub type SpannedPair = Spanned<[Spanned<Number>; 2]>;

/// An optional pair of numbers with each entry's span (a force's components, a drive
/// range): exactly two (use with `#[serde(default)]`).
pub fn option_number_pair<'de, D: Deserializer<'de>>(
    deserializer: D,
) -> Result<Option<SpannedPair>, D::Error> {
    Option::<Spanned<Vec<Spanned<Number>>>>::deserialize(deserializer)?
        .map(|list| exactly_two(list, "numbers"))
        .transpose()
}

/// `[sweep] positions`: at most `MAX_POSITIONS` numbers, counted as they are read, each
/// with its span (use with `#[serde(default)]`).
pub fn option_positions<'de, D: Deserializer<'de>>(
    deserializer: D,
) -> Result<Option<PositionList>, D::Error> {
    let list = Option::<Spanned<Positions>>::deserialize(deserializer)?;
    Ok(list.map(|l| Spanned::new(l.span(), l.into_inner().0)))
}

/// `[sweep] positions` as read: the list and each entry with its span.
pub type PositionList = Spanned<Vec<Spanned<Number>>>;

/// A list of drive positions of bounded length.
struct Positions(Vec<Spanned<Number>>);

impl<'de> Deserialize<'de> for Positions {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_seq(PositionsVisitor)
    }
}

struct PositionsVisitor;

impl<'de> Visitor<'de> for PositionsVisitor {
    type Value = Positions;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(f, "a list of at most {MAX_POSITIONS} drive positions")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Positions, A::Error> {
        let mut values = Vec::with_capacity(seq.size_hint().unwrap_or(0).min(MAX_POSITIONS));
        while let Some(v) = seq.next_element::<Spanned<Number>>()? {
            if values.len() == MAX_POSITIONS {
                return Err(de::Error::custom(format!(
                    "`positions` has more than {MAX_POSITIONS} entries; split the sweep into \
                     several scenes, or use `from`, `to` and `step`"
                )));
            }
            values.push(v);
        }
        Ok(Positions(values))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn literals_skip_function_names() {
        let found: Vec<&str> = literals("atan2(1e3, .5) + log10(2E-4)").collect();
        assert_eq!(found, ["1e3", ".5", "2E-4"]);
    }

    #[test]
    fn formulas_that_overflow_or_divide_by_zero_are_refused() {
        for text in [
            "1e999",
            "1e200*1e200",
            "1/0",
            "0/0",
            "sqrt(-1)",
            "exp(1000)",
        ] {
            let e = constant_formula(text).unwrap_err();
            assert!(e.contains(text), "{e}");
        }
    }

    #[test]
    fn deep_or_long_formulas_are_refused_before_parsing() {
        let deep = format!("{}1{}", "(".repeat(10_000), ")".repeat(10_000));
        assert!(constant_formula(&deep).unwrap_err().contains("longer"));
        let deep = format!("{}1{}", "(".repeat(17), ")".repeat(17));
        assert!(constant_formula(&deep).unwrap_err().contains("deeper"));
    }
}
