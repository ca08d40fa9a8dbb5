//! A diagram's curves as SVG path data: cubic Hermite segments between the drawn points,
//! written as Bézier `C` commands, so that the printed curve is smooth at every point.
//!
//! The slope at a point is the exact derivative dy/dx when the caller has it (a column's
//! velocity coefficient ψ′ beside ψ): the curve then matches the function to fourth order in
//! the step, and has no kink anywhere. Where no exact slope is known, the monotone
//! Fritsch–Carlson slopes are used (the curve passes through every point and adds no extremum
//! between points). A Hermite segment from `(x₀, y₀)` to `(x₁, y₁)` with slopes `m₀`, `m₁`
//! is the Bézier curve with control points `(x₀ + h/3, y₀ + m₀h/3)` and
//! `(x₁ − h/3, y₁ − m₁h/3)`, `h = x₁ − x₀`; its x is linear in the curve parameter.
//!
//! A Bézier curve lies inside the hull of its control points. A segment whose exact-slope
//! control points leave the panel's y range (a step too coarse for the curve's bend, near a
//! singular position) is drawn with the estimated slopes instead, whose control points lie
//! between its ends: no curve leaves its panel.

use std::fmt::Write as _;
use std::ops::Range;

/// How a panel's data coordinates map to pixels: `x` onto `left..right`, `y` onto
/// `bottom..top` (pixels grow downwards), linearly.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct PixelMap {
    /// The data range of the x axis.
    pub x: Range<f64>,
    /// The data range of the y axis.
    pub y: Range<f64>,
    /// Pixel columns of `x.start` and `x.end`.
    pub columns: (f64, f64),
    /// Pixel rows of `y.start` and `y.end`.
    pub rows: (f64, f64),
}

impl PixelMap {
    /// The pixel of the data point `p`.
    pub fn at(&self, p: [f64; 2]) -> [f64; 2] {
        let u = (p[0] - self.x.start) / (self.x.end - self.x.start);
        let v = (p[1] - self.y.start) / (self.y.end - self.y.start);
        [
            self.columns.0 + u * (self.columns.1 - self.columns.0),
            self.rows.0 + v * (self.rows.1 - self.rows.0),
        ]
    }
}

/// The path data (`d` attribute) of a curve through `points` in pixels of `map`: each run of
/// finite points starts with `M`; its intervals are Hermite `C` segments when `smooth` and x
/// runs strictly one way along the run, else straight `L` lines. `slopes`, if given, holds
/// dy/dx at every point (same length as `points`); a non-finite slope is estimated.
pub(crate) fn path_data(
    points: &[[f64; 2]],
    slopes: Option<&[f64]>,
    smooth: bool,
    map: &PixelMap,
) -> String {
    let slopes = slopes.filter(|s| s.len() == points.len());
    let mut d = String::new();
    let finite = |p: &[f64; 2]| p[0].is_finite() && p[1].is_finite();
    let mut start = 0;
    while start < points.len() {
        if !finite(&points[start]) {
            start += 1;
            continue;
        }
        let end = (start..points.len())
            .find(|&k| !finite(&points[k]))
            .unwrap_or(points.len());
        let run = &points[start..end];
        let exact = slopes.map(|s| &s[start..end]);
        write_run(&mut d, run, exact, smooth, map);
        start = end;
    }
    d
}

/// Appends one run of finite points (see [`path_data`]).
fn write_run(
    d: &mut String,
    run: &[[f64; 2]],
    exact: Option<&[f64]>,
    smooth: bool,
    map: &PixelMap,
) {
    let p = |q: [f64; 2]| {
        let [x, y] = map.at(q);
        format!("{x:.3} {y:.3}")
    };
    let _ = write!(d, "M{}", p(run[0]));
    let estimated = if smooth { fritsch_carlson(run) } else { None };
    let Some(estimated) = estimated else {
        for q in &run[1..] {
            let _ = write!(d, " L{}", p(*q));
        }
        return;
    };
    let slope = |k: usize| match exact.map(|e| e[k]) {
        Some(m) if m.is_finite() => m,
        _ => estimated[k],
    };
    let (lo, hi) = (map.y.start.min(map.y.end), map.y.start.max(map.y.end));
    for (k, w) in run.windows(2).enumerate() {
        let h = w[1][0] - w[0][0];
        let controls = |m0: f64, m1: f64| {
            (
                [w[0][0] + h / 3.0, w[0][1] + m0 * h / 3.0],
                [w[1][0] - h / 3.0, w[1][1] - m1 * h / 3.0],
            )
        };
        let (mut c1, mut c2) = controls(slope(k), slope(k + 1));
        if ![c1[1], c2[1]].iter().all(|y| (lo..=hi).contains(y)) {
            (c1, c2) = controls(estimated[k], estimated[k + 1]);
        }
        let _ = write!(d, " C{} {} {}", p(c1), p(c2), p(w[1]));
    }
}

