//! The exact derivative columns: dual numbers from the scene's numbers to its outputs.
//!
//! The kinematic columns: the scene's tangent ([`crate::scene::tangent`], the d/dp of every
//! number of the built mechanism) and the pose's exact sensitivity by implicit
//! differentiation (`mechdiff_core::geometry::Parametric`) give every output's value and
//! drive derivatives with their d/dp as `Dual3<Dual64>`; the outputs are read by the
//! same generic code as a run's ([`crate::scene::evaluate`]), the quantities too (ω and α
//! with their own d/dp). The dynamics columns: the same tangent with the inertias and the
//! effects' numbers ([`dynamics`]) through the dynamics' exact route.
//!
//! Where the route does not reach — a cam drive, `[sweep] of`, a number the tangent does
//! not carry — the function says why, and the caller falls back to Richardson-extrapolated
//! differences, labelled with that reason.

use std::collections::HashMap;

use mechdiff_core::DriveState;
use mechdiff_core::geometry::Parametric;
use mechdiff_core::num_dual::Dual64;

use crate::error::Result;
use crate::scene::dynamics::column_derivatives;
use crate::scene::evaluate::{OnLinks, on_links, points_on_links, quantity_in, values_read};
use crate::scene::setup::{RunOptions, Setup};
use crate::scene::sweep::solve;
use crate::scene::tangent::{SceneTangent, scene_tangent};
use crate::scene::{Plan, Scene};

use super::Runner;

/// The d/dp of every kinematic column (`[row][column]`, the table's column indices; the
/// drive's column 0 is 0), or why the exact route does not reach them.
pub(super) fn kinematic(
    runner: &Runner<'_>,
    scene: &Scene,
    tangent: &std::result::Result<SceneTangent, String>,
) -> std::result::Result<ExactColumns, String> {
    let tangent = tangent.as_ref().map_err(Clone::clone)?;
    reach(scene, tangent)?;
    let positions: Vec<f64> = runner.nominal.rows.iter().map(|r| r[0]).collect();
    let values = kinematic_derivatives(scene, tangent, &positions)
        .map_err(|e| format!("the exact route failed ({e})"))?;
    Ok(ExactColumns {
        values,
        not_reached: HashMap::new(),
    })
}

/// The d/dp of the kinematic columns of `scene` at the drive `positions` (in order, from
/// the sketch, as a run walks them), the scene's tangent `tangent` carried exactly.
///
/// # Errors
/// A position the solver does not reach; a singular pose (no derivative there).
pub fn kinematic_derivatives(
    scene: &Scene,
    tangent: &SceneTangent,
    positions: &[f64],
) -> Result<Vec<Vec<f64>>> {
    let setup = Setup::of(scene, &RunOptions::default())?;
    let data = tangent.data_tangent(&setup.mechanism);
    let parametric =
        Parametric::new(&setup.mechanism, &data).map_err(|e| setup.context.solver_error(e))?;
    match setup.order {
        0 | 1 => walk::<1>(&setup, &parametric, tangent, positions),
        2 => walk::<2>(&setup, &parametric, tangent, positions),
        _ => walk::<3>(&setup, &parametric, tangent, positions),
    }
}

