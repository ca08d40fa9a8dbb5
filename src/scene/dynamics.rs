//! The dynamic part of a scene: masses, gravity, loads, friction, efficiencies, a motor, and
//! the `[[dynamics]]` outputs that need them (forces, reactions, drive torque, energy,
//! shaking force).
//!
//! ```toml
//! [masses]                     # kg, centre (point of the link, or [x, y] in the length
//! rocker = { mass = 30, center = "S2", inertia = 1.2 }   # unit), kg·m² about the centre
//! [gravity]
//! g = 9.81                     # m/s², along −y
//! [[load]]                     # a force (N) at a point of a link, or a torque (N·m)
//! link = "ram"
//! point = "C"
//! force = [-2000, 0]
//! active = [292.024, 67.976]   # optional: only for drive positions in this range
//! [friction]                   # per joint: Coulomb coefficient; revolute: pin_radius
//! slot = { coefficient = 0.15 }
//! [efficiency]                 # per rack-and-pinion or gear joint, in (0, 1]
//! mesh = { efficiency = 0.95 } # driving = "first" (pinion, first gear; default) | "second"
//! [motor]                      # at the drive joint: rotor inertia behind a gear ratio
//! rotor_inertia = 0.002        # kg·m²; ratio = drive speed / motor speed
//! ratio = 0.0333333333333333
//! efficiency = 0.9
//! [[dynamics]]
//! output = "drive_torque"      # shaking_force | inertial_forces | reactions | drive_torque
//!                              # | kinetic_energy | reduced_inertia | power_balance
//! ```
//!
//! From the `[[dynamics]]` outputs mechdiff derives a [`Plan`]: the derivative order and the
//! effects needed; effects whose data is given but which no output needs are not computed.

use std::collections::BTreeMap;

use mechdiff_core::DriveState;
use mechdiff_core::dynamics::run::{Run, run as run_plan};
use mechdiff_core::dynamics::{
    Driving, Dynamics, Efficiency, Friction, Gravity, Load, Motor, Plan, Request, ShakingSummary,
};
use mechdiff_core::geometry::{Inertia, Mechanism, Solver};
use serde::Deserialize;
use toml::Spanned;

use crate::error::{Error, Location, Result};

use super::format::Name;
use super::model::{DriveKind, Joint, JointKind, Scene};
use super::outputs::Column;
use super::resolve::{Context, Geometry};
use super::units::Dimension;

// ---------------------------------------------------------------- the file as written

/// `[masses.<link>]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MassDef {
    /// Mass (kg).
    pub mass: Spanned<f64>,
    /// Centre of gravity: a point of the link, or `[x, y]` at the sketch (length unit).
    pub center: Spanned<CenterDef>,
    /// Moment of inertia about the centre (kg·m²); default 0.
    pub inertia: Option<Spanned<f64>>,
}

/// A centre of gravity: a named point or sketch coordinates.
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub enum CenterDef {
    /// A point of the link.
    Point(String),
    /// Sketch coordinates.
    Xy([f64; 2]),
}

/// `[gravity]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GravityDef {
    /// Acceleration of gravity (m/s²), along −y.
    pub g: Spanned<f64>,
}

/// One `[[load]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadDef {
    /// The loaded link.
    pub link: Name,
    /// Point of application of a force (a point of the link).
    pub point: Option<Name>,
    /// Force (N), global components.
    pub force: Option<Spanned<[f64; 2]>>,
    /// Torque (N·m), counter-clockwise positive.
    pub torque: Option<Spanned<f64>>,
    /// Drive range where the load acts, in the drive's unit.
    pub active: Option<Spanned<[f64; 2]>>,
}

/// `[friction.<joint>]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionDef {
    /// Coulomb coefficient (≥ 0).
    pub coefficient: Spanned<f64>,
    /// Revolute joints: pin radius (length unit).
    pub pin_radius: Option<Spanned<f64>>,
    /// Sliding joints: where the friction force acts, along the guide's normal from the
    /// joint's point (length unit).
    pub contact_offset: Option<Spanned<f64>>,
}

/// The nominally driving side of a mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DrivingSide {
    /// The pinion, or the first gear.
    First,
    /// The rack, or the second gear.
    Second,
}

/// `[efficiency.<joint>]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EfficiencyDef {
    /// Efficiency for direct power flow, in (0, 1].
    pub efficiency: Spanned<f64>,
    /// The nominally driving side (default `first`).
    pub driving: Option<Spanned<DrivingSide>>,
}

