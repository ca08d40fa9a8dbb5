//! The words of a run with `[simulate]`: its quantities in the scene's units, its errors
//! placed in the scene, and its headline numbers.

use mechdiff_core::machine::{FlywheelSizing, MeanSpeed, MotionError, SteadyState};

use crate::error::{Error, Location};
use crate::scene::error_context::ErrorContext;
use crate::scene::model::DriveKind;
use crate::scene::outputs::Column;
use crate::scene::units::{Dimension, Units};

use super::model::SceneMotion;

/// A column of `name` in `unit`, `factor` SI per unit.
pub(crate) fn column(name: &str, unit: &str, factor: f64) -> Column {
    Column {
        name: name.to_owned(),
        unit: unit.to_owned(),
        factor,
    }
}

/// The scene's words for the machine's quantities.
pub(crate) struct Words<'a> {
    pub cx: &'a ErrorContext<'a>,
    pub drive: DriveKind,
}

impl Words<'_> {
    pub(crate) fn units(&self) -> &Units {
        &self.cx.units
    }

    pub(crate) fn of(&self, dimension: Dimension) -> Column {
        column(
            "",
            self.units().symbol(dimension),
            self.units().factor(dimension),
        )
    }

    pub(crate) fn named(&self, name: &str, dimension: Dimension) -> Column {
        Column {
            name: name.to_owned(),
            ..self.of(dimension)
        }
    }

    /// `value` (SI) of `dimension` in the scene's unit, to 7 significant digits.
    pub(crate) fn text(&self, value: f64, dimension: Dimension) -> String {
        let v = self.units().from_si(value, dimension);
        format!("{} {}", significant(v), self.units().symbol(dimension))
    }

    pub(crate) fn speed(&self, value: f64) -> String {
        self.text(value, self.drive.speed_dimension())
    }

    pub(crate) fn position(&self, value: f64) -> String {
        self.text(value, self.drive.dimension())
    }

    pub(crate) fn drive_torque(&self) -> Dimension {
        match self.drive {
            DriveKind::Angle => Dimension::Torque,
            DriveKind::Displacement => Dimension::Force,
        }
    }

    pub(crate) fn inertia(&self) -> Dimension {
        match self.drive {
            DriveKind::Angle => Dimension::MomentOfInertia,
            DriveKind::Displacement => Dimension::Mass,
        }
    }
}

/// `v` to 7 significant digits, without trailing zeros.
pub(crate) fn significant(v: f64) -> String {
    match format!("{v:.6e}").parse::<f64>() {
        Ok(r) => Units::tidy(r),
        Err(_) => v.to_string(),
    }
}

/// The engine's `error` in `analysis`, placed at `location`, with its drive position in the
/// scene's units.
pub(crate) fn motion_error(
    w: &Words<'_>,
    analysis: &'static str,
    location: &Location,
    error: MotionError,
) -> Error {
    let (phi, time) = match &error {
        MotionError::Mechanism { phi, time, .. } | MotionError::Stalled { phi, time } => {
            (Some(*phi), Some(*time))
        }
        MotionError::NoInertia { phi, .. }
        | MotionError::NoConsistentAcceleration { phi, .. }
        | MotionError::NonFinite { phi, .. }
        | MotionError::CannotStart { phi, .. } => (Some(*phi), None),
        MotionError::TooManySteps { phi, time, .. } => (Some(*phi), Some(*time)),
        _ => (None, None),
    };
    let mut position = String::new();
    if let Some(phi) = phi.filter(|p| p.is_finite()) {
        position = format!(" at drive position {}", w.position(phi));
        if let Some(t) = time.filter(|t| t.is_finite()) {
            position.push_str(&format!(", t = {} s", significant(t)));
        }
    }
    if let MotionError::NotReached {
        speed,
        reached,
        reached_as,
        ..
    } = &error
    {
        // The speeds in the scene's unit, and the way out.
        position = format!(
            " ({} not reached; {reached_as} {}: allow more `time`, or ask for a speed the \
             machine reaches)",
            w.speed(*speed),
            w.speed(*reached)
        );
    }
    Error::Motion {
        location: location.clone(),
        analysis,
        position,
        source: Box::new(error),
    }
}

/// The steady state's headline numbers.
pub(crate) fn steady_line(w: &Words<'_>, s: &SteadyState) -> String {
    format!(
        "steady state (from {} at {}): period {} s; ω_min {} at {}, ω_max {} at {}; mean speed \
         {} as the time mean 2π/T and {} as the mid-range (ω_max + ω_min)/2; δ = \
         (ω_max − ω_min)/ω_mean = {} against the time mean, {} against the mid-range \
         ({} turns integrated); the same turn in time from that start: period within {:.1e}, \
         speed back at the start within {:.1e} (relative; the energy and time forms side by \
         side)",
        w.speed(s.omega),
        w.position(s.phi),
        significant(s.period),
        w.speed(s.min.0),
        w.position(s.min.1),
        w.speed(s.max.0),
        w.position(s.max.1),
        w.speed(s.mean_time),
        w.speed(s.mean_mid),
        significant(s.delta_time),
        significant(s.delta_mid),
        s.turns,
        s.period_agreement(),
        s.speed_agreement(),
    )
}

/// The flywheel's headline numbers: exact and classic, and why they differ.
pub(crate) fn flywheel_lines(
    w: &Words<'_>,
    motion: &SceneMotion,
    f: &FlywheelSizing,
) -> Vec<String> {
    let mean = match motion.mean {
        MeanSpeed::Time => "the time mean",
        MeanSpeed::MidRange => "the mid-range speed",
    };
    let inertia = w.inertia();
    let difference = if f.exact > 0.0 {
        format!("{} %", significant(100.0 * (f.classic - f.exact) / f.exact))
    } else {
        "— (no flywheel needed)".to_owned()
    };
    vec![
        format!(
            "flywheel for δ = {} against {} ({}): {} exact (the periodic solution with the \
             motor's characteristic and the varying J(φ), iterated {} times; simulated δ = {}), \
             {} by the classic energy method (ΔE_max = {} J over ω_m² δ, less the rotor and the \
             mean J_m); classic − exact = {}",
            significant(f.target),
            mean,
            w.speed(f.mean_speed),
            w.text(f.exact, inertia),
            f.iterations,
            significant(match motion.mean {
                MeanSpeed::Time => f.steady.delta_time,
                MeanSpeed::MidRange => f.steady.delta_mid,
            }),
            w.text(f.classic, inertia),
            significant(f.energy_swing),
            difference,
        ),
        "  the classic method holds the speed constant where it computes the torques, the \
         motor's torque constant at its mean (a torque that falls with speed damps the \
         fluctuation) and the inertia constant (the varying J_m(φ) exchanges energy with the \
         flywheel); the exact value keeps all three"
            .to_owned(),
    ]
}
