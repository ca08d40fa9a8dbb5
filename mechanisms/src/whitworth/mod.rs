//! The Whitworth shaping machine: crank, slotted rocker, ram.
//!
//! # The figure in words
//!
//! The rocker pivot B0 is the origin; the crank pivot A0 sits a frame distance l0 above it, at
//! (0, l0). The crank (body 1, length l1 < l0) turns at constant speed; its angle φ is
//! measured so that the crank pin A is at the bottom, (0, l0 − l1), at φ = 0:
//!
//! - A = (l1 sin φ, l0 − l1 cos φ).
//!
//! A slides in the slot of the rocker (body 2), which turns about B0. The rocker angle ψ is
//! measured from +y towards +x. The ram (body 3) moves horizontally at height h; its pin C
//! slides in the rocker's slot too. The slider blocks at A and C are massless.
//!
//! # Loop-closure equations
//!
//! B0, A and C lie on the rocker's line (source eqs. 1.25–1.30, 1.37):
//!
//! - tan ψ = x_A / y_A = λ sin φ / (1 − λ cos φ), with λ = l1/l0, so ψ = atan2(x_A, y_A);
//! - x_C = h tan ψ = h x_A / y_A, y_C = h.
//!
//! The centres of gravity follow: S1 on the crank at l_S1 from A0,
//! S1 = (l_S1 sin φ, l0 − l_S1 cos φ); S2 on the rocker at l_S2 from B0,
//! S2 = l_S2 (sin ψ, cos ψ) = (l_S2 / |B0A|) A; S3 offset from C, S3 = (x_C − c_x, h + c_y).
//!
//! These equations are written once, generic over the scalar ([`Whitworth`]'s
//! [`PositionFunction`] impl); ψ′, ψ″, velocities, accelerations and inertial forces follow
//! by any [`mechdiff_core::method`]. The source's own formulas are kept in [`hand`] as the
//! baseline they are verified and benchmarked against.
//! [`symbolic`] has ψ and x_C differentiated at compile time by `#[derivatives]`
//! (straight-line generated code, the "symbolic" method of the tests and benchmarks).
//!
//! With l1 < l0 the rocker swings between ±asin λ; it stops (ψ′ = 0, a dead position) where
//! the crank is perpendicular to the slot, cos φ = λ.
//!
//! # Parameters
//!
//! | parameter | meaning | unit | reference value |
//! |---|---|---|---|
//! | l0 | frame distance A0B0 | m | 0.400 |
//! | l1 | crank length A0A | m | 0.150 |
//! | l_S1 | A0 to the crank's centre of gravity S1 | m | 0.040 |
//! | l_S2 | B0 to the rocker's centre of gravity S2 | m | 0.150 |
//! | h | height of the ram pin C above B0 | m | 0.650 |
//! | c_x, c_y | offset of the ram's centre of gravity S3 from C: S3 = C + (−c_x, c_y) | m | 0, 0 |
//! | m1, m2, m3 | masses of crank, rocker, ram | kg | 15, 30, 50 |
//! | ω | crank speed | rad/s | 10π/3 (100 rpm) |
//!
//! # Source of the reference values
//!
//! A worked exercise, "Task 1 Shaping Machine (Whitworth Mechanism)": inertial forces for
//! dimensioning the foundation of a shaping machine (project reference
//! `whitworth_000_source.md`, notes `whitworth_000.md`). It gives l0, l1 and n = 100 rpm;
//! l_S1, l_S2, h, m1, m2, m3 are not printed and were recovered uniquely from its published
//! tables. c_x and c_y enter no velocity, acceleration or force, and cannot be recovered: 0.

mod forces;
pub mod hand;
mod linkage;
pub mod symbolic;

pub use forces::{CentreAccelerations, InertialForces};

use crate::error::{Error, Result};
use mechdiff_core::{DeadPosition, DeadPositionSearch, DriveState, Point, PositionFunction};
use mechdiff_core::{Scalar, hypot};
use std::f64::consts::TAU;

