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

use super::constraints::{Equations, Frames};
use nalgebra::{DVector, Dyn, LU};
use num_dual::{Dual2_64, Dual3_64};

/// A linear solve with Φ_q already factorised: `solve(b, x)` sets x = Φ_q⁻¹ b, false if
/// singular.
pub(crate) trait Factorised {
    /// x = Φ_q⁻¹ b.
    fn solve_into(&self, b: &[f64], x: &mut [f64]) -> bool;
}

impl Factorised for LU<f64, Dyn, Dyn> {
    fn solve_into(&self, b: &[f64], x: &mut [f64]) -> bool {
        match self.solve(&DVector::from_column_slice(b)) {
            Some(s) => {
                x.copy_from_slice(s.as_slice());
                true
            }
            None => false,
        }
    }
}

/// q″ from q, q′ and the factorised Φ_q at (q, φ); false if singular.
pub(crate) fn second_derivative(
    eq: &Equations,
    lu: &impl Factorised,
    q: &[f64],
    dq: &[f64],
    phi: f64,
    ddq: &mut [f64],
) -> bool {
    let frames: Vec<(f64, f64)> = (0..q.len() / 3).map(|k| q[3 * k + 2].sin_cos()).collect();
    let mut residual = vec![0.0; q.len()];
    SecondOrder::new(q.len()).solve(eq, lu, q, &frames, dq, phi, ddq, &mut residual)
}

/// Buffers for q″ (see [`SecondOrder::solve`]), kept by the tracker so that lifting a pose
/// allocates nothing.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SecondOrder {
    x: Vec<Dual2_64>,
    frames: Vec<(Dual2_64, Dual2_64)>,
    out: Vec<Dual2_64>,
    rhs: Vec<f64>,
}

impl SecondOrder {
    /// Buffers for `n` coordinates (and `n` equations).
    pub fn new(n: usize) -> Self {
        let zero = Dual2_64::from(0.0);
        SecondOrder {
            x: vec![zero; n],
            frames: vec![(zero, zero); n / 3],
            out: vec![zero; n],
            rhs: vec![0.0; n],
        }
    }

    /// q″ into `ddq` and Φ(q, φ) into `residual`, from q, its bodies' `(sin θ, cos θ)`
    /// `frames`, q′ and the factorised Φ_q at (q, φ); false if singular.
    ///
    /// One evaluation of Φ in `Dual2` numbers `q + q′ε`, whose sines and cosines follow
    /// from `frames` by the chain rule (sin(θ + θ′ε) = s + cθ′ε − sθ′²ε²/2, the second
    /// derivative part being what `Dual2` stores), so no trigonometric function is called.
    #[allow(clippy::too_many_arguments)]
    pub fn solve(
        &mut self,
        eq: &Equations,
        lu: &impl Factorised,
        q: &[f64],
        frames: &[(f64, f64)],
        dq: &[f64],
        phi: f64,
        ddq: &mut [f64],
        residual: &mut [f64],
    ) -> bool {
        for ((x, &a), &b) in self.x.iter_mut().zip(q).zip(dq) {
            *x = Dual2_64::new(a, b, 0.0);
        }
        for (k, (f, &(s, c))) in self.frames.iter_mut().zip(frames).enumerate() {
            let w = dq[3 * k + 2];
            *f = (
                Dual2_64::new(s, c * w, -s * w * w),
                Dual2_64::new(c, -s * w, -c * w * w),
            );
        }
        let f = Frames {
            q: &self.x,
            frames: &self.frames,
        };
        eq.evaluate_with(&f, Dual2_64::new(phi, 1.0, 0.0), &mut self.out);
        for ((rhs, r), out) in self.rhs.iter_mut().zip(residual).zip(&self.out) {
            *rhs = -out.v2;
            *r = out.re;
        }
        lu.solve_into(&self.rhs, ddq)
    }
}

/// q‴ from q, q′, q″ and the factorised Φ_q at (q, φ); false if singular.
pub(crate) fn third_derivative(
    eq: &Equations,
    lu: &impl Factorised,
    q: &[f64],
    dq: &[f64],
    ddq: &[f64],
    phi: f64,
    dddq: &mut [f64],
) -> bool {
    let x: Vec<Dual3_64> = (0..q.len())
        .map(|i| Dual3_64::new(q[i], dq[i], ddq[i], 0.0))
        .collect();
    let mut out = vec![Dual3_64::from(0.0); eq.rows()];
    eq.evaluate(&x, Dual3_64::new(phi, 1.0, 0.0, 0.0), &mut out);
    let rhs: Vec<f64> = out.iter().map(|r| -r.v3).collect();
    lu.solve_into(&rhs, dddq)
}

/// The derivatives `[q′, q″, q‴][..order]` (order 1 to 3) at an assembled pose `q` at drive
/// position `phi`: one Jacobian, one LU, `order − 1` dual-number evaluations of Φ. `None` if
/// Φ_q is singular there or `order` is not 1 to 3. ([`super::Tracker`] does this itself; this
/// is for a pose found some other way.)
///
/// ```
/// use mechdiff_core::geometry::{implicit, Drive, Equations, Mechanism};
/// let m = Mechanism::builder()
///     .point("O", [0.0, 0.0]).point("A", [2.0, 0.0])
///     .ground(["O"]).link("crank", ["O", "A"])
///     .revolute("O", "ground", "crank", "O")
///     .drive(Drive::angle("O"))
///     .build().unwrap();
/// let eq = Equations::new(&m);
/// let d = implicit::lift(&eq, &m.sketch_coordinates(), 0.0, 2).unwrap();
/// // The crank's reference point O does not move; its angle θ = φ: θ′ = 1, θ″ = 0.
/// assert_eq!((d[0][2], d[1][2]), (1.0, 0.0));
/// ```
pub fn lift(eq: &Equations, q: &[f64], phi: f64, order: usize) -> Option<Vec<DVector<f64>>> {
    if !(1..=3).contains(&order) || q.len() != eq.coordinates() || eq.rows() != q.len() {
        return None;
    }
    let mut jac = nalgebra::DMatrix::zeros(eq.rows(), eq.coordinates());
    eq.jacobian(q, &mut jac);
    let lu = jac.lu();
    let n = q.len();
    let mut e = vec![0.0; n];
    e[n - 1] = 1.0;
    let mut out = vec![DVector::zeros(n); order];
    let ok = lu.solve_into(&e, out[0].as_mut_slice())
        && (order < 2 || {
            let (done, rest) = out.split_at_mut(1);
            second_derivative(eq, &lu, q, done[0].as_slice(), phi, rest[0].as_mut_slice())
        })
        && (order < 3 || {
            let (done, rest) = out.split_at_mut(2);
            let (d1, d2) = (done[0].as_slice(), done[1].as_slice());
            third_derivative(eq, &lu, q, d1, d2, phi, rest[0].as_mut_slice())
        });
    ok.then_some(out)
}
