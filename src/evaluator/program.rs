//! The run-time evaluator's side of a sweep: the scene traced, differentiated and compiled
//! once, then one program evaluation per drive position.

use mechdiff_core::geometry::Tracker;
use mechdiff_core::trace::{Backend, MixedTracker, ProgramTracker};

use mechdiff_core::DriveState;

use super::code::SceneCode;
use super::cost::Costs;
use super::row::CodeRow;
use super::{Evaluator, JIT_FROM_POSITIONS, LoopPath, LoopPlan};
use crate::error::{Error, Result};
use crate::scene::evaluate::Resolved;
use crate::scene::model::OutputKind;
use crate::scene::setup::Setup;

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
    /// Why `--evaluator jit` interprets this scene's programs (a mixed plan), if it does.
    jit_refused: Option<String>,
    /// The row's columns from the program's values ([`ProgramPath::with_row`]).
    row: Option<CodeRow>,
}

/// The evaluator of a scene whose every loop has a closed form, or of a mixed plan (its
/// loops without one solved by Newton inside the evaluator).
#[derive(Debug, Clone)]
enum Walker {
    Closed(ProgramTracker),
    Mixed(MixedTracker),
}

impl ProgramPath {
    /// The program for `setup`'s run, as its `evaluator` asks, with `tracker` the solver's
    /// tracker at the sketch: `None` for the solver.
    ///
    /// `auto` compiles the program where the cost model says it pays ([`auto_compiles`]),
    /// and keeps the solver wherever the program cannot be had (an output the trace
    /// cannot follow, a host without the JIT).
    ///
    /// # Errors
    /// For `--evaluator program|interpreter|jit` only: [`Error::NoEvaluator`] when the
    /// scene has a cam drive or an output the trace cannot follow.
    pub fn choose(setup: &Setup<'_>, tracker: &Tracker<'_>) -> Result<Option<Self>> {
        let backend = match setup.evaluator {
            Evaluator::Solver => return Ok(None),
            Evaluator::Auto if !auto_compiles(setup, tracker) => return Ok(None),
            // The solver wherever the program cannot be had, or only interpreted.
            Evaluator::Auto => {
                return Ok(Self::new(setup, tracker, Backend::Jit)
                    .ok()
                    .filter(|p| p.backend() == Backend::Jit));
            }
            Evaluator::Program if setup.positions.len() >= JIT_FROM_POSITIONS => Backend::Jit,
            Evaluator::Program | Evaluator::Interpreter => Backend::Interpreter,
            Evaluator::Jit => Backend::Jit,
        };
        Self::new(setup, tracker, backend).map(Some)
    }

