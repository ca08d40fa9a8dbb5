//! The run-time evaluator's side of a sweep: the scene traced, differentiated and compiled
//! once, then one program evaluation per drive position.

use mechdiff_core::geometry::Tracker;
use mechdiff_core::geometry::trace::{Backend, ProgramTracker};

use super::{Evaluator, JIT_FROM_POSITIONS, LoopPath, LoopPlan};
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
    /// For `--evaluator program|interpreter|jit` only: [`Error::NoEvaluator`] when the
    /// scene has a loop without a closed form, a cam drive, or an output the trace cannot
    /// follow.
    pub fn choose(scene: &Scene, tracker: &Tracker<'_>) -> Result<Option<Self>> {
        let backend = match scene.evaluator {
            // `auto`: the solver for now (see `evaluator`).
            Evaluator::Solver | Evaluator::Auto => return Ok(None),
            Evaluator::Program if scene.positions.len() >= JIT_FROM_POSITIONS => Backend::Jit,
            Evaluator::Program | Evaluator::Interpreter => Backend::Interpreter,
            Evaluator::Jit => Backend::Jit,
        };
        Self::new(scene, tracker, backend).map(Some)
    }

    /// Traces `scene` (as `mechdiff codegen` does), with its loops' margins, and compiles it
    /// for `backend`.
    fn new(scene: &Scene, tracker: &Tracker<'_>, backend: Backend) -> Result<Self> {
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
        let tracker = ProgramTracker::new(tracker, &mut code.position, &values, backend)
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

    /// The back end evaluating the program.
    #[cfg(test)]
    pub fn backend(&self) -> Backend {
        self.tracker.backend()
    }

    /// The warning of a run whose JIT is not available on this host (the program is
    /// interpreted instead: the same values).
    pub fn jit_warning(&self) -> Option<String> {
        self.tracker
            .jit_unavailable()
            .map(|e| format!("{e}: the run-time evaluator is interpreted (the same values)"))
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

#[cfg(test)]
mod tests {
    use super::*;

    /// `program` interprets a short sweep and compiles a long one to native code
    /// ([`JIT_FROM_POSITIONS`]); `interpreter` and `jit` do what they say whatever the length.
    #[test]
    fn the_back_end_follows_the_number_of_positions() {
        let text = std::fs::read_to_string("scenes/slider_crank.toml").unwrap();
        for (step, positions) in [("step = 5\n", 73), ("step = 0.1\n", 3601)] {
            let mut scene =
                crate::scene::parse("slider_crank.toml", &text.replace("step = 5\n", step))
                    .unwrap();
            assert_eq!(scene.positions.len(), positions);
            let mechanism = crate::scene::build::mechanism(&scene).unwrap();
            let tracker = mechdiff_core::geometry::Solver::default()
                .track(&mechanism)
                .unwrap();
            let long = positions >= JIT_FROM_POSITIONS;
            for (evaluator, want) in [
                (Evaluator::Interpreter, Backend::Interpreter),
                (Evaluator::Jit, Backend::Jit),
                (
                    Evaluator::Program,
                    if long {
                        Backend::Jit
                    } else {
                        Backend::Interpreter
                    },
                ),
            ] {
                scene.evaluator = evaluator;
                let path = ProgramPath::choose(&scene, &tracker).unwrap().unwrap();
                assert_eq!(
                    path.backend(),
                    want,
                    "{evaluator:?} over {positions} positions"
                );
                assert_eq!(path.jit_warning(), None);
            }
        }
    }
}
