//! The errors of synthesis, and the defects that make a candidate mechanism unusable.

use thiserror::Error;

/// Why a candidate mechanism is rejected (counted over the search, see
/// [`super::Report::defects`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[non_exhaustive]
pub enum Defect {
    /// It cannot assemble at a target's drive angle.
    NoAssemblyAtTarget,
    /// It cannot move from one target to the next: a dyad stops closing in between (a limit
    /// position; with the branch fixed, also every branch change).
    BlockedBetweenTargets,
    /// Free drive angles not increasing, or spanning a full turn or more.
    OutOfOrder,
    /// The crank was required to turn fully and cannot.
    CrankDoesNotRotate,
    /// A dyad's transmission angle falls below the required minimum.
    TransmissionBelowMinimum,
    /// The four-bar loop is not of the Grashof class asked for ([`super::GrashofClass`]).
    WrongGrashofClass,
}

impl Defect {
    /// Every defect, in order.
    pub const ALL: [Defect; 6] = [
        Defect::NoAssemblyAtTarget,
        Defect::BlockedBetweenTargets,
        Defect::OutOfOrder,
        Defect::CrankDoesNotRotate,
        Defect::TransmissionBelowMinimum,
        Defect::WrongGrashofClass,
    ];

    /// What it means, in words.
    pub fn describe(self) -> &'static str {
        match self {
            Defect::NoAssemblyAtTarget => "does not assemble at a target",
            Defect::BlockedBetweenTargets => "blocked (limit position) between two targets",
            Defect::OutOfOrder => "free drive angles out of order or spanning a turn",
            Defect::CrankDoesNotRotate => "crank cannot turn fully",
            Defect::TransmissionBelowMinimum => "transmission angle below the minimum",
            Defect::WrongGrashofClass => "not of the Grashof class asked for",
        }
    }
}

/// Everything that can go wrong in setting up or running a synthesis.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum SynthesisError {
    /// The task names a point, output, link or variable the linkage does not have.
    #[error("unknown {what} `{name}`; the linkage has {}", .known.join(", "))]
    UnknownName {
        /// What kind of name (`point`, `output`, `link`, `variable`).
        what: &'static str,
        /// The name given.
        name: String,
        /// The names it has.
        known: Vec<String>,
    },
    /// A design variable has no bounds (a linkage's dimensions must be bounded).
    #[error("design variable `{variable}` has no bounds; give them with `bound` or `fix`")]
    MissingBound {
        /// The variable.
        variable: String,
    },
    /// Bounds that are not finite or not ordered.
    #[error("bounds of `{variable}` [{lower}, {upper}]: {reason}")]
    InvalidBound {
        /// The variable.
        variable: String,
        /// Lower bound.
        lower: f64,
        /// Upper bound.
        upper: f64,
        /// What is wrong.
        reason: &'static str,
    },
    /// A target value (or a timing angle) that is not finite.
    #[error("{what} {index} is not finite ({value}); every target must be a finite number")]
    NonFiniteTarget {
        /// Which list (`target`, `drive angle`, `pair`, `pose`, `angle weight`).
        what: &'static str,
        /// Its index (0-based).
        index: usize,
        /// The value.
        value: f64,
    },
    /// Too few or too many targets, or a timing list of the wrong length.
    #[error("{count} {what}: {reason}")]
    TargetCount {
        /// What was counted.
        what: &'static str,
        /// How many were given.
        count: usize,
        /// What is needed.
        reason: String,
    },
    /// A search setting out of its range.
    #[error("setting `{setting}` = {value}: {reason}")]
    InvalidSetting {
        /// The setting.
        setting: &'static str,
        /// Its value.
        value: f64,
        /// What is allowed.
        reason: &'static str,
    },
    /// Constraints or weights that contradict each other or do not apply to the linkage.
    #[error("{constraint}: {reason}")]
    InvalidConstraint {
        /// The constraint or setting (`grashof`, `weights`).
        constraint: &'static str,
        /// What is wrong and what to write.
        reason: String,
    },
    /// The time limit ran out before any sample of the bounds was a usable mechanism.
    #[error(
        "the time limit of {limit:?} ran out after {samples} samples of the bounds, none of \
         them a usable mechanism; allow more time or fewer samples"
    )]
    TimeLimit {
        /// How many samples were tried.
        samples: usize,
        /// The limit.
        limit: std::time::Duration,
    },
    /// No sample of the bounds gives a usable mechanism: the bounds exclude every assembly
    /// (with the branch, order and constraints asked for).
    #[error(
        "none of {samples} samples of the bounds gives a mechanism that assembles and moves \
         through the targets ({}); widen the bounds (lengths, pivots), change the branch or \
         relax the constraints",
        .defects.iter().map(|(d, n)| format!("{n}× {}", d.describe())).collect::<Vec<_>>().join(", ")
    )]
    NoAssembly {
        /// How many samples were tried.
        samples: usize,
        /// How many were rejected for each defect.
        defects: Vec<(Defect, usize)>,
    },
}
