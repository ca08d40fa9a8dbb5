//! Derivative methods behind one interface: dual numbers, central differences, hand-derived
//! formulas.
//!
//! Every method turns a [`PositionFunction`] into [`Jet`]s of its outputs at a drive position,
//! so that one mechanism can be evaluated — and compared — by every method:
//!
//! | method | order | how |
//! |---|---|---|
//! | [`Dual1`] | 1 | `Dual64` |
//! | [`Dual2`] | 2 | `Dual2_64` |
//! | [`HyperDual`] | 2 | `HyperDual64` with both infinitesimal parts along φ |
//! | [`Dual3`] | 3 | `Dual3_64` |
//! | [`CentralDifference`] | 1–3 | central differences of step h, O(h²) |
//! | [`HandDerived`] | any | a closure with formulas derived by hand (the baseline) |
//!
//! ```
//! use mechdiff_core::method::{CentralDifference, Differentiator, Dual2};
//! use mechdiff_core::{PositionFunction, Scalar};
//!
//! struct Crank { radius: f64 }
//! impl PositionFunction for Crank {
//!     type Output<T> = [T; 2];
//!     fn evaluate<D: Scalar>(&self, phi: D) -> [D; 2] {
//!         [phi.cos() * self.radius, phi.sin() * self.radius]
//!     }
//!     fn map<A, B>(p: [A; 2], f: impl FnMut(A) -> B) -> [B; 2] {
//!         p.map(f)
//!     }
//! }
//! let crank = Crank { radius: 0.1 };
//! let [x, y] = Dual2.jets(&crank, 0.0);
//! assert_eq!((x.value, y.d1(), x.d2()), (0.1, 0.1, -0.1));
//! let [_, y_fd]: [mechdiff_core::Jet<1>; 2] = CentralDifference::new(1e-4).jets(&crank, 0.0);
//! assert!((y_fd.d1() - 0.1).abs() < 1e-9);
//! ```

use crate::jet::Jet;
use crate::position::{PositionFunction, flatten, rebuild};
use num_dual::{Dual2_64, Dual3_64, Dual64, HyperDual64};

/// A way to compute the value and first `N` derivatives of a position function's outputs.
pub trait Differentiator<F: PositionFunction, const N: usize> {
    /// The outputs of `f` at drive position `phi`, each with its first `N` derivatives.
    fn jets(&self, f: &F, phi: f64) -> F::Output<Jet<N>>;
}

/// First derivatives with `Dual64`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Dual1;

/// First and second derivatives with `Dual2_64`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Dual2;

/// First and second derivatives with `HyperDual64` (ε₁ = ε₂ = dφ).
#[derive(Clone, Copy, Debug, Default)]
pub struct HyperDual;

/// First, second and third derivatives with `Dual3_64`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Dual3;

impl<F: PositionFunction> Differentiator<F, 1> for Dual1 {
    fn jets(&self, f: &F, phi: f64) -> F::Output<Jet<1>> {
        F::map(f.evaluate(Dual64::from(phi).derivative()), |x| {
            Jet::new(x.re, [x.eps])
        })
    }
}

impl<F: PositionFunction> Differentiator<F, 2> for Dual2 {
    #[inline]
    fn jets(&self, f: &F, phi: f64) -> F::Output<Jet<2>> {
        F::map(f.evaluate(Dual2_64::from(phi).derivative()), |x| {
            Jet::new(x.re, [x.v1, x.v2])
        })
    }
}

impl<F: PositionFunction> Differentiator<F, 2> for HyperDual {
    fn jets(&self, f: &F, phi: f64) -> F::Output<Jet<2>> {
        let phi = HyperDual64::from(phi).derivative1().derivative2();
        F::map(f.evaluate(phi), |x| Jet::new(x.re, [x.eps1, x.eps1eps2]))
    }
}

impl<F: PositionFunction> Differentiator<F, 3> for Dual3 {
    fn jets(&self, f: &F, phi: f64) -> F::Output<Jet<3>> {
        let phi = Dual3_64::from(phi).derivative();
        F::map(f.evaluate(phi), |x| Jet::new(x.re, [x.v1, x.v2, x.v3]))
    }
}

/// Central finite differences with step `h`, of second order in `h` for every derivative:
///
/// - x′ ≈ (x₁ − x₋₁) / 2h
/// - x″ ≈ (x₁ − 2x₀ + x₋₁) / h²
/// - x‴ ≈ (x₂ − 2x₁ + 2x₋₁ − x₋₂) / 2h³
///
/// where xₖ = x(φ + kh). The truncation error is O(h²) and the rounding error O(ε/hⁿ) for the
/// n-th derivative, so the best step grows with the order (about 1e-5, 1e-4 and 1e-3 rad for
/// n = 1, 2, 3 on a function of unit scale).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CentralDifference {
    /// The step h in the drive variable.
    pub step: f64,
}

impl CentralDifference {
    /// Central differences with step `h` (in the unit of the drive variable).
    pub const fn new(step: f64) -> Self {
        Self { step }
    }

