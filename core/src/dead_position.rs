//! Dead positions: where a velocity coefficient changes sign.
//!
//! At a dead position (also: reversal or dead-centre position) an output such as the rocker
//! angle ψ stops and turns back: its velocity coefficient ψ′ = dψ/dφ changes sign. They are
//! found by sampling ψ′ over a range, bracketing every sign change, and refining each bracket
//! to full double precision by Newton's method on the exact derivative ψ″ from dual numbers,
//! safeguarded by bisection so that the iterate never leaves its bracket.

use crate::error::{Error, Result};
use crate::jet::Jet;
use crate::method::{Differentiator, Dual3};
use crate::position::PositionFunction;
use std::ops::RangeInclusive;

/// A dead position of an output x(φ): x′ changes sign at φ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DeadPosition {
    /// The drive position φ.
    pub phi: f64,
    /// The output x there (an extreme of x: the ends of a stroke).
    pub value: f64,
    /// The coefficient x′ there: zero up to rounding.
    pub d1: f64,
    /// x″ there: its sign tells a maximum (negative) from a minimum (positive).
    pub d2: f64,
}

/// Where to look for dead positions, and how finely to sample.
///
/// ```
/// use mechdiff_core::{DeadPositionSearch, Jet, PositionFunction, Scalar};
/// struct Cosine;
/// impl PositionFunction for Cosine {
///     type Output<T> = T;
///     fn evaluate<D: Scalar>(&self, phi: D) -> D { phi.cos() }
///     fn map<A, B>(x: A, mut f: impl FnMut(A) -> B) -> B { f(x) }
/// }
/// let search = DeadPositionSearch::new(0.1..=6.0).with_step(0.1);
/// let dead = search.find(&Cosine, |x: &Jet<3>| *x).unwrap();
/// assert_eq!(dead.len(), 1);
/// assert!((dead[0].phi - std::f64::consts::PI).abs() < 1e-15);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct DeadPositionSearch {
    range: RangeInclusive<f64>,
    step: f64,
}

impl DeadPositionSearch {
    /// A search over `range` of the drive variable, sampled at 1° (π/180) steps.
    pub fn new(range: RangeInclusive<f64>) -> Self {
        Self {
            range,
            step: std::f64::consts::PI / 180.0,
        }
    }

    /// Sample every `step` (two sign changes closer than a step can be missed).
    pub fn with_step(self, step: f64) -> Self {
        Self { step, ..self }
    }

    /// Every dead position of the output chosen by `select` from `f`'s outputs, in increasing φ.
    ///
    /// Sign changes of x′ through a pole (x′ jumps instead of passing through zero) are not
    /// dead positions and are not reported.
    pub fn find<F: PositionFunction>(
        &self,
        f: &F,
        select: impl Fn(&F::Output<Jet<3>>) -> Jet<3>,
    ) -> Result<Vec<DeadPosition>> {
        let jet = |phi: f64| -> Result<Jet<3>> {
            let x = select(&Dual3.jets(f, phi));
            if x.is_finite() {
                Ok(x)
            } else {
                Err(Error::NonFinite {
                    phi,
                    quantity: "the coefficient searched for dead positions",
                })
            }
        };
        self.find_roots(jet)
    }

    /// The dead positions of a jet given as a function of φ (of order `N` ≥ 2: x′ is
    /// bracketed, x″ refines it; a third derivative is not read, so an order-2 jet costs
    /// less and finds the same positions).
    pub fn find_roots<const N: usize>(
        &self,
        jet: impl Fn(f64) -> Result<Jet<N>>,
    ) -> Result<Vec<DeadPosition>> {
        const { assert!(N >= 2, "x′ and x″ are needed") };
        let (start, end) = (*self.range.start(), *self.range.end());
        let grid = sample_points(start, end, self.step)?;
        let samples = grid
            .iter()
            .map(|&phi| jet(phi))
            .collect::<Result<Vec<_>>>()?;
        let scale = samples.iter().map(|x| x.d1().abs()).fold(0.0, f64::max);
        let mut dead = Vec::new();
        for (k, pair) in samples.windows(2).enumerate() {
            let (a, b) = (pair[0].d1(), pair[1].d1());
            if a == 0.0 && k > 0 && samples[k - 1].d1().signum() != b.signum() {
                dead.push(dead_position(grid[k], &pair[0]));
            } else if a * b < 0.0 {
                let (phi, x) = refine(&jet, (grid[k], a), (grid[k + 1], b))?;
                // A sign change through a pole leaves |x′| large at the bracket's end.
                if x.d1().abs() <= 1e-9 * scale {
                    dead.push(dead_position(phi, &x));
                }
            }
        }
        Ok(dead)
    }
}

