//! Running the `[[dynamics]]` outputs: the planned sweep and its columns.

use mechdiff_core::cams::CamJoint;
use mechdiff_core::dynamics::run::{Run, Step, StepBuffers, step_reusing};
use mechdiff_core::dynamics::{
    Energy, JointReaction, Plan, PowerBalance, ShakingForce, ShakingSummary, Trace,
};
use mechdiff_core::geometry::{Mechanism, Tracker};
use mechdiff_core::sweep::Consumer;
use mechdiff_core::{DriveState, Scalar};

use crate::error::{Error, Result};
use crate::scene::error_context::ErrorContext;
use crate::scene::model::{Drive, DriveKind, Joint, JointKind};
use crate::scene::outputs::Column;
use crate::scene::units::{Dimension, Units};

use super::format::DynamicQuantity;
use super::resolve::{DynamicsOutput, SceneDynamics};

/// The dynamic columns of a run, their values per drive position, and summary lines.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicsReport {
    /// The plan carried out.
    pub plan: Plan,
    /// Columns: SI, or the file's force, torque, mass and inertia units (their factor).
    pub columns: Vec<Column>,
    /// One row per drive position (empty for a streamed run: its rows were written).
    pub rows: Vec<Vec<f64>>,
    /// Lines printed after the table (shaking-force extremes, power-balance check).
    pub summary: Vec<String>,
    /// The core run: the trace of what was evaluated, and every step for a run in memory
    /// (none for a streamed run).
    pub run: Run,
}

fn column(name: impl Into<String>, unit: &str) -> Column {
    Column {
        name: name.into(),
        unit: unit.to_owned(),
        factor: 1.0,
    }
}

/// The `[[dynamics]]` outputs of a sweep, one drive position at a time: at each position the
/// sweep's tracker has solved (nothing is solved here), the planned step lifted to the
/// plan's order, its columns, and what the summary lines need (the shaking force's
/// extremes, the power balance's largest residual) — so that a sweep of any length streams
/// them in constant memory. A clone continues independently; [`DynamicsSweep::then`] joins a
/// piece solved from a clone, in drive order.
#[derive(Debug, Clone)]
pub(crate) struct DynamicsSweep<'s> {
    d: &'s SceneDynamics,
    mechanism: &'s Mechanism,
    joints: &'s [Joint],
    /// A cam drive's cam, and the driven joint's position at the sketch (the follower's
    /// displacement is added to it).
    cam: Option<(&'s CamJoint, f64)>,
    model: mechdiff_core::dynamics::CompiledModel<'s>,
    plan: Plan,
    drive: DriveState,
    shaking: Option<ShakingSummary>,
    /// The largest power-balance residual relative to its largest term, so far.
    worst_balance: f64,
    trace: Trace,
    /// Every step, when the run keeps them (a run in memory, [`DynamicsReport::run`]).
    steps: Option<Vec<Step>>,
    /// The planned step's buffers, reused at every position.
    buffers: StepBuffers,
}

impl<'s> DynamicsSweep<'s> {
    /// The dynamic outputs `d` of a scene (its words `cx`) ready for a sweep (after
    /// [`before_solving`]'s checks); `None` without outputs. `keep_steps` keeps every
    /// position's step for the report (a run in memory).
    pub(crate) fn new(
        cx: &ErrorContext<'s>,
        d: &'s SceneDynamics,
        mechanism: &'s Mechanism,
        keep_steps: bool,
    ) -> Result<Option<Self>> {
        if d.outputs.is_empty() {
            return Ok(None);
        }
        let scene_drive: &'s Drive = cx.drive;
        let (model, plan, drive) = before_solving(cx, d, mechanism, scene_drive.speed)?;
        mechdiff_core::dynamics::run::check(&plan, &model).map_err(|e| cx.solver_error(e))?;
        Ok(Some(Self {
            d,
            mechanism,
            joints: cx.joints,
            cam: (scene_drive.cam.as_ref()).map(|c| (&c.joint, scene_drive.at_sketch)),
            model,
            plan,
            drive,
            shaking: None,
            worst_balance: 0.0,
            trace: Trace::default(),
            steps: keep_steps.then(Vec::new),
            buffers: StepBuffers::default(),
        }))
    }

