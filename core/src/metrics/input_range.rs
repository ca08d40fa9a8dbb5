//! How far a loop's input turns, from its lengths alone, and where its transmission angle
//! is extreme: the one algorithm behind four-bars and slider-cranks.
//!
//! In both loops the input angle θ enters the closure only through `c = cos(θ − θ_c)`:
//! - four-bar (θ from the frame line, θ_c = 0): |A O₄|² = a² + d² − 2ad·c must lie in
//!   [(b − c)², (b + c)²];
//! - slider-crank (θ from the guide's direction, θ_c = 90°): the rod's rise
//!   r·sin θ − e = r·c − e must lie in [−l, l].
//!
//! So the loop closes iff `c_low ≤ c ≤ c_high`, and its transmission angle μ decreases as c
//! grows (cos μ = (b² + c² − a² − d² + 2ad·c)/(2bc), resp. (r·c − e)/l): μ = 0 where
//! c = c_high (coupler and follower folded; the rod perpendicular to the path, turned
//! back) and μ = 180° where c = c_low (extended). The input passes θ_c iff c_high ≥ 1 and
//! θ_c + 180° iff c_low ≤ −1; each is decided by the sign of a length margin (four-bar:
//! |a − d| − |b − c| and b + c − a − d; slider-crank: e + l − r and l − r − e) with the
//! loop's rounding tolerance, a margin within it being a change point. μ's minimum over
//! the range is where c is largest (θ_c if the range holds it, else an end), its maximum
//! where c is smallest.

use std::f64::consts::{PI, TAU};

/// A position of a loop's input: its angle, and the drive position there when the input is
/// the mechanism's drive.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InputPosition {
    /// The input angle θ (rad): from the frame line O_input → O_output for a four-bar, from
    /// the guide's direction for a slider-crank; counter-clockwise.
    pub angle: f64,
    /// The drive position φ there (rad), when the loop's input is driven; the one nearest
    /// the sketch's drive position for a fully turning input.
    pub drive: Option<f64>,
}

/// What stops an input at an end of its range: the loop's coupler and follower in line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Toggle {
    /// μ = 0: coupler and follower folded onto each other (slider-crank: the rod
    /// perpendicular to the slider's path, pointing one way).
    Folded,
    /// μ = 180°: coupler and follower stretched in line (slider-crank: the rod perpendicular
    /// to the path, pointing the other way).
    Extended,
}

impl Toggle {
    /// The toggle in words.
    pub fn name(self) -> &'static str {
        match self {
            Toggle::Folded => "coupler and follower folded (μ = 0°)",
            Toggle::Extended => "coupler and follower in line (μ = 180°)",
        }
    }
}

/// One end of a rocking input's range.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InputEnd {
    /// Where the input stops.
    pub at: InputPosition,
    /// Why.
    pub toggle: Toggle,
}

/// The range of a loop's input, from the loop's lengths (the other loops of a mechanism
/// may restrict it further).
#[derive(Debug, Clone, PartialEq)]
pub enum InputRange {
    /// The input turns fully; at each change point listed the loop folds flat and its two
    /// branches meet.
    Full {
        /// Change points met along the turn.
        change_points: Vec<InputPosition>,
    },
    /// The input rocks between two toggle positions (on the sketch's side); a change point
    /// on the way is listed.
    Rocks {
        /// The lower end (smaller θ).
        lower: InputEnd,
        /// The upper end.
        upper: InputEnd,
        /// Change points met between the ends.
        change_points: Vec<InputPosition>,
    },
}

impl InputRange {
    /// Whether the input turns fully.
    pub fn is_full(&self) -> bool {
        matches!(self, InputRange::Full { .. })
    }
}

/// The transmission angle μ (unsigned, rad) at one input position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TransmissionAt {
    /// Where.
    pub at: InputPosition,
    /// μ there (rad, in [0, π]).
    pub angle: f64,
}

