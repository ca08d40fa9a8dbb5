//! Running the `[[dynamics]]` outputs: the planned sweep and its columns.

use mechdiff_core::DriveState;
use mechdiff_core::dynamics::run::{Run, run as run_plan};
use mechdiff_core::dynamics::{Plan, ShakingSummary};
use mechdiff_core::geometry::{Mechanism, Solver};

use crate::error::{Error, Result};
use crate::scene::model::{DriveKind, JointKind, Scene};
use crate::scene::outputs::Column;
use crate::scene::units::{Dimension, Units};

use super::format::DynamicQuantity;
use super::resolve::SceneDynamics;

/// The dynamic columns of a run, their values per drive position, and summary lines.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicsReport {
    /// The plan carried out.
    pub plan: Plan,
    /// Columns: SI, or the file's force, torque, mass and inertia units (their factor).
    pub columns: Vec<Column>,
    /// One row per drive position.
    pub rows: Vec<Vec<f64>>,
    /// Lines printed after the table (shaking-force extremes, power-balance check).
    pub summary: Vec<String>,
    /// The core run (every result, and the trace of what was evaluated).
    pub run: Run,
}

fn column(name: impl Into<String>, unit: &str) -> Column {
    Column {
        name: name.into(),
        unit: unit.to_owned(),
        factor: 1.0,
    }
}

