//! Coulomb friction: `T = f·|N|` opposing the relative sliding velocity in prismatic and
//! pin-in-slot joints, and the friction circle (torque `f·r·|R|` opposing the relative
//! rotation) in revolute joints.
//!
//! The normal force `N` is the joint's reaction, unknown until the equilibrium is solved; the
//! direction of the friction force is known from the relative velocity. [`super::kinetostatics`]
//! resolves `|N|` by iteration. At zero relative velocity the (static) friction force is
//! indeterminate; kinetic friction is then taken as zero.

use super::state::{LinkState, dot, of};
use crate::Error;
use crate::geometry::{JointKind, Mechanism};

/// Friction in one joint.
///
/// ```
/// use mechdiff_core::dynamics::Friction;
/// let slot = Friction::sliding("slot", 0.15);
/// let pin = Friction::revolute("B", 0.1, 0.01); // friction circle radius 1 mm
/// assert_eq!((slot.coefficient, pin.pin_radius), (0.15, Some(0.01)));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Friction {
    /// The joint (prismatic, pin in slot or revolute).
    pub joint: String,
    /// Coulomb coefficient of kinetic friction `f ≥ 0`.
    pub coefficient: f64,
    /// Pin radius `r` of a revolute joint (m): friction circle radius `f·r`.
    pub pin_radius: Option<f64>,
    /// Where the friction force acts in a sliding joint: signed distance (m) from the
    /// measuring point (prismatic) or the pin (pin in slot) along the guide's normal
    /// `n = u` turned by +90°. A slider whose centre lies `h` above its contact surface has
    /// offset `−h` when `n` points away from the surface.
    pub contact_offset: f64,
}

impl Friction {
    /// Friction in a prismatic or pin-in-slot joint.
    pub fn sliding(joint: impl Into<String>, coefficient: f64) -> Self {
        Friction {
            joint: joint.into(),
            coefficient,
            pin_radius: None,
            contact_offset: 0.0,
        }
    }

    /// Friction circle in a revolute joint with pin radius `pin_radius` (m).
    pub fn revolute(joint: impl Into<String>, coefficient: f64, pin_radius: f64) -> Self {
        Friction {
            joint: joint.into(),
            coefficient,
            pin_radius: Some(pin_radius),
            contact_offset: 0.0,
        }
    }

    /// Sets the contact offset (see [`Friction::contact_offset`]).
    pub fn with_contact_offset(mut self, offset: f64) -> Self {
        self.contact_offset = offset;
        self
    }
}

/// Friction compiled to link indices, local geometry and the rows of its normal force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum CompiledFriction {
    Sliding {
        joint: usize,
        guide: usize,
        slider: usize,
        /// Unit direction of the guide line, guide-local (unrotated).
        direction: [f64; 2],
        /// The measuring point or pin, slider-local.
        point: [f64; 2],
        offset: f64,
        /// Row of the normal-force multiplier.
        row: usize,
        coefficient: f64,
    },
    Revolute {
        joint: usize,
        a: usize,
        b: usize,
        /// Rows of the two force multipliers.
        row: usize,
        /// Friction circle radius `f·r` (m).
        radius: f64,
    },
}

