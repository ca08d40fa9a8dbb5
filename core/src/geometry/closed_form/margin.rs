//! Loop margins: how far each closed-form loop is from the end of its branch (see the
//! module documentation of `closed_form`), the square root and the slope that measure it,
//! and the rounding it amplifies.

use super::{ClosedForm, Failure};
use crate::Scalar;

/// A loop's distance from the end of its branch, as computed by its formula: the value
/// (`disc` of a square-root pattern, in the units of `size`; the slope of a slide,
/// dimensionless) and the size it is measured against at this pose (`size = 1` for a
/// slope, `1` and `1` for a pattern that always closes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Margin<D> {
    pub value: D,
    pub size: f64,
    /// `size` as a function of the drive position (what the generated guards measure the
    /// condition with; see `trace`).
    pub now: D,
    /// Whether the value is a discriminant (its square root is the loop's lever) rather
    /// than a slope; `None`: the loop always closes.
    pub root: Option<bool>,
}

impl<D: Scalar> Margin<D> {
    pub(super) fn none() -> Self {
        Margin {
            value: D::from(1.0),
            size: 1.0,
            now: D::from(1.0),
            root: None,
        }
    }
}

impl ClosedForm {
    /// How much loop `l` amplifies rounding at a pose where its margin is `margin`
    /// (1 in the sketch's shape): `1/√margin` for a square-root pattern (the lever's
    /// length in the sketch over its length now), `1/|margin|` for a slide's slope, 1 for
    /// a loop that always closes.
    pub fn amplification(&self, l: usize, margin: f64) -> f64 {
        amplification(self.kinds.get(l).copied().flatten(), margin)
    }

    /// Whether loop `l`'s amplification at `margin` is surely at most `limit` (≥ 1), told
    /// without a square root or a division: `|margin|` at least twice the bound's (`1/limit²`
    /// for a square-root pattern, `1/limit` for a slope), so rounding cannot turn the
    /// verdict; `false` near the bound and for NaN (then compute [`ClosedForm::amplification`]).
    pub fn surely_within(&self, l: usize, margin: f64, limit: f64) -> bool {
        match self.kinds.get(l).copied().flatten() {
            Some(true) => margin.abs() * (limit * limit) >= 2.0,
            Some(false) => margin.abs() * limit >= 2.0,
            None => true,
        }
    }

    /// Whether loop `l` has a margin that can vanish (a square root or a slope).
    pub fn has_margin(&self, l: usize) -> bool {
        self.kinds.get(l).copied().flatten().is_some()
    }

    /// Whether loop `l`'s margin is a discriminant (it ends at a limit position or a
    /// change point) rather than a slope (a toggle of a slide).
    pub fn is_root(&self, l: usize) -> bool {
        self.kinds.get(l).copied().flatten() == Some(true)
    }

    /// `σ √disc`, or why there is none: a toggle if `√(size / |disc|)` (the condition
    /// estimate, in the loop's own length scale: `size`, the value of `now`, is the square of what `√disc`
    /// is measured against now, e.g. `l₁² l₂²` for a dyad) exceeds the limit, else a loop
    /// that cannot close by `gap` (m) if `disc < 0`. Records the margin.
    #[inline]
    pub(super) fn root<D: Scalar>(
        &self,
        disc: D,
        now: D,
        gap: f64,
        branch: f64,
        margin: &mut Margin<D>,
    ) -> Result<D, Failure> {
        let size = now.re();
        *margin = Margin {
            value: disc,
            size,
            now,
            root: Some(true),
        };
        let condition = (size / disc.re().abs()).sqrt();
        if condition.is_nan() || condition > self.limit {
            return Err(Failure::Singular { condition });
        }
        if disc.re() < 0.0 {
            return Err(Failure::Unassemblable { residual: gap });
        }
        Ok(disc.sqrt() * branch)
    }

    /// A slide's slope `cross(v, u)` (both unit vectors), or a toggle if it is too small.
    #[inline]
    pub(super) fn slope<D: Scalar>(&self, slope: D, margin: &mut Margin<D>) -> Result<D, Failure> {
        *margin = Margin {
            value: slope,
            size: 1.0,
            now: D::from(1.0),
            root: Some(false),
        };
        let condition = 1.0 / slope.re().abs();
        if condition.is_nan() || condition > self.limit {
            return Err(Failure::Singular { condition });
        }
        Ok(slope)
    }
}

/// How much a loop amplifies rounding at a pose where its margin is `margin`: `root` is
/// `Some(true)` for a square-root pattern (`1/√|margin|`), `Some(false)` for a slide's
/// slope (`1/|margin|`), `None` for a loop that always closes (1).
pub(crate) fn amplification(root: Option<bool>, margin: f64) -> f64 {
    match root {
        Some(true) => 1.0 / margin.abs().sqrt(),
        Some(false) => 1.0 / margin.abs(),
        None => 1.0,
    }
}
