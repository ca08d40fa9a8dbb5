//! Units a scene file may declare, and their conversion to and from SI.
//!
//! The engine works in SI (m, rad, s). A scene converts every number it reads at the edge
//! and prints every result back in the same units, with the unit in the column header.

use serde::Deserialize;

/// Length unit (`[units] length`); also fixes the units of linear velocity (per s) and
/// linear acceleration (per s²).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
pub enum LengthUnit {
    /// Metre.
    #[default]
    #[serde(rename = "m")]
    Metre,
    /// Millimetre.
    #[serde(rename = "mm")]
    Millimetre,
}

/// Angle unit (`[units] angle`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
pub enum AngleUnit {
    /// Radian.
    #[default]
    #[serde(rename = "rad")]
    Radian,
    /// Degree.
    #[serde(rename = "deg")]
    Degree,
}

/// Angular velocity unit (`[units] angular_velocity`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
pub enum AngularVelocityUnit {
    /// Radian per second.
    #[default]
    #[serde(rename = "rad/s")]
    RadianPerSecond,
    /// Degree per second.
    #[serde(rename = "deg/s")]
    DegreePerSecond,
    /// Revolutions per minute.
    #[serde(rename = "rpm")]
    Rpm,
}

/// Angular acceleration unit (`[units] angular_acceleration`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
pub enum AngularAccelerationUnit {
    /// Radian per second squared.
    #[default]
    #[serde(rename = "rad/s^2")]
    RadianPerSecondSquared,
    /// Degree per second squared.
    #[serde(rename = "deg/s^2")]
    DegreePerSecondSquared,
}

/// The units in force for one scene: how to read its numbers and print its results.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Units {
    /// Lengths (and linear velocities and accelerations, per s and s²).
    pub length: LengthUnit,
    /// Angles.
    pub angle: AngleUnit,
    /// Angular velocities.
    pub angular_velocity: AngularVelocityUnit,
    /// Angular accelerations.
    pub angular_acceleration: AngularAccelerationUnit,
}

/// The physical dimension of a printed column, which fixes its unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dimension {
    /// A length (m).
    Length,
    /// An angle (rad).
    Angle,
    /// A linear velocity (m/s).
    Velocity,
    /// A linear acceleration (m/s²).
    Acceleration,
    /// An angular velocity (rad/s).
    AngularVelocity,
    /// An angular acceleration (rad/s²).
    AngularAcceleration,
    /// A linear jerk (m/s³).
    Jerk,
    /// An angular jerk (rad/s³), printed in the angular acceleration's angle unit per s³.
    AngularJerk,
}

impl Units {
    /// The units of printed results: the same, except that angular velocities given in rpm
    /// (a unit for a drive speed) are printed in rad/s.
    pub fn for_outputs(&self) -> Units {
        let mut units = *self;
        if units.angular_velocity == AngularVelocityUnit::Rpm {
            units.angular_velocity = AngularVelocityUnit::RadianPerSecond;
        }
        units
    }

    /// A number for messages and the plan line: at most 15 significant digits, so that the
    /// rounding of a unit conversion does not show (`1500 rpm`, not `1500.0000000000002 rpm`).
    /// Magnitudes from 1e15 up and below 1e-6 are written with an exponent (`1e200`).
    pub fn tidy(value: f64) -> String {
        match format!("{value:.14e}").parse::<f64>() {
            Ok(v) if v != 0.0 && !(1e-6..1e15).contains(&v.abs()) => format!("{v:e}"),
            Ok(v) => (v + 0.0).to_string(),
            Err(_) => value.to_string(),
        }
    }

    /// SI value per unit of the given dimension: `si = file_value * factor`.
    pub fn factor(&self, dimension: Dimension) -> f64 {
        let length = match self.length {
            LengthUnit::Metre => 1.0,
            LengthUnit::Millimetre => 1e-3,
        };
        match dimension {
            Dimension::Length | Dimension::Velocity | Dimension::Acceleration | Dimension::Jerk => {
                length
            }
            Dimension::Angle => match self.angle {
                AngleUnit::Radian => 1.0,
                AngleUnit::Degree => std::f64::consts::PI / 180.0,
            },
            Dimension::AngularVelocity => match self.angular_velocity {
                AngularVelocityUnit::RadianPerSecond => 1.0,
                AngularVelocityUnit::DegreePerSecond => std::f64::consts::PI / 180.0,
                AngularVelocityUnit::Rpm => std::f64::consts::PI / 30.0,
            },
            Dimension::AngularAcceleration | Dimension::AngularJerk => {
                match self.angular_acceleration {
                    AngularAccelerationUnit::RadianPerSecondSquared => 1.0,
                    AngularAccelerationUnit::DegreePerSecondSquared => std::f64::consts::PI / 180.0,
                }
            }
        }
    }

