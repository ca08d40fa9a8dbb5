//! Running a scene: the plan, the sweep, the outputs at every drive position, and the dead
//! positions asked for.

use std::cell::RefCell;
use std::fmt;

use mechdiff_core::geometry::{Kinematics, Mechanism, Mobility, Solver, Tracker};
use mechdiff_core::num_dual::{Dual3_64, DualNum};
use mechdiff_core::{DeadPosition, DeadPositionSearch, DriveState, Jet};

use crate::error::{Error, Result};

use super::build::{mechanism, model_error};
use super::format::{Quantity, Sense};
use super::model::{Output, OutputKind, Scene};
use super::outputs::{Column, columns};
use super::units::{Dimension, Units};

/// What a run computes, printed before the table.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// Number of drive positions.
    pub positions: usize,
    /// Smallest and largest position of the sweep (SI): drive positions, or values of the
    /// output named by `given_by`.
    pub range: (f64, f64),
    /// The output whose values the sweep gives (`[sweep] of`), if any.
    pub given_by: Option<String>,
    /// Highest derivative order with respect to the drive that the outputs need.
    pub order: usize,
    /// The drive state used for velocities and accelerations, if any is asked for.
    pub drive: Option<DriveState>,
    /// Number of output columns (the drive column excluded).
    pub columns: usize,
    /// Outputs whose dead positions are searched.
    pub dead_positions: Vec<String>,
    /// The plan of the `[[dynamics]]` outputs: derivative order and effects.
    pub dynamics: Option<mechdiff_core::dynamics::Plan>,
}

impl Plan {
    /// The plan of a scene.
    pub fn of(scene: &Scene) -> Self {
        let (lo, hi) = scene
            .positions
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &p| {
                (lo.min(p), hi.max(p))
            });
        let times = scene
            .outputs
            .iter()
            .any(|o| o.quantities.iter().any(|q| q.is_time_derivative()));
        let drive = match (times, scene.drive.speed) {
            (true, Some(omega)) => Some(DriveState::accelerating(omega, scene.drive.acceleration)),
            _ => None,
        };
        let drive_dimension = scene.drive.kind.dimension();
        Plan {
            positions: scene.positions.len(),
            range: (lo, hi),
            given_by: scene.sweep_of.map(|k| scene.outputs[k].name.clone()),
            order: scene.order(),
            drive,
            columns: scene
                .outputs
                .iter()
                .map(|o| columns(o, &scene.units, drive_dimension).len())
                .sum(),
            dead_positions: scene
                .outputs
                .iter()
                .filter(|o| o.dead_positions)
                .map(|o| o.name.clone())
                .collect(),
            dynamics: scene
                .dynamics
                .as_ref()
                .filter(|d| !d.outputs.is_empty())
                .and_then(|d| super::build::mechanism(scene).ok().map(|m| d.plan(&m))),
        }
    }

    /// The plan as one line, in the scene's units.
    pub fn describe(&self, scene: &Scene) -> String {
        let what = match self.order {
            0 => "positions only (order 0)",
            1 => "positions and velocity coefficients (order 1)",
            _ => "positions, velocity and acceleration coefficients (order 2)",
        };
        let range = if let Some(k) = scene.sweep_of {
            let output = &scene.outputs[k];
            let text = |v: f64| {
                let d = output.kind.dimension();
                let u = &scene.units;
                format!("{} {}", Units::tidy(u.from_si(v, d)), u.symbol(d))
            };
            let values = if self.positions == 1 {
                format!(
                    "1 drive position where {} = {}",
                    output.name,
                    text(self.range.0)
                )
            } else {
                format!(
                    "{} drive positions where {} goes from {} to {}",
                    self.positions,
                    output.name,
                    text(self.range.0),
                    text(self.range.1)
                )
            };
            format!(
                "{values} (drive positions solved by Newton on {}')",
                output.name
            )
        } else if self.positions == 1 {
            format!("1 drive position, phi = {}", scene.drive_text(self.range.0))
        } else {
            format!(
                "{} drive positions, phi from {} to {}",
                self.positions,
                scene.drive_text(self.range.0),
                scene.drive_text(self.range.1)
            )
        };
        let motion = match self.drive {
            Some(d) => {
                let kind = scene.drive.kind;
                let u = &scene.units;
                format!(
                    "; velocities and accelerations for speed {} {}, acceleration {} {}",
                    Units::tidy(u.from_si(d.omega, kind.speed_dimension())),
                    u.symbol(kind.speed_dimension()),
                    Units::tidy(u.from_si(d.alpha, kind.acceleration_dimension())),
                    u.symbol(kind.acceleration_dimension()),
                )
            }
            None => String::new(),
        };
        let dead = if self.dead_positions.is_empty() {
            String::new()
        } else {
            format!("; dead positions of {}", self.dead_positions.join(", "))
        };
        let dynamics = match &self.dynamics {
            Some(p) => format!("\ndynamics plan: {p}"),
            None => String::new(),
        };
        format!(
            "plan: {range}; {what} by the geometry solver with implicit differentiation{motion}; \
            {} columns{dead}{dynamics}",
            self.columns
        )
    }
}

