//! Transients in time: the start-up from rest under the motor and the coast-down without it.

use super::equation::Machine;
use super::error::MotionError;
use super::integrate::Tolerances;
use super::time::{Record, Simulation, Start, Stop, StopReason, simulate};

/// A start-up from rest.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StartUp {
    /// Time from rest to the speed asked for (s), located as an event.
    pub time_to_speed: f64,
    /// Drive angle travelled meanwhile.
    pub travel: f64,
    /// Largest characteristic torque on the motor shaft over the accepted steps and events
    /// (N·m); a peak between two steps is not searched.
    pub peak_motor_torque: f64,
    /// The run.
    pub simulation: Simulation,
}

/// Starts `machine` from rest at `phi` until its drive speed reaches `speed` (> 0), within
/// `max_time` seconds; every record goes to `sink`.
///
/// # Errors
/// [`MotionError::CannotStart`] when the motor's standstill torque does not accelerate the
/// machine at `phi`, [`MotionError::Stalled`] when it comes to rest on the way,
/// [`MotionError::NotReached`] when the speed is not reached in time, and the errors of
/// [`simulate`].
pub fn start_up(
    machine: &Machine<'_>,
    phi: f64,
    speed: f64,
    max_time: f64,
    tolerances: &Tolerances,
    sink: &mut dyn FnMut(Record),
) -> Result<StartUp, MotionError> {
    if !(speed.is_finite() && speed > 0.0) {
        return Err(MotionError::InvalidValue {
            what: "start-up speed (must be > 0)",
            value: speed,
        });
    }
    machine.validate()?;
    let mut tracker = machine.tracker()?;
    let rest = machine.state(&mut tracker, phi, 0.0)?;
    if rest.alpha.is_nan() || rest.alpha <= 0.0 {
        return Err(MotionError::CannotStart {
            phi,
            motor_torque: rest.motor_torque,
            alpha: rest.alpha,
        });
    }
    let stop = Stop {
        time: Some(max_time),
        speed: Some(speed),
        ..Stop::default()
    };
    let s = simulate(machine, Start::at_rest(phi), &stop, tolerances, sink)?;
    match s.reason {
        StopReason::Speed => Ok(StartUp {
            time_to_speed: s.end.time,
            travel: s.end.phi - phi,
            peak_motor_torque: s.peak_motor_torque,
            simulation: s,
        }),
        StopReason::Rest => Err(MotionError::Stalled {
            phi: s.end.phi,
            time: s.end.time,
        }),
        _ => Err(MotionError::NotReached {
            speed,
            limit: format!("{max_time} s"),
            reached: s.max_speed,
            reached_as: "the highest was",
        }),
    }
}

/// A coast-down.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoastDown {
    /// Time from the start to the end speed (s).
    pub time: f64,
    /// Turns travelled meanwhile (drive angle / 2π).
    pub turns: f64,
    /// The run.
    pub simulation: Simulation,
}

/// Lets `machine` run out without motor torque from `start` until its speed falls to
/// `speed` (`None`: to rest), within `max_time` seconds; every record goes to `sink`.
///
/// # Errors
/// [`MotionError::NotReached`] when the speed is not reached in time, and the errors of
/// [`simulate`].
pub fn coast_down(
    machine: &Machine<'_>,
    start: Start,
    speed: Option<f64>,
    max_time: f64,
    tolerances: &Tolerances,
    sink: &mut dyn FnMut(Record),
) -> Result<CoastDown, MotionError> {
    let coasting = machine.clone().without_motor();
    let stop = Stop {
        time: Some(start.time + max_time),
        speed,
        ..Stop::default()
    };
    let s = simulate(&coasting, start, &stop, tolerances, sink)?;
    match s.reason {
        StopReason::Speed | StopReason::Rest => Ok(CoastDown {
            time: s.end.time - start.time,
            turns: (s.end.phi - start.phi) / std::f64::consts::TAU,
            simulation: s,
        }),
        _ => Err(MotionError::NotReached {
            speed: speed.unwrap_or(0.0),
            limit: format!("{max_time} s"),
            reached: s.end.omega,
            reached_as: "at the end it was",
        }),
    }
}
