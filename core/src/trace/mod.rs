//! Code generation for mechanisms defined by geometry: a mechanism's whole position
//! solution as one symbolic expression graph.
//!
//! When every loop of a mechanism has a closed form (see [`crate::geometry::Solver::track`]), its
//! position solution is a sequence of formulas in the drive position φ. Evaluating those
//! formulas — the very code the solver runs, generic over the scalar — with [`Traced`], a
//! scalar that records into the symbolic arena ([`crate::symbolic::Graph`]), leaves them in
//! one graph: every link's coordinates, the outputs asked for, and each loop's *guard*.
//! The symbolic engine then differentiates the graph to any order, simplifies it, shares
//! subexpressions, and emits it as Rust or compiles it into a [`Program`] for the
//! allocation-free run-time evaluator.
//!
//! **Mixed plans.** A loop without a closed form is a [`NewtonBlock`]: its coordinates are
//! symbols of the graph, its residual, Jacobian and implicit-differentiation right-hand
//! sides are nodes, and the formulas after it read the symbols (their derivatives by the
//! chain rule, see `newton`). Where the graph is evaluated — the generated module's
//! `Tracker`, the run-time [`MixedTracker`] — the block is solved by Newton as the solver
//! solves it.
//!
//! **What is fixed at the trace.** The trace is taken at the sketch pose: each loop's
//! branch sign (the assembly closure the sketch shows, as the solver keeps it) and the turn
//! each angle is unwrapped to are constants of the graph. Angles from `atan2` are recorded
//! as `atan2` nodes, so they are exact in every quadrant, and lie within π of the
//! sketch's angle for the loop's own formula: an angle that turns fully jumps by 2π where
//! the solver, following a sweep, keeps it continuous (the two agree modulo 2π).
//!
//! **Guards.** Each loop's margin, as the solver checks it (see
//! `closed_form::margin`), is recorded as two nodes: its discriminant (or a slide's slope)
//! and its condition estimate `√(size / |disc|)` (`1 / |slope|`). A drive position where
//! the condition exceeds the solver's singular threshold is a toggle
//! ([`crate::Error::Singular`]); where the discriminant is negative, the loop cannot
//! assemble ([`crate::Error::Unassemblable`]): [`GuardKind::verdict`] decides this from the
//! two values exactly as the solver's closed form does.

#[cfg(feature = "jit")]
mod jit;
mod mixed;
mod newton;
mod program;
mod scalar;
mod tracker;

#[cfg(feature = "jit")]
#[cfg_attr(docsrs, doc(cfg(feature = "jit")))]
pub use jit::JitProgram;
pub use mixed::MixedTracker;
pub use newton::{NewtonBlock, coordinate_symbol};
pub use program::Program;
pub use scalar::Traced;
pub use tracker::{Backend, ProgramTracker};

use crate::Error;
use crate::geometry::constraints::Frames;
use crate::geometry::output::{PointOutput, Scalar as Quantity, ScalarOutput};
use crate::geometry::solver::Tracker;
use crate::symbolic::{Graph, Id, rules};
use num_dual::DualNum;
use num_traits::Signed;
use scalar::record;

/// The name of the drive position's symbol in traced graphs.
pub const DRIVE: &str = "phi";

/// The traced pose of a mechanism: its coordinates as [`Traced`] values, to compute the
/// outputs from (inside [`trace`]).
#[derive(Debug)]
pub struct Pose {
    phi: Traced,
    q: Vec<Traced>,
    frames: Vec<(Traced, Traced)>,
}

impl Pose {
    fn frames(&self) -> Frames<'_, Traced> {
        Frames {
            q: &self.q,
            frames: &self.frames,
        }
    }

    /// The drive position φ.
    pub fn drive(&self) -> Traced {
        self.phi
    }

    /// The position `[x, y]` of a resolved point (m).
    pub fn point(&self, point: &PointOutput) -> [Traced; 2] {
        self.frames().point(point.body, point.local)
    }

    /// A resolved angle or displacement (rad or m).
    pub fn value(&self, output: &ScalarOutput) -> Traced {
        let f = self.frames();
        match output.0 {
            Quantity::Rotation { body, offset } => f.angle(body) + offset,
            Quantity::Relative { a, b } => f.angle(b) - f.angle(a),
            Quantity::Displacement(slide) => f.displacement(&slide),
        }
    }
}

