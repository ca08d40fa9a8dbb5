//! `mechdiff.accuracy`: every derivative method of a scene against an extended-precision
//! reference, timed side by side ([`mechdiff::accuracy`], as `mechdiff accuracy` measures
//! it), handed to Python as the report's CSV text (`mechdiff/accuracy.py` makes it a
//! DataFrame).

use mechdiff::accuracy::{self, Timing, formula, whitworth};
use mechdiff::mechanisms::Whitworth;
use mechdiff::mechanisms::whitworth::Parameters;
use mechdiff::scene::Kind;
use pyo3::prelude::*;

use crate::errors::{argument, to_py};

/// The accuracy report of the scene `text` (named `file`; any kind: linkage, cam,
/// formulas, rotor; without `text`, the scene file at the path `file`) as CSV, each
/// method timed `repeats` times over at most `positions` drive positions; or, for
/// `file == "whitworth"` and no text, of the reference machine with crank ratio `crank_ratio`
/// (default 0.375). Without the GIL.
#[pyfunction]
#[pyo3(signature = (file, text = None, repeats = 15, positions = None, crank_ratio = None))]
pub fn accuracy_csv(
    py: Python<'_>,
    file: String,
    text: Option<String>,
    repeats: usize,
    positions: Option<usize>,
    crank_ratio: Option<f64>,
) -> PyResult<String> {
    if repeats > accuracy::MAX_REPEATS {
        return Err(argument(
            py,
            format!(
                "repeats={repeats} is over the limit of {}",
                accuracy::MAX_REPEATS
            ),
        ));
    }
    if positions == Some(0) {
        return Err(argument(
            py,
            "positions=0: measure at least one drive position".to_owned(),
        ));
    }
    let timing = Timing {
        repeats,
        ..Timing::default()
    };
    let measured = py.detach(|| -> mechdiff::Result<String> {
        let text = match text {
            Some(text) => text,
            None if file != "whitworth" => {
                mechdiff::files::read_scene(std::path::Path::new(&file))?
            }
            None => String::new(),
        };
        if file == "whitworth" && text.is_empty() {
            let mut parameters = Parameters::reference();
            if let Some(lambda) = crank_ratio {
                parameters.l1 = lambda * parameters.l0;
            }
            let shaper = Whitworth::new(parameters).map_err(|e| mechdiff::Error::Reference {
                what: "the Whitworth machine".into(),
                reason: e.to_string(),
            })?;
            let linkage = whitworth::linkage(&shaper)?;
            return Ok(thinned(whitworth::case(&shaper, &linkage)?, positions)?
                .measure(&timing)?
                .csv());
        }
        let report = match mechdiff::scene::kind(&text) {
            Kind::Formula => {
                let scene = formula::parse(&text, &file)?;
                thinned(formula::case(&scene, &file)?, positions)?.measure(&timing)?
            }
            Kind::Cam => {
                let scene = mechdiff::scene::cam::parse(&file, &text)?;
                accuracy::cam::case(&scene, positions)?.measure(&timing)?
            }
            Kind::Rotor => {
                let scene = mechdiff::scene::balancing::rotor_scene::parse(&file, &text)?;
                return Ok(accuracy::rotor::report(&scene)?.csv());
            }
            Kind::Linkage => {
                let mut scene = mechdiff::scene::parse(&file, &text)?;
                accuracy::scene::default_outputs(&mut scene);
                let mechanism = mechdiff::scene::build::mechanism(&scene)?;
                accuracy::scene::case_at(&scene, &mechanism, positions)?.measure(&timing)?
            }
        };
        Ok(report.csv())
    });
    measured.map_err(|e| to_py(py, &e))
}

/// `case` thinned to `positions` drive positions, or whole.
fn thinned(
    case: accuracy::Case<'_>,
    positions: Option<usize>,
) -> mechdiff::Result<accuracy::Case<'_>> {
    match positions {
        Some(n) => case.thinned(n),
        None => Ok(case),
    }
}