    /// Sets the drive speed and acceleration the next positions are evaluated at.
    pub(crate) fn set_drive(&mut self, drive: DriveState) {
        self.drive = drive;
    }

    /// Forgets what was summarised so far: a piece of a sweep counts its own.
    pub(crate) fn restart(&mut self) {
        self.shaking = None;
        self.worst_balance = 0.0;
        self.trace = Trace::default();
        if let Some(steps) = &mut self.steps {
            steps.clear();
        }
    }

    /// Joins `later`, a piece solved from this one's state after [`DynamicsSweep::restart`]:
    /// the summary of both pieces, in drive order.
    pub(crate) fn then(&mut self, later: &Self) {
        self.shaking = match (&self.shaking, &later.shaking) {
            (Some(a), Some(b)) => Some(a.then(b)),
            (a, b) => a.or(*b),
        };
        self.worst_balance = self.worst_balance.max(later.worst_balance);
        self.trace.add(&later.trace);
        if let (Some(steps), Some(more)) = (&mut self.steps, &later.steps) {
            steps.extend_from_slice(more);
        }
    }

    /// The report of the sweep so far: the columns (in the units of the scene's words `cx`),
    /// the summary lines and the trace (with the steps, when kept); `rows` are the dynamic
    /// columns of the rows kept, if any.
    ///
    /// # Errors
    /// [`Error::NotFinite`] for a shaking force whose magnitude overflowed.
    pub(crate) fn report(
        &self,
        cx: &ErrorContext<'_>,
        rows: Vec<Vec<f64>>,
    ) -> Result<DynamicsReport> {
        let mut summary = Vec::new();
        let asked = |q| self.d.outputs.iter().any(|o| o.quantity == q);
        if asked(DynamicQuantity::ShakingForce)
            && let Some(s) = &self.shaking
        {
            if !s.magnitude.value.is_finite() {
                return Err(crate::error::Error::NotFinite {
                    file: cx.file.to_owned(),
                    quantity: "the magnitude of the shaking force |SumF| [N]".to_owned(),
                    value: s.magnitude.value.to_string(),
                    position: cx.drive_text(s.magnitude.phi),
                });
            }
            summary.push(format!(
                "shaking force over the sweep: SumF_x from {:.6} N (at {}) to {:.6} N (at {}); SumF_y from {:.6} N (at {}) to {:.6} N (at {}); largest |SumF| {:.6} N (at {})",
                s.force_x[0].value, cx.drive_text(s.force_x[0].phi), s.force_x[1].value, cx.drive_text(s.force_x[1].phi),
                s.force_y[0].value, cx.drive_text(s.force_y[0].phi), s.force_y[1].value, cx.drive_text(s.force_y[1].phi),
                s.magnitude.value, cx.drive_text(s.magnitude.phi),
            ));
        }
        if asked(DynamicQuantity::PowerBalance) {
            let worst = self.worst_balance;
            summary.push(format!(
                "power balance: largest residual {worst:.1e} of the largest power term"
            ));
        }
        Ok(DynamicsReport {
            plan: self.plan,
            columns: columns(cx, self.d, self.mechanism, &self.plan),
            rows,
            summary,
            run: Run {
                steps: self.steps.clone().unwrap_or_default(),
                trace: self.trace,
            },
        })
    }
}