/// The dead positions of one output found in the sweep's range.
#[derive(Debug, Clone, PartialEq)]
pub struct DeadPositions {
    /// The output's name.
    pub output: String,
    /// The output's dimension (angle or length).
    pub dimension: Dimension,
    /// Each dead position: drive position φ (SI) and the output there (SI).
    pub positions: Vec<DeadPosition>,
}

impl DeadPositions {
    /// The stroke: the largest minus the smallest value at the dead positions (SI), if there
    /// are at least two.
    pub fn stroke(&self) -> Option<f64> {
        if self.positions.len() < 2 {
            return None;
        }
        let values = self.positions.iter().map(|d| d.value);
        let hi = values.clone().fold(f64::NEG_INFINITY, f64::max);
        let lo = values.fold(f64::INFINITY, f64::min);
        Some(hi - lo)
    }
}

/// The result of a run: every column at every drive position, in SI, and the dead positions.
#[derive(Debug, Clone)]
pub struct Report {
    /// The plan that was carried out.
    pub plan: Plan,
    /// The drive column first, then the outputs' columns.
    pub columns: Vec<Column>,
    /// One row per drive position: the drive value, then one value per output column (SI).
    pub rows: Vec<Vec<f64>>,
    /// The dead positions asked for.
    pub dead_positions: Vec<DeadPositions>,
    /// The dynamic outputs' run (their columns are also in `columns` and `rows`).
    pub dynamics: Option<super::dynamics::DynamicsReport>,
}

impl Report {
    /// The SI values of the column named `name` (e.g. `psi'`, `vx_C`), in row order.
    pub fn column(&self, name: &str) -> Option<Vec<f64>> {
        let k = self.columns.iter().position(|c| c.name == name)?;
        Some(self.rows.iter().map(|r| r[k]).collect())
    }
}

/// What `mechdiff check` found: the model and its mobility at the sketch pose.
#[derive(Debug, Clone)]
pub struct Checked {
    /// The geometry model built from the scene.
    pub mechanism: Mechanism,
    /// Its mobility at the sketch pose.
    pub mobility: Mobility,
    /// The loops the solver closes in turn (joint names, the drive as `drive <joint>`) and
    /// the sign of each loop's assembly branch in the sketch.
    pub loops: Vec<(Vec<String>, i8)>,
    /// The plan a run would carry out.
    pub plan: Plan,
}

/// Checks a scene without running its sweep: builds the model and checks its mobility and
/// the sketch's assembly.
pub fn check(scene: &Scene) -> Result<Checked> {
    let mechanism = mechanism(scene)?;
    let (mobility, loops) = {
        let tracker = Solver::default()
            .track(&mechanism)
            .map_err(|e| solver_error(scene, e))?;
        (tracker.mobility(), tracker.loops())
    };
    Ok(Checked {
        mechanism,
        mobility,
        loops,
        plan: Plan::of(scene),
    })
}

