//! The run-time evaluator's side of a sweep: the scene traced, differentiated and compiled
//! once, then one program evaluation per drive position.

use mechdiff_core::geometry::Tracker;
use mechdiff_core::geometry::trace::ProgramTracker;

use super::{Evaluator, LoopPath, LoopPlan};
use crate::codegen::scene::SceneCode;
use crate::error::{Error, Result};
use crate::scene::model::Scene;

/// The program of a scene walking its sweep.
#[derive(Debug, Clone)]
pub(crate) struct ProgramPath {
    tracker: ProgramTracker,
    /// Values per output row: the value and its derivatives (`order + 1`).
    width: usize,
    /// Each loop's joints, for the plan line.
    joints: Vec<Vec<String>>,
    /// Each loop's index in the solver's tracker, for the warning about the most
    /// ill-conditioned position.
    loop_indices: Vec<usize>,
}

impl ProgramPath {
    /// The program for `scene`, as its `evaluator` asks, with `tracker` the solver's
    /// tracker at the sketch: `None` for the solver.
    ///
    /// # Errors
    /// For `--evaluator program` only: [`Error::NoEvaluator`] when the scene has a loop
    /// without a closed form, a cam drive, or an output the trace cannot follow.
    pub fn choose(scene: &Scene, tracker: &Tracker<'_>) -> Result<Option<Self>> {
        match scene.evaluator {
            // `auto`: the solver for now (see `evaluator`).
            Evaluator::Solver | Evaluator::Auto => Ok(None),
            Evaluator::Program => Self::new(scene, tracker).map(Some),
        }
    }

    /// Traces `scene` (as `mechdiff codegen` does), with its loops' margins, and compiles it.
    fn new(scene: &Scene, tracker: &Tracker<'_>) -> Result<Self> {
        let unavailable = |reason: String| Error::NoEvaluator {
            file: scene.file.clone(),
            reason,
        };
        let mut code = SceneCode::of(scene).map_err(|e| {
            let text = e.to_string();
            let file = format!("{}: ", scene.file);
            unavailable(text.strip_prefix(&file).unwrap_or(&text).to_owned())
        })?;
        let values: Vec<_> = code.jets.iter().flatten().copied().collect();
        let tracker = ProgramTracker::new(tracker, &mut code.position, &values)
            .map_err(|e| unavailable(e.to_string()))?;
        Ok(ProgramPath {
            tracker,
            width: code.order + 1,
            loop_indices: code.position.guards.iter().map(|g| g.loop_index).collect(),
            joints: code
                .position
                .guards
                .iter()
                .map(|g| g.joints.clone())
                .collect(),
        })
    }

    /// The drive position the program stands at.
    pub fn phi(&self) -> f64 {
        self.tracker.phi()
    }

    /// Values per output row (value and derivatives).
    pub fn width(&self) -> usize {
        self.width
    }

    /// Moves to `phi`: every output row's `[x, x′, …]` in turn, or `None` where the solver
    /// must take the step (see [`ProgramTracker::move_to`]).
    pub fn move_to(&mut self, phi: f64) -> Option<&[f64]> {
        self.tracker.move_to(phi)
    }

    /// Places the program at `phi`, where the solver now stands: `false` if its guards
    /// fail there (rounding at a guard's edge; the caller then keeps the solver).
    pub fn restart(&mut self, phi: f64) -> bool {
        self.tracker.restart(phi)
    }

    /// How much the current pose amplifies rounding, and the solver's index of the loop
    /// that does (as the solver's `Tracker::amplification_loop`).
    pub fn amplification(&self) -> (f64, usize) {
        let (k, l) = self.tracker.amplification();
        (k, self.loop_indices[l])
    }

    /// Each loop on the program path.
    pub fn loops(&self) -> Vec<LoopPlan> {
        (self.joints.iter())
            .map(|joints| LoopPlan {
                joints: joints.clone(),
                path: LoopPath::Program,
            })
            .collect()
    }
}

/// Each loop of `tracker` and the solver's path for it.
pub(crate) fn solver_loops(tracker: &Tracker<'_>) -> Vec<LoopPlan> {
    let closed = tracker.closed_form_loops();
    let all = closed.iter().all(|&c| c);
    (tracker.loops().into_iter().zip(closed))
        .map(|((joints, _), c)| LoopPlan {
            joints,
            path: if all && c {
                LoopPath::ClosedForm
            } else {
                LoopPath::Newton
            },
        })
        .collect()
}
