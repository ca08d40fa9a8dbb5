//! Outputs resolved once: names looked up and link-local coordinates computed before a
//! sweep, so that reading them at every drive position costs only arithmetic.
//!
//! ```
//! use mechdiff_core::geometry::{Drive, Mechanism, Solver};
//! let m = Mechanism::builder()
//!     .point("O", [0.0, 0.0]).point("A", [2.0, 0.0])
//!     .ground(["O"]).link("crank", ["O", "A"])
//!     .revolute("O", "ground", "crank", "O")
//!     .drive(Drive::angle("O"))
//!     .build().unwrap();
//! let (tip, turn) = (m.point_output("crank", "A").unwrap(), m.rotation_output("crank").unwrap());
//! let mut t = Solver::default().track(&m).unwrap();
//! for phi in [0.25, 0.5] {
//!     t.move_to(phi).unwrap();
//!     let k = t.kinematics::<2>().unwrap();
//!     let [x, _] = k.position(&tip);
//!     assert!((x.value - 2.0 * phi.cos()).abs() < 1e-14);
//!     assert_eq!(k.value(&turn).d1(), 1.0); // θ = φ: θ′ = 1
//! }
//! ```

use super::constraints::{self, Body, Slide};
use super::model::{JointKind, Mechanism};
use crate::Error;

/// A point of a link, resolved (see [`Mechanism::point_output`]); read it with
/// [`super::Kinematics::position`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointOutput {
    pub(crate) body: Body,
    /// Link-local coordinates (m).
    pub(crate) local: [f64; 2],
}

/// An angle or displacement, resolved (see [`Mechanism::rotation_output`] and the methods
/// next to it); read it with [`super::Kinematics::value`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScalarOutput(pub(crate) Scalar);

#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Scalar {
    /// θ of a body plus a constant (a segment's direction at the sketch).
    Rotation { body: Body, offset: f64 },
    /// θ_b − θ_a.
    Relative { a: Body, b: Body },
    /// Displacement along a prismatic joint.
    Displacement(Slide),
}

fn invalid(name: &str, problem: impl Into<String>) -> Error {
    Error::InvalidOutput {
        name: name.to_owned(),
        problem: problem.into(),
    }
}

impl Mechanism {
    fn output_link(&self, name: &str) -> Result<usize, Error> {
        self.link_index(name)
            .map_err(|_| invalid(name, "no link of this name"))
    }

    fn output_point_on(&self, link: usize, point: &str) -> Result<[f64; 2], Error> {
        let p = self
            .point_index(point)
            .map_err(|_| invalid(point, "no point of this name"))?;
        if !self.carries(link, p) {
            let problem = format!("point is not on link `{}`", self.links[link].name);
            return Err(invalid(point, problem));
        }
        Ok(self.points[p].sketch)
    }

    fn output_joint(&self, name: &str) -> Result<usize, Error> {
        self.joint_index(name)
            .map_err(|e| invalid(name, e.to_string()))
    }

    /// Point `point` carried by link `link`.
    pub fn point_output(&self, link: &str, point: &str) -> Result<PointOutput, Error> {
        let k = self.output_link(link)?;
        let at = self.output_point_on(k, point)?;
        Ok(self.point_at_index(k, at))
    }

    /// The point of link `link` that is at `sketch` (global, m) in the sketch.
    pub fn point_at_output(&self, link: &str, sketch: [f64; 2]) -> Result<PointOutput, Error> {
        Ok(self.point_at_index(self.output_link(link)?, sketch))
    }

    /// The centre of gravity of link `link` (its [`super::Inertia`] must be given).
    pub fn center_of_gravity_output(&self, link: &str) -> Result<PointOutput, Error> {
        let k = self.output_link(link)?;
        let inertia = self.links[k]
            .inertia
            .ok_or_else(|| invalid(link, "the link has no mass properties"))?;
        Ok(self.point_at_index(k, inertia.center))
    }

    fn point_at_index(&self, k: usize, sketch: [f64; 2]) -> PointOutput {
        PointOutput {
            body: constraints::body(k),
            local: self.local(k, sketch),
        }
    }

    /// Rotation of link `link` since the sketch pose (rad).
    pub fn rotation_output(&self, link: &str) -> Result<ScalarOutput, Error> {
        let body = constraints::body(self.output_link(link)?);
        Ok(ScalarOutput(Scalar::Rotation { body, offset: 0.0 }))
    }

    /// Direction angle of the segment `from → to` (two points of link `link`), measured
    /// counter-clockwise from +x (rad; continuous from the sketch value, not wrapped).
    pub fn angle_output(&self, link: &str, from: &str, to: &str) -> Result<ScalarOutput, Error> {
        let k = self.output_link(link)?;
        let (a, b) = (self.output_point_on(k, from)?, self.output_point_on(k, to)?);
        if a == b {
            return Err(invalid(
                &format!("{from}–{to}"),
                "the two points coincide; the direction is undefined",
            ));
        }
        Ok(ScalarOutput(Scalar::Rotation {
            body: constraints::body(k),
            offset: (b[1] - a[1]).atan2(b[0] - a[0]),
        }))
    }

    /// Displacement in prismatic joint `joint` (m), measured as in the model.
    pub fn displacement_output(&self, joint: &str) -> Result<ScalarOutput, Error> {
        match self.joints[self.output_joint(joint)?].kind {
            JointKind::Prismatic {
                guide,
                line,
                slider,
                point,
            } => Ok(ScalarOutput(Scalar::Displacement(
                constraints::compile_slide(self, guide, line, slider, point),
            ))),
            _ => Err(invalid(joint, "a displacement needs a prismatic joint")),
        }
    }

    /// Relative rotation of link b with respect to link a in revolute joint `joint` since
    /// the sketch (rad).
    pub fn joint_rotation_output(&self, joint: &str) -> Result<ScalarOutput, Error> {
        match self.joints[self.output_joint(joint)?].kind {
            JointKind::Revolute { link_a, link_b, .. } => Ok(ScalarOutput(Scalar::Relative {
                a: constraints::body(link_a),
                b: constraints::body(link_b),
            })),
            _ => Err(invalid(joint, "a joint rotation needs a revolute joint")),
        }
    }
}
