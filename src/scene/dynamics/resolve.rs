//! Checking the dynamic sections: names resolved, values in range, every error located.

use mechdiff_core::dynamics::{
    Driving, Dynamics, Efficiency, Friction, Gravity, Load, Motor, Plan, Request,
};
use mechdiff_core::geometry::{Inertia, Mechanism};
use toml::Spanned;

use crate::error::{Error, Location, Result};
use crate::scene::format::Name;
use crate::scene::limits;
use crate::scene::model::{DriveKind, Joint, JointKind};
use crate::scene::resolve::{Context, Geometry};
use crate::scene::units::Dimension;

use super::format::{CenterDef, DrivingSide, DynamicQuantity, DynamicsSections, LoadDef, MassDef};

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

fn non_negative(cx: &Context, v: &Spanned<f64>, what: &str, largest: f64) -> Result<f64> {
    cx.in_range(v, what, 0.0..=largest, "")
}

/// A non-negative quantity in the file's unit of `dimension`, converted to SI.
fn non_negative_in(
    cx: &Context,
    v: &Spanned<f64>,
    what: &str,
    dimension: Dimension,
) -> Result<f64> {
    let si = cx.number(v, what, dimension)?;
    cx.in_range(v, what, 0.0..=f64::MAX, cx.units.symbol(dimension))?;
    Ok(si)
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
        masses.push((link.to_owned(), mass_properties(cx, link, def, geometry)?));
    }
    let mut data = Dynamics::new();
    if let Some(g) = s.gravity {
        data.gravity = Some(Gravity::down(non_negative(
            cx,
            &g.get_ref().g,
            "g (m/s²)",
            limits::ACCELERATION,
        )?));
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
            limits::FRICTION_COEFFICIENT,
        )?;
        let friction = match &j.kind {
            JointKind::Revolute { .. } => {
                let r = d.pin_radius.as_ref().ok_or_else(|| {
                    cx.invalid(
                        def,
                        format!("friction in revolute joint `{}` needs `pin_radius`", j.name),
                    )
                })?;
                let what = format!("`pin_radius` of joint `{}`", j.name);
                let radius = cx.number(r, &what, Dimension::Length)?;
                if radius < 0.0 {
                    return Err(cx.invalid(r, format!("{what} must be ≥ 0, found {}", r.get_ref())));
                }
                Friction::revolute(&j.name, f, radius)
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
        cx.in_range(
            &Spanned::new(d.ratio.span(), ratio.abs()),
            "the magnitude of the motor's `ratio`",
            limits::RATIO,
            "",
        )?;
        data.motor = Some(Motor {
            rotor_inertia: non_negative_in(
                cx,
                &d.rotor_inertia,
                "the motor's `rotor_inertia`",
                Dimension::MomentOfInertia,
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
    let bounded = |v: f64, at: &Spanned<[f64; 2]>, what: &str| {
        cx.number(&Spanned::new(at.span(), v), what, Dimension::Force)
    };
    let mut load = match (&d.force, &d.torque) {
        (Some(f), None) => {
            let point = d.point.as_ref().ok_or_else(|| {
                cx.invalid(def, "a `force` needs the `point` of the link where it acts")
            })?;
            let p = cx.point_on(point, link, geometry, "`[[load]] point`")?;
            let [fx, fy] = *f.get_ref();
            let fx = bounded(fx, f, "the force's x component")?;
            let fy = bounded(fy, f, "the force's y component")?;
            Load::force(link, p, [fx, fy])
        }
        (None, Some(t)) => Load::torque(link, cx.number(t, "the torque", Dimension::Torque)?),
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
        let end = |v: f64, what: &str| cx.number(&Spanned::new(a.span(), v), what, dim);
        load = load.active_between(
            end(from, "the start of `active`")?,
            end(to, "the end of `active`")?,
        );
    }
    Ok(load)
}

/// A link's mass, centre and moment: given, or from a density per length (uniform bar).
fn mass_properties(
    cx: &Context,
    link: &str,
    def: &Spanned<MassDef>,
    geometry: &Geometry,
) -> Result<Inertia> {
    let d = def.get_ref();
    let (mass, bar) = match (&d.mass, &d.density) {
        (Some(_), Some(_)) | (None, None) => {
            return Err(cx.invalid(
                def,
                format!(
                    "`masses.{link}` needs exactly one of `mass` (with `center`) and \
                     `density` (mass per length of a uniform bar)"
                ),
            ));
        }
        (None, Some(density)) => {
            let density = non_negative_in(
                cx,
                density,
                &format!("the density of link `{link}`"),
                Dimension::Density,
            )?;
            let [a, b] = bar_ends(cx, link, def, geometry)?;
            let bar = Inertia::uniform_bar(density, geometry.sketch(&a), geometry.sketch(&b));
            (bar.mass, Some(bar))
        }
        (Some(m), None) => {
            let what = format!("the mass of link `{link}`");
            (non_negative_in(cx, m, &what, Dimension::Mass)?, None)
        }
    };
    let moment = match (&d.inertia, &bar) {
        (Some(i), _) => non_negative_in(
            cx,
            i,
            &format!("the moment of inertia of link `{link}`"),
            Dimension::MomentOfInertia,
        )?,
        (None, Some(bar)) => bar.moment,
        (None, None) => 0.0,
    };
    let center = match (&d.center, &bar) {
        (Some(center), _) => match center.get_ref() {
            CenterDef::Point(p) => {
                let spanned = Spanned::new(center.span(), p.clone());
                let p =
                    cx.point_on(&spanned, link, geometry, &format!("`masses.{link}.center`"))?;
                geometry.sketch(p)
            }
            CenterDef::Xy(xy) => {
                let coordinate = |v: f64, axis: &str| {
                    let what = format!("the {axis} coordinate of the centre of link `{link}`");
                    cx.number(&Spanned::new(center.span(), v), &what, Dimension::Length)
                };
                [coordinate(xy[0].0, "x")?, coordinate(xy[1].0, "y")?]
            }
        },
        (None, Some(bar)) => bar.center,
        (None, None) => {
            return Err(cx.invalid(
                def,
                format!(
                    "`masses.{link}` gives a `mass` without its `center`; add `center = \"P\"` \
                     (a point of the link) or `center = [x, y]`"
                ),
            ));
        }
    };
    Ok(Inertia {
        mass,
        center,
        moment,
    })
}

/// The ends of a uniform bar: `bar`, or the link's two points.
fn bar_ends(
    cx: &Context,
    link: &str,
    def: &Spanned<MassDef>,
    geometry: &Geometry,
) -> Result<[String; 2]> {
    if let Some(bar) = &def.get_ref().bar {
        return cx.line(bar, link, geometry, &format!("`masses.{link}.bar`"));
    }
    match geometry.link(link).map(|l| l.points.as_slice()) {
        Some([a, b]) => Ok([a.clone(), b.clone()]),
        _ => Err(cx.invalid(
            def,
            format!(
                "link `{link}` does not have exactly two points, so its bar is not known; give \
                 its ends with `bar = [\"P\", \"Q\"]`"
            ),
        )),
    }
}
