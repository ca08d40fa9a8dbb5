//! The sweep's drive positions: a list written in the file, or `from`, `to` and `step`
//! counted on demand, so that a sweep of 10⁸ positions holds none of them in memory.

use crate::error::{Error, Location, Result};

/// The most positions of a sweep whose rows are all held in memory: the runs that need every
/// row at once (dynamics, balancing, `--json`, `--plot`, `--report`). A streamed run (the
/// table, `--csv`, `--jsonl`) has no such limit.
pub const MAX_IN_MEMORY: usize = 1_000_000;

/// The positions of `[sweep]`, in SI, in drive order.
#[derive(Debug, Clone, PartialEq)]
pub enum Positions {
    /// Listed in the file (`positions = [...]`).
    List(Vec<f64>),
    /// `from + i·step` for `i` in `0..count`, counted in the file's units and converted to
    /// SI by `factor`, so that 0..360 by 0.5 deg gives exactly the 721 positions written.
    Steps {
        /// `from`, in the file's units.
        from: f64,
        /// `step`, in the file's units (negative for a sweep from `from` down to `to`).
        step: f64,
        /// The number of positions.
        count: usize,
        /// SI value per file unit.
        factor: f64,
        /// Where `step` is written (named when the sweep is too long for a run in memory).
        location: Location,
    },
}

impl Positions {
    /// The number of positions.
    pub fn len(&self) -> usize {
        match self {
            Self::List(list) => list.len(),
            Self::Steps { count, .. } => *count,
        }
    }

    /// Whether there is no position (never, for a checked scene).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The `i`-th position (SI); `i < len()`.
    pub fn get(&self, i: usize) -> f64 {
        match self {
            Self::List(list) => list[i],
            Self::Steps {
                from, step, factor, ..
            } => (from + i as f64 * step) * factor,
        }
    }

    /// The positions in order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = f64> + Clone + '_ {
        (0..self.len()).map(|i| self.get(i))
    }

    /// The positions in a vector, for the runs that hold every row in memory: at most
    /// `MAX_IN_MEMORY`, else an error naming `step` and what to do instead.
    pub fn to_vec(&self) -> Result<Vec<f64>> {
        if let Self::Steps {
            count, location, ..
        } = self
            && *count > MAX_IN_MEMORY
        {
            return Err(Error::Invalid {
                location: location.clone(),
                message: format!(
                    "the sweep has {count} positions; dynamics, balancing, `--json`, `--plot` \
                     and `--report` hold every row in memory and take at most {MAX_IN_MEMORY}: \
                     use a larger step, or the streamed outputs alone (the table, `--csv`, \
                     `--jsonl`), which take any number"
                ),
            });
        }
        Ok(self.iter().collect())
    }

    /// The smallest and the largest position, without walking a range (`from + i·step`
    /// times a positive factor is monotone in `i`: the extremes are the two ends).
    pub fn range(&self) -> (f64, f64) {
        match self {
            Self::List(list) => (list.iter())
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &p| {
                    (lo.min(p), hi.max(p))
                }),
            Self::Steps { count, .. } => {
                let (first, last) = (self.get(0), self.get(count - 1));
                (first.min(last), first.max(last))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Positions are counted in the file's units, then converted: 0..360 by 0.5 deg ends
    /// exactly on 360 deg (both products exact or correctly rounded in f64).
    #[test]
    fn steps_are_counted_in_the_file_units() {
        let factor = std::f64::consts::PI / 180.0;
        let p = Positions::Steps {
            from: 0.0,
            step: 0.5,
            count: 721,
            factor,
            location: Location {
                file: "s.toml".into(),
                line: 1,
                column: 1,
            },
        };
        assert_eq!(p.len(), 721);
        assert_eq!(p.get(720), 360.0 * factor);
        assert_eq!(p.range(), (0.0, 360.0 * factor));
        assert_eq!(p.to_vec().unwrap().len(), 721);
    }

    /// A sweep downwards (negative step) has the same extremes as its upward twin: `range`
    /// orders its two ends (exact: both are the same products).
    #[test]
    fn a_downward_sweep_has_its_ends_as_range() {
        let location = Location {
            file: "s.toml".into(),
            line: 1,
            column: 1,
        };
        let down = Positions::Steps {
            from: 360.0,
            step: -10.0,
            count: 37,
            factor: 1.0,
            location,
        };
        assert_eq!(down.get(36), 0.0);
        assert_eq!(down.range(), (0.0, 360.0));
    }
}