/// Runs a scene: solves every drive position of the sweep (keeping the sketch's assembly
/// branch), evaluates the outputs, and searches the dead positions asked for.
pub fn run(scene: &Scene) -> Result<Report> {
    let mechanism = mechanism(scene)?;
    let plan = Plan::of(scene);
    let drive_dimension = scene.drive.kind.dimension();
    let mut all = vec![Column {
        name: "phi".to_owned(),
        unit: scene.units.symbol(drive_dimension).to_owned(),
        factor: scene.units.factor(drive_dimension),
    }];
    for output in &scene.outputs {
        all.extend(columns(output, &scene.units, drive_dimension));
    }
    let positions = drive_positions(scene, &mechanism)?;
    let rows = match plan.order {
        0 | 1 => sweep::<1>(scene, &mechanism, &plan, &positions)?,
        _ => sweep::<2>(scene, &mechanism, &plan, &positions)?,
    };
    let mut dead_positions = Vec::new();
    for output in scene.outputs.iter().filter(|o| o.dead_positions) {
        dead_positions.push(DeadPositions {
            output: output.name.clone(),
            dimension: output.kind.dimension(),
            positions: search_dead_positions(scene, &mechanism, output, &positions)?,
        });
    }
    let mut rows = rows;
    let dynamics = match &scene.dynamics {
        Some(d) => super::dynamics::run(scene, d, &mechanism, &positions, scene.drive.speed)?,
        None => None,
    };
    if let Some(d) = &dynamics {
        all.extend(d.columns.iter().cloned());
        for (row, extra) in rows.iter_mut().zip(&d.rows) {
            row.extend_from_slice(extra);
        }
    }
    Ok(Report {
        plan,
        columns: all,
        rows,
        dead_positions,
        dynamics,
    })
}

/// The drive positions of the sweep: as given, or, for `[sweep] of = "output"`, solved so
/// that the output takes each given value (Newton on the output's exact velocity
/// coefficient, from the sketch or the previous position; steps limited to a quarter turn or
/// a quarter of the sketch's size).
fn drive_positions(scene: &Scene, mechanism: &Mechanism) -> Result<Vec<f64>> {
    let Some(k) = scene.sweep_of else {
        return Ok(scene.positions.clone());
    };
    let output = &scene.outputs[k];
    let mut tracker = Solver::default()
        .track(mechanism)
        .map_err(|e| solver_error(scene, e))?;
    let max_step = match scene.drive.kind {
        super::model::DriveKind::Angle => std::f64::consts::FRAC_PI_4,
        super::model::DriveKind::Displacement => 0.25 * sketch_size(scene),
    };
    let dimension = output.kind.dimension();
    let text = |v: f64| {
        format!(
            "{} {}",
            Units::tidy(scene.units.from_si(v, dimension)),
            scene.units.symbol(dimension)
        )
    };
    let mut previous = None;
    let mut drive = Vec::with_capacity(scene.positions.len());
    for &target in &scene.positions {
        let mut phi = tracker.phi();
        let mut reached = false;
        for _ in 0..60 {
            let k = solve::<1>(scene, &mut tracker, phi)?;
            let jet = evaluate(scene, &k, output, &mut previous)?[0];
            let (miss, slope) = (jet.value - target, jet.d1());
            if miss.abs() <= 4.0 * f64::EPSILON * target.abs().max(jet.value.abs()) {
                reached = true;
                break;
            }
            if slope == 0.0 || !slope.is_finite() {
                break;
            }
            let step = (miss / slope).clamp(-max_step, max_step);
            if step.abs() <= 2.0 * f64::EPSILON * phi.abs().max(1.0) {
                reached = true;
                break;
            }
            phi -= step;
        }
        if !reached {
            return Err(Error::NotReached {
                file: scene.file.clone(),
                output: output.name.clone(),
                value: text(target),
                last: scene.drive_text(tracker.phi()),
            });
        }
        drive.push(tracker.phi());
    }
    Ok(drive)
}

/// The sketch's size: the largest distance between two of its points (m).
fn sketch_size(scene: &Scene) -> f64 {
    let mut size: f64 = 0.0;
    for p in &scene.points {
        for q in &scene.points {
            size = size.max((p.sketch[0] - q.sketch[0]).hypot(p.sketch[1] - q.sketch[1]));
        }
    }
    size
}

