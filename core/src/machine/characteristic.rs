//! Motor characteristics: the torque a motor delivers on its own shaft as a function of its
//! speed, `M_motor(ω_d)`, behind the gearbox of [`crate::dynamics::Motor`] (or at the drive
//! joint itself when the model has no motor).
//!
//! A prescribed drive speed, the behaviour of [`crate::dynamics::run`], is not a
//! characteristic: it stays what dynamics does; a characteristic is what lets the speed
//! follow from the equation of motion ([`super::Machine`]).

use super::error::MotionError;

/// The most points a [`TorqueTable`] may have.
pub const MAX_TABLE_POINTS: usize = 10_000;

/// Torque on the motor shaft against the motor's speed.
///
/// ```
/// use mechdiff_core::machine::Characteristic;
/// // Kloss: 0 at synchronous speed, the breakdown torque at the breakdown slip, and a
/// // braking (negative) torque above synchronous speed.
/// let m = Characteristic::Induction { synchronous_speed: 157.08, breakdown_torque: 40.0, breakdown_slip: 0.2 };
/// assert_eq!(m.torque(157.08), 0.0);
/// assert!((m.torque(157.08 * 0.8) - 40.0).abs() < 1e-12);
/// assert!(m.torque(160.0) < 0.0);
/// ```
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Characteristic {
    /// The same torque `M₀` (N·m) at every speed.
    ConstantTorque {
        /// Torque (N·m).
        torque: f64,
    },
    /// A DC shunt motor: `M = M_s·(1 − ω/ω₀)`, negative above the no-load speed.
    Linear {
        /// Torque at standstill `M_s` (N·m).
        stall_torque: f64,
        /// Speed without load `ω₀` (rad/s, > 0).
        no_load_speed: f64,
    },
    /// An induction motor by the Kloss formula, `M = 2 M_k / (s/s_k + s_k/s)` with the slip
    /// `s = (ω_s − ω)/ω_s`, written `M = 2 M_k s s_k / (s² + s_k²)` (no division by `s`): 0 at
    /// synchronous speed and a braking torque above it (generator), never clamped.
    Induction {
        /// Synchronous speed `ω_s` (rad/s, > 0).
        synchronous_speed: f64,
        /// Breakdown (pull-out) torque `M_k` (N·m, > 0).
        breakdown_torque: f64,
        /// Breakdown slip `s_k ∈ (0, 1]`.
        breakdown_slip: f64,
    },
    /// A measured torque–speed curve (see [`TorqueTable`]).
    Table(TorqueTable),
}

impl Characteristic {
    /// The torque (N·m) at motor speed `speed` (rad/s).
    pub fn torque(&self, speed: f64) -> f64 {
        match self {
            Characteristic::ConstantTorque { torque } => *torque,
            Characteristic::Linear {
                stall_torque,
                no_load_speed,
            } => stall_torque * (1.0 - speed / no_load_speed),
            Characteristic::Induction {
                synchronous_speed,
                breakdown_torque,
                breakdown_slip,
            } => {
                let s = (synchronous_speed - speed) / synchronous_speed;
                2.0 * breakdown_torque * s * breakdown_slip
                    / (s * s + breakdown_slip * breakdown_slip)
            }
            Characteristic::Table(t) => t.torque(speed),
        }
    }

    /// The speed (rad/s) at which the torque vanishes, where the characteristic has one: the
    /// no-load speed, the synchronous speed, or the first zero of a table.
    pub fn no_load_speed(&self) -> Option<f64> {
        match self {
            Characteristic::ConstantTorque { .. } => None,
            Characteristic::Linear { no_load_speed, .. } => Some(*no_load_speed),
            Characteristic::Induction {
                synchronous_speed, ..
            } => Some(*synchronous_speed),
            Characteristic::Table(t) => t.zero(),
        }
    }

    /// Checks the numbers.
    ///
    /// # Errors
    /// [`MotionError::InvalidValue`] naming the number that is out of its range.
    pub fn validate(&self) -> Result<(), MotionError> {
        let check = |what: &'static str, value: f64, ok: bool| {
            if value.is_finite() && ok {
                Ok(())
            } else {
                Err(MotionError::InvalidValue { what, value })
            }
        };
        match *self {
            Characteristic::ConstantTorque { torque } => check("motor torque", torque, true),
            Characteristic::Linear {
                stall_torque,
                no_load_speed,
            } => {
                check("stall torque of the motor", stall_torque, true)?;
                check(
                    "no-load speed of the motor (must be > 0)",
                    no_load_speed,
                    no_load_speed > 0.0,
                )
            }
            Characteristic::Induction {
                synchronous_speed,
                breakdown_torque,
                breakdown_slip,
            } => {
                check(
                    "synchronous speed of the motor (must be > 0)",
                    synchronous_speed,
                    synchronous_speed > 0.0,
                )?;
                check(
                    "breakdown torque of the motor (must be > 0)",
                    breakdown_torque,
                    breakdown_torque > 0.0,
                )?;
                check(
                    "breakdown slip of the motor (must be in (0, 1])",
                    breakdown_slip,
                    breakdown_slip > 0.0 && breakdown_slip <= 1.0,
                )
            }
            Characteristic::Table(_) => Ok(()),
        }
    }
}

