//! The run-time evaluator of a *mixed plan* (a loop without a closed form, see
//! [`super::NewtonBlock`]): the traced graph compiled into programs whose inputs are the
//! drive position and the Newton loops' coordinates with their derivatives, and each Newton
//! loop solved between them as the solver's Newton path solves it.
//!
//! Per Newton loop, one program computes its residual Φ and Jacobian Φ_q, one per order k
//! its right-hand side `R_k` (`Φ_q q⁽ᵏ⁾ = −R_k`); a last program computes the outputs' jets
//! and the closed-form loops' guards. A step (at most the solver's longest) is the solver's:
//! the Taylor predictor `q + h q′ + h²/2 q″`, Newton until max |Φ| ≤ tolerance × size, the
//! loop's condition (the solver's own measure, `branch::condition`, on Φ_q scaled as the
//! solver scales it) and branch (the sign of det Φ_q), one polishing step, Φ_q factorised
//! again at the polished pose, then q′, q″, … with that factorisation, and every guard of
//! the closed-form loops. A step that fails (Newton, the branch, a guard) is halved as the
//! solver halves it; where the solver would report an error (a toggle, or a step still
//! failing after its halvings), [`MixedTracker::move_to`] says `None` and the solver takes
//! the move from the last position and reports, as for [`super::ProgramTracker`]. The
//! generated code of the same scene (`mechdiff codegen`) runs the same algorithm on the
//! same graph: the two agree bit for bit (tests/scene_codegen.rs).

use nalgebra::DMatrix;

use super::{GuardKind, PositionGraph, Program, coordinate_symbol};
use crate::Error;
use crate::geometry::Tracker;
use crate::geometry::branch::{self, Loop};
use crate::geometry::halving::{Attempt, StepHalving};
use crate::symbolic::Id;

/// How a step ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Step {
    Accepted,
    /// Newton failed, a branch flipped, a guard failed: the step is halved.
    Failed,
    /// A toggle (the solver reports it at once).
    Singular,
}

/// One Newton loop as the evaluator solves it.
#[derive(Debug, Clone)]
struct Block {
    /// The loop's index in the solver's tracker.
    loop_index: usize,
    /// Its coordinates of order k are the inputs `at + k·n .. at + (k + 1)·n`.
    at: usize,
    n: usize,
    /// Φ (n values) then Φ_q (n × n, row by row).
    system: Program,
    /// `R_1`, `R_2`, …
    lifts: Vec<Program>,
    row_scales: Vec<f64>,
    column_scales: Vec<f64>,
}

/// The run-time evaluator of a mixed plan walking a sweep (see the module documentation).
#[derive(Debug, Clone)]
pub struct MixedTracker {
    blocks: Vec<Block>,
    /// The caller's values, then `[discriminant, condition]` per closed-form loop.
    outputs: Program,
    kinds: Vec<GuardKind>,
    values: usize,
    order: usize,
    /// The drive position, then every block's coordinates, order by order: at the position
    /// reached, and on trial.
    inputs: Vec<f64>,
    trial: Vec<f64>,
    /// Each block's branch (the sign of det Φ_q; 0 before the first position).
    branches: Vec<f64>,
    trial_branches: Vec<f64>,
    /// `inputs` and `branches` at the start of a move, restored if it fails.
    saved_inputs: Vec<f64>,
    saved_branches: Vec<f64>,
    /// Registers of each program (`outputs`, then the blocks' `system` and `lifts`).
    registers: Vec<Vec<f64>>,
    out: Vec<f64>,
    /// Buffers of a block's solve: its program's outputs, the factorised matrix, pivots,
    /// a right-hand side.
    system_out: Vec<f64>,
    lu: Vec<f64>,
    pivots: Vec<usize>,
    rhs: Vec<f64>,
    limit: f64,
    tolerance: f64,
    max_iterations: usize,
    max_substeps: usize,
    max_subdivisions: usize,
    longest: f64,
}

