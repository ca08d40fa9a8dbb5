//! A sweep solved once: the tracker moves to each drive position in order (keeping the
//! sketch's assembly branch), and every [`Consumer`] — kinematic outputs, the dynamics of a
//! [`Plan`](crate::dynamics::Plan), counterweights being sized — reads that one pose, lifted
//! to the derivative order it needs ([`Tracker::kinematics`] copies what the move computed;
//! nothing is solved again). Each position gives one row, the drive position first and then
//! every consumer's values in turn, handed to a [`Sink`]: [`Collect`] keeps them,
//! [`Stream`] passes each on as it comes, so a sweep of any length runs in constant memory.
//! The [`SweepReport`] counts the rows and the tracker's moves.
//!
//! ```
//! use mechdiff_core::geometry::{Drive, Mechanism, Solver, Tracker};
//! use mechdiff_core::sweep::{Collect, Consumer, Sweep};
//! use mechdiff_core::Error;
//! let m = Mechanism::builder()
//!     .point("O", [0.0, 0.0]).point("A", [2.0, 0.0])
//!     .ground(["O"]).link("crank", ["O", "A"])
//!     .revolute("O", "ground", "crank", "O")
//!     .drive(Drive::angle("O"))
//!     .build().unwrap();
//! let tip = m.point_output("crank", "A").unwrap();
//! // The tip's height and its velocity coefficient.
//! struct Height(mechdiff_core::geometry::PointOutput);
//! impl Consumer for Height {
//!     fn at(&mut self, t: &Tracker<'_>, _phi: f64, row: &mut Vec<f64>) -> Result<(), Error> {
//!         let [_, y] = t.position(&self.0);
//!         row.extend([y.value, y.d1()]);
//!         Ok(())
//!     }
//! }
//! let mut height = Height(tip);
//! let mut rows = Collect::default();
//! let report = Sweep::new(&m, &Solver::default()).unwrap()
//!     .with(&mut height)
//!     .run([0.0, 0.5, 1.0], &mut rows)
//!     .unwrap();
//! assert_eq!((report.rows, report.solves), (3, 3));
//! assert!((rows.rows[1][1] - 2.0 * 0.5f64.sin()).abs() < 1e-15); // y = 2 sin φ
//! assert!((rows.rows[1][2] - 2.0 * 0.5f64.cos()).abs() < 1e-15); // y′ = 2 cos φ
//! ```

mod sink;

pub use sink::{Collect, Sink, Stream};

use crate::Error;
use crate::geometry::{Mechanism, Solver, Tracker};

/// What reads the pose of every drive position a [`Sweep`] solves.
pub trait Consumer {
    /// Reads the pose `tracker` stands at, drive position `phi` (moved there by the sweep;
    /// nothing to solve), and appends this consumer's values to `row`.
    ///
    /// # Errors
    /// The consumer's error at `phi`: the sweep stops there.
    fn at(&mut self, tracker: &Tracker<'_>, phi: f64, row: &mut Vec<f64>) -> Result<(), Error>;
}

/// What a sweep evaluated.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SweepReport {
    /// Rows handed to the sink (drive positions read by the consumers).
    pub rows: usize,
    /// Moves of the tracker to a drive position: one per row.
    pub solves: usize,
}

/// A sweep under construction: the tracker at the sketch pose and the consumers of each
/// pose, in row order.
pub struct Sweep<'a, 'm> {
    tracker: Tracker<'m>,
    consumers: Vec<&'a mut dyn Consumer>,
}

impl<'a, 'm> Sweep<'a, 'm> {
    /// A sweep of `mechanism` by `solver`, from the sketch pose.
    ///
    /// # Errors
    /// The sketch does not assemble, or the mechanism is not solvable (see
    /// [`Solver::track`]).
    pub fn new(mechanism: &'m Mechanism, solver: &Solver) -> Result<Self, Error> {
        Ok(Self {
            tracker: solver.track(mechanism)?,
            consumers: Vec::new(),
        })
    }

    /// Adds a consumer; its values follow those of the consumers added before.
    pub fn with(mut self, consumer: &'a mut dyn Consumer) -> Self {
        self.consumers.push(consumer);
        self
    }

    /// Solves each drive position of `positions` once, in order (the tracker moves to the
    /// drive position itself), and hands each row to `sink`.
    ///
    /// # Errors
    /// The first error in drive order: the solver's, a consumer's or the sink's, after the
    /// rows before it were handed on.
    pub fn run(
        self,
        positions: impl IntoIterator<Item = f64>,
        sink: &mut dyn Sink,
    ) -> Result<SweepReport, Error> {
        self.run_moved(positions, sink, |tracker, _, phi| {
            tracker.move_to(phi).map(drop)
        })
    }

    /// [`Sweep::run`] with the tracker brought to the `k`-th drive position `phi` by
    /// `move_to(tracker, k, phi)`: a drive that reaches its next position along a path of
    /// its own (a cam's follower through every displacement it passes, see
    /// [`crate::cams::CamJoint::move_tracker`]).
    ///
    /// # Errors
    /// As [`Sweep::run`], and `move_to`'s.
    pub fn run_moved(
        mut self,
        positions: impl IntoIterator<Item = f64>,
        sink: &mut dyn Sink,
        mut move_to: impl FnMut(&mut Tracker<'m>, usize, f64) -> Result<(), Error>,
    ) -> Result<SweepReport, Error> {
        let mut report = SweepReport::default();
        let mut row = Vec::new();
        for (k, phi) in positions.into_iter().enumerate() {
            move_to(&mut self.tracker, k, phi)?;
            report.solves += 1;
            row.clear();
            row.push(phi);
            for consumer in &mut self.consumers {
                consumer.at(&self.tracker, phi, &mut row)?;
            }
            sink.row(&row)?;
            report.rows += 1;
        }
        Ok(report)
    }
}