/// Runs the dynamic outputs of `scene` at the drive positions `positions`.
pub(crate) fn run(
    scene: &Scene,
    d: &SceneDynamics,
    mechanism: &Mechanism,
    positions: &[f64],
    speed: Option<f64>,
) -> Result<Option<DynamicsReport>> {
    if d.outputs.is_empty() {
        return Ok(None);
    }
    let model = d.data.compile(mechanism).map_err(|source| Error::Model {
        file: scene.file.clone(),
        source,
    })?;
    let plan = d.plan(mechanism);
    let drive = match speed {
        Some(omega) => DriveState::accelerating(omega, scene.drive.acceleration),
        None if plan.order >= 1 => {
            return Err(Error::Invalid {
                location: scene.drive.location.clone(),
                message: "the `[[dynamics]]` outputs need the drive's `speed`".to_owned(),
            });
        }
        None => DriveState::constant_speed(0.0),
    };
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
    let result =
        run_plan(&plan, &model, &Solver::default(), positions, |_| drive).map_err(|e| match e {
            mechdiff_core::Error::SelfLocking {
                phi,
                joints,
                reason,
            } => Error::Invalid {
                location: scene.drive.location.clone(),
                message: format!(
                    "self-locking at drive position {}: joints {} ({reason})",
                    scene.drive_text(phi),
                    joints.join(", ")
                ),
            },
            other => crate::scene::run::solver_error(scene, other),
        })?;
    let m = mechanism;
    let torque_unit = if scene.drive.kind == DriveKind::Angle {
        ("M_drive", "N m")
    } else {
        ("F_drive", "N")
    };
    let mass_links: Vec<&str> = model_links(d);
    let mut columns = Vec::new();
    for o in &d.outputs {
        match o.quantity {
            DynamicQuantity::ShakingForce => columns.extend([
                column("SumF_x", "N"),
                column("SumF_y", "N"),
                column("M_shaking", "N m"),
            ]),
            DynamicQuantity::InertialForces => {
                for l in selected(&o.names, &mass_links) {
                    columns.extend([
                        column(format!("Fx_{l}"), "N"),
                        column(format!("Fy_{l}"), "N"),
                        column(format!("M_{l}"), "N m"),
                    ]);
                }
            }
            DynamicQuantity::Reactions => {
                let all: Vec<&str> = m.joints().iter().map(|j| j.name.as_str()).collect();
                for j in selected(&o.names, &all) {
                    columns.extend(reaction_columns(scene, j));
                }
            }
            DynamicQuantity::DriveTorque => {
                columns.push(column(torque_unit.0, torque_unit.1));
                if d.data.motor.is_some() && plan.effects.motor {
                    columns.push(column("M_motor", "N m"));
                }
            }
            DynamicQuantity::KineticEnergy => columns.push(column("T", "J")),
            DynamicQuantity::ReducedInertia => {
                let u = if scene.drive.kind == DriveKind::Angle {
                    ["kg m^2", "kg m^2/rad"]
                } else {
                    ["kg", "kg/m"]
                };
                columns.extend([column("J_red", u[0]), column("J_red'", u[1])]);
            }
            DynamicQuantity::PowerBalance => columns.extend([
                column("M_balance", torque_unit.1),
                column("dM", torque_unit.1),
                column("P_drive", "W"),
                column("dT/dt", "W"),
                column("P_losses", "W"),
            ]),
        }
    }
    for c in &mut columns {
        in_file_units(c, &scene.units);
    }
    let mut rows = Vec::with_capacity(result.steps.len());
    for step in &result.steps {
        let mut row = Vec::with_capacity(columns.len());
        for o in &d.outputs {
            match o.quantity {
                DynamicQuantity::ShakingForce => {
                    let s = step.shaking.as_ref().expect("planned");
                    row.extend([s.force[0], s.force[1], s.moment]);
                }
                DynamicQuantity::InertialForces => {
                    let s = step.shaking.as_ref().expect("planned");
                    for l in selected(&o.names, &mass_links) {
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
                    let all: Vec<&str> = m.joints().iter().map(|j| j.name.as_str()).collect();
                    for j in selected(&o.names, &all) {
                        let r = s
                            .reactions
                            .iter()
                            .find(|r| r.joint == j)
                            .expect("every joint");
                        row.extend(reaction_values(scene, r));
                    }
                }
                DynamicQuantity::DriveTorque => {
                    let s = step.solution.as_ref().expect("planned");
                    row.push(s.drive_torque);
                    if let Some(ms) = &s.motor {
                        row.push(ms.torque);
                    }
                }
                DynamicQuantity::KineticEnergy => row.push(step.energy.expect("planned").kinetic),
                DynamicQuantity::ReducedInertia => {
                    let e = step.energy.expect("planned");
                    row.extend([
                        e.reduced_inertia,
                        e.reduced_inertia_derivative.unwrap_or(f64::NAN),
                    ]);
                }
                DynamicQuantity::PowerBalance => {
                    let b = step.solution.as_ref().expect("planned").balance;
                    let t = b.torque.unwrap_or(f64::NAN);
                    row.extend([
                        t,
                        b.kinetostatic_torque - t,
                        b.drive,
                        b.kinetic_rate,
                        b.friction + b.efficiency,
                    ]);
                }
            }
        }
        rows.push(row);
    }
    let mut summary = Vec::new();
    if d.outputs
        .iter()
        .any(|o| o.quantity == DynamicQuantity::ShakingForce)
    {
        let forces: Vec<_> = result
            .steps
            .iter()
            .filter_map(|s| s.shaking.clone())
            .collect();
        if let Some(s) = ShakingSummary::of(&forces) {
            if !s.magnitude.value.is_finite() {
                return Err(crate::error::Error::NotFinite {
                    file: scene.file.clone(),
                    quantity: "the magnitude of the shaking force |SumF| [N]".to_owned(),
                    value: s.magnitude.value.to_string(),
                    position: scene.drive_text(s.magnitude.phi),
                });
            }
            summary.push(format!(
                "shaking force over the sweep: SumF_x from {:.6} N (at {}) to {:.6} N (at {}); SumF_y from {:.6} N (at {}) to {:.6} N (at {}); largest |SumF| {:.6} N (at {})",
                s.force_x[0].value, scene.drive_text(s.force_x[0].phi), s.force_x[1].value, scene.drive_text(s.force_x[1].phi),
                s.force_y[0].value, scene.drive_text(s.force_y[0].phi), s.force_y[1].value, scene.drive_text(s.force_y[1].phi),
                s.magnitude.value, scene.drive_text(s.magnitude.phi),
            ));
        }
    }
    if d.outputs
        .iter()
        .any(|o| o.quantity == DynamicQuantity::PowerBalance)
    {
        let worst = result
            .steps
            .iter()
            .filter_map(|s| s.solution.as_ref())
            .map(|s| s.balance.residual.abs() / s.balance.scale().max(f64::MIN_POSITIVE))
            .fold(0.0, f64::max);
        summary.push(format!(
            "power balance: largest residual {worst:.1e} of the largest power term"
        ));
    }
    Ok(Some(DynamicsReport {
        plan,
        columns,
        rows,
        summary,
        run: result,
    }))
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

fn model_links(d: &SceneDynamics) -> Vec<&str> {
    d.masses.iter().map(|(l, _)| l.as_str()).collect()
}

fn selected<'a>(names: &'a [String], all: &[&'a str]) -> Vec<&'a str> {
    if names.is_empty() {
        all.to_vec()
    } else {
        names.iter().map(String::as_str).collect()
    }
}

fn joint_kind<'s>(scene: &'s Scene, name: &str) -> &'s JointKind {
    &scene
        .joints
        .iter()
        .find(|j| j.name == name)
        .expect("a joint of the scene")
        .kind
}

fn reaction_columns(scene: &Scene, j: &str) -> Vec<Column> {
    match joint_kind(scene, j) {
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
    }
}

fn reaction_values(scene: &Scene, r: &mechdiff_core::dynamics::JointReaction) -> Vec<f64> {
    match joint_kind(scene, &r.joint) {
        JointKind::Revolute { .. } => vec![r.force[0], r.force[1], r.friction],
        JointKind::Prismatic { .. } => vec![r.normal, r.friction, r.couple],
        JointKind::PinInSlot { .. } => vec![r.normal, r.friction],
        JointKind::RackPinion { .. } | JointKind::Gear { .. } => vec![r.normal],
        JointKind::Weld { .. } => vec![r.force[0], r.force[1], r.couple],
    }
}
