//! The tangent of a scene: the exact derivative, with respect to one of its `[parameters]`,
//! of every number of the mechanism it builds — each point's sketch coordinates, the joints'
//! numbers (a rack's radius, a gear's ratio), the drive's value at the sketch, its speed and
//! acceleration, the links' inertias — and of the dynamics' effects (gravity, loads, motor).
//!
//! It is the scene's one resolver run in [`Dual64`]: the parameters are evaluated with the one
//! differentiated seeded as the independent variable (`scene::parameters::bindings`), and
//! the resolver's steps that build the mechanism's numbers (the placement of points:
//! coordinates, polar points, the constructions of `scene::construct`; the drive's
//! measure; the joints' numbers) read each number as written with its derivative; they are
//! the same code in `f64` and in [`Dual64`], so a point built from lengths carries their
//! derivatives through its construction exactly. The dynamic sections' numbers the exact
//! dynamics take (`[masses]`, `[gravity]`, the loads, `[motor]`) are read the same way, a
//! uniform bar's with its moving ends.
//!
//! Every formula whose derivative is not zero and that was read only in `f64` is listed
//! ([`SceneTangent::not_carried`]): a number the tangent does not carry (a friction
//! coefficient, a mesh's efficiency, a load's `active` range, `[sweep]`, balancing data), so
//! that a derivative that would need it is not taken as exact.

use std::collections::HashMap;
use std::ops::Range;

use mechdiff_core::dynamics::tangent::EffectsTangent;
use mechdiff_core::dynamics::{LoadKind, Motor};
use mechdiff_core::geometry::{DataTangent, Inertia, Mechanism};
use mechdiff_core::num_dual::Dual64;
use toml::Spanned;
use toml::de::{DeTable, DeValue};

use crate::error::Result;

use super::context::{Context, Geometry};
use super::dynamics::{DynamicsSections, numbers_in};
use super::format::{JointDef, SceneFile};
use super::model::JointKind;
use super::parameters::{self, Setting};
use super::resolve;
use super::source::Source;
use super::units::{Dimension, Units};

/// A number that moves with the parameter and that the tangent does not carry.
#[derive(Debug, Clone, PartialEq)]
pub struct NotCarried {
    /// `file:line:column` of its formula.
    pub location: String,
    /// Its key path in the file (`masses.crank.mass`).
    pub path: String,
}

impl NotCarried {
    /// Whether the number is one of a section the kinematic outputs are computed from
    /// (`[points]`, `[links]`, `[joints]`, `[drive]`, `[sweep]`, `[[output]]`); the others
    /// (masses, loads, balancing, the title, pictures) only reach the dynamics and balancing
    /// columns, if any.
    pub fn affects_kinematics(&self) -> bool {
        const KINEMATIC: [&str; 6] = ["points", "links", "joints", "drive", "sweep", "output"];
        let section = self.path.split(['.', '[']).next().unwrap_or_default();
        KINEMATIC.contains(&section)
    }
}

/// The derivative with respect to one parameter of every number of a scene's mechanism, in
/// the mechanism's orders (points and joints as the file lists them), SI per unit of the
/// parameter as `--set` writes it.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneTangent {
    /// The parameter.
    pub parameter: String,
    /// d(sketch)/dp of every point.
    pub points: Vec<[f64; 2]>,
    /// d/dp of every joint's number: a rack and pinion's signed radius, a gear's ratio; 0
    /// for the others.
    pub joints: Vec<f64>,
    /// d/dp of the drive's value at the sketch pose.
    pub drive_at_sketch: f64,
    /// d/dp of the drive's speed ω.
    pub speed: f64,
    /// d/dp of the drive's acceleration α.
    pub acceleration: f64,
    /// d/dp of each link's mass properties (`[masses]`, SI; a uniform bar's follow its
    /// ends), by link name in the order of `[masses]`.
    pub masses: Vec<(String, Inertia)>,
    /// d/dp of the magnitude of gravity (m/s²).
    pub gravity: f64,
    /// d/dp of each `[[load]]`'s force or torque, in file order.
    pub loads: Vec<LoadKind>,
    /// d/dp of the motor's rotor inertia, ratio and efficiency.
    pub motor: Option<Motor>,
    /// The numbers that move with the parameter and that this tangent does not carry
    /// (friction, mesh efficiencies, a load's `active` range, a cam's data, …): the
    /// derivatives that need them are not exact.
    pub not_carried: Vec<NotCarried>,
}

impl SceneTangent {
    /// The tangent of the mechanism built from the scene ([`super::build::mechanism`]),
    /// as the core's parametric pose takes it, with the inertias of the links with a mass.
    pub fn data_tangent(&self, mechanism: &Mechanism) -> DataTangent {
        let mut data = DataTangent {
            points: self.points.clone(),
            joints: self.joints.clone(),
            drive_at_sketch: self.drive_at_sketch,
            ..DataTangent::zero(mechanism)
        };
        for (link, inertia) in &self.masses {
            let k = mechanism.links().iter().position(|l| l.name == *link);
            if let Some(slot) = k.and_then(|k| data.inertias.get_mut(k))
                && slot.is_some()
            {
                *slot = Some(*inertia);
            }
        }
        data
    }