/// `[motor]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MotorDef {
    /// Rotor moment of inertia (kg·m², ≥ 0).
    pub rotor_inertia: Spanned<f64>,
    /// Drive-joint speed over motor speed (non-zero).
    pub ratio: Spanned<f64>,
    /// Gearbox efficiency in (0, 1]; default 1.
    pub efficiency: Option<Spanned<f64>>,
}

/// What a `[[dynamics]]` output reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DynamicQuantity {
    /// ΣF_x, ΣF_y of the inertial forces and their moment about the origin.
    ShakingForce,
    /// Each link's inertial force and couple.
    InertialForces,
    /// The joint reactions.
    Reactions,
    /// The drive torque (or force), and the motor torque with a motor.
    DriveTorque,
    /// The kinetic energy.
    KineticEnergy,
    /// The reduced moment of inertia and its derivative.
    ReducedInertia,
    /// The drive torque from the power balance, its difference, and the power terms.
    PowerBalance,
}

/// One `[[dynamics]]` entry.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DynamicsOutputDef {
    /// What to report.
    pub output: Spanned<DynamicQuantity>,
    /// For `reactions`: the joints (default: all).
    pub joints: Option<Vec<Name>>,
    /// For `inertial_forces`: the links (default: all with mass).
    pub links: Option<Vec<Name>>,
}

/// The dynamic sections of a scene file, as written.
#[derive(Debug, Default)]
pub struct DynamicsSections<'a> {
    /// `[masses]`.
    pub masses: Option<&'a Spanned<BTreeMap<Name, Spanned<MassDef>>>>,
    /// `[gravity]`.
    pub gravity: Option<&'a Spanned<GravityDef>>,
    /// `[[load]]`.
    pub loads: &'a [Spanned<LoadDef>],
    /// `[friction]`.
    pub friction: Option<&'a Spanned<BTreeMap<Name, Spanned<FrictionDef>>>>,
    /// `[efficiency]`.
    pub efficiency: Option<&'a Spanned<BTreeMap<Name, Spanned<EfficiencyDef>>>>,
    /// `[motor]`.
    pub motor: Option<&'a Spanned<MotorDef>>,
    /// `[[dynamics]]`.
    pub outputs: &'a [Spanned<DynamicsOutputDef>],
}

// ---------------------------------------------------------------- checked

/// One checked `[[dynamics]]` output.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicsOutput {
    /// What it reports.
    pub quantity: DynamicQuantity,
    /// Joints (reactions) or links (inertial forces) it names; empty: all.
    pub names: Vec<String>,
    /// Where it is defined.
    pub location: Location,
}

/// The checked dynamic data and outputs of a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneDynamics {
    /// Mass properties by link (SI).
    pub masses: Vec<(String, Inertia)>,
    /// The effects' data for mechdiff-core.
    pub data: Dynamics,
    /// The outputs, in column order.
    pub outputs: Vec<DynamicsOutput>,
}

impl SceneDynamics {
    /// The requests of the outputs.
    pub fn requests(&self) -> Vec<Request> {
        self.outputs
            .iter()
            .map(|o| match o.quantity {
                DynamicQuantity::ShakingForce | DynamicQuantity::InertialForces => {
                    Request::ShakingForce
                }
                DynamicQuantity::Reactions => Request::Reactions,
                DynamicQuantity::DriveTorque => Request::DriveTorque,
                DynamicQuantity::KineticEnergy => Request::KineticEnergy,
                DynamicQuantity::ReducedInertia => Request::ReducedInertia,
                DynamicQuantity::PowerBalance => Request::PowerBalance,
            })
            .collect()
    }

    /// The plan for `mechanism` (built with the masses).
    pub fn plan(&self, mechanism: &Mechanism) -> Plan {
        Plan::for_requests(&self.requests(), self.data.available(mechanism))
    }
}

fn non_negative(cx: &Context, v: &Spanned<f64>, what: &str) -> Result<f64> {
    let x = *v.get_ref();
    if !(x.is_finite() && x >= 0.0) {
        return Err(cx.invalid(v, format!("{what} must be a finite number ≥ 0, found {x}")));
    }
    Ok(x)
}

fn efficiency(cx: &Context, v: &Spanned<f64>, what: &str) -> Result<f64> {
    let x = *v.get_ref();
    if !(x.is_finite() && x > 0.0 && x <= 1.0) {
        return Err(cx.invalid(v, format!("{what} must be in (0, 1], found {x}")));
    }
    Ok(x)
}