    /// Traces `setup`'s scene (as `mechdiff codegen` does), with its loops' margins, and
    /// compiles it for `backend`.
    fn new(setup: &Setup<'_>, tracker: &Tracker<'_>, backend: Backend) -> Result<Self> {
        let unavailable = |reason: String| Error::NoEvaluator {
            file: setup.file().to_owned(),
            evaluator: setup.evaluator.to_string(),
            reason,
        };
        let mut code = SceneCode::trace(setup).map_err(|e| {
            let text = e.to_string();
            let file = format!("{}: ", setup.file());
            unavailable(text.strip_prefix(&file).unwrap_or(&text).to_owned())
        })?;
        let values: Vec<_> = code.jets.iter().flatten().copied().collect();
        // A mixed plan's programs have several inputs (the Newton loops' coordinates): they
        // are interpreted (`JitProgram` compiles programs of the drive position alone).
        let mut jit_refused = None;
        let walker = if code.position.newton.is_empty() {
            ProgramTracker::new(tracker, &mut code.position, &values, backend).map(Walker::Closed)
        } else {
            if setup.evaluator == Evaluator::Jit {
                jit_refused = Some(
                    "--evaluator jit: the scene has loops solved by Newton inside the \
                     run-time evaluator, whose programs are interpreted (the JIT compiles \
                     programs of the drive position alone; the same values)"
                        .to_owned(),
                );
            }
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
            jit_refused,
            row: None,
        })
    }

    /// The program writing rows of `outputs` (the run's outputs resolved, in the order
    /// traced) at derivative order `order` ([`ProgramPath::row`]).
    pub fn with_row(mut self, outputs: &[Resolved<'_>], order: usize) -> Self {
        self.row = Some(CodeRow::new(outputs, self.width, order));
        self
    }

    /// Moves to `phi` and pushes the row's output columns onto `row` (see
    /// [`CodeRow::push`]), or `false`, `row` untouched, where the solver must take the
    /// step ([`ProgramTracker::move_to`]).
    ///
    /// # Panics
    /// Without [`ProgramPath::with_row`] (a caller's bug).
    pub fn row(
        &mut self,
        phi: f64,
        previous: &mut [Option<f64>],
        drive: &DriveState,
        row: &mut Vec<f64>,
    ) -> bool {
        let columns = self
            .row
            .as_mut()
            .expect("ProgramPath::with_row before rows");
        let values = match &mut self.tracker {
            Walker::Closed(t) => t.move_to(phi),
            Walker::Mixed(t) => t.move_to(phi),
        };
        let Some(values) = values else {
            return false;
        };
        columns.push(values, previous, drive, row);
        true
    }

    /// The back end evaluating the program.
    pub fn backend(&self) -> Backend {
        match &self.tracker {
            Walker::Closed(t) => t.backend(),
            Walker::Mixed(_) => Backend::Interpreter,
        }
    }

    /// The warning of a run whose JIT is not available on this host, or that asked for the
    /// JIT on a mixed plan (the programs are interpreted instead: the same values).
    pub fn jit_warning(&self) -> Option<String> {
        match &self.tracker {
            Walker::Closed(t) => t
                .jit_unavailable()
                .map(|e| format!("{e}: the run-time evaluator is interpreted (the same values)")),
            Walker::Mixed(_) => self.jit_refused.clone(),
        }
    }

    /// The drive position the program stands at.
    pub fn phi(&self) -> f64 {
        match &self.tracker {
            Walker::Closed(t) => t.phi(),
            Walker::Mixed(t) => t.phi(),
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
    /// closed-form plans only: 1 for a mixed plan), where it may exceed `worst` (the
    /// worst so far): loops certainly below it are passed over (see
    /// [`ProgramTracker::amplification_over`]), so only a result above `worst` is exact.
    pub fn amplification_over(&self, worst: f64) -> (f64, usize) {
        match &self.tracker {
            Walker::Closed(t) => {
                let (k, l) = t.amplification_over(worst);
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

/// Whether `auto` evaluates `setup`'s run by the compiled program rather than by the solver
/// (at the sketch, `tracker`): where every loop has a closed form, the drive is no cam,
/// no `[[dynamics]]` or `[balancing]` reads the solver's pose at every position anyway,
/// and the cost model says the program's set-up is repaid by its cheaper rows
/// ([`super::cost`]).
pub(crate) fn auto_compiles(setup: &Setup<'_>, tracker: &Tracker<'_>) -> bool {
    let closed = tracker.closed_form_loops();
    let plain = setup.drive().cam.is_none()
        && setup.dynamics.is_none()
        && setup.balancing.is_none()
        && closed.iter().all(|&c| c);
    plain && auto_costs(setup, closed.len()).program_pays(setup.positions.len())
}

/// The cost model's estimate for `setup`'s run with `loops` loops.
pub(crate) fn auto_costs(setup: &Setup<'_>, loops: usize) -> Costs {
    let values = (setup.outputs.iter())
        .map(|o| match o.kind {
            OutputKind::Point(_) => 2,
            _ => 1,
        })
        .sum();
    Costs::estimate(loops, values)
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
            let scene = crate::scene::parse("slider_crank.toml", &text.replace("step = 5\n", step))
                .unwrap();
            assert_eq!(scene.positions.len(), positions);
            let mut setup = Setup::of(&scene, &Default::default()).unwrap();
            let tracker = setup.solver.track(&setup.mechanism).unwrap();
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
                setup.evaluator = evaluator;
                let path = ProgramPath::choose(&setup, &tracker).unwrap().unwrap();
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
