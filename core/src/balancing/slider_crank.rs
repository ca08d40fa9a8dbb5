//! The slider-crank's primary and secondary unbalance and the classic partial balance.
//!
//! With crank `r`, connecting rod `l`, an in-line slider and the crank turning at constant
//! speed ω, the reciprocating mass `m_rec` (slider and the rod's share at the wrist pin)
//! has the acceleration `ẍ ≈ −r ω² (cos φ + (r/l) cos 2φ)` (the first two terms of the
//! series), so it shakes the frame along the line of stroke with the **primary** force
//! `m_rec r ω² cos φ` and the **secondary** force `m_rec (r²/l) ω² cos 2φ`. The rotating mass
//! (crank and the rod's share at the crank pin, as `m_rot r` at the pin) is balanced fully by
//! a crank counterweight; adding a fraction `c` of `m_rec r` to it turns a primary force
//! `(1 − c) m_rec r ω²` along the line and `c m_rec r ω²` across it: `c = 1/2` makes the
//! primary force's largest value smallest, and it is also the least-squares balance over a
//! revolution (a rotating counterweight cancels only the forward half of the
//! reciprocating `cos φ`).
//!
//! ```
//! use mechdiff_core::balancing::SliderCrankUnbalance;
//! let s = SliderCrankUnbalance::new(0.1, 0.4, 2.0, 0.3).unwrap();
//! assert!((s.primary(100.0) - 2.0 * 0.1 * 1e4).abs() < 1e-9);
//! assert!((s.secondary(100.0) - 2.0 * 0.01 / 0.4 * 1e4).abs() < 1e-9);
//! let half = s.partial_balance(0.5, 100.0).unwrap();
//! assert!((half.counterweight_mass_radius - (0.3 + 0.5 * 2.0 * 0.1)).abs() < 1e-15);
//! ```

use crate::Error;
use crate::geometry::{JointKind, Mechanism};

/// The unbalance data of a slider-crank.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SliderCrankUnbalance {
    /// Crank radius `r` (m).
    pub crank: f64,
    /// Connecting-rod length `l` (m).
    pub rod: f64,
    /// Reciprocating mass `m_rec` (kg).
    pub reciprocating_mass: f64,
    /// Rotating mass-radius `m_rot r` at the crank pin (kg·m), signed: positive when the
    /// rotating masses' centre is on the crank pin's side of the pivot.
    pub rotating_mass_radius: f64,
}

/// A crank counterweight that balances the rotating mass and a fraction of the
/// reciprocating one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PartialBalance {
    /// The fraction `c` of `m_rec r` balanced.
    pub fraction: f64,
    /// Counterweight mass-radius `m_rot r + c m_rec r` (kg·m), opposite the crank pin
    /// (negative: on the pin's side).
    pub counterweight_mass_radius: f64,
    /// Primary force left along the line of stroke, amplitude `(1 − c) m_rec r ω²` (N).
    pub primary_along: f64,
    /// Primary force brought in across the line of stroke, amplitude `c m_rec r ω²` (N).
    pub primary_across: f64,
    /// Secondary force, amplitude `m_rec (r²/l) ω²` (N), which no crank counterweight touches.
    pub secondary: f64,
}

impl SliderCrankUnbalance {
    /// Checks the data: lengths positive, `l > r`, the reciprocating mass finite and ≥ 0,
    /// the rotating mass-radius finite.
    pub fn new(
        crank: f64,
        rod: f64,
        reciprocating_mass: f64,
        rotating_mass_radius: f64,
    ) -> Result<Self, Error> {
        for (v, what) in [(crank, "crank radius"), (rod, "connecting-rod length")] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::NonPositiveLength {
                    what: format!("the slider-crank's {what}"),
                    length: v,
                });
            }
        }
        if rod <= crank {
            return Err(Error::InvalidValue {
                what: format!(
                    "connecting-rod length (m; must exceed the crank radius {crank} m for the \
                     crank to turn fully)"
                ),
                value: rod,
            });
        }
        if !(reciprocating_mass.is_finite() && reciprocating_mass >= 0.0) {
            return Err(Error::InvalidValue {
                what: "reciprocating mass (kg, ≥ 0)".to_owned(),
                value: reciprocating_mass,
            });
        }
        if !rotating_mass_radius.is_finite() {
            return Err(Error::InvalidValue {
                what: "rotating mass-radius (kg m)".to_owned(),
                value: rotating_mass_radius,
            });
        }
        Ok(SliderCrankUnbalance {
            crank,
            rod,
            reciprocating_mass,
            rotating_mass_radius,
        })
    }

    /// Amplitude of the primary unbalance force `m_rec r ω²` (N).
    pub fn primary(&self, omega: f64) -> f64 {
        self.reciprocating_mass * self.crank * omega * omega
    }

    /// Amplitude of the secondary unbalance force `m_rec (r²/l) ω²` (N).
    pub fn secondary(&self, omega: f64) -> f64 {
        self.primary(omega) * self.crank / self.rod
    }

    /// The crank counterweight balancing the rotating mass and the fraction `fraction` (in
    /// [0, 1]) of the reciprocating mass, and the forces it leaves.
    pub fn partial_balance(&self, fraction: f64, omega: f64) -> Result<PartialBalance, Error> {
        if !(0.0..=1.0).contains(&fraction) {
            return Err(Error::InvalidValue {
                what: "fraction of the reciprocating mass to balance (must be in [0, 1])"
                    .to_owned(),
                value: fraction,
            });
        }
        let p = self.primary(omega);
        Ok(PartialBalance {
            fraction,
            counterweight_mass_radius: self.rotating_mass_radius
                + fraction * self.reciprocating_mass * self.crank,
            primary_along: (1.0 - fraction) * p,
            primary_across: fraction * p,
            secondary: self.secondary(omega),
        })
    }
}

