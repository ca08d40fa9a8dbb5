//! Units a scene file may declare, and their conversion to and from SI.
//!
//! The engine works in SI (m, rad, s). A scene converts every number it reads at the edge
//! and prints every result back in the same units, with the unit in the column header.

use serde::Deserialize;
use toml::Spanned;

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
    /// Inch (25.4 mm exactly).
    #[serde(rename = "in")]
    Inch,
    /// Foot (0.3048 m exactly).
    #[serde(rename = "ft")]
    Foot,
}

/// Mass unit (`[units] mass`): link masses, and with the length unit, densities.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
pub enum MassUnit {
    /// Kilogram.
    #[default]
    #[serde(rename = "kg")]
    Kilogram,
    /// Pound (0.45359237 kg exactly).
    #[serde(rename = "lb")]
    Pound,
    /// Slug (1 lbf·s²/ft).
    #[serde(rename = "slug")]
    Slug,
}

/// Force unit (`[units] force`): the components of a `[[load]]` force.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
pub enum ForceUnit {
    /// Newton.
    #[default]
    #[serde(rename = "N")]
    Newton,
    /// Pound-force (0.45359237 kg × 9.80665 m/s² exactly).
    #[serde(rename = "lbf")]
    PoundForce,
}

/// Torque unit (`[units] torque`): a `[[load]]` torque.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
pub enum TorqueUnit {
    /// Newton metre.
    #[default]
    #[serde(rename = "N*m")]
    NewtonMetre,
    /// Newton millimetre.
    #[serde(rename = "N*mm")]
    NewtonMillimetre,
    /// Pound-force inch.
    #[serde(rename = "lbf*in")]
    PoundForceInch,
    /// Pound-force foot.
    #[serde(rename = "lbf*ft")]
    PoundForceFoot,
}

/// Moment of inertia unit (`[units] inertia`): links' and rotors' moments of inertia.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
pub enum InertiaUnit {
    /// Kilogram metre squared.
    #[default]
    #[serde(rename = "kg*m^2")]
    KilogramMetreSquared,
    /// Kilogram millimetre squared (CAD programs' unit).
    #[serde(rename = "kg*mm^2")]
    KilogramMillimetreSquared,
    /// Pound inch squared.
    #[serde(rename = "lb*in^2")]
    PoundInchSquared,
    /// Slug foot squared.
    #[serde(rename = "slug*ft^2")]
    SlugFootSquared,
}

/// One inch (m).
const INCH: f64 = 0.0254;
/// One foot (m).
const FOOT: f64 = 0.3048;
/// One pound (kg).
const POUND: f64 = 0.45359237;
/// One pound-force (N): a pound under standard gravity 9.80665 m/s².
const POUND_FORCE: f64 = POUND * 9.80665;
/// One slug (kg): the mass a pound-force accelerates by one foot per second squared.
const SLUG: f64 = POUND_FORCE / FOOT;

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
    /// Masses (and, per length unit, densities).
    pub mass: MassUnit,
    /// Forces of loads.
    pub force: ForceUnit,
    /// Torques of loads.
    pub torque: TorqueUnit,
    /// Moments of inertia.
    pub inertia: InertiaUnit,
}

/// `[units]`: every field has an SI default.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct UnitsSection {
    /// `"m"` (default), `"mm"`, `"in"` or `"ft"`; velocities and accelerations of points follow (per s, s²).
    pub length: Option<Spanned<LengthUnit>>,
    /// `"rad"` (default) or `"deg"`.
    pub angle: Option<Spanned<AngleUnit>>,
    /// `"rad/s"` (default), `"deg/s"` or `"rpm"`.
    pub angular_velocity: Option<Spanned<AngularVelocityUnit>>,
    /// `"rad/s^2"` (default) or `"deg/s^2"`.
    pub angular_acceleration: Option<Spanned<AngularAccelerationUnit>>,
    /// `"kg"` (default), `"lb"` or `"slug"`: masses; densities are per length unit.
    pub mass: Option<Spanned<MassUnit>>,
    /// `"N"` (default) or `"lbf"`: load forces.
    pub force: Option<Spanned<ForceUnit>>,
    /// `"N*m"` (default), `"N*mm"`, `"lbf*in"` or `"lbf*ft"`: load torques.
    pub torque: Option<Spanned<TorqueUnit>>,
    /// `"kg*m^2"` (default), `"kg*mm^2"`, `"lb*in^2"` or `"slug*ft^2"`: moments of inertia.
    pub inertia: Option<Spanned<InertiaUnit>>,
}

