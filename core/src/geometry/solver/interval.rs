//! Between two drive positions: the check that every loop stays assemblable and on its
//! branch over a whole step, and, where it does not, the end of the branch located to full
//! precision.
//!
//! Every closed-form loop reports a **margin** `f(φ)` (see `closed_form`): 1 in the
//! sketch's shape, positive wherever the loop closes on its branch; a simple root of `f` is
//! a **limit position** (beyond it the loop cannot close: the drive must stop), a double
//! root a **change point** (two assembly branches meet: the Jacobian drops rank with a
//! finite limit), and a root of a slide's slope a toggle. Each evaluation in `Dual2_64`
//! gives `f`, `f′`, `f″` exactly.
//!
//! **The step check** ([`passes`]). A step `[a, b]` of length `h` is accepted for a loop
//! when `f(a), f(b) > 0` and the cubic Hermite interpolant `H` of `f, f′` at both ends stays
//! above its error bound: `f − H = f⁗(ξ)/24 · t²(1 − t)² h⁴` (t = (φ − a)/h), at most
//! `h⁴ max|f⁗| / 384`, and `H″ − f″` at either end is `h² f⁗ / 12` (to leading order), so
//! `e = max |H″ − f″|` at the ends estimates `h⁴ |f⁗|/12` and `|f − H| ≤ e / 32` — the test
//! uses `e / 4`, eight times that, and requires `min H − e/4 > TOUCH`: a margin whose
//! minimum over the step is within [`TOUCH`] of zero is not shown positive (a double root
//! between the two positions — a change point — makes `min H` exactly 0 up to rounding,
//! which may come out positive), so the step is halved and the end of the branch decides. A margin can dip to
//! zero between two positions only by a feature its value, slope and curvature at both
//! ends do not show, i.e. through derivatives of order five and higher; steps are
//! therefore also capped ([`LONGEST_TURN`] rad, or that fraction of the sketch for a
//! displacement drive): over 1/8 rad the geometric functions of a linkage (trigonometric
//! polynomials and their square roots, away from their zeros) are resolved by their
//! Taylor polynomials to ~(1/8)⁵/5! ≈ 3e-7 of their size. This is a subdivision argument
//! on analytic functions, with a safety factor, not interval arithmetic: a margin with a
//! dip narrower than the cap and invisible to three derivatives at both ends of every
//! sub-step would escape it.
//!
//! **The end of a branch.** When halving a step no longer helps, the step's end is
//! classified from the loop's margin at the last position `φ₀` where it closes: the
//! quadratic model `f − f′²/(2f″)` is the margin's minimum nearby. Clearly negative: a
//! limit position, refined by Newton on `f` (quadratic convergence from the assembling
//! side) to full precision ([`Error::Blocked`]). Zero within [`TOUCH`]: a change point,
//! located by Newton on `f′` ([`Error::ChangePoint`]). A blocked range narrower than
//! `2 √(2 TOUCH / f″)` (≈ 3e-7 rad for `f″ ~ 1`) is indistinguishable from a change point
//! in f64 and reported as one.

use super::Tracker;
use crate::Error;
use crate::geometry::closed_form::Failure;
use num_dual::Dual2_64;

/// The longest step checked at once (rad; for a displacement drive, this fraction of the
/// sketch's size).
pub(crate) const LONGEST_TURN: f64 = 0.125;

/// A margin whose local minimum is within this of zero touches it (a change point) rather
/// than crossing it or passing above it. Margins are 1 in the sketch; near a double root
/// a discriminant keeps only rounding (~10 ε: `d² l₁² − g²` cancels terms of size 1 in
/// the margin's units), and a simple root at slope f′ gives a model minimum −f′²/(2f″).
/// A loop whose margin truly passes a minimum above this (a slotted lever whose pin
/// passes 1e-6 of its length from the hinge: 2.5e-13) is regular and computed.
pub(crate) const TOUCH: f64 = 1e-14;

/// A lower bound of a margin over a step above this (times 1 + the size of the margin's
/// terms) shows it positive without the exact test of [`passes`]: ~10⁸ times that test's
/// rounding.
const CLEARLY_POSITIVE: f64 = 1e-6;