/// The walk at derivative order `N`.
fn walk<const N: usize>(
    setup: &Setup<'_>,
    parametric: &Parametric<'_>,
    tangent: &SceneTangent,
    positions: &[f64],
) -> Result<Vec<Vec<f64>>> {
    let (mechanism, cx) = (parametric.mechanism(), &setup.context);
    let outputs = (setup.outputs.iter())
        .map(|output| {
            let points = points_on_links(setup.links, output)?
                .into_iter()
                .map(|(link, point)| {
                    (parametric.point_output(link, point)).map_err(|e| cx.solver_error(e))
                })
                .collect::<Result<Vec<_>>>()?;
            // The outputs read as a run reads them: a line one link carries turns with that
            // link (so ψ′ here is the run's ψ′, and d(ω ψ′)/dω is it exactly).
            let shortcuts = on_links(setup.links, output).map(|on| {
                on.and_then(|on| match on {
                    OnLinks::Line(link, [a, b]) => parametric.angle_output(link, a, b).ok(),
                    OnLinks::Slide(guide, line, slider, point) => {
                        parametric.slide_output(guide, line, slider, point).ok()
                    }
                })
            });
            Ok((output, points, shortcuts))
        })
        .collect::<Result<Vec<_>>>()?;
    let state = Plan::of(setup)
        .drive
        .unwrap_or(DriveState::constant_speed(0.0));
    let drive = DriveState {
        omega: Dual64::new(state.omega, tangent.speed),
        alpha: Dual64::new(state.alpha, tangent.acceleration),
        jerk: Dual64::from(state.jerk),
    };
    let mut tracker = (setup.solver)
        .track(mechanism)
        .map_err(|e| cx.solver_error(e))?;
    let mut rows = Vec::with_capacity(positions.len());
    for &phi in positions {
        let k = solve::<N>(cx, &mut tracker, phi)?;
        let pose = parametric.pose(&k).map_err(|e| cx.solver_error(e))?;
        let mut row = vec![0.0];
        for (output, points, shortcuts) in &outputs {
            // An angle's whole turns (kept continuous by a run) do not change d/dp.
            let point = |i: usize| points[i].position(&pose);
            let shortcut = |i: usize| shortcuts[i].as_ref().map(|r| r.value(&pose));
            let values = values_read(output, point, shortcut);
            for q in &output.quantities {
                for v in &values {
                    row.push(quantity_in([v.re, v.v1, v.v2, v.v3], *q, &drive).eps);
                }
            }
        }
        rows.push(row);
    }
    Ok(rows)
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

/// The exact d/dp of the dynamics columns (`[row][column]`, the table's column indices from
/// `first`, where the table's dynamics columns start), each column with the reason where
/// the route does not reach it: the single place where the dynamics' exact route
/// ([`crate::scene::dynamics::column_derivatives`]) plugs in.
///
/// The scene's tangent carries the mechanism's numbers, the masses (a uniform bar's with its
/// moving ends), gravity, the loads, the motor, ω and α: the route is taken when the
/// parameter moves no other number (friction, a mesh efficiency, a load's `active` range,
/// balancing data, …: then every dynamics column falls back, with the number named). The dynamics' own route then says which columns it does not carry
/// (friction or mesh efficiencies in the plan: the equilibrium's columns).
pub(super) fn dynamics(
    runner: &Runner<'_>,
    scene: &Scene,
    tangent: &std::result::Result<SceneTangent, String>,
    first: usize,
) -> std::result::Result<ExactColumns, String> {
    let Some(d) = &scene.dynamics else {
        return Err("the scene has no dynamics".to_owned());
    };
    let tangent = tangent.as_ref().map_err(Clone::clone)?;
    reach(scene, tangent)?;
    if let Some(n) = tangent.not_carried.first() {
        return Err(format!(
            "`{}` moves `{}` ({}), a number the exact route does not carry",
            tangent.parameter, n.path, n.location
        ));
    }
    let positions: Vec<f64> = runner.nominal.rows.iter().map(|r| r[0]).collect();
    let failed = |e: crate::error::Error| format!("the exact route failed ({e})");
    let mechanism = crate::scene::build::mechanism(scene).map_err(failed)?;
    let data = tangent.data_tangent(&mechanism);
    let cx = scene.error_context();
    let parametric = Parametric::new(&mechanism, &data).map_err(|e| failed(cx.solver_error(e)))?;
    let effects = tangent.effects_tangent();
    let columns = column_derivatives(
        &cx,
        &scene.solver,
        d,
        &parametric,
        &effects,
        &positions,
        scene.drive.speed,
    )
    .map_err(failed)?;
    let width = runner.nominal.columns.len();
    let mut values = vec![vec![0.0; width]; positions.len()];
    for (row, derivatives) in values.iter_mut().zip(&columns.rows) {
        for (i, v) in derivatives.iter().enumerate() {
            row[first + i] = v.unwrap_or(0.0);
        }
    }
    let not_reached = (columns.not_carried.into_iter().enumerate())
        .filter_map(|(i, why)| Some((first + i, why?)))
        .collect();
    Ok(ExactColumns {
        values,
        not_reached,
    })
}

/// Exact derivative columns of one kind.
pub(super) struct ExactColumns {
    /// `values[row][column]`, the table's column indices (0 where not computed).
    pub values: Vec<Vec<f64>>,
    /// The columns of the kind the route does not reach, with the reason.
    pub not_reached: HashMap<usize, String>,
}

/// The scene's tangent with respect to `parameter`, or why it could not be taken.
pub(super) fn tangent(
    runner: &Runner<'_>,
    parameter: &str,
) -> std::result::Result<SceneTangent, String> {
    scene_tangent(runner.file, runner.text, runner.settings, parameter)
        .map_err(|e| format!("the scene's tangent could not be taken: {e}"))
}
