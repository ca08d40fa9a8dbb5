//! Motion laws: the normalised displacement f(u) of one segment, written once.
//!
//! A segment of cam angle β that moves the follower by a lift h (h < 0 for a return) gives
//! s(θ) = s₀ + h·f(u) with u = (θ − θ₀)/β ∈ [0, 1], f(0) = 0 and f(1) = 1 (a dwell has h = 0).
//! Each law is one function generic over the [`Scalar`], so its derivatives (s′ = h f′/β,
//! s″ = h f″/β², s‴ = h f‴/β³) come from dual numbers, never from formulas derived by hand.
//!
//! Piecewise laws (parabolic, modified trapezoidal, modified sine) say where their pieces
//! meet ([`MotionLaw::breaks`]); at a break the [`Side`] picks the piece, so one-sided
//! derivatives are exact too.
//!
//! | law | f(u) |
//! |---|---|
//! | dwell | 0 |
//! | uniform velocity | u |
//! | parabolic (uniform acceleration–retardation) | 2u² for u ≤ ½, 1 − 2(1 − u)² after |
//! | simple harmonic | (1 − cos πu)/2 |
//! | cycloidal | u − sin(2πu)/2π |
//! | 3-4-5 polynomial | 10u³ − 15u⁴ + 6u⁵ |
//! | 4-5-6-7 polynomial | 35u⁴ − 84u⁵ + 70u⁶ − 20u⁷ |
//! | modified trapezoidal | quarter sines of period ½ over the first and last eighth, constant acceleration ±8π/(2+π) over [⅛, ⅜] and [⅝, ⅞], a half cosine between |
//! | modified sine | quarter sines of period ½ over the first and last eighth, a cosine of period 3/2 over [⅛, ⅞] |
//!
//! The modified laws are integrated twice from their acceleration pieces (zero velocity and
//! displacement at u = 0, f(1) = 1); the constants, in closed form:
//!
//! - modified trapezoidal, C = 8π/(2 + π):
//!   f = (4πu − sin 4πu)/(2π(2+π)) on [0, ⅛];
//!   (32πu + π²(64u² − 16u + 1) − 8)/(16π(2+π)) on [⅛, ⅜];
//!   (4πu + π²(4u − 1) + sin 4πu)/(2π(2+π)) on [⅜, ⅝];
//!   (32πu + π²(−64u² + 112u − 33) + 8)/(16π(2+π)) on [⅝, ⅞];
//!   (2πu − ½ sin 4πu + π²)/(π(2+π)) on [⅞, 1].
//! - modified sine, C = 4π²/(π + 4):
//!   f = (πu − ¼ sin 4πu)/(π+4) on [0, ⅛];
//!   (πu − (9/4) sin(π(4u + 1)/3) + 2)/(π+4) on [⅛, ⅞];
//!   (πu − ¼ sin 4πu + 4)/(π+4) on [⅞, 1].

use std::f64::consts::PI;
use std::fmt;

use crate::scalar::Scalar;

/// Which piece to use exactly at a break between two pieces (or at a segment boundary):
/// the one that ends there (`Left`, the limit from below) or the one that starts there
/// (`Right`, the limit from above).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Side {
    /// The limit from below: the piece that ends at the point.
    Left,
    /// The limit from above: the piece that starts at the point (the default convention).
    Right,
}

/// A standard motion law (see the [module documentation](self) for the formulas).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MotionLaw {
    /// No motion: f = 0 (the lift must be 0).
    Dwell,
    /// Constant velocity: f = u (velocity jumps at both ends: an impulse of acceleration).
    UniformVelocity,
    /// Constant acceleration then constant retardation: f = 2u², 1 − 2(1 − u)².
    Parabolic,
    /// Simple harmonic: f = (1 − cos πu)/2.
    SimpleHarmonic,
    /// Cycloidal: f = u − sin(2πu)/2π.
    Cycloidal,
    /// The 3-4-5 polynomial: f = 10u³ − 15u⁴ + 6u⁵.
    Polynomial345,
    /// The 4-5-6-7 polynomial: f = 35u⁴ − 84u⁵ + 70u⁶ − 20u⁷.
    Polynomial4567,
    /// Modified trapezoidal acceleration (sine ramps and constant acceleration, eighths).
    ModifiedTrapezoidal,
    /// Modified sine acceleration (sine ramps and a cosine of period 3/2, eighths).
    ModifiedSine,
}