/// The dynamic columns at drive position `phi`, from the pose the sweep's tracker stands at
/// (moved there by the sweep: for a cam drive, the joint's position s(θ)).
impl Consumer for DynamicsSweep<'_> {
    fn at(
        &mut self,
        tracker: &Tracker<'_>,
        phi: f64,
        row: &mut Vec<f64>,
    ) -> std::result::Result<(), mechdiff_core::Error> {
        // The driven joint's position and motion (through the cam's follower for a cam
        // drive).
        let (joint, state) = match self.cam {
            Some((c, at_sketch)) => {
                let (s, follower) = c.drive_at(phi, &self.drive);
                (at_sketch + s, follower)
            }
            None => (phi, self.drive),
        };
        let (plan, model, trace) = (&self.plan, &self.model, &mut self.trace);
        let step = step_reusing(plan, model, tracker, joint, state, trace, &mut self.buffers)?;
        let cam = self.cam.map(|(c, _)| {
            let [s1, s2, _] = c.svaj(phi).derivatives;
            Cam { s1, s2 }
        });
        let values = StepValues {
            solution: step.solution.as_ref().map(|s| SolutionValues {
                drive_torque: s.drive_torque,
                reactions: &s.reactions,
                motor_torque: s.motor.map(|m| m.torque),
                balance: s.balance,
            }),
            energy: step.energy,
            shaking: step.shaking.as_ref(),
        };
        let (joints, d, m) = (self.joints, self.d, self.mechanism);
        push_row(joints, d, m, &values, self.drive.omega, cam, row);
        if let Some(f) = &step.shaking {
            ShakingSummary::add(&mut self.shaking, f);
        }
        if let Some(s) = &step.solution {
            let b = &s.balance;
            let residual = b.residual.abs() / b.scale().max(f64::MIN_POSITIVE);
            self.worst_balance = self.worst_balance.max(residual);
        }
        if let Some(steps) = &mut self.steps {
            steps.push(step.clone());
        }
        Ok(())
    }
}

/// The scene's error for an error of the `[[dynamics]]` outputs at a solved pose: a
/// self-locking drive located at `[drive]`, the others with drive positions in the scene's
/// units.
pub(crate) fn error(cx: &ErrorContext<'_>, e: mechdiff_core::Error) -> Error {
    match e {
        mechdiff_core::Error::SelfLocking {
            phi,
            joints,
            reason,
        } => Error::SelfLocking {
            location: cx.drive.location.clone(),
            position: cx.joint_text(phi),
            joints: joints.join(", "),
            reason,
        },
        other => cx.solver_error(other),
    }
}

/// What `[[dynamics]]` checks before anything is solved (`mechdiff check` runs it too): the
/// model compiles with the masses, the plan's drive state has the speed it needs, and a power
/// balance has a non-zero speed to divide by. Returns the model, the plan and the drive.
pub(crate) fn before_solving<'m>(
    cx: &ErrorContext<'_>,
    d: &SceneDynamics,
    mechanism: &'m Mechanism,
    speed: Option<f64>,
) -> Result<(mechdiff_core::dynamics::CompiledModel<'m>, Plan, DriveState)> {
    let model = d.data.compile(mechanism).map_err(|source| Error::Model {
        file: cx.file.to_owned(),
        source,
    })?;
    let plan = d.plan(mechanism);
    let drive = drive_state(cx.drive, &plan, speed)?;
    if drive.omega == 0.0
        && let Some(o) = d
            .outputs
            .iter()
            .find(|o| o.quantity == DynamicQuantity::PowerBalance)
    {
        return Err(Error::Invalid {
            location: o.location.clone(),
            message: "the power balance gives the drive torque as power / speed; it needs a \
                      non-zero drive `speed`"
                .to_owned(),
        });
    }
    Ok((model, plan, drive))
}

/// The `drive`'s speed (`speed`, when the scene gives one) and acceleration for `plan`: an
/// error naming the drive when the plan needs velocities and no speed is given.
pub(super) fn drive_state(drive: &Drive, plan: &Plan, speed: Option<f64>) -> Result<DriveState> {
    match speed {
        Some(omega) => Ok(DriveState::accelerating(omega, drive.acceleration)),
        None if plan.order >= 1 => Err(Error::Invalid {
            location: drive.location.clone(),
            message: "the `[[dynamics]]` outputs need the drive's `speed`".to_owned(),
        }),
        None => Ok(DriveState::constant_speed(0.0)),
    }
}

/// The equilibrium's numbers one row reads, in scalar `T` (`f64`, or `Dual64` for the
/// exact derivatives).
pub(super) struct SolutionValues<'a, T> {
    pub drive_torque: T,
    pub reactions: &'a [JointReaction<T>],
    pub motor_torque: Option<T>,
    pub balance: PowerBalance<T>,
}

/// The results at one drive position one row reads; what the plan did not ask for is `None`.
pub(super) struct StepValues<'a, T> {
    pub solution: Option<SolutionValues<'a, T>>,
    pub energy: Option<Energy<T>>,
    pub shaking: Option<&'a ShakingForce<T>>,
}

