//! Exact derivatives of the pose with respect to one parameter p of the mechanism's data.
//!
//! A parameter (a link length, a pivot coordinate, a rack's radius, the drive's sketch value)
//! moves some of the mechanism's numbers; their derivatives with respect to it are a
//! [`DataTangent`]. [`Parametric`] compiles the equations Φ(q, φ; data) once with every datum
//! a [`Dual64`] (value and d/dp), and lifts a pose found by any solver (closed forms or
//! Newton) to the exact total derivatives d/dp of q, q′, q″, q‴ at the same drive position φ.
//!
//! # What is exact, and how
//!
//! Along the solution Φ(q(φ, p), φ; p) = 0 for every φ and p. Differentiating k times in φ
//! gives `Φ_q q⁽ᵏ⁾ + R_k = 0` (see [`super::implicit`]); differentiating that in p gives
//!
//! `Φ_q · ∂q⁽ᵏ⁾/∂p = −∂/∂p [Φ_q q⁽ᵏ⁾ + R_k]`, the right side at fixed `∂q⁽ᵏ⁾/∂p = 0`.
//!
//! So each order costs one evaluation of Φ in `Dual3<Dual64>` numbers: the outer `Dual3`
//! carries q, q′, q″, q‴ (the φ-derivatives, all known), the inner `Dual64` their d/dp,
//! known for the orders below k and set to 0 for order k; the ε part of the output's order-k
//! part is the right side. One back-substitution with the LU of the `f64` Φ_q (the same
//! matrix for every order) gives ∂q⁽ᵏ⁾/∂p. No step is a difference quotient: every number
//! is exact up to the rounding of `f64` arithmetic, the same as the solver's own q′, q″, q‴.
//!
//! The drive row `θ_b − θ_a − (φ − φ₀(p))` brings in φ₀'s tangent
//! ([`DataTangent::drive_at_sketch`]); a rack and pinion's radius and a gear's ratio enter
//! their rows ([`DataTangent::joints`]); the points' sketch positions enter every link-local
//! datum (positions relative to the link's reference point, unit line directions, offsets).
//! [`Parametric::jacobian`] gives Φ_q with its total d/dp (through q(p) and the data) for the
//! dynamics; [`Parametric::point_output`] and the other outputs read positions, angles and
//! displacements with their d/dp.
//!
//! ```
//! use mechdiff_core::geometry::{DataTangent, Drive, Mechanism, Parametric, Solver};
//! // A crank of length p = 2 (point A at (p, 0)): the tip's y = p sin φ, ∂y/∂p = sin φ.
//! let m = Mechanism::builder()
//!     .point("O", [0.0, 0.0]).point("A", [2.0, 0.0])
//!     .ground(["O"]).link("crank", ["O", "A"])
//!     .revolute("O", "ground", "crank", "O")
//!     .drive(Drive::angle("O"))
//!     .build().unwrap();
//! let mut tangent = DataTangent::zero(&m);
//! tangent.points[1] = [1.0, 0.0]; // dA/dp
//! let exact = Parametric::new(&m, &tangent).unwrap();
//! let mut t = Solver::default().track(&m).unwrap();
//! t.move_to(0.5).unwrap();
//! let pose = exact.pose(&t.kinematics::<2>().unwrap()).unwrap();
//! let [_, y] = exact.point_output("crank", "A").unwrap().position(&pose);
//! assert!((y.re.eps - 0.5f64.sin()).abs() < 1e-15); // ∂y/∂p
//! assert!((y.v1.eps - 0.5f64.cos()).abs() < 1e-15); // ∂y′/∂p
//! ```

use super::constraints::{self, Body, Equations, Frames, with_frames};
use super::datum::{Data, joint_number};
use super::kinematics::{self, Kinematics};
use super::length::LoopLengths;
use super::mobility;
use super::model::{Inertia, JointKind, Mechanism};
use super::output::Scalar;
use super::solver::Solver;
use crate::Error;
use nalgebra::{DMatrix, DVector};
use num_dual::{Dual, Dual3, Dual64, DualNum};

