//! The exact derivative columns: dual numbers from the scene's numbers to its outputs.
//!
//! The kinematic columns: the scene's tangent ([`crate::scene::tangent`], the d/dp of every
//! number of the built mechanism) and the pose's exact sensitivity by implicit
//! differentiation (`mechdiff_core::geometry::Parametric`) give every output's value and
//! drive derivatives with their d/dp as `Dual3<Dual64, f64>`; the outputs are read by the
//! same generic code as a run's ([`crate::scene::evaluate`]), the quantities too (ω and α
//! with their own d/dp).
//!
//! Where the route does not reach — a cam drive, `[sweep] of`, a number the tangent does
//! not carry — the function says why, and the caller falls back to Richardson-extrapolated
//! differences, labelled with that reason.

use crate::scene::Scene;
use crate::scene::tangent::{SceneTangent, scene_tangent};

use super::Runner;

/// The d/dp of every kinematic column (`[row][column]`, the table's column indices; the
/// drive's column 0 is 0), or why the exact route does not reach them.
pub(super) fn kinematic(
    runner: &Runner<'_>,
    scene: &Scene,
    parameter: &str,
) -> std::result::Result<Vec<Vec<f64>>, String> {
    let tangent = scene_tangent(runner.file, runner.text, runner.settings, parameter)
        .map_err(|e| format!("the scene's tangent could not be taken: {e}"))?;
    reach(scene, &tangent)?;
    Err(
        "the core's exact pose sensitivity (`Parametric`, branch exact-core) is not merged"
            .to_owned(),
    )
}

/// Whether the exact route reaches the kinematic columns of `scene` with the tangent
/// `tangent`, or why not.
fn reach(scene: &Scene, tangent: &SceneTangent) -> std::result::Result<(), String> {
    if scene.drive.cam.is_some() {
        return Err(
            "a cam drives the scene (the exact route does not carry its motion \
                    law's data)"
                .to_owned(),
        );
    }
    if scene.sweep_of.is_some() {
        return Err(
            "`[sweep] of` solves the drive positions for an output's values, \
                    which move with the parameter"
                .to_owned(),
        );
    }
    if let Some(n) = tangent.not_carried.iter().find(|n| n.affects_kinematics()) {
        return Err(format!(
            "`{}` moves `{}` ({}), a number the exact route does not carry",
            tangent.parameter, n.path, n.location
        ));
    }
    Ok(())
}

/// The single place where the exact d/dp of the dynamics columns plugs in (the `dyn`
/// helper's `src/scene/dynamics`): until it does, they are Richardson-extrapolated.
pub(super) fn dynamics(
    _runner: &Runner<'_>,
    _scene: &Scene,
    _parameter: &str,
) -> std::result::Result<Vec<Vec<f64>>, String> {
    Err("the dynamics columns' exact route is not merged (src/scene/dynamics)".to_owned())
}
