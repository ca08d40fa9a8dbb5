//! The largest value of a function on an interval: samples, then golden-section search.
//!
//! Used for the peak coefficients of motion laws, the peaks of a cam program's derivatives,
//! the maximum pressure angle and the minimum radius of curvature. A function that is
//! smooth on the interval (the callers split at breaks and segment boundaries) is sampled at
//! `samples + 1` points including both ends; the best sample's neighbourhood is refined by
//! golden-section search to the resolution of `f64` (the abscissa to ~1e-8 of the interval,
//! the value, at a smooth maximum, to rounding). A NaN among the samples is returned as the
//! result, never skipped.

/// Golden-section iterations: 0.618⁸⁰ ≈ 2e-17 of the bracket.
const GOLDEN_ITERATIONS: usize = 80;

/// The abscissa and value of the largest `f` on `[a, b]` (ends included).
pub fn maximize(f: impl Fn(f64) -> f64, a: f64, b: f64, samples: usize) -> (f64, f64) {
    let samples = samples.max(2);
    let at = |k: usize| {
        if k == samples {
            b
        } else {
            a + (b - a) * k as f64 / samples as f64
        }
    };
    let (mut best_k, mut best) = (0, f(a));
    for k in 0..=samples {
        let value = if k == 0 { best } else { f(at(k)) };
        if value.is_nan() {
            // A NaN is not a number to compare: return it, so the caller sees it.
            return (at(k), value);
        }
        if value > best {
            (best_k, best) = (k, value);
        }
    }
    let (mut lo, mut hi) = (at(best_k.saturating_sub(1)), at((best_k + 1).min(samples)));
    let ratio = (5f64.sqrt() - 1.0) / 2.0;
    let mut x1 = hi - ratio * (hi - lo);
    let mut x2 = lo + ratio * (hi - lo);
    let (mut f1, mut f2) = (f(x1), f(x2));
    for _ in 0..GOLDEN_ITERATIONS {
        if hi - lo <= f64::EPSILON * (lo.abs() + hi.abs()) {
            break;
        }
        if f1 < f2 {
            lo = x1;
            (x1, f1) = (x2, f2);
            x2 = lo + ratio * (hi - lo);
            f2 = f(x2);
        } else {
            hi = x2;
            (x2, f2) = (x1, f1);
            x1 = hi - ratio * (hi - lo);
            f1 = f(x1);
        }
    }
    let mut result = (at(best_k), best);
    for (x, value) in [(x1, f1), (x2, f2)] {
        if value > result.1 {
            result = (x, value);
        }
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    /// sin on [0, 3] peaks at π/2 with value 1: the value to 1e-15 (rounding at a smooth
    /// maximum), the abscissa to 1e-7 (√ε resolution of a quadratic maximum).
    #[test]
    fn finds_an_interior_maximum() {
        let (x, value) = maximize(f64::sin, 0.0, 3.0, 16);
        assert!((value - 1.0).abs() < 1e-15);
        assert!((x - std::f64::consts::FRAC_PI_2).abs() < 1e-7);
    }

    /// A NaN inside the interval is the answer, not skipped (callers check it).
    #[test]
    fn a_nan_sample_is_returned() {
        let (_, value) = maximize(|x| if x > 0.5 { f64::NAN } else { x }, 0.0, 1.0, 8);
        assert!(value.is_nan());
    }

    /// An increasing function peaks at the right end, exactly.
    #[test]
    fn finds_a_maximum_at_an_end() {
        assert_eq!(maximize(|x| x, -1.0, 2.0, 8), (2.0, 2.0));
    }
}
