//! How `mechdiff run` evaluates the positions of a sweep: by the geometry solver, or by the
//! run-time evaluator of the scene's traced closed forms (`--evaluator`).
//!
//! A scene's whole position solution — every output with its derivatives, every loop's
//! guard — is one expression graph ([`mechdiff_core::trace`]), the very graph
//! `mechdiff codegen` emits as Rust; a loop without a closed form is a Newton block of it,
//! solved by Newton inside the evaluator as the solver solves it
//! ([`mechdiff_core::trace::MixedTracker`]; plan line: `Newton in program`).
//! Compiled into an instruction list ([`mechdiff_core::trace::Program`]), it is
//! evaluated at each drive position without the solver's dual numbers and implicit
//! differentiation. Each step between two positions is accepted only as the solver would
//! accept it at once ([`mechdiff_core::trace::ProgramTracker`]); a step the
//! evaluator cannot prove (a toggle, a limit position, a branch's end, a margin too close
//! to zero to prove) is taken by the solver, which reports it exactly as in a solver run.
//! The results agree with the solver's to rounding (1e-13 relative, tested on every scene
//! of `scenes/`).
//!
//! **Interpreter or native code.** The program runs on one of two back ends that compute the
//! same values bit for bit (tested on every scene of `scenes/`, on random formulas and on
//! the guards' errors): the interpreter ([`mechdiff_core::trace::Program`]) or
//! the same instruction list compiled to machine code by cranelift
//! ([`mechdiff_core::trace::JitProgram`]). Measured in one criterion run of
//! `benches/scene_codegen.rs` (BENCHMARKS.md, "The run-time evaluator compiled to native
//! code"): Whitworth's ψ, ψ′, ψ″ cost 1.73× the hand-derived formulas compiled and 2.97×
//! interpreted (callgrind: 1.75× and 3.38× the hand formulas' instructions, the issue's
//! bound being 2.5×), and the rows of `mechdiff run` 0.70× the interpreter's; but compiling
//! costs 0.22 ms more than the interpreter's set-up for `scenes/whitworth.toml` (0.34 ms
//! against 0.12 ms), which the faster rows repay after about 2 600 positions. So
//! `--evaluator program` interprets a sweep of fewer than [`JIT_FROM_POSITIONS`] positions
//! (the scenes' usual hundreds) and compiles a longer one;
//! `--evaluator interpreter|jit` force one. On a host cranelift does not generate code for,
//! the JIT falls back to the interpreter with a warning.
//!
//! `auto` (the default) chooses by a cost model ([`cost`]): the compiled program where its
//! set-up (tracing, differentiating, compiling: 2.2 to 8.2 million instructions on the
//! shipped scenes) is repaid by its cheaper rows over the sweep's positions
//! (positions × (solver row − program row) > set-up, each estimated from the numbers of
//! loops and output values; the model compiles from 4 667–5 737 positions on the shipped
//! scenes, where the measured break-even is 1 249–5 365), the solver otherwise — so the usual
//! short sweeps of a few hundred positions stay on the solver and a long one runs compiled
//! code. A compiled row writes its columns straight from the program's values
//! (`row.rs`: each value row read once, the quantities fixed before the sweep). Measured
//! (callgrind instructions per position, `scripts/callgrind_rows.sh`, the default row at
//! ≥ 20 000 positions, `long:<scene>`, against the scene's generated code): Whitworth
//! 1 377 (4.6× the code's 298), four-bar 1 808 (2.5× 716), rack 2 060 (2.9× 715),
//! slider-crank 1 308 (3.4× 387); the solver's rows cost 3 137–3 871. Only where every loop has a closed form, the drive is no cam
//! and no `[[dynamics]]` or `[balancing]` reads the solver's pose at every position anyway;
//! and the solver wherever the program cannot be had. The compiled rows agree with the
//! solver's to 1e-13 (tested on every scene of `scenes/`), not bit for bit (the JIT is bit
//! for bit the *interpreter*, not the solver: they differentiate differently), so a long
//! run's last printed digits may differ from `--evaluator solver`'s; the solver stays the
//! reference, and takes every step the program cannot prove.

pub(crate) mod code;
pub mod cost;
mod program;
mod row;

pub(crate) use program::{ProgramPath, solver_loops};

use std::fmt;

use mechdiff_core::trace::Backend;

