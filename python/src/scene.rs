//! The `Scene` class: a read and checked scene with the text and settings it was read from,
//! so that a sensitivity study or a variant re-reads it as the command line's `--set` does.

use std::ops::ControlFlow;
use std::path::PathBuf;

use mechdiff::evaluator::Evaluator;
use mechdiff::{RunOptions, Setting};
use numpy::{PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::columns::Columns;
use crate::errors::{argument, to_py};
use crate::pictures::Pictures;
use crate::variants;

/// Drive positions solved between two looks for Ctrl-C (a few milliseconds of a scene with
/// dynamics; the look itself takes a microsecond).
const CHUNK: usize = 1024;

/// A scene file read and checked (`mechdiff.Scene` wraps it; see `mechdiff/__init__.py`).
#[pyclass(module = "mechdiff._mechdiff", name = "Scene", frozen)]
pub struct Scene {
    /// The name the messages give the file.
    file: String,
    /// The scene's text as read.
    text: String,
    /// The parameters' values replaced (`--set NAME=VALUE`), in order.
    settings: Vec<Setting>,
    /// The scene read with them.
    scene: mechdiff::Scene,
}

/// What a scene pickles as: `Scene.parse` and its arguments (text, file, settings).
type Reduced = (Py<PyAny>, (String, String, Vec<(String, String)>));

/// `(name, value)` pairs as settings.
fn settings_of(pairs: Vec<(String, String)>) -> Vec<Setting> {
    pairs
        .into_iter()
        .map(|(name, value)| Setting { name, value })
        .collect()
}

impl Scene {
    /// Reads `text` (named `file`) with `settings`, without the GIL.
    fn read(py: Python<'_>, file: String, text: String, settings: Vec<Setting>) -> PyResult<Self> {
        let read = py.detach(|| mechdiff::parse_with(&file, &text, &settings));
        let scene = read.map_err(|e| to_py(py, &e))?;
        Ok(Scene {
            file,
            text,
            settings,
            scene,
        })
    }

    /// The read scene.
    pub fn scene(&self) -> &mechdiff::Scene {
        &self.scene
    }

    /// The text, name and settings it was read from.
    pub fn source(&self) -> (&str, &str, &[Setting]) {
        (&self.file, &self.text, &self.settings)
    }
}

#[pymethods]
impl Scene {
    /// Reads and checks the scene file at `path` with `settings` (`[(name, value), ...]`,
    /// each value a number or a formula of the other parameters, in the parameter's unit).
    #[staticmethod]
    #[pyo3(signature = (path, settings = Vec::new()))]
    fn load(py: Python<'_>, path: PathBuf, settings: Vec<(String, String)>) -> PyResult<Self> {
        let text = py
            .detach(|| mechdiff::files::read_scene(&path))
            .map_err(|e| to_py(py, &e))?;
        Self::read(py, path.display().to_string(), text, settings_of(settings))
    }

    /// Reads and checks a scene given as `text`, named `file` in messages.
    #[staticmethod]
    #[pyo3(signature = (text, file = "<text>".to_owned(), settings = Vec::new()))]
    fn parse(
        py: Python<'_>,
        text: String,
        file: String,
        settings: Vec<(String, String)>,
    ) -> PyResult<Self> {
        Self::read(py, file, text, settings_of(settings))
    }

    /// The same scene with `settings` added to its own (a later value of a parameter
    /// replaces an earlier one).
    fn with_settings(&self, py: Python<'_>, settings: Vec<(String, String)>) -> PyResult<Self> {
        let mut all = self.settings.clone();
        for new in settings_of(settings) {
            all.retain(|s| s.name != new.name);
            all.push(new);
        }
        Self::read(py, self.file.clone(), self.text.clone(), all)
    }

    /// The name of the file in messages.
    #[getter]
    fn file(&self) -> &str {
        &self.file
    }

    /// The scene's text as read.
    #[getter]
    fn text(&self) -> &str {
        &self.text
    }

    /// The scene's title, if it has one.
    #[getter]
    fn title(&self) -> Option<&str> {
        self.scene.title.as_deref()
    }

    /// The settings it was read with, `[(name, value), ...]`.
    #[getter]
    fn settings(&self) -> Vec<(String, String)> {
        (self.settings.iter())
            .map(|s| (s.name.clone(), s.value.clone()))
            .collect()
    }

    /// The values of `[parameters]` (after the settings), in the order they were
    /// evaluated, each in the unit of the fields that use it.
    #[getter]
    fn parameters(&self) -> Vec<(String, f64)> {
        self.scene.parameters.clone()
    }

    /// The number of drive positions of the scene's sweep.
    #[getter]
    fn positions(&self) -> usize {
        self.scene.positions.len()
    }

    /// Checks the scene without running its sweep (as `mechdiff check`): a dict with the
    /// `plan` line, the `columns` a run would have (`[(name, unit), ...]`), the
    /// `degrees_of_freedom`, the `loops` the solver closes (`[(joints, branch sign), ...]`)
    /// and which of them by a `closed_form`, and the drive's `motion_range` from the sketch
    /// (`(lower, upper)`, each `(position, kind, joints)` in the drive's unit or `None` when
    /// the drive turns fully that way; or why it could not be walked).
    fn check<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let checked = py
            .detach(|| mechdiff::scene::check(&self.scene))
            .map_err(|e| to_py(py, &e))?;
        let dict = PyDict::new(py);
        dict.set_item("plan", checked.plan.describe(&self.scene))?;
        let columns: Vec<(String, String)> = (checked.columns.iter())
            .map(|c| (c.name.clone(), c.unit.clone()))
            .collect();
        dict.set_item("columns", columns)?;
        dict.set_item("degrees_of_freedom", checked.mobility.degrees_of_freedom)?;
        dict.set_item("loops", checked.loops)?;
        dict.set_item("closed_form", checked.closed_form)?;
        // The ends of the drive's motion range from the sketch, in the drive's unit.
        let drive = self.scene.drive.kind.dimension();
        let end = |limit: &Option<mechdiff::core::geometry::DriveLimit>| {
            limit.as_ref().map(|l| {
                (
                    self.scene.units.from_si(l.phi, drive),
                    mechdiff::scene::kind_words(l.kind).to_owned(),
                    l.joints.clone(),
                )
            })
        };
        match &checked.motion_range {
            Ok(range) => dict.set_item("motion_range", (end(&range.lower), end(&range.upper)))?,
            Err(why) => dict.set_item("motion_range", why)?,
        }
        Ok(dict)
    }

    /// Runs the sweep (or the drive `positions`, in the scene's units of the sweep, when
    /// given) in memory, with the `evaluator` named (`auto`, `solver`, `program`,
    /// `interpreter`, `jit`), without the GIL, looking for Ctrl-C every `CHUNK` positions
    /// (`KeyboardInterrupt`). The columns and findings as a dict (see `Columns::into_py`),
    /// with `pictures`: the run's drawing and diagram (`None` for a run of more than
    /// `MAX_PICTURED_ROWS` positions).
    #[pyo3(signature = (positions = None, evaluator = None))]
    fn run<'py>(
        &self,
        py: Python<'py>,
        positions: Option<PyReadonlyArray1<'py, f64>>,
        evaluator: Option<&str>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let evaluator = match evaluator.unwrap_or("auto") {
            "auto" => Evaluator::Auto,
            "solver" => Evaluator::Solver,
            "program" => Evaluator::Program,
            "interpreter" => Evaluator::Interpreter,
            "jit" => Evaluator::Jit,
            other => {
                return Err(argument(
                    py,
                    format!(
                        "evaluator={other:?} is not one; expected \"auto\", \"solver\", \
                         \"program\", \"interpreter\" or \"jit\""
                    ),
                ));
            }
        };
        let positions = positions.as_ref().map(|p| p.as_slice()).transpose()?;
        let options = RunOptions { evaluator };
        let ran = py.detach(|| {
            let moved;
            let scene = match positions {
                Some(p) => {
                    moved = self.scene.with_positions(p)?;
                    &moved
                }
                None => &self.scene,
            };
            // Ctrl-C: the GIL taken back between chunks of positions to look for it.
            let flow = mechdiff::run_between(scene, &options, |done| {
                if done == 0 || done % CHUNK != 0 {
                    return ControlFlow::Continue(());
                }
                match Python::attach(|py| py.check_signals()) {
                    Ok(()) => ControlFlow::Continue(()),
                    Err(interrupted) => ControlFlow::Break(interrupted),
                }
            })?;
            Ok(flow.map_continue(|report| {
                let columns = Columns::of(scene, &report);
                (columns, Pictures::of(scene, report))
            }))
        });
        let (columns, pictures) = match ran.map_err(|e: mechdiff::Error| to_py(py, &e))? {
            ControlFlow::Continue(done) => done,
            ControlFlow::Break(interrupted) => return Err(interrupted),
        };
        let dict = columns.into_py(py)?;
        dict.set_item("pictures", pictures.map(|p| Py::new(py, p)).transpose()?)?;
        Ok(dict)
    }

    /// The linkage metrics of the scene (as `mechdiff check` prints them: Grashof class, the
    /// input's range, transmission angle, quick return), or `None` when it has none: the
    /// printed lines and the same as JSON text, in the scene's units, without the GIL.
    fn metrics(&self, py: Python<'_>) -> PyResult<Option<(Vec<String>, String)>> {
        let scene = &self.scene;
        py.detach(|| {
            let metrics = mechdiff::scene::metrics::SceneMetrics::of(scene)?;
            Ok(metrics.map(|m| (m.lines(scene), m.json(scene).to_string())))
        })
        .map_err(|e: mechdiff::Error| to_py(py, &e))
    }

    /// The Rust module computing the scene's outputs and their derivatives (as `mechdiff
    /// codegen SCENE` prints it), without the GIL.
    fn codegen(&self, py: Python<'_>) -> PyResult<String> {
        py.detach(|| mechdiff::codegen::scene::module(&self.scene, &self.file))
            .map_err(|e| to_py(py, &e))
    }

    /// Runs the scene with a `[sensitivity]` table asking for `columns`
    /// (`"d(COLUMN)/d(PARAMETER)"`; with none, the scene's own `[sensitivity]` and
    /// `[tolerances]`), without the GIL. Returns the run's dict (its derivative columns
    /// after the others) and, per derivative column, `(name, method, estimated_error,
    /// why)`: `method` is `"exact"` (dual numbers) or `"richardson"` (extrapolated
    /// differences, where the exact route does not reach, with the reason).
    #[allow(clippy::type_complexity)]
    fn sensitivity<'py>(
        &self,
        py: Python<'py>,
        columns: Vec<String>,
    ) -> PyResult<(Bound<'py, PyDict>, Vec<(String, String, f64, String)>)> {
        let mut text = self.text.clone();
        if !columns.is_empty() {
            if mechdiff::sensitivity::requested(&text) {
                return Err(argument(
                    py,
                    format!(
                        "{}: the scene has a `[sensitivity]` or `[tolerances]` table of its \
                         own; call sensitivity() without columns to run it, or remove it to \
                         ask for columns here",
                        self.file
                    ),
                ));
            }
            let list: Vec<String> = (columns.iter())
                .map(|c| toml::Value::String(c.clone()).to_string())
                .collect();
            text.push_str(&format!(
                "\n[sensitivity]\ncolumns = [{}]\n",
                list.join(", ")
            ));
        }
        let options = mechdiff::sensitivity::Options::default();
        let (columns, methods) = py
            .detach(|| {
                let (scene, report, study) =
                    mechdiff::sensitivity::run(&self.file, &text, &self.settings, &options)?;
                let methods = (study.iter())
                    .flat_map(|s| &s.derivatives)
                    .map(|d| match &d.method {
                        mechdiff::sensitivity::Method::Exact => {
                            (d.name.clone(), "exact".to_owned(), 0.0, String::new())
                        }
                        mechdiff::sensitivity::Method::Richardson {
                            estimated_error,
                            why,
                            ..
                        } => (
                            d.name.clone(),
                            "richardson".to_owned(),
                            *estimated_error,
                            why.clone(),
                        ),
                    })
                    .collect::<Vec<_>>();
                Ok((Columns::of(&scene, &report), methods))
            })
            .map_err(|e: mechdiff::Error| to_py(py, &e))?;
        Ok((columns.into_py(py)?, methods))
    }

    /// Runs one variant of the scene per row of `values` (`values[i, j]`: the value of
    /// parameter `names[j]` in variant `i`, in the parameter's unit), each over the scene's
    /// sweep, and returns the `columns` asked for (all when `None`) of every variant as an
    /// array `[variant, position, column]` in the columns' units, with the columns' names
    /// and the variants that failed as `[(index, kind, message), ...]` (their rows NaN). Without the GIL, in
    /// blocks between which Ctrl-C interrupts.
    #[allow(clippy::type_complexity)]
    #[pyo3(signature = (names, values, columns = None))]
    fn run_variants<'py>(
        &self,
        py: Python<'py>,
        names: Vec<String>,
        values: PyReadonlyArray2<'py, f64>,
        columns: Option<Vec<String>>,
    ) -> PyResult<(
        Bound<'py, numpy::PyArray3<f64>>,
        Vec<String>,
        Vec<(usize, String, String)>,
    )> {
        variants::run(py, self, &names, values, columns)
    }

    /// Pickling (Dask ships a scene to its workers): read again from the same text, name
    /// and settings.
    fn __reduce__(&self, py: Python<'_>) -> PyResult<Reduced> {
        let parse = py.get_type::<Scene>().getattr("parse")?.unbind();
        Ok((
            parse,
            (self.text.clone(), self.file.clone(), self.settings()),
        ))
    }
}