/// The extremes of a loop's transmission angle over its input's range, from its lengths.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TransmissionExtremes {
    /// The smallest μ.
    pub min: TransmissionAt,
    /// The largest μ.
    pub max: TransmissionAt,
    /// The worst effective transmission angle min(μ, 180° − μ) (the [0°, 90°] form, 90°
    /// best) over the range: at `min` or at `max`.
    pub worst: TransmissionAt,
}

/// The closure band of a loop (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Band {
    /// θ_c (rad).
    pub centre: f64,
    /// c_high: cos(θ − θ_c) at most this.
    pub high: f64,
    /// c_low: cos(θ − θ_c) at least this.
    pub low: f64,
    /// A length, positive iff c_high > 1 (the input passes θ_c).
    pub high_margin: f64,
    /// A length, positive iff c_low < −1 (the input passes θ_c + 180°).
    pub low_margin: f64,
    /// Margins within this (m) are change points.
    pub tolerance: f64,
}

/// The input's angle at the sketch and how the drive follows it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct InputFrame {
    /// θ at the sketch (rad, in (−π, π]).
    pub sketch: f64,
    /// When driven: the drive position at the sketch and dφ/dθ (±1).
    pub drive: Option<(f64, f64)>,
}

impl InputFrame {
    /// The position at angle `theta` (unwrapped: the drive follows without wrapping).
    pub fn at(&self, theta: f64) -> InputPosition {
        InputPosition {
            angle: theta,
            drive: (self.drive).map(|(phi, sign)| phi + sign * (theta - self.sketch)),
        }
    }

    /// The position at angle `theta` taken on the turn nearest the sketch.
    pub fn nearest(&self, theta: f64) -> InputPosition {
        self.at(self.sketch + wrap(theta - self.sketch))
    }
}

/// `x` wrapped to (−π, π].
pub(crate) fn wrap(x: f64) -> f64 {
    let y = x.rem_euclid(TAU);
    if y > PI { y - TAU } else { y }
}

impl Band {
    /// The range of the input, on the sketch's side.
    pub fn range(&self, input: &InputFrame) -> InputRange {
        let passes_centre = self.high_margin >= -self.tolerance;
        let passes_opposite = self.low_margin >= -self.tolerance;
        let mut change_points = Vec::new();
        if self.high_margin.abs() <= self.tolerance {
            change_points.push(input.nearest(self.centre));
        }
        if self.low_margin.abs() <= self.tolerance {
            change_points.push(input.nearest(self.centre + PI));
        }
        // t = θ − θ_c at the sketch, and the range of t on its side.
        let t = wrap(input.sketch - self.centre);
        let (alpha_high, alpha_low) = (
            self.high.clamp(-1.0, 1.0).acos(),
            self.low.clamp(-1.0, 1.0).acos(),
        );
        let (lower, upper, toggles) = match (passes_centre, passes_opposite) {
            (true, true) => return InputRange::Full { change_points },
            // Through θ_c + 180°: t in [α_high, 2π − α_high] (t taken in [0, 2π)).
            (false, true) => {
                let t = t.rem_euclid(TAU);
                let shift = input.sketch - t;
                (
                    shift + alpha_high,
                    shift + TAU - alpha_high,
                    [Toggle::Folded, Toggle::Folded],
                )
            }
            // Through θ_c: t in [−α_low, α_low].
            (true, false) => {
                let shift = input.sketch - t;
                (shift - alpha_low, shift + alpha_low, [Toggle::Extended; 2])
            }
            // Neither: t in [α_high, α_low] or [−α_low, −α_high], the sketch's side.
            (false, false) => {
                let shift = input.sketch - t;
                if t >= 0.0 {
                    (
                        shift + alpha_high,
                        shift + alpha_low,
                        [Toggle::Folded, Toggle::Extended],
                    )
                } else {
                    (
                        shift - alpha_low,
                        shift - alpha_high,
                        [Toggle::Extended, Toggle::Folded],
                    )
                }
            }
        };
        // Change points strictly inside the range, unwrapped into it.
        let inside = |theta: f64| {
            let k = ((lower - theta) / TAU).ceil();
            let theta = theta + k * TAU;
            (theta < upper).then_some(theta)
        };
        let change_points = change_points
            .iter()
            .filter_map(|p| inside(p.angle).map(|theta| input.at(theta)))
            .collect();
        InputRange::Rocks {
            lower: InputEnd {
                at: input.at(lower),
                toggle: toggles[0],
            },
            upper: InputEnd {
                at: input.at(upper),
                toggle: toggles[1],
            },
            change_points,
        }
    }

