//! `[solver]`: the position solver's settings for a scene ([`Solver`]'s fields), each
//! optional, checked against bounds before anything is solved. Every solve of the scene uses
//! them: the sweep, dynamics and balancing, dead positions and motion limits, `[sweep] of`,
//! accuracy, code generation, pictures and sensitivities.

use mechdiff_core::geometry::Solver;
use std::fmt;

use serde::Deserialize;
use serde::de::{self, Deserializer, Visitor};
use toml::Spanned;

use crate::error::Result;

use super::context::Context;

/// Tolerances allowed (relative to each loop's size). Below 1e-15 (~5 ε) Newton cannot
/// reach the tolerance: rounding in the loop equations is a few ε of the loop's size, so
/// every step would fail. Above 1e-6 the positions carry errors of that size and the
/// default singular threshold, 0.1/√tolerance, drops to 100: ordinary poses would be
/// reported as toggles.
pub const TOLERANCE: (f64, f64) = (1e-15, 1e-6);

/// Newton iterations allowed per attempt. At least 1 (with none, no step can converge);
/// from the solver's predictor Newton converges in 2–5 iterations, and an attempt that
/// stalls or diverges is given up early anyway: 1000 only bounds the work of a bad setting.
pub const MAX_ITERATIONS: (i64, i64) = (1, 1000);

/// Halvings of a failing step allowed. 0 gives up at the first failure; 64 halvings take
/// the longest step (1/8 rad) to 7e-21 rad, below the resolution of f64 at any drive
/// position above 1e-4: more cannot make a step that still fails succeed.
pub const MAX_SUBDIVISIONS: (i64, i64) = (0, 64);

/// Condition numbers allowed as the singular threshold. A scaled Jacobian's condition is at
/// least 1, and that of an ordinary linkage in a regular pose a few units: below 10 regular
/// poses would be reported as toggles. Above 1e15 (~1/(5 ε)) the velocity coefficients of a
/// pose let through have no correct digit left.
pub const SINGULAR_CONDITION: (f64, f64) = (10.0, 1e15);

/// `[solver]` as written: every field optional (the default solver's value).
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverDef {
    /// Newton's residual tolerance, relative to each loop's size.
    pub tolerance: Option<Spanned<Real>>,
    /// Newton iterations per attempt.
    pub max_iterations: Option<Spanned<Count>>,
    /// Halvings of a failing step.
    pub max_subdivisions: Option<Spanned<Count>>,
    /// The condition number above which a pose is a toggle (default 0.1/√tolerance).
    pub singular_condition: Option<Spanned<Real>>,
    /// Solve the loops that match a standard pattern in closed form (default `true`).
    pub closed_form: Option<Spanned<bool>>,
}

/// A setting's number as written: a TOML float or integer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Real(pub f64);

/// A setting's count as written: a TOML integer (a negative one is refused with the range).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Count(pub i64);

impl<'de> Deserialize<'de> for Real {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> std::result::Result<Self, D::Error> {
        struct Number;
        impl Visitor<'_> for Number {
            type Value = Real;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a number, such as 1e-13")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> std::result::Result<Real, E> {
                Ok(Real(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> std::result::Result<Real, E> {
                Ok(Real(v as f64))
            }
        }
        deserializer.deserialize_any(Number)
    }
}

impl<'de> Deserialize<'de> for Count {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> std::result::Result<Self, D::Error> {
        struct Whole;
        impl Visitor<'_> for Whole {
            type Value = Count;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a whole number, such as 50")
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> std::result::Result<Count, E> {
                Ok(Count(v))
            }
        }
        deserializer.deserialize_any(Whole)
    }
}

/// The solver `section` sets (the default solver where it, or a field, is absent).
///
/// # Errors
/// [`crate::Error::Invalid`] at a value outside its bounds (see the constants of this
/// module), naming the field, the bounds, why, and the default.
pub(crate) fn resolve(cx: &Context<'_>, section: Option<&Spanned<SolverDef>>) -> Result<Solver> {
    let mut solver = Solver::default();
    let Some(section) = section else {
        return Ok(solver);
    };
    let def = section.get_ref();
    let out_of = |field: &str, value: String, bounds: String, why: &str, default: &str| {
        format!(
            "`[solver] {field}` = {value} is outside {bounds}: {why}; write a value in that \
             range, or remove the field for the default ({default})"
        )
    };
    if let Some(v) = &def.tolerance {
        let (lo, hi) = TOLERANCE;
        let x = v.get_ref().0;
        if !(lo..=hi).contains(&x) {
            let why = "below it Newton cannot reach the tolerance (rounding), above it the \
                       positions carry errors of that size and regular poses are reported as \
                       toggles";
            let (value, bounds) = (format!("{x:e}"), format!("[{lo:e}, {hi:e}]"));
            let default = format!("{:e}", solver.tolerance);
            let message = out_of("tolerance", value, bounds, why, &default);
            return Err(cx.invalid(v, message));
        }
        solver.tolerance = x;
    }
    let count =
        |v: &Spanned<Count>, field: &str, (lo, hi): (i64, i64), why: &str, default: &str| {
            let n = v.get_ref().0;
            match usize::try_from(n) {
                Ok(k) if (lo..=hi).contains(&n) => Ok(k),
                _ => {
                    let message =
                        out_of(field, n.to_string(), format!("[{lo}, {hi}]"), why, default);
                    Err(cx.invalid(v, message))
                }
            }
        };
    let defaults = Solver::default();
    if let Some(v) = &def.max_iterations {
        let why = "with none no step converges; more than 1000 only spends time (Newton \
                   converges in a few iterations from the solver's predictor)";
        let default = defaults.max_iterations.to_string();
        solver.max_iterations = count(v, "max_iterations", MAX_ITERATIONS, why, &default)?;
    }
    if let Some(v) = &def.max_subdivisions {
        let why = "64 halvings take a step of 1/8 rad below the resolution of f64";
        let default = defaults.max_subdivisions.to_string();
        solver.max_subdivisions = count(v, "max_subdivisions", MAX_SUBDIVISIONS, why, &default)?;
    }
    if let Some(v) = &def.singular_condition {
        let (lo, hi) = SINGULAR_CONDITION;
        let x = v.get_ref().0;
        if !(lo..=hi).contains(&x) {
            let why = "below it regular poses are reported as toggles, above it the velocity \
                       coefficients let through have no correct digit";
            let (value, bounds) = (format!("{x:e}"), format!("[{lo}, {hi:e}]"));
            let message = out_of("singular_condition", value, bounds, why, "0.1/√tolerance");
            return Err(cx.invalid(v, message));
        }
        solver.singular_condition = Some(x);
    }
    if let Some(v) = &def.closed_form {
        solver.closed_form = *v.get_ref();
    }
    Ok(solver)
}