impl Units {
    /// The units a `[units]` section declares (SI where it is silent).
    pub fn declared(section: &UnitsSection) -> Units {
        fn or_default<T: Copy + Default>(unit: &Option<Spanned<T>>) -> T {
            unit.as_ref().map(|u| *u.get_ref()).unwrap_or_default()
        }
        Units {
            length: or_default(&section.length),
            angle: or_default(&section.angle),
            angular_velocity: or_default(&section.angular_velocity),
            angular_acceleration: or_default(&section.angular_acceleration),
            mass: or_default(&section.mass),
            force: or_default(&section.force),
            torque: or_default(&section.torque),
            inertia: or_default(&section.inertia),
        }
    }
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
    /// A mass (kg).
    Mass,
    /// A mass per length (kg/m).
    Density,
    /// A force (N).
    Force,
    /// A torque (N·m).
    Torque,
    /// A moment of inertia (kg·m²).
    MomentOfInertia,
    /// A linear jerk (m/s³).
    Jerk,
    /// An angular jerk (rad/s³), printed in the angular acceleration's angle unit per s³.
    AngularJerk,
}

impl Dimension {
    /// The dimension in words, with its article, for messages (`"a length"`).
    pub fn words(self) -> &'static str {
        match self {
            Dimension::Length => "a length",
            Dimension::Angle => "an angle",
            Dimension::Velocity => "a velocity",
            Dimension::Acceleration => "an acceleration",
            Dimension::AngularVelocity => "an angular velocity",
            Dimension::AngularAcceleration => "an angular acceleration",
            Dimension::Mass => "a mass",
            Dimension::Density => "a mass per length",
            Dimension::Force => "a force",
            Dimension::Torque => "a torque",
            Dimension::MomentOfInertia => "a moment of inertia",
            Dimension::Jerk => "a jerk",
            Dimension::AngularJerk => "an angular jerk",
        }
    }
}

