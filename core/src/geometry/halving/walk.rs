// This file is also emitted into the generated module of a mixed plan, its items `pub(super)`
// there (see `halving::SOURCE`): it uses nothing but `core` and `std`, has no inner
// attributes and no tests (the module's documentation and tests are in `halving.rs`).

/// What one attempted step came to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Attempt<F> {
    /// The step was taken: the walk stands at its end, and the next step may be twice as
    /// long (one halving given back).
    Accepted,
    /// The step was not taken (`F` says why): it is halved and tried again; once halving no
    /// longer helps, `F` goes to the walk's `exhausted`.
    Failed(F),
}

/// How a walk that reached its end went.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Walked {
    /// Steps taken (accepted, or accepted by `exhausted`).
    pub steps: usize,
    /// Attempts that failed.
    pub failures: usize,
}

/// Why a walk stopped short of its end.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stop<E> {
    /// It would have taken more than `max_substeps` attempts.
    TooLong,
    /// A step failed for good: the error of `attempt`, or of `exhausted`.
    Failed(E),
}

/// The limits of a walk from one drive position to another in steps: each at most
/// `longest`, a failing one halved (at most `max_subdivisions` times in a row), at most
/// `max_substeps` attempts in all.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepHalving {
    /// The longest step tried at once (the drive's units, > 0).
    pub longest: f64,
    /// Halvings of a failing step before it is given up.
    pub max_subdivisions: usize,
    /// Attempts (taken or not) allowed in one walk.
    pub max_substeps: usize,
}

impl StepHalving {
    /// Walks `state` from `from` to `to`. Each step goes as far as the last one allowed,
    /// and at most `longest`: `attempt(state, target, h)` tries to move `state` to
    /// `target` (`h`, the step's length as halved, is `target − at` up to rounding; when
    /// the step reaches `to`, `target` is `to` exactly). An accepted step gives back one
    /// halving; a failed one is halved. When halving no longer helps (more than
    /// `max_subdivisions` halvings, or the halved step no longer moves the drive),
    /// `exhausted(state, target, failure)` decides: an error ends the walk, `Ok` means the
    /// caller took the step after all (`state` is at `target`) and the halvings start
    /// over. At least one step is attempted, even when `from == to`. An error of `attempt`
    /// ends the walk at once.
    ///
    /// # Errors
    /// [`Stop::TooLong`] before an attempt beyond `max_substeps`; [`Stop::Failed`] with
    /// the error of `attempt` or `exhausted`. `state` is left where the last step took it.
    // Inlined into each caller: a move of the solver is one step most of the time, and the
    // call (with the state behind a reference) cost it 4 % of its instructions.
    #[inline(always)]
    pub fn walk<S, F, E>(
        &self,
        state: &mut S,
        from: f64,
        to: f64,
        mut attempt: impl FnMut(&mut S, f64, f64) -> Result<Attempt<F>, E>,
        mut exhausted: impl FnMut(&mut S, f64, F) -> Result<(), E>,
    ) -> Result<Walked, Stop<E>> {
        let halved = |full: f64, halvings: usize| full / f64::powi(2.0, halvings.min(1074) as i32);
        let mut walked = Walked {
            steps: 0,
            failures: 0,
        };
        let (mut at, mut halvings) = (from, 0usize);
        while at != to || walked.steps == 0 {
            if walked.steps + walked.failures >= self.max_substeps {
                return Err(Stop::TooLong);
            }
            let remaining = to - at;
            let full = if remaining.abs() > self.longest {
                self.longest.copysign(remaining)
            } else {
                remaining
            };
            let h = halved(full, halvings);
            let target = if halvings == 0 && full == remaining {
                to
            } else {
                at + h
            };
            match attempt(state, target, h).map_err(Stop::Failed)? {
                Attempt::Accepted => {
                    at = target;
                    walked.steps += 1;
                    halvings = halvings.saturating_sub(1);
                }
                Attempt::Failed(failure) => {
                    walked.failures += 1;
                    halvings += 1;
                    if halvings > self.max_subdivisions || at + halved(full, halvings) == at {
                        exhausted(state, target, failure).map_err(Stop::Failed)?;
                        at = target;
                        walked.steps += 1;
                        halvings = 0;
                    }
                }
            }
        }
        Ok(walked)
    }
}
