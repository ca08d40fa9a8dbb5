//! The scalar the compiled data of a mechanism is in, and how evaluation numbers take it in.
//!
//! The solver compiles a mechanism's link-local data (points, line directions, offsets, a
//! radius or ratio, φ₀) in `f64` and evaluates the equations in `f64` or in dual numbers over
//! `f64` (the φ-derivatives). The exact parameter sensitivities ([`super::parametric`])
//! compile the same data in [`Dual64`], its ε part the derivative with respect to one
//! parameter, and evaluate in dual numbers over `Dual64`. One generic implementation serves
//! both: the data scalar `T` is a [`Datum`], the evaluation scalar `D` [`Absorb`]s it. With
//! `T = f64` the operations are the very ones the solver always used (`D · f64`, `D − f64`),
//! monomorphised, so its hot path is unchanged.

use super::model::{JointKind, Mechanism};
use num_dual::{Dual64, DualNum};

/// A scalar the link-local data is compiled in: `f64`, or [`Dual64`] for data carrying its
/// derivative with respect to one parameter.
pub(crate) trait Datum: crate::Scalar {
    /// `√(x² + y²)`; for `f64` exactly [`f64::hypot`], the solver's rounding.
    fn length(x: Self, y: Self) -> Self;
    /// `atan2(y, x)`; for `f64` exactly [`f64::atan2`].
    fn direction(y: Self, x: Self) -> Self;
}

impl Datum for f64 {
    #[inline]
    fn length(x: f64, y: f64) -> f64 {
        x.hypot(y)
    }

    #[inline]
    fn direction(y: f64, x: f64) -> f64 {
        y.atan2(x)
    }
}

impl Datum for Dual64 {
    /// The value is `f64::hypot`'s (so it matches the solver's data bit for bit), the
    /// derivative `(x x′ + y y′)/r`.
    fn length(x: Dual64, y: Dual64) -> Dual64 {
        let r = x.re.hypot(y.re);
        Dual64::new(r, (x.re * x.eps + y.re * y.eps) / r)
    }

    /// The value is `f64::atan2`'s, the derivative `(x y′ − y x′)/(x² + y²)`.
    fn direction(y: Dual64, x: Dual64) -> Dual64 {
        let r2 = x.re * x.re + y.re * y.re;
        Dual64::new(y.re.atan2(x.re), (x.re * y.eps - y.re * x.eps) / r2)
    }
}

/// An evaluation scalar that can take in data of type `T`: multiply by it, subtract it, or
/// become it. `D · f64` for every dual number over `f64` (what the solver does), `D · Dual64`
/// (num-dual's `scale`: every part times the datum) for every dual number over `Dual64`.
pub(crate) trait Absorb<T>: crate::Scalar {
    /// The datum as an evaluation number (no derivative parts of its own).
    fn datum(t: T) -> Self;
    /// `self · t`.
    fn times(self, t: T) -> Self;
    /// `self − t`.
    fn minus(self, t: T) -> Self;
    /// `self + t`.
    fn plus(self, t: T) -> Self;
}

impl<D: crate::Scalar> Absorb<f64> for D {
    #[inline]
    fn datum(t: f64) -> D {
        D::from(t)
    }

    #[inline]
    fn times(self, t: f64) -> D {
        self * t
    }

    #[inline]
    fn minus(self, t: f64) -> D {
        self - t
    }

    #[inline]
    fn plus(self, t: f64) -> D {
        self + t
    }
}

impl<D: crate::Scalar + DualNum<InnerDual = Dual64>> Absorb<Dual64> for D {
    #[inline]
    fn datum(t: Dual64) -> D {
        D::from_re(t)
    }

    #[inline]
    fn times(self, t: Dual64) -> D {
        self.scale(&t)
    }

    #[inline]
    fn minus(self, t: Dual64) -> D {
        self - D::from_re(t)
    }

    #[inline]
    fn plus(self, t: Dual64) -> D {
        self + D::from_re(t)
    }
}

/// The numbers a mechanism's equations are compiled from, in the datum scalar `T`: every
/// point's sketch position, each joint's number (a rack and pinion's radius, a gear's ratio,
/// 0 otherwise) and the drive's value at the sketch.
#[derive(Debug, Clone)]
pub(crate) struct Data<'m, T> {
    /// The model (its topology: links, joints, drive).
    pub m: &'m Mechanism,
    /// Sketch position of every point, in point order (m).
    pub points: Vec<[T; 2]>,
    /// Each joint's number, in joint order.
    pub numbers: Vec<T>,
    /// φ at the sketch (rad or m).
    pub drive_at_sketch: T,
}

/// A joint's number (radius or ratio), 0 for a joint without one.
pub(crate) fn joint_number(kind: &JointKind) -> f64 {
    match *kind {
        JointKind::RackPinion { radius, .. } => radius,
        JointKind::Gear { ratio, .. } => ratio,
        _ => 0.0,
    }
}

impl<'m> Data<'m, f64> {
    /// The model's own numbers.
    pub fn of(m: &'m Mechanism) -> Self {
        Data {
            m,
            points: m.points.iter().map(|p| p.sketch).collect(),
            numbers: m.joints.iter().map(|j| joint_number(&j.kind)).collect(),
            drive_at_sketch: m.drive_at_sketch,
        }
    }
}

impl<T: Datum> Data<'_, T> {
    /// Sketch position of point `i`.
    #[inline]
    pub fn point(&self, i: usize) -> [T; 2] {
        self.points[i]
    }

    /// Sketch position of link `link`'s reference point (its first point; the origin for
    /// the ground): see [`Mechanism::reference_sketch`].
    pub fn reference(&self, link: usize) -> [T; 2] {
        let zero = T::from(0.0);
        if link == 0 {
            return [zero, zero];
        }
        self.m.links[link]
            .points
            .first()
            .map_or([zero, zero], |&p| self.points[p])
    }

    /// Sketch position `at` in the frame of link `link`: see [`Mechanism::local`].
    pub fn local(&self, link: usize, at: [T; 2]) -> [T; 2] {
        let r = self.reference(link);
        [at[0] - r[0], at[1] - r[1]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `Dual64`'s length and direction have exactly the `f64` values (so the parametric data's
    /// values are the solver's bit for bit) and the derivatives of num-dual's chain rule
    /// through `crate::hypot` and `crate::atan2` (1e-15 relative: a few roundings).
    #[test]
    fn dual_length_and_direction_are_the_f64_values_with_exact_derivatives() {
        for (x, y) in [(3.0, 4.0), (-0.2, 1e-3), (1e-9, -2.0), (-5.0, -0.5)] {
            let (dx, dy) = (0.3, -0.7);
            let (xd, yd) = (Dual64::new(x, dx), Dual64::new(y, dy));
            let r = Dual64::length(xd, yd);
            assert_eq!(r.re, f64::hypot(x, y));
            let want = crate::hypot(xd, yd).eps;
            assert!(
                (r.eps - want).abs() <= 1e-15 * want.abs().max(1.0),
                "{x}, {y}"
            );
            let a = Dual64::direction(yd, xd);
            assert_eq!(a.re, y.atan2(x));
            let want = crate::atan2(yd, xd).eps;
            assert!(
                (a.eps - want).abs() <= 1e-15 * want.abs().max(1.0),
                "{x}, {y}"
            );
        }
    }
}