/// A torque–speed curve given by points: linear interpolation between neighbouring points,
/// and outside the table the first and last segments extended as straight lines (so a curve
/// that falls through zero keeps falling: a braking torque above its no-load speed).
///
/// ```
/// use mechdiff_core::machine::TorqueTable;
/// let t = TorqueTable::new(vec![0.0, 100.0, 150.0], vec![30.0, 20.0, 0.0]).unwrap();
/// assert_eq!(t.torque(50.0), 25.0);
/// assert_eq!(t.torque(160.0), -4.0); // the last segment extended
/// assert!(TorqueTable::new(vec![0.0, 0.0], vec![1.0, 2.0]).is_err()); // not increasing
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct TorqueTable {
    speeds: Vec<f64>,
    torques: Vec<f64>,
}

impl TorqueTable {
    /// A table of `torques` (N·m) at `speeds` (rad/s).
    ///
    /// # Errors
    /// [`MotionError::Table`] when the columns differ in length, have fewer than 2 or more
    /// than [`MAX_TABLE_POINTS`] points, hold a number that is not finite, or the speeds do
    /// not increase strictly.
    pub fn new(speeds: Vec<f64>, torques: Vec<f64>) -> Result<Self, MotionError> {
        let bad = |reason: String| Err(MotionError::Table { reason });
        if speeds.len() != torques.len() {
            return bad(format!(
                "{} speeds but {} torques",
                speeds.len(),
                torques.len()
            ));
        }
        if !(2..=MAX_TABLE_POINTS).contains(&speeds.len()) {
            return bad(format!(
                "{} points; a table needs 2 to {MAX_TABLE_POINTS}",
                speeds.len()
            ));
        }
        if let Some(i) =
            (0..speeds.len()).find(|&i| !(speeds[i].is_finite() && torques[i].is_finite()))
        {
            return bad(format!(
                "point {} (speed {}, torque {}) is not finite",
                i + 1,
                speeds[i],
                torques[i]
            ));
        }
        if let Some(i) = (1..speeds.len()).find(|&i| speeds[i] <= speeds[i - 1]) {
            return bad(format!(
                "the speeds must increase: point {} ({}) after point {} ({})",
                i + 1,
                speeds[i],
                i,
                speeds[i - 1]
            ));
        }
        Ok(TorqueTable { speeds, torques })
    }

    /// The table's points `(speed, torque)` (rad/s, N·m), in increasing speed.
    pub fn points(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.speeds
            .iter()
            .copied()
            .zip(self.torques.iter().copied())
    }

    /// The interpolated torque at `speed`.
    pub fn torque(&self, speed: f64) -> f64 {
        let n = self.speeds.len();
        // The segment [i − 1, i] holding `speed`, the end segments beyond the table.
        let i = self.speeds.partition_point(|&s| s < speed).clamp(1, n - 1);
        let (s0, s1) = (self.speeds[i - 1], self.speeds[i]);
        let (m0, m1) = (self.torques[i - 1], self.torques[i]);
        m0 + (m1 - m0) * (speed - s0) / (s1 - s0)
    }

    /// The first speed at which the interpolated torque falls to zero from above, if any.
    fn zero(&self) -> Option<f64> {
        (1..self.speeds.len()).find_map(|i| {
            let (m0, m1) = (self.torques[i - 1], self.torques[i]);
            (m0 > 0.0 && m1 <= 0.0).then(|| {
                self.speeds[i - 1] + (self.speeds[i] - self.speeds[i - 1]) * m0 / (m0 - m1)
            })
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Kloss: the maximum over slip is the breakdown torque at the breakdown slip, the
    /// torque is odd in the slip (generator above synchronous speed).
    #[test]
    fn kloss_peaks_at_the_breakdown_slip_and_is_odd_in_the_slip() {
        let ws = 100.0;
        let m = Characteristic::Induction {
            synchronous_speed: ws,
            breakdown_torque: 50.0,
            breakdown_slip: 0.25,
        };
        let peak = (0..=1000)
            .map(|i| m.torque(ws * (1.0 - f64::from(i) / 1000.0)))
            .fold(f64::MIN, f64::max);
        assert!((peak - 50.0).abs() < 1e-12, "{peak}");
        for s in [0.01, 0.1, 0.5, 1.0] {
            let (below, above) = (m.torque(ws * (1.0 - s)), m.torque(ws * (1.0 + s)));
            assert!((below + above).abs() < 1e-12 * below.abs(), "{s}");
        }
    }

    /// A linear characteristic changes sign at its no-load speed.
    #[test]
    fn linear_characteristic_brakes_above_no_load_speed() {
        let m = Characteristic::Linear {
            stall_torque: 10.0,
            no_load_speed: 50.0,
        };
        assert_eq!((m.torque(0.0), m.torque(50.0)), (10.0, 0.0));
        // 10·(1 − 60/50) = −2, to rounding (60/50 is not exact in binary).
        assert!((m.torque(60.0) + 2.0).abs() < 1e-14);
        assert_eq!(m.no_load_speed(), Some(50.0));
    }

    /// Bad tables and numbers are refused with what is wrong.
    #[test]
    fn bad_tables_and_numbers_are_refused() {
        let e = TorqueTable::new(vec![0.0, 1.0, f64::NAN], vec![1.0; 3]).unwrap_err();
        assert!(e.to_string().contains("point 3"), "{e}");
        assert!(TorqueTable::new(vec![0.0], vec![1.0]).is_err());
        assert!(TorqueTable::new(vec![0.0, 1.0], vec![1.0]).is_err());
        let m = Characteristic::Induction {
            synchronous_speed: 100.0,
            breakdown_torque: 1.0,
            breakdown_slip: 0.0,
        };
        assert!(matches!(
            m.validate(),
            Err(MotionError::InvalidValue { .. })
        ));
    }
}