/// Sub-steps (accepted or not) allowed in one move: 10⁵ steps of 1/8 rad are ~2 000
/// turns; a move asking for more is refused ([`Error::MoveTooLong`]) rather than run for
/// hours.
pub(crate) const MAX_SUBSTEPS: usize = 100_000;

/// Newton iterations allowed when refining a limit position or a change point.
const REFINE: usize = 60;

/// Bisections allowed when bracketing where a loop stops closing (a bracket of f64 halves
/// to adjacent numbers in at most ~2100 steps; 200 cover any bracket above 2⁻²⁰⁰ of φ).
const BISECT: usize = 200;

/// Positions sampled across a smallest step whose ends both close, when the margin's model
/// does not place its zero inside the step.
const SAMPLES: usize = 64;

/// Whether a margin with values `a` at the start and `b` at the end of a step of length `h`
/// (each with its first and second derivative in φ) is shown positive over the whole step
/// (see the module documentation).
pub(crate) fn passes(a: Dual2_64, b: Dual2_64, h: f64) -> bool {
    if !(a.re > 0.0 && b.re > 0.0) {
        return false;
    }
    if h == 0.0 || (a == b && a.v1 == 0.0 && a.v2 == 0.0) {
        return true;
    }
    // In t = (φ − a)/h ∈ [0, 1]: H = p0 + m0 t + c2 t² + c3 t³.
    let (p0, p1) = (a.re, b.re);
    let (m0, m1) = (h * a.v1, h * b.v1);
    let d = p1 - p0;
    let c2 = 3.0 * d - 2.0 * m0 - m1;
    let c3 = -2.0 * d + m0 + m1;
    let curvature_gap =
        ((2.0 * c2 - h * h * a.v2).abs()).max((2.0 * c2 + 6.0 * c3 - h * h * b.v2).abs());
    // Cheap check first: H − L = t(1 − t)[(m0 − d)(1 − t) − (m1 − d)t] with L the chord,
    // so min H ≥ min(p0, p1) − max(|m0 − d|, |m1 − d|)/4. A step whose margin clears
    // that bound by far more than the rounding of the exact test below (margins are 1 in
    // the sketch) passes that test too: its extrema need not be found.
    let chord_gap = (m0 - d).abs().max((m1 - d).abs());
    let size = p0.max(p1) + chord_gap + curvature_gap;
    if p0.min(p1) - (chord_gap + curvature_gap) / 4.0 > CLEARLY_POSITIVE * (1.0 + size) {
        return true;
    }
    let at = |t: f64| p0 + t * (m0 + t * (c2 + t * c3));
    let mut low = p0.min(p1);
    // H′ = m0 + 2 c2 t + 3 c3 t²: its roots in (0, 1).
    let (qa, qb, qc) = (3.0 * c3, 2.0 * c2, m0);
    if qa == 0.0 {
        if qb != 0.0 {
            low = low.min(at((-qc / qb).clamp(0.0, 1.0)));
        }
    } else {
        let disc = qb * qb - 4.0 * qa * qc;
        if disc >= 0.0 {
            let r = disc.sqrt();
            for t in [(-qb + r) / (2.0 * qa), (-qb - r) / (2.0 * qa)] {
                low = low.min(at(t.clamp(0.0, 1.0)));
            }
        }
    }
    let bound = low - curvature_gap / 4.0;
    // Above the band where a touching margin (a change point) leaves only rounding.
    bound > TOUCH
}