impl MixedTracker {
    /// Compiles `values` (nodes of `position`'s graph, jets already taken with
    /// [`PositionGraph::jets`]) with the Newton loops' programs, and walks to the drive
    /// position of `tracker` (the sketch), whose mechanism `position` traces.
    ///
    /// # Errors
    /// [`Error::NoClosedForm`] if `position` has no Newton loop (use
    /// [`super::ProgramTracker`]) or the program cannot solve the sketch (the solver can: a
    /// bug, reported rather than walked); [`Error::UnboundSymbol`] for a symbol the graph
    /// should not have.
    pub fn new(
        tracker: &Tracker<'_>,
        position: &PositionGraph,
        values: &[Id],
    ) -> Result<Self, Error> {
        let first = position.newton.first().ok_or_else(|| Error::NoClosedForm {
            what: "the mixed-plan evaluator (every loop has a closed form: use the program)"
                .to_owned(),
            joints: Vec::new(),
        })?;
        let order = first.derivatives.len();
        // The inputs: φ, then each block's coordinates of orders 0 to `order`.
        let mut names = vec![super::DRIVE.to_owned()];
        let mut blocks = Vec::new();
        for b in &position.newton {
            let at = names.len();
            for k in 0..=order {
                names.extend(b.columns.iter().map(|&c| coordinate_symbol(c, k)));
            }
            blocks.push((b, at));
        }
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        let compile = |roots: &[Id]| Program::compile_inputs(&position.graph, roots, &names);
        let mut roots = values.to_vec();
        for g in &position.guards {
            roots.extend([g.discriminant, g.condition]);
        }
        let outputs = compile(&roots)?;
        let mut registers = vec![outputs.registers()];
        let mut compiled = Vec::new();
        for (b, at) in blocks {
            let mut system_roots = b.residual.clone();
            system_roots.extend(&b.jacobian);
            let system = compile(&system_roots)?;
            let lifts = (b.derivatives.iter())
                .map(|rhs| compile(rhs))
                .collect::<Result<Vec<_>, _>>()?;
            registers.push(system.registers());
            registers.extend(lifts.iter().map(Program::registers));
            compiled.push(Block {
                loop_index: b.loop_index,
                at,
                n: b.columns.len(),
                system,
                lifts,
                row_scales: b.row_scales.clone(),
                column_scales: b.column_scales.clone(),
            });
        }
        let mut inputs = vec![0.0; names.len()];
        inputs[0] = tracker.phi();
        for (b, block) in position.newton.iter().zip(&compiled) {
            inputs[block.at..block.at + block.n].copy_from_slice(&b.sketch);
        }
        let largest = compiled.iter().map(|b| b.n).max().unwrap_or(0);
        let mut walk = MixedTracker {
            out: vec![0.0; roots.len()],
            kinds: position.guards.iter().map(|g| g.kind).collect(),
            values: values.len(),
            order,
            trial: inputs.clone(),
            saved_inputs: inputs.clone(),
            inputs,
            branches: vec![0.0; compiled.len()],
            trial_branches: vec![0.0; compiled.len()],
            saved_branches: vec![0.0; compiled.len()],
            registers,
            system_out: vec![0.0; largest + largest * largest],
            lu: vec![0.0; largest * largest],
            pivots: vec![0; largest],
            rhs: vec![0.0; largest],
            limit: position.limit,
            tolerance: position.newton_tolerance,
            max_iterations: position.max_iterations,
            max_substeps: position.max_substeps,
            max_subdivisions: position.max_subdivisions,
            longest: position.longest_step,
            blocks: compiled,
            outputs,
        };
        if walk.step(tracker.phi()) != Step::Accepted {
            return Err(Error::NoClosedForm {
                what: "the mixed-plan evaluator (its Newton fails at the sketch)".to_owned(),
                joints: first.joints.clone(),
            });
        }
        walk.accept();
        Ok(walk)
    }

    /// The drive position reached.
    pub fn phi(&self) -> f64 {
        self.inputs[0]
    }

    /// Moves to `phi` in steps the solver would take at once: the values asked for at
    /// `phi`, or `None` (the tracker stays where it was) where a step needs the solver
    /// (Newton failing, a toggle, a branch flip, a guard failing, a drive position that is
    /// not finite, too many sub-steps).
    pub fn move_to(&mut self, phi: f64) -> Option<&[f64]> {
        if !self.walk(phi) {
            return None;
        }
        Some(&self.out[..self.values])
    }

    /// Places the tracker at `phi`, where the solver now stands: `false` (the tracker
    /// unmoved) if it cannot get there itself.
    pub fn restart(&mut self, phi: f64) -> bool {
        self.walk(phi)
    }

    /// Index (in the solver's tracker) of each Newton loop.
    pub fn newton_loops(&self) -> Vec<usize> {
        self.blocks.iter().map(|b| b.loop_index).collect()
    }

