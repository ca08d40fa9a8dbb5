//! Where and how a cam program is discontinuous.
//!
//! At every segment boundary (the end of the turn included, where the last segment meets
//! the first) and at every break inside a law, the one-sided values of s, s′, s″, s‴ are
//! compared. A jump in s′ is an infinite acceleration (an impulse: the follower is struck);
//! a jump in s″ is an infinite jerk. The fundamental law of cam design asks for s, s′ and
//! s″ continuous over the whole turn (finite jerk).
//!
//! A derivative "jumps" when its one-sided values differ by more than [`JUMP_TOLERANCE`]
//! times the largest magnitude that derivative takes over the turn (so rounding in the
//! evaluation is never reported as a jump).

use std::f64::consts::TAU;
use std::fmt;

use super::extrema::maximize;
use super::law::Side;
use super::program::CamProgram;

/// Relative size (of the derivative's largest magnitude over the turn) above which a
/// difference of one-sided values is a jump.
pub const JUMP_TOLERANCE: f64 = 1e-9;

/// Where a boundary is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BoundaryKind {
    /// Between two segments (`before` ends, `after` starts; indices from 0).
    Segments {
        /// The segment that ends there.
        before: usize,
        /// The segment that starts there.
        after: usize,
    },
    /// A break between two pieces of one segment's law.
    InsideSegment {
        /// The segment.
        segment: usize,
    },
}

/// The one-sided values at one boundary.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Boundary {
    /// Cam angle (rad, in [0, 2π); the end of the turn is reported at 0).
    pub angle: f64,
    /// Between segments, or inside one.
    pub kind: BoundaryKind,
    /// s, s′, s″, s‴ from below.
    pub left: [f64; 4],
    /// s, s′, s″, s‴ from above.
    pub right: [f64; 4],
    /// For each order 0..=3, whether that derivative jumps.
    pub jumps: [bool; 4],
}

impl Boundary {
    /// The lowest order that jumps (0 = displacement, 1 = s′, …), if any.
    pub fn first_jump(&self) -> Option<usize> {
        self.jumps.iter().position(|&j| j)
    }

    /// right − left of derivative `order`.
    pub fn jump(&self, order: usize) -> f64 {
        self.right[order] - self.left[order]
    }
}

/// Every boundary of a program with its one-sided values and jumps.
///
/// ```
/// use mechdiff_core::cams::{CamProgram, ContinuityReport, MotionLaw, Segment};
/// use std::f64::consts::PI;
/// let program = CamProgram::new(vec![
///     Segment::law(MotionLaw::UniformVelocity, 80.0, PI),
///     Segment::law(MotionLaw::UniformVelocity, -80.0, PI),
/// ], 0.0).unwrap();
/// let report = ContinuityReport::new(&program);
/// // s′ jumps at 0 (= 2π) and at π: impulses of acceleration.
/// assert_eq!(report.boundaries.iter().filter(|b| b.first_jump() == Some(1)).count(), 2);
/// assert!(!report.satisfies_fundamental_law());
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct ContinuityReport {
    /// The boundaries in order of cam angle, starting at 0.
    pub boundaries: Vec<Boundary>,
    /// The largest |s|, |s′|, |s″|, |s‴| over the turn (the scale of the jump test).
    pub scale: [f64; 4],
}

impl ContinuityReport {
    /// Evaluates the one-sided values at every boundary and break of `program`.
    pub fn new(program: &CamProgram) -> Self {
        let scale = derivative_peaks(program);
        let n = program.len();
        let mut places: Vec<(f64, BoundaryKind)> = Vec::new();
        for index in 0..n {
            places.push((
                program.start(index),
                BoundaryKind::Segments {
                    before: (index + n - 1) % n,
                    after: index,
                },
            ));
            let segment = program.segments().nth(index).expect("index < len");
            let (a, b) = (program.start(index), program.end(index));
            for &fraction in segment.breaks() {
                places.push((
                    a + fraction * (b - a),
                    BoundaryKind::InsideSegment { segment: index },
                ));
            }
        }
        let boundaries = places
            .into_iter()
            .map(|(angle, kind)| {
                let (left, right) = match kind {
                    BoundaryKind::Segments { before, after } => {
                        let end = if after == 0 { TAU } else { angle };
                        (program.svaj_on(before, end), program.svaj_on(after, angle))
                    }
                    BoundaryKind::InsideSegment { .. } => (
                        program.svaj(angle, Side::Left),
                        program.svaj(angle, Side::Right),
                    ),
                };
                let left = [left.value, left.d1(), left.d2(), left.d3()];
                let right = [right.value, right.d1(), right.d2(), right.d3()];
                let jumps =
                    std::array::from_fn(|k| (right[k] - left[k]).abs() > JUMP_TOLERANCE * scale[k]);
                Boundary {
                    angle,
                    kind,
                    left,
                    right,
                    jumps,
                }
            })
            .collect();
        ContinuityReport { boundaries, scale }
    }

