//! Checking `[motor] characteristic` and `[simulate]`: values in range and in SI, counts
//! bounded, the analyses' needs met — every error located.

use mechdiff_core::machine::{Characteristic, MeanSpeed, Tolerances, TorqueTable};
use toml::Spanned;

use crate::error::Result;
use crate::scene::context::Context;
use crate::scene::dynamics::MotorDef;
use crate::scene::model::DriveKind;
use crate::scene::units::{Dimension, Units};
use crate::scene::values::Number;

use super::format::{CharacteristicDef, CharacteristicKind, Find, MeanSpeedDef, SimulateDef};
use super::model::SceneMotion;

/// The longest time a start-up or coast-down may simulate (s): over 11 days.
pub const MAX_TIME: f64 = 1e6;
/// The most turns of a steady-state search (the engine's bound).
pub const MAX_TURNS: usize = 100_000;
/// The smallest tolerance per step: below it DOP853's error estimate is rounding.
pub const SMALLEST_TOLERANCE: f64 = 1e-14;
/// The largest tolerance per step.
pub const LARGEST_TOLERANCE: f64 = 1e-3;
/// The most integration steps of one run.
pub const MAX_STEPS: usize = 100_000_000;

/// Checks `[motor] characteristic` and `[simulate]`; `None` without `[simulate]`.
pub(crate) fn resolve(
    cx: &Context,
    motor: Option<&Spanned<MotorDef>>,
    simulate: Option<&Spanned<SimulateDef>>,
    drive: DriveKind,
) -> Result<Option<SceneMotion>> {
    let characteristic = motor.and_then(|m| m.get_ref().characteristic.as_ref());
    let Some(section) = simulate else {
        if let Some(c) = characteristic {
            return Err(cx.invalid(
                c,
                "a motor characteristic drives the machine in a `[simulate]` section, which this \
                 scene does not have; add one (e.g. `[simulate]` with `find = [\"start_up\"]`) \
                 or remove `characteristic`",
            ));
        }
        return Ok(None);
    };
    let s = section.get_ref();
    let Some(c) = characteristic else {
        return Err(cx.invalid(
            section,
            "`[simulate]` needs the motor's characteristic: add `[motor]` with `rotor_inertia`, \
             `ratio` and e.g. `characteristic = { type = \"induction\", synchronous_speed = \
             1500, breakdown_torque = 40, breakdown_slip = 0.25 }`",
        ));
    };
    let mut find: Vec<Find> = s.find.get_ref().iter().map(|f| *f.get_ref()).collect();
    find.sort_by_key(|f| *f as u8);
    find.dedup();
    if find.is_empty() {
        return Err(cx.invalid(
            &s.find,
            "`find` names no analysis; give one or more of \"start_up\", \"steady_state\", \
             \"coast_down\", \"flywheel\"",
        ));
    }
    let periodic = find
        .iter()
        .find(|f| matches!(f, Find::SteadyState | Find::Flywheel));
    if let (Some(f), DriveKind::Displacement) = (periodic, drive) {
        let at = (s.find.get_ref().iter().find(|w| w.get_ref() == f))
            .map_or_else(|| cx.at(&s.find), |w| cx.at(w));
        return Err(crate::error::Error::Invalid {
            location: at,
            message:
                "a steady periodic state (and a flywheel) needs a crank that turns; this scene's \
             drive slides: ask for \"start_up\" or \"coast_down\""
                    .to_owned(),
        });
    }
    let characteristic = self::characteristic(cx, c)?;
    let plain = |v: &Spanned<Number>| -> Result<f64> {
        let x: f64 = cx.value(v)?;
        Ok(x)
    };
    let start = match &s.start {
        Some(v) => cx.number(v, "`start`", drive.dimension())?,
        None => 0.0,
    };
    let speed = match &s.speed {
        Some(v) => Some(cx.positive(v, "`speed`", drive.speed_dimension())?),
        None => None,
    };
    let time = match &s.time {
        Some(v) => {
            let t = plain(v)?;
            if !(t.is_finite() && t > 0.0 && t <= MAX_TIME) {
                return Err(cx.invalid(
                    v,
                    format!(
                        "`time` is the longest simulated time in seconds, > 0 and at most \
                         {MAX_TIME:e} s; found {}",
                        Units::tidy(t)
                    ),
                ));
            }
            t
        }
        None => 60.0,
    };
    let turns = match &s.turns {
        Some(v) => {
            let n = plain(v)?;
            if !(n.is_finite() && n.fract() == 0.0 && (2.0..=MAX_TURNS as f64).contains(&n)) {
                return Err(cx.invalid(
                    v,
                    format!(
                        "`turns` is the most turns the steady-state search integrates, a whole \
                         number from 2 to {MAX_TURNS}; found {}",
                        Units::tidy(n)
                    ),
                ));
            }
            n as usize
        }
        None => 200,
    };
    let flywheel_dimension = match drive {
        DriveKind::Angle => Dimension::MomentOfInertia,
        DriveKind::Displacement => Dimension::Mass,
    };
    let flywheel = match &s.flywheel {
        Some(v) => {
            let j = cx.number(v, "the `flywheel`'s inertia", flywheel_dimension)?;
            if j < 0.0 {
                return Err(cx.invalid(
                    v,
                    format!(
                        "the `flywheel`'s inertia must be ≥ 0, found {} {}; a flywheel adds \
                         inertia",
                        Units::tidy(cx.value::<f64>(v)?),
                        cx.units.symbol(flywheel_dimension)
                    ),
                ));
            }
            j
        }
        None => 0.0,
    };
    let delta = match (&s.delta, find.contains(&Find::Flywheel)) {
        (Some(v), true) => {
            let d = plain(v)?;
            if !(d.is_finite() && d > 0.0 && d < 2.0) {
                return Err(cx.invalid(
                    v,
                    format!(
                        "`delta` is a coefficient of speed fluctuation (ω_max − ω_min)/ω_mean, \
                         > 0 and < 2 (e.g. 0.02); found {}",
                        Units::tidy(d)
                    ),
                ));
            }
            Some(d)
        }
        (None, true) => {
            return Err(cx.invalid(
                &s.find,
                "\"flywheel\" needs the coefficient of speed fluctuation to size it for: add \
                 `delta = 0.02` (for example) to `[simulate]`",
            ));
        }
        (Some(v), false) => {
            return Err(cx.invalid(
                v,
                "`delta` sizes a flywheel: add \"flywheel\" to `find`, or remove `delta`",
            ));
        }
        (None, false) => None,
    };
    let tolerance = match &s.tolerance {
        Some(v) => {
            let t = plain(v)?;
            if !(t.is_finite() && (SMALLEST_TOLERANCE..=LARGEST_TOLERANCE).contains(&t)) {
                return Err(cx.invalid(
                    v,
                    format!(
                        "`tolerance` is the integration's relative and absolute error per step, \
                         from {SMALLEST_TOLERANCE:e} to {LARGEST_TOLERANCE:e}; found {}",
                        Units::tidy(t)
                    ),
                ));
            }
            t
        }
        None => 1e-10,
    };
    let max_steps = match &s.max_steps {
        Some(v) => {
            let n = plain(v)?;
            if !(n.is_finite() && n.fract() == 0.0 && (1.0..=MAX_STEPS as f64).contains(&n)) {
                return Err(cx.invalid(
                    v,
                    format!(
                        "`max_steps` is the most integration steps of one run, a whole number \
                         from 1 to {MAX_STEPS:e}; found {}",
                        Units::tidy(n)
                    ),
                ));
            }
            n as usize
        }
        None => 1_000_000,
    };
    if find.contains(&Find::StartUp) && speed.is_none() && characteristic.no_load_speed().is_none()
    {
        return Err(cx.invalid(
            section,
            "\"start_up\" runs until the drive reaches a speed, and a constant-torque motor has \
             no no-load speed to take it from: add `speed` to `[simulate]`",
        ));
    }
    let at = |v: &Option<Spanned<Number>>| match v {
        Some(v) => cx.at(v),
        None => cx.at(section),
    };
    Ok(Some(SceneMotion {
        characteristic,
        characteristic_at: cx.at(c),
        find,
        start,
        speed,
        time,
        turns,
        flywheel,
        delta,
        mean: match s.mean_speed.as_ref().map(|m| *m.get_ref()) {
            Some(MeanSpeedDef::MidRange) => MeanSpeed::MidRange,
            _ => MeanSpeed::Time,
        },
        tolerances: Tolerances::default()
            .with_relative(tolerance)
            .with_absolute(tolerance)
            .with_max_steps(max_steps),
        location: cx.at(section),
        turns_at: at(&s.turns),
        time_at: at(&s.time),
    }))
}