    /// The extremes of μ over `range`, `mu(θ)` the loop's transmission angle (rad, in
    /// [0, π], decreasing in cos(θ − θ_c)); at a toggle end μ is 0 or π exactly.
    pub fn extremes(
        &self,
        range: &InputRange,
        input: &InputFrame,
        mu: impl Fn(f64) -> f64,
    ) -> TransmissionExtremes {
        let at = |position: InputPosition| TransmissionAt {
            at: position,
            angle: mu(position.angle),
        };
        let (min, max) = match range {
            InputRange::Full { .. } => (
                at(input.nearest(self.centre)),
                at(input.nearest(self.centre + PI)),
            ),
            InputRange::Rocks { lower, upper, .. } => {
                let end = |e: &InputEnd| TransmissionAt {
                    at: e.at,
                    angle: match e.toggle {
                        Toggle::Folded => 0.0,
                        Toggle::Extended => PI,
                    },
                };
                // θ_c (resp. θ_c + π) inside the range, unwrapped into it.
                let inside = |theta: f64| {
                    let (lo, hi) = (lower.at.angle, upper.at.angle);
                    let theta = theta + ((lo - theta) / TAU).ceil() * TAU;
                    (theta <= hi).then(|| at(input.at(theta)))
                };
                let cos = |e: &InputEnd| (e.at.angle - self.centre).cos();
                let (larger, smaller) = if cos(lower) >= cos(upper) {
                    (lower, upper)
                } else {
                    (upper, lower)
                };
                (
                    inside(self.centre).unwrap_or_else(|| end(larger)),
                    inside(self.centre + PI).unwrap_or_else(|| end(smaller)),
                )
            }
        };
        let worst = if min.angle <= PI - max.angle {
            min
        } else {
            TransmissionAt {
                angle: PI - max.angle,
                ..max
            }
        };
        TransmissionExtremes { min, max, worst }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(sketch: f64) -> InputFrame {
        InputFrame {
            sketch,
            drive: Some((sketch, 1.0)),
        }
    }

    /// A band open on both sides is a full turn; μ's extremes are at θ_c and θ_c + π, on
    /// the turn nearest the sketch.
    #[test]
    fn a_band_open_on_both_sides_is_a_full_turn() {
        let band = Band {
            centre: 0.0,
            high: 2.0,
            low: -2.0,
            high_margin: 1.0,
            low_margin: 1.0,
            tolerance: 1e-15,
        };
        let input = frame(3.0);
        let range = band.range(&input);
        assert!(range.is_full());
        let e = band.extremes(&range, &input, |t| 1.5 - t.cos());
        assert_eq!((e.min.at.angle, e.max.at.angle), (0.0, PI));
    }

    /// Closed at θ_c only: the input rocks through θ_c + π between ±acos(c_high), both ends
    /// folded; μ's minimum (0) is at an end, its maximum at θ_c + π.
    #[test]
    fn a_band_closed_at_the_centre_rocks_through_the_opposite_side() {
        let band = Band {
            centre: 0.0,
            high: 0.5,
            low: -2.0,
            high_margin: -1.0,
            low_margin: 1.0,
            tolerance: 1e-15,
        };
        let input = frame(-3.0);
        let InputRange::Rocks { lower, upper, .. } = band.range(&input) else {
            panic!("the input must rock");
        };
        let third = PI / 3.0;
        // Taken on the sketch's turn: −3 rad lies in [−2π + π/3, −π/3].
        assert!((lower.at.angle - (third - TAU)).abs() < 1e-15);
        assert!((upper.at.angle + third).abs() < 1e-15);
        assert_eq!(
            (lower.toggle, upper.toggle),
            (Toggle::Folded, Toggle::Folded)
        );
    }
}