/// The derivative with respect to one parameter p of every number of a Mechanism.
#[derive(Debug, Clone, PartialEq)]
pub struct DataTangent {
    /// d(sketch)/dp of every point, in the mechanism's point order (the order the builder got
    /// them).
    pub points: Vec<[f64; 2]>,
    /// d/dp of each joint's number, in joint order: a rack and pinion's radius, a gear's
    /// ratio; 0 otherwise (a nonzero entry for a joint without a number is an error).
    pub joints: Vec<f64>,
    /// d/dp of the drive's value at the sketch pose ([`Mechanism::drive_at_sketch`], whether
    /// given by `Drive::at_sketch` or implied by the sketch).
    pub drive_at_sketch: f64,
    /// d/dp of each link's inertia (mass, center, moment, fields as in [`Inertia`]), in link
    /// order (index 0 = ground); `None` for a link without inertia (and only for one).
    pub inertias: Vec<Option<Inertia>>,
}

impl DataTangent {
    /// The tangent of a parameter that moves nothing: every entry 0, shaped for `m`.
    pub fn zero(m: &Mechanism) -> Self {
        let zero = Inertia {
            mass: 0.0,
            center: [0.0, 0.0],
            moment: 0.0,
        };
        DataTangent {
            points: vec![[0.0, 0.0]; m.points.len()],
            joints: vec![0.0; m.joints.len()],
            drive_at_sketch: 0.0,
            inertias: m.links.iter().map(|l| l.inertia.map(|_| zero)).collect(),
        }
    }

    /// d/dp of the drive value the sketch implies: 0 for an angle drive, the sketch
    /// displacement `u·(r_point − r_line0)` of a displacement drive. This is the
    /// [`DataTangent::drive_at_sketch`] of a model whose [`Drive`](super::Drive) has no
    /// `at_sketch` (the value is then implied by the points); errors as [`Parametric::new`].
    ///
    /// ```
    /// use mechdiff_core::geometry::{DataTangent, Drive, Mechanism};
    /// // A slider at B = (p, 0) on the x axis, driven by its displacement (p at the sketch).
    /// let m = Mechanism::builder()
    ///     .point("O", [0.0, 0.0]).point("X", [1.0, 0.0]).point("B", [0.3, 0.0])
    ///     .ground(["O", "X"]).link("slider", ["B"])
    ///     .prismatic("guide", "ground", ["O", "X"], "slider", "B")
    ///     .drive(Drive::displacement("guide"))
    ///     .build().unwrap();
    /// let mut tangent = DataTangent::zero(&m);
    /// tangent.points[2] = [1.0, 0.0];
    /// assert_eq!(tangent.implied_drive_at_sketch(&m).unwrap(), 1.0);
    /// ```
    pub fn implied_drive_at_sketch(&self, m: &Mechanism) -> Result<f64, Error> {
        self.check(m)?;
        Ok(constraints::sketch_drive_value(&self.data(m)).eps)
    }

    /// `m`'s numbers with this tangent as their ε parts (the shape checked).
    fn data<'m>(&self, m: &'m Mechanism) -> Data<'m, Dual64> {
        Data {
            m,
            points: (m.points.iter().zip(&self.points))
                .map(|(p, d)| [0, 1].map(|i| Dual64::new(p.sketch[i], d[i])))
                .collect(),
            numbers: (m.joints.iter().zip(&self.joints))
                .map(|(j, &d)| Dual64::new(joint_number(&j.kind), d))
                .collect(),
            drive_at_sketch: Dual64::new(m.drive_at_sketch, self.drive_at_sketch),
        }
    }

    /// Checks the shape (and finiteness) of the tangent against `m`.
    fn check(&self, m: &Mechanism) -> Result<(), Error> {
        let mismatch = |what: &str, problem: String| Error::ParametricMismatch {
            what: format!("the data tangent's {what}"),
            problem,
        };
        let count = |what: &str, got: usize, expected: usize, of: &str| {
            if got == expected {
                Ok(())
            } else {
                Err(mismatch(
                    what,
                    format!("{got} given, the mechanism has {expected} {of} (one entry each)"),
                ))
            }
        };
        count("points", self.points.len(), m.points.len(), "points")?;
        count("joints", self.joints.len(), m.joints.len(), "joints")?;
        count("inertias", self.inertias.len(), m.links.len(), "links")?;
        let not_finite = |what: String, value: f64| Error::InvalidValue {
            what: format!("d/dp of {what} (the data tangent)"),
            value,
        };
        for (p, d) in m.points.iter().zip(&self.points) {
            if let Some(&v) = d.iter().find(|v| !v.is_finite()) {
                return Err(not_finite(format!("point `{}`", p.name), v));
            }
        }
        for (j, &d) in m.joints.iter().zip(&self.joints) {
            if !d.is_finite() {
                return Err(not_finite(format!("joint `{}`", j.name), d));
            }
            let has_number = matches!(
                j.kind,
                JointKind::RackPinion { .. } | JointKind::Gear { .. }
            );
            if d != 0.0 && !has_number {
                return Err(mismatch(
                    "joints",
                    format!(
                        "joint `{}` is {} and has no number (only a rack and pinion's radius \
                         and a gear's ratio have one); its entry must be 0, got {d}",
                        j.name,
                        j.kind.kind_name()
                    ),
                ));
            }
        }
        if !self.drive_at_sketch.is_finite() {
            return Err(not_finite(
                "the drive's sketch value".to_owned(),
                self.drive_at_sketch,
            ));
        }
        for (l, d) in m.links.iter().zip(&self.inertias) {
            match (l.inertia, d) {
                (Some(_), Some(d)) => {
                    let values = [d.mass, d.center[0], d.center[1], d.moment];
                    if let Some(&v) = values.iter().find(|v| !v.is_finite()) {
                        return Err(not_finite(format!("the inertia of link `{}`", l.name), v));
                    }
                }
                (None, None) => {}
                (has, _) => {
                    let (has, give) = if has.is_some() {
                        ("has", "Some (zero if p does not move it)")
                    } else {
                        ("has no", "None")
                    };
                    return Err(mismatch(
                        "inertias",
                        format!("link `{}` {has} inertia: its entry must be {give}", l.name),
                    ));
                }
            }
        }
        Ok(())
    }
}

