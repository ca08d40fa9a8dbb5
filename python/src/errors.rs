//! The facade's [`mechdiff::Error`] as a Python exception of `mechdiff.errors`.
//!
//! The classes live in Python (`mechdiff/errors.py`), so that they can also derive from
//! `ValueError` or `OSError` where a Python user expects that; here each error picks its
//! class and hands over its message (the facade's, word for word: `file:line:column`, the
//! drive position in the scene's units, what to do) and its parts as attributes: `kind`
//! (the Rust variant), `file`, `line`, `column`, `position`, and `settings` for a run with
//! parameters moved. The class is the variant's own (`UnknownPointError`) where
//! `mechdiff/errors.py` has one (`class_for`), under the class of its group
//! (`InvalidSceneError`) that [`parts`] names.

use mechdiff::Error;
use mechdiff::error::Location;
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;

/// The Python module holding the exception classes.
const MODULE: &str = "mechdiff.errors";

/// What an exception carries besides its message.
#[derive(Default)]
struct Parts {
    /// The class's name in [`MODULE`].
    class: &'static str,
    /// The scene file.
    file: Option<String>,
    /// Line and column in it, from 1.
    at: Option<(usize, usize)>,
    /// The drive position, with its unit.
    position: Option<String>,
    /// The parameters as moved (a study's run, a parameter sweep).
    settings: Option<String>,
}

/// The Python exception for `error`: its class from [`MODULE`], its message, its parts.
pub fn to_py(py: Python<'_>, error: &Error) -> PyErr {
    match raise(py, error) {
        Ok(err) | Err(err) => err,
    }
}

fn raise(py: Python<'_>, error: &Error) -> PyResult<PyErr> {
    let mut parts = parts(error);
    let innermost = innermost(error);
    if !std::ptr::eq(innermost, error) {
        // A run with parameters moved: the class and the place are those of the failure
        // inside it, the message the whole story.
        let inner = self::parts(innermost);
        parts.class = inner.class;
        parts.file = parts.file.or(inner.file);
        parts.at = parts.at.or(inner.at);
        parts.position = parts.position.or(inner.position);
    }
    // The class of the variant (`UnknownPointError`), under the class of its group.
    let kind = kind(innermost);
    let class = (py.import(MODULE)?.getattr("class_for")?).call1((&kind, parts.class))?;
    let exception = class.call1((error.to_string(),))?;
    exception.setattr("kind", kind)?;
    exception.setattr("file", parts.file)?;
    exception.setattr("line", parts.at.map(|a| a.0))?;
    exception.setattr("column", parts.at.map(|a| a.1))?;
    exception.setattr("position", parts.position)?;
    exception.setattr("settings", parts.settings)?;
    Ok(PyErr::from_value(exception))
}

/// The error a run with moved parameters failed with, through every layer.
fn innermost(error: &Error) -> &Error {
    match error {
        Error::Perturbed { source, .. } | Error::AtParameter { source, .. } => innermost(source),
        other => other,
    }
}

/// The variant's name (`Unassemblable`): the first word of its debug form.
pub fn kind(error: &Error) -> String {
    let debug = format!("{error:?}");
    debug
        .split(|c: char| !c.is_alphanumeric())
        .next()
        .unwrap_or_default()
        .to_owned()
}

fn located(class: &'static str, location: &Location) -> Parts {
    Parts {
        class,
        file: Some(location.file.to_string()),
        at: Some((location.line, location.column)),
        ..Parts::default()
    }
}

fn in_file(class: &'static str, file: &str, position: Option<&str>) -> Parts {
    Parts {
        class,
        file: Some(file.to_owned()),
        position: position.map(str::to_owned),
        ..Parts::default()
    }
}

/// The class and parts of one layer of an error.
fn parts(error: &Error) -> Parts {
    match error {
        Error::Read { path, .. }
        | Error::TooLarge { path, .. }
        | Error::NotRegularFile { path, .. }
        | Error::OutsideSceneFolder { path, .. } => Parts {
            class: "SceneFileError",
            file: Some(path.display().to_string()),
            ..Parts::default()
        },
        Error::NotUtf8 { location, .. } => located("SceneFileError", location),
        Error::Syntax { location, .. } => located("SceneSyntaxError", location),
        Error::UnknownPoint { location, .. }
        | Error::UnknownName { location, .. }
        | Error::DuplicatePoint { location, .. }
        | Error::NonPositiveLength { location, .. }
        | Error::OutOfRange { location, .. }
        | Error::Import { location, .. }
        | Error::Unconstructible { location, .. }
        | Error::Invalid { location, .. } => located("InvalidSceneError", location),
        Error::Setting { setting, .. } => Parts {
            class: "SettingError",
            settings: Some(setting.clone()),
            ..Parts::default()
        },
        Error::OverLimit { .. } => Parts {
            class: "LimitError",
            ..Parts::default()
        },
        Error::SelfLocking {
            location, position, ..
        } => Parts {
            position: Some(position.clone()),
            ..located("SelfLockingError", location)
        },
        Error::Motion {
            location, position, ..
        } => Parts {
            // ` at drive position 12.5 deg, t = 0.31 s`, or empty.
            position: (position.strip_prefix(" at drive position "))
                .map(str::to_owned)
                .or_else(|| (!position.is_empty()).then(|| position.trim().to_owned())),
            ..located("MotionError", location)
        },
        Error::Codegen { origin, .. } => in_file("FormulaError", origin, None),
        Error::Write { path, .. } | Error::OutputIsInput { output: path, .. } => Parts {
            class: "SceneFileError",
            file: Some(path.display().to_string()),
            ..Parts::default()
        },
        Error::Model { file, .. } => in_file("ModelError", file, None),
        Error::Unassemblable { file, position, .. } => {
            in_file("UnassemblableError", file, Some(position))
        }
        Error::Blocked { file, limit, .. } => in_file("BlockedError", file, Some(limit)),
        Error::ChangePoint { file, position, .. } => {
            in_file("ChangePointError", file, Some(position))
        }
        Error::Singular { file, position, .. } => in_file("SingularError", file, Some(position)),
        Error::BranchFlip { file, to, .. } => in_file("BranchFlipError", file, Some(to)),
        Error::NotReached { file, last, .. } => in_file("NotReachedError", file, Some(last)),
        Error::MoveTooLong { file, to, .. } => in_file("MoveTooLongError", file, Some(to)),
        Error::NotFinite { file, position, .. } => in_file("NotFiniteError", file, Some(position)),
        Error::FormulaAt { file, .. } => in_file("MotionError", file, None),
        Error::NoEvaluator { file, .. } => in_file("EvaluatorError", file, None),
        Error::Study { file, .. } => in_file("StudyError", file, None),
        Error::Perturbed { settings, .. } => Parts {
            class: "StudyError",
            settings: Some(settings.clone()),
            ..Parts::default()
        },
        Error::AtParameter { setting, .. } => Parts {
            class: "SettingError",
            settings: Some(setting.clone()),
            ..Parts::default()
        },
        _ => Parts {
            class: "MechdiffError",
            ..Parts::default()
        },
    }
}

/// A Python exception for a failure of the binding itself (an argument of the wrong
/// shape): `mechdiff.errors.ArgumentError`, a `ValueError`.
pub fn argument(py: Python<'_>, message: String) -> PyErr {
    let made = py
        .import(MODULE)
        .and_then(|m| m.getattr("ArgumentError"))
        .and_then(|class| class.call1((message.clone(),)));
    match made {
        Ok(exception) => PyErr::from_value(exception),
        Err(_) => PyRuntimeError::new_err(message),
    }
}
