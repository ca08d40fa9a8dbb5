//! The source's hand-derived formulas: the baseline the automatic derivatives are verified and
//! benchmarked against.
//!
//! Equation numbers are the source's ("Task 1 Shaping Machine", reference `whitworth_000`).
//! All of them were checked symbolically (notes `whitworth_000.md`). The time-derivative forms
//! (1.10), (1.11), (1.23), (1.24), (1.41) assume a constant crank speed, as the source does;
//! [`pose`] gives the same formulas as derivatives with respect to φ, which a
//! [`DriveState`](mechdiff_core::DriveState) turns into accelerations for any α.
//!
//! ```
//! use mechdiff_core::method::{Differentiator, Dual2, HandDerived};
//! use mechdiff_mechanisms::{Whitworth, whitworth::hand};
//!
//! let shaper = Whitworth::reference();
//! let by_hand = HandDerived(|phi| hand::pose(&shaper, phi));
//! let (hand, dual) = (by_hand.jets(&shaper, 1.0), Dual2.jets(&shaper, 1.0));
//! assert!((hand.c.x.d2() - dual.c.x.d2()).abs() < 1e-15);
//! ```

use super::{Pose, Whitworth};
use mechdiff_core::{Jet, Point};

/// ψ′ = λ (cos φ − λ) / (1 − 2λ cos φ + λ²), eq. (1.35).
pub fn velocity_coefficient(lambda: f64, phi: f64) -> f64 {
    let cos = phi.cos();
    lambda * (cos - lambda) / (1.0 - 2.0 * lambda * cos + lambda * lambda)
}

/// ψ″ = λ sin φ (λ² − 1) / (1 − 2λ cos φ + λ²)², eq. (1.36).
pub fn acceleration_coefficient(lambda: f64, phi: f64) -> f64 {
    let (sin, cos) = phi.sin_cos();
    let d = 1.0 - 2.0 * lambda * cos + lambda * lambda;
    lambda * sin * (lambda * lambda - 1.0) / (d * d)
}

/// ψ from tan ψ = λ sin φ / (1 − λ cos φ) (1.30), with ψ′ (1.35) and ψ″ (1.36), sharing one
/// sin/cos evaluation: the fastest hand-written ψ, ψ′, ψ″. ψ = atan(tan ψ) is valid on the
/// whole revolution because 1 − λ cos φ > 0 for λ < 1 (|ψ| < π/2).
pub fn rocker_angle(lambda: f64, phi: f64) -> Jet<2> {
    let (sin, cos) = phi.sin_cos();
    let y = 1.0 - lambda * cos;
    let d = 1.0 - 2.0 * lambda * cos + lambda * lambda;
    Jet::new(
        (lambda * sin / y).atan(),
        [
            lambda * (cos - lambda) / d,
            lambda * sin * (lambda * lambda - 1.0) / (d * d),
        ],
    )
}

/// x_C′ = hλ (cos φ − λ) / (1 − λ cos φ)²: the ram's velocity coefficient, (1.39) over ω.
pub fn ram_velocity_coefficient(shaper: &Whitworth, phi: f64) -> f64 {
    let (lambda, h) = (shaper.lambda(), shaper.parameters.h);
    let cos = phi.cos();
    let y = 1.0 - lambda * cos;
    h * lambda * (cos - lambda) / (y * y)
}

/// x_C″ = hλ sin φ (2λ² − λ cos φ − 1) / (1 − λ cos φ)³: (1.41) over ω².
pub fn ram_acceleration_coefficient(shaper: &Whitworth, phi: f64) -> f64 {
    let (lambda, h) = (shaper.lambda(), shaper.parameters.h);
    let (sin, cos) = phi.sin_cos();
    let y = 1.0 - lambda * cos;
    h * lambda * sin * (2.0 * lambda * lambda - lambda * cos - 1.0) / (y * y * y)
}

/// ẋ_S3 = ẋ_C = hλω (cos φ − λ) / (1 − λ cos φ)², eq. (1.39).
pub fn ram_velocity(shaper: &Whitworth, phi: f64, omega: f64) -> f64 {
    omega * ram_velocity_coefficient(shaper, phi)
}

