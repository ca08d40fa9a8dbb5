//! Grashof's criterion: which links of a four-bar turn fully, from its four lengths alone;
//! and its counterpart for a slider-crank (the crank turns fully iff r + |e| ≤ l).
//!
//! With s the shortest, l the longest and p, q the other two lengths of a four-bar loop:
//!
//! | inequality | frame is | class |
//! |---|---|---|
//! | s + l < p + q | next to the shortest (the shortest is the input) | crank-rocker |
//! | s + l < p + q | next to the shortest (the shortest is the output) | rocker-crank |
//! | s + l < p + q | the shortest | double-crank (drag link) |
//! | s + l < p + q | opposite the shortest (the shortest is the coupler) | double-rocker (Grashof) |
//! | s + l = p + q | any | change point: the loop can fold flat, where its two branches meet |
//! | s + l > p + q | any | triple-rocker (non-Grashof): no link turns fully |
//!
//! Strict Grashof linkages have exactly one shortest link: with two equal shortest links
//! s + l ≥ p + q always (p + q = s + m, m ≤ l).

use super::words::short;
use std::fmt;

/// The four lengths of a four-bar loop (m): frame d, input a, coupler b, output c.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FourBarLengths {
    /// Frame d: the distance between the two frame pivots.
    pub frame: f64,
    /// Input a: the input link's pivot on the frame to its joint with the coupler.
    pub input: f64,
    /// Coupler b: between its joints with the input and the output.
    pub coupler: f64,
    /// Output (follower) c: its pivot on the frame to its joint with the coupler.
    pub output: f64,
}

/// The role of a link in a four-bar loop.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// The frame (the link both pivots are on; the ground in a mechanism).
    Frame,
    /// The input link (crank or rocker), pivoted on the frame.
    Input,
    /// The coupler, joining input and output.
    Coupler,
    /// The output link (follower), pivoted on the frame.
    Output,
}

impl Role {
    /// The role's name, as used in messages ("frame", "input", …).
    pub fn name(self) -> &'static str {
        match self {
            Role::Frame => "frame",
            Role::Input => "input",
            Role::Coupler => "coupler",
            Role::Output => "output",
        }
    }
}

/// One length of an inequality, with the link it belongs to.
#[derive(Debug, Clone, PartialEq)]
pub struct LengthTerm {
    /// The link's name in the mechanism.
    pub link: String,
    /// Its role in the loop.
    pub role: Role,
    /// Its length (m).
    pub length: f64,
}

impl fmt::Display for LengthTerm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} {} m", self.link, short(self.length))
    }
}

/// Grashof's class of a four-bar loop, for its frame and its input.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GrashofClass {
    /// s + l < p + q and the input is the shortest link: the input turns fully, the output
    /// rocks.
    CrankRocker,
    /// s + l < p + q and the output is the shortest link: the output turns fully, the input
    /// rocks.
    RockerCrank,
    /// s + l < p + q and the frame is the shortest link: input and output both turn fully
    /// (a drag link).
    DoubleCrank,
    /// s + l < p + q and the coupler is the shortest link: input and output rock, the
    /// coupler turns fully relative to the frame (Grashof double-rocker).
    DoubleRocker,
    /// s + l = p + q (within the loop's tolerance): the loop can fold flat; there its two
    /// assembly branches meet.
    ChangePoint,
    /// s + l > p + q: no link turns fully relative to another (non-Grashof triple-rocker).
    TripleRocker,
}

impl GrashofClass {
    /// The class in the field's words ("crank-rocker", "double-crank (drag link)", …).
    pub fn name(self) -> &'static str {
        match self {
            GrashofClass::CrankRocker => "crank-rocker",
            GrashofClass::RockerCrank => "rocker-crank",
            GrashofClass::DoubleCrank => "double-crank (drag link)",
            GrashofClass::DoubleRocker => "double-rocker (Grashof)",
            GrashofClass::ChangePoint => "change point",
            GrashofClass::TripleRocker => "triple-rocker (non-Grashof)",
        }
    }
}

/// Grashof's inequality s + l vs p + q of a four-bar loop, with the links it names, and the
/// class it gives for the loop's frame and input.
#[derive(Debug, Clone, PartialEq)]
pub struct Grashof {
    /// The class.
    pub class: GrashofClass,
    /// s, the shortest link (of lengths equal within the tolerance, the first in the order
    /// frame, input, coupler, output).
    pub shortest: LengthTerm,
    /// l, the longest link (the first of equals, as for s).
    pub longest: LengthTerm,
    /// p and q, the other two (in the order frame, input, coupler, output).
    pub others: [LengthTerm; 2],
    /// s + l (m).
    pub s_plus_l: f64,
    /// p + q (m).
    pub p_plus_q: f64,
    /// |s + l − (p + q)| at most this (m) is a change point: what the lengths' rounding
    /// can account for (see [`length_tolerance`]).
    pub tolerance: f64,
}

