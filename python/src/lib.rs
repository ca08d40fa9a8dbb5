//! `mechdiff._mechdiff`: the Rust half of the mechdiff Python package.
//!
//! A thin layer over the facade's library API ([`mechdiff::parse_with`], [`mechdiff::run_with`],
//! [`mechdiff::sensitivity::run`]): a [`scene::Scene`] holds a read scene with its text and
//! settings; its runs hand columns to NumPy without copying them again ([`columns`]); its
//! failures become the exception classes of `mechdiff/errors.py` ([`errors`]). The Python
//! modules beside it (`mechdiff/__init__.py`, `mechdiff/study.py`) present the results.
//!
//! Every run releases the GIL (`Python::detach`), so two Python threads run two scenes at
//! once; a batch of variants ([`variants`]) checks for Ctrl-C between its blocks.

mod columns;
mod errors;
mod scene;
mod synthesis;
mod variants;

use pyo3::prelude::*;

/// The extension module: the `Scene` class and the limits a caller may need.
#[pymodule]
fn _mechdiff(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<scene::Scene>()?;
    m.add_class::<synthesis::SynthesisProblem>()?;
    m.add("MAX_VARIANTS", variants::MAX_VARIANTS)?;
    m.add("MAX_VALUES", variants::MAX_VALUES)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
