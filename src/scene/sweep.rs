//! The sweep, one drive position at a time: the tracker walks the drive positions in order
//! (keeping the sketch's assembly branch), solving each once, and each position gives one
//! row of SI values: the outputs', then those of `[[dynamics]]`, which read the same pose
//! (as do the counterweights of `[balancing]`), through [`mechdiff_core::sweep::Consumer`].
//! [`super::run()`] collects the rows; [`crate::stream`] formats and writes them as they come.

use mechdiff_core::geometry::{Kinematics, Tracker};
use mechdiff_core::num_dual::{Dual2_64, Dual3_64};
use mechdiff_core::sweep::Consumer;
use mechdiff_core::{DriveState, JetDual};

use crate::error::{Error, Result};
use crate::evaluator::{LoopPlan, ProgramPath, solver_loops};
use mechdiff_core::trace::Backend;

use super::balancing::BalancingSweep;
use super::dynamics::DynamicsSweep;
use super::error_context::ErrorContext;
use super::evaluate::{Resolved, evaluate_pose, quantity};
use super::model::Output;
use super::outputs::{Column, columns};
use super::plan::Plan;
use super::setup::Setup;

/// A pose that amplifies rounding more than this (see `Tracker::amplification`) is
/// reported as ill-conditioned: its results carry a relative error above ~2e-12.
const ILL_CONDITIONED: f64 = 1e4;

/// The most ill-conditioned position of a sweep: its amplification of rounding, drive
/// position and loop (in the order of `Tracker::loops`).
type Worst = (f64, f64, usize);

/// Whether `candidate` (an amplification) replaces the worst so far: a larger one, the
/// first of equals kept, NaN below every number. An associative choice, so that the worst
/// of a sweep solved in pieces, chosen among the pieces' in order, is the sequential one.
fn is_worse(candidate: f64, worst: Option<&Worst>) -> bool {
    worst.is_none_or(|w| !candidate.is_nan() && (w.0.is_nan() || candidate > w.0))
}

/// The columns of a run's kinematic `outputs`: the drive first, then each output's, in the
/// units of the scene's words `cx`.
pub fn kinematic_columns(cx: &ErrorContext<'_>, outputs: &[Output]) -> Vec<Column> {
    let (drive, units) = (cx.drive, &cx.units);
    let drive_dimension = drive.kind.dimension();
    let mut all = vec![Column {
        // A cam drive's column is the cam angle θ; the driven joint follows s(θ).
        name: if drive.cam.is_some() { "theta" } else { "phi" }.to_owned(),
        unit: units.symbol(drive_dimension).to_owned(),
        factor: units.factor(drive_dimension),
    }];
    for output in outputs {
        all.extend(columns(output, units, drive_dimension));
    }
    all
}

/// A sweep under way: call [`Sweeper::row`] with the drive positions in order. A clone
/// continues from the same state independently (see [`Sweeper::same_state`]).
#[derive(Debug, Clone)]
pub struct Sweeper<'s> {
    setup: &'s Setup<'s>,
    walk: Walk<'s>,
    worst: Option<Worst>,
    /// The run-time evaluator, when the run's `evaluator` chose it: it takes every step
    /// it can prove, the solver the others (see [`crate::evaluator`]).
    program: Option<ProgramPath>,
    /// Why the run-time evaluator is interpreted where the JIT was asked for.
    jit_warning: Option<String>,
    /// The drive position of the last row (for a cam drive, the next move goes along the
    /// cam from there); `None` at the sketch.
    last: Option<f64>,
    /// The `[[dynamics]]` outputs, fed the pose of every position the sweep solves.
    dynamics: Option<DynamicsSweep<'s>>,
    /// The counterweights of `[balancing]`, fed the pose of every position.
    balancing: Option<BalancingSweep<'s>>,
    /// What the sweep evaluated so far.
    counts: Counts,
}

