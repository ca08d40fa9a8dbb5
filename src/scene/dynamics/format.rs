//! The dynamic sections as written (serde, every value with its span).

use std::collections::BTreeMap;

use serde::Deserialize;
use toml::Spanned;

use crate::scene::values::Name;
use crate::scene::values::Number;

/// `[masses.<link>]`: a `mass` with its `center` (and `inertia`), or a `density` per length
/// for a uniform bar.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MassDef {
    /// Mass (kg).
    #[serde(default)]
    pub mass: Option<Spanned<Number>>,
    /// Mass per length of a uniform slender bar (kg/m): mass ρ·L at the bar's midpoint and
    /// moment of inertia m·L²/12 about it, unless `center` or `inertia` are given.
    #[serde(default)]
    pub density: Option<Spanned<Number>>,
    /// With `density`: the bar's ends, two points of the link (default: the link's two
    /// points, when it has two).
    #[serde(default, deserialize_with = "crate::scene::values::option_name_pair")]
    pub bar: Option<Spanned<[Name; 2]>>,
    /// Centre of gravity: a point of the link, or `[x, y]` at the sketch (length unit);
    /// required with `mass`.
    pub center: Option<Spanned<CenterDef>>,
    /// Moment of inertia about the centre (kg·m²); default 0 with `mass`, m·L²/12 with
    /// `density`.
    #[serde(default)]
    pub inertia: Option<Spanned<Number>>,
}

/// A centre of gravity: a named point or sketch coordinates.
#[derive(Debug)]
pub enum CenterDef {
    /// A point of the link.
    Point(String),
    /// Sketch coordinates, each with its span (a scene's tangent keeps their derivatives by
    /// place).
    Xy([Spanned<Number>; 2]),
}

impl<'de> Deserialize<'de> for CenterDef {
    fn deserialize<De: serde::Deserializer<'de>>(deserializer: De) -> Result<Self, De::Error> {
        deserializer.deserialize_any(CenterVisitor)
    }
}

struct CenterVisitor;

impl<'de> serde::de::Visitor<'de> for CenterVisitor {
    type Value = CenterDef;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a centre: a point of the link (`\"P\"`) or sketch coordinates `[x, y]`")
    }

    fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<CenterDef, E> {
        Ok(CenterDef::Point(v.to_owned()))
    }

    fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut seq: A) -> Result<CenterDef, A::Error> {
        let mut xy = Vec::with_capacity(2);
        while let Some(n) = seq.next_element::<Spanned<crate::scene::values::Number>>()? {
            xy.push(n);
        }
        let n = xy.len();
        let xy: [Spanned<Number>; 2] = xy.try_into().map_err(|_| {
            serde::de::Error::custom(format!(
                "expected exactly two coordinates, found {n}; a centre is written `[x, y]`"
            ))
        })?;
        Ok(CenterDef::Xy(xy))
    }
}

/// `[gravity]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GravityDef {
    /// Acceleration of gravity (m/s²), along −y.
    pub g: Spanned<Number>,
}

/// One `[[load]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadDef {
    /// The loaded link.
    pub link: Name,
    /// Point of application of a force (a point of the link).
    pub point: Option<Name>,
    /// Force (N), global components, each with its span.
    #[serde(default, deserialize_with = "crate::scene::values::option_number_pair")]
    pub force: Option<crate::scene::values::SpannedPair>,
    /// Torque (N·m), counter-clockwise positive.
    #[serde(default)]
    pub torque: Option<Spanned<Number>>,
    /// Drive range where the load acts, in the drive's unit.
    #[serde(default, deserialize_with = "crate::scene::values::option_number_pair")]
    pub active: Option<crate::scene::values::SpannedPair>,
}

/// `[friction.<joint>]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionDef {
    /// Coulomb coefficient (≥ 0).
    pub coefficient: Spanned<Number>,
    /// Revolute joints: pin radius (length unit).
    #[serde(default)]
    pub pin_radius: Option<Spanned<Number>>,
    /// Sliding joints: where the friction force acts, along the guide's normal from the
    /// joint's point (length unit).
    #[serde(default)]
    pub contact_offset: Option<Spanned<Number>>,
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
    pub efficiency: Spanned<Number>,
    /// The nominally driving side (default `first`).
    pub driving: Option<Spanned<DrivingSide>>,
}

/// `[motor]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MotorDef {
    /// Rotor moment of inertia (kg·m², ≥ 0).
    pub rotor_inertia: Spanned<Number>,
    /// Drive-joint speed over motor speed (non-zero).
    pub ratio: Spanned<Number>,
    /// Gearbox efficiency in (0, 1]; default 1.
    #[serde(default)]
    pub efficiency: Option<Spanned<Number>>,
    /// The torque–speed characteristic on the motor shaft, which `[simulate]` moves the
    /// machine with (see [`crate::scene::motion`]).
    #[serde(default)]
    pub characteristic: Option<Spanned<crate::scene::motion::CharacteristicDef>>,
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
