//! Decimation for drawing only: a sweep of any length becomes a bounded number of drawn
//! points (the CSV and JSON outputs always carry every row).

/// At most `max` row indices spread evenly over `rows` rows, the first and the last
/// included (all of them when there are no more than `max`).
pub fn sample(rows: usize, max: usize) -> Vec<usize> {
    let max = max.max(2);
    if rows <= max {
        return (0..rows).collect();
    }
    let mut picked: Vec<usize> = (0..max)
        .map(|k| ((k as f64) * (rows - 1) as f64 / (max - 1) as f64).round() as usize)
        .collect();
    picked.dedup();
    picked
}

/// A curve of `len` points thinned to at most `5 · buckets` points for drawing: the
/// points are cut into `buckets` runs of consecutive points, and each run keeps its first and
/// last points and its lowest and highest y, in their order, so that no peak is lost at the
/// drawing's resolution. A non-finite y inside a run is kept (it breaks the drawn line).
/// Memory is bounded by the output: the input is read once, as an iterator.
pub fn decimate(
    points: impl Iterator<Item = [f64; 2]>,
    len: usize,
    buckets: usize,
) -> Vec<[f64; 2]> {
    let buckets = buckets.max(1);
    if len <= 4 * buckets {
        return points.collect();
    }
    let per = len.div_ceil(buckets);
    let mut out = Vec::with_capacity(4 * buckets + 4);
    let mut state = Bucket::default();
    for (k, p) in points.enumerate() {
        state.add(k, p);
        if (k + 1) % per == 0 {
            state.flush(&mut out);
            state = Bucket::default();
        }
    }
    state.flush(&mut out);
    out
}

/// The points kept from one run: (index, point) of the first, last, lowest, highest and
/// first non-finite.
#[derive(Default)]
struct Bucket {
    first: Option<(usize, [f64; 2])>,
    last: Option<(usize, [f64; 2])>,
    low: Option<(usize, [f64; 2])>,
    high: Option<(usize, [f64; 2])>,
    broken: Option<(usize, [f64; 2])>,
}

impl Bucket {
    fn add(&mut self, k: usize, p: [f64; 2]) {
        self.first.get_or_insert((k, p));
        self.last = Some((k, p));
        if !(p[0].is_finite() && p[1].is_finite()) {
            self.broken.get_or_insert((k, p));
            return;
        }
        if self.low.is_none_or(|(_, q)| p[1] < q[1]) {
            self.low = Some((k, p));
        }
        if self.high.is_none_or(|(_, q)| p[1] > q[1]) {
            self.high = Some((k, p));
        }
    }

    fn flush(&self, out: &mut Vec<[f64; 2]>) {
        let mut kept: Vec<(usize, [f64; 2])> =
            [self.first, self.low, self.high, self.broken, self.last]
                .into_iter()
                .flatten()
                .collect();
        kept.sort_by_key(|(k, _)| *k);
        kept.dedup_by_key(|(k, _)| *k);
        out.extend(kept.into_iter().map(|(_, p)| p));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The extremes of every run survive, the output is bounded, the order is kept.
    #[test]
    fn a_million_points_keep_their_peaks_in_bounded_output() {
        let n = 1_000_000;
        let f = |k: usize| {
            let x = k as f64 / n as f64;
            // One sharp spike of one sample that a plain every-k-th sampling would miss.
            if k == 123_457 { 50.0 } else { (20.0 * x).sin() }
        };
        let out = decimate((0..n).map(|k| [k as f64, f(k)]), n, 800);
        assert!(out.len() <= 4 * 800 + 4, "{} points", out.len());
        assert!(out.iter().any(|p| p[1] == 50.0), "the spike is kept");
        assert!(out.windows(2).all(|w| w[0][0] < w[1][0]), "x order is kept");
        assert_eq!(out.first().map(|p| p[0]), Some(0.0));
        assert_eq!(out.last().map(|p| p[0]), Some((n - 1) as f64));
    }

    /// Short curves are not touched; samples include both ends and are bounded.
    #[test]
    fn short_curves_and_samples() {
        let out = decimate((0..10).map(|k| [k as f64, 0.0]), 10, 800);
        assert_eq!(out.len(), 10);
        let s = sample(1_000_001, 721);
        assert_eq!(s.len(), 721);
        assert_eq!((s[0], s[720]), (0, 1_000_000));
        assert_eq!(sample(5, 721), vec![0, 1, 2, 3, 4]);
    }

    /// A non-finite value inside a run is kept so that the drawn line breaks there.
    #[test]
    fn non_finite_values_break_the_line() {
        let n = 10_000;
        let out = decimate(
            (0..n).map(|k| [k as f64, if k == 5000 { f64::NAN } else { 1.0 }]),
            n,
            100,
        );
        assert!(out.iter().any(|p| p[1].is_nan()));
    }
}
