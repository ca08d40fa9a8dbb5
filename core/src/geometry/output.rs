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
use super::datum::{Data, Datum};
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

/// A resolved angle or displacement, its data in `T` (`f64`, or `Dual64` in
/// [`super::parametric`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Scalar<T = f64> {
    /// θ of a body plus a constant (a segment's direction at the sketch).
    Rotation { body: Body, offset: T },
    /// θ_b − θ_a.
    Relative { a: Body, b: Body },
    /// Displacement along a prismatic joint.
    Displacement(Slide<T>),
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

    /// Index of point `point`, which must be carried by link `link`.
    fn output_point_on(&self, link: usize, point: &str) -> Result<usize, Error> {
        let p = self
            .point_index(point)
            .map_err(|_| invalid(point, "no point of this name"))?;
        if !self.carries(link, p) {
            let problem = format!("point is not on link `{}`", self.links[link].name);
            return Err(invalid(point, problem));
        }
        Ok(p)
    }

    fn output_joint(&self, name: &str) -> Result<usize, Error> {
        self.joint_index(name)
            .map_err(|e| invalid(name, e.to_string()))
    }

    /// Point `point` carried by link `link`.
    pub fn point_output(&self, link: &str, point: &str) -> Result<PointOutput, Error> {
        let (body, local) = self.resolve_point(&Data::of(self), link, point)?;
        Ok(PointOutput { body, local })
    }

    /// Point `point` of link `link`: its body and link-local coordinates from `data`.
    pub(crate) fn resolve_point<T: Datum>(
        &self,
        data: &Data<'_, T>,
        link: &str,
        point: &str,
    ) -> Result<(Body, [T; 2]), Error> {
        let k = self.output_link(link)?;
        let p = self.output_point_on(k, point)?;
        Ok((constraints::body(k), data.local(k, data.point(p))))
    }

    /// The point of link `link` that is at `sketch` (global, m) in the sketch.
    pub fn point_at_output(&self, link: &str, sketch: [f64; 2]) -> Result<PointOutput, Error> {
        Ok(self.point_at_index(self.output_link(link)?, sketch))
    }

    /// The centre of gravity of link `link` (its [`super::Inertia`] must be given).
    pub fn center_of_gravity_output(&self, link: &str) -> Result<PointOutput, Error> {
        let k = self.output_link(link)?;
        Ok(self.point_at_index(k, self.output_center(k)?))
    }

    /// The centre of gravity of link `k` at the sketch (global).
    pub(crate) fn output_center(&self, k: usize) -> Result<[f64; 2], Error> {
        let inertia = self.links[k]
            .inertia
            .ok_or_else(|| invalid(&self.links[k].name, "the link has no mass properties"))?;
        Ok(inertia.center)
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
        Ok(ScalarOutput(self.resolve_angle(
            &Data::of(self),
            link,
            from,
            to,
        )?))
    }

    /// [`Mechanism::angle_output`] with the sketch from `data`.
    pub(crate) fn resolve_angle<T: Datum>(
        &self,
        data: &Data<'_, T>,
        link: &str,
        from: &str,
        to: &str,
    ) -> Result<Scalar<T>, Error> {
        let k = self.output_link(link)?;
        let (a, b) = (self.output_point_on(k, from)?, self.output_point_on(k, to)?);
        if self.points[a].sketch == self.points[b].sketch {
            return Err(invalid(
                &format!("{from}–{to}"),
                "the two points coincide; the direction is undefined",
            ));
        }
        let (a, b) = (data.point(a), data.point(b));
        Ok(Scalar::Rotation {
            body: constraints::body(k),
            offset: T::direction(b[1] - a[1], b[0] - a[0]),
        })
    }

    /// Displacement in prismatic joint `joint` (m), measured as in the model.
    pub fn displacement_output(&self, joint: &str) -> Result<ScalarOutput, Error> {
        Ok(ScalarOutput(
            self.resolve_displacement(&Data::of(self), joint)?,
        ))
    }

    /// [`Mechanism::displacement_output`] with the sketch from `data`.
    pub(crate) fn resolve_displacement<T: Datum>(
        &self,
        data: &Data<'_, T>,
        joint: &str,
    ) -> Result<Scalar<T>, Error> {
        match self.joints[self.output_joint(joint)?].kind {
            JointKind::Prismatic {
                guide,
                line,
                slider,
                point,
            } => Ok(Scalar::Displacement(constraints::compile_slide(
                data, guide, line, slider, point,
            ))),
            _ => Err(invalid(joint, "a displacement needs a prismatic joint")),
        }
    }

    /// Displacement of point `point` of link `point_link` along the line `line` (`from → to`)
    /// of link `line_link` (m), measured from `from`: `(p − a)·u` with `u` the line's unit direction,
    /// which turns with its link (a slider's travel along its guide, read without a square
    /// root or a division per position).
    ///
    /// ```
    /// use mechdiff_core::geometry::{Drive, Mechanism, Solver};
    /// let m = Mechanism::builder()
    ///     .point("O", [0.0, 0.0]).point("A", [2.0, 0.0]).point("X", [0.0, 1.0])
    ///     .ground(["O", "X"]).link("crank", ["O", "A"])
    ///     .revolute("O", "ground", "crank", "O")
    ///     .drive(Drive::angle("O"))
    ///     .build().unwrap();
    /// let height = m.slide_output("ground", ["O", "X"], "crank", "A").unwrap();
    /// let mut t = Solver::default().track(&m).unwrap();
    /// t.move_to(0.5).unwrap();
    /// assert!((t.kinematics::<1>().unwrap().value(&height).value - 2.0 * 0.5f64.sin()).abs() < 1e-15);
    /// ```
    pub fn slide_output(
        &self,
        line_link: &str,
        line: [&str; 2],
        point_link: &str,
        point: &str,
    ) -> Result<ScalarOutput, Error> {
        let data = Data::of(self);
        Ok(ScalarOutput(self.resolve_slide(
            &data, line_link, line, point_link, point,
        )?))
    }

    /// [`Mechanism::slide_output`] with the sketch from `data`.
    pub(crate) fn resolve_slide<T: Datum>(
        &self,
        data: &Data<'_, T>,
        line_link: &str,
        [from, to]: [&str; 2],
        point_link: &str,
        point: &str,
    ) -> Result<Scalar<T>, Error> {
        let (guide, slider) = (self.output_link(line_link)?, self.output_link(point_link)?);
        let (a, b) = (
            self.output_point_on(guide, from)?,
            self.output_point_on(guide, to)?,
        );
        if self.points[a].sketch == self.points[b].sketch {
            return Err(invalid(
                &format!("{from}–{to}"),
                "the two points coincide; the direction is undefined",
            ));
        }
        let p = self.output_point_on(slider, point)?;
        Ok(Scalar::Displacement(constraints::compile_slide(
            data,
            guide,
            [a, b],
            slider,
            p,
        )))
    }

    /// Relative rotation of link b with respect to link a in revolute joint `joint` since
    /// the sketch (rad).
    pub fn joint_rotation_output(&self, joint: &str) -> Result<ScalarOutput, Error> {
        Ok(ScalarOutput(self.resolve_joint_rotation(joint)?))
    }

    /// [`Mechanism::joint_rotation_output`], for data in any `T` (it has none).
    pub(crate) fn resolve_joint_rotation<T>(&self, joint: &str) -> Result<Scalar<T>, Error> {
        match self.joints[self.output_joint(joint)?].kind {
            JointKind::Revolute { link_a, link_b, .. } => Ok(Scalar::Relative {
                a: constraints::body(link_a),
                b: constraints::body(link_b),
            }),
            _ => Err(invalid(joint, "a joint rotation needs a revolute joint")),
        }
    }

    /// The body of link `link` (for a rotation output).
    pub(crate) fn output_body(&self, link: &str) -> Result<Body, Error> {
        Ok(constraints::body(self.output_link(link)?))
    }
}