/// Pose coordinates (x, y, θ per moving link): `re`, `v1`, `v2`, `v3` = q, q′, q″, q‴ (the
/// φ-derivatives, zero above the order asked), each a [`Dual64`] whose `eps` part is its
/// exact total derivative d/dp at fixed φ.
pub type PoseTangent = Vec<Dual3<Dual64>>;

/// A mechanism's equations compiled with its data and the data's derivative with respect to
/// one parameter: lifts poses to their exact d/dp (see the [module](self) documentation).
#[derive(Debug, Clone)]
pub struct Parametric<'m> {
    mechanism: &'m Mechanism,
    tangent: DataTangent,
    /// Every point, joint number and φ₀ with its d/dp.
    data: Data<'m, Dual64>,
    /// Φ compiled from `data`.
    equations: Equations<Dual64>,
    /// Φ compiled in `f64`, for Φ_q (the solver's own equations).
    plain: Equations,
    /// The loops' length scales, scaling angular rows and columns for the condition
    /// estimate (see `length`).
    lengths: LoopLengths,
}

/// The `k`-th φ-derivative part of `x` (0 = the value).
fn part(x: &mut Dual3<Dual64>, k: usize) -> &mut Dual64 {
    match k {
        0 => &mut x.re,
        1 => &mut x.v1,
        2 => &mut x.v2,
        _ => &mut x.v3,
    }
}

impl<'m> Parametric<'m> {
    /// Compiles `m`'s equations with the data's derivative `tangent`. Errors
    /// ([`Error::ParametricMismatch`], [`Error::InvalidValue`]) when the tangent's lengths do
    /// not match the mechanism, an entry is not finite, or it gives a number to a joint
    /// without one.
    pub fn new(m: &'m Mechanism, tangent: &DataTangent) -> Result<Self, Error> {
        tangent.check(m)?;
        let data = tangent.data(m);
        Ok(Parametric {
            mechanism: m,
            tangent: tangent.clone(),
            equations: constraints::compile(&data),
            data,
            lengths: LoopLengths::of(m, &Equations::new(m)),
            plain: Equations::new(m),
        })
    }