    /// Walks to `phi` as the solver's Newton path does, with its walk
    /// ([`StepHalving::walk`]): steps of at most the solver's longest, a failing step halved
    /// (at most the solver's number of times; a toggle is not retried). On failure restores
    /// the state of the start.
    fn walk(&mut self, phi: f64) -> bool {
        if !phi.is_finite() {
            return false;
        }
        self.saved_inputs.copy_from_slice(&self.inputs);
        self.saved_branches.copy_from_slice(&self.branches);
        let halving = StepHalving {
            longest: self.longest,
            max_subdivisions: self.max_subdivisions,
            max_substeps: self.max_substeps,
        };
        let from = self.phi();
        let walked = halving.walk(
            self,
            from,
            phi,
            |walk, target, _| match walk.step(target) {
                Step::Accepted => {
                    walk.accept();
                    Ok(Attempt::Accepted)
                }
                Step::Failed => Ok(Attempt::Failed(())),
                Step::Singular => Err(()),
            },
            |_, _, ()| Err(()),
        );
        if walked.is_err() {
            self.inputs.copy_from_slice(&self.saved_inputs);
            self.branches.copy_from_slice(&self.saved_branches);
        }
        walked.is_ok()
    }

    fn accept(&mut self) {
        self.inputs.copy_from_slice(&self.trial);
        self.branches.copy_from_slice(&self.trial_branches);
    }

    /// One step to `target` into `trial` (and `out`).
    fn step(&mut self, target: f64) -> Step {
        let h = target - self.phi();
        self.trial.copy_from_slice(&self.inputs);
        self.trial[0] = target;
        let mut program = 1;
        for b in 0..self.blocks.len() {
            match self.solve_block(b, h, program) {
                Step::Accepted => program += 1 + self.blocks[b].lifts.len(),
                failure => return failure,
            }
        }
        self.outputs
            .evaluate_inputs(&self.trial, &mut self.registers[0], &mut self.out);
        let guards = &self.out[self.values..];
        let closed = (self.kinds.iter().zip(guards.chunks_exact(2)))
            .all(|(kind, g)| kind.verdict(g[0], g[1], self.limit).is_ok());
        if closed { Step::Accepted } else { Step::Failed }
    }

    /// Newton on block `b` from the predictor, the checks, the polish and the derivatives
    /// (`program`: the index of the block's first program in `registers`).
    fn solve_block(&mut self, b: usize, h: f64, program: usize) -> Step {
        let block = &self.blocks[b];
        let (at, n) = (block.at, block.n);
        for i in at..at + n {
            let second = if self.order >= 2 {
                self.inputs[i + 2 * n]
            } else {
                0.0
            };
            self.trial[i] = self.inputs[i] + h * (self.inputs[i + n] + 0.5 * h * second);
        }
        let mut converged = false;
        for iteration in 0..=self.max_iterations {
            self.evaluate_system(b, program);
            let norm = amax(&self.system_out[..n]);
            if norm <= self.tolerance {
                converged = true;
                break;
            }
            if !norm.is_finite() || iteration == self.max_iterations || !self.newton_step(b) {
                break;
            }
        }
        if !converged {
            return Step::Failed;
        }
        // The solver's checks at the converged pose: a toggle, then the branch.
        if !self.regular(b) || !self.factor(n) {
            return Step::Singular;
        }
        let sign = self.determinant(n).signum();
        if self.branches[b] != 0.0 && sign != self.branches[b] {
            return Step::Failed;
        }
        self.trial_branches[b] = sign;
        // The polishing step with that factorisation, then Φ_q factorised again.
        self.newton_step_factorised(b);
        self.evaluate_system(b, program);
        if !self.factor(n) {
            return Step::Singular;
        }
        for k in 1..=self.order {
            let lift = &self.blocks[b].lifts[k - 1];
            lift.evaluate_inputs(&self.trial, &mut self.registers[program + k], &mut self.rhs);
            for r in &mut self.rhs[..n] {
                *r = -*r;
            }
            lu_solve(&self.lu[..n * n], &self.pivots[..n], &mut self.rhs[..n]);
            let to = at + k * n;
            self.trial[to..to + n].copy_from_slice(&self.rhs[..n]);
        }
        let finite = (self.trial[at..at + (self.order + 1) * n].iter()).all(|x| x.is_finite());
        if finite { Step::Accepted } else { Step::Failed }
    }

    /// Φ and Φ_q of block `b` at the trial inputs, into `system_out`.
    fn evaluate_system(&mut self, b: usize, program: usize) {
        self.blocks[b].system.evaluate_inputs(
            &self.trial,
            &mut self.registers[program],
            &mut self.system_out,
        );
    }

    /// Factorises Φ_q (from `system_out`) into `lu`; `false` if singular.
    fn factor(&mut self, n: usize) -> bool {
        self.lu[..n * n].copy_from_slice(&self.system_out[n..n + n * n]);
        lu_factor(&mut self.lu[..n * n], &mut self.pivots[..n])
    }