/// What a sweep evaluated: each drive position is solved once by the tracker (or proven by
/// the run-time evaluator), and every consumer — the kinematic outputs, `[[dynamics]]`,
/// `[balancing]` — reads that one pose.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Counts {
    /// Rows computed.
    pub rows: usize,
    /// Moves of the sweep's tracker to a drive position (one per row the solver gives; with
    /// the run-time evaluator, one per row whose pose `[[dynamics]]` or `[balancing]` reads,
    /// and one where the solver takes over from the evaluator).
    pub solves: usize,
    /// Rows the run-time evaluator gave.
    pub program_steps: usize,
}

impl Counts {
    fn and(self, later: Counts) -> Counts {
        Counts {
            rows: self.rows + later.rows,
            solves: self.solves + later.solves,
            program_steps: self.program_steps + later.program_steps,
        }
    }
}

/// The walk at the derivative order the plan needs.
#[derive(Debug, Clone)]
enum Walk<'s> {
    First(Outputs<'s>),
    Second(Outputs<'s>),
    Third(Outputs<'s>),
}

/// The tracker and what the outputs' evaluation carries from one position to the next.
#[derive(Debug, Clone)]
struct Outputs<'s> {
    tracker: Tracker<'s>,
    drive: DriveState,
    outputs: Vec<Resolved<'s>>,
    /// Each angle output's value at the previous position (angles are kept continuous).
    previous: Vec<Option<f64>>,
    /// q‴ of the pose (the third order's buffer, reused at every position).
    dddq: Vec<f64>,
}

impl<'s> Sweeper<'s> {
    /// Starts a sweep of `setup`'s run at the sketch pose.
    pub fn new(setup: &'s Setup<'s>, plan: &Plan) -> Result<Self> {
        let tracker = (setup.solver)
            .track(&setup.mechanism)
            .map_err(|e| setup.context.solver_error(e))?;
        let outputs = (setup.outputs.iter())
            .map(|output| Resolved::new(setup, output))
            .collect::<Result<Vec<_>>>()?;
        let order = match plan.order {
            0 | 1 => 1,
            2 => 2,
            _ => 3,
        };
        let program = ProgramPath::choose(setup, &tracker)?.map(|p| p.with_row(&outputs, order));
        let jit_warning = program.as_ref().and_then(ProgramPath::jit_warning);
        let outputs = Outputs {
            tracker,
            drive: plan.drive.unwrap_or(DriveState::constant_speed(0.0)),
            previous: vec![None; outputs.len()],
            outputs,
            dddq: Vec::new(),
        };
        let walk = match order {
            1 => Walk::First(outputs),
            2 => Walk::Second(outputs),
            _ => Walk::Third(outputs),
        };
        Ok(Self {
            setup,
            walk,
            worst: None,
            program,
            jit_warning,
            last: None,
            dynamics: None,
            balancing: None,
            counts: Counts::default(),
        })
    }

    /// The sweep feeding `dynamics` and `balancing` the pose of every position it solves,
    /// after the kinematic outputs' columns: the dynamic columns are appended to each row.
    pub(crate) fn with_effects(
        mut self,
        dynamics: Option<DynamicsSweep<'s>>,
        balancing: Option<BalancingSweep<'s>>,
    ) -> Self {
        self.dynamics = dynamics;
        self.balancing = balancing;
        self
    }

    /// Sets the drive speed and acceleration the next rows are evaluated at, outputs and
    /// `[[dynamics]]` alike (the machine in motion: each row at its simulated φ̇, φ̈).
    pub(crate) fn set_drive(&mut self, drive: DriveState) {
        self.outputs_mut().drive = drive;
        if let Some(d) = &mut self.dynamics {
            d.set_drive(drive);
        }
    }

    /// What the sweep evaluated so far (of a sweep solved in pieces: the pieces kept).
    pub fn counts(&self) -> Counts {
        self.counts
    }

    /// The `[[dynamics]]` outputs' part of the sweep so far.
    pub(crate) fn dynamics(&self) -> Option<&DynamicsSweep<'s>> {
        self.dynamics.as_ref()
    }

    /// Takes the counterweights' part of the sweep, to size them.
    pub(crate) fn take_balancing(&mut self) -> Option<BalancingSweep<'s>> {
        self.balancing.take()
    }

    /// Feeds the pose the tracker stands at, drive position `phi`, to `[[dynamics]]` (its
    /// columns appended to `row`) and `[balancing]`.
    fn effects(&mut self, phi: f64, row: &mut Vec<f64>) -> Result<()> {
        let cx = &self.setup.context;
        let tracker = match &self.walk {
            Walk::First(o) | Walk::Second(o) | Walk::Third(o) => &o.tracker,
        };
        if let Some(d) = &mut self.dynamics {
            (d.at(tracker, phi, row)).map_err(|e| super::dynamics::error(cx, e))?;
        }
        if let Some(b) = &mut self.balancing {
            (b.at(tracker, phi, row)).map_err(|e| b.error(cx, e))?;
        }
        Ok(())
    }

    fn has_effects(&self) -> bool {
        self.dynamics.is_some() || self.balancing.is_some()
    }

    /// The run-time evaluator's back end, `None` on the solver (for the plan line).
    pub fn backend(&self) -> Option<Backend> {
        self.program.as_ref().map(ProgramPath::backend)
    }

    /// Each loop and the path that evaluates it (for the plan line).
    pub fn loops(&self) -> Vec<LoopPlan> {
        match &self.program {
            Some(p) => p.loops(),
            None => solver_loops(&self.outputs().tracker),
        }
    }

    fn outputs(&self) -> &Outputs<'s> {
        match &self.walk {
            Walk::First(o) | Walk::Second(o) | Walk::Third(o) => o,
        }
    }

    /// The row at `phi` from the run-time evaluator, if it proves the step there.
    fn program_row(&mut self, phi: f64, row: &mut Vec<f64>) -> bool {
        let Some(p) = &mut self.program else {
            return false;
        };
        let (Walk::First(o) | Walk::Second(o) | Walk::Third(o)) = &mut self.walk;
        if !p.row(phi, &mut o.previous, &o.drive, row) {
            return false;
        }
        // Only a loop that may beat the worst so far is measured (`amplification_over`).
        let floor = self.worst.map_or(f64::NAN, |w| w.0);
        let (amplification, l) = p.amplification_over(floor);
        if is_worse(amplification, self.worst.as_ref()) {
            self.worst = Some((amplification, phi, l));
        }
        true
    }

    /// Moves to drive position `phi` (SI) and writes its row into `row` (cleared first):
    /// the drive position, then every output column (SI), in `kinematic_columns` order.
    pub fn row(&mut self, phi: f64, row: &mut Vec<f64>) -> Result<()> {
        row.clear();
        row.push(phi);
        self.counts.rows += 1;
        let setup = self.setup;
        if self.program_row(phi, row) {
            self.counts.program_steps += 1;
            if self.has_effects() {
                // The effects read the tracker's pose: it follows the program.
                let last = self.last;
                move_along(&setup.context, &mut self.outputs_mut().tracker, last, phi)?;
                self.counts.solves += 1;
            }
            self.last = Some(phi);
            return self.effects(phi, row);
        }
        if let Some(at) = self.program.as_ref().map(ProgramPath::phi) {
            // The solver takes this step from where the program stands (it has not moved
            // since the last step it took; the steps between were proven).
            let tracker = &mut self.outputs_mut().tracker;
            if tracker.phi() != at {
                tracker
                    .move_to(at)
                    .map_err(|e| setup.context.solver_error(e))?;
                self.counts.solves += 1;
            }
        }
        let (last, cx) = (self.last, &setup.context);
        self.counts.solves += 1;
        let o = match &mut self.walk {
            // Orders 1 and 2 both read the pose in `Dual2_64`: the first derivatives of an
            // order-1 run are those of an order-2 run, bit for bit.
            Walk::First(o) => {
                move_along(cx, &mut o.tracker, last, phi)?;
                o.push_tracked::<Dual2_64, 1>(cx, phi, row)?;
                o
            }
            Walk::Second(o) => {
                move_along(cx, &mut o.tracker, last, phi)?;
                o.push_tracked::<Dual2_64, 2>(cx, phi, row)?;
                o
            }
            Walk::Third(o) => {
                move_along(cx, &mut o.tracker, last, phi)?;
                o.push_tracked::<Dual3_64, 3>(cx, phi, row)?;
                o
            }
        };
        self.last = Some(phi);
        // Only an amplification above the warning's limit can be reported (see
        // `Sweeper::warnings`): the others are not computed.
        if let Some((amplification, l)) = o.tracker.amplification_over(ILL_CONDITIONED)
            && is_worse(amplification, self.worst.as_ref())
        {
            self.worst = Some((amplification, phi, l));
        }
        if let Some(p) = &mut self.program
            && !p.restart(phi)
        {
            // The solver accepted a position whose guard the program's rounding fails:
            // the solver goes on alone.
            self.program = None;
        }
        self.effects(phi, row)
    }

    /// Whether `other` (a sweep of the same scene) continues exactly as this one: the same
    /// tracker state bit for bit (`Tracker::same_state`) and the same previous value of
    /// every angle output. Then [`Sweeper::row`] gives both the same rows, bit for bit, and
    /// the same errors.
    pub fn same_state(&self, other: &Sweeper<'_>) -> bool {
        let (a, b) = (self.outputs(), other.outputs());
        let previous = |o: &Outputs<'_>| -> Vec<Option<u64>> {
            o.previous.iter().map(|p| p.map(f64::to_bits)).collect()
        };
        // The run-time evaluator's state is not compared: a sweep on it is never taken as
        // continuing another (its pieces are solved again in order).
        self.program.is_none()
            && other.program.is_none()
            && self.last.map(f64::to_bits) == other.last.map(f64::to_bits)
            && a.tracker.same_state(&b.tracker)
            && previous(a) == previous(b)
    }

    /// Whether the sweep's state after a position is a function of the position alone and
    /// the turns of its angles, so that a sweep solved in pieces from states reached by
    /// other routes usually finds them [`Sweeper::same_state`] as the sequential ones:
    /// every loop in closed form, on the solver. Newton's poses differ in their last bits
    /// with the route (its start and its steps), so a sweep with a loop on Newton is best
    /// walked in order; so is one on the run-time evaluator (its state is not compared).
    pub fn is_route_independent(&self) -> bool {
        // Counterweights are sized from every pose in order: walked in order.
        self.program.is_none()
            && self.balancing.is_none()
            && self
                .outputs()
                .tracker
                .closed_form_loops()
                .iter()
                .all(|&c| c)
    }

    /// Forgets the most ill-conditioned position seen so far, what was evaluated and the
    /// dynamics' summary: a piece of a sweep counts its own (see [`Sweeper::follow`]).
    pub fn restart_worst(&mut self) {
        self.worst = None;
        self.counts = Counts::default();
        if let Some(d) = &mut self.dynamics {
            d.restart();
        }
    }

    /// Becomes `later`, a piece of the sweep solved from this one's state (a clone, its
    /// count restarted), keeping the most ill-conditioned position of both: the sweeper is
    /// then the one that walked this one's positions and the piece's in order.
    pub fn follow(&mut self, mut later: Sweeper<'s>) {
        let earlier_stays = match &later.worst {
            None => true,
            Some(w) => !is_worse(w.0, self.worst.as_ref()),
        };
        if earlier_stays {
            later.worst = self.worst;
        }
        later.counts = self.counts.and(later.counts);
        if let (Some(earlier), Some(d)) = (&self.dynamics, &mut later.dynamics) {
            let mut joined = earlier.clone();
            joined.then(d);
            *d = joined;
        }
        *self = later;
    }

    fn outputs_mut(&mut self) -> &mut Outputs<'s> {
        match &mut self.walk {
            Walk::First(o) | Walk::Second(o) | Walk::Third(o) => o,
        }
    }

    /// The warnings about the rows so far: a JIT asked for but not available on this host,
    /// and the most ill-conditioned position, if its rounding error is worth a word.
    pub fn warnings(&self) -> Vec<String> {
        let mut warnings: Vec<String> = self.jit_warning.iter().cloned().collect();
        let Some((amplification, phi, l)) = self.worst.as_ref().filter(|w| w.0 > ILL_CONDITIONED)
        else {
            return warnings;
        };
        let joints = self.outputs().tracker.joints_of_loop(*l);
        warnings.push(format!(
            "ill-conditioned position at drive position {}: the loop of joints {} amplifies \
             rounding by {amplification:.1e} (its lever is that much shorter than in the \
             sketch); expect a relative error of about {:.0e} in the results there",
            self.setup.context.drive_text(*phi),
            joints.join(", "),
            amplification * f64::EPSILON,
        ));
        warnings
    }
}