/// The dimension of a unit symbol as `[units]` writes it (`"in"`, `"deg"`, `"lbf"`,
/// `"kg*mm^2"`) and its value in SI.
///
/// ```
/// use mechdiff_scene::units::{Dimension, unit_factor};
///
/// assert_eq!(unit_factor("in"), Some((Dimension::Length, 0.0254)));
/// assert_eq!(unit_factor("furlong"), None);
/// ```
pub fn unit_factor(symbol: &str) -> Option<(Dimension, f64)> {
    use serde::de::IntoDeserializer;
    use serde::de::value::{Error, StrDeserializer};
    fn read<T: for<'de> Deserialize<'de>>(symbol: &str) -> Option<T> {
        let deserializer: StrDeserializer<Error> = symbol.into_deserializer();
        T::deserialize(deserializer).ok()
    }
    let d = Units::default();
    let units = if let Some(length) = read(symbol) {
        (Dimension::Length, Units { length, ..d })
    } else if let Some(angle) = read(symbol) {
        (Dimension::Angle, Units { angle, ..d })
    } else if let Some(angular_velocity) = read(symbol) {
        let units = Units {
            angular_velocity,
            ..d
        };
        (Dimension::AngularVelocity, units)
    } else if let Some(angular_acceleration) = read(symbol) {
        let units = Units {
            angular_acceleration,
            ..d
        };
        (Dimension::AngularAcceleration, units)
    } else if let Some(mass) = read(symbol) {
        (Dimension::Mass, Units { mass, ..d })
    } else if let Some(force) = read(symbol) {
        (Dimension::Force, Units { force, ..d })
    } else if let Some(torque) = read(symbol) {
        (Dimension::Torque, Units { torque, ..d })
    } else {
        (
            Dimension::MomentOfInertia,
            Units {
                inertia: read(symbol)?,
                ..d
            },
        )
    };
    Some((units.0, units.1.factor(units.0)))
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
            LengthUnit::Inch => INCH,
            LengthUnit::Foot => FOOT,
        };
        let mass = match self.mass {
            MassUnit::Kilogram => 1.0,
            MassUnit::Pound => POUND,
            MassUnit::Slug => SLUG,
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
            Dimension::Mass => mass,
            Dimension::Density => mass / length,
            Dimension::Force => match self.force {
                ForceUnit::Newton => 1.0,
                ForceUnit::PoundForce => POUND_FORCE,
            },
            Dimension::Torque => match self.torque {
                TorqueUnit::NewtonMetre => 1.0,
                TorqueUnit::NewtonMillimetre => 1e-3,
                TorqueUnit::PoundForceInch => POUND_FORCE * INCH,
                TorqueUnit::PoundForceFoot => POUND_FORCE * FOOT,
            },
            Dimension::MomentOfInertia => match self.inertia {
                InertiaUnit::KilogramMetreSquared => 1.0,
                InertiaUnit::KilogramMillimetreSquared => 1e-6,
                InertiaUnit::PoundInchSquared => POUND * INCH * INCH,
                InertiaUnit::SlugFootSquared => SLUG * FOOT * FOOT,
            },
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
        match dimension {
            Dimension::Length => length_symbol(self.length),
            Dimension::Velocity => match self.length {
                LengthUnit::Metre => "m/s",
                LengthUnit::Millimetre => "mm/s",
                LengthUnit::Inch => "in/s",
                LengthUnit::Foot => "ft/s",
            },
            Dimension::Acceleration => match self.length {
                LengthUnit::Metre => "m/s^2",
                LengthUnit::Millimetre => "mm/s^2",
                LengthUnit::Inch => "in/s^2",
                LengthUnit::Foot => "ft/s^2",
            },
            Dimension::Jerk => match self.length {
                LengthUnit::Metre => "m/s^3",
                LengthUnit::Millimetre => "mm/s^3",
                LengthUnit::Inch => "in/s^3",
                LengthUnit::Foot => "ft/s^3",
            },
            Dimension::Mass => match self.mass {
                MassUnit::Kilogram => "kg",
                MassUnit::Pound => "lb",
                MassUnit::Slug => "slug",
            },
            Dimension::Density => match (self.mass, self.length) {
                (MassUnit::Kilogram, LengthUnit::Metre) => "kg/m",
                (MassUnit::Kilogram, LengthUnit::Millimetre) => "kg/mm",
                (MassUnit::Kilogram, LengthUnit::Inch) => "kg/in",
                (MassUnit::Kilogram, LengthUnit::Foot) => "kg/ft",
                (MassUnit::Pound, LengthUnit::Metre) => "lb/m",
                (MassUnit::Pound, LengthUnit::Millimetre) => "lb/mm",
                (MassUnit::Pound, LengthUnit::Inch) => "lb/in",
                (MassUnit::Pound, LengthUnit::Foot) => "lb/ft",
                (MassUnit::Slug, LengthUnit::Metre) => "slug/m",
                (MassUnit::Slug, LengthUnit::Millimetre) => "slug/mm",
                (MassUnit::Slug, LengthUnit::Inch) => "slug/in",
                (MassUnit::Slug, LengthUnit::Foot) => "slug/ft",
            },
            Dimension::Force => match self.force {
                ForceUnit::Newton => "N",
                ForceUnit::PoundForce => "lbf",
            },
            Dimension::Torque => match self.torque {
                TorqueUnit::NewtonMetre => "N*m",
                TorqueUnit::NewtonMillimetre => "N*mm",
                TorqueUnit::PoundForceInch => "lbf*in",
                TorqueUnit::PoundForceFoot => "lbf*ft",
            },
            Dimension::MomentOfInertia => match self.inertia {
                InertiaUnit::KilogramMetreSquared => "kg*m^2",
                InertiaUnit::KilogramMillimetreSquared => "kg*mm^2",
                InertiaUnit::PoundInchSquared => "lb*in^2",
                InertiaUnit::SlugFootSquared => "slug*ft^2",
            },
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
        LengthUnit::Inch => "in",
        LengthUnit::Foot => "ft",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn imperial_units_are_their_definitions() {
        let units = Units {
            length: LengthUnit::Inch,
            mass: MassUnit::Slug,
            force: ForceUnit::PoundForce,
            torque: TorqueUnit::PoundForceFoot,
            inertia: InertiaUnit::KilogramMillimetreSquared,
            ..Units::default()
        };
        // NIST SP 811 values: 1 lbf = 4.4482216152605 N, 1 slug = 14.593902937206 kg
        // (to its 14 digits), 1 lbf·ft = 1.3558179483314004 N·m; 1e-15 relative is a few
        // roundings of the products.
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-15 * b.abs();
        assert!(close(units.factor(Dimension::Force), 4.4482216152605));
        assert!((units.factor(Dimension::Mass) - 14.593902937206).abs() < 1e-12);
        assert!(close(units.factor(Dimension::Torque), 1.3558179483314004));
        assert!(close(units.factor(Dimension::Length), 0.0254));
        assert!(close(units.factor(Dimension::MomentOfInertia), 1e-6));
        assert!(close(
            units.factor(Dimension::Density),
            14.593902937206364 / 0.0254
        ));
        assert_eq!(units.symbol(Dimension::Velocity), "in/s");
    }

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