/// The geometry, masses and crank speed of a Whitworth shaping machine (SI units; see the
/// [module](self) docs for the figure).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Parameters {
    /// Frame distance l0 between the crank pivot A0 and the rocker pivot B0 (m).
    pub l0: f64,
    /// Crank length l1 = A0A (m), shorter than l0.
    pub l1: f64,
    /// Distance l_S1 from A0 to the crank's centre of gravity S1 (m).
    pub l_s1: f64,
    /// Distance l_S2 from B0 to the rocker's centre of gravity S2 (m).
    pub l_s2: f64,
    /// Height h of the ram pin C above B0 (m).
    pub h: f64,
    /// Horizontal offset c_x of the ram's centre of gravity: x_S3 = x_C − c_x (m).
    pub c_x: f64,
    /// Vertical offset c_y of the ram's centre of gravity: y_S3 = h + c_y (m).
    pub c_y: f64,
    /// Crank mass m1 (kg).
    pub m1: f64,
    /// Rocker mass m2 (kg).
    pub m2: f64,
    /// Ram mass m3 (kg).
    pub m3: f64,
    /// Crank speed ω (rad/s), constant.
    pub crank_speed: f64,
}

impl Parameters {
    /// The reference machine of the source exercise (see [`Whitworth::reference`]).
    pub fn reference() -> Self {
        Self {
            l0: 0.400,
            l1: 0.150,
            l_s1: 0.040,
            l_s2: 0.150,
            h: 0.650,
            c_x: 0.0,
            c_y: 0.0,
            m1: 15.0,
            m2: 30.0,
            m3: 50.0,
            crank_speed: DriveState::from_rpm(100.0).omega,
        }
    }

    /// Every parameter in range, or the first one that is not.
    fn validate(&self) -> Result<()> {
        const LENGTH: &str = "a length must be positive";
        const MASS: &str = "a mass must be positive";
        let positive = [
            ("l0", self.l0, "m", LENGTH),
            ("l1", self.l1, "m", LENGTH),
            ("l_S1", self.l_s1, "m", LENGTH),
            ("l_S2", self.l_s2, "m", LENGTH),
            ("h", self.h, "m", LENGTH),
            ("m1", self.m1, "kg", MASS),
            ("m2", self.m2, "kg", MASS),
            ("m3", self.m3, "kg", MASS),
            (
                "ω",
                self.crank_speed,
                "rad/s",
                "the crank speed must be positive (the crank turns at constant speed)",
            ),
        ];
        for (name, value, unit, if_not_positive) in positive {
            let reason = if !value.is_finite() {
                "must be finite"
            } else if value <= 0.0 {
                if_not_positive
            } else {
                continue;
            };
            return Err(Error::InvalidParameter {
                name,
                value,
                unit,
                reason,
            });
        }
        for (name, value) in [("c_x", self.c_x), ("c_y", self.c_y)] {
            if !value.is_finite() {
                return Err(Error::InvalidParameter {
                    name,
                    value,
                    unit: "m",
                    reason: "must be finite",
                });
            }
        }
        if self.l1 >= self.l0 {
            return Err(Error::CrankNotShorterThanFrame {
                l1: self.l1,
                l0: self.l0,
            });
        }
        Ok(())
    }
}

/// A Whitworth shaping machine with validated parameters.
///
/// ```
/// use mechdiff_core::{PositionFunction, method::{Differentiator, Dual2}};
/// use mechdiff_mechanisms::Whitworth;
///
/// let shaper = Whitworth::reference();
/// // At φ = 0 the crank pin is at the bottom: ψ = 0, ψ′ = λ/(1 − λ) = 0.6.
/// let pose = Dual2.jets(&shaper, 0.0);
/// assert_eq!(pose.psi.value, 0.0);
/// assert!((pose.psi.d1() - 0.6).abs() < 1e-15);
/// // The shaking force on the frame at φ = 0: ΣF_y = 111.856 N (source table: 111.9 N).
/// let forces = shaper.inertial_forces(0.0, &shaper.drive())?;
/// assert!((forces.sum.y - 111.8555165456794).abs() < 1e-11);
/// # Ok::<(), mechdiff_mechanisms::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Whitworth {
    parameters: Parameters,
}

