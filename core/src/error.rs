//! The errors of mechdiff-core.

use thiserror::Error;

/// Everything that can go wrong in mechdiff-core.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum Error {
    /// A sweep over the drive variable is not a finite, non-empty range with a positive step.
    #[error("invalid sweep from {start} to {end} with step {step}: {reason}")]
    InvalidSweep {
        /// First drive position.
        start: f64,
        /// Last drive position.
        end: f64,
        /// Step between drive positions.
        step: f64,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// A computed quantity is NaN or infinite at a drive position where it should be finite.
    #[error("{quantity} is not finite at drive position φ = {phi}")]
    NonFinite {
        /// The drive position.
        phi: f64,
        /// Which quantity.
        quantity: &'static str,
    },
}

/// The result type of mechdiff-core.
pub type Result<T, E = Error> = std::result::Result<T, E>;