/// How a run evaluates positions (`mechdiff run --evaluator`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Evaluator {
    /// The default path: the solver, or the run-time evaluator compiled to native code where
    /// the cost model says it pays (see the module documentation and [`cost`]).
    #[default]
    Auto,
    /// The geometry solver: closed forms (or Newton) in dual numbers at every position.
    Solver,
    /// The run-time evaluator of the traced closed forms (a loop without one solved by
    /// Newton inside it); an error for a scene with a cam drive. Compiled to native code
    /// for a sweep of at least [`JIT_FROM_POSITIONS`] positions whose loops all have closed
    /// forms, interpreted otherwise (see the module documentation).
    Program,
    /// The run-time evaluator, always interpreted.
    Interpreter,
    /// The run-time evaluator, always compiled to native code by cranelift (interpreted,
    /// with a warning, on a host cranelift does not generate code for).
    Jit,
}

impl fmt::Display for Evaluator {
    /// The option's value as written on the command line (`program`, `jit`, …).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Evaluator::Auto => "auto",
            Evaluator::Solver => "solver",
            Evaluator::Program => "program",
            Evaluator::Interpreter => "interpreter",
            Evaluator::Jit => "jit",
        })
    }
}

/// From how many drive positions `--evaluator program` compiles the program to native code
/// rather than interpreting it: where the compilation has paid for itself (BENCHMARKS.md).
pub const JIT_FROM_POSITIONS: usize = 2500;

/// Which path evaluates a loop in a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LoopPath {
    /// The run-time evaluator of the traced closed forms.
    Program,
    /// The solver's closed form, in dual numbers.
    ClosedForm,
    /// The solver's Newton iteration with implicit differentiation (a loop's closed form,
    /// if it has one, only seeds it).
    Newton,
    /// Newton's iteration inside the run-time evaluator (a loop without a closed form in a
    /// mixed plan: its residual, Jacobian and implicit derivatives traced).
    NewtonInProgram,
}

/// One loop of a run and the path that evaluates it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LoopPlan {
    /// The loop's joints (the drive as `drive <joint>`), as the solver names them.
    pub joints: Vec<String>,
    /// The path.
    pub path: LoopPath,
}

impl fmt::Display for LoopPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            LoopPath::Program => "program",
            LoopPath::ClosedForm => "closed form",
            LoopPath::Newton => "Newton",
            LoopPath::NewtonInProgram => "Newton in program",
        })
    }
}

impl fmt::Display for LoopPlan {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "[{}] {}", self.joints.join(", "), self.path)
    }
}

/// The words of the plan line for a run whose loops take `loops`, the run-time evaluator
/// on `backend` if it runs: by whom, and each loop's path (`by the geometry solver
/// (exact): loops [O2, drive `O2`] closed form, …`).
pub fn describe(loops: &[LoopPlan], backend: Option<Backend>) -> String {
    let each: Vec<String> = loops.iter().map(LoopPlan::to_string).collect();
    let each = each.join(", ");
    let how = match backend {
        Some(Backend::Jit) => "compiled to native code; ",
        Some(Backend::Interpreter) => "interpreted; ",
        None => "",
    };
    if loops.iter().any(|l| l.path == LoopPath::NewtonInProgram) {
        format!(
            "by the run-time evaluator of the traced closed forms and, for loops without \
             one, Newton in the program ({how}exact; a step it cannot prove is taken by the \
             geometry solver): loops {each}"
        )
    } else if loops.iter().any(|l| l.path == LoopPath::Program) {
        format!(
            "by the run-time evaluator of the traced closed forms ({how}exact; a step it \
             cannot prove is taken by the geometry solver): loops {each}"
        )
    } else if loops.iter().any(|l| l.path == LoopPath::Newton) {
        format!(
            "by the geometry solver (exact; Newton with implicit differentiation): loops {each}"
        )
    } else {
        format!("by the geometry solver (exact): loops {each}")
    }
}

#[cfg(all(test, feature = "cli"))]
mod tests {
    use super::Evaluator;
    use clap::ValueEnum;

    /// The names a run prints are the values `--evaluator` accepts (written out for a library
    /// built without clap).
    #[test]
    fn each_evaluator_displays_as_its_command_line_value() {
        for evaluator in Evaluator::value_variants() {
            let value = evaluator
                .to_possible_value()
                .expect("no variant is skipped");
            assert_eq!(evaluator.to_string(), value.get_name());
        }
    }
}
