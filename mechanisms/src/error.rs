//! The errors of mechdiff-mechanisms.

use thiserror::Error;

/// Everything that can go wrong when building or evaluating a closed-form mechanism.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter is out of its physical range (zero, negative or not finite, say).
    #[error("invalid parameter {name} = {value} {unit}: {reason}")]
    InvalidParameter {
        /// The parameter's name as in the mechanism's parameter table (`l1`, `m2`, …).
        name: &'static str,
        /// The value given.
        value: f64,
        /// Its unit (SI).
        unit: &'static str,
        /// Why it is invalid.
        reason: &'static str,
    },
    /// A crank that is not shorter than the frame: the Whitworth's rocker would turn fully
    /// round (l1 > l0), or its angle be undefined at φ = 0 (l1 = l0), and the ram pin at its
    /// fixed height could not follow.
    #[error(
        "invalid parameter l1 = {l1} m: the crank must be shorter than the frame l0 = {l0} m; \
         with l1 ≥ l0 the rocker turns fully round and the ram pin at height h cannot follow \
         (at l1 = l0 the rocker angle ψ is undefined at φ = 0)"
    )]
    CrankNotShorterThanFrame {
        /// Crank length l1 (m).
        l1: f64,
        /// Frame distance l0 between the crank pivot and the rocker pivot (m).
        l0: f64,
    },
    /// An input of an evaluation (drive position φ, drive speed ω, …) is not finite.
    #[error("{name} = {value} is not finite")]
    NonFiniteInput {
        /// Which input (`φ`, `ω`, `α`).
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// The dead-position search did not find the number of dead positions the geometry has.
    #[error("expected {expected} dead positions of {output}, found {found}")]
    DeadPositionCount {
        /// The output searched (`the rocker angle ψ`).
        output: &'static str,
        /// How many the geometry has.
        expected: usize,
        /// How many the search found.
        found: usize,
    },
    /// An error of the derivative core (an invalid sweep, a non-finite derivative).
    #[error(transparent)]
    Core(#[from] mechdiff_core::Error),
}

/// The result type of mechdiff-mechanisms.
pub type Result<T, E = Error> = std::result::Result<T, E>;
