//! What accuracy costs in time: every derivative method of a mechanism (or of a hard formula)
//! run over its sweep against a reference computed in extended precision, and timed side by
//! side in one process (`mechdiff accuracy`).
//!
//! A [`Case`] holds the drive positions, the outputs and their reference values (value, ′, ″,
//! ‴ from the symbolic engine's 256-bit evaluation, kept as double-double numbers) and the
//! [`Method`]s to compare. [`Case::measure`] evaluates every method at every position and
//! reports, per derivative order:
//!
//! - the **scaled error** |x − x_ref| / max_sweep |x_ref| (the output's own scale, so that a
//!   derivative passing through zero does not blow the relative error up), its maximum and
//!   RMS over the sweep and the outputs, and the **digits lost** log₁₀(max error / ε) with ε
//!   the machine epsilon of `f64`;
//! - the **time per drive position**: the median of repeated sweeps, with the fastest and
//!   slowest repeat, and the ratio to the fastest exact method.
//!
//! Finite differences are run at a grid of steps h; the step that minimises the error is
//! found for each order (the U-shaped curve of truncation against rounding error, see
//! [`differences`]). The hard cases (near-singular mechanisms, dead positions, saturating and
//! overflowing functions) are [`formula`] scenes in `scenes/hard/`; [`Case::bounds`] gives the
//! bound every exact method must meet, condition number × ε, the condition number computed
//! from the reference.
//!
//! ```no_run
//! use mechdiff::accuracy::{Timing, whitworth};
//! let shaper = mechdiff::mechanisms::Whitworth::reference();
//! let linkage = whitworth::linkage(&shaper)?;
//! let case = whitworth::case(&shaper, &linkage)?;
//! let report = case.measure(&Timing::default())?;
//! print!("{}", report.table());
//! # Ok::<(), mechdiff::Error>(())
//! ```

pub mod cam;
pub mod differences;
pub(crate) mod double_double;
pub mod evaluator;
pub mod extended_newton;
pub mod formula;
mod method;
#[cfg(feature = "pictures")]
pub mod plot;
pub mod reference;
mod report;
pub mod rotor;
pub mod scene;
pub mod whitworth;

pub use differences::StepScan;
pub use double_double::DoubleDouble;
pub use method::{EPSILON, Evaluate, Failure, Kind, MAX_ORDER, Method, Positions, Values};
pub use reference::Reference;
pub use report::{Measurement, Report};

use std::time::Instant;

use crate::Error;

/// A mechanism or formula, its sweep, its reference values and the methods to compare.
pub struct Case<'a> {
    /// What is measured ("Whitworth, λ = 0.375: ψ, x_C").
    pub title: String,
    /// The outputs' names.
    pub outputs: Vec<String>,
    /// The drive positions of the sweep (rad).
    pub positions: Vec<f64>,
    /// `reference[position][output][order]`, in extended precision.
    pub reference: Vec<Vec<[Reference; MAX_ORDER + 1]>>,
    /// `condition[position][output][order]`: Σ |x ∂f⁽ᵏ⁾/∂x| over the inputs x (drive and
    /// parameters), so that a relative change ε of every input moves f⁽ᵏ⁾ by at most
    /// ε × condition (to first order). `None` where not computed.
    pub condition: Option<Vec<Vec<[f64; MAX_ORDER + 1]>>>,
    /// The exact methods (finite differences are added by [`Case::measure`] from
    /// [`Case::positions_f64`]).
    pub methods: Vec<Method<'a>>,
    /// The outputs' values in `f64` at a drive position, for finite differences.
    pub positions_f64: Positions<'a>,
    /// Errors relative to each reference value (absolute where it is 0) instead of scaled by
    /// the output's max over the sweep: for outputs whose small values matter (a saturating
    /// function's derivative, 4e^−2x for tanh′ at large x).
    pub relative: bool,
    /// Per drive position, the lowest derivative order that jumps there (a cam's segment
    /// joint: the exact methods and the reference take the same one-sided value), or `None`;
    /// empty when nothing jumps. A finite difference's stencil straddles the jump there, so
    /// its errors at these orders are not counted (NaN in [`Case::errors`]): the jump is the
    /// function's, not an error of the method.
    pub jumps: Vec<Option<usize>>,
    /// Lines printed under the title: what the reference is, what was left out and why.
    pub notes: Vec<String>,
}

