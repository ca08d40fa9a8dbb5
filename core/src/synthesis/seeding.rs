//! A sampled linkage's drive angles read off its own motion: the starts of the local phase
//! get the timing that suits their dimensions, not a random one.
//!
//! - Drive angles given up to a common offset ([`Timing::Relative`]): the offset `drive0`
//!   that fits best among [`OFFSETS`] equally spaced values of its range.
//! - Free drive angles ([`Timing::Free`]): the traced point's path is computed at
//!   [`GRID`] (or more, two per target) equally spaced crank angles of one turn, and each
//!   target is matched to a point of it, in the order given along one counter-clockwise
//!   turn, so that the sum of squared distances is least (a dynamic programme over the
//!   grid, for every grid point the first target may take; its cost n·m² for n targets
//!   and m grid points, so it is skipped when that exceeds [`MAX_WORK`]).
//!
//! Absolute timing has nothing to fit. The fitted angles stay within their bounds (shifted
//! by whole turns where needed); a fit that cannot keep them there, or finds no assembled
//! position, leaves the sample as drawn.

use super::problem::Problem;
use super::task::{Task, Timing};
use std::f64::consts::TAU;

/// Candidate offsets of relative timing.
pub(crate) const OFFSETS: usize = 36;
/// Grid points of the path for free timing (at least; two per target when there are more).
pub(crate) const GRID: usize = 72;
/// The most work (targets × grid points²) of one free-timing fit.
pub(crate) const MAX_WORK: usize = 5_000_000;

/// Fits the timing variables of `x` to its linkage; returns the residual evaluations spent
/// (a path of m grid points counts as m / n evaluations of the n targets' residuals,
/// rounded up).
pub(crate) fn fit_timing(problem: &Problem, x: &mut [f64]) -> usize {
    let base = problem.linkage.variable_names().len()
        + usize::from(matches!(problem.task, Task::Motion { .. }));
    let timing = problem.task.timing();
    let mut spent = 0;
    let rounds = if matches!(problem.task, Task::Path { .. }) {
        SIMILARITY_ROUNDS
    } else {
        1
    };
    for round in 0..rounds {
        spent += match timing {
            Timing::Absolute(_) => 0,
            Timing::Relative(_) => fit_offset(problem, x, base),
            Timing::Free => fit_free(problem, x, base),
        };
        if round + 1 < rounds {
            spent += 1;
            if !fit_similarity(problem, x, base) {
                break;
            }
        }
    }
    spent
}

/// The most residual evaluations [`fit_timing`] spends on one sample of `problem`.
pub(crate) fn fit_cost(problem: &Problem) -> usize {
    let rounds = if matches!(problem.task, Task::Path { .. }) {
        SIMILARITY_ROUNDS
    } else {
        1
    };
    let n = problem.task.target_count().max(1);
    let one = match problem.task.timing() {
        Timing::Absolute(_) => 0,
        Timing::Relative(_) => OFFSETS,
        Timing::Free => GRID.max(2 * n).div_ceil(n),
    };
    rounds * (one + 1)
}

/// Rounds of (timing, placement) fits of a path task's sample.
pub(crate) const SIMILARITY_ROUNDS: usize = 3;

/// Path generation: moves, turns and scales the sampled linkage so that its points at the
/// current drive angles fall on the targets as nearly as a similarity can take them
/// (least squares, Umeyama's closed form in the plane; no turn for absolute timing, as the
/// drive angles must stay), the drive angles turned with it. Kept only if every variable
/// stays within its bounds; returns whether it was kept.
fn fit_similarity(problem: &Problem, x: &mut [f64], base: usize) -> bool {
    let Task::Path { targets, .. } = &problem.task else {
        return false;
    };
    let phis = problem.drive_angles(x);
    let Ok(points) = phis
        .iter()
        .map(|&phi| {
            problem
                .linkage
                .pose(x, phi, &problem.branch)
                .map(|p| p.points[problem.selected])
        })
        .collect::<Result<Vec<[f64; 2]>, _>>()
    else {
        return false;
    };
    let n = points.len() as f64;
    let mean = |v: &[[f64; 2]]| {
        let s = v.iter().fold([0.0, 0.0], |a, p| [a[0] + p[0], a[1] + p[1]]);
        [s[0] / n, s[1] / n]
    };
    let (cp, ct) = (mean(&points), mean(targets));
    // z = Σ conj(p')·t' / Σ|p'|²: scale·e^{i·rotation} of the best similarity.
    let (mut re, mut im, mut norm) = (0.0, 0.0, 0.0);
    for (p, t) in points.iter().zip(targets) {
        let (a, b) = (p[0] - cp[0], p[1] - cp[1]);
        let (c, d) = (t[0] - ct[0], t[1] - ct[1]);
        re += a * c + b * d;
        im += a * d - b * c;
        norm += a * a + b * b;
    }
    if norm <= 0.0 || !norm.is_finite() {
        return false;
    }
    let turning = !matches!(problem.task.timing(), Timing::Absolute(_));
    let (scale, rotation) = if turning {
        (re.hypot(im) / norm, im.atan2(re))
    } else {
        (re / norm, 0.0)
    };
    if !(scale > 0.0 && scale.is_finite()) {
        return false;
    }
    let (sin, cos) = rotation.sin_cos();
    let shift = [
        ct[0] - scale * (cos * cp[0] - sin * cp[1]),
        ct[1] - scale * (sin * cp[0] + cos * cp[1]),
    ];
    let mut y = problem.linkage.similar(x, scale, rotation, shift);
    y[base..].copy_from_slice(&x[base..]);
    for phi in &mut y[base..] {
        *phi += rotation;
    }
    // Drive angles back within their bounds by whole turns (all together: their order and
    // spans stay).
    let (lower, upper) = (&problem.lower, &problem.upper);
    let outside = |y: &[f64], i: usize| y[i] < lower[i] || y[i] > upper[i];
    for _ in 0..2 {
        if (base..y.len()).any(|i| y[i] > upper[i]) {
            y[base..].iter_mut().for_each(|phi| *phi -= TAU);
        } else if (base..y.len()).any(|i| y[i] < lower[i]) {
            y[base..].iter_mut().for_each(|phi| *phi += TAU);
        }
    }
    if (0..y.len()).any(|i| outside(&y, i)) {
        return false;
    }
    x.copy_from_slice(&y);
    true
}