impl Outputs<'_> {
    /// Pushes the columns of every output at drive position `phi`, read in `D` (order N)
    /// from the pose as the tracker's move solved it (see
    /// [`mechdiff_core::geometry::PoseJets`]): every quantity
    /// once, at the order the plan needs, nothing allocated per row (the third order's q‴
    /// goes into a buffer kept from row to row).
    fn push_tracked<D: JetDual, const N: usize>(
        &mut self,
        cx: &ErrorContext<'_>,
        phi: f64,
        row: &mut Vec<f64>,
    ) -> Result<()> {
        let pose = if N >= 3 {
            (self.tracker.third_derivatives(&mut self.dddq)).map_err(|e| cx.solver_error(e))?;
            self.tracker.pose_jets_with(&self.dddq)
        } else {
            self.tracker.pose_jets()
        };
        for (resolved, previous) in self.outputs.iter().zip(self.previous.iter_mut()) {
            let mut values = evaluate_pose::<D, N>(&pose, resolved, previous);
            if let Some(cam) = &cx.drive.cam {
                // Derivatives with respect to the cam angle (the chain rule through s(θ)).
                values = values.map(|v| cam.joint.compose(phi, &v));
            }
            for q in &resolved.output.quantities {
                for v in &values {
                    row.push(quantity(v, *q, &self.drive));
                }
            }
        }
        Ok(())
    }
}

