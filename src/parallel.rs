//! Work shared among threads: rayon with the `parallel` feature; without it, the same calls
//! run in order on the calling thread.
//!
//! The callers ([`crate::stream`], the Monte-Carlo samples of [`crate::sensitivity`], the
//! local searches of [`crate::scene::synthesize`]) give the same results in either case by
//! construction: every parallel piece of work writes to
//! its own place and is joined in order. Only the names used by the crate are provided.

#[cfg(feature = "parallel")]
pub(crate) use rayon::{ThreadPool, ThreadPoolBuilder, join, prelude};

#[cfg(not(feature = "parallel"))]
pub(crate) use sequential::{ThreadPool, ThreadPoolBuilder, join, prelude};

/// rayon's API as used by the crate, run in order on the calling thread.
#[cfg(any(test, not(feature = "parallel")))]
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

#[cfg(test)]
mod tests {
    use super::sequential;

    /// What the stream's formatting does: chunks of rows, each turned into its own text, then
    /// joined in order (`stream::format_batch`).
    fn texts_in_order(rows: &[f64], chunk: usize) -> Vec<String> {
        use sequential::prelude::*;
        let mut texts = vec![String::new(); rows.len().div_ceil(chunk)];
        (texts.par_iter_mut())
            .zip(rows.par_chunks(chunk))
            .for_each(|(text, rows)| {
                for x in rows {
                    text.push_str(&format!("{x:e}\n"));
                }
            });
        texts
    }

    /// The sequential stand-ins do what a plain loop does: the texts of the chunks are those
    /// of the rows in order, `join` gives both results, the pool has one thread and runs
    /// the work it is given.
    #[test]
    fn the_sequential_stand_ins_give_the_results_of_a_plain_loop() {
        let rows: Vec<f64> = (0..1000).map(|k| f64::from(k).sqrt()).collect();
        let texts = texts_in_order(&rows, 64);
        let plain: String = rows.iter().map(|x| format!("{x:e}\n")).collect();
        assert_eq!(texts.concat(), plain);
        use sequential::prelude::*;
        let lengths: usize = texts.par_iter().map(String::len).sum();
        assert_eq!(lengths, plain.len());
        assert_eq!(sequential::join(|| 1, || "two"), (1, "two"));
        let pool = sequential::ThreadPoolBuilder::new()
            .num_threads(8)
            .build()
            .unwrap();
        assert_eq!(pool.current_num_threads(), 1);
        assert_eq!(pool.install(|| rows.len()), 1000);
    }

    /// With the `parallel` feature, rayon's calls give the same texts as the stand-ins.
    #[cfg(feature = "parallel")]
    #[test]
    fn rayon_gives_the_texts_of_the_sequential_stand_ins() {
        use rayon::prelude::*;
        let rows: Vec<f64> = (0..1000).map(|k| f64::from(k).ln_1p()).collect();
        let mut texts = vec![String::new(); rows.len().div_ceil(64)];
        (texts.par_iter_mut())
            .zip(rows.par_chunks(64))
            .for_each(|(text, rows)| {
                for x in rows {
                    text.push_str(&format!("{x:e}\n"));
                }
            });
        assert_eq!(texts, texts_in_order(&rows, 64));
    }
}
