//! The scene file as written: serde structures that mirror the TOML one to one.
//!
//! Everything here is *syntax*: names are still strings, numbers are still in the file's
//! units, and every value keeps its byte span so that later stages can say `file:line:col`.
//! `#[serde(deny_unknown_fields)]` everywhere turns a misspelt key into an error that lists
//! the keys expected at that place. The meaning (units applied, names resolved, geometry
//! checked) is given in [`super::resolve`].

use std::collections::BTreeMap;

use serde::Deserialize;
use serde::de::{self, Deserializer, MapAccess, SeqAccess, Visitor};
use toml::Spanned;

use super::units::{AngleUnit, AngularAccelerationUnit, AngularVelocityUnit, LengthUnit};
use super::values::Number;

/// A name with the place where it is written.
pub type Name = Spanned<String>;

/// The whole scene file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// A one-line title printed above the table.
    pub title: Option<String>,
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
    /// Dynamic outputs (forces, reactions, drive torque, energy, shaking force).
    #[serde(default, rename = "dynamics")]
    pub dynamics: Vec<Spanned<super::dynamics::DynamicsOutputDef>>,
    /// A rotor to balance (see [`super::balancing`]).
    pub rotor: Option<Spanned<super::balancing::RotorDef>>,
    /// Counterweights to size for the linkage (see [`super::balancing`]).
    pub balancing: Option<Spanned<super::balancing::BalancingDef>>,
    /// What the pictures show (see [`super::plot`]).
    pub plot: Option<Spanned<super::plot::PlotDef>>,
}

/// `[units]`: every field has an SI default.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct UnitsSection {
    /// `"m"` (default) or `"mm"`; velocities and accelerations of points follow (per s, s²).
    pub length: Option<Spanned<LengthUnit>>,
    /// `"rad"` (default) or `"deg"`.
    pub angle: Option<Spanned<AngleUnit>>,
    /// `"rad/s"` (default), `"deg/s"` or `"rpm"`.
    pub angular_velocity: Option<Spanned<AngularVelocityUnit>>,
    /// `"rad/s^2"` (default) or `"deg/s^2"`.
    pub angular_acceleration: Option<Spanned<AngularAccelerationUnit>>,
}

/// How a point is placed in the sketch.
#[derive(Debug, Clone, PartialEq)]
pub enum PointDef {
    /// `[x, y]`: global coordinates.
    Xy([f64; 2]),
    /// `{ from = "B", length = 1.065, angle = 63 }`: polar from another point
    /// (angle counter-clockwise from +x).
    Polar {
        /// The point measured from.
        from: Name,
        /// Distance from `from` (must be positive).
        length: Spanned<f64>,
        /// Direction, counter-clockwise from +x.
        angle: Spanned<f64>,
    },
}

/// A number with its span, as the format's fields keep it.
fn number(n: Spanned<Number>) -> Spanned<f64> {
    Spanned::new(n.span(), n.into_inner().0)
}

const POLAR_KEYS: &[&str] = &["from", "length", "angle"];

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
            "a point: `[x, y]` or `{ from = \"P\", length = L, angle = a }` (polar from point P)",
        )
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<PointDef, A::Error> {
        let Number(x) = seq
            .next_element()?
            .ok_or_else(|| de::Error::invalid_length(0, &self))?;
        let Number(y) = seq
            .next_element()?
            .ok_or_else(|| de::Error::invalid_length(1, &self))?;
        if seq.next_element::<de::IgnoredAny>()?.is_some() {
            return Err(de::Error::invalid_length(3, &self));
        }
        Ok(PointDef::Xy([x, y]))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<PointDef, A::Error> {
        let (mut from, mut length, mut angle) = (None, None, None);
        while let Some(key) = map.next_key::<String>()? {
            match key.as_str() {
                "from" => from = Some(map.next_value()?),
                "length" => length = Some(number(map.next_value()?)),
                "angle" => angle = Some(number(map.next_value()?)),
                other => return Err(de::Error::unknown_field(other, POLAR_KEYS)),
            }
        }
        Ok(PointDef::Polar {
            from: from.ok_or_else(|| de::Error::missing_field("from"))?,
            length: length.ok_or_else(|| de::Error::missing_field("length"))?,
            angle: angle.ok_or_else(|| de::Error::missing_field("angle"))?,
        })
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
/// [`super::resolve`] so that it can say which field is missing for which type.
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
    #[serde(default, deserialize_with = "crate::scene::values::option_number")]
    pub radius: Option<Spanned<f64>>,
    /// Gear: the two revolute joints in mesh, `[driving, driven]`.
    #[serde(default, deserialize_with = "crate::scene::values::option_name_pair")]
    pub gears: Option<Spanned<[Name; 2]>>,
    /// Gear: Δθ_driven = ratio · Δθ_driving (negative for an external mesh).
    #[serde(default, deserialize_with = "crate::scene::values::option_number")]
    pub ratio: Option<Spanned<f64>>,
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
    #[serde(default, deserialize_with = "crate::scene::values::option_number")]
    pub speed: Option<Spanned<f64>>,
    /// The drive acceleration α (angular acceleration unit) or slide acceleration
    /// (length unit per s²). Default 0.
    #[serde(default, deserialize_with = "crate::scene::values::option_number")]
    pub acceleration: Option<Spanned<f64>>,
    /// A cam scene file (path relative to this file) whose follower moves the joint: the
    /// sweep, `speed` and `acceleration` are then the cam's (see [`super::model::DriveCam`]).
    pub cam: Option<Name>,
}

/// `[sweep]`: `from`, `to`, `step`, or `positions`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepSection {
    /// First drive position (angle or length unit).
    #[serde(default, deserialize_with = "crate::scene::values::option_number")]
    pub from: Option<Spanned<f64>>,
    /// Last drive position (included when the step divides the range).
    #[serde(default, deserialize_with = "crate::scene::values::option_number")]
    pub to: Option<Spanned<f64>>,
    /// Positive step.
    #[serde(default, deserialize_with = "crate::scene::values::option_number")]
    pub step: Option<Spanned<f64>>,
    /// An explicit list of drive positions.
    #[serde(default, deserialize_with = "crate::scene::values::option_positions")]
    pub positions: Option<super::values::PositionList>,
    /// The positions (range or list) are values of this output (an angle or slider output),
    /// in its unit; the drive positions that give them are solved for.
    pub of: Option<Name>,
}

/// What an output reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// The value (position, angle, displacement).
    Position,
    /// First derivative with respect to the drive (ψ′).
    VelocityCoefficient,
    /// Second derivative with respect to the drive (ψ″).
    AccelerationCoefficient,
    /// Time derivative (ψ̇ = ω ψ′).
    Velocity,
    /// Second time derivative (ψ̈ = α ψ′ + ω² ψ″).
    Acceleration,
}

/// One `[[output]]` entry: exactly one of `point`, `angle`, `slider`.
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
    /// What to report (default: position, velocity, acceleration).
    pub quantities: Option<Spanned<Vec<Spanned<Quantity>>>>,
    /// Find where this output's velocity coefficient changes sign in the sweep range and
    /// print those dead positions and the stroke between them.
    #[serde(default)]
    pub dead_positions: bool,
}

/// The sense in which an output angle is counted.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Sense {
    /// Counter-clockwise positive.
    Ccw,
    /// Clockwise positive.
    Cw,
}
