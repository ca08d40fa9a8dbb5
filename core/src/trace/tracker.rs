//! A sweep walked by the run-time evaluator: the traced position solution evaluated by a
//! [`Program`] at each drive position, each step between two positions accepted only when
//! the solver itself would accept it at once.
//!
//! The solver's closed-form path ([`crate::geometry::Tracker::move_to`]) accepts a step when
//! every loop's guard holds at its end and every loop's margin (the discriminant or slope
//! of the guard, scaled to 1 in the sketch, with its first two derivatives in φ) is shown
//! positive over the whole step by the Hermite test of `solver::interval`, steps capped at
//! the solver's longest step. [`ProgramTracker::move_to`] makes the same checks, on the
//! program's values of the same formulas (equal to the solver's to rounding), and says
//! `None` where any of them fails: a guard, a margin, a non-finite drive position, a move
//! of more sub-steps than the solver allows. The caller then asks the solver, which halves
//! the step, locates the end of the branch, and reports — so every error and every
//! position the evaluator cannot prove is the solver's own answer.

#[cfg(feature = "jit")]
use super::JitProgram;
use super::{DRIVE, GuardKind, PositionGraph, Program};
use crate::Error;
use crate::geometry::Tracker;
use crate::geometry::closed_form::amplification;
use crate::geometry::solver::interval::{MAX_SUBSTEPS, passes};
use crate::symbolic::{Id, rules};
use num_dual::Dual2_64;

/// Which back end evaluates a [`ProgramTracker`]'s program: the same values, bit for bit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Backend {
    /// The interpreter ([`Program`]): ready as soon as compiled to instructions.
    Interpreter,
    /// Native code (`JitProgram`, feature `jit`): costs a compilation by cranelift once,
    /// then each evaluation less (BENCHMARKS.md); the interpreter where the host has no JIT
    /// or mechdiff-core is built without the feature (see
    /// [`ProgramTracker::jit_unavailable`]).
    Jit,
}

/// The program, interpreted or compiled.
#[derive(Debug, Clone)]
enum Code {
    Interpreted {
        program: Program,
        registers: Vec<f64>,
    },
    #[cfg(feature = "jit")]
    Compiled(JitProgram),
}

impl Code {
    fn evaluate(&mut self, phi: f64, out: &mut [f64]) {
        match self {
            Code::Interpreted { program, registers } => program.evaluate(phi, registers, out),
            #[cfg(feature = "jit")]
            Code::Compiled(jit) => jit.evaluate(phi, out),
        }
    }
}

/// One loop's guard as the program reads it (a loop that always closes has none to check).
#[derive(Debug, Clone, Copy)]
struct Loop {
    /// The loop's index among the position's guards.
    index: usize,
    /// Where its guard values `[disc, condition, disc′, disc″]` start in the outputs.
    at: usize,
    kind: GuardKind,
    /// The solver's margin is the discriminant (or slope) times this.
    scale: f64,
}

/// The run-time evaluator walking a sweep (see the module documentation).
///
/// ```
/// use mechdiff_core::geometry::{Drive, Mechanism, Solver};
/// use mechdiff_core::trace;
/// let m = Mechanism::builder()
///     .point("O", [0.0, 0.0]).point("A", [2.0, 0.0])
///     .ground(["O"]).link("crank", ["O", "A"])
///     .revolute("O", "ground", "crank", "O")
///     .drive(Drive::angle("O"))
///     .build().unwrap();
/// let tip = m.point_output("crank", "A").unwrap();
/// let t = Solver::default().track(&m).unwrap();
/// let mut traced = trace::trace(&t, |pose| pose.point(&tip).to_vec()).unwrap();
/// let x = traced.outputs[0];
/// let jit = trace::Backend::Jit;
/// let mut walk = trace::ProgramTracker::new(&t, &mut traced, &[x], jit).unwrap();
/// let values = walk.move_to(0.5).unwrap();
/// assert!((values[0] - 2.0 * 0.5f64.cos()).abs() < 1e-15);
/// assert!(walk.move_to(f64::NAN).is_none());
/// ```
#[derive(Debug, Clone)]
pub struct ProgramTracker {
    code: Code,
    /// The program's number of instructions.
    instructions: usize,
    /// Why the JIT asked for is not used, if it is not.
    jit_unavailable: Option<Error>,
    /// The program's outputs: the caller's values, then `[disc, condition, disc′, disc″]`
    /// loop by loop.
    out: Vec<f64>,
    values: usize,
    /// The loops with a guard to check (not those that always close), in solving order.
    loops: Vec<Loop>,
    /// The solver's singular threshold.
    limit: f64,
    /// The solver's longest step.
    longest: f64,
    /// The drive position reached, and each loop's margin there.
    phi: f64,
    margins: Vec<Dual2_64>,
    /// Margins at a step's end (swapped with `margins` when the step is accepted).
    trial: Vec<Dual2_64>,
}

