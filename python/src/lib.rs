//! `mechdiff._mechdiff`: the Rust half of the mechdiff Python package.
//!
//! A thin layer over the facade's library API ([`mechdiff::parse_with`], [`mechdiff::run_with`],
//! [`mechdiff::sensitivity::run`]): a `scene::Scene` holds a read scene with its text and
//! settings; its runs hand columns to NumPy without copying them again (`columns`); its
//! failures become the exception classes of `mechdiff/errors.py` (`errors`); its pictures
//! show in Jupyter (`pictures`). Cam and rotor scenes (`cam`, `rotor`), formula
//! derivatives (`formula`) and the accuracy report (`accuracy`) are beside it. The Python
//! modules beside it (`mechdiff/__init__.py`, `mechdiff/study.py`) present the results.
//!
//! Every run releases the GIL (`Python::detach`), so two Python threads run two scenes at
//! once; a batch of variants (`variants`) checks for Ctrl-C between its blocks.

mod accuracy;
mod cam;
mod columns;
mod errors;
mod formula;
mod pictures;
mod rotor;
mod scene;
mod synthesis;
mod variants;

use pyo3::prelude::*;

/// The extension module: the `Scene`, `Cam`, `Rotor` and `Formula` classes, the accuracy
/// report, and the limits a caller may need.
#[pymodule]
fn _mechdiff(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<scene::Scene>()?;
    m.add_class::<pictures::Pictures>()?;
    m.add_class::<cam::Cam>()?;
    m.add_class::<rotor::Rotor>()?;
    m.add_class::<formula::Formula>()?;
    m.add_function(wrap_pyfunction!(accuracy::accuracy_csv, m)?)?;
    m.add("MAX_CAM_ANGLES", cam::MAX_CAM_ANGLES)?;
    m.add("MAX_POINTS", formula::MAX_POINTS)?;
    m.add("MAX_PICTURED_ROWS", pictures::MAX_PICTURED_ROWS)?;
    m.add_class::<synthesis::SynthesisProblem>()?;
    m.add("MAX_VARIANTS", variants::MAX_VARIANTS)?;
    m.add("MAX_VALUES", variants::MAX_VALUES)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