fn sweep<const N: usize>(
    scene: &Scene,
    mechanism: &Mechanism,
    plan: &Plan,
    positions: &[f64],
) -> Result<Vec<Vec<f64>>> {
    let mut tracker = Solver::default()
        .track(mechanism)
        .map_err(|e| solver_error(scene, e))?;
    let drive = plan.drive.unwrap_or(DriveState::constant_speed(0.0));
    let mut previous: Vec<Option<f64>> = vec![None; scene.outputs.len()];
    let mut rows = Vec::with_capacity(positions.len());
    for &phi in positions {
        let k = solve::<N>(scene, &mut tracker, phi)?;
        let mut row = vec![phi];
        for (output, previous) in scene.outputs.iter().zip(previous.iter_mut()) {
            let values = evaluate(scene, &k, output, previous)?;
            for q in &output.quantities {
                for v in &values {
                    row.push(quantity(v, *q, &drive));
                }
            }
        }
        rows.push(row);
    }
    Ok(rows)
}

fn solve<'m, const N: usize>(
    scene: &Scene,
    tracker: &mut Tracker<'m>,
    phi: f64,
) -> Result<Kinematics<'m, N>> {
    tracker.move_to(phi).map_err(|e| solver_error(scene, e))?;
    tracker
        .kinematics::<N>()
        .map_err(|e| solver_error(scene, e))
}

/// One quantity of a jet: its value, a coefficient, or a time derivative.
fn quantity<const N: usize>(jet: &Jet<N>, q: Quantity, drive: &DriveState) -> f64 {
    let d = |k: usize| jet.derivative(k).unwrap_or(0.0);
    match q {
        Quantity::Position => jet.value,
        Quantity::VelocityCoefficient => d(1),
        Quantity::AccelerationCoefficient => d(2),
        Quantity::Velocity => drive.omega * d(1),
        Quantity::Acceleration => drive.alpha * d(1) + drive.omega * drive.omega * d(2),
    }
}

/// The output's jets at the current pose: `[x, y]` for a point, one jet otherwise. Angles are
/// kept continuous along the sweep through `previous`.
fn evaluate<const N: usize>(
    scene: &Scene,
    k: &Kinematics<'_, N>,
    output: &Output,
    previous: &mut Option<f64>,
) -> Result<Vec<Jet<N>>> {
    let point = |name: &str| -> Result<[Dual3_64; 2]> {
        let link = scene
            .links
            .iter()
            .find(|l| l.points.iter().any(|p| p == name))
            .expect("outputs name points carried by a link (checked when the scene was read)");
        let [x, y] = k
            .point(&link.name, name)
            .map_err(|e| solver_error(scene, e))?;
        Ok([dual(&x), dual(&y)])
    };
    Ok(match &output.kind {
        OutputKind::Point(name) => point(name)?.iter().map(jet::<N>).collect(),
        OutputKind::Angle {
            line,
            reference,
            sense,
        } => {
            let mut angle = direction(point(&line[0])?, point(&line[1])?);
            if let Some([a, b]) = reference {
                angle -= direction(point(a)?, point(b)?);
            }
            if *sense == Sense::Cw {
                angle = -angle;
            }
            let target = previous.unwrap_or_else(|| sketch_angle(scene, output));
            let turns = ((target - angle.re) / std::f64::consts::TAU).round();
            angle.re += turns * std::f64::consts::TAU;
            *previous = Some(angle.re);
            vec![jet::<N>(&angle)]
        }
        OutputKind::Slider {
            point: p,
            line: [a, b],
            ..
        } => {
            // s = (p − a)·u with u the unit direction a → b of the guide or slot (both points
            // on one link, so |b − a| is constant; it is differentiated anyway, exactly).
            let (p, a, b) = (point(p)?, point(a)?, point(b)?);
            let u = [b[0] - a[0], b[1] - a[1]];
            let norm = (u[0] * u[0] + u[1] * u[1]).sqrt();
            let s = ((p[0] - a[0]) * u[0] + (p[1] - a[1]) * u[1]) / norm;
            vec![jet::<N>(&s)]
        }
    })
}

