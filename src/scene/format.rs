//! The scene file as written: serde structures that mirror the TOML one to one.
//!
//! Everything here is *syntax*: names are still strings, numbers are still in the file's
//! units, and every value keeps its byte span so that later stages can say `file:line:col`.
//! `#[serde(deny_unknown_fields)]` everywhere turns a misspelt key into an error that lists
//! the keys expected at that place. The meaning (units applied, names resolved, geometry
//! checked) is given in `scene::resolve`.

use std::collections::BTreeMap;

use serde::Deserialize;
use serde::de::{self, Deserializer, MapAccess, SeqAccess, Visitor};
use toml::Spanned;

use super::construct::{Along, Side};
use super::dynamics::DynamicsSections;
pub use super::quantity::{Quantity, Sense, TransmissionForm};
pub use super::units::UnitsSection;
pub use super::values::Name;
use super::values::Number;

/// The whole scene file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// A one-line title printed above the table.
    pub title: Option<String>,
    /// Named values for formulas, as written; evaluated before the rest is resolved (see
    /// [`super::parameters`]).
    pub parameters: Option<super::parameters::ParameterTable>,
    /// Units of every number in the file (and of the printed results).
    #[serde(default)]
    pub units: UnitsSection,
    /// Points at the sketch pose, by name.
    pub points: Spanned<BTreeMap<Name, Spanned<PointDef>>>,
    /// Links (rigid bodies) by name, each a list of point names; `ground` is the frame.
    pub links: Spanned<BTreeMap<Name, Spanned<Vec<Name>>>>,
    /// Joints by name.
    pub joints: Spanned<BTreeMap<Name, Spanned<JointDef>>>,
    /// The driven joint and its motion.
    pub drive: Spanned<DriveSection>,
    /// The drive positions to compute.
    pub sweep: Spanned<SweepSection>,
    /// What to compute and print, in the order of the columns.
    #[serde(default, rename = "output")]
    pub outputs: Vec<Spanned<OutputDef>>,
    /// Masses by link (see [`super::dynamics`]).
    pub masses: Option<Spanned<BTreeMap<Name, Spanned<super::dynamics::MassDef>>>>,
    /// Gravity.
    pub gravity: Option<Spanned<super::dynamics::GravityDef>>,
    /// External loads.
    #[serde(default, rename = "load")]
    pub loads: Vec<Spanned<super::dynamics::LoadDef>>,
    /// Friction by joint.
    pub friction: Option<Spanned<BTreeMap<Name, Spanned<super::dynamics::FrictionDef>>>>,
    /// Efficiency by rack-and-pinion or gear joint.
    pub efficiency: Option<Spanned<BTreeMap<Name, Spanned<super::dynamics::EfficiencyDef>>>>,
    /// A motor at the drive joint.
    pub motor: Option<Spanned<super::dynamics::MotorDef>>,
    /// The machine moving under its motor (see [`super::motion`]).
    pub simulate: Option<Spanned<super::motion::SimulateDef>>,
    /// Dynamic outputs (forces, reactions, drive torque, energy, shaking force).
    #[serde(default, rename = "dynamics")]
    pub dynamics: Vec<Spanned<super::dynamics::DynamicsOutputDef>>,
    /// A rotor to balance (see [`super::balancing`]).
    pub rotor: Option<Spanned<super::balancing::RotorDef>>,
    /// Counterweights to size for the linkage (see [`super::balancing`]).
    pub balancing: Option<Spanned<super::balancing::BalancingDef>>,
    /// What the pictures show (see [`super::plot`]).
    pub plot: Option<Spanned<super::plot::PlotDef>>,
    /// The position solver's settings (see [`super::solver`]).
    pub solver: Option<Spanned<super::solver::SolverDef>>,
    /// Derivative columns with respect to parameters; read by the sensitivity study
    /// (`mechdiff::sensitivity`), not by the scene reader.
    pub sensitivity: Option<de::IgnoredAny>,
    /// ± tolerances of parameters for a tolerance study; read by the sensitivity study
    /// (`mechdiff::sensitivity`), not by the scene reader.
    pub tolerances: Option<de::IgnoredAny>,
    /// Dimensional synthesis of the scene's parameters; read by `mechdiff synthesize`
    /// ([`super::synthesize`]), not by the scene reader.
    pub synthesize: Option<de::IgnoredAny>,
}

