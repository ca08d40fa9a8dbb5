//! Ruler-and-compass constructions that place a sketch point from lengths: the RRR dyad
//! (two circles), the RRP dyad (a circle and a line) and a polar offset.
//!
//! Pure plane geometry (SI), in any [`Carried`] scalar: `f64`, or dual numbers carrying
//! the derivative of every length with respect to a parameter (the scene's tangent), whose
//! real parts are the `f64` results bit for bit. The scene's placement names the points,
//! converts units and turns a [`NoSolution`] into a message at the place in the file.

use crate::scalar::Carried;

/// Which of the two intersections of two circles: on the left or right of the directed line
/// from the first centre to the second.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Side {
    /// Left of centre 1 → centre 2 (counter-clockwise from it).
    Left,
    /// Right of centre 1 → centre 2.
    Right,
}

/// Which of the two intersections of a circle and a line: the one farther along the line's
/// direction (first point → second) or the one behind it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Along {
    /// Farther along the line's direction.
    Forward,
    /// Farther against the line's direction.
    Backward,
}

/// Why a construction has no point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NoSolution {
    /// The two centres coincide: the circles are concentric.
    Concentric,
    /// The centres are farther apart (`distance`) than the sum of the radii.
    TooFar {
        /// Distance between the centres.
        distance: f64,
    },
    /// One circle lies inside the other: the centres' distance is below |r1 − r2|.
    Inside {
        /// Distance between the centres.
        distance: f64,
    },
    /// The line passes the circle's centre at `distance`, more than the radius.
    Misses {
        /// Distance from the centre to the line.
        distance: f64,
    },
    /// The line's two points coincide.
    NoLine,
}

/// The intersection of the circle about `c1` of radius `r1` with the circle about `c2` of
/// radius `r2` on the given `side` of `c1 → c2` (the RRR dyad).
///
/// Tangent circles (the two solutions coincide) give their one point.
///
/// # Errors
/// [`NoSolution`] when the circles do not meet or are concentric.
pub fn circles<D: Carried>(
    c1: [D; 2],
    r1: D,
    c2: [D; 2],
    r2: D,
    side: Side,
) -> Result<[D; 2], NoSolution> {
    let (dx, dy) = (c2[0] - c1[0], c2[1] - c1[1]);
    let d = dx.hypot(dy);
    let (dr, r1r, r2r) = (d.re(), r1.re(), r2.re());
    if dr == 0.0 {
        return Err(NoSolution::Concentric);
    }
    if dr > r1r + r2r {
        return Err(NoSolution::TooFar { distance: dr });
    }
    if dr < (r1r - r2r).abs() {
        return Err(NoSolution::Inside { distance: dr });
    }
    // Along c1 → c2 by a, then across by h (the law of cosines, Heron-free form).
    let a = (r1 * r1 - r2 * r2 + d * d) / (d * 2.0);
    let h = (r1 * r1 - a * a).non_negative().sqrt();
    let (ux, uy) = (dx / d, dy / d);
    let h = match side {
        Side::Left => h,
        Side::Right => -h,
    };
    Ok([c1[0] + a * ux - h * uy, c1[1] + a * uy + h * ux])
}

/// The intersection of the circle about `c` of radius `r` with the line through `p` and `q`,
/// the one `along` the line's direction (the RRP dyad).
///
/// # Errors
/// [`NoSolution`] when the line misses the circle or `p` = `q`.
pub fn circle_line<D: Carried>(
    c: [D; 2],
    r: D,
    [p, q]: [[D; 2]; 2],
    along: Along,
) -> Result<[D; 2], NoSolution> {
    let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
    let length = dx.hypot(dy);
    if length.re() == 0.0 {
        return Err(NoSolution::NoLine);
    }
    let (ux, uy) = (dx / length, dy / length);
    // The foot of the perpendicular from c, at s along the line and e across it.
    let s = (c[0] - p[0]) * ux + (c[1] - p[1]) * uy;
    let e = (c[1] - p[1]) * ux - (c[0] - p[0]) * uy;
    if e.re().abs() > r.re() {
        return Err(NoSolution::Misses {
            distance: e.re().abs(),
        });
    }
    let t = (r * r - e * e).non_negative().sqrt();
    let t = match along {
        Along::Forward => s + t,
        Along::Backward => s - t,
    };
    Ok([p[0] + t * ux, p[1] + t * uy])
}

/// The point at `length` from `origin` in the direction `angle` (radians, counter-clockwise
/// from +x).
pub fn polar<D: Carried>(origin: [D; 2], length: D, angle: D) -> [D; 2] {
    [
        origin[0] + length * angle.cos(),
        origin[1] + length * angle.sin(),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_3_4_5_triangle_is_found_on_either_side() {
        // Centres 5 apart on x, radii 4 and 3: the apex is at (3.2, ±2.4) (16/5 and 12/5),
        // within a few roundings.
        let left = circles([0.0, 0.0], 4.0, [5.0, 0.0], 3.0, Side::Left).unwrap();
        let right = circles([0.0, 0.0], 4.0, [5.0, 0.0], 3.0, Side::Right).unwrap();
        for (got, want) in [(left, [3.2, 2.4]), (right, [3.2, -2.4])] {
            assert!((got[0] - want[0]).abs() < 1e-15 && (got[1] - want[1]).abs() < 1e-15);
        }
        assert_eq!(
            circles([0.0, 0.0], 1.0, [5.0, 0.0], 1.0, Side::Left),
            Err(NoSolution::TooFar { distance: 5.0 })
        );
        assert!(matches!(
            circles([0.0, 0.0], 4.0, [1.0, 0.0], 1.0, Side::Left),
            Err(NoSolution::Inside { .. })
        ));
    }

    #[test]
    fn a_circle_meets_a_line_ahead_and_behind() {
        // Circle about (0, 3) of radius 5 and the x axis: x = ±4 exactly.
        let line = [[-1.0, 0.0], [1.0, 0.0]];
        assert_eq!(
            circle_line([0.0, 3.0], 5.0, line, Along::Forward),
            Ok([4.0, 0.0])
        );
        assert_eq!(
            circle_line([0.0, 3.0], 5.0, line, Along::Backward),
            Ok([-4.0, 0.0])
        );
        assert_eq!(
            circle_line([0.0, 6.0], 5.0, line, Along::Forward),
            Err(NoSolution::Misses { distance: 6.0 })
        );
    }
}