impl Grashof {
    /// Grashof's class of a loop of `lengths` whose links are named `names` (frame, input,
    /// coupler, output), with `tolerance` (m) deciding equality.
    ///
    /// ```
    /// use mechdiff_core::metrics::{FourBarLengths, Grashof, GrashofClass};
    /// let lengths = FourBarLengths { frame: 0.4, input: 0.1, coupler: 0.45, output: 0.3 };
    /// let g = Grashof::classify(&lengths, ["ground", "crank", "coupler", "rocker"], 1e-15);
    /// assert_eq!(g.class, GrashofClass::CrankRocker);
    /// assert_eq!((g.shortest.link.as_str(), g.longest.link.as_str()), ("crank", "coupler"));
    /// assert_eq!(
    ///     g.to_string(),
    ///     "crank-rocker: s + l = crank 0.1 m + coupler 0.45 m = 0.55 m \
    ///      < p + q = ground 0.4 m + rocker 0.3 m = 0.7 m"
    /// );
    /// ```
    pub fn classify(lengths: &FourBarLengths, names: [&str; 4], tolerance: f64) -> Grashof {
        let values = [
            lengths.frame,
            lengths.input,
            lengths.coupler,
            lengths.output,
        ];
        let roles = [Role::Frame, Role::Input, Role::Coupler, Role::Output];
        let term = |i: usize| LengthTerm {
            link: names[i].to_owned(),
            role: roles[i],
            length: values[i],
        };
        // Of lengths equal within the tolerance, the first in the order frame, input,
        // coupler, output is named (not the one rounding made a hair shorter).
        let (min, max) = (values.iter()).fold((f64::INFINITY, 0.0f64), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
        let s = (0..4).find(|&i| values[i] <= min + tolerance).unwrap_or(0);
        let l = (0..4)
            .find(|&i| i != s && values[i] >= max - tolerance)
            .unwrap_or((s + 1) % 4);
        let mut rest = (0..4).filter(|&i| i != s && i != l);
        let (p, q) = (rest.next().unwrap_or(s), rest.next().unwrap_or(l));
        let (s_plus_l, p_plus_q) = (values[s] + values[l], values[p] + values[q]);
        let excess = s_plus_l - p_plus_q;
        let class = if excess.abs() <= tolerance {
            GrashofClass::ChangePoint
        } else if excess > 0.0 {
            GrashofClass::TripleRocker
        } else {
            match roles[s] {
                Role::Input => GrashofClass::CrankRocker,
                Role::Output => GrashofClass::RockerCrank,
                Role::Frame => GrashofClass::DoubleCrank,
                Role::Coupler => GrashofClass::DoubleRocker,
            }
        };
        Grashof {
            class,
            shortest: term(s),
            longest: term(l),
            others: [term(p), term(q)],
            s_plus_l,
            p_plus_q,
            tolerance,
        }
    }
}

impl fmt::Display for Grashof {
    /// `crank-rocker: s + l = crank 0.1 m + coupler 0.45 m = 0.55 m < p + q = … = 0.7 m`
    /// (lengths to six decimals).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let relation = match self.class {
            GrashofClass::ChangePoint => "=",
            GrashofClass::TripleRocker => ">",
            _ => "<",
        };
        write!(
            f,
            "{}: s + l = {} + {} = {} m {relation} p + q = {} + {} = {} m",
            self.class.name(),
            self.shortest,
            self.longest,
            short(self.s_plus_l),
            self.others[0],
            self.others[1],
            short(self.p_plus_q)
        )
    }
}

/// Relative rounding allowed per length by [`length_tolerance`], in units of `f64::EPSILON`.
pub const ROUNDING_ULPS: f64 = 16.0;

/// The tolerance (m) within which two sums of a loop's lengths are equal: the lengths are
/// distances between sketch points, so each carries the rounding of its points'
/// coordinates (≤ ε/2 of the largest coordinate `magnitude` each, ≤ ε·magnitude·√2 for a
/// difference) and of `hypot` (ε of the length). Four lengths summed: the difference
/// s + l − (p + q) is off by at most about 4ε·(magnitude·√2 + length) + ε·Σ;
/// [`ROUNDING_ULPS`]` · ε · (magnitude + Σ lengths)` bounds that with a margin of two. A
/// loop closer to the change point than rounding can tell is one: the solver meets its
/// branches' meeting point anyway (its loop condition grows without bound there).
pub fn length_tolerance(lengths: &[f64], magnitude: f64) -> f64 {
    let total: f64 = lengths.iter().map(|l| l.abs()).sum();
    ROUNDING_ULPS * f64::EPSILON * (magnitude.abs() + total)
}

/// The lengths of a slider-crank loop (m): crank r, rod l, and the offset e of the slider's
/// path from the crank pivot (signed: positive to the left of the guide's direction).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SliderCrankLengths {
    /// Crank r: its pivot to the crank pin.
    pub crank: f64,
    /// Rod (connecting rod) l: crank pin to the slider's pin.
    pub rod: f64,
    /// Offset e: signed distance of the slider pin's path from the crank pivot (m).
    pub offset: f64,
}

