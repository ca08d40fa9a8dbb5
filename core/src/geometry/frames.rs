//! The sines and cosines of the links' angles, computed once per pose and shared by Φ, Φ_q
//! and the lift, and kept up to date along Newton steps without calling `sin_cos`.

use super::constraints::{Body, Line, Slide};
use super::datum::Absorb;
use num_dual::DualNum;

/// Calls `body` with the sines and cosines of every body's angle, kept on the stack for up to
/// 8 moving links (most mechanisms), on the heap beyond.
pub(crate) fn with_frames<D: DualNum<Primitive = f64> + Copy, T>(
    q: &[D],
    body: impl FnOnce(&Frames<'_, D>) -> T,
) -> T {
    let n = q.len() / 3;
    let sin_cos = |k: usize| q[3 * k + 2].sin_cos();
    if n <= 8 {
        let zero = D::from(0.0);
        let mut frames = [(zero, zero); 8];
        for (k, f) in frames.iter_mut().enumerate().take(n) {
            *f = sin_cos(k);
        }
        body(&Frames {
            q,
            frames: &frames[..n],
        })
    } else {
        let frames: Vec<(D, D)> = (0..n).map(sin_cos).collect();
        body(&Frames { q, frames: &frames })
    }
}

/// `(sin, cos)` of angle `to`, given `(sin, cos)` of a nearby angle `from`.
///
/// Along Newton steps the angles move by ~1e-7 and less; rotating the known pair by the
/// difference d (exact: the operands are close) with sin d and cos d − 1 from their Taylor
/// series is then as accurate as `sin_cos` (the first terms left out are below 1e-20 for
/// |d| ≤ 1e-3; the result differs from the rounded sin/cos of `to` by about one ulp) and
/// far cheaper. Larger differences use `sin_cos`.
pub(crate) fn turn((s, c): (f64, f64), from: f64, to: f64) -> (f64, f64) {
    let d = to - from;
    if d.abs() > 1e-3 || !d.is_finite() {
        return to.sin_cos();
    }
    let d2 = d * d;
    let sin_d = d * (1.0 - d2 / 6.0 * (1.0 - d2 / 20.0));
    let cos_d_minus_1 = -0.5 * d2 * (1.0 - d2 / 12.0);
    (
        s + (s * cos_d_minus_1 + c * sin_d),
        c + (c * cos_d_minus_1 - s * sin_d),
    )
}

/// The vector fixed at `p` in body `b` (link-local data in `T`), turned with the body:
/// `(sin θ, cos θ)` of every body in `frames`.
#[inline]
pub(crate) fn rotate<T: Copy, D: Absorb<T>>(frames: &[(D, D)], b: Body, p: [T; 2]) -> [D; 2] {
    match b {
        None => [D::datum(p[0]), D::datum(p[1])],
        Some(k) => {
            let (s, c) = frames[k];
            [c.times(p[0]) - s.times(p[1]), s.times(p[0]) + c.times(p[1])]
        }
    }
}

/// Sine and cosine of every body's angle, for evaluating point positions. The link-local data
/// the methods take is in any scalar `T` the evaluation scalar `D` absorbs (see
/// [`super::datum`]).
pub(crate) struct Frames<'a, D> {
    pub q: &'a [D],
    pub frames: &'a [(D, D)],
}

impl<D: DualNum<Primitive = f64> + Copy> Frames<'_, D> {
    #[inline]
    pub fn rotate<T: Copy>(&self, b: Body, p: [T; 2]) -> [D; 2]
    where
        D: Absorb<T>,
    {
        rotate(self.frames, b, p)
    }

    #[inline]
    pub fn point<T: Copy>(&self, b: Body, p: [T; 2]) -> [D; 2]
    where
        D: Absorb<T>,
    {
        let r = self.rotate(b, p);
        match b {
            None => r,
            Some(k) => [self.q[3 * k] + r[0], self.q[3 * k + 1] + r[1]],
        }
    }

    #[inline]
    pub fn angle(&self, b: Body) -> D {
        b.map_or(D::from(0.0), |k| self.q[3 * k + 2])
    }

    /// Unit direction of `line` and the vector from its origin to `r`.
    #[inline]
    pub fn along<T: Copy>(&self, line: &Line<T>, r: [D; 2]) -> ([D; 2], [D; 2])
    where
        D: Absorb<T>,
    {
        let u = self.rotate(line.body, line.direction);
        let a = self.point(line.body, line.origin);
        (u, [r[0] - a[0], r[1] - a[1]])
    }

    pub fn displacement<T: Copy>(&self, slide: &Slide<T>) -> D
    where
        D: Absorb<T>,
    {
        let (u, d) = self.along(&slide.line, self.point(slide.slider, slide.point));
        u[0] * d[0] + u[1] * d[1]
    }
}

#[cfg(test)]
mod tests {
    use super::turn;

    #[test]
    fn turning_by_a_small_angle_matches_sin_cos() {
        // Angles over several turns, differences from 1e-3 (the largest turned) down to
        // 1e-16. sin and cos are O(1): 4e-16 absolute is two ulps, the rounding of the
        // rotation formula plus that of `sin_cos` itself.
        for i in 0..400 {
            let from = -20.0 + 0.1 * i as f64;
            for d in [1e-3, -7e-4, 3e-6, -1e-7, 5e-10, 1e-13, -2e-16] {
                let to = from + d;
                let (s, c) = turn(from.sin_cos(), from, to);
                let (s0, c0) = to.sin_cos();
                assert!(
                    (s - s0).abs() <= 4e-16 && (c - c0).abs() <= 4e-16,
                    "from {from}, d {d}: ({s}, {c}) vs ({s0}, {c0})"
                );
            }
        }
        // Larger differences fall back to sin_cos itself.
        assert_eq!(turn(0.0f64.sin_cos(), 0.0, 0.5), 0.5f64.sin_cos());
    }
}