/// A cam drive's follower motion at one position: `s′`, `s″` with respect to the cam angle.
#[derive(Clone, Copy)]
pub(super) struct Cam<T> {
    pub s1: T,
    pub s2: T,
}

/// One row of the dynamic columns (in the order of [`columns`]), from one position's results
/// in any scalar: the `f64` table, and (with `Dual64`) its exact derivatives, pushed onto
/// `row`. `joints` are the scene's (their kinds say which numbers a reaction has); `omega`
/// is the drive speed. Nothing is allocated but `row`'s growth.
pub(super) fn push_row<T: Scalar>(
    joints: &[Joint],
    d: &SceneDynamics,
    m: &Mechanism,
    step: &StepValues<'_, T>,
    omega: T,
    cam: Option<Cam<T>>,
    row: &mut Vec<T>,
) {
    for o in &d.outputs {
        push_output_row(joints, d, m, o, step, omega, cam, row);
    }
}

/// The values of output `o`'s columns in one row, pushed onto `row` (see [`push_row`]).
#[allow(clippy::too_many_arguments)]
pub(super) fn push_output_row<T: Scalar>(
    joints: &[Joint],
    d: &SceneDynamics,
    m: &Mechanism,
    o: &DynamicsOutput,
    step: &StepValues<'_, T>,
    omega: T,
    cam: Option<Cam<T>>,
    row: &mut Vec<T>,
) {
    let nan = T::from(f64::NAN);
    match o.quantity {
        DynamicQuantity::ShakingForce => {
            let s = step.shaking.expect("planned");
            row.extend([s.force[0], s.force[1], s.moment]);
        }
        DynamicQuantity::InertialForces => {
            let s = step.shaking.expect("planned");
            for l in selected(&o.names, model_links(d)) {
                let k = m.link_index(l).expect("checked");
                let f = s
                    .links
                    .iter()
                    .find(|x| x.link == k)
                    .expect("a link with mass");
                row.extend([f.force[0], f.force[1], f.couple]);
            }
        }
        DynamicQuantity::Reactions => {
            let s = step.solution.as_ref().expect("planned");
            let all = m.joints().iter().map(|j| j.name.as_str());
            for j in selected(&o.names, all) {
                let r = s
                    .reactions
                    .iter()
                    .find(|r| r.joint == j)
                    .expect("every joint");
                push_reaction_values(joints, r, has_friction(d, j), row);
            }
        }
        DynamicQuantity::DriveTorque => {
            let s = step.solution.as_ref().expect("planned");
            row.push(s.drive_torque);
            if let Some(c) = cam {
                // F_s s′ (CamJoint::torque).
                row.push(s.drive_torque * c.s1);
            }
            if let Some(t) = s.motor_torque {
                row.push(t);
            }
        }
        DynamicQuantity::KineticEnergy => row.push(step.energy.expect("planned").kinetic),
        DynamicQuantity::ReducedInertia => {
            let e = step.energy.expect("planned");
            let (j, dj) = (
                e.reduced_inertia,
                e.reduced_inertia_derivative.unwrap_or(nan),
            );
            row.extend(match cam {
                // Reduced to the cam shaft: J_θ = J_s s′², J_θ′ = J_s′ s′³ + 2 J_s s′ s″.
                Some(Cam { s1, s2 }) => [j * s1 * s1, dj * s1 * s1 * s1 + j * s1 * s2 * 2.0],
                None => [j, dj],
            });
        }
        DynamicQuantity::PowerBalance => {
            let s = step.solution.as_ref().expect("planned");
            let b = s.balance;
            let (t, kinetostatic) = match cam {
                // The cam-shaft torque from the balance, (dT/dt − P_others)/ω, against
                // F_s s′ (defined in a dwell too, where the follower stands still).
                Some(c) => {
                    let others = b.gravity + b.loads + b.friction + b.efficiency;
                    ((b.kinetic_rate - others) / omega, s.drive_torque * c.s1)
                }
                None => (b.torque.unwrap_or(nan), b.kinetostatic_torque),
            };
            row.extend([
                t,
                kinetostatic - t,
                b.drive,
                b.kinetic_rate,
                b.friction + b.efficiency,
            ]);
        }
    }
}