impl Whitworth {
    /// A machine with the given parameters, if every one is in range: lengths, masses and the
    /// crank speed finite and positive, offsets c_x, c_y finite, and the crank shorter than
    /// the frame (l1 < l0).
    ///
    /// ```
    /// use mechdiff_mechanisms::{Error, Whitworth, whitworth::Parameters};
    /// let long_crank = Parameters { l1: 0.5, ..Parameters::reference() };
    /// assert!(matches!(
    ///     Whitworth::new(long_crank),
    ///     Err(Error::CrankNotShorterThanFrame { .. })
    /// ));
    /// ```
    pub fn new(parameters: Parameters) -> Result<Self> {
        parameters.validate()?;
        Ok(Self { parameters })
    }

    /// The machine of the source exercise "Task 1 Shaping Machine (Whitworth Mechanism)"
    /// (reference `whitworth_000`): l0 = 0.400 m, l1 = 0.150 m, n = 100 rpm as printed;
    /// l_S1 = 0.040 m, l_S2 = 0.150 m, h = 0.650 m, m1 = 15 kg, m2 = 30 kg, m3 = 50 kg as
    /// recovered from its tables; c_x = c_y = 0.
    pub fn reference() -> Self {
        Self::new(Parameters::reference()).expect("the reference parameters are valid")
    }

    /// The parameters.
    pub fn parameters(&self) -> &Parameters {
        &self.parameters
    }

    /// The crank ratio λ = l1/l0, in (0, 1).
    pub fn lambda(&self) -> f64 {
        self.parameters.l1 / self.parameters.l0
    }

    /// The drive: the crank at its constant speed ω.
    pub fn drive(&self) -> DriveState {
        DriveState::constant_speed(self.parameters.crank_speed)
    }

    /// The rocker angle ψ(φ) alone, as a position function of its own: what the dead-position
    /// search and the ψ-only benchmarks evaluate.
    pub fn rocker(&self) -> RockerAngle {
        RockerAngle {
            l0: self.parameters.l0,
            l1: self.parameters.l1,
        }
    }

    /// Both dead positions of the rocker (ψ′ = 0), found numerically over one revolution, in
    /// increasing φ: at φ = acos λ the rocker is at its largest angle +asin λ (ψ″ < 0), at
    /// φ = 2π − acos λ at its smallest −asin λ.
    pub fn dead_positions(&self) -> Result<[DeadPosition; 2]> {
        let found = DeadPositionSearch::new(0.0..=TAU).find(&self.rocker(), |psi| *psi)?;
        <[DeadPosition; 2]>::try_from(found).map_err(|found| Error::DeadPositionCount {
            output: "the rocker angle ψ",
            expected: 2,
            found: found.len(),
        })
    }

    /// The ram's stroke |x_C(φ₁) − x_C(φ₂)| between the two dead positions (m).
    pub fn stroke(&self) -> Result<f64> {
        let [first, second] = self.dead_positions()?;
        Ok((self.evaluate(first.phi).c.x - self.evaluate(second.phi).c.x).abs())
    }
}

/// The positions of the Whitworth's links at one crank angle: the rocker angle, the slider
/// points and the centres of gravity, each of scalar type `T`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Pose<T> {
    /// Rocker angle ψ (rad), from +y towards +x.
    pub psi: T,
    /// Crank pin A (m), the slider in the rocker's slot.
    pub a: Point<T>,
    /// Ram pin C (m), at height h on the rocker's line.
    pub c: Point<T>,
    /// Centre of gravity S1 of the crank (m).
    pub s1: Point<T>,
    /// Centre of gravity S2 of the rocker (m).
    pub s2: Point<T>,
    /// Centre of gravity S3 of the ram (m).
    pub s3: Point<T>,
}

