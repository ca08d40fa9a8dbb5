//! The frames of a report that plays the machine's motion in real time: its states at equal
//! steps of simulated time, taken from the integration's records as they stream by, with
//! bounded memory however long the run.
//!
//! Between two consecutive records `(t, φ, φ̇, φ̈)` the state at a frame's time is the cubic
//! Hermite interpolant of φ (with φ̇ at both ends) and of φ̇ (with φ̈ at both ends): of the
//! integration's order within a step, far below what a drawing or a six-digit table shows.
//! The frame's φ̈ and everything else is then evaluated exactly at that `(φ, φ̇)`.
//!
//! The frame step starts at 2⁻²⁰ s and doubles (every other frame dropped) whenever more
//! than [`PLAYBACK_FRAMES`] are held, so every step is a power of two times the first one
//! and the frames of two motions (a start-up and a steady period) can be joined on one clock
//! with one step.

use std::ops::Range;

use crate::scene::outputs::Column;

/// The most frames a report plays (all its motions together).
pub const PLAYBACK_FRAMES: usize = 720;

/// The first frame step (s): 2⁻²⁰ s.
const FIRST_STEP: f64 = 1.0 / 1_048_576.0;

/// The states of one motion at `t₀ + k·step`, kept as the records stream by.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Clocked {
    /// `(t, φ, φ̇)` of each frame, SI.
    pub states: Vec<[f64; 3]>,
    /// The frame step (s).
    pub step: f64,
    /// The last record `(t, φ, φ̇, φ̈)`.
    last: Option<[f64; 4]>,
}

impl Clocked {
    /// Offers the record `(t, φ, φ̇, φ̈)` (in time order): the frames up to `t` are added.
    pub fn push(&mut self, record: [f64; 4]) {
        if self.step == 0.0 {
            self.step = FIRST_STEP;
        }
        let [t1, p1, w1, a1] = record;
        match self.last {
            None => self.add([t1, p1, w1]),
            Some([t0, p0, w0, a0]) if t1 > t0 => {
                let h = t1 - t0;
                loop {
                    let t = self.start() + self.states.len() as f64 * self.step;
                    if t > t1 {
                        break;
                    }
                    let s = (t - t0) / h;
                    let (s2, s3) = (s * s, s * s * s);
                    let [h00, h10, h01, h11] = [
                        2.0 * s3 - 3.0 * s2 + 1.0,
                        s3 - 2.0 * s2 + s,
                        3.0 * s2 - 2.0 * s3,
                        s3 - s2,
                    ];
                    let phi = h00 * p0 + h10 * h * w0 + h01 * p1 + h11 * h * w1;
                    let omega = h00 * w0 + h10 * h * a0 + h01 * w1 + h11 * h * a1;
                    self.add([t, phi, omega]);
                }
            }
            Some(_) => {}
        }
        self.last = Some(record);
    }

    /// The first frame's time.
    fn start(&self) -> f64 {
        self.states.first().map_or(0.0, |s| s[0])
    }

    fn add(&mut self, state: [f64; 3]) {
        self.states.push(state);
        if self.states.len() > PLAYBACK_FRAMES {
            self.coarsen();
        }
    }

    /// Keeps every other frame and doubles the step.
    fn coarsen(&mut self) {
        let mut k = 0;
        self.states.retain(|_| {
            k += 1;
            k % 2 == 1
        });
        self.step *= 2.0;
    }

    /// Coarsens until the step is at least `step` (a power of two times this one's).
    fn coarsen_to(&mut self, step: f64) {
        while self.step < step && !self.states.is_empty() {
            self.coarsen();
        }
    }
}

/// One motion of the playback.
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    /// What it shows (`the start-up`, `one period of the steady state`).
    pub name: String,
    /// Its frames.
    pub frames: Range<usize>,
}

/// The frames of a report's playback: the motion over time (start-up, coast-down), then one
/// period of the steady state, on one clock with one step, each frame a row of the tables'
/// columns evaluated at its state.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Playback {
    /// `clock` (the playback's time, s), then the machine's state columns `t`, `phi`,
    /// `omega`, `alpha`, `M_motor`, `M_drive`, `J`, then the scene's outputs.
    pub columns: Vec<Column>,
    /// One row per frame (SI).
    pub rows: Vec<Vec<f64>>,
    /// The clock's step between frames (s of simulated time).
    pub step: f64,
    /// The motions played, in order.
    pub parts: Vec<Part>,
}

/// The motions' frames on one clock with one step and at most [`PLAYBACK_FRAMES`] in all:
/// each `(name, frames)` coarsened to the common step; empty motions are left out.
pub(crate) fn join(mut motions: Vec<(String, Clocked)>) -> (f64, Vec<(String, Clocked)>) {
    motions.retain(|(_, c)| !c.states.is_empty());
    let mut step = motions.iter().map(|(_, c)| c.step).fold(0.0, f64::max);
    loop {
        for (_, c) in &mut motions {
            c.coarsen_to(step);
        }
        let total: usize = motions.iter().map(|(_, c)| c.states.len()).sum();
        if total <= PLAYBACK_FRAMES {
            break;
        }
        step *= 2.0;
    }
    (step, motions)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A motion with constant acceleration a: φ = ½at², φ̇ = at. The frames lie at equal
    /// steps of time and the cubic Hermite interpolant is exact for it (to rounding, 1e-12);
    /// their number stays within the bound however many records come.
    #[test]
    fn frames_are_at_equal_times_bounded_and_exact_for_a_quadratic_motion() {
        let a = 3.0;
        let mut c = Clocked::default();
        let n = 200_000;
        for k in 0..=n {
            let t = 10.0 * k as f64 / n as f64;
            c.push([t, 0.5 * a * t * t, a * t, a]);
        }
        assert!(c.states.len() <= PLAYBACK_FRAMES && c.states.len() > PLAYBACK_FRAMES / 2);
        for (k, [t, phi, omega]) in c.states.iter().copied().enumerate() {
            assert_eq!(t, k as f64 * c.step);
            assert!((phi - 0.5 * a * t * t).abs() < 1e-12 * (1.0 + phi));
            assert!((omega - a * t).abs() < 1e-12 * (1.0 + omega));
        }
        // The last frame is within one step of the end.
        assert!(10.0 - c.states.last().unwrap()[0] < c.step);
    }

    /// Two motions joined take the coarser step and share the frame bound.
    #[test]
    fn joined_motions_share_one_step_and_the_bound() {
        let mut long = Clocked::default();
        let mut short = Clocked::default();
        for k in 0..=1000 {
            let t = k as f64 * 1e-3;
            long.push([t, t, 1.0, 0.0]);
            short.push([t * 1e-2, t * 1e-2, 1.0, 0.0]);
        }
        let (step, joined) = join(vec![("a".into(), long), ("b".into(), short)]);
        let total: usize = joined.iter().map(|(_, c)| c.states.len()).sum();
        assert!(total <= PLAYBACK_FRAMES);
        for (_, c) in &joined {
            for w in c.states.windows(2) {
                assert!((w[1][0] - w[0][0] - step).abs() < 1e-15);
            }
        }
    }
}