impl ProgramTracker {
    /// Compiles `values` (nodes of `position`'s graph: what the caller reads at every
    /// position) with every loop's guard and margin derivatives, and starts at the drive
    /// position of `tracker` (the sketch), whose mechanism `position` traces; evaluated by
    /// `backend` (the interpreter if the JIT is not available: see
    /// [`ProgramTracker::jit_unavailable`]).
    ///
    /// # Errors
    /// The symbolic engine's limits ([`Error::ExpressionTooLarge`], …) differentiating the
    /// margins; [`Error::NoClosedForm`] if `position` has a Newton loop, or if the
    /// program's guards fail at the sketch (the
    /// solver's do not: a bug, reported rather than walked).
    pub fn new(
        tracker: &Tracker<'_>,
        position: &mut PositionGraph,
        values: &[Id],
        backend: Backend,
    ) -> Result<Self, Error> {
        if let Some(block) = position.newton.first() {
            return Err(Error::NoClosedForm {
                what: "the run-time evaluator (mixed plans are evaluated by generated code \
                       or the solver)"
                    .to_owned(),
                joints: block.joints.clone(),
            });
        }
        let mut roots = values.to_vec();
        for guard in &position.guards {
            let jet =
                position
                    .graph
                    .try_derivatives(guard.discriminant, DRIVE, 2, rules::MAX_NODES)?;
            roots.extend([guard.discriminant, guard.condition, jet[1], jet[2]]);
        }
        let program = Program::compile(&position.graph, &roots, DRIVE)?;
        let instructions = program.instructions();
        let (code, jit_unavailable) = match backend {
            Backend::Interpreter => (
                Code::Interpreted {
                    registers: program.registers(),
                    program,
                },
                None,
            ),
            #[cfg(not(feature = "jit"))]
            Backend::Jit => (
                Code::Interpreted {
                    registers: program.registers(),
                    program,
                },
                Some(Error::JitUnavailable {
                    reason: "mechdiff-core is built without its `jit` feature".to_owned(),
                }),
            ),
            #[cfg(feature = "jit")]
            Backend::Jit => match JitProgram::compile(&program) {
                Ok(jit) => (Code::Compiled(jit), None),
                Err(e) => (
                    Code::Interpreted {
                        registers: program.registers(),
                        program,
                    },
                    Some(e),
                ),
            },
        };
        let loops: Vec<Loop> = (position.guards.iter().enumerate())
            .filter(|(_, g)| g.kind != GuardKind::Always)
            .map(|(index, g)| Loop {
                index,
                at: values.len() + 4 * index,
                kind: g.kind,
                scale: g.scale,
            })
            .collect();
        let one = Dual2_64::from(1.0);
        let mut walk = ProgramTracker {
            code,
            instructions,
            jit_unavailable,
            out: vec![0.0; roots.len()],
            values: values.len(),
            limit: position.limit,
            longest: tracker.longest_step(),
            phi: tracker.phi(),
            margins: vec![one; loops.len()],
            trial: vec![one; loops.len()],
            loops,
        };
        if !walk.restart(tracker.phi()) {
            return Err(Error::NoClosedForm {
                what: "the run-time evaluator (its guards fail at the sketch)".to_owned(),
                joints: position
                    .guards
                    .first()
                    .map_or_else(Vec::new, |g| g.joints.clone()),
            });
        }
        Ok(walk)
    }

    /// The drive position reached.
    pub fn phi(&self) -> f64 {
        self.phi
    }

    /// Number of instructions of the program (see [`Program::instructions`]).
    pub fn instructions(&self) -> usize {
        self.instructions
    }

    /// The back end evaluating the program.
    pub fn backend(&self) -> Backend {
        match self.code {
            Code::Interpreted { .. } => Backend::Interpreter,
            #[cfg(feature = "jit")]
            Code::Compiled(_) => Backend::Jit,
        }
    }

