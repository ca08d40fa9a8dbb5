//! The progress bar of a long run on stderr: indicatif's with the `progress` feature; without
//! it, a bar that shows nothing.

#[cfg(feature = "progress")]
pub(crate) use indicatif::ProgressBar;

/// A progress bar on stderr counting drive positions, or a hidden one.
#[cfg(feature = "progress")]
pub(crate) fn bar(shown: bool, positions: usize) -> ProgressBar {
    use indicatif::ProgressStyle;
    if !shown {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(positions as u64);
    if let Ok(style) = ProgressStyle::with_template(
        "{bar:40} {human_pos}/{human_len} positions, {per_sec}, {eta} left",
    ) {
        bar.set_style(style);
    }
    bar
}

/// No progress bar: built without the `progress` feature.
#[cfg(not(feature = "progress"))]
pub(crate) fn bar(_shown: bool, _positions: usize) -> ProgressBar {
    ProgressBar
}

/// A bar that shows nothing (indicatif's API as used by the crate).
#[cfg(not(feature = "progress"))]
#[derive(Debug)]
pub(crate) struct ProgressBar;

#[cfg(not(feature = "progress"))]
impl ProgressBar {
    /// Runs `work` (nothing to hide while it writes).
    pub(crate) fn suspend<R>(&self, work: impl FnOnce() -> R) -> R {
        work()
    }

    /// Nothing to count.
    pub(crate) fn inc(&self, _delta: u64) {}

    /// Nothing to clear.
    pub(crate) fn finish_and_clear(&self) {}
}
