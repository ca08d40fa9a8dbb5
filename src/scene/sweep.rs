//! The sweep, one drive position at a time: the tracker walks the drive positions in order
//! (keeping the sketch's assembly branch) and each position gives one row of SI values.
//! [`super::run`] collects the rows; [`crate::stream`] formats and writes them as they come.

use mechdiff_core::DriveState;
use mechdiff_core::geometry::{Kinematics, Mechanism, Tracker};

use crate::error::{Error, Result};
use crate::evaluator::{LoopPlan, ProgramPath, solver_loops};

use super::evaluate::{Resolved, evaluate, from_code, quantity};
use super::model::Scene;
use super::outputs::{Column, columns};
use super::plan::Plan;
use super::run::solver_error;

/// A pose that amplifies rounding more than this (see `Tracker::amplification`) is
/// reported as ill-conditioned: its results carry a relative error above ~2e-12.
const ILL_CONDITIONED: f64 = 1e4;

/// The most ill-conditioned position of a sweep: its amplification of rounding, drive
/// position and loop joints.
type Worst = (f64, f64, Vec<String>);

/// The columns of a scene's kinematic outputs: the drive first, then each output's.
pub fn kinematic_columns(scene: &Scene) -> Vec<Column> {
    let drive_dimension = scene.drive.kind.dimension();
    let mut all = vec![Column {
        // A cam drive's column is the cam angle θ; the driven joint follows s(θ).
        name: if scene.drive.cam.is_some() {
            "theta"
        } else {
            "phi"
        }
        .to_owned(),
        unit: scene.units.symbol(drive_dimension).to_owned(),
        factor: scene.units.factor(drive_dimension),
    }];
    for output in &scene.outputs {
        all.extend(columns(output, &scene.units, drive_dimension));
    }
    all
}

/// A sweep under way: call [`Sweeper::row`] with the drive positions in order.
#[derive(Debug)]
pub struct Sweeper<'s> {
    scene: &'s Scene,
    walk: Walk<'s>,
    worst: Option<Worst>,
    /// The run-time evaluator, when the scene's `evaluator` chose it: it takes every step
    /// it can prove, the solver the others (see [`crate::evaluator`]).
    program: Option<ProgramPath>,
}

/// The walk at the derivative order the plan needs.
#[derive(Debug)]
enum Walk<'s> {
    First(Outputs<'s>),
    Second(Outputs<'s>),
    Third(Outputs<'s>),
}

/// The tracker and what the outputs' evaluation carries from one position to the next.
#[derive(Debug)]
struct Outputs<'s> {
    tracker: Tracker<'s>,
    drive: DriveState,
    outputs: Vec<Resolved<'s>>,
    /// Each angle output's value at the previous position (angles are kept continuous).
    previous: Vec<Option<f64>>,
}

impl<'s> Sweeper<'s> {
    /// Starts a sweep at the sketch pose.
    pub fn new(scene: &'s Scene, mechanism: &'s Mechanism, plan: &Plan) -> Result<Self> {
        let tracker = mechdiff_core::geometry::Solver::default()
            .track(mechanism)
            .map_err(|e| solver_error(scene, e))?;
        let outputs = (scene.outputs.iter())
            .map(|output| Resolved::new(scene, mechanism, output))
            .collect::<Result<Vec<_>>>()?;
        let program = ProgramPath::choose(scene, &tracker)?;
        let outputs = Outputs {
            tracker,
            drive: plan.drive.unwrap_or(DriveState::constant_speed(0.0)),
            previous: vec![None; outputs.len()],
            outputs,
        };
        let walk = match plan.order {
            0 | 1 => Walk::First(outputs),
            2 => Walk::Second(outputs),
            _ => Walk::Third(outputs),
        };
        Ok(Self {
            scene,
            walk,
            worst: None,
            program,
        })
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
        let width = p.width();
        let Some(values) = p.move_to(phi) else {
            return false;
        };
        let scene = self.scene;
        match &mut self.walk {
            Walk::First(o) => o.push_code::<1>(scene, values, width, row),
            Walk::Second(o) => o.push_code::<2>(scene, values, width, row),
            Walk::Third(o) => o.push_code::<3>(scene, values, width, row),
        }
        let (amplification, joints) = p.amplification();
        if self.worst.as_ref().is_none_or(|w| amplification > w.0) {
            self.worst = Some((amplification, phi, joints.to_vec()));
        }
        true
    }

    /// Moves to drive position `phi` (SI) and writes its row into `row` (cleared first):
    /// the drive position, then every output column (SI), in [`kinematic_columns`] order.
    pub fn row(&mut self, phi: f64, row: &mut Vec<f64>) -> Result<()> {
        row.clear();
        row.push(phi);
        if self.program_row(phi, row) {
            return Ok(());
        }
        let scene = self.scene;
        if let Some(at) = self.program.as_ref().map(ProgramPath::phi) {
            // The solver takes this step from where the program stands (it has not moved
            // since the last step it took; the steps between were proven).
            let tracker = &mut self.outputs_mut().tracker;
            if tracker.phi() != at {
                tracker.move_to(at).map_err(|e| solver_error(scene, e))?;
            }
        }
        // The solver moves the driven joint: φ itself, or s(θ) for a cam drive.
        let joint = scene.drive.joint_position(phi);
        let o = match &mut self.walk {
            Walk::First(o) => {
                let k = solve::<1>(scene, &mut o.tracker, joint)?;
                o.push(scene, phi, &k, row);
                o
            }
            Walk::Second(o) => {
                let k = solve::<2>(scene, &mut o.tracker, joint)?;
                o.push(scene, phi, &k, row);
                o
            }
            Walk::Third(o) => {
                let k = solve::<3>(scene, &mut o.tracker, joint)?;
                o.push(scene, phi, &k, row);
                o
            }
        };
        let (amplification, joints) = o.tracker.amplification();
        if self.worst.as_ref().is_none_or(|w| amplification > w.0) {
            self.worst = Some((amplification, phi, joints));
        }
        if let Some(p) = &mut self.program
            && !p.restart(phi)
        {
            // The solver accepted a position whose guard the program's rounding fails:
            // the solver goes on alone.
            self.program = None;
        }
        Ok(())
    }

    fn outputs_mut(&mut self) -> &mut Outputs<'s> {
        match &mut self.walk {
            Walk::First(o) | Walk::Second(o) | Walk::Third(o) => o,
        }
    }

    /// The warnings about the rows so far: the most ill-conditioned position, if its
    /// rounding error is worth a word.
    pub fn warnings(&self) -> Vec<String> {
        let Some((amplification, phi, joints)) =
            self.worst.as_ref().filter(|w| w.0 > ILL_CONDITIONED)
        else {
            return Vec::new();
        };
        vec![format!(
            "ill-conditioned position at drive position {}: the loop of joints {} amplifies \
             rounding by {amplification:.1e} (its lever is that much shorter than in the \
             sketch); expect a relative error of about {:.0e} in the results there",
            self.scene.drive_text(*phi),
            joints.join(", "),
            amplification * f64::EPSILON,
        )]
    }
}