    /// Why the JIT asked for is not used ([`Error::JitUnavailable`]), if it is not.
    pub fn jit_unavailable(&self) -> Option<&Error> {
        self.jit_unavailable.as_ref()
    }

    /// Evaluates at `phi` into `out` and the trial margins; `false` if a guard fails.
    fn evaluate(&mut self, phi: f64) -> bool {
        self.code.evaluate(phi, &mut self.out);
        for (lp, trial) in self.loops.iter().zip(&mut self.trial) {
            let g = &self.out[lp.at..lp.at + 4];
            if lp.kind.verdict(g[0], g[1], self.limit).is_err() {
                return false;
            }
            *trial = Dual2_64::new(g[0], g[2], g[3]) * lp.scale;
        }
        true
    }

    /// Moves to `phi` as the solver's closed-form path would in whole steps: the values
    /// asked for at `phi`, or `None` (the tracker stays where it was) where the solver
    /// must decide — a guard failing at a step's end, a margin not shown positive over a
    /// step, a drive position that is not finite, a move of more sub-steps than the
    /// solver takes.
    pub fn move_to(&mut self, phi: f64) -> Option<&[f64]> {
        if !phi.is_finite() {
            return None;
        }
        let (from, mut steps) = (self.phi, 0);
        while self.phi != phi || steps == 0 {
            let remaining = phi - self.phi;
            let target = if remaining.abs() > self.longest {
                self.phi + self.longest.copysign(remaining)
            } else {
                phi
            };
            let h = target - self.phi;
            let proven = steps < MAX_SUBSTEPS
                && self.evaluate(target)
                && (self.loops.iter().zip(&self.margins).zip(&self.trial))
                    .all(|((_, &a), &b)| passes(a, b, h));
            if !proven {
                if steps > 0 {
                    // Back to the move's start: its margins are the program's values
                    // there, evaluated again (the same bits; only a move of several
                    // sub-steps that fails pays this).
                    let restored = self.restart(from);
                    debug_assert!(restored, "the guards held at the move's start");
                }
                self.phi = from;
                return None;
            }
            std::mem::swap(&mut self.margins, &mut self.trial);
            self.phi = target;
            steps += 1;
        }
        Some(&self.out[..self.values])
    }

    /// Places the tracker at `phi` (where the solver stands after deciding a step):
    /// `false`, the tracker unmoved, if a guard fails there.
    pub fn restart(&mut self, phi: f64) -> bool {
        if !(phi.is_finite() && self.evaluate(phi)) {
            return false;
        }
        std::mem::swap(&mut self.margins, &mut self.trial);
        self.phi = phi;
        true
    }

    /// How much the current pose amplifies rounding, and in which loop (its index), as
    /// [`Tracker::amplification`] computes it from the same margins.
    pub fn amplification(&self) -> (f64, usize) {
        self.amplification_over(f64::NAN)
    }

    /// [`ProgramTracker::amplification`] where it may exceed `floor` (the worst of a sweep
    /// so far; NaN or below 1 for none): a loop whose margin shows its amplification below
    /// `floor` by far more than rounding (`|margin| floor² > 1 + 10⁻⁹` for a square root,
    /// `|margin| floor > 1 + 10⁻⁹` for a slope) is passed over without its square root and
    /// quotient. So the result equals [`ProgramTracker::amplification`]'s, loop included,
    /// whenever that is above `floor` or NaN, and is at most `floor` otherwise.
    pub fn amplification_over(&self, floor: f64) -> (f64, usize) {
        /// Margin of the test above rounding: the amplification's own rounding is a few ε.
        const CLEARLY: f64 = 1.0 + 1e-9;
        let mut worst = (1.0, 0);
        for (lp, m) in self.loops.iter().zip(&self.margins) {
            let root = lp.kind.root();
            let below = match root {
                Some(true) => m.re.abs() * floor * floor > CLEARLY,
                _ => m.re.abs() * floor > CLEARLY,
            };
            if below && floor >= 1.0 {
                continue;
            }
            let k = amplification(root, m.re);
            if k > worst.0 || k.is_nan() {
                worst = (k, lp.index);
            }
        }
        worst
    }
}

impl GuardKind {
    /// As the solver's closed form records it: `Some(true)` for a square root's
    /// discriminant, `Some(false)` for a slope, `None` for a loop that always closes.
    fn root(self) -> Option<bool> {
        match self {
            GuardKind::Always => None,
            GuardKind::Root => Some(true),
            GuardKind::Slope => Some(false),
        }
    }
}
