//! Finite differences in the report: central, forward and Richardson-extrapolated central
//! differences, scanned over the step h to find the step that minimises each order's error.
//!
//! With samples xₖ = x(φ + kh):
//!
//! - **central** (O(h²)): [`CentralDifference::stencil`] — x′ ≈ (x₁ − x₋₁)/2h,
//!   x″ ≈ (x₁ − 2x₀ + x₋₁)/h², x‴ ≈ (x₂ − 2x₁ + 2x₋₁ − x₋₂)/2h³;
//! - **forward** (O(h)): x′ ≈ (x₁ − x₀)/h, x″ ≈ (x₂ − 2x₁ + x₀)/h²,
//!   x‴ ≈ (x₃ − 3x₂ + 3x₁ − x₀)/h³;
//! - **Richardson** (O(h⁴)): (4 C(h/2) − C(h))/3 with C the central differences, whose error
//!   expansions hold even powers of h only.
//!
//! The truncation error falls as hᵖ and the rounding error grows as ε/hⁿ for the n-th
//! derivative: the error against h is U-shaped, and its minimum is found on a grid of four
//! steps per decade from 1e-1 to 1e-10, not assumed.

use mechdiff_core::method::CentralDifference;

use super::method::{Kind, MAX_ORDER, Method, Positions, Values};
use crate::Error;

/// A finite-difference scheme.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scheme {
    /// Central differences, O(h²).
    Central,
    /// Forward differences, O(h).
    Forward,
    /// Richardson extrapolation of central differences at h and h/2, O(h⁴).
    Richardson,
}

impl Scheme {
    /// Every scheme, in the order of the report.
    pub const ALL: [Scheme; 3] = [Scheme::Central, Scheme::Forward, Scheme::Richardson];

    /// The scheme's name in the report.
    pub fn name(self) -> &'static str {
        match self {
            Scheme::Central => "central",
            Scheme::Forward => "forward",
            Scheme::Richardson => "Richardson",
        }
    }

    /// Value and first three derivatives of every output at `phi` with step `h`; `x` holds
    /// scratch space of one value per output.
    fn apply(
        self,
        f: &Positions<'_>,
        phi: f64,
        h: f64,
        scratch: &mut [Vec<f64>; 5],
        out: &mut [Values],
    ) -> Result<(), Error> {
        let offsets: [f64; 5] = match self {
            Scheme::Central => [-2.0, -1.0, 0.0, 1.0, 2.0],
            Scheme::Forward => [0.0, 1.0, 2.0, 3.0, 0.0],
            // The central stencil at h (±h, ±2h) and at h/2 (±h/2, ±h): x(φ ± h/2) are the
            // two extra samples, in the slots of x₋₂ … (see below).
            Scheme::Richardson => [-2.0, -1.0, 0.0, 1.0, 2.0],
        };
        let samples = if self == Scheme::Forward { 4 } else { 5 };
        for (x, &k) in scratch.iter_mut().zip(&offsets).take(samples) {
            f(phi + k * h, x)?;
        }
        match self {
            Scheme::Central => {
                for (o, v) in out.iter_mut().enumerate() {
                    let d = CentralDifference::stencil([0, 1, 2, 3, 4].map(|s| scratch[s][o]), h);
                    *v = [scratch[2][o], d[0], d[1], d[2]];
                }
            }
            Scheme::Forward => {
                for (o, v) in out.iter_mut().enumerate() {
                    let [x0, x1, x2, x3] = [0, 1, 2, 3].map(|s| scratch[s][o]);
                    *v = [
                        x0,
                        (x1 - x0) / h,
                        (x2 - 2.0 * x1 + x0) / (h * h),
                        (x3 - 3.0 * x2 + 3.0 * x1 - x0) / (h * h * h),
                    ];
                }
            }
            Scheme::Richardson => {
                let coarse: Vec<[f64; 3]> = (0..out.len())
                    .map(|o| CentralDifference::stencil([0, 1, 2, 3, 4].map(|s| scratch[s][o]), h))
                    .collect();
                // The fine stencil at h/2 needs x(φ ± h/2) besides x(φ ± h).
                let (m1, p1) = (scratch[1].clone(), scratch[3].clone());
                f(phi - 0.5 * h, &mut scratch[1])?;
                f(phi + 0.5 * h, &mut scratch[3])?;
                for (o, v) in out.iter_mut().enumerate() {
                    let fine = CentralDifference::stencil(
                        [m1[o], scratch[1][o], scratch[2][o], scratch[3][o], p1[o]],
                        0.5 * h,
                    );
                    let extrapolated: [f64; 3] =
                        std::array::from_fn(|k| (4.0 * fine[k] - coarse[o][k]) / 3.0);
                    *v = [
                        scratch[2][o],
                        extrapolated[0],
                        extrapolated[1],
                        extrapolated[2],
                    ];
                }
            }
        }
        Ok(())
    }
}