    /// The d/dp of the effects' numbers as the core's exact dynamics take them (gravity,
    /// loads, motor, the drive's ω and α).
    pub fn effects_tangent(&self) -> EffectsTangent {
        EffectsTangent {
            gravity: [0.0, -self.gravity],
            loads: self.loads.clone(),
            motor: self.motor,
            omega: self.speed,
            alpha: self.acceleration,
        }
    }

    /// Whether the tangent carries every number the kinematic outputs depend on.
    pub fn carries_kinematics(&self) -> bool {
        !self.not_carried.iter().any(NotCarried::affects_kinematics)
    }
}

/// The tangent of the scene `text` (named `file`, with `settings`) with respect to its
/// parameter `parameter`: see the module's doc.
///
/// # Errors
/// As [`super::parse_with`]: the tangent is taken of a scene that reads.
pub fn scene_tangent(
    file: &str,
    text: &str,
    settings: &[Setting],
    parameter: &str,
) -> Result<SceneTangent> {
    let source = Source::new(file, text);
    let raw: SceneFile = toml::from_str(text).map_err(|e| source.syntax_error(&e))?;
    let parameters = raw.parameters.as_ref();
    let bindings =
        parameters::bindings_of(parameters, &raw.units, &source, settings, Some(parameter))?;
    let cx = Context::new(&source, Units::declared(&raw.units), &bindings);
    // The scene resolved as a run resolves it (every number read and checked, the formulas
    // that move noted), then the mechanism's numbers in Dual64 by the same steps.
    let scene = resolve::scene(&raw, &cx)?;
    let (points, placed) = cx.points_in::<Dual64>(&raw.points)?;
    let names: HashMap<&str, usize> = (placed.iter().enumerate())
        .map(|(i, p)| (p.name.as_str(), i))
        .collect();
    let geometry = Geometry::new(&placed, &names, &scene.links);
    let joints = &scene.joints;
    let mut joint_tangents = vec![0.0; joints.len()];
    for (t, joint) in joint_tangents.iter_mut().zip(joints) {
        let Some(def) = raw
            .joints
            .get_ref()
            .iter()
            .find(|(n, _)| *n.get_ref() == joint.name)
        else {
            continue;
        };
        *t = joint_number_tangent(&cx, def.1.get_ref(), &joint.kind)?;
    }
    let drive = raw.drive.get_ref();
    let (_, measure) = cx.drive_measure(&raw.drive, &geometry, joints)?;
    let at = |name: &str| points[names[name]];
    let drive_at_sketch = measure.at(at).eps;
    let speed_dimension = measure.kind().speed_dimension();
    let speed = match &drive.speed {
        Some(v) => cx.tangent(v, speed_dimension)?,
        None => 0.0,
    };
    let acceleration = match &drive.acceleration {
        Some(v) => cx.tangent(v, measure.kind().acceleration_dimension())?,
        None => 0.0,
    };
    // The dynamic sections' numbers, read by the run's own code in dual numbers.
    let dynamics = numbers_in::<Dual64>(
        &cx,
        &DynamicsSections::of(&raw),
        &geometry,
        measure.kind(),
        &|name: &str| points[names[name]],
    )?;
    let not_read = cx.not_carried();
    let mut not_carried: Vec<NotCarried> = (key_paths(text, &not_read).into_iter())
        .zip(not_read)
        .map(|(path, span)| NotCarried {
            location: source.location(span).to_string(),
            path,
        })
        .collect();
    // A construction at its limit (tangent circles, a line touching a circle) has no
    // derivative: its point is not carried.
    for ((name, def), xy) in sorted_points(&raw).into_iter().zip(&points) {
        if !(xy[0].eps.is_finite() && xy[1].eps.is_finite()) {
            not_carried.push(NotCarried {
                location: source.location(def.span()).to_string(),
                path: format!("points.{name} (a construction at its limit: no derivative)"),
            });
        }
    }
    Ok(SceneTangent {
        parameter: parameter.to_owned(),
        points: points.iter().map(|p| [p[0].eps, p[1].eps]).collect(),
        joints: joint_tangents,
        drive_at_sketch,
        speed,
        acceleration,
        masses: (dynamics.masses.into_iter())
            .map(|(link, m)| {
                let inertia = Inertia {
                    mass: m.mass.eps,
                    center: [m.center[0].eps, m.center[1].eps],
                    moment: m.moment.eps,
                };
                (link, inertia)
            })
            .collect(),
        gravity: dynamics.gravity.map_or(0.0, |g| g.eps),
        loads: (dynamics.loads.iter())
            .map(|(_, kind)| match kind {
                LoadKind::Force([x, y]) => LoadKind::Force([x.eps, y.eps]),
                LoadKind::Torque(t) => LoadKind::Torque(t.eps),
            })
            .collect(),
        motor: dynamics.motor.map(|m| Motor {
            rotor_inertia: m.rotor_inertia.eps,
            ratio: m.ratio.eps,
            efficiency: m.efficiency.eps,
        }),
        not_carried,
    })
}