    /// The mechanism.
    pub fn mechanism(&self) -> &'m Mechanism {
        self.mechanism
    }

    /// The data's derivative with respect to the parameter.
    pub fn tangent(&self) -> &DataTangent {
        &self.tangent
    }

    /// At the pose of `k` (from any solver; N = 1..=3): q..q^(N) and their exact d/dp, with
    /// one LU of Φ_q and N + 1 evaluations of Φ in `Dual3<Dual64>`.
    ///
    /// Errors: [`Error::Singular`] naming the drive position where Φ_q is singular (its
    /// scaled condition number above the default [`Solver::singular_threshold`]: the pose
    /// itself is a toggle, where d/dp is unbounded); [`Error::ParametricMismatch`] if `k` is
    /// a pose of another mechanism; [`Error::NonFinite`] if the pose is not finite.
    pub fn pose<const N: usize>(&self, k: &Kinematics<'m, N>) -> Result<PoseTangent, Error> {
        const {
            assert!(
                N >= 1 && N <= 3,
                "the pose is lifted with derivatives of order 1 to 3"
            )
        };
        let m = self.mechanism;
        let n = m.coordinate_count();
        if !(std::ptr::eq(k.mechanism(), m) || k.mechanism() == m) || k.coordinates.len() != n {
            return Err(Error::ParametricMismatch {
                what: "the pose".to_owned(),
                problem: "it was solved for another mechanism; solve this one's".to_owned(),
            });
        }
        let phi = k.phi;
        let finite = k
            .coordinates
            .iter()
            .all(|j| j.value.is_finite() && j.derivatives.iter().all(|d| d.is_finite()));
        if !(finite && phi.is_finite()) {
            return Err(Error::NonFinite {
                phi,
                quantity: "the pose given for its parameter derivatives",
            });
        }
        let q: Vec<f64> = k.coordinates.iter().map(|j| j.value).collect();
        let lu = self.factorise(&q, phi)?;
        let singular = || Error::Singular {
            phi,
            condition: f64::INFINITY,
            joints: self.joint_names(),
        };
        // q, q′, …, q^(N) known, their d/dp filled in order by order.
        let mut x: PoseTangent = (k.coordinates.iter())
            .map(|j| {
                let d = |i: usize| Dual64::from(j.derivatives.get(i).copied().unwrap_or(0.0));
                Dual3::new(Dual64::from(j.value), d(0), d(1), d(2))
            })
            .collect();
        let one = Dual64::from(1.0);
        let phi = Dual3::new(Dual64::from(phi), one, Dual64::from(0.0), Dual64::from(0.0));
        let mut out = vec![Dual3::from_re(Dual64::from(0.0)); n];
        let mut rhs = DVector::zeros(n);
        for order in 0..=N {
            with_frames(&x, |f| self.equations.evaluate_with(f, phi, &mut out));
            for (r, o) in rhs.iter_mut().zip(out.iter_mut()) {
                *r = -part(o, order).eps;
            }
            let tangent = lu.solve(&rhs).ok_or_else(singular)?;
            for (x, t) in x.iter_mut().zip(tangent.iter()) {
                part(x, order).eps = *t;
            }
        }
        Ok(x)
    }

    /// The LU of Φ_q at `q`, or [`Error::Singular`] if Φ_q (scaled as the solver scales it)
    /// is singular there.
    fn factorise(
        &self,
        q: &[f64],
        phi: f64,
    ) -> Result<nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>, Error> {
        let n = q.len();
        let mut jac = DMatrix::zeros(n, n);
        self.plain.jacobian(q, &mut jac);
        let mut scaled = jac.clone();
        mobility::scale(&self.plain, &mut scaled, &self.lengths);
        mobility::unit_columns(&mut scaled);
        let sigma = scaled
            .iter()
            .all(|x| x.is_finite())
            .then(|| scaled.try_svd(false, false, f64::EPSILON, super::branch::SVD_ITERATIONS))
            .flatten()
            .map(|svd| svd.singular_values);
        let condition = sigma.map_or(f64::INFINITY, |s| s.max() / s.min());
        // NaN (a failed SVD) counts as singular.
        if condition.is_nan() || condition > Solver::default().singular_threshold() {
            return Err(Error::Singular {
                phi,
                condition,
                joints: self.joint_names(),
            });
        }
        Ok(jac.lu())
    }

    fn joint_names(&self) -> Vec<String> {
        self.mechanism
            .joints
            .iter()
            .map(|j| j.name.clone())
            .collect()
    }

    /// Φ_q at the pose and its exact total derivative d/dp (through q(p) and the data), in
    /// `Dual64`: entry `(i, j)` is `∂Φ_i/∂q_j` with its d/dp in `eps`. The pose is one
    /// [`Parametric::pose`] gave (only its values `re` and their d/dp are used). One
    /// evaluation of Φ in `Dual<Dual64>` per column.
    ///
    /// # Panics
    ///
    /// If `pose` does not have one entry per coordinate (a pose of another mechanism): the
    /// poses [`Parametric::pose`] returns always have.
    pub fn jacobian(&self, pose: &[Dual3<Dual64>]) -> DMatrix<Dual64> {
        let n = pose.len();
        assert_eq!(
            n,
            self.plain.coordinates(),
            "Parametric::jacobian: a pose of {n} coordinates for a mechanism of {}",
            self.plain.coordinates()
        );
        let rows = self.plain.rows();
        let q: Vec<Dual64> = pose.iter().map(|x| x.re).collect();
        let frames: Vec<(Dual64, Dual64)> = (0..n / 3).map(|k| q[3 * k + 2].sin_cos()).collect();
        let zero = Dual64::from(0.0);
        let mut x: Vec<Dual<Dual64>> = q.iter().map(|&v| Dual::from_re(v)).collect();
        let mut fr: Vec<(Dual<Dual64>, Dual<Dual64>)> = frames
            .iter()
            .map(|&(s, c)| (Dual::from_re(s), Dual::from_re(c)))
            .collect();
        let mut out = vec![Dual::from_re(zero); rows];
        let mut jac = DMatrix::from_element(rows, n, zero);
        let phi = Dual::from_re(zero);
        for j in 0..n {
            // The direction e_j: q_j + ε, and for an angle its sine and cosine by the chain
            // rule.
            x[j].eps = Dual64::from(1.0);
            if j % 3 == 2 {
                let (s, c) = frames[j / 3];
                fr[j / 3] = (Dual::new(s, c), Dual::new(c, -s));
            }
            let f = Frames { q: &x, frames: &fr };
            self.equations.evaluate_with(&f, phi, &mut out);
            for (i, o) in out.iter().enumerate() {
                jac[(i, j)] = o.eps;
            }
            x[j].eps = zero;
            if j % 3 == 2 {
                let (s, c) = frames[j / 3];
                fr[j / 3] = (Dual::from_re(s), Dual::from_re(c));
            }
        }
        jac
    }

    /// A point of a link resolved once (as [`Mechanism::point_output`]): its link-local
    /// data with d/dp.
    pub fn point_output(&self, link: &str, point: &str) -> Result<ParametricPoint, Error> {
        let (body, local) = self.mechanism.resolve_point(&self.data, link, point)?;
        Ok(ParametricPoint { body, local })
    }

    /// Link `link`'s centre of gravity (as [`Mechanism::center_of_gravity_output`]), with the
    /// d/dp of its sketch position from [`DataTangent::inertias`].
    pub fn center_of_gravity_output(&self, link: &str) -> Result<ParametricPoint, Error> {
        let k = self
            .mechanism
            .link_index(link)
            .map_err(|_| Error::InvalidOutput {
                name: link.to_owned(),
                problem: "no link of this name".to_owned(),
            })?;
        let center = self.mechanism.output_center(k)?;
        let d = self.tangent.inertias[k].map_or([0.0, 0.0], |i| i.center);
        let at = [0, 1].map(|i| Dual64::new(center[i], d[i]));
        Ok(ParametricPoint {
            body: constraints::body(k),
            local: self.data.local(k, at),
        })
    }

    /// Rotation of link `link` since the sketch (as [`Mechanism::rotation_output`]).
    pub fn rotation_output(&self, link: &str) -> Result<ParametricScalar, Error> {
        let body = self.mechanism.output_body(link)?;
        Ok(ParametricScalar(Scalar::Rotation {
            body,
            offset: Dual64::from(0.0),
        }))
    }

    /// Direction angle of the segment `from → to` of link `link` (as
    /// [`Mechanism::angle_output`]), its sketch direction with d/dp.
    pub fn angle_output(
        &self,
        link: &str,
        from: &str,
        to: &str,
    ) -> Result<ParametricScalar, Error> {
        let s = self.mechanism.resolve_angle(&self.data, link, from, to)?;
        Ok(ParametricScalar(s))
    }

    /// Displacement in prismatic joint `joint` (as [`Mechanism::displacement_output`]).
    pub fn displacement_output(&self, joint: &str) -> Result<ParametricScalar, Error> {
        let s = self.mechanism.resolve_displacement(&self.data, joint)?;
        Ok(ParametricScalar(s))
    }

    /// Displacement of a point along a line of a link (as [`Mechanism::slide_output`]), the
    /// line's sketch with d/dp.
    pub fn slide_output(
        &self,
        line_link: &str,
        [from, to]: [&str; 2],
        point_link: &str,
        point: &str,
    ) -> Result<ParametricScalar, Error> {
        let s =
            (self.mechanism).resolve_slide(&self.data, line_link, [from, to], point_link, point)?;
        Ok(ParametricScalar(s))
    }

    /// Relative rotation in revolute joint `joint` (as
    /// [`Mechanism::joint_rotation_output`]).
    pub fn joint_rotation_output(&self, joint: &str) -> Result<ParametricScalar, Error> {
        Ok(ParametricScalar(
            self.mechanism.resolve_joint_rotation(joint)?,
        ))
    }
}