impl<'a> DynamicsSections<'a> {
    /// The dynamic sections of the scene file `file` (written here, beside the file they
    /// view, so that the sections' own format does not name the whole file).
    pub fn of(file: &'a SceneFile) -> Self {
        DynamicsSections {
            masses: file.masses.as_ref(),
            gravity: file.gravity.as_ref(),
            loads: &file.loads,
            friction: file.friction.as_ref(),
            efficiency: file.efficiency.as_ref(),
            motor: file.motor.as_ref(),
            outputs: &file.dynamics,
        }
    }
}

/// How a point is placed in the sketch.
#[derive(Debug, Clone, PartialEq)]
pub enum PointDef {
    /// `[x, y]`: global coordinates, each with its span.
    Xy([Spanned<Number>; 2]),
    /// `{ from = "B", length = 1.065, angle = 63 }`: polar from another point
    /// (angle counter-clockwise from +x).
    Polar {
        /// The point measured from.
        from: Name,
        /// Distance from `from` (must be positive).
        length: Spanned<Number>,
        /// Direction, counter-clockwise from +x.
        angle: Spanned<Number>,
    },
    /// `{ circles = ["A", "D"], radii = [b, c], side = "left" }`: the intersection of the
    /// circles about two points (the RRR dyad), on the given side of the directed line from
    /// the first centre to the second.
    Circles {
        /// The two centres.
        circles: Spanned<[Name; 2]>,
        /// The two radii (positive).
        radii: [Spanned<Number>; 2],
        /// Which intersection.
        side: Spanned<Side>,
    },
    /// `{ circle = "A", radius = b, line = ["P", "Q"], along = "forward" }`: the intersection
    /// of a circle and a line (the RRP dyad), the one farther along P → Q or behind.
    CircleLine {
        /// The centre.
        circle: Name,
        /// The radius (positive).
        radius: Spanned<Number>,
        /// The line, through two points.
        line: Spanned<[Name; 2]>,
        /// Which intersection.
        along: Spanned<Along>,
    },
}

const POINT_KEYS: &[&str] = &[
    "from", "length", "angle", "circles", "radii", "side", "circle", "radius", "line", "along",
];

impl<'de> Deserialize<'de> for PointDef {
    fn deserialize<De: Deserializer<'de>>(deserializer: De) -> Result<Self, De::Error> {
        deserializer.deserialize_any(PointVisitor)
    }
}

struct PointVisitor;

impl<'de> Visitor<'de> for PointVisitor {
    type Value = PointDef;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str(
            "a point: `[x, y]`, `{ from = \"P\", length = L, angle = a }` (polar from point P), \
             `{ circles = [\"A\", \"B\"], radii = [r1, r2], side = \"left\" }` or \
             `{ circle = \"A\", radius = r, line = [\"P\", \"Q\"], along = \"forward\" }`",
        )
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<PointDef, A::Error> {
        let x = seq
            .next_element()?
            .ok_or_else(|| de::Error::invalid_length(0, &self))?;
        let y = seq
            .next_element()?
            .ok_or_else(|| de::Error::invalid_length(1, &self))?;
        if seq.next_element::<de::IgnoredAny>()?.is_some() {
            return Err(de::Error::invalid_length(3, &self));
        }
        Ok(PointDef::Xy([x, y]))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<PointDef, A::Error> {
        let mut keys = PointKeys::default();
        while let Some(key) = map.next_key::<String>()? {
            match key.as_str() {
                "from" => keys.from = Some(map.next_value()?),
                "length" => keys.length = Some(map.next_value()?),
                "angle" => keys.angle = Some(map.next_value()?),
                "circles" => keys.circles = Some(map.next_value::<NamePair>()?.0),
                "radii" => keys.radii = Some(map.next_value::<NumberPair>()?.0),
                "side" => keys.side = Some(map.next_value()?),
                "circle" => keys.circle = Some(map.next_value()?),
                "radius" => keys.radius = Some(map.next_value()?),
                "line" => keys.line = Some(map.next_value::<NamePair>()?.0),
                "along" => keys.along = Some(map.next_value()?),
                other => return Err(de::Error::unknown_field(other, POINT_KEYS)),
            }
        }
        keys.point()
    }
}

/// The keys of a point written as a table, before the kind of point is known.
#[derive(Default)]
struct PointKeys {
    from: Option<Name>,
    length: Option<Spanned<Number>>,
    angle: Option<Spanned<Number>>,
    circles: Option<Spanned<[Name; 2]>>,
    radii: Option<[Spanned<Number>; 2]>,
    side: Option<Spanned<Side>>,
    circle: Option<Name>,
    radius: Option<Spanned<Number>>,
    line: Option<Spanned<[Name; 2]>>,
    along: Option<Spanned<Along>>,
}

impl PointKeys {
    /// The point these keys describe: `circles` makes a dyad, `circle` a circle–line
    /// intersection, otherwise a polar point; every key of that kind is required.
    fn point<E: de::Error>(self) -> Result<PointDef, E> {
        let missing = |key: &'static str, kind: &str| {
            E::custom(format!("missing field `{key}` (a point {kind})"))
        };
        if let Some(circles) = self.circles {
            let kind = "`{ circles = [\"A\", \"B\"], radii = [r1, r2], side = \"left\" }`";
            return Ok(PointDef::Circles {
                circles,
                radii: self.radii.ok_or_else(|| missing("radii", kind))?,
                side: self.side.ok_or_else(|| missing("side", kind))?,
            });
        }
        if let Some(circle) = self.circle {
            let kind =
                "`{ circle = \"A\", radius = r, line = [\"P\", \"Q\"], along = \"forward\" }`";
            return Ok(PointDef::CircleLine {
                circle,
                radius: self.radius.ok_or_else(|| missing("radius", kind))?,
                line: self.line.ok_or_else(|| missing("line", kind))?,
                along: self.along.ok_or_else(|| missing("along", kind))?,
            });
        }
        let kind = "`{ from = \"P\", length = L, angle = a }`";
        Ok(PointDef::Polar {
            from: self.from.ok_or_else(|| missing("from", kind))?,
            length: self.length.ok_or_else(|| missing("length", kind))?,
            angle: self.angle.ok_or_else(|| missing("angle", kind))?,
        })
    }
}

