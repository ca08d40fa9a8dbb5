//! The tangent of a scene: the exact derivative, with respect to one of its `[parameters]`,
//! of every number of the mechanism it builds — each point's sketch coordinates, the joints'
//! numbers (a rack's radius, a gear's ratio), the drive's value at the sketch, its speed and
//! acceleration, the links' inertias — and of the dynamics' effects (gravity, loads, motor).
//!
//! The scene is read once more in dual numbers ([`Dual64`]): the parameters are evaluated
//! with the one differentiated as the independent variable ([`super::parameters`]), and
//! every quoted formula of the file is evaluated with them ([`super::values::formula_in`]),
//! its derivative kept under its place in the file (`Tangents`). The resolver's steps that
//! build the mechanism's numbers (`scene::placement`: coordinates, polar points, the
//! constructions of `scene::construct`; the drive's measure; the joints' numbers) then
//! read each number with its derivative (`resolve::Context::number_in`) and are the
//! same code in `f64` and in [`Dual64`], so a point built from lengths carries their
//! derivatives through its construction exactly. The dynamic sections' numbers the exact
//! dynamics take (`[masses]`, `[gravity]`, the loads, `[motor]`) are read the same way
//! (`dynamics::numbers_in`), a uniform bar's with its moving ends.
//!
//! Every formula whose derivative is not zero and that no step read is listed
//! ([`SceneTangent::not_carried`]): a number the tangent does not carry (a friction
//! coefficient, a mesh's efficiency, a load's `active` range, a cam file's data), so that
//! a derivative that would need it is not taken as exact.

use std::cell::RefCell;
use std::collections::{HashMap, HashSet};
use std::ops::Range;

use mechdiff_core::Scalar;
use mechdiff_core::dynamics::tangent::EffectsTangent;
use mechdiff_core::dynamics::{LoadKind, Motor};
use mechdiff_core::geometry::{DataTangent, Inertia, Mechanism};
use mechdiff_core::num_dual::Dual64;
use toml::Spanned;
use toml::de::{DeTable, DeValue};

use crate::error::Result;

use super::dynamics::{DynamicsSections, numbers_in};
use super::format::{JointDef, SceneFile};
use super::model::JointKind;
use super::parameters::{self, Setting};
use super::resolve::Context;
use super::source::Source;
use super::units::Dimension;
use super::values::formula_in;

/// A scalar a scene's numbers are read in: `f64` (no derivative) or [`Dual64`] (the
/// derivative with respect to one parameter).
///
/// The operations whose `f64` form rounds differently from the generic one (`hypot`,
/// `atan2`) are the trait's, so that the real part of a dual result is the `f64` result bit
/// for bit.
pub trait Carried: Scalar {
    /// The number `value` with derivative `tangent` (dropped by `f64`).
    fn with_tangent(value: f64, tangent: f64) -> Self;
    /// The derivative carried (0 for `f64`).
    fn tangent(&self) -> f64;
    /// `√(self² + y²)`, its real part [`f64::hypot`].
    fn hypot(self, y: Self) -> Self {
        let h = self.re().hypot(y.re());
        Self::with_tangent(h, (self.re() * self.tangent() + y.re() * y.tangent()) / h)
    }
    /// The angle of the vector (x, y) = (`x`, `self`), its real part [`f64::atan2`].
    fn atan2(self, x: Self) -> Self {
        let (y, x_re) = (self.re(), x.re());
        let squared = x_re * x_re + y * y;
        Self::with_tangent(
            y.atan2(x_re),
            (x_re * self.tangent() - y * x.tangent()) / squared,
        )
    }
    /// `max(self, 0)`: 0 where the real part is negative (a tangency rounded below 0).
    fn non_negative(self) -> Self {
        if self.re() < 0.0 {
            Self::constant(0.0)
        } else {
            self
        }
    }
}

impl Carried for f64 {
    fn with_tangent(value: f64, _: f64) -> Self {
        value
    }

    fn tangent(&self) -> f64 {
        0.0
    }

    fn hypot(self, y: f64) -> f64 {
        f64::hypot(self, y)
    }

    fn atan2(self, x: f64) -> f64 {
        f64::atan2(self, x)
    }
}

impl Carried for Dual64 {
    fn with_tangent(value: f64, tangent: f64) -> Self {
        Dual64::new(value, tangent)
    }

    fn tangent(&self) -> f64 {
        self.eps
    }
}

/// The derivatives of a scene file's formulas with respect to one parameter, by the place
/// of each formula in the file: those that are not zero, each with the key path it is at.
#[derive(Debug, Default)]
pub(crate) struct Tangents {
    numbers: HashMap<Range<usize>, (f64, String)>,
    read: RefCell<HashSet<Range<usize>>>,
}

impl Tangents {
    /// Evaluates every quoted string of `text` that is a formula of the `parameters` (values
    /// in the file's units with their derivatives) and keeps the derivatives that are not
    /// zero. `[parameters]` itself is skipped (its values are the bindings).
    ///
    /// # Errors
    /// The TOML error of a text that does not parse (never an empty table: every formula
    /// would be taken as not moving).
    fn of_file(
        text: &str,
        parameters: &HashMap<String, Dual64>,
    ) -> std::result::Result<Self, toml::de::Error> {
        let mut tangents = Tangents::default();
        let table = DeTable::parse(text)?;
        for (key, value) in table.get_ref() {
            if key.get_ref() != "parameters" {
                tangents.walk(value, key.get_ref(), parameters);
            }
        }
        Ok(tangents)
    }

