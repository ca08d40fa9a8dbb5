//! The follower's travel between two cam angles: where it turns back, and where it reaches
//! a displacement.
//!
//! A cam joint drives a linkage through the follower's displacement s(θ). Between two cam
//! angles the linkage passes every displacement s takes there, not only the two ends: a cam
//! that lifts the follower past the linkage's reach and back inside one step would otherwise
//! be jumped. The displacements s takes over `[θ₀, θ₁]` are the union of its monotone
//! stretches, so the linkage's own proof of motion (its tracker's checked, halved steps and
//! refined limits) covers the step when it is walked through the follower's **reversals**,
//! the cam angles where s turns back ([`CamProgram::reversals`]); a limit found in the
//! follower's displacement is taken back to the cam angle where s reaches it on its
//! monotone stretch ([`CamProgram::reaching`], bisection to adjacent floating-point
//! numbers).
//!
//! How the reversals are found, from the program's exact derivatives:
//!
//! - the step is cut at every segment boundary and every break of a law (where s′ may
//!   jump, and where a rise meets a return);
//! - a standard law is monotone over its segment (f′ ≥ 0 on [0, 1] for every law: see
//!   [`super::law`]; a dwell is constant), so its stretches need nothing more;
//! - on a formula segment, s′ (with s″ and s‴, exact from dual numbers) is shown of one
//!   sign over each sub-step of at most 1/8 rad by the linkage's own step test
//!   ([`crate::geometry`]'s Hermite test on a margin, applied to ±s′); a sub-step it
//!   cannot show is halved, down to [`SHORTEST`], and what is left unshown is kept as a
//!   candidate point;
//! - finally the displacement is compared along the candidate points in walk order, and the
//!   points where its direction changes (across any dwell) are the reversals.
//!
//! A point kept that is not a reversal costs one move of the linkage; a reversal missed
//! would cost a jump, so a candidate is kept whenever in doubt. What a sub-step shorter
//! than [`SHORTEST`] could hide is an excursion of at most ½ max|s″| · SHORTEST² beyond
//! its ends (1e-18 of s″'s size), far below any linkage's resolution.

use std::f64::consts::TAU;

use num_dual::Dual2_64;

use super::law::Side;
use super::program::{CamProgram, SegmentMotion};
use crate::error::{Error, Result};
use crate::geometry::solver::interval::{LONGEST_TURN, passes};

/// A sub-step of a formula segment shorter than this (rad) is not halved further: its
/// middle is kept as a candidate reversal.
pub const SHORTEST: f64 = 1e-9;

/// Sub-steps of formula segments examined in one call: a formula that turns back more
/// often than this within one step is refused ([`Error::MoveTooLong`]) rather than
/// followed for hours.
pub const MAX_SUBSTEPS: usize = 100_000;

/// Bisections when locating a cam angle: a bracket of f64 halves to adjacent numbers in at
/// most ~2100 steps.
const BISECT: usize = 2200;

impl CamProgram {
    /// The cam angles strictly between `from` and `to`, in order from `from`, where the
    /// follower turns back (s changes direction; see the module documentation), with the
    /// one-sided limits `side` at boundaries. Walking s(from), s at each reversal, then
    /// s(to) passes every displacement the follower takes between `from` and `to`. A move
    /// longer than a turn gives the reversals of its first turn (by then the follower has
    /// passed every displacement of its program).
    ///
    /// ```
    /// use mechdiff_core::cams::{CamProgram, MotionLaw, Segment, Side};
    /// use std::f64::consts::PI;
    /// // Rise 20 over a half turn, return over the other: the follower turns back at π.
    /// let program = CamProgram::new(vec![
    ///     Segment::law(MotionLaw::Cycloidal, 20.0, PI),
    ///     Segment::law(MotionLaw::Cycloidal, -20.0, PI),
    /// ], 0.0).unwrap();
    /// let turns = program.reversals(3.0, 3.5, Side::Right).unwrap();
    /// assert_eq!(turns.len(), 1);
    /// assert!((turns[0] - PI).abs() < 1e-15);
    /// assert!(program.reversals(0.5, 3.0, Side::Right).unwrap().is_empty());
    /// ```
    ///
    /// # Errors
    /// [`Error::MoveTooLong`] if a formula segment needs more than [`MAX_SUBSTEPS`]
    /// sub-steps to be followed between `from` and `to`.
    pub fn reversals(&self, from: f64, to: f64, side: Side) -> Result<Vec<f64>> {
        if !(from.is_finite() && to.is_finite()) || from == to {
            return Ok(Vec::new());
        }
        let end = if (to - from).abs() > TAU {
            from + TAU.copysign(to - from)
        } else {
            to
        };
        let (lo, hi) = (from.min(end), from.max(end));
        let mut points = vec![lo];
        points.extend(self.knots(lo, hi));
        points.push(hi);
        let mut candidates = Vec::new();
        let mut budget = MAX_SUBSTEPS;
        for pair in points.windows(2) {
            let (p, q) = (pair[0], pair[1]);
            let (index, _) = self.locate(0.5 * (p + q), side);
            if let SegmentMotion::Formula(_) = self.segment(index).motion {
                self.formula_candidates(index, p, q, &mut candidates, &mut budget)
                    .ok_or(Error::MoveTooLong {
                        from,
                        to,
                        steps: MAX_SUBSTEPS,
                        longest: SHORTEST,
                    })?;
            }
        }
        if points.len() == 2 && candidates.is_empty() {
            // One stretch of one segment, monotone: nothing to evaluate.
            return Ok(Vec::new());
        }
        points.extend(candidates);
        // In walk order, from `from`.
        points.sort_by(|a, b| ((a - from) * (end - from)).total_cmp(&((b - from) * (end - from))));
        points.dedup();
        let s = |t: f64| self.svaj(t, side).value;
        let mut reversals = Vec::new();
        // The direction of travel so far (0 before any), and the last point where s moved
        // in it (a dwell after it keeps the direction: the follower turns back where it
        // stopped).
        let (mut direction, mut last) = (0.0, points[0]);
        let mut previous = s(points[0]);
        for &t in &points[1..] {
            let now = s(t);
            if now != previous {
                let step = (now - previous).signum();
                if direction != 0.0 && step != direction {
                    reversals.push(last);
                }
                (direction, last) = (step, t);
            }
            previous = now;
        }
        Ok(reversals)
    }

