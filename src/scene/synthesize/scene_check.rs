//! The scene with the parameters found, moved through the targets by the scene's own
//! solver: does it draw the linkage the engine sized? Its points named as the engine names
//! them (`A`, `B`, `P`; `E`, `Q`) are compared with the engine's closed forms at every
//! target's drive position.

use mechdiff_core::synthesis::Report;

use super::Setup;
use crate::error::Result;
use crate::scene::build::mechanism;

/// The ground link's name in a scene.
const GROUND: &str = "ground";

/// How the scene found places the linkage's points.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneCheck {
    /// The points compared (those of the engine's the scene has on a moving link).
    pub compared: Vec<String>,
    /// The largest distance between a point as the scene's solver places it and as the
    /// engine does, over every target (m).
    pub deviation: f64,
}

impl Setup {
    /// Reads `found` (the scene with `report`'s parameters, [`Setup::found_scene`]) and moves
    /// it from its sketch through the targets' drive positions with the scene's solver,
    /// comparing its points with the engine's.
    ///
    /// # Errors
    /// The scene's errors: the scene found cannot be read (its sketch does not assemble
    /// with the parameters found) or cannot be moved to a target.
    pub fn check_scene(&self, report: &Report, found: &str) -> Result<SceneCheck> {
        let scene = crate::scene::parse(&self.source.file, found)?;
        let m = mechanism(&scene)?;
        let problem = &self.problem;
        let linkage = problem.linkage();
        let context = scene.error_context();
        let mut outputs = Vec::new();
        for (k, name) in linkage.point_names().iter().enumerate() {
            let carrier = scene
                .links
                .iter()
                .find(|l| l.name != GROUND && l.points.iter().any(|p| p == name));
            if let Some(link) = carrier {
                let output = m
                    .point_output(&link.name, name)
                    .map_err(|e| context.solver_error(e))?;
                outputs.push((k, output));
            }
        }
        let mut tracker = scene
            .solver
            .track(&m)
            .map_err(|e| context.solver_error(e))?;
        let x = report.x();
        let mut deviation = 0.0f64;
        for phi in problem.drive_angles(&x) {
            tracker
                .move_to(scene.drive.joint_position(phi))
                .map_err(|e| context.solver_error(e))?;
            let Ok(pose) = linkage.pose(&x, phi, problem.branch()) else {
                continue;
            };
            for (k, output) in &outputs {
                let [px, py] = tracker.position(output);
                let want = pose.points[*k];
                deviation = deviation.max((px.value - want[0]).hypot(py.value - want[1]));
            }
        }
        Ok(SceneCheck {
            compared: outputs
                .iter()
                .map(|(k, _)| linkage.point_names()[*k].to_owned())
                .collect(),
            deviation,
        })
    }
}
