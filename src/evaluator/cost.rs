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
//! measured one (the program is chosen only where it wins) and within ~6× of it:
//!
//! | scene (loops, values) | solver row | program row | set-up | break-even: measured, model |
//! |---|---|---|---|---|
//! | Whitworth (3, 2) | 3 172 | 1 405 | 2.21 M | 1 249, 5 180 |
//! | four-bar (2, 3) | 3 400 | 2 267 | 6.08 M | 5 365, 5 737 |
//! | rack, mechanism 001 (3, 2) | 3 871 | 2 177 | 8.22 M | 4 851, 5 180 |
//! | slider-crank (2, 2) | 3 137 | 1 691 | 2.80 M | 1 934, 4 667 |
//!
//! (The solver rows are those that read the outputs from the pose as the move solved it;
//! a cheaper solver row moves the true break-even up, so the constants are fitted again
//! whenever either row changes.) The set-up follows the size of the traced expressions more
//! than the number of loops (the rack's is 3.7× the Whitworth's), so the model cannot tell
//! the Whitworth from the rack and keeps the solver longer than it needs to on the smaller
//! scenes. Per loop the solver's row costs 150 more than the program's and per value 100
//! more, so the break-even stays below 25 000 positions (the set-up per value ÷ the saving
//! per value) however many loops and values a scene has.

/// Instructions of a solver row: constant part.
const SOLVER_ROW: f64 = 2050.0;
/// Instructions of a solver row per loop (closed form in second-order dual numbers, the
/// step's checks).
const SOLVER_ROW_PER_LOOP: f64 = 250.0;
/// Instructions of a solver row per output value (read from the pose in third-order dual
/// numbers, its quantities).
const SOLVER_ROW_PER_VALUE: f64 = 350.0;
/// Instructions of a compiled program's row: constant part.
const PROGRAM_ROW: f64 = 750.0;
/// Instructions of a compiled program's row per loop (its guard, its margin's Hermite test).
const PROGRAM_ROW_PER_LOOP: f64 = 100.0;
/// Instructions of a compiled program's row per output value.
const PROGRAM_ROW_PER_VALUE: f64 = 250.0;
/// Instructions of the program's set-up: constant part.
const SETUP: f64 = 0.0;
/// Instructions of the program's set-up per loop.
const SETUP_PER_LOOP: f64 = 1.7e6;
/// Instructions of the program's set-up per output value.
const SETUP_PER_VALUE: f64 = 2.5e6;

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

#[cfg(test)]
mod tests {
    use super::Costs;

    /// Measured per shipped scene (`scripts/callgrind_rows.sh`, callgrind instructions,
    /// this model's table): loops, output values, the solver row, the compiled program's
    /// row, its set-up.
    const MEASURED: [(&str, usize, usize, f64, f64, f64); 4] = [
        ("whitworth", 3, 2, 3172.0, 1405.0, 2.206e6),
        ("four_bar", 2, 3, 3399.9, 2266.7, 6.079e6),
        ("rack", 3, 2, 3871.1, 2176.6, 8.218e6),
        ("slider_crank", 2, 2, 3137.0, 1691.0, 2.796e6),
    ];

    /// `auto` never compiles where the set-up exceeds what the compiled rows save: on each
    /// shipped scene the model's break-even is at or above the measured one (set-up ÷
    /// (solver row − program row)), and the model does not compile at the measured
    /// break-even; yet it compiles within 6× of it, not never.
    #[test]
    fn the_program_is_chosen_only_where_its_set_up_is_repaid() {
        for (scene, loops, values, solver_row, program_row, setup) in MEASURED {
            let model = Costs::estimate(loops, values);
            let even = model.break_even() as f64;
            let measured = setup / (solver_row - program_row);
            assert!(
                even >= measured,
                "{scene}: model {even}, measured {measured}"
            );
            let positions = measured.floor() as usize;
            assert!(!model.program_pays(positions), "{scene} at {positions}");
            assert!(
                even <= 6.0 * measured,
                "{scene}: model {even}, measured {measured}"
            );
        }
    }

    /// However many loops and values, a run long enough pays for the set-up: the model
    /// saves per loop and per value, so its break-even stays below 25 000 positions (the
    /// set-up per value ÷ the saving per value).
    #[test]
    fn every_scene_has_a_break_even() {
        for loops in 1..40 {
            for values in 1..200 {
                let even = Costs::estimate(loops, values).break_even();
                assert!(even < 25_000, "{loops} loops, {values} values: {even}");
            }
        }
    }
}
