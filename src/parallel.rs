//! Work shared among threads: rayon with the `parallel` feature; without it, the same calls
//! run in order on the calling thread.
//!
//! The callers ([`crate::stream`], the Monte-Carlo samples of [`crate::sensitivity`]) give
//! the same results in either case by construction: every parallel piece of work writes to
//! its own place and is joined in order. Only the names used by the crate are provided.

#[cfg(feature = "parallel")]
pub(crate) use rayon::{ThreadPoolBuilder, join, prelude};

#[cfg(not(feature = "parallel"))]
pub(crate) use sequential::{ThreadPoolBuilder, join, prelude};

/// rayon's API as used by the crate, run in order on the calling thread.
#[cfg(not(feature = "parallel"))]
mod sequential {
    use std::convert::Infallible;

    /// Runs `a`, then `b`.
    pub(crate) fn join<A, B, RA, RB>(a: A, b: B) -> (RA, RB)
    where
        A: FnOnce() -> RA,
        B: FnOnce() -> RB,
    {
        let ra = a();
        (ra, b())
    }

    /// A builder of the one-thread "pool" (the number of threads asked for is ignored).
    #[derive(Debug, Default)]
    pub(crate) struct ThreadPoolBuilder;

    impl ThreadPoolBuilder {
        /// A builder.
        pub(crate) fn new() -> Self {
            Self
        }

        /// Ignored: the work runs on the calling thread.
        pub(crate) fn num_threads(self, _threads: usize) -> Self {
            self
        }

        /// The pool; it cannot fail.
        pub(crate) fn build(self) -> Result<ThreadPool, Infallible> {
            Ok(ThreadPool)
        }
    }

    /// The calling thread.
    #[derive(Debug)]
    pub(crate) struct ThreadPool;

    impl ThreadPool {
        /// One.
        pub(crate) fn current_num_threads(&self) -> usize {
            1
        }

        /// Runs `work` on the calling thread.
        pub(crate) fn install<R>(&self, work: impl FnOnce() -> R) -> R {
            work()
        }
    }

    /// The slice methods of rayon's prelude, as the ordinary iterators.
    pub(crate) mod prelude {
        /// `par_iter`, `par_iter_mut` and `par_chunks`, in order.
        pub(crate) trait ParallelSlice<T> {
            /// [`slice::iter`].
            fn par_iter(&self) -> std::slice::Iter<'_, T>;
            /// [`slice::iter_mut`].
            fn par_iter_mut(&mut self) -> std::slice::IterMut<'_, T>;
            /// [`slice::chunks`].
            fn par_chunks(&self, size: usize) -> std::slice::Chunks<'_, T>;
        }

        impl<T> ParallelSlice<T> for [T] {
            fn par_iter(&self) -> std::slice::Iter<'_, T> {
                self.iter()
            }

            fn par_iter_mut(&mut self) -> std::slice::IterMut<'_, T> {
                self.iter_mut()
            }

            fn par_chunks(&self, size: usize) -> std::slice::Chunks<'_, T> {
                self.chunks(size)
            }
        }
    }
}
