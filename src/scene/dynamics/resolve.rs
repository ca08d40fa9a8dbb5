//! Checking the dynamic sections: names resolved, values in range, every error located.

use mechdiff_core::dynamics::{
    Driving, Dynamics, Efficiency, Friction, Gravity, Load, LoadKind, Motor,
};
use mechdiff_core::geometry::Inertia;
use toml::Spanned;

use crate::error::{Error, Result};
use crate::scene::context::{Context, Geometry};
use crate::scene::format::Name;
use crate::scene::limits;
use crate::scene::model::{DriveKind, Joint, JointKind};
use crate::scene::scalar::Carried;
use crate::scene::units::Dimension;
use crate::scene::values::Number;

// The checked types are named here by the run side (`run.rs`) too.
pub(super) use super::model::{DynamicsOutput, SceneDynamics};

use super::format::{CenterDef, DrivingSide, DynamicQuantity, DynamicsSections, LoadDef, MassDef};

/// A non-negative number the file writes in SI (m/s², a ratio), at most `largest`, in the
/// scalar `D` (with its derivative).
fn non_negative<D: Carried>(
    cx: &Context,
    v: &Spanned<Number>,
    what: &str,
    largest: f64,
) -> Result<D> {
    let x = cx.in_range(v, what, 0.0..=largest, "")?;
    cx.carry_plain(x, v)
}

/// A non-negative quantity in the file's unit of `dimension`, converted to SI, in the scalar
/// `D` (with its derivative).
fn non_negative_in<D: Carried>(
    cx: &Context,
    v: &Spanned<Number>,
    what: &str,
    dimension: Dimension,
) -> Result<D> {
    let si = cx.number_in::<D>(v, what, dimension)?;
    cx.in_range(v, what, 0.0..=f64::MAX, cx.units.symbol(dimension))?;
    Ok(si)
}

/// An efficiency in (0, 1], in the scalar `D` (with its derivative).
fn efficiency<D: Carried>(cx: &Context, v: &Spanned<Number>, what: &str) -> Result<D> {
    let x: f64 = cx.value(v)?;
    if !(x.is_finite() && x > 0.0 && x <= 1.0) {
        return Err(cx.invalid(v, format!("{what} must be in (0, 1], found {x}")));
    }
    cx.carry_plain(x, v)
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
    let numbers = numbers_in::<f64>(cx, s, geometry, drive, &|name| geometry.sketch(name))?;
    let masses: Vec<(String, Inertia)> = (numbers.masses.into_iter())
        .map(|(link, m)| {
            let inertia = Inertia {
                mass: m.mass,
                center: m.center,
                moment: m.moment,
            };
            (link, inertia)
        })
        .collect();
    let mut data = Dynamics::new();
    data.gravity = numbers.gravity.map(Gravity::down);
    data.loads = numbers.loads.into_iter().map(|(load, _)| load).collect();
    data.motor = numbers.motor;
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
                    return Err(cx.invalid(
                        r,
                        format!("{what} must be ≥ 0, found {}", cx.value::<f64>(r)?),
                    ));
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
        let eta = efficiency::<f64>(
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
                    let l = cx.link(l, geometry, "`[[dynamics]] links`")?;
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

/// A link's mass properties (SI) in the scalar `D`: with `D = Dual64`, with their
/// derivatives with respect to the parameter the context carries.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct MassIn<D> {
    /// Mass (kg).
    pub mass: D,
    /// Centre of gravity at the sketch pose (m).
    pub center: [D; 2],
    /// Moment of inertia about the centre (kg·m²).
    pub moment: D,
}

/// The numbers of the dynamic sections that the exact dynamics carry, read in the scalar
/// `D`: `[masses]`, `[gravity]`, the `[[load]]`s' magnitudes and `[motor]`. Friction, mesh
/// efficiencies and a load's `active` range are read in `f64` only
/// (by [`resolve`]): a scene tangent lists them as not carried when they move.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct NumbersIn<D> {
    /// Mass properties by link, in the order of `[masses]`.
    pub masses: Vec<(String, MassIn<D>)>,
    /// The magnitude of gravity (m/s², along −y).
    pub gravity: Option<D>,
    /// Each load (its `f64` value) with its force or torque in `D`, in file order.
    pub loads: Vec<(Load, LoadKind<D>)>,
    /// The motor.
    pub motor: Option<Motor<D>>,
}

/// Reads and checks the numbers of the dynamic sections `s` in the scalar `D` (one code for
/// the run, `f64`, and for a scene's tangent, `Dual64`); `at` gives a point's sketch
/// coordinates in `D` (a uniform bar's ends and a centre at a point move with the points).
pub(crate) fn numbers_in<D: Carried>(
    cx: &Context,
    s: &DynamicsSections,
    geometry: &Geometry,
    drive: DriveKind,
    at: &dyn Fn(&str) -> [D; 2],
) -> Result<NumbersIn<D>> {
    let mut masses = Vec::new();
    for (name, def) in s.masses.map(|m| m.get_ref().iter()).into_iter().flatten() {
        let link = cx.link(name, geometry, "`[masses]`")?;
        masses.push((
            link.to_owned(),
            mass_properties(cx, link, def, geometry, at)?,
        ));
    }
    let gravity = match s.gravity {
        Some(g) => Some(non_negative::<D>(
            cx,
            &g.get_ref().g,
            "g (m/s²)",
            limits::ACCELERATION,
        )?),
        None => None,
    };
    let loads = (s.loads.iter())
        .map(|def| load(cx, def, geometry, drive))
        .collect::<Result<Vec<_>>>()?;
    let motor = match s.motor {
        Some(m) => {
            let d = m.get_ref();
            let ratio: f64 = cx.value(&d.ratio)?;
            cx.in_range(
                &Spanned::new(d.ratio.span(), Number::Literal(ratio.abs())),
                "the magnitude of the motor's `ratio`",
                limits::RATIO,
                "",
            )?;
            Some(Motor {
                rotor_inertia: non_negative_in::<D>(
                    cx,
                    &d.rotor_inertia,
                    "the motor's `rotor_inertia`",
                    Dimension::MomentOfInertia,
                )?,
                ratio: cx.carry_plain(ratio, &d.ratio)?,
                efficiency: match &d.efficiency {
                    Some(e) => efficiency::<D>(cx, e, "the motor's gearbox `efficiency`")?,
                    None => D::constant(1.0),
                },
            })
        }
        None => None,
    };
    Ok(NumbersIn {
        masses,
        gravity,
        loads,
        motor,
    })
}