/// The indices of every k-th of `n` drive positions, the last always kept, k the smallest
/// that leaves at most `count` (all of them if `n ≤ count`; the last alone if `count` is 0
/// or 1): what `--positions` measures.
pub fn thin(n: usize, count: usize) -> Vec<usize> {
    if n <= count {
        return (0..n).collect();
    }
    if count <= 1 {
        return (n.checked_sub(1)).into_iter().collect();
    }
    // Every k-th from the first, plus the last: at most ⌊(n − 1)/k⌋ + 1 ≤ count, and the
    // last adds one only when (n − 1)/k is not a whole number (then the first part has at
    // most count − 1).
    let k = (n - 1).div_ceil(count - 1);
    (0..n).filter(|&i| i % k == 0 || i + 1 == n).collect()
}

/// The most timed repeats per method (`--repeats`): the median and spread settle after a few
/// tens, and every repeat lasts at least [`Timing::minimum_seconds`].
pub const MAX_REPEATS: usize = 1000;

/// How long to time each method.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Timing {
    /// Sweeps timed per method (the median and the spread are over these).
    pub repeats: usize,
    /// Each timed repeat runs the sweep often enough to last at least this long (s).
    pub minimum_seconds: f64,
}

impl Default for Timing {
    /// 15 repeats of at least 2 ms each.
    fn default() -> Self {
        Timing {
            repeats: 15,
            minimum_seconds: 2e-3,
        }
    }
}

impl Timing {
    /// One repeat of one sweep: for tests, where only the errors are read.
    pub fn quick() -> Self {
        Timing {
            repeats: 1,
            minimum_seconds: 0.0,
        }
    }
}