/// The output angle at the sketch pose, where the sweep's angle continuity starts.
fn sketch_angle(scene: &Scene, output: &Output) -> f64 {
    let sketch = |name: &str| {
        scene
            .points
            .iter()
            .find(|p| p.name == name)
            .map_or([0.0, 0.0], |p| p.sketch)
    };
    let dir = |[a, b]: &[String; 2]| {
        let (a, b) = (sketch(a), sketch(b));
        (b[1] - a[1]).atan2(b[0] - a[0])
    };
    match &output.kind {
        OutputKind::Angle {
            line,
            reference,
            sense,
        } => {
            let angle = dir(line) - reference.as_ref().map_or(0.0, dir);
            if *sense == Sense::Cw { -angle } else { angle }
        }
        _ => 0.0,
    }
}

/// Direction angle of `a → b`, with derivatives.
fn direction(a: [Dual3_64; 2], b: [Dual3_64; 2]) -> Dual3_64 {
    mechdiff_core::atan2(b[1] - a[1], b[0] - a[0])
}

fn dual<const N: usize>(j: &Jet<N>) -> Dual3_64 {
    let d = |k: usize| j.derivatives.get(k).copied().unwrap_or(0.0);
    Dual3_64::new(j.value, d(0), d(1), d(2))
}

fn jet<const N: usize>(x: &Dual3_64) -> Jet<N> {
    let d = [x.v1, x.v2, x.v3];
    Jet::new(x.re, std::array::from_fn(|k| d[k]))
}

/// Every dead position of an angle or slider output in the sweep's range.
fn search_dead_positions(
    scene: &Scene,
    mechanism: &Mechanism,
    output: &Output,
    positions: &[f64],
) -> Result<Vec<DeadPosition>> {
    let (lo, hi) = positions
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &p| {
            (lo.min(p), hi.max(p))
        });
    // Sample at least as finely as the sweep, and at least 360 intervals over the range.
    let sweep_step = positions
        .windows(2)
        .map(|w| (w[1] - w[0]).abs())
        .fold(f64::INFINITY, f64::min);
    let step = sweep_step.min((hi - lo) / 360.0);
    let tracker = RefCell::new(
        Solver::default()
            .track(mechanism)
            .map_err(|e| solver_error(scene, e))?,
    );
    let previous = RefCell::new(None);
    let failure = RefCell::new(None);
    let found = DeadPositionSearch::new(lo..=hi)
        .with_step(step)
        .find_roots(|phi| {
            let mut t = tracker.borrow_mut();
            let k = t.move_to(phi).and_then(|_| t.kinematics::<3>())?;
            match evaluate(scene, &k, output, &mut previous.borrow_mut()) {
                Ok(jets) => Ok(jets[0]),
                Err(e) => {
                    *failure.borrow_mut() = Some(e);
                    Err(mechdiff_core::Error::NonFinite {
                        phi,
                        quantity: "a dead-position search output",
                    })
                }
            }
        });
    if let Some(e) = failure.into_inner() {
        return Err(e);
    }
    found.map_err(|e| solver_error(scene, e))
}

/// A core solver error, with drive positions in the scene's units.
pub(crate) fn solver_error(scene: &Scene, source: mechdiff_core::Error) -> Error {
    use mechdiff_core::Error as Core;
    let joined = |joints: &[String]| joints.join(", ");
    match source {
        Core::Unassemblable {
            phi,
            last_assembled,
            joints,
            residual,
        } => Error::Unassemblable {
            file: scene.file.clone(),
            position: scene.drive_text(phi),
            last: scene.drive_text(last_assembled),
            loop_joints: joined(&joints),
            residual,
        },
        Core::Singular {
            phi,
            condition,
            joints,
        } => Error::Singular {
            file: scene.file.clone(),
            position: scene.drive_text(phi),
            loop_joints: joined(&joints),
            condition,
        },
        Core::BranchFlip { from, to, joints } => Error::BranchFlip {
            file: scene.file.clone(),
            from: scene.drive_text(from),
            to: scene.drive_text(to),
            loop_joints: joined(&joints),
        },
        other => model_error(scene, other),
    }
}

impl fmt::Display for Plan {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} drive positions, derivative order {}",
            self.positions, self.order
        )
    }
}
