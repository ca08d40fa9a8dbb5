//! The plan of a run: what is computed, printed before the table.

use std::fmt;

use mechdiff_core::DriveState;

use super::outputs::columns;
use super::setup::Setup;

/// What a run computes, printed before the table.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// Number of drive positions.
    pub positions: usize,
    /// Smallest and largest position of the sweep (SI): drive positions, or values of the
    /// output named by `given_by`.
    pub range: (f64, f64),
    /// The output whose values the sweep gives (`[sweep] of`), if any.
    pub given_by: Option<String>,
    /// Highest derivative order with respect to the drive that the outputs need.
    pub order: usize,
    /// The drive state used for velocities and accelerations, if any is asked for.
    pub drive: Option<DriveState>,
    /// Number of output columns (the drive column excluded).
    pub columns: usize,
    /// Outputs whose dead positions are searched.
    pub dead_positions: Vec<String>,
    /// The plan of the `[[dynamics]]` outputs: derivative order and effects.
    pub dynamics: Option<mechdiff_core::dynamics::Plan>,
    /// Each loop and the path that evaluates it, once the sweep is set up
    /// ([`super::Sweeper::loops`]); empty before.
    pub loops: Vec<crate::evaluator::LoopPlan>,
    /// The run-time evaluator's back end, when it evaluates the sweep (set with `loops`).
    pub backend: Option<mechdiff_core::trace::Backend>,
}

impl Plan {
    /// The plan of a scene's run.
    pub fn of(setup: &Setup<'_>) -> Self {
        let (lo, hi) = setup.positions.range();
        let drive = setup.drive();
        let times =
            (setup.outputs.iter()).any(|o| o.quantities.iter().any(|q| q.is_time_derivative()));
        let state = match (times, drive.speed) {
            (true, Some(omega)) => Some(DriveState::accelerating(omega, drive.acceleration)),
            _ => None,
        };
        let drive_dimension = drive.kind.dimension();
        Plan {
            positions: setup.positions.len(),
            range: (lo, hi),
            given_by: setup.sweep_of.map(|k| setup.outputs[k].name.clone()),
            order: setup.order,
            drive: state,
            columns: (setup.outputs.iter())
                .map(|o| columns(o, &setup.context.units, drive_dimension).len())
                .sum(),
            dead_positions: (setup.outputs.iter())
                .filter(|o| o.dead_positions)
                .map(|o| o.name.clone())
                .collect(),
            dynamics: (setup.dynamics)
                .filter(|d| !d.outputs.is_empty())
                .map(|d| d.plan(&setup.mechanism)),
            loops: Vec::new(),
            backend: None,
        }
    }

    /// Records who evaluates the sweep's positions: each loop's path and the run-time
    /// evaluator's back end (for the plan line; see [`super::Sweeper::loops`]).
    pub(crate) fn evaluated_by(
        &mut self,
        loops: Vec<crate::evaluator::LoopPlan>,
        backend: Option<mechdiff_core::trace::Backend>,
    ) {
        self.loops = loops;
        self.backend = backend;
    }
}

impl fmt::Display for Plan {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} drive positions, derivative order {}",
            self.positions, self.order
        )
    }
}