/// The revolute joint point between links `a` and `b`, if there is one.
fn revolute_between(m: &Mechanism, a: usize, b: usize) -> Option<usize> {
    m.joints.iter().find_map(|j| match j.kind {
        JointKind::Revolute {
            link_a,
            link_b,
            point,
        } if (link_a, link_b) == (a, b) || (link_a, link_b) == (b, a) => Some(point),
        _ => None,
    })
}

impl SliderCrankUnbalance {
    /// The unbalance data of the slider-crank formed by `crank` (turning about a fixed pivot
    /// O), `rod` (hinged to the crank at A) and `slider` (hinged to the rod at B, on a
    /// straight ground guide through O): r = |OA|, l = |AB| at the sketch, and the masses
    /// split by the two-mass equivalent of the rod (its mass shared between A and B by the
    /// position of its centre of gravity along AB): `m_rec = m_slider + m_rod·|AG|/l`,
    /// `m_rot r = m_crank·(OG_crank · OA)/r + m_rod·(1 − |AG|/l)·r` (the crank's centre of
    /// gravity projected on the crank line).
    ///
    /// Errors: unknown links, links that are not joined in that way, links without mass
    /// data, a guide that does not pass through O (an offset slider-crank, for which these
    /// formulas do not hold).
    pub fn from_mechanism(
        m: &Mechanism,
        crank: &str,
        rod: &str,
        slider: &str,
    ) -> Result<Self, Error> {
        let index = |name: &str| {
            m.link_index(name).map_err(|_| Error::UnknownName {
                what: "link",
                name: name.to_owned(),
                context: "the slider-crank's unbalance".to_owned(),
            })
        };
        let (c, r, s) = (index(crank)?, index(rod)?, index(slider)?);
        let joint = |a: usize, b: usize, what: &str| {
            revolute_between(m, a, b).ok_or_else(|| Error::InvalidJoint {
                joint: what.to_owned(),
                problem: format!(
                    "the slider-crank's unbalance needs a revolute joint between `{}` and `{}`",
                    m.links[a].name, m.links[b].name
                ),
            })
        };
        let o = m.points[joint(0, c, "crank pivot")?].sketch;
        let a = m.points[joint(c, r, "crank pin")?].sketch;
        let b = m.points[joint(r, s, "wrist pin")?].sketch;
        let guide = m.joints.iter().find_map(|j| match j.kind {
            JointKind::Prismatic {
                guide: 0,
                line,
                slider: k,
                ..
            } if k == s => Some(line),
            _ => None,
        });
        let Some(line) = guide else {
            return Err(Error::InvalidJoint {
                joint: format!("guide of `{slider}`"),
                problem: format!("`{slider}` must slide on a prismatic joint on the ground"),
            });
        };
        let (p, q) = (m.points[line[0]].sketch, m.points[line[1]].sketch);
        let length = |u: [f64; 2], v: [f64; 2]| (v[0] - u[0]).hypot(v[1] - u[1]);
        let cross = |u: [f64; 2], v: [f64; 2], w: [f64; 2]| {
            (v[0] - u[0]) * (w[1] - u[1]) - (v[1] - u[1]) * (w[0] - u[0])
        };
        let (crank_r, rod_l) = (length(o, a), length(a, b));
        let offset = cross(p, q, o) / length(p, q);
        if offset.abs() > 1e-9 * (crank_r + rod_l) {
            return Err(Error::InvalidValue {
                what: format!(
                    "offset of the guide of `{slider}` from the crank pivot (m; the primary and \
                     secondary unbalance formulas are for an in-line slider-crank)"
                ),
                value: offset,
            });
        }
        let inertia = |k: usize| {
            m.links[k].inertia.ok_or_else(|| Error::MissingData {
                what: "the slider-crank's unbalance".to_owned(),
                missing: format!("mass data for link `{}`", m.links[k].name),
            })
        };
        let (ic, ir, is) = (inertia(c)?, inertia(r)?, inertia(s)?);
        let dot = |u: [f64; 2], v: [f64; 2], w: [f64; 2]| {
            (v[0] - u[0]) * (w[0] - u[0]) + (v[1] - u[1]) * (w[1] - u[1])
        };
        let share_b = if rod_l > 0.0 {
            dot(a, b, ir.center) / (rod_l * rod_l)
        } else {
            0.0
        };
        let crank_mr = if crank_r > 0.0 {
            ic.mass * dot(o, a, ic.center) / crank_r
        } else {
            0.0
        };
        Self::new(
            crank_r,
            rod_l,
            is.mass + ir.mass * share_b,
            crank_mr + ir.mass * (1.0 - share_b) * crank_r,
        )
    }
}
