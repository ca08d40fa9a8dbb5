//! The diameter of a point set (the largest distance between two of its points), in time
//! O(n log n): the convex hull (Andrew's monotone chain), then rotating calipers over the
//! antipodal pairs of its vertices. A scene of 10⁵ points is measured without 10¹⁰ pairs.

/// The largest distance between two of `points` (0 for fewer than two; NaN coordinates are
/// not expected: the reader refuses them first).
pub fn diameter(points: impl IntoIterator<Item = [f64; 2]>) -> f64 {
    let hull = convex_hull(points.into_iter().collect());
    let distance = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
    let h = hull.len();
    if h < 3 {
        return if h == 2 {
            distance(hull[0], hull[1])
        } else {
            0.0
        };
    }
    // For each edge (i, i+1), the vertex j farthest from its line moves forward as i does;
    // the diameter is between an antipodal pair (i or i+1, j).
    let mut largest: f64 = 0.0;
    let mut j = 1;
    for i in 0..h {
        let (a, b) = (hull[i], hull[(i + 1) % h]);
        let mut steps = 0;
        while steps < h && area(a, b, hull[(j + 1) % h]) > area(a, b, hull[j]) {
            j = (j + 1) % h;
            steps += 1;
        }
        // With an edge parallel to (a, b), both of its ends are antipodal to a and b.
        for c in [hull[j], hull[(j + 1) % h]] {
            largest = largest.max(distance(a, c)).max(distance(b, c));
        }
    }
    largest
}

/// Twice the signed area of the triangle (o, a, b): positive when it turns left.
fn cross(o: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
}

/// Twice the area of the triangle (a, b, c), unsigned.
fn area(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    cross(a, b, c).abs()
}

/// The vertices of the convex hull of `points`, counter-clockwise, without collinear points.
fn convex_hull(mut points: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    points.sort_by(|p, q| p[0].total_cmp(&q[0]).then(p[1].total_cmp(&q[1])));
    points.dedup();
    if points.len() < 3 {
        return points;
    }
    let mut hull: Vec<[f64; 2]> = Vec::with_capacity(2 * points.len());
    for &p in &points {
        while hull.len() >= 2 && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0 {
            hull.pop();
        }
        hull.push(p);
    }
    let lower = hull.len() + 1;
    for &p in points.iter().rev().skip(1) {
        while hull.len() >= lower && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0 {
            hull.pop();
        }
        hull.push(p);
    }
    hull.pop();
    hull
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The definition, over every pair.
    fn every_pair(points: &[[f64; 2]]) -> f64 {
        let mut largest: f64 = 0.0;
        for p in points {
            for q in points {
                largest = largest.max((p[0] - q[0]).hypot(p[1] - q[1]));
            }
        }
        largest
    }

    #[test]
    fn the_diameter_equals_the_largest_distance_over_every_pair() {
        // A deterministic scatter (a linear congruential generator), collinear and repeated
        // points, a regular polygon (every vertex on the hull): the same pair is found, so
        // the same rounded hypot, bit for bit.
        let mut state: u64 = 12345;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let mut cases: Vec<Vec<[f64; 2]>> = Vec::new();
        for n in [0, 1, 2, 3, 5, 17, 200] {
            cases.push((0..n).map(|_| [next(), 1e-3 * next()]).collect());
        }
        cases.push((0..50).map(|k| [k as f64, 2.0 * k as f64]).collect());
        cases.push(vec![[1.0, 1.0]; 4]);
        cases.push(vec![
            [0.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [0.0, 1.0],
            [1.0, 0.5],
        ]);
        for n in [4, 6, 8, 100] {
            cases.push(
                (0..n)
                    .map(|k| {
                        let t = std::f64::consts::TAU * k as f64 / n as f64;
                        [t.cos(), t.sin()]
                    })
                    .collect(),
            );
        }
        cases.push(
            (0..101)
                .map(|k| {
                    let t = std::f64::consts::TAU * k as f64 / 101.0;
                    [3.0 * t.cos(), 3.0 * t.sin()]
                })
                .collect(),
        );
        for points in cases {
            assert_eq!(
                diameter(points.iter().copied()),
                every_pair(&points),
                "{points:?}"
            );
        }
    }
}