impl Outputs<'_> {
    /// Pushes the columns of every output from the generated code's `values` (each output
    /// row `[x, x′, …]`, `width` values).
    fn push_code<const N: usize>(
        &mut self,
        scene: &Scene,
        values: &[f64],
        width: usize,
        row: &mut Vec<f64>,
    ) {
        let mut at = 0;
        for (resolved, previous) in self.outputs.iter().zip(self.previous.iter_mut()) {
            let jets = from_code::<N>(scene, resolved, values, &mut at, width, previous);
            for q in &resolved.output.quantities {
                for v in &jets {
                    row.push(quantity(v, *q, &self.drive));
                }
            }
        }
    }

    fn push<const N: usize>(
        &mut self,
        scene: &Scene,
        phi: f64,
        k: &Kinematics<'_, N>,
        row: &mut Vec<f64>,
    ) {
        for (resolved, previous) in self.outputs.iter().zip(self.previous.iter_mut()) {
            let mut values = evaluate(scene, k, resolved, previous);
            if let Some(cam) = &scene.drive.cam {
                // Derivatives with respect to the cam angle (the chain rule through s(θ)).
                values = values.iter().map(|v| cam.joint.compose(phi, v)).collect();
            }
            for q in &resolved.output.quantities {
                for v in &values {
                    row.push(quantity(v, *q, &self.drive));
                }
            }
        }
    }
}

pub(crate) fn solve<'m, const N: usize>(
    scene: &Scene,
    tracker: &mut Tracker<'m>,
    phi: f64,
) -> Result<Kinematics<'m, N>> {
    tracker.move_to(phi).map_err(|e| solver_error(scene, e))?;
    tracker
        .kinematics::<N>()
        .map_err(|e| solver_error(scene, e))
}

/// Checks that every value of a row is finite, and still finite in the column's printed
/// unit: an overflow for some combination of inputs is an error naming the column and the
/// drive position, never an `inf` or `NaN` in the table.
pub fn check_row(scene: &Scene, columns: &[Column], row: &[f64]) -> Result<()> {
    for (value, column) in row.iter().zip(columns) {
        if !value.is_finite() || !(value / column.factor).is_finite() {
            return Err(not_finite(scene, column.header(), *value, row[0]));
        }
    }
    Ok(())
}

/// `quantity` is `value` (not finite) at drive position `phi`.
pub(crate) fn not_finite(scene: &Scene, quantity: String, value: f64, phi: f64) -> Error {
    Error::NotFinite {
        file: scene.file.clone(),
        quantity,
        value: value.to_string(),
        position: if phi.is_finite() {
            scene.drive_text(phi)
        } else {
            phi.to_string()
        },
    }
}