/// Exactly two names.
struct NamePair(Spanned<[Name; 2]>);

impl<'de> Deserialize<'de> for NamePair {
    fn deserialize<De: Deserializer<'de>>(deserializer: De) -> Result<Self, De::Error> {
        crate::scene::values::name_pair(deserializer).map(NamePair)
    }
}

/// Exactly two numbers, each with its span.
struct NumberPair([Spanned<Number>; 2]);

impl<'de> Deserialize<'de> for NumberPair {
    fn deserialize<De: Deserializer<'de>>(deserializer: De) -> Result<Self, De::Error> {
        let list = Vec::<Spanned<Number>>::deserialize(deserializer)?;
        let n = list.len();
        let pair: [Spanned<Number>; 2] = list.try_into().map_err(|_| {
            de::Error::custom(format!(
                "expected exactly two numbers, found {n}; a pair is written `[first, second]`"
            ))
        })?;
        Ok(NumberPair(pair))
    }
}

/// The kinds of joint a scene can name (`type = "..."`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum JointKind {
    /// Two links turn about a shared point (`at`).
    Revolute,
    /// The second link translates along a line of the first, without turning.
    Prismatic,
    /// A point of the second link slides in a straight slot of the first (turning freely).
    PinInSlot,
    /// A pinion's turning in its revolute joint is tied to a rack's travel in its prismatic
    /// joint by rolling: s = R·θ.
    RackPinion,
    /// Two gears in mesh: the turning in one revolute joint is tied to the turning in
    /// another by a fixed ratio.
    Gear,
    /// The two links are welded into one rigid body.
    Weld,
}

/// One `[joints.<name>]` entry. Which fields are required depends on `type`; the check is in
/// `scene::resolve` so that it can say which field is missing for which type.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointDef {
    /// The joint type.
    #[serde(rename = "type")]
    pub kind: Spanned<JointKind>,
    /// The two links joined: `[base, moving]` (for slides and slots the first carries the line).
    /// A revolute or weld joint may list more links (`[a, b, c]`): it stands for the
    /// joints a–b, a–c, … at the same place.
    pub links: Option<Spanned<Vec<Name>>>,
    /// Revolute: the shared point.
    pub at: Option<Name>,
    /// Prismatic: the guide line, two points of the first link (direction first → second).
    #[serde(default, deserialize_with = "crate::scene::values::option_name_pair")]
    pub line: Option<Spanned<[Name; 2]>>,
    /// Prismatic: the point of the second link whose travel along `line` is the joint's
    /// displacement (it must lie on the line in the sketch).
    pub point: Option<Name>,
    /// Pin in slot: the pin, a point of the second link.
    pub pin: Option<Name>,
    /// Pin in slot: the slot's centre line, two points of the first link.
    #[serde(default, deserialize_with = "crate::scene::values::option_name_pair")]
    pub slot: Option<Spanned<[Name; 2]>>,
    /// Rack and pinion: the pinion's revolute joint.
    pub pinion: Option<Name>,
    /// Rack and pinion: the rack's prismatic joint.
    pub rack: Option<Name>,
    /// Rack and pinion: the pinion's pitch radius (length unit, positive).
    #[serde(default)]
    pub radius: Option<Spanned<Number>>,
    /// Gear: the two revolute joints in mesh, `[driving, driven]`.
    #[serde(default, deserialize_with = "crate::scene::values::option_name_pair")]
    pub gears: Option<Spanned<[Name; 2]>>,
    /// Gear: Δθ_driven = ratio · Δθ_driving (negative for an external mesh).
    #[serde(default)]
    pub ratio: Option<Spanned<Number>>,
}