/// ẍ_S3 = hλω² sin φ (2λ² − λ cos φ − 1) / (1 − λ cos φ)³ at constant ω, eq. (1.41).
pub fn ram_acceleration(shaper: &Whitworth, phi: f64, omega: f64) -> f64 {
    omega * omega * ram_acceleration_coefficient(shaper, phi)
}

/// ẍ_S1 = −ω² l_S1 sin φ, ÿ_S1 = ω² l_S1 cos φ at constant ω, eqs. (1.10), (1.11).
pub fn crank_centre_acceleration(shaper: &Whitworth, phi: f64, omega: f64) -> Point<f64> {
    let (sin, cos) = phi.sin_cos();
    let k = omega * omega * shaper.parameters.l_s1;
    Point::new(-k * sin, k * cos)
}

/// ẍ_S2 = −l_S2 ω² (ψ′² sin ψ − ψ″ cos ψ), ÿ_S2 = −l_S2 ω² (ψ′² cos ψ + ψ″ sin ψ) at constant
/// ω, eqs. (1.23), (1.24), with sin ψ, cos ψ from (1.31), (1.32).
pub fn rocker_centre_acceleration(shaper: &Whitworth, phi: f64, omega: f64) -> Point<f64> {
    let lambda = shaper.lambda();
    let (sin_psi, cos_psi) = rocker_sin_cos(lambda, phi);
    let (d1, d2) = (
        velocity_coefficient(lambda, phi),
        acceleration_coefficient(lambda, phi),
    );
    let k = -shaper.parameters.l_s2 * omega * omega;
    Point::new(
        k * (d1 * d1 * sin_psi - d2 * cos_psi),
        k * (d1 * d1 * cos_psi + d2 * sin_psi),
    )
}

/// sin ψ = λ sin φ / √(1 − 2λ cos φ + λ²) and cos ψ = (1 − λ cos φ) / √(…), eqs. (1.31), (1.32).
fn rocker_sin_cos(lambda: f64, phi: f64) -> (f64, f64) {
    let (sin, cos) = phi.sin_cos();
    let b0a = (1.0 - 2.0 * lambda * cos + lambda * lambda).sqrt();
    (lambda * sin / b0a, (1.0 - lambda * cos) / b0a)
}

/// The whole [`Pose`] with first and second derivatives with respect to φ, from the source's
/// formulas: (1.4)–(1.9) for S1 (and A, with l1 for l_S1), (1.30), (1.35), (1.36) for ψ,
/// (1.12)–(1.17) for S2, (1.37), (1.39), (1.41) for C and S3, each time derivative divided by
/// the powers of ω it carries.
pub fn pose(shaper: &Whitworth, phi: f64) -> Pose<Jet<2>> {
    let p = &shaper.parameters;
    let lambda = shaper.lambda();
    let (sin, cos) = phi.sin_cos();
    let on_crank = |r: f64| {
        Point::new(
            Jet::new(r * sin, [r * cos, -r * sin]),
            Jet::new(p.l0 - r * cos, [r * sin, r * cos]),
        )
    };
    let psi = rocker_angle(lambda, phi);
    let (d1, d2) = (psi.d1(), psi.d2());
    let (sin_psi, cos_psi) = rocker_sin_cos(lambda, phi);
    let s2 = Point::new(
        Jet::new(
            p.l_s2 * sin_psi,
            [
                p.l_s2 * d1 * cos_psi,
                p.l_s2 * (d2 * cos_psi - d1 * d1 * sin_psi),
            ],
        ),
        Jet::new(
            p.l_s2 * cos_psi,
            [
                -p.l_s2 * d1 * sin_psi,
                -p.l_s2 * (d1 * d1 * cos_psi + d2 * sin_psi),
            ],
        ),
    );
    let x_c = Jet::new(
        p.h * lambda * sin / (1.0 - lambda * cos),
        [
            ram_velocity_coefficient(shaper, phi),
            ram_acceleration_coefficient(shaper, phi),
        ],
    );
    let x_s3 = Jet::new(x_c.value - p.c_x, x_c.derivatives);
    Pose {
        psi,
        a: on_crank(p.l1),
        c: Point::new(x_c, Jet::from(p.h)),
        s1: on_crank(p.l_s1),
        s2,
        s3: Point::new(x_s3, Jet::from(p.h + p.c_y)),
    }
}
