//! What `auto`, the default evaluator, chooses: the geometry solver, or the run-time
//! evaluator compiled to native code, whichever the cost model says costs a run less.
//!
//! The model counts instructions (callgrind, `scripts/callgrind_rows.sh`; load-independent):
//! a row of the solver and a row of the compiled program, each a constant plus a cost per
//! loop and per output value (a scalar output, or a coordinate of a point output, with its
//! derivatives), and the program's set-up (tracing the scene, differentiating it, compiling
//! the instruction list with cranelift), a constant plus a cost per loop and per value. The
//! program runs when its set-up is repaid by the rows it saves:
//!
//! positions × (solver row − program row) > set-up.
//!
//! The constants are fitted to the counts of the four shipped scenes
//! (`scripts/callgrind_rows.sh solver:<scene> jit:<scene>`; set-up: the `jit` count at no
//! repetition minus the `solver`'s) so that on each the model's break-even lies above the
//! measured one (the program is chosen only where it wins) and within ~5× of it:
//!
//! | scene (loops, values) | solver row | program row | set-up | break-even: measured, model |
//! |---|---|---|---|---|
//! | Whitworth (3, 2) | 4 264 | 1 598 | 2.20 M | 825, 4 091 |
//! | four-bar (2, 3) | 4 138 | 2 470 | 6.09 M | 3 651, 3 864 |
//! | rack, mechanism 001 (3, 2) | 4 793 | 2 383 | 8.21 M | 3 407, 4 091 |
//! | slider-crank (2, 2) | 4 311 | 1 850 | 2.79 M | 1 134, 3 415 |
//!
//! The set-up follows the size of the traced expressions more than the number of loops (the
//! rack's is 3.7× the Whitworth's), so the model cannot tell the Whitworth from the rack
//! and keeps the solver longer than it needs to on the smaller scenes. Per loop and per
//! value the solver's row costs 150 more than the program's, so the break-even stays below
//! 13 334 positions however many loops and values a scene has.

/// Instructions of a solver row: constant part.
const SOLVER_ROW: f64 = 2350.0;
/// Instructions of a solver row per loop (closed form in second-order dual numbers, the
/// step's checks).
const SOLVER_ROW_PER_LOOP: f64 = 450.0;
/// Instructions of a solver row per output value (read from the pose in third-order dual
/// numbers, its quantities).
const SOLVER_ROW_PER_VALUE: f64 = 500.0;
/// Instructions of a compiled program's row: constant part.
const PROGRAM_ROW: f64 = 900.0;
/// Instructions of a compiled program's row per loop (its guard, its margin's Hermite test).
const PROGRAM_ROW_PER_LOOP: f64 = 300.0;
/// Instructions of a compiled program's row per output value.
const PROGRAM_ROW_PER_VALUE: f64 = 350.0;
/// Instructions of the program's set-up: constant part.
const SETUP: f64 = 0.0;
/// Instructions of the program's set-up per loop.
const SETUP_PER_LOOP: f64 = 2.0e6;
/// Instructions of the program's set-up per output value.
const SETUP_PER_VALUE: f64 = 1.5e6;

/// The costs of a run, in instructions, as the model estimates them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Costs {
    /// One row by the solver.
    pub solver_row: f64,
    /// One row by the compiled program.
    pub program_row: f64,
    /// Setting the compiled program up, once per run.
    pub setup: f64,
}

impl Costs {
    /// The model's estimate for a scene of `loops` loops (the drive's included) and
    /// `values` output values (a point counts two).
    pub fn estimate(loops: usize, values: usize) -> Self {
        let (l, v) = (loops as f64, values as f64);
        Costs {
            solver_row: SOLVER_ROW + SOLVER_ROW_PER_LOOP * l + SOLVER_ROW_PER_VALUE * v,
            program_row: PROGRAM_ROW + PROGRAM_ROW_PER_LOOP * l + PROGRAM_ROW_PER_VALUE * v,
            setup: SETUP + SETUP_PER_LOOP * l + SETUP_PER_VALUE * v,
        }
    }

    /// Whether the compiled program costs a run of `positions` rows less than the solver.
    pub fn program_pays(&self, positions: usize) -> bool {
        positions as f64 * (self.solver_row - self.program_row) > self.setup
    }

    /// From how many positions the compiled program pays (the smallest run it is chosen
    /// for).
    pub fn break_even(&self) -> usize {
        let saved = self.solver_row - self.program_row;
        if saved <= 0.0 {
            return usize::MAX;
        }
        (self.setup / saved).floor() as usize + 1
    }
}
