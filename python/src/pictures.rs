//! A run's pictures for Jupyter (`Run._repr_html_`): the mechanism drawn at the first
//! drawn position and the run's diagram, as the facade's HTML report draws them
//! ([`mechdiff::pictures::run`]), each an inline SVG that needs no network.

use mechdiff::pictures::run::{Animation, diagram};
use mechdiff::{Report, Scene};
use pyo3::prelude::*;

use crate::errors::to_py;

/// The most drive positions of a run whose report is kept for its pictures (a few MB at
/// most); a longer run is shown without them (plot a run at fewer positions).
pub const MAX_PICTURED_ROWS: usize = 1 << 16;

/// A run's scene and report, kept for its pictures.
#[pyclass(module = "mechdiff._mechdiff", name = "Pictures", frozen)]
pub struct Pictures {
    scene: Scene,
    report: Report,
}

impl Pictures {
    /// The pictures of `report`, a run of `scene`, if it is short enough to keep.
    pub fn of(scene: &Scene, report: Report) -> Option<Self> {
        (report.rows.len() <= MAX_PICTURED_ROWS).then(|| Pictures {
            scene: scene.clone(),
            report,
        })
    }
}

#[pymethods]
impl Pictures {
    /// The run's diagram (its panels against the drive position, dead positions and limits
    /// marked) as SVG text, without the GIL.
    fn diagram_svg(&self, py: Python<'_>) -> PyResult<String> {
        py.detach(|| diagram(&self.scene, &self.report)?.to_svg())
            .map_err(|e| to_py(py, &e))
    }

    /// The mechanism drawn at the run's first drawn position, its traced paths over the
    /// sweep, as SVG text, without the GIL.
    fn drawing_svg(&self, py: Python<'_>) -> PyResult<String> {
        py.detach(|| {
            let animation = Animation::of(&self.scene, &self.report)?;
            let title = (self.scene.title.clone()).unwrap_or_else(|| self.scene.file.clone());
            let first = animation.poses.xy.first().cloned().unwrap_or_default();
            Ok(animation.drawing(&self.scene, &title, &first).to_svg())
        })
        .map_err(|e: mechdiff::Error| to_py(py, &e))
    }
}