    fn determinant(&self, n: usize) -> f64 {
        let mut det = 1.0;
        for k in 0..n {
            det *= self.lu[k * n + k];
            if self.pivots[k] != k {
                det = -det;
            }
        }
        det
    }

    /// One Newton step of block `b` from `system_out`: `false` if Φ_q is singular.
    fn newton_step(&mut self, b: usize) -> bool {
        let factored = self.factor(self.blocks[b].n);
        if factored {
            self.newton_step_factorised(b);
        }
        factored
    }

    /// `q −= Φ_q⁻¹ Φ` with Φ from `system_out` and Φ_q factorised in `lu`.
    fn newton_step_factorised(&mut self, b: usize) {
        let (at, n) = (self.blocks[b].at, self.blocks[b].n);
        self.rhs[..n].copy_from_slice(&self.system_out[..n]);
        lu_solve(&self.lu[..n * n], &self.pivots[..n], &mut self.rhs[..n]);
        for (q, s) in self.trial[at..at + n].iter_mut().zip(&self.rhs[..n]) {
            *q -= s;
        }
    }

    /// Whether block `b`'s Φ_q (in `system_out`) is regular by the solver's measure: the
    /// condition of the block scaled as the solver scales it, its columns of unit length.
    fn regular(&self, b: usize) -> bool {
        let block = &self.blocks[b];
        let n = block.n;
        let jacobian = &self.system_out[n..n + n * n];
        let scaled = DMatrix::from_fn(n, n, |r, c| {
            jacobian[r * n + c] * block.row_scales[r] * block.column_scales[c]
        });
        let whole = Loop {
            rows: (0..n).collect(),
            columns: (0..n).collect(),
        };
        let condition = branch::condition(&scaled, &whole, self.limit);
        !(condition.is_nan() || condition > self.limit)
    }
}

/// max |x_i|, NaN if any x_i is NaN.
fn amax(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |m, &v| {
        if v.abs() > m || v.is_nan() {
            v.abs()
        } else {
            m
        }
    })
}

/// Gaussian elimination with partial pivoting of the row-major n × n matrix `a`, in place
/// (L below the diagonal, U on and above), `pivots[k]` the row swapped with row k; `false`
/// if a pivot is zero or not finite.
fn lu_factor(a: &mut [f64], pivots: &mut [usize]) -> bool {
    let n = pivots.len();
    for k in 0..n {
        let mut p = k;
        for i in k + 1..n {
            if a[i * n + k].abs() > a[p * n + k].abs() {
                p = i;
            }
        }
        let pivot = a[p * n + k];
        if pivot == 0.0 || !pivot.is_finite() {
            return false;
        }
        if p != k {
            for j in 0..n {
                a.swap(p * n + j, k * n + j);
            }
        }
        pivots[k] = p;
        for i in k + 1..n {
            let m = a[i * n + k] / a[k * n + k];
            a[i * n + k] = m;
            for j in k + 1..n {
                a[i * n + j] -= m * a[k * n + j];
            }
        }
    }
    true
}

/// Solves `A x = b` in place with `A` factorised by [`lu_factor`].
fn lu_solve(a: &[f64], pivots: &[usize], b: &mut [f64]) {
    let n = pivots.len();
    for (k, &p) in pivots.iter().enumerate() {
        b.swap(k, p);
    }
    for i in 0..n {
        for j in 0..i {
            b[i] -= a[i * n + j] * b[j];
        }
    }
    for i in (0..n).rev() {
        for j in i + 1..n {
            b[i] -= a[i * n + j] * b[j];
        }
        b[i] /= a[i * n + i];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3 × 3 system needing a row swap: the solution against the exact one, 1e-15
    /// (a few roundings of numbers of size 1); the determinant's sign follows the swaps.
    #[test]
    fn gaussian_elimination_solves_with_pivoting() {
        // A = [[0, 2, 1], [1, 1, 0], [2, 0, 3]], x = [1, −1, 2], b = A x.
        let mut a = [0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 2.0, 0.0, 3.0];
        let mut b = [0.0, 0.0, 8.0];
        let mut pivots = [0; 3];
        assert!(lu_factor(&mut a, &mut pivots));
        lu_solve(&a, &pivots, &mut b);
        for (x, e) in b.iter().zip([1.0, -1.0, 2.0]) {
            assert!((x - e).abs() <= 1e-15, "{b:?}");
        }
        let mut singular = [1.0, 2.0, 2.0, 4.0];
        assert!(!lu_factor(&mut singular, &mut [0; 2]));
    }
}
