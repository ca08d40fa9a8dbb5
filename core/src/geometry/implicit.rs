//! Exact derivatives of the pose by implicit differentiation, with one LU of Φ_q.
//!
//! Along the solution curve Φ(q(φ), φ) = 0. Differentiating k times gives
//! `Φ_q q⁽ᵏ⁾ + R_k(q, q′, …, q⁽ᵏ⁻¹⁾) = 0`, where `R_k` is the k-th derivative of
//! `t ↦ Φ(q + q′t + … + q⁽ᵏ⁻¹⁾tᵏ⁻¹/(k−1)!, φ + t)` at `t = 0`, i.e. the k-th derivative with
//! the unknown `q⁽ᵏ⁾` set to zero. So each order costs one evaluation of Φ with num-dual's
//! `Dual<k>` numbers and one back-substitution with the same LU:
//!
//! - k = 1: Φ depends on φ only through the drive row (`… − (φ − φ₀)`), so `Φ_φ = −e_drive`
//!   and `q′ = LU⁻¹ e_drive` needs no evaluation at all;
//! - k = 2: `q″ = −LU⁻¹ v₂` with `v₂` from `Dual2` numbers `q + q′ε`;
//! - k = 3: `q‴ = −LU⁻¹ v₃` with `v₃` from `Dual3` numbers `q + q′ε + q″ε²/2`.
//!
//! The alternative, num-dual's `implicit_derivative_vec`, redoes Newton steps in dual
//! arithmetic with a `DualVec` Jacobian and a dual LU per order; the bench
//! `geometry_solver` measures both (see BENCHMARKS.md) and this one is faster.

use super::constraints::Equations;
use nalgebra::{DVector, Dyn, LU};
use num_dual::{Dual2_64, Dual3_64};

/// q″ from q, q′ and the LU of Φ_q at (q, φ); `None` if the LU is singular.
pub(crate) fn second_derivative(
    eq: &Equations,
    lu: &LU<f64, Dyn, Dyn>,
    q: &DVector<f64>,
    dq: &DVector<f64>,
    phi: f64,
) -> Option<DVector<f64>> {
    let x: Vec<Dual2_64> = q.iter().zip(dq.iter()).map(|(&a, &b)| Dual2_64::new(a, b, 0.0)).collect();
    let mut out = vec![Dual2_64::from(0.0); eq.rows()];
    eq.evaluate(&x, Dual2_64::new(phi, 1.0, 0.0), &mut out);
    let rhs = DVector::from_iterator(out.len(), out.iter().map(|r| -r.v2));
    lu.solve(&rhs)
}

/// q‴ from q, q′, q″ and the LU of Φ_q at (q, φ); `None` if the LU is singular.
pub(crate) fn third_derivative(
    eq: &Equations,
    lu: &LU<f64, Dyn, Dyn>,
    q: &DVector<f64>,
    dq: &DVector<f64>,
    ddq: &DVector<f64>,
    phi: f64,
) -> Option<DVector<f64>> {
    let x: Vec<Dual3_64> =
        (0..q.len()).map(|i| Dual3_64::new(q[i], dq[i], ddq[i], 0.0)).collect();
    let mut out = vec![Dual3_64::from(0.0); eq.rows()];
    eq.evaluate(&x, Dual3_64::new(phi, 1.0, 0.0, 0.0), &mut out);
    let rhs = DVector::from_iterator(out.len(), out.iter().map(|r| -r.v3));
    lu.solve(&rhs)
}