pub(crate) fn compile(
    m: &Mechanism,
    f: &Friction,
    rows: &[usize],
) -> Result<CompiledFriction, Error> {
    let context = || format!("friction in joint `{}`", f.joint);
    let joint = m.joint_index(&f.joint).map_err(|_| Error::UnknownName {
        what: "joint",
        name: f.joint.clone(),
        context: context(),
    })?;
    if !(f.coefficient.is_finite() && f.coefficient >= 0.0) {
        return Err(Error::InvalidValue {
            what: format!("friction coefficient of joint `{}` (must be ≥ 0)", f.joint),
            value: f.coefficient,
        });
    }
    if !f.contact_offset.is_finite() {
        return Err(Error::InvalidValue {
            what: format!("contact offset of {}", context()),
            value: f.contact_offset,
        });
    }
    let unit = |line: [usize; 2]| {
        let (a, b) = (m.points[line[0]].sketch, m.points[line[1]].sketch);
        let d = [b[0] - a[0], b[1] - a[1]];
        let len = d[0].hypot(d[1]);
        [d[0] / len, d[1] / len]
    };
    let row = rows[joint];
    match m.joints[joint].kind {
        JointKind::Prismatic {
            guide,
            line,
            slider,
            point,
        } => Ok(CompiledFriction::Sliding {
            joint,
            guide,
            slider,
            direction: unit(line),
            point: m.local(slider, m.points[point].sketch),
            offset: f.contact_offset,
            row: row + 1,
            coefficient: f.coefficient,
        }),
        JointKind::PinInSlot {
            slot_link,
            line,
            pin_link,
            pin,
        } => Ok(CompiledFriction::Sliding {
            joint,
            guide: slot_link,
            slider: pin_link,
            direction: unit(line),
            point: m.local(pin_link, m.points[pin].sketch),
            offset: f.contact_offset,
            row,
            coefficient: f.coefficient,
        }),
        JointKind::Revolute { link_a, link_b, .. } => {
            let r = f.pin_radius.ok_or_else(|| Error::MissingData {
                what: context(),
                missing: "the pin radius of the revolute joint".to_owned(),
            })?;
            if !(r.is_finite() && r >= 0.0) {
                return Err(Error::InvalidValue {
                    what: format!("pin radius of {} (must be ≥ 0)", context()),
                    value: r,
                });
            }
            Ok(CompiledFriction::Revolute {
                joint,
                a: link_a,
                b: link_b,
                row,
                radius: f.coefficient * r,
            })
        }
        ref other => Err(Error::InvalidJoint {
            joint: f.joint.clone(),
            problem: format!(
                "friction is modelled in prismatic, pin-in-slot and revolute joints, not in a {} joint \
                 (give it an efficiency instead)",
                other.kind_name()
            ),
        }),
    }
}

/// The sliding geometry of a friction joint at an instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Sliding {
    /// Guide direction `u` (global).
    pub u: [f64; 2],
    /// Where the friction force acts (global).
    pub contact: [f64; 2],
    /// Relative sliding velocity of the slider along `u` at the contact (m/s).
    pub velocity: f64,
}

/// Sign of a relative velocity, zero below a rounding threshold.
pub(crate) fn sign(v: f64, scale: f64) -> f64 {
    if v.abs() <= 1e-12 * scale {
        0.0
    } else {
        v.signum()
    }
}

impl CompiledFriction {
    pub fn joint(&self) -> usize {
        match *self {
            CompiledFriction::Sliding { joint, .. } | CompiledFriction::Revolute { joint, .. } => {
                joint
            }
        }
    }

    /// Sliding geometry (sliding joints only).
    pub fn sliding(&self, states: &[LinkState]) -> Option<Sliding> {
        let CompiledFriction::Sliding {
            guide,
            slider,
            direction,
            point,
            offset,
            ..
        } = *self
        else {
            return None;
        };
        let (g, s) = (of(states, guide), of(states, slider));
        let u = g.arm(direction);
        let p = s.position(point);
        let contact = [p[0] - offset * u[1], p[1] + offset * u[0]];
        let (vs, vg) = (s.velocity_at(contact), g.velocity_at(contact));
        Some(Sliding {
            u,
            contact,
            velocity: dot(u, [vs[0] - vg[0], vs[1] - vg[1]]),
        })
    }

    /// Relative angular velocity `ω_b − ω_a` (revolute joints only).
    pub fn relative_rotation(&self, states: &[LinkState]) -> Option<f64> {
        match *self {
            CompiledFriction::Revolute { a, b, .. } => {
                Some(of(states, b).omega - of(states, a).omega)
            }
            CompiledFriction::Sliding { .. } => None,
        }
    }
}