    /// The derivative stencil: samples x₋₂, x₋₁, x₀, x₁, x₂ at φ + kh → the first three
    /// derivatives (what [`Differentiator::jets`] applies to each output; public for callers
    /// that sample a function themselves, such as the accuracy report).
    pub fn stencil([m2, m1, x0, p1, p2]: [f64; 5], h: f64) -> [f64; 3] {
        [
            (p1 - m1) / (2.0 * h),
            (p1 - 2.0 * x0 + m1) / (h * h),
            (p2 - 2.0 * p1 + 2.0 * m1 - m2) / (2.0 * h * h * h),
        ]
    }
}

impl<F: PositionFunction, const N: usize> Differentiator<F, N> for CentralDifference {
    fn jets(&self, f: &F, phi: f64) -> F::Output<Jet<N>> {
        const { assert!(N >= 1 && N <= 3, "central differences give orders 1 to 3") };
        let h = self.step;
        let (shape, center) = flatten::<F, f64>(f.evaluate(phi));
        // Only the samples the order needs: ±h for orders 1 and 2, ±2h as well for order 3.
        let offsets: &[i32] = if N == 3 { &[-2, -1, 1, 2] } else { &[-1, 1] };
        let samples: Vec<Vec<f64>> = offsets
            .iter()
            .map(|&k| flatten::<F, f64>(f.evaluate(phi + f64::from(k) * h)).1)
            .collect();
        let sample = |k: i32, i: usize| -> f64 {
            offsets
                .iter()
                .position(|&o| o == k)
                .map_or(0.0, |j| samples[j][i])
        };
        let jets = center.iter().enumerate().map(|(i, &x0)| {
            let d = Self::stencil(
                [sample(-2, i), sample(-1, i), x0, sample(1, i), sample(2, i)],
                h,
            );
            Jet::new(x0, std::array::from_fn(|k| d[k]))
        });
        rebuild::<F, Jet<N>>(shape, jets)
    }
}

/// Formulas derived by hand: a closure from φ to the jets of the outputs.
///
/// The baseline every automatic method is verified and benchmarked against.
pub struct HandDerived<G>(pub G);

impl<F, G, const N: usize> Differentiator<F, N> for HandDerived<G>
where
    F: PositionFunction,
    G: Fn(f64) -> F::Output<Jet<N>>,
{
    fn jets(&self, _f: &F, phi: f64) -> F::Output<Jet<N>> {
        (self.0)(phi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Scalar;

    /// x(φ) = exp(sin φ) and y(φ) = φ³: derivatives known in closed form.
    struct Curve;

    impl PositionFunction for Curve {
        type Output<T> = (T, T);
        fn evaluate<D: Scalar>(&self, phi: D) -> (D, D) {
            (phi.sin().exp(), phi.powi(3))
        }
        fn map<A, B>((x, y): (A, A), mut f: impl FnMut(A) -> B) -> (B, B) {
            (f(x), f(y))
        }
    }

    fn exact(phi: f64) -> [f64; 4] {
        let (s, c) = phi.sin_cos();
        let e = s.exp();
        [e, c * e, (c * c - s) * e, (c * c * c - 3.0 * s * c - c) * e]
    }

    /// Every dual-number method reproduces the closed-form derivatives to 1e-14 relative:
    /// exact methods in f64, a few roundings apart.
    #[test]
    fn dual_methods_match_closed_form_derivatives() {
        for phi in [-2.0, -0.3, 0.0, 0.7, 2.5] {
            let want = exact(phi);
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-14 * b.abs().max(1.0);
            let (x1, _) = Dual1.jets(&Curve, phi);
            let (x2, y2) = Dual2.jets(&Curve, phi);
            let (xh, _) = HyperDual.jets(&Curve, phi);
            let (x3, y3) = Dual3.jets(&Curve, phi);
            assert!(close(x1.d1(), want[1]));
            assert!(close(x2.d1(), want[1]) && close(x2.d2(), want[2]));
            assert!(close(xh.d1(), want[1]) && close(xh.d2(), want[2]));
            assert!(close(x3.d1(), want[1]) && close(x3.d2(), want[2]));
            assert!(close(x3.d3(), want[3]));
            assert!(close(y2.d2(), 6.0 * phi) && close(y3.d3(), 6.0));
        }
    }

    /// Halving h divides the central-difference error by 4 (order 2) for each derivative:
    /// the ratio is checked to lie in [3.5, 4.5], far from 2 (order 1) and 8 (order 3).
    #[test]
    fn central_differences_converge_at_order_two() {
        let phi = 0.7;
        let want = exact(phi);
        let error = |h: f64| {
            let (x, _): (Jet<3>, _) = CentralDifference::new(h).jets(&Curve, phi);
            [1, 2, 3].map(|k| (x.derivatives[k - 1] - want[k]).abs())
        };
        let (coarse, fine) = (error(4e-3), error(2e-3));
        for k in 0..3 {
            let ratio = coarse[k] / fine[k];
            assert!(
                (3.5..=4.5).contains(&ratio),
                "order {}: ratio {ratio}",
                k + 1
            );
        }
    }

    /// The hand-derived closure is returned as given.
    #[test]
    fn hand_derived_closure_is_called_at_phi() {
        let hand = HandDerived(|phi: f64| (Jet::new(phi, [1.0]), Jet::new(0.0, [0.0])));
        let (x, _): (Jet<1>, Jet<1>) = Differentiator::<Curve, 1>::jets(&hand, &Curve, 0.25);
        assert_eq!(x.value, 0.25);
    }
}
