//! What a run reads of a scene, resolved once at the edge: the geometry model, the drive,
//! the outputs, the effects' settings, the solver, and the scene's words for errors
//! ([`ErrorContext`]: file, units, drive, joints).
//!
//! The runner ([`super::run`](mod@super::run), [`super::Sweeper`], [`crate::stream`]) and the effects
//! (`[[dynamics]]`, `[balancing]`) take a [`Setup`] or the parts of it they need, never the
//! whole [`Scene`]: the scene is data, read once here. How a run evaluates its positions is
//! an option of the run ([`RunOptions`]), not part of the scene.

use mechdiff_core::geometry::{Mechanism, Solver};

use crate::error::Result;
use crate::evaluator::Evaluator;

use super::balancing::SceneBalancing;
use super::dynamics::SceneDynamics;
use super::error_context::ErrorContext;
use super::model::{Drive, Link, Output, Point, Scene};
use super::positions::Positions;

/// How a run is carried out, beside the scene (`mechdiff run` options): the same scene run
/// with other options gives the same numbers, to the rounding the option names.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RunOptions {
    /// How the positions are evaluated: by the solver, or by the run-time evaluator of the
    /// scene's traced closed forms (`mechdiff run --evaluator`; see [`crate::evaluator`]).
    pub evaluator: Evaluator,
}

/// A scene resolved for a run: what the runner and the effects read, built once from the
/// scene ([`Setup::of`]).
#[derive(Debug, Clone)]
pub struct Setup<'s> {
    /// The scene's words for errors and positions: file, units, drive, joints.
    pub context: ErrorContext<'s>,
    /// The geometry model built from the scene.
    pub mechanism: Mechanism,
    /// The position solver every solve of the run uses (`[solver]`).
    pub solver: Solver,
    /// The drive positions (SI), or the values of the output `sweep_of` names.
    pub positions: &'s Positions,
    /// Index into `outputs` of the output whose values the sweep gives (`[sweep] of`).
    pub sweep_of: Option<usize>,
    /// The kinematic outputs, in column order.
    pub outputs: &'s [Output],
    /// The points at their sketch positions (where an angle output's continuity starts).
    pub points: &'s [Point],
    /// The links and the points they carry (where an output's points are read).
    pub links: &'s [Link],
    /// Masses, effects and the `[[dynamics]]` outputs, if any.
    pub dynamics: Option<&'s SceneDynamics>,
    /// The rotor and counterweights to balance, if any.
    pub balancing: Option<&'s SceneBalancing>,
    /// The highest derivative order the outputs need ([`Scene::order`]).
    pub order: usize,
    /// How the positions are evaluated ([`RunOptions::evaluator`]).
    pub evaluator: Evaluator,
}

impl<'s> Setup<'s> {
    /// Resolves `scene` for a run with `options`: builds its geometry model.
    ///
    /// # Errors
    /// The model's errors ([`super::build::mechanism`]), located in the file.
    pub fn of(scene: &'s Scene, options: &RunOptions) -> Result<Self> {
        Ok(Setup {
            context: scene.error_context(),
            mechanism: super::build::mechanism(scene)?,
            solver: scene.solver,
            positions: &scene.positions,
            sweep_of: scene.sweep_of,
            outputs: &scene.outputs,
            points: &scene.points,
            links: &scene.links,
            dynamics: scene.dynamics.as_ref(),
            balancing: scene.balancing.as_ref(),
            order: scene.order(),
            evaluator: options.evaluator,
        })
    }

    /// The drive.
    pub fn drive(&self) -> &'s Drive {
        self.context.drive
    }

    /// The scene file, as messages name it.
    pub fn file(&self) -> &'s str {
        self.context.file
    }
}
