//! The constraints a local step can slide along, as smooth inequalities c(x) > 0 with their
//! gradients: the order of free drive angles (φᵢ₊₁ − φᵢ > 0, and 2π − (φₙ − φ₁) > 0) and the
//! crank's full turn (Grashof with the crank shortest: ground, coupler and rocker each longer
//! than the crank, and s + l < p + q; the slider-crank's rod − crank − |offset| > 0).
//!
//! They restate conditions of [`Problem::check`] that a least-squares path often runs into:
//! without them a step across one is only rejected, the damping grows and the search stalls
//! against the constraint; with them Levenberg–Marquardt keeps the linearised condition
//! (see `lm`). Where the maximum (the longest link) or |offset| has a kink, the gradient of
//! the current side is used. The other defects (assembly, transmission) stay rejections.

use super::linkage::Linkage;
use super::problem::Problem;
use super::task::Timing;
use std::f64::consts::TAU;

/// One inequality c(x) > 0: its value and its gradient over every design variable.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Inequality {
    /// c(x).
    pub value: f64,
    /// ∂c/∂x, one entry per design variable (zero where c does not depend on it).
    pub gradient: Vec<f64>,
}

impl Problem {
    /// The sliding inequalities at `x` (see the module doc): the order of free drive angles,
    /// and the crank's full turn where it is required.
    pub(crate) fn inequalities(&self, x: &[f64]) -> Vec<Inequality> {
        let n = x.len();
        let mut out = Vec::new();
        let unit = |pairs: &[(usize, f64)], value: f64| {
            let mut gradient = vec![0.0; n];
            for &(i, g) in pairs {
                gradient[i] += g;
            }
            Inequality { value, gradient }
        };
        if matches!(self.task.timing(), Timing::Free) {
            let first = n - self.task.target_count();
            for i in first..n - 1 {
                out.push(unit(&[(i + 1, 1.0), (i, -1.0)], x[i + 1] - x[i]));
            }
            out.push(unit(
                &[(first, 1.0), (n - 1, -1.0)],
                TAU - (x[n - 1] - x[first]),
            ));
        }
        if self.constraints.crank_rotates {
            match self.linkage {
                Linkage::SliderCrank => {
                    let sign = x[4].signum();
                    out.push(unit(
                        &[(3, 1.0), (2, -1.0), (4, -sign)],
                        x[3] - x[2] - x[4].abs(),
                    ));
                }
                _ => {
                    let (dx, dy) = (x[2] - x[0], x[3] - x[1]);
                    let ground = dx.hypot(dy);
                    if ground > 0.0 {
                        let (ux, uy) = (dx / ground, dy / ground);
                        // ∂ground/∂(o2x, o2y, o4x, o4y).
                        let dground = [(0, -ux), (1, -uy), (2, ux), (3, uy)];
                        let scaled = |s: f64| dground.map(|(i, g)| (i, s * g));
                        let mut ground_minus_crank = scaled(1.0).to_vec();
                        ground_minus_crank.push((4, -1.0));
                        out.push(unit(&ground_minus_crank, ground - x[4]));
                        out.push(unit(&[(5, 1.0), (4, -1.0)], x[5] - x[4]));
                        out.push(unit(&[(6, 1.0), (4, -1.0)], x[6] - x[4]));
                        // p + q − s − l = ground + coupler + rocker − 2·longest − crank.
                        let (coupler, rocker) = (x[5], x[6]);
                        let longest = ground.max(coupler).max(rocker);
                        let mut pairs = scaled(1.0).to_vec();
                        pairs.extend([(5, 1.0), (6, 1.0), (4, -1.0)]);
                        if longest == ground {
                            pairs.extend(scaled(-2.0));
                        } else if longest == coupler {
                            pairs.push((5, -2.0));
                        } else {
                            pairs.push((6, -2.0));
                        }
                        let value = ground + coupler + rocker - 2.0 * longest - x[4];
                        out.push(unit(&pairs, value));
                    }
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synthesis::{Constraints, Task};

    /// Each gradient matches central differences of its value (step 1e-6 on values of order
    /// 1–10 away from kinks: error of order 1e-10, so 1e-7 is a safe margin).
    #[test]
    fn gradients_match_differences() {
        let task = Task::Path {
            point: "P".into(),
            targets: vec![[0.0, 1.0], [0.5, 1.2], [1.0, 1.1]],
            timing: Timing::Free,
        };
        let mut builder = Problem::builder(Linkage::FourBar, task).constraints(Constraints {
            crank_rotates: true,
            ..Constraints::default()
        });
        for name in Linkage::FourBar.variable_names() {
            builder = builder.bound(name, -10.0, 10.0);
        }
        let problem = builder.build().unwrap();
        let x = [0.1, -0.2, 3.1, 0.7, 1.0, 3.7, 2.9, 0.4, 0.8, 0.3, 1.4, 2.2];
        let at = problem.inequalities(&x);
        assert_eq!(at.len(), 3 + 4);
        for i in 0..x.len() {
            let h = 1e-6;
            let (mut up, mut down) = (x, x);
            up[i] += h;
            down[i] -= h;
            let (cu, cd) = (problem.inequalities(&up), problem.inequalities(&down));
            for (k, c) in at.iter().enumerate() {
                let difference = (cu[k].value - cd[k].value) / (2.0 * h);
                assert!(
                    (difference - c.gradient[i]).abs() < 1e-7,
                    "inequality {k}, variable {i}: {difference} against {}",
                    c.gradient[i]
                );
            }
        }
    }
}