impl Tracker<'_> {
    /// Where the first loop that stops closing between the current position and `phi`
    /// (the move started at `start`) does so; `tried` is the smallest step's end that
    /// failed, with the loop that failed it (and how, if its formula failed there).
    /// `None`: the margin stays clear of zero up to `tried` (the step's check failed by
    /// rounding only), so `tried` may be accepted. `toggle_at_phi`: the condition at `phi`
    /// if its formula found `phi` itself a toggle.
    pub(super) fn end_of_branch(
        &mut self,
        start: f64,
        phi: f64,
        tried: f64,
        (first, failure): (usize, Option<Failure>),
        toggle_at_phi: Option<f64>,
    ) -> Option<Error> {
        let a = self.phi;
        let at_tried = self.stops_closing(tried);
        // Bracket the first position where a loop stops closing: lo closes, hi does not.
        let (mut lo, mut hi) = (a, tried);
        let (mut l, mut why) = at_tried.unwrap_or((first, failure));
        if at_tried.is_some() {
            for _ in 0..BISECT {
                let mid = lo + 0.5 * (hi - lo);
                if mid == lo || mid == hi {
                    break;
                }
                match self.stops_closing(mid) {
                    Some(found) => ((l, why), hi) = (found, mid),
                    None => lo = mid,
                }
            }
        }
        let joints = self.loop_joints(&self.loops[l]);
        let Some(f) = self.margin(l, lo).filter(|_| self.closed.has_margin(l)) else {
            let failure = why.unwrap_or(Failure::Singular {
                condition: f64::INFINITY,
            });
            return Some(self.closed_failure(hi, l, failure));
        };
        if !self.closed.is_root(l) {
            // A slide's slot turning parallel to its guide: a toggle.
            let at = self.refine(l, lo, false).unwrap_or(hi);
            return Some(Error::Singular {
                phi: at,
                condition: f64::INFINITY,
                joints,
            });
        }
        let model_minimum = if f.v2 > 0.0 {
            f.re - f.v1 * f.v1 / (2.0 * f.v2)
        } else {
            f64::NEG_INFINITY
        };
        if model_minimum >= -TOUCH {
            let at = self.refine(l, lo, true).unwrap_or(lo);
            if at_tried.is_none() {
                let inside = (at - a) * (at - tried) <= 0.0;
                let lowest = if inside {
                    self.margin(l, at).map_or(0.0, |f| f.re)
                } else {
                    f64::INFINITY
                };
                if lowest > TOUCH {
                    return None;
                }
            }
            return Some(Error::ChangePoint { phi: at, joints });
        }
        let refined = self.refine(l, lo, false);
        let limit = if at_tried.is_some() {
            // Bisected where the loops stop closing; Newton polishes that to the margin's
            // zero (which rounding may place a few 1e-12 past the bisection's bracket).
            refined.unwrap_or(lo)
        } else {
            // Both ends of the step close (`lo` is its start). Newton from there may leave
            // the step for a zero behind the start (the limit on the other side, seen at
            // sketch sizes of 1e8 m); then the margin's first zero inside the step, if any.
            match refined.filter(|&x| bracketed(x, a, tried)) {
                Some(limit) => limit,
                None => self.first_zero_sampled(l, a, tried)?,
            }
        };
        if let Some(condition) = toggle_at_phi {
            // Asked for the limit position itself (within the band where the loop's
            // condition exceeds the threshold): a toggle there.
            if (limit - phi).abs() <= (phi - lo).abs() {
                return Some(Error::Singular {
                    phi,
                    condition,
                    joints,
                });
            }
        }
        Some(Error::Blocked {
            from: start,
            to: phi,
            limit,
            joints,
        })
    }

    /// The loop that stops closing at `phi` (its formula fails, or its margin is not
    /// positive), if any.
    fn stops_closing(&mut self, phi: f64) -> Option<(usize, Option<Failure>)> {
        match self.evaluate_closed(phi) {
            Err((l, failure)) => Some((l, Some(failure))),
            Ok(()) => (self.closed_margins.iter())
                .position(|m| m.re.is_nan() || m.re <= 0.0)
                .map(|l| (l, None)),
        }
    }

    /// The first zero of loop `l`'s margin from `a` towards `b` (both close), found where a
    /// sample of [`SAMPLES`] evenly spaced positions first sees it not positive and then
    /// bisected to full precision; `None` if every sample is clear of zero.
    fn first_zero_sampled(&mut self, l: usize, a: f64, b: f64) -> Option<f64> {
        let positive = |this: &mut Self, x: f64| this.margin(l, x).is_some_and(|f| f.re > 0.0);
        let mut lo = a;
        for k in 1..=SAMPLES {
            let x = a + (b - a) * (k as f64 / SAMPLES as f64);
            if positive(self, x) {
                lo = x;
                continue;
            }
            let mut hi = x;
            for _ in 0..BISECT {
                let mid = lo + 0.5 * (hi - lo);
                if mid == lo || mid == hi {
                    break;
                }
                if positive(self, mid) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            return Some(lo);
        }
        None
    }

    /// Loop `l`'s margin at `phi`, if the loops before it close there.
    fn margin(&mut self, l: usize, phi: f64) -> Option<Dual2_64> {
        match self.evaluate_closed(phi) {
            Err((k, _)) if k < l => None,
            _ => Some(self.closed_margins[l]),
        }
    }

    /// Newton from `from` on loop `l`'s margin (`extremum`: on its derivative), to full
    /// precision.
    fn refine(&mut self, l: usize, from: f64, extremum: bool) -> Option<f64> {
        let mut x = from;
        for _ in 0..REFINE {
            let f = self.margin(l, x)?;
            let (value, slope) = if extremum { (f.v1, f.v2) } else { (f.re, f.v1) };
            if value == 0.0 {
                break;
            }
            let next = x - value / slope;
            if !next.is_finite() || next == x {
                break;
            }
            let moved = (next - x).abs();
            x = next;
            if moved <= f64::EPSILON * x.abs() {
                break;
            }
        }
        Some(x)
    }
}

