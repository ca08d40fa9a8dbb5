//! A scene's position solution traced into one expression graph and differentiated: what
//! the run-time evaluator compiles ([`super::program`]) and what `mechdiff codegen` emits
//! ([`crate::codegen::scene`]).

use mechdiff_core::symbolic::Id;
use mechdiff_core::trace::{self, PositionGraph};

use crate::error::{Error, Result};
use crate::scene::error_context::ErrorContext;
use crate::scene::evaluate::{Resolved, values_on_sketch_turn};
use crate::scene::model::OutputKind;
use crate::scene::setup::Setup;

/// A scene's position solution, traced and differentiated.
#[derive(Debug, Clone)]
pub struct SceneCode {
    /// The traced graph, its outputs and guards.
    pub position: PositionGraph,
    /// The outputs' names: the scene's, `name.x` and `name.y` for a point.
    pub names: Vec<String>,
    /// The highest derivative order.
    pub order: usize,
    /// Per output, its value and derivatives 1 to `order`.
    pub jets: Vec<Vec<Id>>,
}

impl SceneCode {
    /// Traces the scene of `setup`: its loops' closed forms (a loop without one as a Newton
    /// block) and its outputs, differentiated to the order its outputs need, at least 2.
    ///
    /// # Errors
    /// The model's errors at the sketch; the symbolic engine's limits (as
    /// [`Error::Codegen`]); a cam drive (its cam program is not traced).
    pub fn trace(setup: &Setup<'_>) -> Result<Self> {
        let cx = &setup.context;
        let codegen = |source| Error::Codegen {
            origin: cx.file.to_owned(),
            source,
        };
        refuse_a_cam_drive(cx)?;
        let tracker = (setup.solver)
            .track(&setup.mechanism)
            .map_err(|e| cx.solver_error(e))?;
        let resolved = (setup.outputs.iter())
            .map(|o| Resolved::new(setup, o))
            .collect::<Result<Vec<_>>>()?;
        let mut position = trace::trace(&tracker, |pose| {
            resolved
                .iter()
                .flat_map(|r| {
                    let point = |i: usize| pose.point(&r.points()[i]);
                    values_on_sketch_turn(r, point)
                })
                .collect()
        })
        .map_err(codegen)?;
        let names = (setup.outputs.iter())
            .flat_map(|o| match o.kind {
                OutputKind::Point(_) => vec![format!("{}.x", o.name), format!("{}.y", o.name)],
                _ => vec![o.name.clone()],
            })
            .collect();
        let order = setup.order.max(2);
        let jets = position.jets(order).map_err(codegen)?;
        Ok(SceneCode {
            position,
            names,
            order,
            jets,
        })
    }
}

/// Refuses a scene with a cam drive: the generated pose would be a function of the
/// follower's position, not of the cam angle the scene's table is written in (refused
/// rather than mislabelled).
///
/// # Errors
/// [`Error::Codegen`] for a cam drive.
pub(crate) fn refuse_a_cam_drive(cx: &ErrorContext<'_>) -> Result<()> {
    match cx.drive.cam {
        Some(_) => Err(Error::Codegen {
            origin: cx.file.to_owned(),
            source: mechdiff_core::Error::Untraceable {
                operation: "a cam-driven joint ([drive] cam; the cam program is not traced)"
                    .to_owned(),
            },
        }),
        None => Ok(()),
    }
}
