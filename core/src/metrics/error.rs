//! Why a linkage metric cannot be given.

use crate::Error;
use crate::geometry::DriveLimit;
use thiserror::Error;

/// Why a metric does not apply to a mechanism, or could not be computed; the solver's own
/// error is kept as the source.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum MetricsError {
    /// A time ratio needs a turning crank, and the drive is a displacement.
    #[error(
        "the drive `{joint}` is a displacement; a time ratio needs a crank that turns (drive an angle)"
    )]
    NotAngleDrive {
        /// The driven joint.
        joint: String,
    },
    /// A time ratio needs a crank that turns fully, and the drive stops.
    #[error(
        "the crank does not turn fully: it stops at drive position {} rad ({}), so it has no \
         time ratio",
        limit.phi,
        super::words::reason(limit)
    )]
    CrankDoesNotTurn {
        /// Where it stops, and why.
        limit: DriveLimit,
    },
    /// A time ratio needs an output with exactly two dead positions per turn.
    #[error(
        "the output has {found} dead positions over one crank turn; a time ratio needs exactly \
         two (a rocker or a slider driven by a crank)"
    )]
    DeadPositions {
        /// How many were found.
        found: usize,
    },
    /// The loop's input is not the mechanism's drive, so its time ratio is not defined by
    /// this loop alone.
    #[error(
        "the input `{input}` of this loop is not the drive; its time ratio is the mechanism's \
         (ask for it with the output)"
    )]
    InputNotDriven {
        /// The loop's input link.
        input: String,
    },
    /// The solver failed while the metric was computed.
    #[error("solving the mechanism for its linkage metrics failed")]
    Geometry(#[from] Error),
}