/// What a loop's guard measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GuardKind {
    /// The loop always closes (a driven crank, a gear): no guard.
    Always,
    /// A square root's discriminant: negative where the loop cannot assemble.
    Root,
    /// A slide's slope: zero at a toggle.
    Slope,
}

/// One loop's guard: nodes of the graph and how to read them.
#[derive(Debug, Clone, PartialEq)]
pub struct Guard {
    /// The loop's index in the solver's tracker (`Tracker::joints_of_loop`).
    pub loop_index: usize,
    /// The joints of the loop (as the solver's errors name them).
    pub joints: Vec<String>,
    /// What the guard measures.
    pub kind: GuardKind,
    /// The discriminant (m², m⁴; see `closed_form`) or the slope.
    pub discriminant: Id,
    /// The condition estimate (dimensionless).
    pub condition: Id,
    /// The factor that makes the discriminant (or slope) the solver's margin: its sign and
    /// size in the sketch (1 in the sketch's shape; see [`ProgramTracker`]).
    pub scale: f64,
}

/// Why a loop fails at a drive position, as [`GuardKind::verdict`] finds it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GuardFailure {
    /// The loop cannot assemble (its discriminant is negative).
    Unassemblable,
    /// The loop is at (or too near) a toggle: its condition estimate.
    Singular {
        /// The condition estimate.
        condition: f64,
    },
}

impl GuardKind {
    /// The verdict on a loop whose guard values are `discriminant` and `condition`, with
    /// the solver's singular threshold `limit`: the checks of the solver's closed form
    /// (`ClosedForm::root`, `ClosedForm::slope`), in the same order.
    pub fn verdict(
        self,
        discriminant: f64,
        condition: f64,
        limit: f64,
    ) -> Result<(), GuardFailure> {
        if self == GuardKind::Always {
            return Ok(());
        }
        if condition.is_nan() || condition > limit {
            return Err(GuardFailure::Singular { condition });
        }
        if self == GuardKind::Root && discriminant < 0.0 {
            return Err(GuardFailure::Unassemblable);
        }
        Ok(())
    }
}

/// A mechanism's position solution as one graph in the drive position [`DRIVE`].
#[derive(Debug, Clone)]
pub struct PositionGraph {
    /// The graph.
    pub graph: Graph,
    /// The outputs' values, in the order they were traced.
    pub outputs: Vec<Id>,
    /// One guard per loop, in solving order.
    pub guards: Vec<Guard>,
    /// The solver's singular threshold (see [`crate::geometry::Solver::singular_threshold`]).
    pub limit: f64,
    /// The drive position of the sketch, where the trace was taken.
    pub sketch_drive: f64,
    /// The loops solved by Newton's method, in solving order (empty when every loop has a
    /// closed form).
    pub newton: Vec<NewtonBlock>,
    /// Newton's convergence limit on max |Φ| (m or rad): the solver's tolerance times the
    /// linkage's length scale (the extent of its loops' points; see
    /// [`crate::geometry::Solver::tolerance`]).
    pub newton_tolerance: f64,
    /// The solver's Newton iterations per attempt.
    pub max_iterations: usize,
    /// The solver's step halvings before a failure is reported.
    pub max_subdivisions: usize,
    /// The solver's longest step of the drive (rad or m).
    pub longest_step: f64,
    /// The solver's most sub-steps in one move.
    pub max_substeps: usize,
}

