//! The run-time evaluator's side of a sweep: the scene traced, differentiated and compiled
//! once, then one program evaluation per drive position.

use mechdiff_core::geometry::Tracker;
use mechdiff_core::geometry::trace::{MixedTracker, ProgramTracker};

use super::{Evaluator, LoopPath, LoopPlan};
use crate::codegen::scene::SceneCode;
use crate::error::{Error, Result};
use crate::scene::model::Scene;

/// The program of a scene walking its sweep.
#[derive(Debug, Clone)]
pub(crate) struct ProgramPath {
    tracker: Walker,
    /// Values per output row: the value and its derivatives (`order + 1`).
    width: usize,
    /// Each loop's joints and path, in solving order, for the plan line.
    loops: Vec<LoopPlan>,
    /// Each closed-form loop's index in the solver's tracker, for the warning about the
    /// most ill-conditioned position.
    loop_indices: Vec<usize>,
}

/// The evaluator of a scene whose every loop has a closed form, or of a mixed plan (its
/// loops without one solved by Newton inside the evaluator).
#[derive(Debug, Clone)]
enum Walker {
    Closed(ProgramTracker),
    Mixed(MixedTracker),
}

impl ProgramPath {
    /// The program for `scene`, as its `evaluator` asks, with `tracker` the solver's
    /// tracker at the sketch: `None` for the solver.
    ///
    /// # Errors
    /// For `--evaluator program` only: [`Error::NoEvaluator`] when the scene has a cam
    /// drive or an output the trace cannot follow.
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
        let walker = if code.position.newton.is_empty() {
            ProgramTracker::new(tracker, &mut code.position, &values).map(Walker::Closed)
        } else {
            MixedTracker::new(tracker, &code.position, &values).map(Walker::Mixed)
        };
        let walker = walker.map_err(|e| unavailable(e.to_string()))?;
        let position = &code.position;
        let mut loops: Vec<(usize, LoopPlan)> = (position.guards.iter())
            .map(|g| (g.loop_index, g.joints.clone(), LoopPath::Program))
            .chain(
                (position.newton.iter())
                    .map(|b| (b.loop_index, b.joints.clone(), LoopPath::NewtonInProgram)),
            )
            .map(|(l, joints, path)| (l, LoopPlan { joints, path }))
            .collect();
        loops.sort_by_key(|(l, _)| *l);
        Ok(ProgramPath {
            tracker: walker,
            width: code.order + 1,
            loop_indices: position.guards.iter().map(|g| g.loop_index).collect(),
            loops: loops.into_iter().map(|(_, plan)| plan).collect(),
        })
    }

    /// The drive position the program stands at.
    pub fn phi(&self) -> f64 {
        match &self.tracker {
            Walker::Closed(t) => t.phi(),
            Walker::Mixed(t) => t.phi(),
        }
    }

    /// Values per output row (value and derivatives).
    pub fn width(&self) -> usize {
        self.width
    }

    /// Moves to `phi`: every output row's `[x, x′, …]` in turn, or `None` where the solver
    /// must take the step (see [`ProgramTracker::move_to`]).
    pub fn move_to(&mut self, phi: f64) -> Option<&[f64]> {
        match &mut self.tracker {
            Walker::Closed(t) => t.move_to(phi),
            Walker::Mixed(t) => t.move_to(phi),
        }
    }

    /// Places the program at `phi`, where the solver now stands: `false` if its guards
    /// fail there (rounding at a guard's edge; the caller then keeps the solver).
    pub fn restart(&mut self, phi: f64) -> bool {
        match &mut self.tracker {
            Walker::Closed(t) => t.restart(phi),
            Walker::Mixed(t) => t.restart(phi),
        }
    }

    /// How much the current pose amplifies rounding, and the solver's index of the loop
    /// that does (as the solver's `Tracker::amplification_loop`, which measures it on
    /// closed-form plans only: 1 for a mixed plan).
    pub fn amplification(&self) -> (f64, usize) {
        match &self.tracker {
            Walker::Closed(t) => {
                let (k, l) = t.amplification();
                (k, self.loop_indices[l])
            }
            Walker::Mixed(_) => (1.0, 0),
        }
    }

    /// Each loop and its path in the evaluator.
    pub fn loops(&self) -> Vec<LoopPlan> {
        self.loops.clone()
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