/// A load (`f64`) with its force or torque in `D`. The `active` range is read in `f64` (a
/// discrete choice, not differentiated; a scene tangent lists it as not carried when it
/// moves).
fn load<D: Carried>(
    cx: &Context,
    def: &Spanned<LoadDef>,
    geometry: &Geometry,
    drive: DriveKind,
) -> Result<(Load, LoadKind<D>)> {
    let d = def.get_ref();
    let link = cx.link(&d.link, geometry, "`[[load]]`")?;
    let (mut load, kind) = match (&d.force, &d.torque) {
        (Some(f), None) => {
            let point = d.point.as_ref().ok_or_else(|| {
                cx.invalid(def, "a `force` needs the `point` of the link where it acts")
            })?;
            let p = cx.point_on(point, link, geometry, "`[[load]] point`")?;
            let [fx, fy] = f.get_ref();
            let fx = cx.number_in::<D>(fx, "the force's x component", Dimension::Force)?;
            let fy = cx.number_in::<D>(fy, "the force's y component", Dimension::Force)?;
            (
                Load::force(link, p, [fx.re(), fy.re()]),
                LoadKind::Force([fx, fy]),
            )
        }
        (None, Some(t)) => {
            let torque = cx.number_in::<D>(t, "the torque", Dimension::Torque)?;
            (Load::torque(link, torque.re()), LoadKind::Torque(torque))
        }
        _ => {
            return Err(cx.invalid(
                def,
                "a `[[load]]` has either `force = [Fx, Fy]` (with `point`) or `torque = M`",
            ));
        }
    };
    if let Some(a) = &d.active {
        let [from, to] = a.get_ref();
        let dim = drive.dimension();
        // Each end is checked at the pair (as `active`), its formula evaluated at its place.
        let end = |v: &Spanned<Number>, what: &str| {
            let written = Spanned::new(a.span(), Number::Literal(cx.value(v)?));
            cx.number(&written, what, dim)
        };
        load = load.active_between(
            end(from, "the start of `active`")?,
            end(to, "the end of `active`")?,
        );
    }
    Ok((load, kind))
}

/// A link's mass, centre and moment in `D`: given, or from a density per length (a uniform
/// bar between two points, which move with the sketch: `at`).
fn mass_properties<D: Carried>(
    cx: &Context,
    link: &str,
    def: &Spanned<MassDef>,
    geometry: &Geometry,
    at: &dyn Fn(&str) -> [D; 2],
) -> Result<MassIn<D>> {
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
            let density = non_negative_in::<D>(
                cx,
                density,
                &format!("the density of link `{link}`"),
                Dimension::Density,
            )?;
            let [a, b] = bar_ends(cx, link, def, geometry)?;
            let bar = uniform_bar(density, at(&a), at(&b));
            (bar.mass, Some(bar))
        }
        (Some(m), None) => {
            let what = format!("the mass of link `{link}`");
            (non_negative_in::<D>(cx, m, &what, Dimension::Mass)?, None)
        }
    };
    let moment = match (&d.inertia, &bar) {
        (Some(i), _) => non_negative_in::<D>(
            cx,
            i,
            &format!("the moment of inertia of link `{link}`"),
            Dimension::MomentOfInertia,
        )?,
        (None, Some(bar)) => bar.moment,
        (None, None) => D::constant(0.0),
    };
    let center = match (&d.center, &bar) {
        (Some(center), _) => match center.get_ref() {
            CenterDef::Point(p) => {
                let spanned = Spanned::new(center.span(), p.clone());
                at(cx.point_on(&spanned, link, geometry, &format!("`masses.{link}.center`"))?)
            }
            CenterDef::Xy([x, y]) => {
                let coordinate = |v: &Spanned<Number>, axis: &str| {
                    let what = format!("the {axis} coordinate of the centre of link `{link}`");
                    cx.number_in::<D>(v, &what, Dimension::Length)
                };
                [coordinate(x, "x")?, coordinate(y, "y")?]
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
    Ok(MassIn {
        mass,
        center,
        moment,
    })
}

/// A uniform slender bar of mass per length `density` from `a` to `b`: mass ρ·L at the
/// midpoint, moment m·L²/12 about it (core's `uniform_bar_of`, with the length rounded as
/// [`Carried::hypot`] rounds it).
fn uniform_bar<D: Carried>(density: D, a: [D; 2], b: [D; 2]) -> MassIn<D> {
    let length = Carried::hypot(b[0] - a[0], b[1] - a[1]);
    let (mass, center, moment) = mechdiff_core::geometry::uniform_bar_of(density, length, a, b);
    MassIn {
        mass,
        center,
        moment,
    }
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
