//! The pose and its exact derivatives at one drive position, and the outputs read from it.

use super::constraints::{self, Body, Frames};
use super::model::{JointKind, Mechanism};
use crate::{Error, Jet};
use num_dual::{Dual3_64, DualNum};

/// The pose coordinates at drive position φ with their first `N` derivatives with respect to
/// φ (`N` ≤ 3), and the mechanism they belong to. Outputs are [`Jet`]s: turn them into
/// velocities and accelerations with [`Jet::motion`] and a [`crate::DriveState`].
#[derive(Debug, Clone)]
pub struct Kinematics<'m, const N: usize> {
    mechanism: &'m Mechanism,
    /// Drive position.
    pub phi: f64,
    /// `(x, y, θ)` per moving link, each with its derivatives.
    pub coordinates: Vec<Jet<N>>,
}

impl<'m, const N: usize> Kinematics<'m, N> {
    pub(crate) fn new(mechanism: &'m Mechanism, phi: f64, coordinates: Vec<Jet<N>>) -> Self {
        Kinematics {
            mechanism,
            phi,
            coordinates,
        }
    }

    /// The coordinates as third-order dual numbers (derivatives above `N` are zero).
    fn duals(&self) -> Vec<Dual3_64> {
        self.coordinates
            .iter()
            .map(|j| {
                let d = |k: usize| j.derivatives.get(k).copied().unwrap_or(0.0);
                Dual3_64::new(j.value, d(0), d(1), d(2))
            })
            .collect()
    }

    fn jet(x: Dual3_64) -> Jet<N> {
        let d = [x.v1, x.v2, x.v3];
        Jet::new(x.re, std::array::from_fn(|k| d[k]))
    }

