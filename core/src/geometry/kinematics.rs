//! The pose and its exact derivatives at one drive position, and the outputs read from it.

use super::constraints::Body;
use super::datum::Absorb;
use super::model::Mechanism;
use super::output::{PointOutput, Scalar, ScalarOutput};
use crate::{Error, Jet};
use num_dual::Dual3_64;

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

    /// The mechanism the pose belongs to.
    pub(crate) fn mechanism(&self) -> &'m Mechanism {
        self.mechanism
    }

    /// Coordinate `i` as a third-order dual number (derivatives above `N` are zero).
    fn dual(&self, i: usize) -> Dual3_64 {
        let j = &self.coordinates[i];
        let d = |k: usize| j.derivatives.get(k).copied().unwrap_or(0.0);
        Dual3_64::new(j.value, d(0), d(1), d(2))
    }

    /// Position `[x, y]` of a resolved point (m): see [`Mechanism::point_output`].
    pub fn position(&self, point: &PointOutput) -> [Jet<N>; 2] {
        position(|i| self.dual(i), point).map(jet)
    }

    /// Value of a resolved angle or displacement (rad or m): see
    /// [`Mechanism::rotation_output`].
    pub fn value(&self, output: &ScalarOutput) -> Jet<N> {
        jet(value(|i| self.dual(i), output))
    }

    /// Position `[x, y]` of point `point` carried by link `link` (m). In a loop over drive
    /// positions, resolve the point once with [`Mechanism::point_output`] and read it with
    /// [`Kinematics::position`] instead.
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
        Ok(self.position(&self.mechanism.point_output(link, point)?))
    }

    /// Position of the point of link `link` that is at `sketch` (global, m) in the sketch.
    pub fn point_at(&self, link: &str, sketch: [f64; 2]) -> Result<[Jet<N>; 2], Error> {
        Ok(self.position(&self.mechanism.point_at_output(link, sketch)?))
    }

    /// Position of link `link`'s centre of gravity (its [`super::Inertia`] must be given).
    pub fn center_of_gravity(&self, link: &str) -> Result<[Jet<N>; 2], Error> {
        Ok(self.position(&self.mechanism.center_of_gravity_output(link)?))
    }

    /// Rotation of link `link` since the sketch pose (rad). In a loop, resolve it once with
    /// [`Mechanism::rotation_output`] and read it with [`Kinematics::value`].
    pub fn rotation(&self, link: &str) -> Result<Jet<N>, Error> {
        Ok(self.value(&self.mechanism.rotation_output(link)?))
    }

    /// Direction angle of the segment `from → to` (two points of link `link`), measured
    /// counter-clockwise from +x (rad; continuous from the sketch value, not wrapped).
    pub fn angle(&self, link: &str, from: &str, to: &str) -> Result<Jet<N>, Error> {
        Ok(self.value(&self.mechanism.angle_output(link, from, to)?))
    }

    /// Displacement in prismatic joint `joint` (m), measured as in the model.
    pub fn displacement(&self, joint: &str) -> Result<Jet<N>, Error> {
        Ok(self.value(&self.mechanism.displacement_output(joint)?))
    }

    /// Relative rotation of link b with respect to link a in revolute joint `joint` since the
    /// sketch (rad).
    pub fn joint_rotation(&self, joint: &str) -> Result<Jet<N>, Error> {
        Ok(self.value(&self.mechanism.joint_rotation_output(joint)?))
    }
}

/// The first `N` derivatives of `x`.
#[inline]
pub(crate) fn jet<const N: usize>(x: Dual3_64) -> Jet<N> {
    let d = [x.v1, x.v2, x.v3];
    Jet::new(x.re, std::array::from_fn(|k| d[k]))
}

/// `A(θ_b)·v` for a link-local vector `v` (data in `T`), `(sin θ_k, cos θ_k)` of body `k`
/// being `frame(k)`.
#[inline(always)]
fn rotate<T: Copy, D: Absorb<T>>(frame: &impl Fn(usize) -> (D, D), b: Body, v: [T; 2]) -> [D; 2] {
    match b {
        None => [D::datum(v[0]), D::datum(v[1])],
        Some(k) => {
            let (s, c) = frame(k);
            [c.times(v[0]) - s.times(v[1]), s.times(v[0]) + c.times(v[1])]
        }
    }
}

