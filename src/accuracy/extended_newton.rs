//! The reference pose of a geometry scene whose loops are solved by Newton: the position
//! solve and the implicit derivatives carried out in double-double precision.
//!
//! The unknown is the whole jet q(φ), q′, q″, q‴ as `Dual3<DoubleDouble>` numbers, and the
//! equations are the solver's own constraint equations Φ(q, φ) = 0 ([`Equations::evaluate`],
//! generic over the scalar) with the drive position φ a `Dual3<DoubleDouble>` too (its
//! derivative parts 1, 0, 0; for a cam-driven joint, the follower's s(θ) with its
//! derivatives). A jet satisfies Φ(q(φ + t), φ + t) = O(t⁴) exactly when its value solves
//! Φ = 0 and its derivative parts are the implicit derivatives, so one Newton iteration in
//! this algebra does both:
//!
//! q ← q − J⁻¹ Φ(q, φ),
//!
//! with J = Φ_q at the `f64` pose (a fixed, approximate Jacobian: the iteration contracts by
//! about cond(J)·ε per step, and the residual is computed in double-double, so the fixed
//! point is the double-double solution). Started from the solver's `f64` jet, a few
//! iterations reach the double-double level (≈ 1e-31 relative); the iteration stops when the
//! correction is below that, or when it stops falling below 1e-26 (near a toggle the
//! attainable accuracy is cond(Φ_q) times the double-double's rounding), and reports a
//! failure otherwise — where J is nearly singular — rather than return a reference it does
//! not have.

use mechdiff_core::geometry::Equations;
use mechdiff_core::num_dual::Dual3;
use nalgebra::DMatrix;

use super::double_double::DoubleDouble;

/// A coordinate (or an equation's residual) with its first three derivatives, in
/// double-double.
pub type Jet = Dual3<DoubleDouble>;

/// Iterations before the solve is given up.
const MAX_ITERATIONS: usize = 30;

/// The correction, relative to each derivative order's largest coordinate, below which the
/// iteration has converged: a few units of the double-double's last place (2⁻¹⁰⁴ ≈ 5e-32).
const CONVERGED: f64 = 1e-30;

/// Where Φ_q is ill-conditioned the corrections stop falling at about cond(Φ_q) times the
/// double-double's rounding; a correction that no longer halves is accepted if it is below
/// this (still ten digits beyond `f64`'s 1e-16, so the reference measures an `f64` method's
/// error to its last bits), and is a failure above it.
const STAGNATED: f64 = 1e-26;

