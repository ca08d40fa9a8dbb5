//! The `Cam` class: a cam scene (a file with a `[cam]` section) read and checked, its SVAJ
//! table, profile, summary and report as the command line writes them
//! ([`mechdiff::report::cam`]), and s, s′, s″, s‴ at any cam angles as NumPy arrays.

use std::path::PathBuf;

use mechdiff::core::cams::continuity::ContinuityReport;
use mechdiff::core::cams::law::Side;
use mechdiff::report::cam;
use mechdiff::scene::cam::CamScene;
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::{argument, to_py};

/// The most cam angles of one `svaj_at` call (80 MB of results).
pub const MAX_CAM_ANGLES: usize = 10_000_000;

/// A cam scene read and checked (`mechdiff.Cam` wraps it; see `mechdiff/cams.py`).
#[pyclass(module = "mechdiff._mechdiff", name = "Cam", frozen)]
pub struct Cam {
    scene: CamScene,
}

/// Text a writer of [`cam`] wrote into memory (it cannot fail there).
fn written(write: impl FnOnce(&mut Vec<u8>) -> std::io::Result<()>) -> String {
    let mut out = Vec::new();
    // Writing into a vector cannot fail.
    let _ = write(&mut out);
    String::from_utf8_lossy(&out).into_owned()
}

#[pymethods]
impl Cam {
    /// Reads and checks the cam scene file at `path`.
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        let scene = py.detach(|| mechdiff::scene::cam::load(&path));
        Ok(Cam {
            scene: scene.map_err(|e| to_py(py, &e))?,
        })
    }

    /// Reads and checks a cam scene given as `text`, named `file` in messages.
    #[staticmethod]
    #[pyo3(signature = (text, file = "<text>".to_owned()))]
    fn parse(py: Python<'_>, text: String, file: String) -> PyResult<Self> {
        let scene = py.detach(|| mechdiff::scene::cam::parse(&file, &text));
        Ok(Cam {
            scene: scene.map_err(|e| to_py(py, &e))?,
        })
    }

    /// The name of the file in messages.
    #[getter]
    fn file(&self) -> &str {
        &self.scene.file
    }

    /// The scene's title, if it has one.
    #[getter]
    fn title(&self) -> Option<&str> {
        self.scene.title.as_deref()
    }

    /// The SVAJ table as the report prints it, every `step` of the file: a dict with
    /// `headers` (`name [unit]`, the cam angle first), `theta` (the cam angles in the file's
    /// unit), `side` (`"left"`/`"right"` for the two rows at a boundary where a derivative
    /// jumps, else `""`) and `values` (an array `[row, column]` of the other columns, in
    /// their units).
    fn svaj<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let (header, theta, side, values) = py.detach(|| {
            let report = ContinuityReport::new(&self.scene.mechanism.program);
            let rows = cam::svaj_rows(&self.scene, &report);
            let (header, cells) = cam::table_cells(&self.scene, &rows);
            let theta: Vec<f64> = rows.iter().map(|r| r.shown_theta).collect();
            let side: Vec<&str> = (rows.iter())
                .map(|r| match r.side {
                    Some(Side::Left) => "left",
                    Some(Side::Right) => "right",
                    None => "",
                })
                .collect();
            let values: Vec<Vec<f64>> = cells.into_iter().map(|(_, v)| v).collect();
            (header, theta, side, values)
        });
        let dict = PyDict::new(py);
        dict.set_item("headers", header)?;
        dict.set_item("theta", PyArray1::from_vec(py, theta))?;
        dict.set_item("side", side)?;
        dict.set_item("values", PyArray2::from_vec2(py, &values)?)?;
        Ok(dict)
    }

    /// s, s′, s″, s‴ (SI: m or rad, per rad of cam angle) at the cam angles `theta` (rad),
    /// as an array `[angle, 4]`; at a boundary the limit from `side` (`"right"`, the
    /// segment that starts there, or `"left"`).
    #[pyo3(signature = (theta, side = "right"))]
    fn svaj_at<'py>(
        &self,
        py: Python<'py>,
        theta: PyReadonlyArray1<'py, f64>,
        side: &str,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let side = match side {
            "right" => Side::Right,
            "left" => Side::Left,
            other => {
                return Err(argument(
                    py,
                    format!("side={other:?} is not one; expected \"right\" or \"left\""),
                ));
            }
        };
        let theta = theta.as_slice()?;
        if theta.len() > MAX_CAM_ANGLES {
            return Err(argument(
                py,
                format!(
                    "{} cam angles in one call is over the limit of {MAX_CAM_ANGLES}; ask in \
                     chunks",
                    theta.len()
                ),
            ));
        }
        if let Some(i) = theta.iter().position(|t| !t.is_finite()) {
            return Err(argument(
                py,
                format!(
                    "cam angle {i} (from 0) is {}; give finite angles (rad)",
                    theta[i]
                ),
            ));
        }
        let program = &self.scene.mechanism.program;
        let values: Vec<f64> = py.detach(|| {
            (theta.iter())
                .flat_map(|&t| {
                    let jet = program.svaj(t, side);
                    [jet.value, jet.d1(), jet.d2(), jet.d3()]
                })
                .collect()
        });
        PyArray1::from_vec(py, values).reshape([theta.len(), 4])
    }

    /// The profile for CAD/CNC as the CSV of `mechdiff run --profile-csv` writes it (cam
    /// angle, pitch point, profile point, outward normal, every 0.5°), as text.
    fn profile_csv(&self, py: Python<'_>) -> String {
        py.detach(|| written(|out| cam::write_profile_csv(&self.scene, out)))
    }

    /// The summary as the JSON of `mechdiff run --json` (follower, base circle, largest
    /// pressure angle, smallest radii of curvature, undercut, boundaries' continuity,
    /// warnings), as text.
    fn summary_json(&self, py: Python<'_>) -> String {
        py.detach(|| written(|out| cam::write_json(&self.scene, out)))
    }

    /// The report `mechdiff run` prints, as text.
    fn report(&self, py: Python<'_>) -> String {
        py.detach(|| written(|out| cam::write_report(&self.scene, out)))
    }
}