impl Case<'_> {
    /// The case at every k-th drive position only (the last always kept), k the smallest
    /// that leaves at most `count` positions: a quick check of a long sweep. The reference,
    /// condition numbers and jumps are kept with their positions.
    ///
    /// # Errors
    /// [`Error::Reference`] if `count` is 0.
    pub fn thinned(mut self, count: usize) -> Result<Self, Error> {
        if count == 0 {
            return Err(Error::Reference {
                what: self.title,
                reason: "--positions must be at least 1".into(),
            });
        }
        if self.positions.len() <= count {
            return Ok(self);
        }
        let keep = thin(self.positions.len(), count);
        fn pick<T: Clone>(values: &[T], keep: &[usize]) -> Vec<T> {
            if values.is_empty() {
                return Vec::new();
            }
            keep.iter().map(|&i| values[i].clone()).collect()
        }
        self.positions = pick(&self.positions, &keep);
        self.reference = pick(&self.reference, &keep);
        self.condition = self.condition.map(|c| pick(&c, &keep));
        self.jumps = pick(&self.jumps, &keep);
        self.title = format!("{} (thinned to {} by --positions)", self.title, keep.len());
        Ok(self)
    }

    /// The scale of each output and order: max over the sweep of |reference| (1 where the
    /// reference is zero all along: the error is then absolute).
    pub fn scales(&self) -> Vec<[f64; MAX_ORDER + 1]> {
        (0..self.outputs.len())
            .map(|o| {
                std::array::from_fn(|k| {
                    let scale = self
                        .reference
                        .iter()
                        .map(|row| row[o][k].hi.abs())
                        .fold(0.0, f64::max);
                    if scale > 0.0 { scale } else { 1.0 }
                })
            })
            .collect()
    }

    /// The bound every exact method must meet at each position, output and order, in the
    /// case's error measure (scaled, or relative): 16 ε (condition / scale + 1) — the error
    /// that a few roundings of every input and of the result cause, by the computed
    /// condition number. `None` without one.
    pub fn bounds(&self) -> Option<Vec<Vec<[f64; MAX_ORDER + 1]>>> {
        let scales = self.scales();
        let condition = self.condition.as_ref()?;
        Some(
            condition
                .iter()
                .zip(&self.reference)
                .map(|(row, reference)| {
                    row.iter()
                        .zip(&scales)
                        .zip(reference)
                        .map(|((c, s), r)| {
                            std::array::from_fn(|k| {
                                let scale = if self.relative {
                                    Some(r[k].hi.abs()).filter(|&r| r > 0.0).unwrap_or(1.0)
                                } else {
                                    s[k]
                                };
                                16.0 * EPSILON * (c[k] / scale + 1.0)
                            })
                        })
                        .collect()
                })
                .collect(),
        )
    }

    /// Every exact method's errors checked against [`Case::bounds`], per position, output
    /// and order: the [`Violation`]s; a NaN, an
    /// infinite value or an error of the method is an infinite error. The methods are run
    /// once each.
    ///
    /// # Errors
    /// A method's own error if it fails at a position.
    pub fn bound_violations(&mut self) -> Result<Vec<Violation>, Error> {
        let Some(bounds) = self.bounds() else {
            return Ok(Vec::new());
        };
        let scales = self.scales();
        let mut violations = Vec::new();
        let mut methods = std::mem::take(&mut self.methods);
        for method in methods.iter_mut().filter(|m| m.kind == Kind::Exact) {
            let mut values = vec![[f64::NAN; MAX_ORDER + 1]; self.outputs.len()];
            for (i, &phi) in self.positions.iter().enumerate() {
                if (method.evaluate)(phi, &mut values).is_err() {
                    values.iter_mut().for_each(|v| v.fill(f64::NAN));
                }
                for (o, value) in values.iter().enumerate() {
                    for k in 0..=method.order {
                        let r = &self.reference[i][o][k];
                        let scale = if self.relative {
                            Some(r.hi.abs()).filter(|&r| r > 0.0).unwrap_or(1.0)
                        } else {
                            scales[o][k]
                        };
                        let error = if value[k].is_finite() {
                            r.error(value[k]) / scale
                        } else {
                            f64::INFINITY
                        };
                        // NaN errors (never, as written) would count as violations too.
                        if error.partial_cmp(&bounds[i][o][k]) != Some(std::cmp::Ordering::Less)
                            && error != bounds[i][o][k]
                        {
                            violations.push(Violation {
                                method: method.name.clone(),
                                output: self.outputs[o].clone(),
                                order: k,
                                phi,
                                error,
                                bound: bounds[i][o][k],
                            });
                        }
                    }
                }
            }
        }
        self.methods = methods;
        Ok(violations)
    }

    /// Runs every method over the sweep: errors against the reference, then times. Finite
    /// differences are scanned over steps h from 1e-1 to 1e-10 (four per decade) and the
    /// step minimising each order's max error is reported.
    ///
    /// A method that returns NaN or an infinite value, or fails with an error, is not
    /// stopped: its error there is infinite and the first such position is kept
    /// ([`Measurement::failure`]); a method that fails with an error is not timed.
    ///
    /// # Errors
    /// Only if the reference's own `f64` evaluation fails during the step scan.
    pub fn measure(mut self, timing: &Timing) -> Result<Report, Error> {
        if timing.repeats > MAX_REPEATS {
            return Err(Error::OverLimit {
                option: "--repeats",
                value: timing.repeats as u64,
                limit: MAX_REPEATS as u64,
                what: "timed repeats",
                advice: "15 (the default) give a steady median",
            });
        }
        let scales = self.scales();
        let mut measurements = Vec::new();
        let methods = std::mem::take(&mut self.methods);
        for mut method in methods {
            let (errors, mut failure) = self.errors(&mut method, &scales)?;
            let time = self.time(&mut method, &mut failure, timing);
            measurements.push(Measurement::new(&method, errors, failure, time));
        }
        let scans = differences::scan(&self.positions_f64, self.outputs.len(), |method| {
            Ok(self.errors(method, &scales)?.0)
        })?;
        for method in differences::best_methods(&self.positions_f64, &scans, self.outputs.len()) {
            let mut method = method;
            let (errors, mut failure) = self.errors(&mut method, &scales)?;
            let time = self.time(&mut method, &mut failure, timing);
            measurements.push(Measurement::new(&method, errors, failure, time));
        }
        Ok(Report::new(
            self.title.clone(),
            self.notes.clone(),
            self.positions.clone(),
            measurements,
            scans,
        ))
    }

    /// The time per position of `method` (see [`time_method`]); NaN if it failed with an
    /// error in the error pass (its time would be the failure's) or fails while timed (a
    /// repeated sweep carries the drive on by whole turns, see the geometry methods): that
    /// failure is then recorded if none was.
    fn time(
        &self,
        method: &mut Method<'_>,
        failure: &mut Option<Failure>,
        timing: &Timing,
    ) -> [f64; 3] {
        if matches!(
            failure,
            Some(Failure {
                reason: Some(_),
                ..
            })
        ) {
            return [f64::NAN; 3];
        }
        match time_method(method, &self.positions, self.outputs.len(), timing) {
            Ok(time) => time,
            Err(error) => {
                let phi = match &error {
                    Error::Method { phi, .. } => *phi,
                    _ => f64::NAN,
                };
                failure.get_or_insert(Failure {
                    output: self.outputs.join(", "),
                    order: 0,
                    phi,
                    value: f64::NAN,
                    reason: Some(format!("while timed (repeated sweeps): {error}")),
                });
                [f64::NAN; 3]
            }
        }
    }

    /// The scaled errors of `method` at every position: `[position][order]`, the maximum
    /// over the outputs (NaN above the method's order, and for a finite difference at the
    /// orders that jump at that position, see [`Case::jumps`]; infinite where the method
    /// returned NaN or an infinite value), and the first such failure.
    ///
    /// # Errors
    /// The method's own error if it fails at a position.
    pub fn errors(
        &self,
        method: &mut Method<'_>,
        scales: &[[f64; MAX_ORDER + 1]],
    ) -> Result<(Vec<Values>, Option<Failure>), Error> {
        let mut values = vec![[f64::NAN; MAX_ORDER + 1]; self.outputs.len()];
        let mut errors = Vec::with_capacity(self.positions.len());
        let mut failure = None;
        for (&phi, reference) in self.positions.iter().zip(&self.reference) {
            if let Err(error) = (method.evaluate)(phi, &mut values) {
                failure.get_or_insert(Failure {
                    output: self.outputs.join(", "),
                    order: 0,
                    phi,
                    value: f64::NAN,
                    reason: Some(error.to_string()),
                });
                let mut worst = [f64::NAN; MAX_ORDER + 1];
                worst[..=method.order].fill(f64::INFINITY);
                errors.push(worst);
                continue;
            }
            let mut worst = [f64::NAN; MAX_ORDER + 1];
            let counted = match (method.kind, self.jumps.get(errors.len())) {
                (Kind::Approximate { .. }, Some(&Some(jump))) => jump.saturating_sub(1),
                _ => method.order,
            }
            .min(method.order);
            for (o, (value, reference)) in values.iter().zip(reference).enumerate() {
                for k in 0..=counted {
                    let scale = if self.relative {
                        Some(reference[k].hi.abs())
                            .filter(|&r| r > 0.0)
                            .unwrap_or(1.0)
                    } else {
                        scales[o][k]
                    };
                    let error = if value[k].is_finite() {
                        reference[k].error(value[k]) / scale
                    } else {
                        failure.get_or_insert(Failure {
                            output: self.outputs[o].clone(),
                            order: k,
                            phi,
                            value: value[k],
                            reason: None,
                        });
                        f64::INFINITY
                    };
                    worst[k] = if worst[k].is_nan() {
                        error
                    } else {
                        worst[k].max(error)
                    };
                }
            }
            errors.push(worst);
        }
        Ok((errors, failure))
    }
}

