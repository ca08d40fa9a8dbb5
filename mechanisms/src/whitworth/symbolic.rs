//! ψ and x_C differentiated at compile time by `#[derivatives]`: the "symbolic" method of the
//! tests and benchmarks.
//!
//! The position functions are written once, as the source writes them: (1.30)
//! tan ψ = λ sin φ / (1 − λ cos φ) and (1.37) x_C = h tan ψ. The macro (the symbolic engine
//! of [`mechdiff_core::symbolic`]) generates ψ′, ψ″, ψ‴ and x_C′, x_C″, x_C‴ as straight-line
//! code that computes sin φ and cos φ once and shares the common denominator
//! λ² sin² φ + (1 − λ cos φ)² = 1 − 2λ cos φ + λ² between the derivatives (see the snapshot
//! `macros/src/snapshots/…whitworth_expansion_snapshot.snap` for the code). ψ = atan(tan ψ)
//! holds on the whole revolution because 1 − λ cos φ > 0 for λ < 1.
//!
//! ```
//! use mechdiff_mechanisms::whitworth::{hand, symbolic};
//!
//! let (phi, lambda) = (1.0, 0.375);
//! let generated = symbolic::rocker_angle_jet(phi, lambda);
//! let by_hand = hand::rocker_angle(lambda, phi);
//! assert!((generated.d2() - by_hand.d2()).abs() < 1e-15);
//! ```

use mechdiff_macros::derivatives;

/// Rocker angle ψ (rad) at crank angle φ (rad), for the crank ratio λ = l1/l0 < 1, eq. (1.30).
///
/// The macro generates [`rocker_angle_jet`] (ψ, ψ′, ψ″), [`rocker_angle_jet3`] (up to ψ‴) and
/// [`rocker_angle_expression`] (the s-expression the engine differentiates).
#[derivatives(wrt = phi, order = 2, name = rocker_angle_jet)]
#[derivatives(wrt = phi, order = 3, name = rocker_angle_jet3, expression = rocker_angle_expression)]
pub fn rocker_angle(phi: f64, lambda: f64) -> f64 {
    (lambda * phi.sin() / (1.0 - lambda * phi.cos())).atan()
}

/// Ram position x_C = h tan ψ (m) at crank angle φ (rad), for λ = l1/l0 < 1 and the ram
/// height h (m), eq. (1.37).
///
/// The macro generates [`ram_position_jet`] (x_C, x_C′, x_C″), [`ram_position_jet3`] (up to
/// x_C‴) and [`ram_position_expression`].
#[derivatives(wrt = phi, order = 2, name = ram_position_jet)]
#[derivatives(wrt = phi, order = 3, name = ram_position_jet3, expression = ram_position_expression)]
pub fn ram_position(phi: f64, lambda: f64, h: f64) -> f64 {
    let psi = (lambda * phi.sin() / (1.0 - lambda * phi.cos())).atan();
    h * psi.tan()
}