/// Traces the position solution of `tracker`'s mechanism and the outputs `outputs`
/// computes from its pose: the loops with a closed form as formulas, each other loop as a
/// [`NewtonBlock`] (its coordinates as symbols, its residual and Jacobian as nodes).
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
/// let traced = trace::trace(&t, |pose| pose.point(&tip).to_vec()).unwrap();
/// assert!(traced.newton.is_empty());
/// let x = traced.graph.evaluate_f64(&traced.outputs[..1], &[("phi", 0.5)]).unwrap();
/// assert!((x[0] - 2.0 * 0.5f64.cos()).abs() < 1e-15);
/// ```
///
/// # Errors
/// [`Error::Untraceable`] if the outputs use an operation without a symbolic form;
/// [`Error::ExpressionTooLarge`] if a Newton loop's Jacobian outgrows the engine's limit.
pub fn trace(
    tracker: &Tracker<'_>,
    outputs: impl FnOnce(&Pose) -> Vec<Traced>,
) -> Result<PositionGraph, Error> {
    let closed = tracker.closed_form_table();
    // The loops the solver solves in closed form (all that match, unless turned off).
    let in_use = tracker.closed_form_loops();
    let (eq, loops, lengths) = tracker.structure();
    let sketch = tracker.coordinates();
    let phi0 = tracker.phi();
    let (graph, traced) = record(Graph::new(), || {
        let phi = Traced::symbol(DRIVE, phi0);
        let mut pose = Pose {
            phi,
            q: sketch.iter().map(|&x| Traced::from(x)).collect(),
            frames: sketch
                .chunks_exact(3)
                .map(|c| (Traced::from(c[2].sin()), Traced::from(c[2].cos())))
                .collect(),
        };
        let mut guards = Vec::new();
        let mut blocks: Vec<(usize, Vec<Id>)> = Vec::new();
        // A loop without a closed form: its coordinates become symbols, its rows of Φ the
        // block's residual.
        let mut newton = |l: usize, q: &mut [Traced], frames: &mut [(Traced, Traced)]| {
            let columns = &loops[l].columns;
            for &c in columns {
                q[c] = Traced::symbol(&coordinate_symbol(c, 0), sketch[c]);
                if c % 3 == 2 {
                    frames[c / 3] = q[c].sin_cos();
                }
            }
            let mut out = vec![Traced::from(0.0); eq.rows()];
            let f = Frames {
                q: &*q,
                frames: &*frames,
            };
            eq.evaluate_with(&f, phi, &mut out);
            blocks.push((l, loops[l].rows.iter().map(|&r| out[r].id()).collect()));
            Ok(())
        };
        let solved = closed.solve_each_or(
            phi,
            sketch,
            &mut pose.q,
            &mut pose.frames,
            &in_use,
            |l, margin, scale| {
                let (kind, condition) = match margin.root {
                    None => (GuardKind::Always, Traced::from(1.0)),
                    Some(true) => (GuardKind::Root, (margin.now / margin.value.abs()).sqrt()),
                    Some(false) => (GuardKind::Slope, margin.value.abs().recip()),
                };
                guards.push((l, kind, margin.value.id(), condition.id(), scale));
            },
            &mut newton,
        );
        let values: Vec<Id> = outputs(&pose).into_iter().map(Traced::id).collect();
        (solved, guards, blocks, values)
    });
    let (solved, guards, blocks, values) = traced.map_err(|operation| Error::Untraceable {
        operation: operation.to_owned(),
    })?;
    // The sketch pose assembles (the tracker was built there), so every loop closes.
    if let Err((l, _)) = solved {
        return Err(Error::NoClosedForm {
            what: "code generation (its closed form fails at the sketch: a bug)".to_owned(),
            joints: tracker.joints_of_loop(l),
        });
    }
    let mut position = PositionGraph {
        graph,
        outputs: values,
        guards: guards
            .into_iter()
            .map(|(l, kind, discriminant, condition, scale)| Guard {
                loop_index: l,
                joints: tracker.joints_of_loop(l),
                kind,
                discriminant,
                condition,
                scale,
            })
            .collect(),
        newton: Vec::new(),
        limit: tracker.solver_singular_threshold(),
        sketch_drive: phi0,
        newton_tolerance: tracker.solver().tolerance * lengths.linkage,
        max_iterations: tracker.solver().max_iterations,
        max_subdivisions: tracker.solver().max_subdivisions,
        longest_step: tracker.longest_step(),
        max_substeps: crate::geometry::solver::interval::MAX_SUBSTEPS,
    };
    for (l, residual) in blocks {
        let columns = loops[l].columns.clone();
        let length = lengths.loops[l];
        let mut block = NewtonBlock {
            loop_index: l,
            joints: tracker.joints_of_loop(l),
            sketch: columns.iter().map(|&c| sketch[c]).collect(),
            row_scales: (loops[l].rows.iter())
                .map(|&r| if eq.angular[r] { length } else { 1.0 })
                .collect(),
            column_scales: (columns.iter())
                .map(|&c| if c % 3 == 2 { length } else { 1.0 })
                .collect(),
            columns,
            residual,
            jacobian: Vec::new(),
            derivatives: Vec::new(),
        };
        block.differentiate(&mut position.graph)?;
        position.newton.push(block);
    }
    Ok(position)
}