/// The key path (`friction.O2.coefficient`, `load[0].force[1]`) of the value at each of
/// `spans` in the TOML `text` (the value's place, for messages; `?` where none is found).
fn key_paths(text: &str, spans: &[Range<usize>]) -> Vec<String> {
    fn walk(value: &Spanned<DeValue<'_>>, path: &str, found: &mut HashMap<Range<usize>, String>) {
        match value.get_ref() {
            DeValue::Array(items) => {
                for (i, item) in items.iter().enumerate() {
                    walk(item, &format!("{path}[{i}]"), found);
                }
            }
            DeValue::Table(table) => {
                for (key, item) in table {
                    walk(item, &format!("{path}.{}", key.get_ref()), found);
                }
            }
            _ => {}
        }
        found.insert(value.span(), path.to_owned());
    }
    if spans.is_empty() {
        return Vec::new();
    }
    let mut found = HashMap::new();
    if let Ok(table) = DeTable::parse(text) {
        for (key, value) in table.get_ref() {
            walk(value, key.get_ref(), &mut found);
        }
    }
    (spans.iter())
        .map(|span| found.get(span).cloned().unwrap_or_else(|| "?".to_owned()))
        .collect()
}

/// d/dp of a joint's number (SI): a rack's signed radius, a gear's ratio.
fn joint_number_tangent(cx: &Context<'_>, def: &JointDef, kind: &JointKind) -> Result<f64> {
    Ok(match (kind, &def.radius, &def.ratio) {
        // The radius is signed by the side of the rack the pinion is on, which a derivative
        // does not change.
        (JointKind::RackPinion { radius, .. }, Some(r), _) => {
            radius.signum() * cx.tangent(r, Dimension::Length)?
        }
        (JointKind::Gear { .. }, _, Some(r)) => cx.tangent_plain(r)?,
        _ => 0.0,
    })
}

/// The points of `[points]` in the file's order (the order of [`Context::points_in`]).
fn sorted_points(raw: &SceneFile) -> Vec<(&str, &Spanned<super::format::PointDef>)> {
    let mut entries: Vec<_> = (raw.points.get_ref().iter())
        .map(|(n, d)| (n.get_ref().as_str(), n.span().start, d))
        .collect();
    entries.sort_by_key(|e| e.1);
    entries.into_iter().map(|(n, _, d)| (n, d)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::values::Number;

    /// A scene whose points are formulas of `l` and constructions from them.
    const SCENE: &str = r#"[parameters]
l = 0.3
k = "sqrt(l)*sin(l) + atan2(l, 1.7)"
[units]
angle = "deg"
[points]
O = [0.0, 0.0]
A = ["2*l", "l^2"]
B = { from = "A", length = "exp(-l)/7 + k", angle = "l*100/3" }
C = { circles = ["O", "B"], radii = ["3*l", "2*k + l^3"], side = "left" }
[links]
ground = ["O"]
crank = ["O", "A", "B", "C"]
[joints]
O = { type = "revolute", at = "O", links = ["ground", "crank"] }
[drive]
joint = "O"
line = ["O", "A"]
[sweep]
positions = [0.0]
"#;

    /// The one resolver run in `f64` and in `Dual64` (with `l` seeded): every formula's and
    /// every constructed point's real part is the `f64` value bit for bit (the same code,
    /// and the operations whose dual forms round differently are [`Carried`]'s), and the
    /// derivative of `A = [2l, l²]` is (2, 2l) exactly (both rules are a doubling in f64).
    #[test]
    fn the_dual_resolution_has_the_f64_values_as_its_real_part() {
        let source = Source::new("t.toml", SCENE);
        let bindings = parameters::bindings(SCENE, &source, &[], Some("l")).unwrap();
        let raw: SceneFile = toml::from_str(SCENE).unwrap();
        let cx = Context::new(&source, Units::declared(&raw.units), &bindings);
        for text in ["2*l", "l^2", "exp(-l)/7 + k", "l*100/3", "2*k + l^3", "k"] {
            let n = Number::Formula(text.to_owned());
            let re: f64 = n.value_in(&bindings).unwrap();
            let dual: Dual64 = n.value_in(&bindings).unwrap();
            assert_eq!(dual.re.to_bits(), re.to_bits(), "{text}");
            assert!(dual.eps != 0.0, "{text} moves with l");
        }
        let (values, _) = cx.points_in::<f64>(&raw.points).unwrap();
        let (duals, _) = cx.points_in::<Dual64>(&raw.points).unwrap();
        for (v, d) in values.iter().zip(&duals) {
            for k in 0..2 {
                assert_eq!(d[k].re.to_bits(), v[k].to_bits(), "{v:?} vs {d:?}");
            }
        }
        let l = 0.3;
        assert_eq!([duals[1][0].eps, duals[1][1].eps], [2.0, 2.0 * l]);
        // Every formula that moves was read with its derivative.
        assert!(cx.not_carried().is_empty(), "{:?}", cx.not_carried());
    }
}