fn joint<'j>(cx: &Context, name: &Name, joints: &'j [Joint], context: &str) -> Result<&'j Joint> {
    joints
        .iter()
        .find(|j| &j.name == name.get_ref())
        .ok_or_else(|| Error::UnknownName {
            location: cx.at(name),
            what: "joint",
            name: name.get_ref().clone(),
            context: context.to_owned(),
            known: joints
                .iter()
                .map(|j| j.name.as_str())
                .collect::<Vec<_>>()
                .join(", "),
        })
}

/// Checks the dynamic sections; `None` when the scene has none.
pub(crate) fn resolve(
    cx: &Context,
    s: &DynamicsSections,
    geometry: &Geometry,
    joints: &[Joint],
    drive: DriveKind,
) -> Result<Option<SceneDynamics>> {
    let any = s.masses.is_some()
        || s.gravity.is_some()
        || !s.loads.is_empty()
        || s.friction.is_some()
        || s.efficiency.is_some()
        || s.motor.is_some()
        || !s.outputs.is_empty();
    if !any {
        return Ok(None);
    }
    let mut masses = Vec::new();
    for (name, def) in s.masses.map(|m| m.get_ref().iter()).into_iter().flatten() {
        let link = cx.link(name, geometry.links, "`[masses]`")?;
        let d = def.get_ref();
        let mass = non_negative(cx, &d.mass, &format!("the mass of link `{link}` (kg)"))?;
        let moment = match &d.inertia {
            Some(i) => non_negative(
                cx,
                i,
                &format!("the moment of inertia of link `{link}` (kg·m²)"),
            )?,
            None => 0.0,
        };
        let center = match d.center.get_ref() {
            CenterDef::Point(p) => {
                let spanned = Spanned::new(d.center.span(), p.clone());
                let p =
                    cx.point_on(&spanned, link, geometry, &format!("`masses.{link}.center`"))?;
                geometry.sketch(p)
            }
            CenterDef::Xy([x, y]) => {
                if !(x.is_finite() && y.is_finite()) {
                    return Err(cx.invalid(&d.center, "the centre must have finite coordinates"));
                }
                [
                    cx.units.to_si(*x, Dimension::Length),
                    cx.units.to_si(*y, Dimension::Length),
                ]
            }
        };
        masses.push((
            link.to_owned(),
            Inertia {
                mass,
                center,
                moment,
            },
        ));
    }
    let mut data = Dynamics::new();
    if let Some(g) = s.gravity {
        data.gravity = Some(Gravity::down(non_negative(cx, &g.get_ref().g, "g (m/s²)")?));
    }
    for def in s.loads {
        data.loads.push(load(cx, def, geometry, drive)?);
    }
    for (name, def) in s.friction.map(|m| m.get_ref().iter()).into_iter().flatten() {
        let j = joint(cx, name, joints, "`[friction]`")?;
        let d = def.get_ref();
        let f = non_negative(
            cx,
            &d.coefficient,
            &format!("the friction coefficient of joint `{}`", j.name),
        )?;
        let friction = match &j.kind {
            JointKind::Revolute { .. } => {
                let r = d.pin_radius.as_ref().ok_or_else(|| {
                    cx.invalid(
                        def,
                        format!("friction in revolute joint `{}` needs `pin_radius`", j.name),
                    )
                })?;
                Friction::revolute(
                    &j.name,
                    f,
                    cx.units
                        .to_si(non_negative(cx, r, "pin_radius")?, Dimension::Length),
                )
            }
            JointKind::Prismatic { .. } | JointKind::PinInSlot { .. } => {
                let offset = match &d.contact_offset {
                    Some(o) => cx.number(o, "contact_offset", Dimension::Length)?,
                    None => 0.0,
                };
                Friction::sliding(&j.name, f).with_contact_offset(offset)
            }
            other => {
                return Err(cx.invalid(
                    name,
                    format!(
                        "friction applies to revolute, prismatic and pin-in-slot joints; `{}` is a {} \
                         joint (give it an `[efficiency]` instead)",
                        j.name,
                        other.type_name()
                    ),
                ));
            }
        };
        data.friction.push(friction);
    }
    for (name, def) in s
        .efficiency
        .map(|m| m.get_ref().iter())
        .into_iter()
        .flatten()
    {
        let j = joint(cx, name, joints, "`[efficiency]`")?;
        if !matches!(
            j.kind,
            JointKind::RackPinion { .. } | JointKind::Gear { .. }
        ) {
            return Err(cx.invalid(
                name,
                format!(
                    "an efficiency applies to a rack_pinion or gear joint; `{}` is a {} joint",
                    j.name,
                    j.kind.type_name()
                ),
            ));
        }
        let d = def.get_ref();
        let eta = efficiency(
            cx,
            &d.efficiency,
            &format!("the efficiency of joint `{}`", j.name),
        )?;
        let driving = match d.driving.as_ref().map(|s| *s.get_ref()) {
            Some(DrivingSide::Second) => Driving::Second,
            _ => Driving::First,
        };
        data.efficiency
            .push(Efficiency::new(&j.name, eta).driven_from(driving));
    }
    if let Some(m) = s.motor {
        let d = m.get_ref();
        let ratio = *d.ratio.get_ref();
        if !(ratio.is_finite() && ratio != 0.0) {
            return Err(cx.invalid(
                &d.ratio,
                format!("the motor's `ratio` must be finite and non-zero, found {ratio}"),
            ));
        }
        data.motor = Some(Motor {
            rotor_inertia: non_negative(
                cx,
                &d.rotor_inertia,
                "the motor's `rotor_inertia` (kg·m²)",
            )?,
            ratio,
            efficiency: match &d.efficiency {
                Some(e) => efficiency(cx, e, "the motor's gearbox `efficiency`")?,
                None => 1.0,
            },
        });
    }
    let mut outputs = Vec::new();
    for def in s.outputs {
        let d = def.get_ref();
        let quantity = *d.output.get_ref();
        let needs_mass = matches!(
            quantity,
            DynamicQuantity::ShakingForce
                | DynamicQuantity::InertialForces
                | DynamicQuantity::KineticEnergy
                | DynamicQuantity::ReducedInertia
        );
        if needs_mass && masses.is_empty() {
            return Err(cx.invalid(
                &d.output,
                "this output needs masses; give them in `[masses]` (e.g. `crank = { mass = 2, center = \"S1\" }`)",
            ));
        }
        let mut names = Vec::new();
        match (quantity, &d.joints, &d.links) {
            (DynamicQuantity::Reactions, Some(js), None) => {
                for j in js {
                    names.push(joint(cx, j, joints, "`[[dynamics]] joints`")?.name.clone());
                }
            }
            (DynamicQuantity::InertialForces, None, Some(ls)) => {
                for l in ls {
                    let l = cx.link(l, geometry.links, "`[[dynamics]] links`")?;
                    if !masses.iter().any(|(m, _)| m == l) {
                        return Err(
                            cx.invalid(def, format!("link `{l}` has no mass in `[masses]`"))
                        );
                    }
                    names.push(l.to_owned());
                }
            }
            (_, None, None) => {}
            _ => {
                return Err(cx.invalid(
                    def,
                    "`joints` goes with `output = \"reactions\"`, `links` with `output = \"inertial_forces\"`",
                ));
            }
        }
        outputs.push(DynamicsOutput {
            quantity,
            names,
            location: cx.at(def),
        });
    }
    Ok(Some(SceneDynamics {
        masses,
        data,
        outputs,
    }))
}