/// `(sin θ_k, cos θ_k)` of body `k` from its angle, coordinate `3k + 2` of the pose.
#[inline]
fn sin_cos_of<D: crate::Scalar>(coordinate: &impl Fn(usize) -> D) -> impl Fn(usize) -> (D, D) {
    move |k| coordinate(3 * k + 2).sin_cos()
}

/// Position of the point of body `b` at link-local `p`.
#[inline]
pub(crate) fn place<T: Copy, D: Absorb<T>>(
    coordinate: &impl Fn(usize) -> D,
    b: Body,
    p: [T; 2],
) -> [D; 2] {
    place_with(coordinate, &sin_cos_of(coordinate), b, p)
}

/// [`place`] with the bodies' `(sin θ, cos θ)` given by `frame(k)`.
#[inline(always)]
pub(crate) fn place_with<T: Copy, D: Absorb<T>>(
    coordinate: &impl Fn(usize) -> D,
    frame: &impl Fn(usize) -> (D, D),
    b: Body,
    p: [T; 2],
) -> [D; 2] {
    let r = rotate(frame, b, p);
    match b {
        None => r,
        Some(k) => [coordinate(3 * k) + r[0], coordinate(3 * k + 1) + r[1]],
    }
}

#[inline]
fn rotation_of<D: crate::Scalar>(coordinate: &impl Fn(usize) -> D, b: Body) -> D {
    b.map_or(D::from(0.0), |k| coordinate(3 * k + 2))
}

/// A resolved point of the pose whose coordinate `i` (with derivatives) is `coordinate(i)`.
#[inline]
pub(crate) fn position<D: crate::Scalar>(
    coordinate: impl Fn(usize) -> D,
    point: &PointOutput,
) -> [D; 2] {
    place(&coordinate, point.body, point.local)
}

/// A resolved angle or displacement of the pose whose coordinate `i` (with derivatives) is
/// `coordinate(i)`.
#[inline]
pub(crate) fn value<D: crate::Scalar>(coordinate: impl Fn(usize) -> D, output: &ScalarOutput) -> D {
    scalar(coordinate, &output.0)
}

/// [`value`] for a resolved output whose data is in `T`.
#[inline]
pub(crate) fn scalar<T: Copy, D: Absorb<T>>(
    coordinate: impl Fn(usize) -> D,
    output: &Scalar<T>,
) -> D {
    let frame = sin_cos_of(&coordinate);
    scalar_with(&coordinate, &frame, output)
}

/// [`scalar`] with the bodies' `(sin θ, cos θ)` given by `frame(k)`.
#[inline(always)]
pub(crate) fn scalar_with<T: Copy, D: Absorb<T>>(
    coordinate: &impl Fn(usize) -> D,
    frame: &impl Fn(usize) -> (D, D),
    output: &Scalar<T>,
) -> D {
    match *output {
        Scalar::Rotation { body, offset } => rotation_of(coordinate, body).plus(offset),
        Scalar::Relative { a, b } => rotation_of(coordinate, b) - rotation_of(coordinate, a),
        Scalar::Displacement(slide) => {
            let u = rotate(frame, slide.line.body, slide.line.direction);
            let a = place_with(coordinate, frame, slide.line.body, slide.line.origin);
            let r = place_with(coordinate, frame, slide.slider, slide.point);
            u[0] * (r[0] - a[0]) + u[1] * (r[1] - a[1])
        }
    }
}

impl PointOutput {
    /// The point's position `[x, y]` in the pose `q` (`(x, y, θ)` per moving link) in any
    /// scalar: e.g. a pose from [`super::Tracker::closed_form_pose`].
    pub fn position_in<D: crate::Scalar>(&self, q: &[D]) -> [D; 2] {
        position(|i| q[i], self)
    }
}

impl ScalarOutput {
    /// The angle or displacement in the pose `q` (`(x, y, θ)` per moving link) in any
    /// scalar: e.g. a pose from [`super::Tracker::closed_form_pose`].
    pub fn value_in<D: crate::Scalar>(&self, q: &[D]) -> D {
        value(|i| q[i], self)
    }
}