    /// The first cam angle from `from` towards `to` where the displacement reaches
    /// `target`, where s is monotone between `from` and `to` (a stretch between two
    /// reversals): bisection on s(θ) − target to adjacent floating-point numbers, the one
    /// nearer `target` in displacement. A target outside s's range there gives the nearer
    /// end.
    ///
    /// ```
    /// use mechdiff_core::cams::{CamProgram, MotionLaw, Segment, Side};
    /// use std::f64::consts::PI;
    /// let program = CamProgram::new(vec![
    ///     Segment::law(MotionLaw::SimpleHarmonic, 2.0, PI),
    ///     Segment::law(MotionLaw::SimpleHarmonic, -2.0, PI),
    /// ], 0.0).unwrap();
    /// // s = 1 − cos θ reaches 1.5 at θ = 2π/3 on the rise, at 4π/3 on the return.
    /// assert!((program.reaching(0.0, PI, 1.5, Side::Right) - 2.0 * PI / 3.0).abs() < 1e-15);
    /// assert!((program.reaching(PI, 5.0, 1.5, Side::Right) - 4.0 * PI / 3.0).abs() < 1e-15);
    /// ```
    pub fn reaching(&self, from: f64, to: f64, target: f64, side: Side) -> f64 {
        let s = |t: f64| self.svaj(t, side).value;
        let direction = (s(to) - s(from)).signum();
        let reached = |t: f64| (s(t) - target) * direction >= 0.0;
        if s(to) == s(from) || reached(from) {
            return from;
        }
        if !reached(to) {
            return to;
        }
        let (mut before, mut after) = (from, to);
        for _ in 0..BISECT {
            let mid = before + 0.5 * (after - before);
            if mid == before || mid == after {
                break;
            }
            if reached(mid) {
                after = mid;
            } else {
                before = mid;
            }
        }
        if (s(before) - target).abs() < (s(after) - target).abs() {
            before
        } else {
            after
        }
    }

    /// The segment boundaries and law breaks strictly between `lo` and `hi` (at most a
    /// turn apart), in increasing order.
    fn knots(&self, lo: f64, hi: f64) -> Vec<f64> {
        let (mut index, local) = self.locate(lo, Side::Right);
        let mut base = lo - local;
        let mut knots = Vec::new();
        // Each segment of the (at most two) turns met once.
        for _ in 0..=2 * self.len() {
            let (start, end) = (base + self.start(index), base + self.end(index));
            for &b in self.segment(index).breaks() {
                let at = start + b * (end - start);
                if lo < at && at < hi {
                    knots.push(at);
                }
            }
            if end >= hi {
                break;
            }
            if end > lo {
                knots.push(end);
            }
            index += 1;
            if index == self.len() {
                (index, base) = (0, base + TAU);
            }
        }
        knots
    }

    /// Pushes onto `out` the points of `[p, q]` (inside formula segment `index`) where s′
    /// is not shown of one sign (see the module documentation); `None` once `budget`
    /// sub-steps are used up.
    fn formula_candidates(
        &self,
        index: usize,
        p: f64,
        q: f64,
        out: &mut Vec<f64>,
        budget: &mut usize,
    ) -> Option<()> {
        // s′ with its first two derivatives, on the segment's own formula at its ends.
        let slope = |t: f64| {
            let j = self.svaj_on(index, t);
            let [s1, s2, s3] = j.derivatives;
            Dual2_64::new(s1, s2, s3)
        };
        let pieces = ((q - p) / LONGEST_TURN).ceil().max(1.0) as usize;
        let at = |k: usize| {
            if k == pieces {
                q
            } else {
                p + (q - p) * k as f64 / pieces as f64
            }
        };
        let mut stack: Vec<(f64, f64)> = (0..pieces).rev().map(|k| (at(k), at(k + 1))).collect();
        while let Some((x, y)) = stack.pop() {
            *budget = budget.checked_sub(1)?;
            let (a, b) = (slope(x), slope(y));
            let sign = a.re.signum();
            if a.re * b.re > 0.0 && passes(a * sign, b * sign, y - x) {
                continue;
            }
            let mid = x + 0.5 * (y - x);
            if y - x <= SHORTEST || mid == x || mid == y {
                if a.re * b.re < 0.0 {
                    out.push(self.root_of_slope(index, x, y));
                } else {
                    out.push(mid);
                }
                continue;
            }
            stack.push((mid, y));
            stack.push((x, mid));
        }
        Some(())
    }