/// A point of a link resolved once, its link-local coordinates with their d/dp; read it with
/// [`ParametricPoint::position`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParametricPoint {
    pub(crate) body: Body,
    pub(crate) local: [Dual64; 2],
}

impl ParametricPoint {
    /// Link-local coordinates (m; relative to the link's reference point, as drawn), with
    /// their d/dp.
    pub fn local(&self) -> [Dual64; 2] {
        self.local
    }

    /// [x, y] with φ-derivatives and their d/dp, at a pose from [`Parametric::pose`].
    pub fn position(&self, pose: &[Dual3<Dual64>]) -> [Dual3<Dual64>; 2] {
        kinematics::place(&|i| pose[i], self.body, self.local)
    }
}

/// An angle or displacement resolved once, its data with d/dp; read it with
/// [`ParametricScalar::value`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParametricScalar(pub(crate) Scalar<Dual64>);

impl ParametricScalar {
    /// The value (rad or m) with φ-derivatives and their d/dp, at a pose from
    /// [`Parametric::pose`].
    pub fn value(&self, pose: &[Dual3<Dual64>]) -> Dual3<Dual64> {
        kinematics::scalar(|i| pose[i], &self.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Jet;
    use crate::geometry::Drive;
    use std::f64::consts::FRAC_PI_2;

    /// An isosceles slider-crank (crank = rod = 1) drawn at crank angle 0.5: at φ = π/2 the
    /// rod stands perpendicular to the guide over O, a branch point where Φ_q is singular.
    #[test]
    fn a_singular_pose_is_an_error_naming_the_drive_position() {
        let s = 0.5f64;
        let m = Mechanism::builder()
            .point("O", [0.0, 0.0])
            .point("A", [s.cos(), s.sin()])
            .point("B", [2.0 * s.cos(), 0.0])
            .point("X", [1.0, 0.0])
            .ground(["O", "X"])
            .link("crank", ["O", "A"])
            .link("rod", ["A", "B"])
            .link("slider", ["B"])
            .revolute("O", "ground", "crank", "O")
            .revolute("A", "crank", "rod", "A")
            .revolute("B", "rod", "slider", "B")
            .prismatic("guide", "ground", ["O", "X"], "slider", "B")
            .drive(Drive::angle("O").at_sketch(s))
            .build()
            .unwrap();
        let q = [
            0.0,
            0.0,
            FRAC_PI_2 - s,
            0.0,
            1.0,
            s - FRAC_PI_2,
            0.0,
            0.0,
            0.0,
        ];
        let jets = q.iter().map(|&v| Jet::new(v, [0.0])).collect();
        let k = Kinematics::<1>::new(&m, FRAC_PI_2, jets);
        let mut tangent = DataTangent::zero(&m);
        tangent.points[1] = [1.0, 0.0];
        let exact = Parametric::new(&m, &tangent).unwrap();
        match exact.pose(&k) {
            Err(Error::Singular { phi, condition, .. }) => {
                assert_eq!(phi, FRAC_PI_2);
                assert!(condition > 1e10, "{condition}");
            }
            other => panic!("expected a singular pose, got {other:?}"),
        }
        // Slightly away from it the same pose is regular (a check of the check).
        let q = [0.0, 0.0, 1.0 - s, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        let (a, b) = ([1f64.cos(), 1f64.sin()], 2.0 * 1f64.cos());
        let turn = (-a[1]).atan2(b - a[0]) - (-s.sin()).atan2(s.cos());
        let q = [q[0], q[1], q[2], a[0], a[1], turn, b, 0.0, 0.0];
        let jets = q.iter().map(|&v| Jet::new(v, [0.0])).collect();
        assert!(exact.pose(&Kinematics::<1>::new(&m, 1.0, jets)).is_ok());
    }
}
