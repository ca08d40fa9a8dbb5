//! Named mathematical constants: `std::f64::consts::PI` and its kin.
//!
//! A named constant is a symbol of the IR written as its Rust path (so emitted code names it
//! as the user would), differentiated as a constant and evaluated by every [`Arithmetic`]
//! at its own precision (π in 256-bit evaluation is π to 256 bits, not the `f64` value).
//! Infix formulas may write `pi` or `PI` for π, and any constant by its path with or without
//! the `std::` / `core::` prefix.
//!
//! [`Arithmetic`]: super::eval::Arithmetic

/// The path every named constant is stored under.
const PREFIX: &str = "std::f64::consts::";

/// The constants known by name: their short name, `f64` value, and a formula in the
/// primitives for evaluation at any precision.
pub(crate) const KNOWN: &[(&str, f64, Formula)] = {
    use std::f64::consts as c;
    &[
        ("PI", c::PI, Formula::PiTimes(1.0, 1.0)),
        ("TAU", c::TAU, Formula::PiTimes(2.0, 1.0)),
        ("FRAC_PI_2", c::FRAC_PI_2, Formula::PiTimes(1.0, 2.0)),
        ("FRAC_PI_3", c::FRAC_PI_3, Formula::PiTimes(1.0, 3.0)),
        ("FRAC_PI_4", c::FRAC_PI_4, Formula::PiTimes(1.0, 4.0)),
        ("FRAC_PI_6", c::FRAC_PI_6, Formula::PiTimes(1.0, 6.0)),
        ("E", c::E, Formula::Exp(1.0)),
        ("SQRT_2", c::SQRT_2, Formula::Sqrt(2.0)),
        ("LN_2", c::LN_2, Formula::Ln(2.0)),
        ("LN_10", c::LN_10, Formula::Ln(10.0)),
    ]
};

/// How a named constant is computed from exact `f64` numbers.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Formula {
    /// π · a / b (π = 4 atan 1).
    PiTimes(f64, f64),
    /// exp(a).
    Exp(f64),
    /// √a.
    Sqrt(f64),
    /// ln a.
    Ln(f64),
}

/// The stored name of the constant a formula calls `name` (`pi`, `PI`,
/// `f64::consts::PI`, `core::f64::consts::TAU`, …), if it is one.
pub(crate) fn canonical(name: &str) -> Option<String> {
    if name == "pi" {
        return Some(format!("{PREFIX}PI"));
    }
    let short = [
        "::std::f64::consts::",
        "std::f64::consts::",
        "core::f64::consts::",
        "f64::consts::",
    ]
    .iter()
    .find_map(|prefix| name.strip_prefix(prefix))
    .unwrap_or(if name == "PI" { name } else { "" });
    KNOWN
        .iter()
        .any(|(known, ..)| *known == short)
        .then(|| format!("{PREFIX}{short}"))
}

/// The entry of the stored name `name`, if it is a named constant.
pub(crate) fn lookup(name: &str) -> Option<(f64, Formula)> {
    let short = name.strip_prefix(PREFIX)?;
    KNOWN
        .iter()
        .find(|(known, ..)| *known == short)
        .map(|(_, value, formula)| (*value, *formula))
}

/// Whether `name` is a named constant (a path), not a parameter of generated code.
pub fn is_named_constant(name: &str) -> bool {
    lookup(name).is_some()
}

/// The names of the known constants, for error messages.
pub(crate) fn known_names() -> String {
    let names: Vec<&str> = KNOWN.iter().map(|(name, ..)| *name).collect();
    format!("pi, {PREFIX}{{{}}}", names.join(", "))
}
