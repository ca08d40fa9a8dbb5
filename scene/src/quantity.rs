//! What an output reports (`quantities = [...]`) and the sense an output angle is counted
//! in: words of the file that the checked scene keeps as they are, so both the file as
//! written and the checked scene name them.

use serde::Deserialize;

/// What an output reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// The value (position, angle, displacement).
    Position,
    /// First derivative with respect to the drive (ψ′).
    VelocityCoefficient,
    /// Second derivative with respect to the drive (ψ″).
    AccelerationCoefficient,
    /// Time derivative (ψ̇ = ω ψ′).
    Velocity,
    /// Second time derivative (ψ̈ = α ψ′ + ω² ψ″).
    Acceleration,
    /// Third derivative with respect to the drive (ψ‴).
    JerkCoefficient,
    /// Third time derivative (ψ⃛ = φ⃛ ψ′ + 3ωα ψ″ + ω³ ψ‴, with φ⃛ = 0).
    Jerk,
}

impl Quantity {
    /// The derivative order this quantity needs (0 to 3).
    pub fn order(self) -> usize {
        match self {
            Quantity::Position => 0,
            Quantity::VelocityCoefficient | Quantity::Velocity => 1,
            Quantity::AccelerationCoefficient | Quantity::Acceleration => 2,
            Quantity::JerkCoefficient | Quantity::Jerk => 3,
        }
    }

    /// Whether the quantity is a time derivative (needs the drive's speed).
    pub fn is_time_derivative(self) -> bool {
        matches!(
            self,
            Quantity::Velocity | Quantity::Acceleration | Quantity::Jerk
        )
    }

    /// The quantity's name in words, for messages (`"jerk"`, `"velocity coefficient"`).
    pub fn words(self) -> &'static str {
        match self {
            Quantity::Position => "position",
            Quantity::VelocityCoefficient => "velocity coefficient",
            Quantity::AccelerationCoefficient => "acceleration coefficient",
            Quantity::JerkCoefficient => "jerk coefficient",
            Quantity::Velocity => "velocity",
            Quantity::Acceleration => "acceleration",
            Quantity::Jerk => "jerk",
        }
    }
}

/// The sense in which an output angle is counted.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Sense {
    /// Counter-clockwise positive.
    Ccw,
    /// Clockwise positive.
    Cw,
}

/// The form a `transmission_angle` output reports μ in (see
/// `mechdiff_core::metrics::TransmissionAngle`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TransmissionForm {
    /// The oriented angle from the coupler to the follower, in (−180°, 180°]: its sign is
    /// the loop's assembly branch.
    Signed,
    /// μ = |signed| in [0°, 180°]: the textbooks' transmission angle.
    Unsigned,
    /// min(μ, 180° − μ) in [0°, 90°]: 90° is ideal transmission.
    Effective,
    /// 90° − effective, in [0°, 90°]: how far from ideal.
    Deviation,
}