    /// Where s′ changes sign between `x` and `y` on segment `index` (bisection).
    fn root_of_slope(&self, index: usize, x: f64, y: f64) -> f64 {
        let slope = |t: f64| self.svaj_on(index, t).derivatives[0];
        let (mut before, mut after) = (x, y);
        let sign = slope(x).signum();
        for _ in 0..BISECT {
            let mid = before + 0.5 * (after - before);
            if mid == before || mid == after {
                break;
            }
            if slope(mid).signum() == sign {
                before = mid;
            } else {
                after = mid;
            }
        }
        before
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cams::{Formula, MotionLaw, Segment};
    use std::f64::consts::PI;

    /// The standard laws need no search (see the module documentation): f′ ≥ 0 on [0, 1]
    /// for every law, at 10⁴ + 1 points on each side of every break (exact, from dual
    /// numbers; a rounding of −1e-15 of f′'s size of 1 is allowed at the ends, where
    /// f′ = 0).
    #[test]
    fn every_law_is_monotone_over_its_segment() {
        for &law in MotionLaw::ALL {
            for side in [Side::Left, Side::Right] {
                for k in 0..=10_000 {
                    let u = num_dual::Dual64::from(k as f64 / 1e4).derivative();
                    let slope = law.rise(u, side).eps;
                    assert!(slope >= -1e-15, "{law} at u = {}: f′ = {slope}", u.re);
                }
            }
        }
    }

    /// s = 0.01 (2 − cos 3x) over one turn turns back at x = kπ/3, where s′ = 0.03 sin 3x
    /// changes sign (the root located to adjacent numbers: |s″| = 0.09 there, so 8e-15 rad
    /// is a few roundings of x); both walk directions find the same points in their order.
    #[test]
    fn a_formula_turns_back_where_its_slope_changes_sign() {
        let f = Formula::parse("0.01*(2 - cos(3*x))").unwrap();
        let program = CamProgram::new(vec![Segment::formula(f, TAU)], 0.0).unwrap();
        let forward = program.reversals(0.1, 6.2, Side::Right).unwrap();
        assert_eq!(forward.len(), 5, "{forward:?}");
        for (k, t) in forward.iter().enumerate() {
            let want = (k + 1) as f64 * PI / 3.0;
            assert!((t - want).abs() < 8e-15, "{t} vs {want}");
        }
        let mut backward = program.reversals(6.2, 0.1, Side::Right).unwrap();
        backward.reverse();
        assert_eq!(backward.len(), 5, "{backward:?}");
        for (a, b) in forward.iter().zip(&backward) {
            assert!((a - b).abs() < 8e-15, "{a} vs {b}");
        }
        // Between two reversals the follower moves one way: none.
        assert!(program.reversals(1.1, 2.0, Side::Right).unwrap().is_empty());
    }

    /// A rise, a dwell and a return inside one move: the follower turns back once, where
    /// the rise ends (the dwell holds it there); a move of several turns gives the first
    /// turn's reversals.
    #[test]
    fn a_dwell_between_rise_and_return_is_one_reversal() {
        let program = CamProgram::new(
            vec![
                Segment::law(MotionLaw::Cycloidal, 1.0, PI / 2.0),
                Segment::law(MotionLaw::Dwell, 0.0, PI / 2.0),
                Segment::law(MotionLaw::Cycloidal, -1.0, PI),
            ],
            0.0,
        )
        .unwrap();
        let turns = program.reversals(1.0, 3.5, Side::Right).unwrap();
        assert_eq!(turns.len(), 1, "{turns:?}");
        assert!((turns[0] - PI / 2.0).abs() < 1e-15);
        // From 1 over 3 turns: the top (π/2) and the bottom (2π) of the first turn.
        let turns = program
            .reversals(1.0, 1.0 + 3.0 * TAU, Side::Right)
            .unwrap();
        assert_eq!(turns.len(), 2, "{turns:?}");
        assert!((turns[0] - PI / 2.0).abs() < 1e-15 && (turns[1] - TAU).abs() < 1e-14);
    }

    /// A formula that turns back more often than the sub-steps allow is refused.
    #[test]
    fn a_wildly_oscillating_formula_is_refused() {
        let f = Formula::parse("1e-6*(2 - cos(2e6*pi*u))").unwrap();
        let program = CamProgram::new(vec![Segment::formula(f, TAU)], 0.0).unwrap();
        let e = program.reversals(0.0, 3.0, Side::Right).unwrap_err();
        assert!(matches!(e, Error::MoveTooLong { .. }), "{e:?}");
    }
}