/// Whether a slider-crank's crank turns fully: r + |e| vs l.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SliderCrankClass {
    /// r + |e| < l: the crank turns fully, the slider reciprocates.
    Crank,
    /// r + |e| = l (within the loop's tolerance): the rod stands perpendicular to the path
    /// once per turn, where the loop's two branches meet.
    ChangePoint,
    /// r + |e| > l: the crank rocks between two positions where the rod stands perpendicular
    /// to the slider's path.
    Rocker,
}

impl SliderCrankClass {
    /// The class in words.
    pub fn name(self) -> &'static str {
        match self {
            SliderCrankClass::Crank => "crank turns fully",
            SliderCrankClass::ChangePoint => "change point",
            SliderCrankClass::Rocker => "crank rocks",
        }
    }
}

/// The criterion r + |e| ≤ l of a slider-crank, with its numbers.
#[derive(Debug, Clone, PartialEq)]
pub struct SliderCrankCriterion {
    /// The class.
    pub class: SliderCrankClass,
    /// r + |e| (m).
    pub crank_plus_offset: f64,
    /// l (m).
    pub rod: f64,
    /// |r + |e| − l| at most this (m) is a change point (see [`length_tolerance`]).
    pub tolerance: f64,
}

impl SliderCrankCriterion {
    /// The criterion for `lengths`, with `tolerance` (m) deciding equality.
    ///
    /// ```
    /// use mechdiff_core::metrics::{SliderCrankClass, SliderCrankCriterion, SliderCrankLengths};
    /// let lengths = SliderCrankLengths { crank: 0.1, rod: 0.4, offset: -0.012 };
    /// let c = SliderCrankCriterion::classify(&lengths, 1e-15);
    /// assert_eq!(c.class, SliderCrankClass::Crank);
    /// assert_eq!(c.crank_plus_offset, 0.112);
    /// ```
    pub fn classify(lengths: &SliderCrankLengths, tolerance: f64) -> SliderCrankCriterion {
        let crank_plus_offset = lengths.crank + lengths.offset.abs();
        let excess = crank_plus_offset - lengths.rod;
        let class = if excess.abs() <= tolerance {
            SliderCrankClass::ChangePoint
        } else if excess < 0.0 {
            SliderCrankClass::Crank
        } else {
            SliderCrankClass::Rocker
        };
        SliderCrankCriterion {
            class,
            crank_plus_offset,
            rod: lengths.rod,
            tolerance,
        }
    }
}

impl fmt::Display for SliderCrankCriterion {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let relation = match self.class {
            SliderCrankClass::Crank => "<",
            SliderCrankClass::ChangePoint => "=",
            SliderCrankClass::Rocker => ">",
        };
        write!(
            f,
            "{}: r + |e| = {} m {relation} l = {} m",
            self.class.name(),
            short(self.crank_plus_offset),
            short(self.rod)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const NAMES: [&str; 4] = ["ground", "crank", "coupler", "rocker"];

    /// a + b = c + d is a change point only within the rounding tolerance: a frame 1e-9 m
    /// longer makes a Grashof crank-rocker, 1e-9 m shorter a triple-rocker.
    #[test]
    fn a_change_point_is_equality_within_rounding() {
        for (offset, class) in [
            (0.0, GrashofClass::ChangePoint),
            (1e-9, GrashofClass::CrankRocker),
            (-1e-9, GrashofClass::TripleRocker),
        ] {
            let lengths = FourBarLengths {
                frame: 0.2 + offset,
                input: 0.1,
                coupler: 0.3,
                output: 0.2,
            };
            let all = [
                lengths.frame,
                lengths.input,
                lengths.coupler,
                lengths.output,
            ];
            let tolerance = length_tolerance(&all, 0.3);
            assert!(tolerance < 1e-13, "{tolerance}");
            assert_eq!(Grashof::classify(&lengths, NAMES, tolerance).class, class);
        }
    }

    /// r + |e| = l is the slider-crank's change point; the sign of the offset does not
    /// matter.
    #[test]
    fn a_slider_crank_turns_iff_crank_plus_offset_is_at_most_the_rod() {
        for (offset, class) in [
            (0.1, SliderCrankClass::ChangePoint),
            (-0.1, SliderCrankClass::ChangePoint),
            (0.099, SliderCrankClass::Crank),
            (-0.101, SliderCrankClass::Rocker),
        ] {
            let lengths = SliderCrankLengths {
                crank: 0.2,
                rod: 0.3,
                offset,
            };
            let tolerance = length_tolerance(&[0.2, 0.3, offset], 0.3);
            assert_eq!(
                SliderCrankCriterion::classify(&lengths, tolerance).class,
                class
            );
        }
    }
}