/// Prints a force, torque, mass or moment-of-inertia column (and a reduced inertia's
/// derivative) in the file's unit of that dimension when `[units]` names one other than
/// SI (`force = "lbf"`, `torque = "lbf*in"`, ...); energies and powers stay in J and W.
/// Only the printing changes: the report keeps SI values.
fn in_file_units(column: &mut Column, units: &Units) {
    let (dimension, per_radian) = match column.unit.as_str() {
        "N" => (Dimension::Force, false),
        "N m" => (Dimension::Torque, false),
        "kg" => (Dimension::Mass, false),
        "kg m^2" => (Dimension::MomentOfInertia, false),
        "kg m^2/rad" => (Dimension::MomentOfInertia, true),
        // The reduced mass's derivative with respect to a linear drive: mass per length.
        "kg/m" => (Dimension::Density, false),
        _ => return,
    };
    let factor = units.factor(dimension);
    if factor != 1.0 {
        let symbol = units.symbol(dimension);
        column.unit = if per_radian {
            format!("{symbol}/rad")
        } else {
            symbol.to_owned()
        };
        column.factor = factor;
    }
}

/// The columns the dynamic outputs `d` of a scene (its words `cx`) add to the table, in
/// order, in the file's units: what [`DynamicsSweep`] fills, known before anything is
/// solved (`mechdiff check` checks a study's columns against them).
pub(crate) fn columns(
    cx: &ErrorContext<'_>,
    d: &SceneDynamics,
    mechanism: &Mechanism,
    plan: &Plan,
) -> Vec<Column> {
    let mut columns: Vec<Column> = (d.outputs.iter())
        .flat_map(|o| output_columns(cx, d, mechanism, plan, o))
        .collect();
    for c in &mut columns {
        in_file_units(c, &cx.units);
    }
    columns
}

/// The columns of output `o` (in SI; [`columns`] puts them in the file's units).
pub(super) fn output_columns(
    cx: &ErrorContext<'_>,
    d: &SceneDynamics,
    mechanism: &Mechanism,
    plan: &Plan,
    o: &DynamicsOutput,
) -> Vec<Column> {
    let torque_unit = if cx.drive.joint_kind() == DriveKind::Angle {
        ("M_drive", "N m")
    } else {
        ("F_drive", "N")
    };
    // With a cam the balance gives the cam-shaft torque.
    let balance_unit = if cx.drive.cam.is_some() {
        "N m"
    } else {
        torque_unit.1
    };
    let mut columns = Vec::new();
    match o.quantity {
        DynamicQuantity::ShakingForce => columns.extend([
            column("SumF_x", "N"),
            column("SumF_y", "N"),
            column("M_shaking", "N m"),
        ]),
        DynamicQuantity::InertialForces => {
            for l in selected(&o.names, model_links(d)) {
                columns.extend([
                    column(format!("Fx_{l}"), "N"),
                    column(format!("Fy_{l}"), "N"),
                    column(format!("M_{l}"), "N m"),
                ]);
            }
        }
        DynamicQuantity::Reactions => {
            let all = mechanism.joints().iter().map(|j| j.name.as_str());
            for j in selected(&o.names, all) {
                columns.extend(reaction_columns(cx.joints, j, has_friction(d, j)));
            }
        }
        DynamicQuantity::DriveTorque => {
            columns.push(column(torque_unit.0, torque_unit.1));
            if cx.drive.cam.is_some() {
                columns.push(column("M_cam", "N m"));
            }
            if d.data.motor.is_some() && plan.effects.motor {
                columns.push(column("M_motor", "N m"));
            }
        }
        DynamicQuantity::KineticEnergy => columns.push(column("T", "J")),
        DynamicQuantity::ReducedInertia => {
            let u = if cx.drive.kind == DriveKind::Angle {
                ["kg m^2", "kg m^2/rad"]
            } else {
                ["kg", "kg/m"]
            };
            columns.extend([column("J_red", u[0]), column("J_red'", u[1])]);
        }
        DynamicQuantity::PowerBalance => columns.extend([
            column("M_balance", balance_unit),
            column("dM", balance_unit),
            column("P_drive", "W"),
            column("dT/dt", "W"),
            column("P_losses", "W"),
        ]),
    }
    columns
}