    fn with_frames<T>(&self, f: impl FnOnce(&Frames<'_, Dual3_64>) -> T) -> T {
        let q = self.duals();
        let frames: Vec<_> = (0..q.len() / 3).map(|k| q[3 * k + 2].sin_cos()).collect();
        f(&Frames {
            q: &q,
            frames: &frames,
        })
    }

    fn link(&self, name: &str) -> Result<usize, Error> {
        self.mechanism
            .link_index(name)
            .map_err(|_| Error::InvalidOutput {
                name: name.to_owned(),
                problem: "no link of this name".to_owned(),
            })
    }

    fn point_on(&self, link: usize, point: &str) -> Result<[f64; 2], Error> {
        let m = self.mechanism;
        let p = m.point_index(point).map_err(|_| Error::InvalidOutput {
            name: point.to_owned(),
            problem: "no point of this name".to_owned(),
        })?;
        if !m.carries(link, p) {
            return Err(Error::InvalidOutput {
                name: point.to_owned(),
                problem: format!("point is not on link `{}`", m.links[link].name),
            });
        }
        Ok(m.points[p].sketch)
    }

    /// Position `[x, y]` of point `point` carried by link `link` (m).
    ///
    /// ```
    /// use mechdiff_core::geometry::{Drive, Mechanism, Solver};
    /// let m = Mechanism::builder()
    ///     .point("O", [0.0, 0.0]).point("A", [2.0, 0.0])
    ///     .ground(["O"]).link("crank", ["O", "A"])
    ///     .revolute("O", "ground", "crank", "O")
    ///     .drive(Drive::angle("O"))
    ///     .build().unwrap();
    /// let mut t = Solver::default().track(&m).unwrap();
    /// t.move_to(0.5).unwrap();
    /// let [x, y] = t.kinematics::<2>().unwrap().point("crank", "A").unwrap();
    /// assert!((x.value - 2.0 * 0.5f64.cos()).abs() < 1e-14);
    /// assert!((y.d1() - 2.0 * 0.5f64.cos()).abs() < 1e-14); // y′ = 2 cos φ
    /// assert!((x.d2() + 2.0 * 0.5f64.cos()).abs() < 1e-14); // x″ = −2 cos φ
    /// ```
    pub fn point(&self, link: &str, point: &str) -> Result<[Jet<N>; 2], Error> {
        let k = self.link(link)?;
        let at = self.point_on(k, point)?;
        Ok(self.point_at_index(k, at))
    }

    /// Position of the point of link `link` that is at `sketch` (global, m) in the sketch.
    pub fn point_at(&self, link: &str, sketch: [f64; 2]) -> Result<[Jet<N>; 2], Error> {
        Ok(self.point_at_index(self.link(link)?, sketch))
    }

    /// Position of link `link`'s centre of gravity (its [`super::Inertia`] must be given).
    pub fn center_of_gravity(&self, link: &str) -> Result<[Jet<N>; 2], Error> {
        let k = self.link(link)?;
        let inertia = self.mechanism.links[k]
            .inertia
            .ok_or_else(|| Error::InvalidOutput {
                name: link.to_owned(),
                problem: "the link has no mass properties".to_owned(),
            })?;
        Ok(self.point_at_index(k, inertia.center))
    }

    fn point_at_index(&self, k: usize, sketch: [f64; 2]) -> [Jet<N>; 2] {
        let local = self.mechanism.local(k, sketch);
        let r = self.with_frames(|f| f.point(constraints::body(k), local));
        [Self::jet(r[0]), Self::jet(r[1])]
    }

    /// Rotation of link `link` since the sketch pose (rad).
    pub fn rotation(&self, link: &str) -> Result<Jet<N>, Error> {
        let k = self.link(link)?;
        Ok(self.rotation_of(constraints::body(k)))
    }

    fn rotation_of(&self, b: Body) -> Jet<N> {
        b.map_or(Jet::from(0.0), |k| self.coordinates[3 * k + 2])
    }

    /// Direction angle of the segment `from → to` (two points of link `link`), measured
    /// counter-clockwise from +x (rad; continuous from the sketch value, not wrapped).
    pub fn angle(&self, link: &str, from: &str, to: &str) -> Result<Jet<N>, Error> {
        let k = self.link(link)?;
        let (a, b) = (self.point_on(k, from)?, self.point_on(k, to)?);
        if a == b {
            return Err(Error::InvalidOutput {
                name: format!("{from}–{to}"),
                problem: "the two points coincide; the direction is undefined".to_owned(),
            });
        }
        let mut jet = self.rotation_of(constraints::body(k));
        jet.value += (b[1] - a[1]).atan2(b[0] - a[0]);
        Ok(jet)
    }

    /// Displacement in prismatic joint `joint` (m), measured as in the model.
    pub fn displacement(&self, joint: &str) -> Result<Jet<N>, Error> {
        let m = self.mechanism;
        let j = m.joint_index(joint).map_err(|e| Error::InvalidOutput {
            name: joint.to_owned(),
            problem: e.to_string(),
        })?;
        match m.joints[j].kind {
            JointKind::Prismatic {
                guide,
                line,
                slider,
                point,
            } => {
                let slide = constraints::compile_slide(m, guide, line, slider, point);
                Ok(Self::jet(self.with_frames(|f| f.displacement(&slide))))
            }
            _ => Err(Error::InvalidOutput {
                name: joint.to_owned(),
                problem: "a displacement needs a prismatic joint".to_owned(),
            }),
        }
    }

    /// Relative rotation of link b with respect to link a in revolute joint `joint` since the
    /// sketch (rad).
    pub fn joint_rotation(&self, joint: &str) -> Result<Jet<N>, Error> {
        let m = self.mechanism;
        let j = m.joint_index(joint).map_err(|e| Error::InvalidOutput {
            name: joint.to_owned(),
            problem: e.to_string(),
        })?;
        match m.joints[j].kind {
            JointKind::Revolute { link_a, link_b, .. } => {
                let (a, b) = (
                    self.rotation_of(constraints::body(link_a)),
                    self.rotation_of(constraints::body(link_b)),
                );
                Ok(Jet::new(
                    b.value - a.value,
                    std::array::from_fn(|k| b.derivatives[k] - a.derivatives[k]),
                ))
            }
            _ => Err(Error::InvalidOutput {
                name: joint.to_owned(),
                problem: "a joint rotation needs a revolute joint".to_owned(),
            }),
        }
    }
}