    /// Converts a value written in the file to SI.
    pub fn to_si(&self, value: f64, dimension: Dimension) -> f64 {
        value * self.factor(dimension)
    }

    /// Converts an SI value to the scene's units for printing.
    pub fn from_si(&self, value: f64, dimension: Dimension) -> f64 {
        value / self.factor(dimension)
    }

    /// The unit's symbol, as printed in headers.
    pub fn symbol(&self, dimension: Dimension) -> &'static str {
        let metre = self.length == LengthUnit::Metre;
        match dimension {
            Dimension::Length => length_symbol(self.length),
            Dimension::Velocity if metre => "m/s",
            Dimension::Velocity => "mm/s",
            Dimension::Acceleration if metre => "m/s^2",
            Dimension::Acceleration => "mm/s^2",
            Dimension::Jerk if metre => "m/s^3",
            Dimension::Jerk => "mm/s^3",
            Dimension::Angle => match self.angle {
                AngleUnit::Radian => "rad",
                AngleUnit::Degree => "deg",
            },
            Dimension::AngularVelocity => match self.angular_velocity {
                AngularVelocityUnit::RadianPerSecond => "rad/s",
                AngularVelocityUnit::DegreePerSecond => "deg/s",
                AngularVelocityUnit::Rpm => "rpm",
            },
            Dimension::AngularAcceleration => match self.angular_acceleration {
                AngularAccelerationUnit::RadianPerSecondSquared => "rad/s^2",
                AngularAccelerationUnit::DegreePerSecondSquared => "deg/s^2",
            },
            Dimension::AngularJerk => match self.angular_acceleration {
                AngularAccelerationUnit::RadianPerSecondSquared => "rad/s^3",
                AngularAccelerationUnit::DegreePerSecondSquared => "deg/s^3",
            },
        }
    }

    /// The unit of a velocity or acceleration coefficient (d^order value / d drive^order).
    ///
    /// Coefficients are printed with angles in radians (so ψ′ of a crank-driven link is the
    /// familiar dimensionless ratio) and lengths in the scene's length unit: `mm/rad`,
    /// `rad/m^2`, `1`, `1/rad`.
    pub fn coefficient_symbol(&self, value: Dimension, drive: Dimension, order: u32) -> String {
        let numerator = match value {
            Dimension::Angle => "rad",
            _ => length_symbol(self.length),
        };
        let denominator = match drive {
            Dimension::Angle => "rad",
            _ => length_symbol(self.length),
        };
        let power = |k: u32| {
            if k == 1 {
                String::new()
            } else {
                format!("^{k}")
            }
        };
        match (numerator == denominator, order) {
            (true, 1) => "1".to_owned(),
            (true, k) => format!("1/{denominator}{}", power(k - 1)),
            (false, k) => format!("{numerator}/{denominator}{}", power(k)),
        }
    }

    /// SI value per printed unit of a coefficient (see [`Units::coefficient_symbol`]).
    pub fn coefficient_factor(&self, value: Dimension, drive: Dimension, order: u32) -> f64 {
        let scale = |d: Dimension| match d {
            Dimension::Angle => 1.0,
            _ => self.factor(Dimension::Length),
        };
        scale(value) / scale(drive).powi(order as i32)
    }
}

fn length_symbol(unit: LengthUnit) -> &'static str {
    match unit {
        LengthUnit::Metre => "m",
        LengthUnit::Millimetre => "mm",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rpm_converts_to_rad_per_second() {
        let units = Units {
            angular_velocity: AngularVelocityUnit::Rpm,
            ..Units::default()
        };
        // 100 rpm = 10π/3 rad/s; one rounding in the factor and one in the product.
        let omega = units.to_si(100.0, Dimension::AngularVelocity);
        assert!((omega - 10.0 * std::f64::consts::PI / 3.0).abs() <= 4.0 * f64::EPSILON * omega);
    }

    #[test]
    fn coefficient_units_keep_radians_and_the_length_unit() {
        let units = Units {
            length: LengthUnit::Millimetre,
            angle: AngleUnit::Degree,
            ..Units::default()
        };
        assert_eq!(
            units.coefficient_symbol(Dimension::Angle, Dimension::Angle, 1),
            "1"
        );
        assert_eq!(
            units.coefficient_symbol(Dimension::Angle, Dimension::Angle, 2),
            "1/rad"
        );
        assert_eq!(
            units.coefficient_symbol(Dimension::Length, Dimension::Angle, 2),
            "mm/rad^2"
        );
        assert_eq!(
            units.coefficient_symbol(Dimension::Angle, Dimension::Length, 1),
            "rad/mm"
        );
        // rad per mm² → rad per m²: a factor 1e6 (exact powers of ten within one rounding).
        let f = units.coefficient_factor(Dimension::Angle, Dimension::Length, 2);
        assert!((f - 1e6).abs() <= 1e6 * 4.0 * f64::EPSILON);
    }
}