/// Whether `x` lies between `a` and `b`, or within a few rounding errors of either end (a
/// root polished by Newton may land an ulp past the bracket's end).
fn bracketed(x: f64, a: f64, b: f64) -> bool {
    let slack = 4.0 * f64::EPSILON * x.abs().max(a.abs()).max(b.abs());
    x >= a.min(b) - slack && x <= a.max(b) + slack
}

#[cfg(test)]
mod tests {
    use super::*;

    fn jet(f: impl Fn(f64) -> [f64; 3], x: f64) -> Dual2_64 {
        let [a, b, c] = f(x);
        Dual2_64::new(a, b, c)
    }

    #[test]
    fn a_dip_below_zero_between_positive_ends_fails() {
        // f = (φ − 1)² − 0.01: positive at 0.8 and 1.2, negative at 1 (a blocked range of
        // width 0.2 inside the step).
        let f = |x: f64| [(x - 1.0).powi(2) - 0.01, 2.0 * (x - 1.0), 2.0];
        assert!(!passes(jet(f, 0.8), jet(f, 1.2), 0.4));
        // Either side of it the check passes.
        assert!(passes(jet(f, 0.5), jet(f, 0.85), 0.35));
    }

    #[test]
    fn a_touch_fails_and_a_clear_margin_passes() {
        // f = sin²φ touches zero at 0 (a change point); over [−0.1, 0.1] the check fails,
        // over [0.1, 0.2] (f ≥ 0.0099) it passes.
        let f = |x: f64| [x.sin().powi(2), (2.0 * x).sin(), 2.0 * (2.0 * x).cos()];
        assert!(!passes(jet(f, -0.1), jet(f, 0.1), 0.2));
        assert!(passes(jet(f, 0.1), jet(f, 0.2), 0.1));
    }

    #[test]
    fn inconsistent_curvature_fails() {
        // Ends that agree with a cubic in value and slope but whose curvatures say the
        // function bends far away from it (a quartic bump): not accepted.
        let f = |x: f64| {
            let b = 40.0;
            [
                0.1 + 0.0 * x - b * x * x * (1.0 - x) * (1.0 - x),
                -b * (2.0 * x * (1.0 - x) * (1.0 - x) - 2.0 * x * x * (1.0 - x)),
                -b * (2.0 - 12.0 * x + 12.0 * x * x),
            ]
        };
        // At 0 and 1 value 0.1, slope 0, but f(½) = 0.1 − 40/16 < 0.
        assert!(!passes(jet(f, 0.0), jet(f, 1.0), 1.0));
    }
}