/// A scheme's error over the steps h: the U-shaped curve and its minimum per order.
#[derive(Clone, Debug, PartialEq)]
pub struct StepScan {
    /// The scheme.
    pub scheme: Scheme,
    /// The steps h, decreasing.
    pub steps: Vec<f64>,
    /// `errors[step][order - 1]`: the max scaled error over the sweep and the outputs, for
    /// the orders ′, ″, ‴.
    pub errors: Vec<[f64; MAX_ORDER]>,
    /// Per order ′, ″, ‴: the step with the smallest max error, and that error.
    pub best: [(f64, f64); MAX_ORDER],
}

/// The steps scanned: 10^(−j/4) for j = 4 … 40 (1e-1 to 1e-10).
pub fn steps() -> Vec<f64> {
    (4..=40).map(|j| 10f64.powf(-f64::from(j) / 4.0)).collect()
}

/// A finite-difference method of `scheme` with step `h` over `f`.
pub fn method<'a>(
    f: &'a Positions<'a>,
    scheme: Scheme,
    h: f64,
    outputs: usize,
    name: String,
) -> Method<'a> {
    let mut scratch: [Vec<f64>; 5] = std::array::from_fn(|_| vec![0.0; outputs]);
    Method {
        name,
        kind: Kind::Approximate { step: h },
        order: MAX_ORDER,
        evaluate: Box::new(move |phi, out| scheme.apply(f, phi, h, &mut scratch, out)),
    }
}

/// Every scheme's error over [`steps`] of the outputs `f` (`outputs` of them), with the best
/// step per order: `errors` gives a method's scaled errors at every position of the sweep,
/// `[position][order]` ([`Case::errors`](super::Case::errors)).
///
/// # Errors
/// The evaluation's error if the case's `f64` evaluation fails at a sample (a step that
/// leaves the range where the mechanism assembles).
pub fn scan(
    f: &Positions<'_>,
    outputs: usize,
    mut errors: impl FnMut(&mut Method<'_>) -> Result<Vec<Values>, Error>,
) -> Result<Vec<StepScan>, Error> {
    let steps = steps();
    Scheme::ALL
        .iter()
        .map(|&scheme| {
            let mut worst_per_step = Vec::with_capacity(steps.len());
            for &h in &steps {
                let mut method = method(f, scheme, h, outputs, String::new());
                // A NaN of a finite difference at a too-large step (outside the domain) is
                // an infinite error of that step, not a failure of the report.
                let per_position = errors(&mut method)?;
                let worst = std::array::from_fn(|k| {
                    per_position.iter().map(|e| e[k + 1]).fold(0.0, f64::max)
                });
                worst_per_step.push(worst);
            }
            let best = std::array::from_fn(|k| {
                steps
                    .iter()
                    .zip(&worst_per_step)
                    .map(|(&h, e)| (h, e[k]))
                    .min_by(|a, b| a.1.total_cmp(&b.1))
                    .unwrap_or((f64::NAN, f64::INFINITY))
            });
            Ok(StepScan {
                scheme,
                steps: steps.clone(),
                errors: worst_per_step,
                best,
            })
        })
        .collect()
}

/// The methods at each scheme's best steps: one per distinct best step, named after the
/// orders it is best for ("central h=1e-5 (best ′)").
pub fn best_methods<'a>(
    f: &'a Positions<'a>,
    scans: &[StepScan],
    outputs: usize,
) -> Vec<Method<'a>> {
    let mut methods = Vec::new();
    for scan in scans {
        let mut done: Vec<f64> = Vec::new();
        for (k, &(h, _)) in scan.best.iter().enumerate() {
            if done.contains(&h) || !h.is_finite() {
                continue;
            }
            done.push(h);
            let primes: Vec<&str> = (k..MAX_ORDER)
                .filter(|&j| scan.best[j].0 == h)
                .map(|j| ["′", "″", "‴"][j])
                .collect();
            let name = format!(
                "{} h={h:.1e} (best {})",
                scan.scheme.name(),
                primes.join("")
            );
            methods.push(method(f, scan.scheme, h, outputs, name));
        }
    }
    methods
}
