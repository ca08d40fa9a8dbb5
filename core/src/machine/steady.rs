//! The steady periodic state: the energy `E₀` at the start angle φ₀ whose turn in the energy
//! form ends with the same energy, `E(φ₀ + 2π; E₀) = E₀`, found by shooting — a bracket of
//! start energies whose turns gain and lose energy, narrowed by the Illinois variant of
//! regula falsi — not by running until the motion looks steady.
//!
//! The mean speed is given both ways: the time mean `ω_m = 2π/T` (T the period, equal to
//! `(1/T)∫ω dt`) and the mid-range `(ω_max + ω_min)/2`; the coefficient of speed fluctuation
//! `δ = (ω_max − ω_min)/ω_mean` with each.

use super::angle::{AngleSample, integrate};
use super::equation::Machine;
use super::error::MotionError;
use super::integrate::Tolerances;
use super::time::{Start, Stop, simulate};
use crate::geometry::DriveKind;
use std::f64::consts::TAU;

/// How the steady state is searched.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteadySettings {
    /// Start angle φ₀ of the periodic turn (rad).
    pub phi: f64,
    /// A speed near the steady one (rad/s at the drive); `None`: 95 % of the motor's
    /// no-load (or synchronous) speed through the gearbox.
    pub guess: Option<f64>,
    /// The most turns the search integrates (each trial start energy is one turn).
    pub max_turns: usize,
    /// Relative width of the bracket of start energies that ends the search.
    pub tolerance: f64,
    /// Error control of each turn.
    pub tolerances: Tolerances,
}

impl Default for SteadySettings {
    /// From φ₀ = 0, at most 200 turns, start energy to 1e-13 relative, turns integrated
    /// with relative and absolute tolerance 1e-12.
    fn default() -> Self {
        SteadySettings {
            phi: 0.0,
            guess: None,
            max_turns: 200,
            tolerance: 1e-13,
            tolerances: Tolerances::default()
                .with_relative(1e-12)
                .with_absolute(1e-12),
        }
    }
}

/// The steady periodic state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteadyState {
    /// Start angle φ₀.
    pub phi: f64,
    /// Speed at φ₀ (rad/s).
    pub omega: f64,
    /// Period `T` of one turn (s).
    pub period: f64,
    /// Lowest speed and its angle.
    pub min: (f64, f64),
    /// Highest speed and its angle.
    pub max: (f64, f64),
    /// Time-mean speed `2π/T`.
    pub mean_time: f64,
    /// Mid-range speed `(ω_max + ω_min)/2`.
    pub mean_mid: f64,
    /// `δ = (ω_max − ω_min)/(2π/T)`.
    pub delta_time: f64,
    /// `δ = (ω_max − ω_min)/((ω_max + ω_min)/2)`.
    pub delta_mid: f64,
    /// Energy gained over the reported turn, `E(φ₀ + 2π) − E₀` (J): the periodicity reached.
    pub gain: f64,
    /// Turns integrated by the search (the reported turn included).
    pub turns: usize,
    /// Evaluations of the equation of motion (the check in time included).
    pub evaluations: usize,
    /// The same turn integrated in time from (φ₀, ω₀), beside the energy form that found it.
    pub in_time: InTimeCheck,
}

/// The periodic turn of a [`SteadyState`], found in the energy form (E and t over φ), run
/// again in time ((φ, φ̇) over t) from the same start: the two formulations side by side.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InTimeCheck {
    /// The time form's duration of the turn from φ₀ to φ₀ + 2π (s).
    pub period: f64,
    /// The time form's speed back at φ₀ + 2π (rad/s).
    pub omega: f64,
}

impl SteadyState {
    /// `|T_time − T|/T`: the formulations' agreement on the period.
    pub fn period_agreement(&self) -> f64 {
        (self.in_time.period - self.period).abs() / self.period
    }