fn dead_position<const N: usize>(phi: f64, x: &Jet<N>) -> DeadPosition {
    DeadPosition {
        phi,
        value: x.value,
        d1: x.d1(),
        d2: x.d2(),
    }
}

/// start, start + step, …, end (the last point always `end`).
fn sample_points(start: f64, end: f64, step: f64) -> Result<Vec<f64>> {
    let invalid = |reason| {
        Err(Error::InvalidSweep {
            start,
            end,
            step,
            reason,
        })
    };
    if !(start.is_finite() && end.is_finite() && step.is_finite()) {
        return invalid("start, end and step must be finite");
    }
    if step <= 0.0 {
        return invalid("the step must be positive");
    }
    if end <= start {
        return invalid("the range must not be empty");
    }
    let intervals = ((end - start) / step).ceil();
    if intervals > 1e7 {
        return invalid("more than 10 million sample points");
    }
    let n = intervals as usize;
    Ok((0..n)
        .map(|k| start + k as f64 * step)
        .chain([end])
        .collect())
}

/// Newton on x′ with derivative x″, kept inside the bracket [a, b] where x′ changes sign;
/// a step that would leave the bracket (or not shrink it fast enough) is a bisection.
fn refine<const N: usize>(
    jet: &impl Fn(f64) -> Result<Jet<N>>,
    (mut a, fa): (f64, f64),
    (mut b, _): (f64, f64),
) -> Result<(f64, Jet<N>)> {
    let sign_a = fa.signum();
    let mut phi = 0.5 * (a + b);
    let mut best: Option<(f64, Jet<N>)> = None;
    for _ in 0..200 {
        let x = jet(phi)?;
        if best.is_none_or(|(_, y)| x.d1().abs() < y.d1().abs()) {
            best = Some((phi, x));
        }
        if x.d1() == 0.0 {
            break;
        }
        if x.d1().signum() == sign_a {
            a = phi;
        } else {
            b = phi;
        }
        let newton = phi - x.d1() / x.d2();
        let next = if newton > a.min(b) && newton < a.max(b) {
            newton
        } else {
            0.5 * (a + b)
        };
        if next == phi || (b - a).abs() <= 2.0 * f64::EPSILON * phi.abs().max(f64::MIN_POSITIVE) {
            break;
        }
        phi = next;
    }
    Ok(best.expect("the loop evaluates at least once"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn polynomial(phi: f64) -> Result<Jet<3>> {
        // x = (φ − 1)²(φ − 3)... x′ = 0 at φ = 1 and φ = 7/3.
        let x = (phi - 1.0).powi(2) * (phi - 3.0);
        let d1 = (phi - 1.0) * (3.0 * phi - 7.0);
        let d2 = 6.0 * phi - 10.0;
        Ok(Jet::new(x, [d1, d2, 6.0]))
    }

    /// Both roots of x′ = (φ − 1)(3φ − 7) are found to 1 ulp-scale (4e-16): Newton converges
    /// quadratically at simple roots.
    #[test]
    fn finds_both_roots_of_a_cubic_to_full_precision() {
        let dead = DeadPositionSearch::new(0.0..=4.0)
            .with_step(0.1)
            .find_roots(polynomial)
            .unwrap();
        assert_eq!(dead.len(), 2);
        assert!((dead[0].phi - 1.0).abs() <= 4e-16);
        assert!((dead[1].phi - 7.0 / 3.0).abs() <= 4e-16 * 7.0 / 3.0);
        assert!(dead[0].d2 < 0.0 && dead[1].d2 > 0.0);
    }

    /// tan φ has x′ = 1/cos²φ > 0 everywhere: no dead position; and 1/φ-like jumps through a pole
    /// are not reported.
    #[test]
    fn a_pole_is_not_a_dead_position() {
        let jump = |phi: f64| Ok(Jet::new(0.0, [1.0 / (phi - 0.55), 0.0, 0.0]));
        let dead = DeadPositionSearch::new(0.0..=1.0)
            .with_step(0.1)
            .find_roots(jump)
            .unwrap();
        assert!(dead.is_empty());
    }

    /// A negative step, an empty range and a NaN bound are typed errors, not panics.
    #[test]
    fn invalid_sweeps_are_errors() {
        for (range, step) in [(0.0..=1.0, -0.1), (1.0..=0.0, 0.1), (0.0..=f64::NAN, 0.1)] {
            let result = DeadPositionSearch::new(range)
                .with_step(step)
                .find_roots(polynomial);
            assert!(
                matches!(result, Err(Error::InvalidSweep { .. })),
                "{result:?}"
            );
        }
    }
}