fn fit_offset(problem: &Problem, x: &mut [f64], index: usize) -> usize {
    let (lo, hi) = (problem.lower[index], problem.upper[index]);
    if lo >= hi {
        return 0;
    }
    let mut best = (f64::INFINITY, x[index]);
    for k in 0..OFFSETS {
        x[index] = lo + (hi - lo) * (k as f64 + 0.5) / OFFSETS as f64;
        if let Ok(r) = problem.residuals(x) {
            let value: f64 = r.iter().map(|v| v * v).sum();
            if value < best.0 {
                best = (value, x[index]);
            }
        }
    }
    x[index] = best.1;
    OFFSETS
}

fn fit_free(problem: &Problem, x: &mut [f64], first: usize) -> usize {
    let Task::Path { targets, .. } = &problem.task else {
        return 0;
    };
    let n = targets.len();
    let m = GRID.max(2 * n);
    if n.saturating_mul(m).saturating_mul(m) > MAX_WORK {
        return 0;
    }
    let point = problem.selected;
    let step = TAU / m as f64;
    let start = problem.lower[first].max(-TAU);
    // The path at the grid angles (None where the linkage does not assemble).
    let path: Vec<Option<[f64; 2]>> = (0..m)
        .map(|k| {
            let phi = start + k as f64 * step;
            problem
                .linkage
                .pose(x, phi, &problem.branch)
                .ok()
                .map(|p| p.points[point])
        })
        .collect();
    let spent = m.div_ceil(n);
    let cost = |i: usize, k: usize| {
        path[k % m].map_or(f64::INFINITY, |p| {
            (p[0] - targets[i][0]).powi(2) + (p[1] - targets[i][1]).powi(2)
        })
    };
    let mut best: (f64, Vec<usize>) = (f64::INFINITY, Vec::new());
    for (s, start_point) in path.iter().enumerate() {
        if start_point.is_none() {
            continue;
        }
        // value[i][j]: least cost of targets 0..=i with target i at grid index s + j.
        let mut value = vec![vec![f64::INFINITY; m]; n];
        let mut from = vec![vec![0usize; m]; n];
        value[0][0] = cost(0, s);
        for i in 1..n {
            let (mut least, mut at) = (f64::INFINITY, 0);
            for j in 1..m {
                if value[i - 1][j - 1] < least {
                    (least, at) = (value[i - 1][j - 1], j - 1);
                }
                if least.is_finite() {
                    value[i][j] = least + cost(i, s + j);
                    from[i][j] = at;
                }
            }
        }
        let (total, mut j) = value[n - 1]
            .iter()
            .enumerate()
            .map(|(j, v)| (*v, j))
            .fold((f64::INFINITY, 0), |a, b| if b.0 < a.0 { b } else { a });
        if total < best.0 {
            let mut chosen = vec![0; n];
            for i in (0..n).rev() {
                chosen[i] = s + j;
                j = from[i][j];
            }
            best = (total, chosen);
        }
    }
    if !best.0.is_finite() {
        return spent;
    }
    let mut angles: Vec<f64> = best.1.iter().map(|&k| start + k as f64 * step).collect();
    // Within the bounds: shift by whole turns towards them.
    let (lo, hi) = (
        problem.lower[first..].to_vec(),
        problem.upper[first..].to_vec(),
    );
    for _ in 0..3 {
        if angles.iter().zip(&hi).any(|(a, h)| a > h) {
            angles.iter_mut().for_each(|a| *a -= TAU);
        } else if angles.iter().zip(&lo).any(|(a, l)| a < l) {
            angles.iter_mut().for_each(|a| *a += TAU);
        }
    }
    let inside = angles
        .iter()
        .zip(lo.iter().zip(&hi))
        .all(|(a, (l, h))| a >= l && a <= h);
    if inside {
        x[first..].copy_from_slice(&angles);
    }
    spent
}