impl<T> Pose<T> {
    /// Applies `f` to every scalar: ψ, then A, C, S1, S2, S3 (x before y).
    pub fn map<U>(self, mut f: impl FnMut(T) -> U) -> Pose<U> {
        Pose {
            psi: f(self.psi),
            a: self.a.map(&mut f),
            c: self.c.map(&mut f),
            s1: self.s1.map(&mut f),
            s2: self.s2.map(&mut f),
            s3: self.s3.map(&mut f),
        }
    }
}

/// A point on the crank at distance `radius` from A0 = (0, l0), given sin φ and cos φ.
#[inline]
fn on_crank<D: Scalar>(l0: f64, radius: f64, (sin, cos): (D, D)) -> Point<D> {
    Point::new(sin * radius, -cos * radius + l0)
}

/// The angle from +y towards +x of the line from B0 (the origin) through `p`, for a point
/// above B0: tan ψ = x/y (1.30). The crank pin is always above B0 (y_A ≥ l0 − l1 > 0, since
/// `Whitworth::new` demands l1 < l0), so atan(x/y) is atan2(x, y) without its quadrant branch.
#[inline]
fn angle_from_vertical<D: Scalar>(p: Point<D>) -> D {
    (p.x / p.y).atan()
}

impl PositionFunction for Whitworth {
    type Output<T> = Pose<T>;

    fn evaluate<D: Scalar>(&self, phi: D) -> Pose<D> {
        let p = &self.parameters;
        let sin_cos = phi.sin_cos();
        let a = on_crank(p.l0, p.l1, sin_cos);
        // C on the line B0A at height h; S2 on it at distance l_S2 from B0.
        let x_c = a.x / a.y * p.h;
        let along_rocker = hypot(a.x, a.y).recip() * p.l_s2;
        Pose {
            psi: angle_from_vertical(a),
            a,
            c: Point::new(x_c, D::constant(p.h)),
            s1: on_crank(p.l0, p.l_s1, sin_cos),
            s2: Point::new(a.x * along_rocker, a.y * along_rocker),
            s3: Point::new(x_c - p.c_x, D::constant(p.h + p.c_y)),
        }
    }

    fn map<A, B>(pose: Pose<A>, f: impl FnMut(A) -> B) -> Pose<B> {
        pose.map(f)
    }
}

/// The Whitworth's rocker angle ψ(φ) alone, from the same equations as the full [`Pose`].
///
/// ```
/// use mechdiff_core::{method::{Differentiator, Dual2}, Jet};
/// use mechdiff_mechanisms::Whitworth;
/// let psi: Jet<2> = Dual2.jets(&Whitworth::reference().rocker(), std::f64::consts::PI);
/// assert!((psi.d1() + 0.375 / 1.375).abs() < 1e-15); // ψ′(π) = −λ/(1 + λ)
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RockerAngle {
    l0: f64,
    l1: f64,
}

impl PositionFunction for RockerAngle {
    type Output<T> = T;

    // Inlined into the caller's `Differentiator::jets`, as num-dual's own code is: compiled
    // as a function of its own, the call cost ~105 instructions per ψ (BENCHMARKS.md).
    #[inline]
    fn evaluate<D: Scalar>(&self, phi: D) -> D {
        angle_from_vertical(on_crank(self.l0, self.l1, phi.sin_cos()))
    }

    fn map<A, B>(psi: A, mut f: impl FnMut(A) -> B) -> B {
        f(psi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// At φ = 90° the geometry is simple: A = (l1, l0), tan ψ = λ, x_C = hλ = 0.24375 m
    /// (reference sweep, exact in decimal); to 1e-16 m, a few roundings.
    #[test]
    fn pose_at_quarter_turn_matches_the_figure() {
        let pose = Whitworth::reference().evaluate(std::f64::consts::FRAC_PI_2);
        assert!((pose.a.x - 0.15).abs() < 1e-16 && (pose.a.y - 0.4).abs() < 1e-16);
        assert!((pose.psi - 0.375f64.atan()).abs() < 1e-16);
        assert!((pose.c.x - 0.24375).abs() < 1e-16 && pose.c.y == 0.65);
        // S2 at l_S2 from B0 along the slot.
        assert!((pose.s2.x.hypot(pose.s2.y) - 0.15).abs() < 1e-16);
    }
}