/// The characteristic `c` in SI: torques in N·m, speeds in rad/s.
fn characteristic(cx: &Context, c: &Spanned<CharacteristicDef>) -> Result<Characteristic> {
    let d = c.get_ref();
    let kind = *d.kind.get_ref();
    let name = match kind {
        CharacteristicKind::Constant => "constant",
        CharacteristicKind::Linear => "linear",
        CharacteristicKind::Induction => "induction",
        CharacteristicKind::Table => "table",
    };
    let fields: [(&str, bool, bool); 8] = [
        (
            "torque",
            d.torque.is_some(),
            kind == CharacteristicKind::Constant,
        ),
        (
            "stall_torque",
            d.stall_torque.is_some(),
            kind == CharacteristicKind::Linear,
        ),
        (
            "no_load_speed",
            d.no_load_speed.is_some(),
            kind == CharacteristicKind::Linear,
        ),
        (
            "synchronous_speed",
            d.synchronous_speed.is_some(),
            kind == CharacteristicKind::Induction,
        ),
        (
            "breakdown_torque",
            d.breakdown_torque.is_some(),
            kind == CharacteristicKind::Induction,
        ),
        (
            "breakdown_slip",
            d.breakdown_slip.is_some(),
            kind == CharacteristicKind::Induction,
        ),
        (
            "speeds",
            d.speeds.is_some(),
            kind == CharacteristicKind::Table,
        ),
        (
            "torques",
            d.torques.is_some(),
            kind == CharacteristicKind::Table,
        ),
    ];
    let needed: Vec<&str> = fields.iter().filter(|f| f.2).map(|f| f.0).collect();
    for (field, given, wanted) in fields {
        if given != wanted {
            let message = if given {
                format!(
                    "a `{name}` characteristic has no `{field}`; it is given by `{}`",
                    needed.join("`, `")
                )
            } else {
                format!(
                    "a `{name}` characteristic needs `{field}` (it is given by `{}`)",
                    needed.join("`, `")
                )
            };
            return Err(cx.invalid(c, message));
        }
    }
    let torque = |v: &Option<Spanned<Number>>, what: &str| -> Result<f64> {
        let v = v.as_ref().expect("checked above");
        cx.number(v, what, Dimension::Torque)
    };
    let speed = |v: &Option<Spanned<Number>>, what: &str| -> Result<f64> {
        let v = v.as_ref().expect("checked above");
        cx.positive(v, what, Dimension::AngularVelocity)
    };
    let result = match kind {
        CharacteristicKind::Constant => Characteristic::ConstantTorque {
            torque: torque(&d.torque, "the motor's `torque`")?,
        },
        CharacteristicKind::Linear => Characteristic::Linear {
            stall_torque: torque(&d.stall_torque, "the motor's `stall_torque`")?,
            no_load_speed: speed(&d.no_load_speed, "the motor's `no_load_speed`")?,
        },
        CharacteristicKind::Induction => {
            let breakdown_torque = torque(&d.breakdown_torque, "the motor's `breakdown_torque`")?;
            let v = d.breakdown_torque.as_ref().expect("checked above");
            if breakdown_torque <= 0.0 {
                return Err(cx.invalid(v, "the motor's `breakdown_torque` must be > 0"));
            }
            let slip = d.breakdown_slip.as_ref().expect("checked above");
            let s: f64 = cx.value(slip)?;
            if !(s.is_finite() && s > 0.0 && s <= 1.0) {
                return Err(cx.invalid(
                    slip,
                    format!(
                        "the motor's `breakdown_slip` is a fraction of the synchronous speed in \
                         (0, 1] (e.g. 0.25); found {}",
                        Units::tidy(s)
                    ),
                ));
            }
            Characteristic::Induction {
                synchronous_speed: speed(&d.synchronous_speed, "the motor's `synchronous_speed`")?,
                breakdown_torque,
                breakdown_slip: s,
            }
        }
        CharacteristicKind::Table => {
            let column = |v: &Option<Spanned<Vec<Spanned<Number>>>>,
                          what: &str,
                          dimension: Dimension|
             -> Result<Vec<f64>> {
                let list = v.as_ref().expect("checked above").get_ref();
                if list.len() > mechdiff_core::machine::characteristic::MAX_TABLE_POINTS {
                    return Err(cx.invalid(
                        v.as_ref().expect("checked above"),
                        format!(
                            "`{what}` has {} points; a table has at most {}",
                            list.len(),
                            mechdiff_core::machine::characteristic::MAX_TABLE_POINTS
                        ),
                    ));
                }
                list.iter()
                    .map(|x| cx.number(x, &format!("a value of `{what}`"), dimension))
                    .collect()
            };
            let speeds = column(&d.speeds, "speeds", Dimension::AngularVelocity)?;
            let torques = column(&d.torques, "torques", Dimension::Torque)?;
            let table = TorqueTable::new(speeds, torques)
                .map_err(|e| cx.invalid(c, format!("the motor's {e}")))?;
            Characteristic::Table(table)
        }
    };
    // The ranges of the numbers, as the engine states them (a second guard).
    result
        .validate()
        .map_err(|e| cx.invalid(c, format!("the motor's characteristic: {e}")))?;
    Ok(result)
}