/// The links with mass of `d`'s model.
fn model_links(d: &SceneDynamics) -> impl Iterator<Item = &str> + Clone {
    d.masses.iter().map(|(l, _)| l.as_str())
}

/// The names an output selects (`names`), or all of `all` when it names none.
fn selected<'a>(
    names: &'a [String],
    all: impl Iterator<Item = &'a str>,
) -> impl Iterator<Item = &'a str> {
    let chosen = (!names.is_empty()).then(|| names.iter().map(String::as_str));
    let every = names.is_empty().then_some(all);
    chosen
        .into_iter()
        .flatten()
        .chain(every.into_iter().flatten())
}

fn joint_kind<'s>(joints: &'s [Joint], name: &str) -> &'s JointKind {
    &joints
        .iter()
        .find(|j| j.name == name)
        .expect("a joint of the scene")
        .kind
}

/// Whether joint `j` has friction in the scene (`[friction.j]`): only then do its reactions
/// carry a friction column (a joint without friction gets none, not a column of zeros).
fn has_friction(d: &SceneDynamics, j: &str) -> bool {
    d.data.friction.iter().any(|f| f.joint == j)
}

/// The reaction columns of joint `j`; the friction column (`Mf_j`, `T_j`) only if `friction`.
fn reaction_columns(joints: &[Joint], j: &str, friction: bool) -> Vec<Column> {
    let mut columns = match joint_kind(joints, j) {
        JointKind::Revolute { .. } => vec![
            column(format!("Fx_{j}"), "N"),
            column(format!("Fy_{j}"), "N"),
            column(format!("Mf_{j}"), "N m"),
        ],
        JointKind::Prismatic { .. } => {
            vec![
                column(format!("N_{j}"), "N"),
                column(format!("T_{j}"), "N"),
                column(format!("M_{j}"), "N m"),
            ]
        }
        JointKind::PinInSlot { .. } => {
            vec![column(format!("N_{j}"), "N"), column(format!("T_{j}"), "N")]
        }
        JointKind::RackPinion { .. } => vec![column(format!("F_{j}"), "N")],
        JointKind::Gear { .. } => vec![column(format!("M_{j}"), "N m")],
        JointKind::Weld { .. } => vec![
            column(format!("Fx_{j}"), "N"),
            column(format!("Fy_{j}"), "N"),
            column(format!("M_{j}"), "N m"),
        ],
    };
    if let Some(k) = friction_index(joint_kind(joints, j)).filter(|_| !friction) {
        columns.remove(k);
    }
    columns
}

/// Where a joint kind's reaction numbers hold the friction (torque or force), if they hold
/// one: the one place [`reaction_columns`] and [`reaction_values`] agree on.
fn friction_index(kind: &JointKind) -> Option<usize> {
    match kind {
        JointKind::Revolute { .. } => Some(2),
        JointKind::Prismatic { .. } | JointKind::PinInSlot { .. } => Some(1),
        JointKind::RackPinion { .. } | JointKind::Gear { .. } | JointKind::Weld { .. } => None,
    }
}

/// The numbers of reaction `r` (of one of `joints`) in the order of [`reaction_columns`],
/// pushed onto `row`; the friction number only if `friction`.
fn push_reaction_values<T: Scalar>(
    joints: &[Joint],
    r: &JointReaction<T>,
    friction: bool,
    row: &mut Vec<T>,
) {
    let kind = joint_kind(joints, &r.joint);
    let values = match kind {
        JointKind::Revolute { .. } => [r.force[0], r.force[1], r.friction],
        JointKind::Prismatic { .. } => [r.normal, r.friction, r.couple],
        JointKind::PinInSlot { .. } => [r.normal, r.friction, r.friction],
        JointKind::RackPinion { .. } | JointKind::Gear { .. } => [r.normal; 3],
        JointKind::Weld { .. } => [r.force[0], r.force[1], r.couple],
    };
    let count = match kind {
        JointKind::PinInSlot { .. } => 2,
        JointKind::RackPinion { .. } | JointKind::Gear { .. } => 1,
        _ => 3,
    };
    let skip = friction_index(kind).filter(|_| !friction);
    for (k, v) in values.into_iter().take(count).enumerate() {
        if Some(k) != skip {
            row.push(v);
        }
    }
}
