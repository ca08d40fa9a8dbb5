//! The drive's motion range: how far the drive can move either way from the sketch before a
//! loop stops closing (limit positions), its branches meet (change points) or it toggles.

use super::Tracker;
use super::interval::LONGEST_TURN;
use crate::Error;
use crate::geometry::DriveKind;
use std::f64::consts::TAU;

/// Why the drive cannot move beyond a drive position.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LimitKind {
    /// A limit position: beyond it a loop cannot close (found to full precision on the
    /// closed-form path; on the Newton path, the last position that assembled).
    Limit,
    /// A change point: two assembly branches of a loop meet.
    ChangePoint,
    /// A toggle: the loop's Jacobian is singular there.
    Toggle,
    /// The Newton path would switch a loop to its other branch after this position.
    BranchFlip,
}

/// One end of the drive's motion range.
#[derive(Debug, Clone, PartialEq)]
pub struct DriveLimit {
    /// The drive position (rad or m).
    pub phi: f64,
    /// What stops the drive there.
    pub kind: LimitKind,
    /// The joints of the loop that stops it.
    pub joints: Vec<String>,
}

/// How far the drive moves from the sketch: each end is `None` when no limit was met
/// within `searched` of the sketch's drive position.
#[derive(Debug, Clone, PartialEq)]
pub struct MotionRange {
    /// The end below the sketch's drive position.
    pub lower: Option<DriveLimit>,
    /// The end above it.
    pub upper: Option<DriveLimit>,
    /// How far each way was searched: a full turn (2π) for an angle drive (no limit either
    /// way: the crank turns fully), 20 sketch sizes for a displacement.
    pub searched: f64,
}

impl Tracker<'_> {
    /// The drive's motion range from the current position, walked both ways with the
    /// solver's own steps (1/8 rad, or 1/8 of the sketch for a displacement): each end is
    /// the first limit position, change point or toggle met (see [`Error::Blocked`],
    /// [`Error::ChangePoint`]). The tracker itself does not move.
    ///
    /// ```
    /// use mechdiff_core::geometry::{Drive, Mechanism, Solver};
    /// // A slider-crank whose guide is 0.5 above the crank pivot, rod 1.49: the crank
    /// // (r = 1) cannot pass below sin φ = (0.5 − 1.49)/1 = −0.99.
    /// let b = 1.0 + (1.49f64 * 1.49 - 0.25).sqrt();
    /// let m = Mechanism::builder()
    ///     .point("O", [0.0, 0.0]).point("A", [1.0, 0.0]).point("B", [b, 0.5])
    ///     .point("G", [0.0, 0.5]).point("H", [1.0, 0.5])
    ///     .ground(["O", "G", "H"]).link("crank", ["O", "A"]).link("rod", ["A", "B"])
    ///     .link("slider", ["B"])
    ///     .revolute("O", "ground", "crank", "O").revolute("A", "crank", "rod", "A")
    ///     .revolute("B", "rod", "slider", "B")
    ///     .prismatic("guide", "ground", ["G", "H"], "slider", "B")
    ///     .drive(Drive::angle("O"))
    ///     .build().unwrap();
    /// let range = Solver::default().track(&m).unwrap().motion_range().unwrap();
    /// let limit = (-0.99f64).asin();
    /// assert!((range.upper.unwrap().phi - (std::f64::consts::PI - limit)).abs() < 1e-12);
    /// assert!((range.lower.unwrap().phi - limit).abs() < 1e-12);
    /// ```
    pub fn motion_range(&self) -> Result<MotionRange, Error> {
        let size = self.lengths.linkage;
        let (step, searched) = match self.mechanism.drive_kind() {
            DriveKind::Angle => (LONGEST_TURN, TAU),
            DriveKind::Displacement => (LONGEST_TURN * size, 20.0 * size),
        };
        let upper = self.clone().walk(step, searched)?;
        let lower = self.clone().walk(-step, searched)?;
        Ok(MotionRange {
            lower,
            upper,
            searched,
        })
    }

    /// Walks by `step` until `searched` from the current position, or a limit.
    fn walk(&mut self, step: f64, searched: f64) -> Result<Option<DriveLimit>, Error> {
        let start = self.phi;
        let steps = (searched / step.abs()).ceil() as usize;
        for k in 1..=steps {
            let phi = start + step * (k as f64).min(searched / step.abs());
            let (phi, kind, joints) = match self.move_to(phi) {
                Ok(_) => continue,
                Err(Error::Blocked { limit, joints, .. }) => (limit, LimitKind::Limit, joints),
                Err(Error::ChangePoint { phi, joints }) => (phi, LimitKind::ChangePoint, joints),
                Err(Error::Singular { phi, joints, .. }) => (phi, LimitKind::Toggle, joints),
                Err(Error::Unassemblable {
                    last_assembled,
                    joints,
                    ..
                }) => (last_assembled, LimitKind::Limit, joints),
                Err(Error::BranchFlip { from, joints, .. }) => {
                    (from, LimitKind::BranchFlip, joints)
                }
                Err(e) => return Err(e),
            };
            return Ok(Some(DriveLimit { phi, kind, joints }));
        }
        Ok(None)
    }
}