/// Fritsch–Carlson's slopes dy/dx at the points of a run whose x runs strictly one way
/// (`None` otherwise, or with fewer than two points): the mean of neighbouring secants where
/// they agree in sign, zero at an extremum, limited to three times the smaller secant; the
/// end secants at the ends. The Hermite curve with these slopes is monotone between points.
fn fritsch_carlson(run: &[[f64; 2]]) -> Option<Vec<f64>> {
    let n = run.len();
    if n < 2 {
        return None;
    }
    let dx: Vec<f64> = run.windows(2).map(|w| w[1][0] - w[0][0]).collect();
    let rising = dx[0] > 0.0;
    if !dx.iter().all(|&d| if rising { d > 0.0 } else { d < 0.0 }) {
        return None;
    }
    let secant: Vec<f64> = run
        .windows(2)
        .zip(&dx)
        .map(|(w, d)| (w[1][1] - w[0][1]) / d)
        .collect();
    Some(
        (0..n)
            .map(|k| {
                if k == 0 {
                    return secant[0];
                }
                if k == n - 1 {
                    return secant[n - 2];
                }
                let (a, b) = (secant[k - 1], secant[k]);
                if a * b > 0.0 {
                    let m = 0.5 * (a + b);
                    m.signum() * m.abs().min(3.0 * a.abs().min(b.abs()))
                } else {
                    0.0
                }
            })
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_map() -> PixelMap {
        PixelMap {
            x: 0.0..1.0,
            y: 0.0..1.0,
            columns: (0.0, 1000.0),
            rows: (1000.0, 0.0),
        }
    }

    /// A cubic is reproduced exactly by one Hermite segment with its exact end slopes: the
    /// Bézier point at t = ½ is the cubic's value at the middle (to the 1e-3 px of the
    /// written digits).
    #[test]
    fn exact_slopes_reproduce_a_cubic() {
        let f = |x: f64| 0.5 + x * x * x - 0.5 * x;
        let df = |x: f64| 3.0 * x * x - 0.5;
        let points = [[0.0, f(0.0)], [1.0, f(1.0)]];
        let d = path_data(&points, Some(&[df(0.0), df(1.0)]), true, &unit_map());
        let n: Vec<f64> = d
            .split(|c: char| c == ' ' || c.is_ascii_alphabetic())
            .filter_map(|t| t.parse().ok())
            .collect();
        assert_eq!(n.len(), 8, "{d}");
        let mid = |a: f64, b: f64, c: f64, e: f64| (a + 3.0 * b + 3.0 * c + e) / 8.0;
        let (x, y) = (mid(n[0], n[2], n[4], n[6]), mid(n[1], n[3], n[5], n[7]));
        let want = unit_map().at([0.5, f(0.5)]);
        assert!(
            (x - want[0]).abs() < 2e-3 && (y - want[1]).abs() < 2e-3,
            "{x} {y} {want:?}"
        );
    }

    /// An exact slope too steep for the step (its control point would leave the panel's y
    /// range) gives way to the estimated slope: every control point, hence the whole curve,
    /// stays inside the panel.
    #[test]
    fn steep_slopes_stay_inside_the_panel() {
        let points = [[0.0, 0.1], [0.5, 0.5], [1.0, 0.9]];
        let d = path_data(&points, Some(&[1e6, 0.8, -1e6]), true, &unit_map());
        let n: Vec<f64> = d
            .split(|c: char| c == ' ' || c.is_ascii_alphabetic())
            .filter_map(|t| t.parse().ok())
            .collect();
        assert!(
            n.iter()
                .skip(1)
                .step_by(2)
                .all(|y| (0.0..=1000.0).contains(y)),
            "{d}"
        );
    }

    /// Non-finite points break the curve into runs, each starting with `M`; a run whose x
    /// turns back is drawn with straight lines.
    #[test]
    fn runs_and_turning_x() {
        let p = [
            [0.0, 0.0],
            [0.5, 0.5],
            [f64::NAN, 0.0],
            [0.6, 0.1],
            [0.4, 0.2],
            [0.7, 0.3],
        ];
        let d = path_data(&p, None, true, &unit_map());
        assert_eq!(d.matches('M').count(), 2, "{d}");
        assert!(d.contains('C') && d.contains('L'), "{d}");
    }
}