/// The pose jet solving Φ(q, φ) = 0 at the drive position `drive` (a jet), refined in
/// double-double from `start` (the `f64` solver's jet at `drive.re`, the derivatives in the
/// same variable as `drive`'s).
///
/// # Errors
/// A sentence saying why (the Jacobian is singular, or the iteration did not converge
/// within 30 steps, with the last correction).
pub fn solve(equations: &Equations, start: &[Jet], drive: Jet) -> Result<Vec<Jet>, String> {
    let n = start.len();
    if equations.rows() != n || equations.coordinates() != n {
        return Err(format!(
            "the model has {} equations for {} coordinates (a drive's position needs as many)",
            equations.rows(),
            equations.coordinates()
        ));
    }
    let q0: Vec<f64> = start.iter().map(|x| x.re.hi).collect();
    let mut jacobian = DMatrix::zeros(n, n);
    equations.jacobian(&q0, &mut jacobian);
    let lu = jacobian.lu();
    let mut q = start.to_vec();
    let zero = Jet::from(0.0);
    let mut residual = vec![zero; n];
    let mut last = f64::INFINITY;
    for _ in 0..MAX_ITERATIONS {
        equations.evaluate(&q, drive, &mut residual);
        // The correction of each derivative order: J⁻¹ applied to that part of Φ.
        let mut converged = true;
        let mut worst = 0.0_f64;
        let mut corrections = [(); 4].map(|()| vec![0.0; n]);
        for (k, correction) in corrections.iter_mut().enumerate() {
            let rhs = nalgebra::DVector::from_iterator(
                n,
                residual.iter().map(|r| part(r, k).hi + part(r, k).lo),
            );
            let solved = lu
                .solve(&rhs)
                .ok_or("the Jacobian Φ_q is singular at the f64 pose (a toggle position)")?;
            correction.copy_from_slice(solved.as_slice());
            let scale = q.iter().map(|x| part(x, k).hi.abs()).fold(0.0, f64::max);
            let size = correction.iter().fold(0.0_f64, |a, c| a.max(f64::abs(*c)));
            if !size.is_finite() {
                return Err("the double-double Newton iteration diverged".into());
            }
            converged &= size <= CONVERGED * scale;
            worst = worst.max(if scale > 0.0 { size / scale } else { size });
        }
        for (i, x) in q.iter_mut().enumerate() {
            x.re -= DoubleDouble::new(corrections[0][i]);
            x.v1 -= DoubleDouble::new(corrections[1][i]);
            x.v2 -= DoubleDouble::new(corrections[2][i]);
            x.v3 -= DoubleDouble::new(corrections[3][i]);
        }
        if converged || (worst > 0.5 * last && worst <= STAGNATED) {
            return Ok(q);
        }
        last = worst;
    }
    Err(format!(
        "the double-double Newton iteration did not converge in {MAX_ITERATIONS} steps (last \
         relative correction {last:.1e}; Φ_q is ill-conditioned here, near a toggle)"
    ))
}

/// The `f64` jet of the solver (value and derivatives) as a double-double jet.
pub fn lift(value: f64, derivatives: [f64; 3]) -> Jet {
    let [d1, d2, d3] = derivatives;
    Jet::new(
        DoubleDouble::new(value),
        DoubleDouble::new(d1),
        DoubleDouble::new(d2),
        DoubleDouble::new(d3),
    )
}

/// Part `k` of a jet: value, ′, ″, ‴.
fn part(x: &Jet, k: usize) -> DoubleDouble {
    match k {
        0 => x.re,
        1 => x.v1,
        2 => x.v2,
        _ => x.v3,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use mechdiff_core::geometry::{Drive, Mechanism};

    /// A crank of length 2 (one moving link, three coordinates: the pin O stays at the origin
    /// and the angle θ = φ): the solve from a perturbed start returns θ = φ with θ′ = 1,
    /// θ″ = θ‴ = 0 to the double-double's precision (1e-30 absolute: every part is an exact
    /// small integer or φ itself).
    #[test]
    fn a_crank_is_solved_to_double_double_precision() {
        let m = Mechanism::builder()
            .point("O", [0.0, 0.0])
            .point("A", [2.0, 0.0])
            .ground(["O"])
            .link("crank", ["O", "A"])
            .revolute("O", "ground", "crank", "O")
            .drive(Drive::angle("O"))
            .build()
            .unwrap();
        let eq = Equations::new(&m);
        let phi = 0.7;
        let start = vec![
            lift(1e-16, [0.0; 3]),
            lift(-1e-16, [0.0; 3]),
            lift(phi + 2e-16, [1.0 - 1e-15, 1e-15, 0.0]),
        ];
        let drive = Jet::new(
            DoubleDouble::new(phi),
            DoubleDouble::new(1.0),
            DoubleDouble::new(0.0),
            DoubleDouble::new(0.0),
        );
        let q = solve(&eq, &start, drive).unwrap();
        let expected = [[0.0; 4], [0.0; 4], [phi, 1.0, 0.0, 0.0]];
        for (x, e) in q.iter().zip(expected) {
            for (k, expected) in e.into_iter().enumerate() {
                let p = part(x, k);
                assert!(
                    ((p.hi - expected) + p.lo).abs() <= 1e-30,
                    "{k}: {p:?} vs {expected}"
                );
            }
        }
    }
}