/// `[drive]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DriveSection {
    /// The driven joint: revolute (the drive is an angle) or prismatic (a displacement).
    pub joint: Name,
    /// Revolute drive: the line of the joint's second link whose angle is the drive.
    #[serde(default, deserialize_with = "crate::scene::values::option_name_pair")]
    pub line: Option<Spanned<[Name; 2]>>,
    /// Revolute drive: the line of the joint's first link the angle is measured from,
    /// counter-clockwise (default: the +x axis; only when the first link is the ground).
    #[serde(default, deserialize_with = "crate::scene::values::option_name_pair")]
    pub reference: Option<Spanned<[Name; 2]>>,
    /// The drive speed ω (angular velocity unit) or the slide velocity (length unit per s).
    #[serde(default)]
    pub speed: Option<Spanned<Number>>,
    /// The drive acceleration α (angular acceleration unit) or slide acceleration
    /// (length unit per s²). Default 0.
    #[serde(default)]
    pub acceleration: Option<Spanned<Number>>,
    /// A cam scene file (path relative to this file) whose follower moves the joint: the
    /// sweep, `speed` and `acceleration` are then the cam's (see [`super::model::DriveCam`]).
    pub cam: Option<Name>,
}

/// `[sweep]`: `from`, `to`, `step`, or `positions`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepSection {
    /// First drive position (angle or length unit).
    #[serde(default)]
    pub from: Option<Spanned<Number>>,
    /// Last drive position (included when the step divides the range).
    #[serde(default)]
    pub to: Option<Spanned<Number>>,
    /// Step between positions: its size; `to` below `from` walks down (a negative step too).
    #[serde(default)]
    pub step: Option<Spanned<Number>>,
    /// An explicit list of drive positions.
    #[serde(default, deserialize_with = "crate::scene::values::option_positions")]
    pub positions: Option<super::values::PositionList>,
    /// The positions (range or list) are values of this output (an angle or slider output),
    /// in its unit; the drive positions that give them are solved for.
    pub of: Option<Name>,
}

/// One `[[output]]` entry: exactly one of `point`, `angle`, `slider`, `transmission_angle`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputDef {
    /// Column name (default: the point's or joint's name; required for angles).
    pub name: Option<Name>,
    /// A point's x and y.
    pub point: Option<Name>,
    /// The angle of the line through two points (normally of one link).
    #[serde(default, deserialize_with = "crate::scene::values::option_name_pair")]
    pub angle: Option<Spanned<[Name; 2]>>,
    /// For `angle`: the line it is measured from (default: the +x axis).
    #[serde(default, deserialize_with = "crate::scene::values::option_name_pair")]
    pub reference: Option<Spanned<[Name; 2]>>,
    /// For `angle`: `"ccw"` (default) or `"cw"`.
    pub sense: Option<Spanned<Sense>>,
    /// The displacement of a prismatic or pin-in-slot joint.
    pub slider: Option<Name>,
    /// The transmission angle μ of the four-bar or slider-crank loop whose follower (output
    /// link, or slider) is this link.
    pub transmission_angle: Option<Name>,
    /// For `transmission_angle`: which form (default `"unsigned"`).
    pub form: Option<Spanned<TransmissionForm>>,
    /// What to report (default: position, velocity, acceleration).
    pub quantities: Option<Spanned<Vec<Spanned<Quantity>>>>,
    /// Find where this output's velocity coefficient changes sign in the sweep range and
    /// print those dead positions and the stroke between them.
    #[serde(default)]
    pub dead_positions: bool,
}
