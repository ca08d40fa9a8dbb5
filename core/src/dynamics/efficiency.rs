//! Transmission efficiency of gear pairs and rack-and-pinions, by direction of power flow.
//!
//! An ideal mesh transmits the power it receives; with efficiency `η` the driven side gets
//! `η` times the power the driving side puts in (direct flow). When the flow reverses (the
//! nominally driven side drives), the nominal driving side gets `η` times what the other side
//! puts in, so its force is `1/η` times the ideal one relative to the other side. In the
//! equilibrium equations this scales the output side's part of the mesh's constraint row by
//! `κ = η` (direct) or `κ = 1/η` (reverse): the lost power is `(1 − κ)·P_in`, `P_in` the
//! power the nominal driving side delivers to the mesh.

use crate::Error;
use crate::geometry::{JointKind, Mechanism};

/// Which side of a mesh is nominally driving (direct power flow).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Driving {
    /// The pinion of a rack-and-pinion, or the first revolute joint of a gear pair.
    #[default]
    First,
    /// The rack of a rack-and-pinion, or the second revolute joint of a gear pair.
    Second,
}

/// Efficiency of one rack-and-pinion or gear joint.
///
/// ```
/// use mechdiff_core::dynamics::{Driving, Efficiency};
/// let mesh = Efficiency::new("mesh", 0.95);
/// assert_eq!(mesh.driving, Driving::First);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Efficiency {
    /// The rack-and-pinion or gear joint.
    pub joint: String,
    /// Efficiency `η ∈ (0, 1]` for direct power flow.
    pub efficiency: f64,
    /// The nominally driving side.
    pub driving: Driving,
}

impl Efficiency {
    /// Efficiency `η` of joint `joint`, driven from its first side (pinion / first gear).
    pub fn new(joint: impl Into<String>, efficiency: f64) -> Self {
        Efficiency {
            joint: joint.into(),
            efficiency,
            driving: Driving::First,
        }
    }

    /// Sets the nominally driving side.
    pub fn driven_from(mut self, driving: Driving) -> Self {
        self.driving = driving;
        self
    }
}

/// Checks `η ∈ (0, 1]`.
pub(crate) fn check_efficiency(what: impl FnOnce() -> String, eta: f64) -> Result<(), Error> {
    if eta.is_finite() && eta > 0.0 && eta <= 1.0 {
        Ok(())
    } else {
        Err(Error::InvalidValue {
            what: format!("{} (must be in (0, 1])", what()),
            value: eta,
        })
    }
}

/// An efficiency compiled: the mesh's row and the driving side's part of that row of `Φ_q`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct CompiledEfficiency {
    pub joint: usize,
    pub row: usize,
    pub eta: f64,
    /// The first side's part of the row (dense, one entry per coordinate).
    pub first: Vec<f64>,
    /// The nominally driving side.
    pub driving: Driving,
}

pub(crate) fn compile(
    m: &Mechanism,
    e: &Efficiency,
    rows: &[usize],
) -> Result<CompiledEfficiency, Error> {
    let joint = m.joint_index(&e.joint).map_err(|_| Error::UnknownName {
        what: "joint",
        name: e.joint.clone(),
        context: "efficiency".to_owned(),
    })?;
    check_efficiency(
        || format!("efficiency of joint `{}`", e.joint),
        e.efficiency,
    )?;
    let n = m.coordinate_count();
    let mut first = vec![0.0; n];
    let add_angle = |v: &mut Vec<f64>, link: usize, w: f64| {
        if link > 0 {
            v[3 * (link - 1) + 2] += w;
        }
    };
    let revolute = |j: usize| match m.joints[j].kind {
        JointKind::Revolute { link_a, link_b, .. } => (link_a, link_b),
        _ => (0, 0),
    };
    // The first side's part of the row: −R(θ_b − θ_a) for a rack-and-pinion,
    // −ratio(θ_b1 − θ_a1) for a gear (see the constraint table in `geometry`).
    let factor = match m.joints[joint].kind {
        JointKind::RackPinion { pinion, radius, .. } => {
            let (a, b) = revolute(pinion);
            (a, b, radius)
        }
        JointKind::Gear { joint_a, ratio, .. } => {
            let (a, b) = revolute(joint_a);
            (a, b, ratio)
        }
        ref other => {
            return Err(Error::InvalidJoint {
                joint: e.joint.clone(),
                problem: format!(
                    "an efficiency applies to a rack-and-pinion or gear joint, not to a {} joint",
                    other.kind_name()
                ),
            });
        }
    };
    add_angle(&mut first, factor.1, -factor.2);
    add_angle(&mut first, factor.0, factor.2);
    Ok(CompiledEfficiency {
        joint,
        row: rows[joint],
        eta: e.efficiency,
        first,
        driving: e.driving,
    })
}

impl CompiledEfficiency {
    /// The driving side's part of the row, given the full row of `Φ_q`.
    pub fn input_part(&self, row: &[f64]) -> Vec<f64> {
        match self.driving {
            Driving::First => self.first.clone(),
            Driving::Second => row.iter().zip(&self.first).map(|(r, f)| r - f).collect(),
        }
    }
}
