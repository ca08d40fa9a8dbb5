//! The symbolic run-time evaluator as a method of the accuracy report: the scene's closed
//! forms traced into the symbolic engine, differentiated to the third order, compiled into
//! the instruction list of [`mechdiff_core::trace::Program`] (what
//! `mechdiff codegen` builds, [`SceneCode`]) and evaluated per drive position in `f64`.
//!
//! The traced angles lie on the sketch's turn; they are compared on the reference's turn
//! (moved by whole turns only when more than half a turn away), as the solver's are. A
//! drive position where a loop's guard fails is the solver's error there (the method
//! fails, it does not return a value).

use std::rc::Rc;

use crate::Error;
use crate::codegen::scene::{SceneCode, guard_error};
use crate::scene::Scene;

use super::scene::{near, nearest};
use super::{MAX_ORDER, Method, Values};

/// The method's name in the report.
pub const NAME: &str = "symbolic (run-time evaluator)";

/// The evaluator of `scene`'s traced closed forms as an exact method of order 3; `angle`,
/// `targets` and `positions` as the geometry methods take them (which columns are angles,
/// the reference's values per position, the sweep).
///
/// # Errors
/// Why there is no traced form, as a sentence: a cam-driven joint (the cam program is not
/// traced), a mixed plan (its Newton loop named), derivatives beyond the engine's limits.
pub fn method<'a>(
    scene: &'a Scene,
    angle: &[bool],
    targets: &Rc<Vec<Vec<f64>>>,
    positions: &Rc<Vec<f64>>,
) -> Result<Method<'a>, String> {
    if scene.drive.cam.is_some() {
        return Err(
            "the cam program of a cam-driven joint is not traced (`mechdiff codegen` refuses \
             it too)"
                .into(),
        );
    }
    let mut code = SceneCode::of(scene).map_err(|e| e.to_string())?;
    if let Some(block) = code.position.newton.first() {
        // The row evaluates the program at each drive position on its own; a Newton loop
        // inside it needs the sweep walked in order from the sketch (`MixedTracker`).
        return Err(format!(
            "a mixed plan: the loop [{}] is solved by Newton inside the evaluator, which walks \
             the sweep in order (`mechdiff run --evaluator program`); this row measures plans \
             whose every loop has a closed form",
            block.joints.join(", ")
        ));
    }
    code.jets = code
        .position
        .jets(MAX_ORDER)
        .map_err(|e| format!("third derivatives of the traced graph: {e}"))?;
    code.order = MAX_ORDER;
    let program = code.program(scene).map_err(|e| e.to_string())?;
    let mut registers = program.registers();
    let mut out = vec![0.0; program.outputs()];
    let (angle, targets, positions) = (angle.to_vec(), targets.clone(), positions.clone());
    let width = MAX_ORDER + 1;
    Ok(Method::exact(
        NAME,
        MAX_ORDER,
        move |phi, values: &mut [Values]| {
            program.evaluate(phi, &mut registers, &mut out);
            let jets = match code.read(&out) {
                Ok(jets) => jets,
                Err((l, failure)) => {
                    return Err(guard_error(scene, phi)?.unwrap_or_else(|| Error::Reference {
                    what: scene.file.clone(),
                    reason: format!(
                        "{NAME}: the guard of loop {l} fails at φ = {phi} rad ({failure:?}) \
                         where the solver's closed forms do not"
                    ),
                }));
                }
            };
            let i = nearest(&positions, phi);
            for (k, (value, jet)) in values.iter_mut().zip(jets.chunks(width)).enumerate() {
                *value = [jet[0], jet[1], jet[2], jet[3]];
                if angle[k] {
                    value[0] = near(jet[0], targets[i][k]);
                }
            }
            Ok(())
        },
    ))
}