/// Breaks as fractions of the segment, where two pieces of a law meet.
const PARABOLIC_BREAKS: &[f64] = &[0.5];
const TRAPEZOIDAL_BREAKS: &[f64] = &[0.125, 0.375, 0.625, 0.875];
const SINE_BREAKS: &[f64] = &[0.125, 0.875];

/// |u − break| within this is "at the break" (u = (θ − θ₀)/β carries a few roundings).
pub(crate) const AT_BREAK: f64 = 16.0 * f64::EPSILON;

impl MotionLaw {
    /// Every law, in declaration order.
    pub const ALL: &'static [MotionLaw] = &[
        MotionLaw::Dwell,
        MotionLaw::UniformVelocity,
        MotionLaw::Parabolic,
        MotionLaw::SimpleHarmonic,
        MotionLaw::Cycloidal,
        MotionLaw::Polynomial345,
        MotionLaw::Polynomial4567,
        MotionLaw::ModifiedTrapezoidal,
        MotionLaw::ModifiedSine,
    ];

    /// The name used in scene files (`law = "cycloidal"`).
    pub fn name(self) -> &'static str {
        match self {
            MotionLaw::Dwell => "dwell",
            MotionLaw::UniformVelocity => "uniform_velocity",
            MotionLaw::Parabolic => "parabolic",
            MotionLaw::SimpleHarmonic => "simple_harmonic",
            MotionLaw::Cycloidal => "cycloidal",
            MotionLaw::Polynomial345 => "polynomial_345",
            MotionLaw::Polynomial4567 => "polynomial_4567",
            MotionLaw::ModifiedTrapezoidal => "modified_trapezoidal",
            MotionLaw::ModifiedSine => "modified_sine",
        }
    }

    /// The law called `name` (as [`name`](Self::name) gives it), if there is one.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.iter().copied().find(|law| law.name() == name)
    }

    /// The fractions of the segment (strictly between 0 and 1) where the law's pieces meet;
    /// a derivative may jump there (s″ of the parabolic law at ½, s‴ of the modified laws).
    pub fn breaks(self) -> &'static [f64] {
        match self {
            MotionLaw::Parabolic => PARABOLIC_BREAKS,
            MotionLaw::ModifiedTrapezoidal => TRAPEZOIDAL_BREAKS,
            MotionLaw::ModifiedSine => SINE_BREAKS,
            _ => &[],
        }
    }

    /// The index of the piece that holds `u` (the one chosen by `side` at a break).
    pub fn piece(self, u: f64, side: Side) -> usize {
        self.breaks()
            .iter()
            .take_while(|&&b| u > b + AT_BREAK || (side == Side::Right && u >= b - AT_BREAK))
            .count()
    }

    /// The normalised displacement f(u), 0 at u = 0 and 1 at u = 1 (0 throughout for a
    /// dwell), on the piece that `side` picks at a break. Outside [0, 1] the end pieces are
    /// continued analytically.
    ///
    /// ```
    /// use mechdiff_core::cams::{MotionLaw, Side};
    /// use num_dual::Dual3_64;
    /// let f = MotionLaw::Cycloidal.rise(Dual3_64::from(0.25).derivative(), Side::Right);
    /// // f′ = 1 − cos 2πu = 1 at u = ¼, f″ = 2π sin 2πu = 2π.
    /// assert!((f.v1 - 1.0).abs() < 1e-15 && (f.v2 - 2.0 * std::f64::consts::PI).abs() < 1e-14);
    /// ```
    pub fn rise<D: Scalar>(self, u: D, side: Side) -> D {
        let piece = self.piece(u.re(), side);
        match self {
            MotionLaw::Dwell => u * 0.0,
            MotionLaw::UniformVelocity => u,
            MotionLaw::Parabolic => {
                if piece == 0 {
                    u * u * 2.0
                } else {
                    let rest = -u + 1.0;
                    -(rest * rest * 2.0) + 1.0
                }
            }
            MotionLaw::SimpleHarmonic => (-(u * PI).cos() + 1.0) * 0.5,
            MotionLaw::Cycloidal => u - (u * (2.0 * PI)).sin() / (2.0 * PI),
            MotionLaw::Polynomial345 => u * u * u * (u * (u * 6.0 - 15.0) + 10.0),
            MotionLaw::Polynomial4567 => {
                let u2 = u * u;
                u2 * u2 * (u * (u * (u * -20.0 + 70.0) - 84.0) + 35.0)
            }
            MotionLaw::ModifiedTrapezoidal => modified_trapezoidal(u, piece),
            MotionLaw::ModifiedSine => modified_sine(u, piece),
        }
    }
}

