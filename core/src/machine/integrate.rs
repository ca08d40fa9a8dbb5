//! What every integration of the equation of motion shares: the tolerances, the integrator
//! (DOP853 of `differential-equations`: order 8 with error control and a dense output of
//! order 7) and the location of an event on the dense output.

use super::error::MotionError;
use differential_equations::methods::{DormandPrince, Ordinary};
use differential_equations::prelude::{ExplicitRungeKutta, IVP, Interpolation, ODE};

/// DOP853 on a state of two numbers.
pub(crate) type Dop853 = ExplicitRungeKutta<Ordinary, DormandPrince, f64, [f64; 2], 8, 12, 16>;

/// The largest step count a run may be given.
pub const MAX_STEPS: usize = 100_000_000;

/// Error control of an integration.
///
/// ```
/// use mechdiff_core::machine::Tolerances;
/// let t = Tolerances::default().with_relative(1e-12);
/// assert!(t.validate().is_ok());
/// assert!(Tolerances::default().with_relative(0.0).validate().is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerances {
    /// Relative tolerance of each step (> 0; below 1e-14 round-off dominates).
    pub relative: f64,
    /// Absolute tolerance of each step (> 0), in the units of the state.
    pub absolute: f64,
    /// The most steps a run takes (at most [`MAX_STEPS`]).
    pub max_steps: usize,
}

impl Default for Tolerances {
    /// Relative and absolute 1e-10, at most one million steps.
    fn default() -> Self {
        Tolerances {
            relative: 1e-10,
            absolute: 1e-10,
            max_steps: 1_000_000,
        }
    }
}

impl Tolerances {
    /// Sets the relative tolerance.
    pub fn with_relative(mut self, relative: f64) -> Self {
        self.relative = relative;
        self
    }

    /// Sets the absolute tolerance.
    pub fn with_absolute(mut self, absolute: f64) -> Self {
        self.absolute = absolute;
        self
    }

    /// Sets the step limit.
    pub fn with_max_steps(mut self, max_steps: usize) -> Self {
        self.max_steps = max_steps;
        self
    }

    /// Checks the numbers.
    ///
    /// # Errors
    /// [`MotionError::InvalidValue`] for a tolerance that is not positive and finite, or a
    /// step limit of 0 or above [`MAX_STEPS`].
    pub fn validate(&self) -> Result<(), MotionError> {
        for (what, v) in [
            ("relative tolerance (must be > 0)", self.relative),
            ("absolute tolerance (must be > 0)", self.absolute),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(MotionError::InvalidValue { what, value: v });
            }
        }
        if !(1..=MAX_STEPS).contains(&self.max_steps) {
            return Err(MotionError::InvalidValue {
                what: "step limit (must be 1 to 10⁸)",
                value: self.max_steps as f64,
            });
        }
        Ok(())
    }

    /// The integrator with these tolerances; `steps` is the number of steps left.
    pub(crate) fn method(&self, steps: usize) -> Dop853 {
        ExplicitRungeKutta::dop853()
            .rtol(self.relative)
            .atol(self.absolute)
            .max_steps(steps.max(1))
    }
}

/// The zero of `g(t, y(t))` on the step `[t0, t1]` of `interpolator`, with `g0` and `g1` its
/// values at the ends, of opposite signs (or `g1 = 0`): the Illinois variant of regula falsi,
/// down to adjacent floating-point times. Gives the time, the state and `|g|` there.
pub(crate) fn locate<I: Interpolation<f64, [f64; 2]> + ?Sized>(
    interpolator: &mut I,
    (mut t0, mut g0): (f64, f64),
    (mut t1, mut g1): (f64, f64),
    y1: [f64; 2],
    g: impl Fn(f64, &[f64; 2]) -> f64,
) -> (f64, [f64; 2], f64) {
    let mut best = (t1, y1, g1.abs());
    let mut side = 0;
    for _ in 0..200 {
        if g1 == 0.0 || (t1 - t0).abs() <= 2.0 * f64::EPSILON * t0.abs().max(t1.abs()) {
            break;
        }
        let mut t = (t0 * g1 - t1 * g0) / (g1 - g0);
        if !(t > t0.min(t1) && t < t0.max(t1)) {
            t = 0.5 * (t0 + t1);
        }
        let Ok(y) = interpolator.interpolate(t) else {
            break;
        };
        let v = g(t, &y);
        if v.abs() < best.2 {
            best = (t, y, v.abs());
        }
        if v == 0.0 {
            break;
        }
        if (v > 0.0) == (g1 > 0.0) {
            t1 = t;
            g1 = v;
            if side == 1 {
                g0 *= 0.5;
            }
            side = 1;
        } else {
            t0 = t;
            g0 = v;
            if side == -1 {
                g1 *= 0.5;
            }
            side = -1;
        }
    }
    best
}

/// The state at `to` of the system `ode` integrated from `(from, y)` with `tolerances`: a
/// value of full accuracy where the dense output has less (the interpolant of the crate's
/// DOP853 is of lower order than its steps).
pub(crate) fn state_at<F: ODE<f64, [f64; 2]>>(
    ode: &F,
    (from, y): (f64, [f64; 2]),
    to: f64,
    tolerances: &Tolerances,
) -> Result<[f64; 2], MotionError> {
    if to == from {
        return Ok(y);
    }
    let solution = IVP::ode(ode, from, to, y)
        .method(tolerances.method(tolerances.max_steps))
        .solve()
        .map_err(failed)?;
    solution.y.last().copied().ok_or(MotionError::Integrator {
        time: from,
        message: "no step was taken".to_owned(),
    })
}

/// Whether `g` crossed zero on a step from `g0` to `g1` (leaving zero does not count).
pub(crate) fn crossed(g0: f64, g1: f64) -> bool {
    g0 != 0.0 && (g1 == 0.0 || (g0 > 0.0) != (g1 > 0.0))
}

/// The integrator's error as a [`MotionError`].
pub(crate) fn failed(e: differential_equations::prelude::Error<f64, [f64; 2]>) -> MotionError {
    use differential_equations::prelude::Error;
    let time = match &e {
        Error::MaxSteps { t, .. } | Error::StepSize { t, .. } | Error::Stiffness { t, .. } => *t,
        _ => f64::NAN,
    };
    MotionError::Integrator {
        time,
        message: format!("{e:?}"),
    }
}
