//! The drive's motion range in words: a full turn, or between which limits and why.

use super::error::MetricsError;
use super::words::{reason, short};
use crate::geometry::{DriveKind, DriveLimit, Mechanism, MotionRange, Solver};
use std::fmt;

/// How far the drive moves from the sketch, as the solver walks it (see
/// [`crate::geometry::Tracker::motion_range`]), with the words for it.
#[derive(Debug, Clone, PartialEq)]
pub struct DriveMotion {
    /// An angle or a displacement.
    pub kind: DriveKind,
    /// The drive position at the sketch (rad or m).
    pub sketch: f64,
    /// Its ends.
    pub range: MotionRange,
}

impl DriveMotion {
    /// The drive's motion range of `m`, walked by `solver` from the sketch.
    ///
    /// # Errors
    /// [`MetricsError::Geometry`] when `m` cannot be tracked or walked.
    pub fn of(m: &Mechanism, solver: &Solver) -> Result<DriveMotion, MetricsError> {
        let tracker = solver.track(m)?;
        Ok(DriveMotion {
            kind: m.drive_kind().clone(),
            sketch: tracker.phi(),
            range: tracker.motion_range()?,
        })
    }

    /// Whether an angle drive turns fully (no limit either way within a turn).
    pub fn turns_fully(&self) -> bool {
        self.kind == DriveKind::Angle && self.range.lower.is_none() && self.range.upper.is_none()
    }

    /// The range in words, drive positions formatted by `position` (the caller's units):
    /// "turns fully", or "moves from … (why) to … (why)".
    ///
    /// ```
    /// use mechdiff_core::geometry::{DriveKind, DriveLimit, LimitKind, MotionRange};
    /// use mechdiff_core::metrics::DriveMotion;
    /// let limit = |phi| DriveLimit { phi, kind: LimitKind::Limit, joints: vec!["B".into()] };
    /// let range = MotionRange { lower: Some(limit(-2.0)), upper: Some(limit(2.0)), searched: 6.3 };
    /// let motion = DriveMotion { kind: DriveKind::Angle, sketch: 0.0, range };
    /// assert_eq!(
    ///     motion.describe(|phi| format!("{phi} rad")),
    ///     "rocks from -2 rad (a limit position: the loop of joints B cannot close beyond it) \
    ///      to 2 rad (a limit position: the loop of joints B cannot close beyond it)"
    /// );
    /// ```
    pub fn describe(&self, position: impl Fn(f64) -> String) -> String {
        if self.turns_fully() {
            return "turns fully".to_owned();
        }
        let verb = match self.kind {
            DriveKind::Angle => "rocks",
            DriveKind::Displacement => "moves",
        };
        let end = |limit: &Option<DriveLimit>, sign: f64| match limit {
            Some(l) => format!("{} ({})", position(l.phi), reason(l)),
            None => format!(
                "beyond {} (no limit searched that far)",
                position(self.sketch + sign * self.range.searched)
            ),
        };
        format!(
            "{verb} from {} to {}",
            end(&self.range.lower, -1.0),
            end(&self.range.upper, 1.0)
        )
    }
}

impl fmt::Display for DriveMotion {
    /// [`DriveMotion::describe`] in degrees for an angle, metres for a displacement, to six
    /// decimals.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let text = match self.kind {
            DriveKind::Angle => self.describe(|phi| format!("{}°", short(phi.to_degrees()))),
            DriveKind::Displacement => self.describe(|s| format!("{} m", short(s))),
        };
        f.write_str(&text)
    }
}