impl fmt::Display for MotionLaw {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The modified trapezoidal law on piece `piece` (see the module documentation).
fn modified_trapezoidal<D: Scalar>(u: D, piece: usize) -> D {
    let k = 2.0 + PI;
    let sine = (u * (4.0 * PI)).sin();
    let pi2 = PI * PI;
    match piece {
        0 => (u * (4.0 * PI) - sine) / (2.0 * PI * k),
        1 => (u * (32.0 * PI) + (u * (u * 64.0 - 16.0) + 1.0) * pi2 - 8.0) / (16.0 * PI * k),
        2 => (u * (4.0 * PI) + (u * 4.0 - 1.0) * pi2 + sine) / (2.0 * PI * k),
        3 => (u * (32.0 * PI) + (u * (u * -64.0 + 112.0) - 33.0) * pi2 + 8.0) / (16.0 * PI * k),
        _ => (u * (2.0 * PI) - sine * 0.5 + pi2) / (PI * k),
    }
}

/// The modified sine law on piece `piece` (see the module documentation).
fn modified_sine<D: Scalar>(u: D, piece: usize) -> D {
    let k = PI + 4.0;
    match piece {
        0 => (u * PI - (u * (4.0 * PI)).sin() * 0.25) / k,
        1 => (u * PI - ((u * 4.0 + 1.0) * (PI / 3.0)).sin() * 2.25 + 2.0) / k,
        _ => (u * PI - (u * (4.0 * PI)).sin() * 0.25 + 4.0) / k,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every law starts at 0 and ends at 1 (0 for a dwell), and its pieces join in value at
    /// every break: 1e-15 absolute, a few roundings of numbers of size 1.
    #[test]
    fn laws_run_from_zero_to_one_and_pieces_join() {
        for &law in MotionLaw::ALL {
            let end = if law == MotionLaw::Dwell { 0.0 } else { 1.0 };
            assert!(law.rise(0.0_f64, Side::Right).abs() < 1e-15, "{law}");
            assert!((law.rise(1.0_f64, Side::Left) - end).abs() < 1e-15, "{law}");
            for &b in law.breaks() {
                let (l, r): (f64, f64) = (law.rise(b, Side::Left), law.rise(b, Side::Right));
                assert!((l - r).abs() < 1e-15, "{law} at {b}: {l} vs {r}");
            }
        }
    }

    /// The piece index follows the side only at a break.
    #[test]
    fn side_picks_the_piece_at_a_break_only() {
        let law = MotionLaw::ModifiedTrapezoidal;
        assert_eq!(law.piece(0.375, Side::Left), 1);
        assert_eq!(law.piece(0.375, Side::Right), 2);
        assert_eq!(law.piece(0.3, Side::Left), 1);
        assert_eq!(law.piece(0.3, Side::Right), 1);
        assert_eq!(law.piece(0.99, Side::Left), 4);
    }

    #[test]
    fn names_round_trip() {
        for &law in MotionLaw::ALL {
            assert_eq!(MotionLaw::from_name(law.name()), Some(law));
        }
        assert_eq!(MotionLaw::from_name("cubic"), None);
    }
}