fn load(
    cx: &Context,
    def: &Spanned<LoadDef>,
    geometry: &Geometry,
    drive: DriveKind,
) -> Result<Load> {
    let d = def.get_ref();
    let link = cx.link(&d.link, geometry.links, "`[[load]]`")?;
    let finite = |v: f64, at: &Location| -> Result<f64> {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(Error::Invalid {
                location: at.clone(),
                message: format!("a load value must be finite, found {v}"),
            })
        }
    };
    let mut load = match (&d.force, &d.torque) {
        (Some(f), None) => {
            let point = d.point.as_ref().ok_or_else(|| {
                cx.invalid(def, "a `force` needs the `point` of the link where it acts")
            })?;
            let p = cx.point_on(point, link, geometry, "`[[load]] point`")?;
            let [fx, fy] = *f.get_ref();
            let at = cx.at(f);
            Load::force(link, p, [finite(fx, &at)?, finite(fy, &at)?])
        }
        (None, Some(t)) => Load::torque(link, finite(*t.get_ref(), &cx.at(t))?),
        _ => {
            return Err(cx.invalid(
                def,
                "a `[[load]]` has either `force = [Fx, Fy]` (with `point`) or `torque = M`",
            ));
        }
    };
    if let Some(a) = &d.active {
        let [from, to] = *a.get_ref();
        let dim = drive.dimension();
        let at = cx.at(a);
        load = load.active_between(
            cx.units.to_si(finite(from, &at)?, dim),
            cx.units.to_si(finite(to, &at)?, dim),
        );
    }
    Ok(load)
}

// ---------------------------------------------------------------- running

/// The dynamic columns of a run, their values per drive position, and summary lines.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicsReport {
    /// The plan carried out.
    pub plan: Plan,
    /// Columns (SI units, factor 1).
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
            other => super::run::solver_error(scene, other),
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
