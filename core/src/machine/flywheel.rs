//! The flywheel that brings the coefficient of speed fluctuation δ to a requested value,
//! two ways side by side.
//!
//! **Exact**: the steady periodic state with the motor is found for a flywheel `J_f`
//! ([`super::steady_state`]), and `J_f` is iterated (secant steps on `1/δ(J_f)`, nearly
//! linear in `J_f`) until δ is the one requested.
//!
//! **Classic energy method**: the turning-moment diagram at constant speed `ω_m` (today's
//! prescribed-speed kinetostatics, `M_drive(φ, ω_m, 0)`, inertia torques of the mechanism at
//! that speed included) against a constant motor torque equal to its mean; the largest
//! swing of the work difference `ΔE_max = max W − min W`, `W(φ) = ∫(M̄ − M_drive) dφ`, gives
//! `J = ΔE_max/(δ ω_m²)`, from which the rotor (`J_d/τ²`) and the mechanism's mean reduced
//! inertia are taken off. It holds the speed constant where the torques are computed, the
//! motor torque constant (a motor whose torque falls with speed damps the fluctuation) and
//! the inertia constant (the varying `J_m(φ)` exchanges energy with the flywheel): the exact
//! result differs by those three.

use super::angle::AngleSample;
use super::equation::Machine;
use super::error::MotionError;
use super::steady::{SteadySettings, SteadyState, steady_state};
use crate::DriveState;
use crate::dynamics::{Effects, kinetostatics};
use std::f64::consts::TAU;

/// Which mean speed δ is taken against.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeanSpeed {
    /// The time mean `2π/T`.
    Time,
    /// The mid-range `(ω_max + ω_min)/2` (the textbooks' δ).
    MidRange,
}

/// Points of the classic method's turning-moment diagram over one turn.
const DIAGRAM_POINTS: usize = 3600;

/// The most flywheel iterations.
const MAX_ITERATIONS: usize = 40;

/// A flywheel sized both ways.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlywheelSizing {
    /// The requested δ.
    pub target: f64,
    /// Flywheel inertia from the periodic solution with the motor (kg·m²); 0 when the
    /// machine without flywheel already runs within δ.
    pub exact: f64,
    /// The steady state with the exact flywheel.
    pub steady: SteadyState,
    /// Flywheel inertia by the classic energy method (kg·m², may be negative: no flywheel
    /// needed by that method).
    pub classic: f64,
    /// The largest swing of the work difference `ΔE_max` of the classic method (J).
    pub energy_swing: f64,
    /// The mean speed of both methods (the exact steady state's, by the chosen mean).
    pub mean_speed: f64,
    /// Steady states computed.
    pub iterations: usize,
}

/// Sizes the flywheel of `machine` (replacing its flywheel) for δ = `target` against the
/// mean speed `mean`, with the steady states searched by `settings`.
///
/// # Errors
/// [`MotionError::InvalidValue`] for a target not in (0, 2); [`MotionError::Flywheel`] when
/// the iteration does not meet the target; the errors of [`steady_state`] and of the
/// kinetostatics.
pub fn flywheel(
    machine: &Machine<'_>,
    target: f64,
    mean: MeanSpeed,
    settings: &SteadySettings,
) -> Result<FlywheelSizing, MotionError> {
    if !(target.is_finite() && target > 0.0 && target < 2.0) {
        return Err(MotionError::InvalidValue {
            what: "coefficient of speed fluctuation (must be in (0, 2))",
            value: target,
        });
    }
    let delta = |s: &SteadyState| match mean {
        MeanSpeed::Time => s.delta_time,
        MeanSpeed::MidRange => s.delta_mid,
    };
    let mean_of = |s: &SteadyState| match mean {
        MeanSpeed::Time => s.mean_time,
        MeanSpeed::MidRange => s.mean_mid,
    };
    let solve = |j: f64| {
        let m = machine.clone().with_flywheel(j);
        steady_state(&m, settings, &mut |_: AngleSample| {})
    };
    let mut iterations = 1;
    let mut a = (0.0, solve(0.0)?);
    let (classic, _) = classic(machine, mean_of(&a.1), target)?;
    let sized = |exact, steady: SteadyState, iterations| -> Result<FlywheelSizing, MotionError> {
        let (classic, energy_swing) = self::classic(machine, mean_of(&steady), target)?;
        Ok(FlywheelSizing {
            target,
            exact,
            steady,
            classic,
            energy_swing,
            mean_speed: mean_of(&steady),
            iterations,
        })
    };
    if delta(&a.1) <= target {
        return sized(0.0, a.1, iterations);
    }
    // g(J) = 1/δ(J) − 1/δ_target, nearly linear in J.
    let g = |s: &SteadyState| 1.0 / delta(s) - 1.0 / target;
    let mut j = if classic > 0.0 {
        classic
    } else {
        // The machine's own reduced inertia as the first trial.
        let mut t = machine.tracker()?;
        machine
            .state(&mut t, settings.phi, a.1.mean_time)?
            .reduced_inertia
    };
    for _ in 0..MAX_ITERATIONS {
        iterations += 1;
        let b = (j, solve(j)?);
        if ((delta(&b.1) / target) - 1.0).abs() <= 1e-10 {
            return sized(j, b.1, iterations);
        }
        let (ga, gb) = (g(&a.1), g(&b.1));
        let mut next = if gb != ga {
            b.0 - gb * (b.0 - a.0) / (gb - ga)
        } else {
            2.0 * b.0
        };
        if !(next.is_finite() && next > 0.0) {
            next = 0.5 * b.0;
        }
        a = b;
        j = next;
    }
    Err(MotionError::Flywheel {
        target,
        reached: delta(&a.1),
        inertia: a.0,
        iterations,
    })
}

/// The classic energy method at mean speed `omega` for δ = `target`: (flywheel inertia,
/// `ΔE_max`).
fn classic(machine: &Machine<'_>, omega: f64, target: f64) -> Result<(f64, f64), MotionError> {
    let mut tracker = machine.tracker()?;
    let effects = Effects {
        motor: false,
        ..machine.effects
    };
    let h = TAU / DIAGRAM_POINTS as f64;
    let mut torque = Vec::with_capacity(DIAGRAM_POINTS + 1);
    let mut inertia = 0.0;
    for i in 0..=DIAGRAM_POINTS {
        let phi = i as f64 * h;
        let s = machine.state(&mut tracker, phi, omega)?;
        let at = |source| MotionError::Mechanism {
            phi,
            time: f64::NAN,
            source,
        };
        let k = tracker.kinematics::<2>().map_err(at)?;
        let d = DriveState::constant_speed(omega);
        let m = kinetostatics::solve_at(&machine.model, &effects, phi, &k.coordinates, &d)
            .map_err(at)?
            .drive_torque;
        torque.push(m);
        if i < DIAGRAM_POINTS {
            inertia += s.reduced_inertia - machine.flywheel;
        }
    }
    let mean_inertia = inertia / DIAGRAM_POINTS as f64;
    let mean_torque = torque[..DIAGRAM_POINTS].iter().sum::<f64>() / DIAGRAM_POINTS as f64;
    // W(φ) by the trapezoidal rule.
    let (mut w, mut lo, mut hi) = (0.0f64, 0.0f64, 0.0f64);
    for pair in torque.windows(2) {
        w += h * (mean_torque - 0.5 * (pair[0] + pair[1]));
        lo = lo.min(w);
        hi = hi.max(w);
    }
    let swing = hi - lo;
    Ok((swing / (target * omega * omega) - mean_inertia, swing))
}