    /// `|ω_time(φ₀ + 2π) − ω₀|/ω₀`: how closely the time form returns to the periodic
    /// start speed.
    pub fn speed_agreement(&self) -> f64 {
        (self.in_time.omega - self.omega).abs() / self.omega
    }
}

/// The steady periodic state of `machine`; the samples of the periodic turn (φ, t, ω, E)
/// go to `sink`.
///
/// # Errors
/// [`MotionError::MissingData`] for a drive that is not an angle or without a guess speed
/// where the motor has no no-load speed; [`MotionError::NoSteadyState`] when no start
/// energy of a periodic turn is bracketed or pinned down within the turns allowed; the
/// integration's errors.
pub fn steady_state(
    machine: &Machine<'_>,
    settings: &SteadySettings,
    sink: &mut dyn FnMut(AngleSample),
) -> Result<SteadyState, MotionError> {
    machine.validate()?;
    settings.tolerances.validate()?;
    if machine.model.mechanism.drive_kind != DriveKind::Angle {
        return Err(MotionError::MissingData {
            what: "a steady periodic state",
            missing: "an angle drive (a crank that turns)",
        });
    }
    if !(settings.tolerance.is_finite() && settings.tolerance > 0.0) {
        return Err(MotionError::InvalidValue {
            what: "steady-state tolerance (must be > 0)",
            value: settings.tolerance,
        });
    }
    if settings.max_turns < 2 || settings.max_turns > 100_000 {
        return Err(MotionError::InvalidValue {
            what: "turns of the steady-state search (must be 2 to 100000)",
            value: settings.max_turns as f64,
        });
    }
    let guess = match settings.guess {
        Some(w) if w.is_finite() && w > 0.0 => w,
        Some(w) => {
            return Err(MotionError::InvalidValue {
                what: "guess speed (must be > 0)",
                value: w,
            });
        }
        None => match machine.motor.as_ref().and_then(|c| c.no_load_speed()) {
            Some(w) if w > 0.0 => 0.95 * w * machine.ratio().abs(),
            _ => {
                return Err(MotionError::MissingData {
                    what: "a steady state of this motor",
                    missing: "a guess of the speed",
                });
            }
        },
    };
    let phi0 = settings.phi;
    let mut t = machine.tracker()?;
    let j0 = machine.state(&mut t, phi0, guess)?.reduced_inertia;
    let mut tracker = Some(t);
    let mut turns = 0;
    let mut evaluations = 0;
    // The energy gained over one turn from start energy `e`; `None`: the machine stalls.
    let mut gain = |e: f64, turns: &mut usize| -> Result<Option<f64>, MotionError> {
        *turns += 1;
        let r = integrate(
            machine,
            &mut tracker,
            phi0,
            e,
            0.0,
            phi0 + TAU,
            &settings.tolerances,
            false,
            &mut |_| {},
        );
        match r {
            Ok(run) => {
                evaluations += run.evaluations;
                Ok(Some(run.end.energy - e))
            }
            Err(MotionError::Stalled { .. }) => Ok(None),
            Err(e) => Err(e),
        }
    };
    let energy = |w: f64| 0.5 * j0 * w * w;
    let no_steady = |turns, g: Option<f64>, e: f64, reason| MotionError::NoSteadyState {
        turns,
        gain: g.unwrap_or(f64::NEG_INFINITY),
        omega: (2.0 * e / j0).sqrt(),
        reason,
    };
    // A bracket: `lo` gains energy, `hi` loses it (or stalls).
    let e_guess = energy(guess);
    let g_guess = gain(e_guess, &mut turns)?;
    let (mut lo, mut hi) = match g_guess {
        Some(g) if g > 0.0 => ((e_guess, g), (f64::NAN, None)),
        Some(g) if g == 0.0 => ((e_guess, g), (e_guess, Some(g))),
        other => ((f64::NAN, 0.0), (e_guess, other)),
    };
    while lo.0.is_nan() || hi.0.is_nan() {
        if turns >= settings.max_turns {
            let (e, g) = if lo.0.is_nan() {
                hi
            } else {
                (lo.0, Some(lo.1))
            };
            return Err(no_steady(
                turns,
                g,
                e,
                "no start speed that gains and one that loses energy",
            ));
        }
        if lo.0.is_nan() {
            if hi.0 < 1e-6 * e_guess {
                return Err(no_steady(
                    turns,
                    hi.1,
                    hi.0,
                    "every turn loses energy down to 1/1000 of the guess speed",
                ));
            }
            let e = hi.0 / 2.25;
            match gain(e, &mut turns)? {
                Some(g) if g > 0.0 => lo = (e, g),
                other => hi = (e, other),
            }
        } else {
            if lo.0 > 1e6 * e_guess {
                return Err(no_steady(
                    turns,
                    Some(lo.1),
                    lo.0,
                    "every turn gains energy up to 1000 times the guess speed",
                ));
            }
            let e = lo.0 * 2.25;
            match gain(e, &mut turns)? {
                Some(g) if g > 0.0 => lo = (e, g),
                other => hi = (e, other),
            }
            if !hi.0.is_nan() && hi.1.is_none() {
                return Err(no_steady(
                    turns,
                    None,
                    e,
                    "the machine stalls above a speed at which it gains energy",
                ));
            }
        }
    }
    // Illinois on the bracket.
    let mut side = 0;
    while hi.0 - lo.0 > settings.tolerance * hi.0 && lo.1 != 0.0 {
        if turns >= settings.max_turns {
            return Err(no_steady(
                turns,
                hi.1,
                hi.0,
                "the start energy is not pinned down within the turns",
            ));
        }
        let e = match hi.1 {
            Some(gh) => {
                let e = (lo.0 * gh - hi.0 * lo.1) / (gh - lo.1);
                if e > lo.0 && e < hi.0 {
                    e
                } else {
                    0.5 * (lo.0 + hi.0)
                }
            }
            None => 0.5 * (lo.0 + hi.0),
        };
        match gain(e, &mut turns)? {
            Some(g) if g > 0.0 => {
                lo = (e, g);
                if side == -1
                    && let Some(gh) = hi.1.as_mut()
                {
                    *gh *= 0.5;
                }
                side = -1;
            }
            Some(g) if g == 0.0 => {
                lo = (e, g);
                hi = (e, Some(g));
            }
            other => {
                hi = (e, other);
                if side == 1 {
                    lo.1 *= 0.5;
                }
                side = 1;
            }
        }
    }
    // The start energy: the end of the bracket with the smaller gain.
    let e0 = match hi.1 {
        Some(gh) if gh.abs() < lo.1.abs() => hi.0,
        _ => lo.0,
    };
    turns += 1;
    let run = integrate(
        machine,
        &mut tracker,
        phi0,
        e0,
        0.0,
        phi0 + TAU,
        &settings.tolerances,
        true,
        sink,
    )?;
    evaluations += run.evaluations;
    let x = run.extremes;
    let period = run.end.time;
    let mean_time = TAU / period;
    let mean_mid = 0.5 * (x.max.0 + x.min.0);
    let swing = x.max.0 - x.min.0;
    let omega0 = (2.0 * e0 / j0).sqrt();
    let start = Start {
        time: 0.0,
        phi: phi0,
        omega: omega0,
    };
    let one_turn = Stop {
        turns: Some(1.0),
        ..Stop::default()
    };
    let again = simulate(machine, start, &one_turn, &settings.tolerances, &mut |_| {})?;
    evaluations += again.evaluations;
    Ok(SteadyState {
        phi: phi0,
        omega: omega0,
        period,
        min: x.min,
        max: x.max,
        mean_time,
        mean_mid,
        delta_time: swing / mean_time,
        delta_mid: swing / mean_mid,
        gain: run.end.energy - e0,
        turns,
        evaluations,
        in_time: InTimeCheck {
            period: again.last_period.unwrap_or(again.end.time),
            omega: again.end.omega,
        },
    })
}
