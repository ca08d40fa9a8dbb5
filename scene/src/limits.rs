//! The range of every number a scene may contain, in SI.
//!
//! The limits are far beyond any machine (a length of a million kilometres, a drive turning
//! a million radians per second) and close enough to 1 that the engine's products of them
//! (ω²·ψ″·m·l, …) stay well inside `f64`. A number outside its range is refused where it is
//! written, with `file:line:column`; what may still overflow in combination is caught when
//! the results are checked (by the run). The table is repeated in
//! `docs/scene-format.md`.

use std::ops::RangeInclusive;

use crate::units::Dimension;

/// Largest magnitude of a length: coordinates, lengths, radii, offsets (m).
pub const LENGTH: f64 = 1e9;
/// Largest magnitude of an angle: drive positions, polar angles (rad).
pub const ANGLE: f64 = 1e6;
/// Largest magnitude of an angular velocity: the drive speed (rad/s).
pub const ANGULAR_VELOCITY: f64 = 1e6;
/// Largest magnitude of a linear velocity: a slide's drive speed (m/s).
pub const VELOCITY: f64 = 1e6;
/// Largest magnitude of an angular acceleration (rad/s²).
pub const ANGULAR_ACCELERATION: f64 = 1e12;
/// Largest magnitude of a linear acceleration: a slide's drive acceleration, gravity (m/s²).
pub const ACCELERATION: f64 = 1e12;
/// Largest magnitude of a jerk, linear (m/s³) or angular (rad/s³): no number of a scene
/// file is a jerk today (jerks are outputs only); the bound completes the table.
pub const JERK: f64 = 1e18;
/// Largest mass of a link (kg).
pub const MASS: f64 = 1e9;
/// Largest moment of inertia of a link or rotor (kg·m²).
pub const MOMENT_OF_INERTIA: f64 = 1e12;
/// Largest magnitude of a force component (N).
pub const FORCE: f64 = 1e12;
/// Largest magnitude of a torque (N·m).
pub const TORQUE: f64 = 1e12;
/// Largest Coulomb friction coefficient.
pub const FRICTION_COEFFICIENT: f64 = 100.0;
/// Smallest and largest magnitude of a transmission ratio (gear pair, motor gearbox): its
/// reciprocal is used as well.
pub const RATIO: RangeInclusive<f64> = 1e-6..=1e6;
/// Smallest pitch radius of a pinion (m): the pinion turns by the rack's travel over it; and
/// smallest radius of a counterweight (its mass is the m·r found over this radius).
pub const SMALLEST_RADIUS: f64 = 1e-9;

/// The largest magnitude of a quantity of `dimension` (SI).
pub fn largest(dimension: Dimension) -> f64 {
    match dimension {
        Dimension::Length => LENGTH,
        Dimension::Angle => ANGLE,
        Dimension::Velocity => VELOCITY,
        Dimension::Acceleration => ACCELERATION,
        Dimension::AngularVelocity => ANGULAR_VELOCITY,
        Dimension::AngularAcceleration => ANGULAR_ACCELERATION,
        Dimension::Mass => MASS,
        Dimension::Density => MASS,
        Dimension::Force => FORCE,
        Dimension::Torque => TORQUE,
        Dimension::MomentOfInertia => MOMENT_OF_INERTIA,
        Dimension::Jerk | Dimension::AngularJerk => JERK,
    }
}