/// Moves `tracker` to drive position `phi`. The solver moves the driven joint: to φ
/// itself, or for a cam drive to s(θ) along the cam from the previous position `last`
/// (through every displacement the follower passes between them, see
/// [`mechdiff_core::cams::CamJoint::move_tracker`]; from the sketch, straight to s(θ)).
fn move_along(
    cx: &ErrorContext<'_>,
    tracker: &mut Tracker<'_>,
    last: Option<f64>,
    phi: f64,
) -> Result<()> {
    match (&cx.drive.cam, last) {
        (Some(cam), Some(from)) => {
            let offset = cx.drive.at_sketch;
            (cam.joint)
                .move_tracker(tracker, offset, from, phi)
                .map_err(|e| cx.cam_error(e))
        }
        _ => (tracker.move_to(cx.drive.joint_position(phi)))
            .map(drop)
            .map_err(|e| cx.solver_error(e)),
    }
}

/// Moves `tracker` to the driven joint's position `phi` and lifts the pose to `N`
/// derivatives.
pub(crate) fn solve<'m, const N: usize>(
    cx: &ErrorContext<'_>,
    tracker: &mut Tracker<'m>,
    phi: f64,
) -> Result<Kinematics<'m, N>> {
    tracker.move_to(phi).map_err(|e| cx.solver_error(e))?;
    tracker.kinematics::<N>().map_err(|e| cx.solver_error(e))
}

/// Checks that every value of a row is finite, and still finite in the column's printed
/// unit: an overflow for some combination of inputs is an error naming the column and the
/// drive position, never an `inf` or `NaN` in the table.
pub fn check_row(cx: &ErrorContext<'_>, columns: &[Column], row: &[f64]) -> Result<()> {
    for (value, column) in row.iter().zip(columns) {
        if !value.is_finite() || !(value / column.factor).is_finite() {
            return Err(not_finite(cx, column.header(), *value, row[0]));
        }
    }
    Ok(())
}

/// `quantity` is `value` (not finite) at drive position `phi`.
pub(crate) fn not_finite(cx: &ErrorContext<'_>, quantity: String, value: f64, phi: f64) -> Error {
    Error::NotFinite {
        file: cx.file.to_owned(),
        quantity,
        value: value.to_string(),
        position: if phi.is_finite() {
            cx.drive_text(phi)
        } else {
            phi.to_string()
        },
    }
}