impl PositionGraph {
    /// Every output's value and derivatives 1 to `order` with respect to φ, output by
    /// output: `[x, x′, …, x⁽ᵒʳᵈᵉʳ⁾]`.
    ///
    /// # Errors
    /// [`Error::DerivativeOrderTooHigh`], [`Error::ExpressionTooLarge`] beyond the
    /// symbolic engine's limits.
    ///
    /// With Newton loops, the derivatives are total ones (through the loops' derivative
    /// symbols, see [`NewtonBlock`]), and each block's right-hand sides `R_1 … R_order`
    /// ([`NewtonBlock::derivatives`]) are set too.
    pub fn jets(&mut self, order: usize) -> Result<Vec<Vec<Id>>, Error> {
        if self.newton.is_empty() {
            return self
                .outputs
                .clone()
                .into_iter()
                .map(|x| {
                    self.graph
                        .try_derivatives(x, DRIVE, order, rules::MAX_NODES)
                })
                .collect();
        }
        if order > rules::MAX_DERIVATIVE_ORDER {
            return Err(Error::DerivativeOrderTooHigh {
                order,
                limit: rules::MAX_DERIVATIVE_ORDER,
            });
        }
        let next = newton::successors(&self.newton, order);
        for block in &mut self.newton {
            block.lift(&mut self.graph, &next, order)?;
        }
        let mut jets = Vec::with_capacity(self.outputs.len());
        for &x in &self.outputs {
            let mut jet = vec![x];
            for _ in 0..order {
                let last = *jet.last().expect("not empty");
                jet.push(newton::total(&mut self.graph, last, &next, &|_| false)?);
            }
            jets.push(jet);
        }
        Ok(jets)
    }

    /// The guards' nodes, `[discriminant, condition]` loop by loop.
    pub fn guard_nodes(&self) -> Vec<Id> {
        self.guards
            .iter()
            .flat_map(|g| [g.discriminant, g.condition])
            .collect()
    }

    /// The first loop whose guard fails at the values `guards` (as from
    /// [`PositionGraph::guard_nodes`]), and why.
    pub fn first_failure(&self, guards: &[f64]) -> Option<(usize, GuardFailure)> {
        self.guards.iter().enumerate().find_map(|(l, g)| {
            g.kind
                .verdict(guards[2 * l], guards[2 * l + 1], self.limit)
                .err()
                .map(|f| (l, f))
        })
    }
}

/// The error the solver's closed forms give at drive position `phi`, evaluated directly
/// from the sketch pose (as the traced graph is), if any loop fails there: what a guard
/// failure of the generated code stands for, with the solver's data (residual, condition,
/// joints; `last_assembled` is the sketch's drive position).
pub fn closed_form_error(tracker: &Tracker<'_>, phi: f64) -> Option<Error> {
    let closed = tracker.closed_forms()?;
    let sketch = tracker.coordinates();
    let mut q = sketch.to_vec();
    let mut frames: Vec<(f64, f64)> = sketch.chunks_exact(3).map(|c| c[2].sin_cos()).collect();
    let mut margins = vec![0.0; tracker.closed_form_loops().len()];
    closed
        .solve_all(phi, sketch, &mut q, &mut frames, &mut margins)
        .err()
        .map(|(l, failure)| tracker.closed_failure(phi, l, failure))
}
