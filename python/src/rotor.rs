//! The `Rotor` class: a rotor scene (a `[rotor]` section) read and checked, its answers
//! (static, two-plane and couple-plane balance) as the command line writes them
//! ([`mechdiff::report::rotor`]).

use std::path::PathBuf;

use mechdiff::scene::balancing::RotorScene;
use pyo3::prelude::*;

use crate::errors::to_py;

/// A rotor scene read, checked and answered (`mechdiff.Rotor` wraps it; see
/// `mechdiff/rotors.py`).
#[pyclass(module = "mechdiff._mechdiff", name = "Rotor", frozen)]
pub struct Rotor {
    scene: RotorScene,
    /// The answers as the JSON of `mechdiff run --json`.
    json: String,
    /// The report's lines as printed.
    lines: Vec<String>,
}

impl Rotor {
    fn answered(
        py: Python<'_>,
        read: impl Send + FnOnce() -> mechdiff::Result<RotorScene>,
    ) -> PyResult<Self> {
        let answered = py.detach(|| {
            let scene = read()?;
            let answers = scene.rotor.answers()?;
            let lines = scene.lines()?;
            let mut json = Vec::new();
            // Writing into a vector cannot fail.
            let _ = mechdiff::report::rotor::write_json(&scene, &answers, &mut json);
            let json = String::from_utf8_lossy(&json).into_owned();
            Ok(Rotor { scene, json, lines })
        });
        answered.map_err(|e: mechdiff::Error| to_py(py, &e))
    }
}

#[pymethods]
impl Rotor {
    /// Reads and checks the rotor scene file at `path` and computes its answers.
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        Self::answered(py, move || {
            mechdiff::scene::balancing::rotor_scene::load(&path)
        })
    }

    /// Reads and checks a rotor scene given as `text` (named `file` in messages) and
    /// computes its answers.
    #[staticmethod]
    #[pyo3(signature = (text, file = "<text>".to_owned()))]
    fn parse(py: Python<'_>, text: String, file: String) -> PyResult<Self> {
        Self::answered(py, move || {
            mechdiff::scene::balancing::rotor_scene::parse(&file, &text)
        })
    }

    /// The name of the file in messages.
    #[getter]
    fn file(&self) -> &str {
        &self.scene.file
    }

    /// The answers as the JSON of `mechdiff run --json`: `{"file", "title", "rows"}`, a
    /// row per mass and answer keyed by the CSV's headers, in the scene's units.
    fn answers_json(&self) -> &str {
        &self.json
    }

    /// The report's lines as `mechdiff run` prints them.
    fn lines(&self) -> Vec<String> {
        self.lines.clone()
    }
}