    fn walk(
        &mut self,
        value: &Spanned<DeValue<'_>>,
        path: &str,
        parameters: &HashMap<String, Dual64>,
    ) {
        match value.get_ref() {
            DeValue::String(text) => {
                // A string that is not a formula of the parameters (a name) has no entry.
                if let Ok(v) = formula_in(text, parameters)
                    && v.eps != 0.0
                {
                    self.numbers.insert(value.span(), (v.eps, path.to_owned()));
                }
            }
            DeValue::Array(items) => {
                for (i, item) in items.iter().enumerate() {
                    self.walk(item, &format!("{path}[{i}]"), parameters);
                }
            }
            DeValue::Table(table) => {
                for (key, item) in table {
                    self.walk(item, &format!("{path}.{}", key.get_ref()), parameters);
                }
            }
            _ => {}
        }
    }

    /// The derivative of the number at `span` (in the file's unit of its field; 0 for a
    /// number that does not move), now counted as carried.
    pub(crate) fn at(&self, span: Range<usize>) -> f64 {
        match self.numbers.get(&span) {
            Some((t, _)) => {
                self.read.borrow_mut().insert(span);
                *t
            }
            None => 0.0,
        }
    }

    /// The formulas that move and were not read, as `(place, key path)`, in the file's order.
    fn not_read(&self) -> Vec<(Range<usize>, String)> {
        let read = self.read.borrow();
        let mut left: Vec<(Range<usize>, String)> = (self.numbers.iter())
            .filter(|(span, _)| !read.contains(*span))
            .map(|(span, (_, path))| (span.clone(), path.clone()))
            .collect();
        left.sort_by_key(|(span, _)| span.start);
        left
    }
}

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
    let duals = parameters::read_tangent(text, &source, settings, parameter)?;
    let bindings: Vec<(String, f64)> = duals.iter().map(|(n, v)| (n.clone(), v.re)).collect();
    let raw: SceneFile = parameters::with_scope(bindings, || toml::from_str(text))
        .map_err(|e| source.syntax_error(&e))?;
    let tangents = Tangents::of_file(text, &duals.into_iter().collect())
        .map_err(|e| source.syntax_error(&e))?;
    let cx = Context::with_tangents(&source, super::resolve::units(&raw.units), &tangents);
    let (points, placed) = cx.points_in::<Dual64>(&raw.points)?;
    let names: HashMap<&str, usize> = (placed.iter().enumerate())
        .map(|(i, p)| (p.name.as_str(), i))
        .collect();
    let links = cx.links(&raw.links, &names)?;
    let geometry = super::resolve::Geometry::new(&placed, &names, &links);
    let joints = cx.joints(&raw.joints, &geometry)?;
    let mut joint_tangents = vec![0.0; joints.len()];
    for (t, joint) in joint_tangents.iter_mut().zip(&joints) {
        let Some(def) = raw
            .joints
            .get_ref()
            .iter()
            .find(|(n, _)| *n.get_ref() == joint.name)
        else {
            continue;
        };
        *t = joint_number_tangent(&cx, def.1.get_ref(), &joint.kind);
    }
    let drive = raw.drive.get_ref();
    let (_, measure) = cx.drive_measure(&raw.drive, &geometry, &joints)?;
    let at = |name: &str| points[names[name]];
    let drive_at_sketch = measure.at(at).eps;
    let speed_dimension = measure.kind().speed_dimension();
    let speed = drive
        .speed
        .as_ref()
        .map_or(0.0, |v| cx.tangent(v, speed_dimension));
    let acceleration = drive.acceleration.as_ref().map_or(0.0, |v| {
        cx.tangent(v, measure.kind().acceleration_dimension())
    });
    // The dynamic sections' numbers, read by the run's own code in dual numbers.
    let dynamics = numbers_in::<Dual64>(
        &cx,
        &DynamicsSections::of(&raw),
        &geometry,
        measure.kind(),
        &|name: &str| points[names[name]],
    )?;
    let mut not_carried: Vec<NotCarried> = tangents
        .not_read()
        .into_iter()
        .map(|(span, path)| NotCarried {
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

/// d/dp of a joint's number (SI): a rack's signed radius, a gear's ratio.
fn joint_number_tangent(cx: &Context<'_>, def: &JointDef, kind: &JointKind) -> f64 {
    match kind {
        // The radius is signed by the side of the rack the pinion is on, which a derivative
        // does not change.
        JointKind::RackPinion { radius, .. } => def
            .radius
            .as_ref()
            .map_or(0.0, |r| radius.signum() * cx.tangent(r, Dimension::Length)),
        JointKind::Gear { .. } => def.ratio.as_ref().map_or(0.0, |r| cx.tangent_plain(r)),
        _ => 0.0,
    }
}

/// The points of `[points]` in the file's order (the order of [`Context::points_in`]).
fn sorted_points(raw: &SceneFile) -> Vec<(&str, &Spanned<super::format::PointDef>)> {
    let mut entries: Vec<_> = (raw.points.get_ref().iter())
        .map(|(n, d)| (n.get_ref().as_str(), n.span().start, d))
        .collect();
    entries.sort_by_key(|e| e.1);
    entries.into_iter().map(|(n, _, d)| (n, d)).collect()
}