/// An exact method's error above its bound ([`Case::bound_violations`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Violation {
    /// The method.
    pub method: String,
    /// The output.
    pub output: String,
    /// The derivative order (0: the value).
    pub order: usize,
    /// The drive position (rad).
    pub phi: f64,
    /// The error (scaled or relative, as the case measures it; ∞ for NaN, ∞ or an error).
    pub error: f64,
    /// The bound it exceeds.
    pub bound: f64,
}

/// The time per drive position (s) of `method` over `positions`: median, fastest and
/// slowest of `timing.repeats` repeats.
fn time_method(
    method: &mut Method<'_>,
    positions: &[f64],
    outputs: usize,
    timing: &Timing,
) -> Result<[f64; 3], Error> {
    let mut values = vec![[f64::NAN; MAX_ORDER + 1]; outputs];
    let mut sweep = |values: &mut [Values]| -> Result<(), Error> {
        for &phi in positions {
            (method.evaluate)(std::hint::black_box(phi), values)?;
            std::hint::black_box(&*values);
        }
        Ok(())
    };
    // Calibrate: sweeps per repeat so that a repeat lasts `minimum_seconds`.
    let start = Instant::now();
    sweep(&mut values)?;
    let once = start.elapsed().as_secs_f64().max(1e-9);
    let sweeps = ((timing.minimum_seconds / once).ceil() as usize).max(1);
    let mut per_position = Vec::with_capacity(timing.repeats.max(1));
    for _ in 0..timing.repeats.max(1) {
        let start = Instant::now();
        for _ in 0..sweeps {
            sweep(&mut values)?;
        }
        let seconds = start.elapsed().as_secs_f64();
        per_position.push(seconds / (sweeps * positions.len().max(1)) as f64);
    }
    per_position.sort_by(f64::total_cmp);
    let median = per_position[per_position.len() / 2];
    Ok([
        median,
        per_position[0],
        per_position[per_position.len() - 1],
    ])
}