    /// Whether s, s′ and s″ are continuous over the whole turn (finite jerk everywhere).
    pub fn satisfies_fundamental_law(&self) -> bool {
        self.boundaries
            .iter()
            .all(|b| !b.jumps[..3].contains(&true))
    }

    /// The boundaries where derivative `order` jumps.
    pub fn jumps_of(&self, order: usize) -> impl Iterator<Item = &Boundary> {
        self.boundaries.iter().filter(move |b| b.jumps[order])
    }
}

/// The largest |s|, |s′|, |s″|, |s‴| over the turn: per segment (and per piece of its law),
/// ends included as one-sided values; NaN if a formula is not a number somewhere.
pub fn derivative_peaks(program: &CamProgram) -> [f64; 4] {
    let mut peaks = [0.0f64; 4];
    for index in 0..program.len() {
        let segment = program.segments().nth(index).expect("index < len");
        let (a, b) = (program.start(index), program.end(index));
        let mut cuts = vec![a];
        cuts.extend(segment.breaks().iter().map(|f| a + f * (b - a)));
        cuts.push(b);
        for piece in cuts.windows(2) {
            let (lo, hi) = (piece[0], piece[1]);
            let mid = 0.5 * (lo + hi);
            let at = |t: f64, k: usize| {
                let side = if t < mid { Side::Right } else { Side::Left };
                let jet = if t == a || t == b {
                    program.svaj_on(index, t)
                } else {
                    program.svaj(t, side)
                };
                [jet.value, jet.d1(), jet.d2(), jet.d3()][k].abs()
            };
            for (k, peak) in peaks.iter_mut().enumerate() {
                let (_, value) = maximize(|t| at(t, k), lo, hi, 32);
                // A NaN anywhere is the answer (f64::max would drop it).
                *peak = if value.is_nan() || peak.is_nan() {
                    f64::NAN
                } else {
                    peak.max(value)
                };
            }
        }
    }
    peaks
}

impl fmt::Display for ContinuityReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        const NAMES: [&str; 4] = ["s", "s′", "s″", "s‴"];
        const MEANING: [&str; 4] = [
            "the displacement itself jumps",
            "infinite acceleration (an impulse: the follower is struck)",
            "infinite jerk",
            "a jump of jerk (finite)",
        ];
        for b in &self.boundaries {
            let place = match b.kind {
                BoundaryKind::Segments { before, after } => {
                    format!("segments {} → {}", before + 1, after + 1)
                }
                BoundaryKind::InsideSegment { segment } => {
                    format!("inside segment {}", segment + 1)
                }
            };
            let angle = b.angle.to_degrees();
            match b.first_jump() {
                None => writeln!(f, "  {angle:>9.4}°  {place}: s, s′, s″, s‴ continuous")?,
                Some(k) => writeln!(
                    f,
                    "  {angle:>9.4}°  {place}: {} jumps from {:.6} to {:.6} (by {:+.6}): {}",
                    NAMES[k],
                    b.left[k],
                    b.right[k],
                    b.jump(k),
                    MEANING[k]
                )?,
            }
        }
        if self.satisfies_fundamental_law() {
            writeln!(
                f,
                "  fundamental law of cam design: met (s, s′, s″ continuous)"
            )
        } else {
            writeln!(
                f,
                "  fundamental law of cam design: NOT met (s, s′ or s″ jumps above)"
            )
        }
    }
}
