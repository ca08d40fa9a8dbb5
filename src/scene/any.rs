//! The one reader of `mechdiff check` and `mechdiff run`: a scene file of any kind (linkage,
//! cam, rotor, formulas) read, resolved and checked as far as a run goes before it solves
//! anything. `check` prints what [`read`] returns and stops; `run` goes on from it, so every
//! scene `run` accepts `check` accepts, and every error `run` gives before solving `check`
//! gives.

use crate::accuracy::formula::{self, FormulaScene};
use crate::error::Result;

use super::balancing::rotor_scene::{self, RotorScene};
use super::cam::{self, CamScene};
use super::setup::{RunOptions, Setup};
use super::{Kind, Scene, parameters, preflight};

/// A scene file read and checked up to solving.
#[derive(Debug, Clone)]
pub enum AnyScene {
    /// A linkage, its dynamics and balancing checked (`preflight::before_solving`).
    Linkage(Box<Scene>),
    /// A cam (the whole analysis is checked finite when it is read).
    Cam(Box<CamScene>),
    /// A rotor alone, its answers checked finite.
    Rotor(Box<RotorScene>),
    /// Formulas of the drive, compiled; the number of drive positions.
    Formula(Box<FormulaScene>, usize),
}

/// Reads the scene `text` (`file` names it in messages) as the kind its sections say
/// ([`super::kind`]), with `settings` (`--set`) for a linkage's `[parameters]`.
///
/// # Errors
/// The located error of the reader of that kind, or of the checks a run makes before
/// solving.
pub fn read(file: &str, text: &str, settings: &[parameters::Setting]) -> Result<AnyScene> {
    Ok(match super::kind(text) {
        Kind::Linkage => {
            let scene = super::parse_with(file, text, settings)?;
            preflight::before_solving(&Setup::of(&scene, &RunOptions::default())?)?;
            AnyScene::Linkage(Box::new(scene))
        }
        Kind::Cam => AnyScene::Cam(Box::new(cam::parse(file, text)?)),
        Kind::Rotor => {
            let scene = rotor_scene::parse(file, text)?;
            scene.rotor.answers()?;
            AnyScene::Rotor(Box::new(scene))
        }
        Kind::Formula => {
            let scene = formula::parse(text, file)?;
            let positions = formula::check(&scene, file)?;
            AnyScene::Formula(Box::new(scene), positions)
        }
    })
}
