//! The search's convergence history: the best objective against the evaluations spent, one
//! point per improvement, bounded in size.

/// The most points a [`History`] keeps.
pub const MAX_HISTORY: usize = 1000;

/// One improvement of the best objective.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Improvement {
    /// Residual evaluations spent when it was found (counted as [`super::Report::evaluations`]).
    pub evaluations: usize,
    /// The best objective from then on.
    pub objective: f64,
}

/// The improvements of the best objective in the order found. At most [`MAX_HISTORY`] are
/// kept: when one more would exceed it, every second of the older ones is dropped (the first
/// and the latest always kept), so a long search keeps an even sketch of its whole course.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct History {
    improvements: Vec<Improvement>,
}

impl History {
    /// Records `objective` found after `evaluations`, if it improves on the best so far
    /// (non-finite values are never an improvement).
    pub fn record(&mut self, evaluations: usize, objective: f64) {
        if !objective.is_finite()
            || self
                .improvements
                .last()
                .is_some_and(|best| objective >= best.objective)
        {
            return;
        }
        if self.improvements.len() == MAX_HISTORY {
            let last = self.improvements.len() - 1;
            let mut k = 0;
            self.improvements.retain(|_| {
                let keep = k % 2 == 0 || k == last;
                k += 1;
                keep
            });
        }
        self.improvements.push(Improvement {
            evaluations,
            objective,
        });
    }

    /// The improvements kept, in the order found (objectives decreasing).
    pub fn improvements(&self) -> &[Improvement] {
        &self.improvements
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_improvements_are_kept_and_never_more_than_the_bound() {
        let mut h = History::default();
        h.record(1, 4.0);
        h.record(2, 5.0);
        h.record(3, f64::NAN);
        h.record(4, 4.0);
        h.record(5, 1.0);
        assert_eq!(
            h.improvements(),
            [
                Improvement {
                    evaluations: 1,
                    objective: 4.0
                },
                Improvement {
                    evaluations: 5,
                    objective: 1.0
                }
            ]
        );
        let mut long = History::default();
        for k in 0..100_000 {
            long.record(k, 1.0 / (k as f64 + 1.0));
            assert!(long.improvements().len() <= MAX_HISTORY);
        }
        let kept = long.improvements();
        assert_eq!(kept[0].evaluations, 0);
        assert_eq!(kept[kept.len() - 1].evaluations, 99_999);
        assert!(kept.windows(2).all(|w| w[1].objective < w[0].objective));
    }
}
