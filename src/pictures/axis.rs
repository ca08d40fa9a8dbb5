//! Where the ticks of an axis go: multiples of 30°, 45° or 90° on an angle axis, of 1, 2 or 5
//! times a power of ten on any other, and the round length of a drawing's scale bar.

use std::ops::Range;

/// Steps of an angle axis (degrees), smallest first: below 30° the 1-2-5 steps and 15°, then
/// the multiples of 30°, 45° and 90° a reader counts a revolution in.
const ANGLE_STEPS: [f64; 13] = [
    1.0, 2.0, 5.0, 10.0, 15.0, 30.0, 45.0, 90.0, 180.0, 360.0, 720.0, 1440.0, 3600.0,
];

/// The ticks of an angle axis over `range` (degrees): multiples of the smallest step of
/// [`ANGLE_STEPS`] that leaves at most 9 ticks inside the range (so 4 to 9 for any span
/// from 3° to 32 400°; never 50°). Narrower or wider ranges fall back to [`ticks`].
pub fn angle_ticks(range: &Range<f64>) -> Vec<f64> {
    for step in ANGLE_STEPS {
        let t = multiples(range, step);
        if t.len() <= 9 {
            return if t.len() >= 4 { t } else { ticks(range, 9) };
        }
    }
    ticks(range, 9)
}

/// The ticks over `range` at multiples of the 1-2-5 step that gives at most `most` ticks.
pub fn ticks(range: &Range<f64>, most: usize) -> Vec<f64> {
    let span = range.end - range.start;
    if !(span.is_finite() && span > 0.0) {
        return vec![range.start];
    }
    let mut step = 10f64.powf((span / most.max(1) as f64).log10().floor());
    for factor in [1.0, 2.0, 5.0, 10.0, 20.0, 50.0] {
        let t = multiples(range, step * factor);
        if t.len() <= most.max(2) {
            return t;
        }
    }
    step *= 100.0;
    multiples(range, step)
}

/// The multiples of `step` inside `range` (at most 10 001, so a degenerate step stays cheap).
fn multiples(range: &Range<f64>, step: f64) -> Vec<f64> {
    let first = (range.start / step).ceil();
    let last = (range.end / step).floor();
    if !(first.is_finite() && last.is_finite()) || last - first > 10_000.0 {
        return Vec::new();
    }
    let mut out = Vec::new();
    let mut k = first;
    while k <= last {
        // `+ 0.0` turns −0 into 0.
        out.push(k * step + 0.0);
        k += 1.0;
    }
    out
}

/// The round length (1, 2 or 5 times a power of ten) closest below `most`, for a scale bar.
pub fn round_length(most: f64) -> f64 {
    if !(most.is_finite() && most > 0.0) {
        return 1.0;
    }
    let power = 10f64.powf(most.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|f| f * power)
        .find(|&l| l <= most * (1.0 + 1e-12))
        .unwrap_or(power)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A revolution gets ticks every 45° (9 ticks), two revolutions every 90°, 100° every 15°
    /// or 30°; never a step that is not a multiple of 15° above 10°.
    #[test]
    fn angle_ticks_are_multiples_of_30_45_or_90_degrees() {
        assert_eq!(angle_ticks(&(0.0..360.0)).len(), 9);
        assert_eq!(angle_ticks(&(0.0..360.0))[1], 45.0);
        assert_eq!(angle_ticks(&(0.0..720.0))[1], 90.0);
        for span in [40.0, 100.0, 250.0, 360.0, 500.0, 1000.0, 5000.0] {
            let t = angle_ticks(&(-7.0..span - 7.0));
            assert!((4..=9).contains(&t.len()), "{span}: {t:?}");
            let step = t[1] - t[0];
            assert!(step <= 10.0 || (step % 15.0).abs() < 1e-9, "{span}: {step}");
        }
    }

    /// Scale bars are 1, 2 or 5 times a power of ten, at most the room given.
    #[test]
    fn round_lengths() {
        assert_eq!(round_length(0.37), 0.2);
        assert_eq!(round_length(73.0), 50.0);
        assert_eq!(round_length(1.0), 1.0);
    }
}
