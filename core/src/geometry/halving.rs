//! One step-halving walk from one drive position to another, written once: the solver's
//! closed-form and Newton paths ([`super::Tracker::move_to`]), the mixed plan's run-time
//! evaluator ([`crate::trace::MixedTracker`]) and the generated code of a mixed plan (which
//! includes [`SOURCE`], so that it depends on nothing) all walk with [`StepHalving::walk`].
//!
//! Steps of at most a longest one (1/8 rad, or 1/8 of the sketch for a displacement drive:
//! see the solver); a step that fails is halved and tried again, an accepted one gives one
//! halving back; after `max_subdivisions` halvings (or once a halved step no longer moves
//! the drive position) the caller decides from the last failure, and a walk of more than
//! `max_substeps` attempts is refused rather than run for hours.

mod walk;

use std::sync::LazyLock;

pub use walk::{Attempt, StepHalving, Stop, Walked};

/// The walk's source as the solver compiles it.
const WALK: &str = include_str!("halving/walk.rs");

/// The source of the walk (`halving/walk.rs`), for the generated code of a mixed plan to
/// include in a module of its own: the same text the solver compiles, so the two walk alike
/// step for step, except that its items are `pub(super)` instead of `pub` — visible to the
/// generated module that includes them, not a part of that module's public items.
pub static SOURCE: LazyLock<String> = LazyLock::new(|| WALK.replace("\npub ", "\npub(super) "));

#[cfg(test)]
mod tests {
    use super::*;

    /// The emitted walk is the compiled one with each of its items (a line starting `pub `:
    /// `Attempt`, `Walked`, `Stop`, `StepHalving`) made `pub(super)`, and nothing else
    /// changed.
    #[test]
    fn the_emitted_walk_has_its_items_private_to_the_including_module() {
        let items = |text: &str, start: &str| text.lines().filter(|l| l.starts_with(start)).count();
        assert_eq!(items(WALK, "pub "), 4);
        assert_eq!(items(&SOURCE, "pub "), 0);
        assert_eq!(items(&SOURCE, "pub(super) "), 4);
        assert_eq!(SOURCE.replace("\npub(super) ", "\npub "), WALK);
    }

    const HALVING: StepHalving = StepHalving {
        longest: 0.125,
        max_subdivisions: 24,
        max_substeps: 100_000,
    };

    /// A walk of 1 in steps of at most 1/8: eight steps, the last one landing on `to`
    /// exactly (not on the sum of the steps), each target the last plus 1/8 (exact in
    /// binary).
    #[test]
    fn long_walks_go_in_steps_of_at_most_the_longest() {
        let mut targets = Vec::new();
        let walked = HALVING.walk(
            &mut targets,
            0.0,
            1.0,
            |t: &mut Vec<f64>, target, h| {
                assert_eq!(h, 0.125);
                t.push(target);
                Ok::<_, ()>(Attempt::<()>::Accepted)
            },
            |_, _, ()| Err(()),
        );
        assert_eq!(
            walked,
            Ok(Walked {
                steps: 8,
                failures: 0
            })
        );
        let expected: Vec<f64> = (1..=8).map(|k| f64::from(k) * 0.125).collect();
        assert_eq!(targets, expected);
    }

    /// Steps longer than 0.03 fail: from 0 to 0.1 the first try (0.1) and its half fail,
    /// a quarter (0.025) is taken; then half the remaining 0.075 fails and a quarter of it
    /// is taken; then half the remaining (0.028) is taken and the rest at full length:
    /// 4 steps, 3 failures, ending on 0.1 exactly.
    #[test]
    fn failing_steps_are_halved_and_grow_back() {
        let mut at = 0.0;
        let walked = HALVING.walk(
            &mut at,
            0.0,
            0.1,
            |at: &mut f64, target, _| {
                if target - *at > 0.03 {
                    return Ok::<_, ()>(Attempt::Failed(()));
                }
                *at = target;
                Ok(Attempt::Accepted)
            },
            |_, _, ()| Err(()),
        );
        assert_eq!(at, 0.1);
        let walked = walked.unwrap();
        assert_eq!(walked.steps, 4, "{walked:?}");
        assert_eq!(walked.failures, 3, "{walked:?}");
    }

    /// A step that always fails is halved `max_subdivisions` times, then given to
    /// `exhausted`: its error ends the walk after 1 + 24 attempts, at the last target tried
    /// (the first step over 2²⁴).
    #[test]
    fn a_step_failing_after_every_halving_goes_to_exhausted() {
        let mut tries = 0usize;
        let stop = HALVING.walk(
            &mut tries,
            0.0,
            1.0,
            |tries: &mut usize, _, _| {
                *tries += 1;
                Ok::<_, f64>(Attempt::Failed(()))
            },
            |_, target, ()| Err(target),
        );
        assert_eq!(tries, 25);
        assert_eq!(stop, Err(Stop::Failed(0.125 / f64::powi(2.0, 24))));
    }

    /// `exhausted` may take the step after all: the walk goes on, its halvings start
    /// over. Every attempt fails and `max_subdivisions` is 1: each step is tried at full
    /// length, then at half, and that half is taken by `exhausted` (the last one, once half
    /// of the rest no longer moves the position, at full length). The walk still ends on
    /// its end exactly, after 1 or 2 failures per step.
    #[test]
    fn exhausted_may_take_the_step() {
        let halving = StepHalving {
            max_subdivisions: 1,
            ..HALVING
        };
        let mut at = 0.0;
        let walked = halving.walk(
            &mut at,
            0.0,
            0.25,
            |_: &mut f64, _, _| Ok::<_, ()>(Attempt::Failed(())),
            |at, target, ()| {
                *at = target;
                Ok(())
            },
        );
        assert_eq!(at, 0.25);
        let walked = walked.unwrap();
        assert!(walked.steps > 1, "{walked:?}");
        assert!(
            (2 * walked.steps - 1..=2 * walked.steps).contains(&walked.failures),
            "{walked:?}"
        );
    }

    /// A walk needing more attempts than `max_substeps` stops before the one too many; a
    /// walk to where it stands attempts one step.
    #[test]
    fn walks_are_bounded_and_never_empty() {
        let bounded = StepHalving {
            max_substeps: 3,
            ..HALVING
        };
        let mut count = 0usize;
        let accept = |count: &mut usize, _, _| {
            *count += 1;
            Ok::<_, ()>(Attempt::<()>::Accepted)
        };
        let stop = bounded.walk(&mut count, 0.0, 1.0, accept, |_, _, ()| Err(()));
        assert_eq!((stop, count), (Err(Stop::TooLong), 3));
        count = 0;
        let walked = bounded.walk(&mut count, 0.5, 0.5, accept, |_, _, ()| Err(()));
        assert_eq!(
            (walked, count),
            (
                Ok(Walked {
                    steps: 1,
                    failures: 0
                }),
                1
            )
        );
    }
}
