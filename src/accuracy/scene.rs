//! Mechanism scenes (`scenes/four_bar.toml`, …) in the accuracy report: the scene's outputs
//! over its sweep by the geometry solver's two paths and by finite differences, against a
//! reference computed in double-double precision.
//!
//! | method | order | what runs |
//! |---|---|---|
//! | geometry closed form | 3 | the solver's closed-form path (formulas in `Dual2_64`, ‴ in `Dual3_64`) |
//! | geometry Newton + implicit | 3 | the same model with the closed forms off: Newton, then implicit differentiation |
//! | central, forward, Richardson | 3 | differences of the closed-form positions in `f64` |
//!
//! **Reference.** The solver's closed forms are written once, generic over the scalar
//! ([`mechdiff_core::Scalar`]); [`Tracker::closed_form_pose`] evaluates them in
//! `Dual3<DoubleDouble>` ([`DoubleDouble`]: ≈ 32 digits, its functions from 256-bit
//! arithmetic) at the exact `f64` drive position, so value, ′, ″ and ‴ come from
//! higher-precision arithmetic and forward-mode differentiation, with no rounding of `f64`
//! and no finite step; the outputs (points, angles, slider displacements) are read from that
//! pose by the same generic code as `mechdiff run`. A scene with a loop that no closed form
//! matches (solved by Newton only) has no such reference: it is refused with the loop named
//! ([`mechdiff_core::Error::NoClosedForm`]), not reported against a reference it does not
//! have.
//!
//! Angles are compared on the turn of the reference at the same position (an angle is
//! defined up to whole turns; the reference is kept continuous along the sweep, and a
//! method's value is moved by whole turns only where it is more than half a turn away).

use std::cell::RefCell;
use std::f64::consts::TAU;

use mechdiff_core::geometry::{Mechanism, Solver, Tracker};
use mechdiff_core::num_dual::{Dual3, Dual3_64};

use super::double_double::DoubleDouble;
use super::reference::Reference;
use super::{Case, MAX_ORDER, Method, Values};
use crate::Error;
use crate::scene::Scene;
use crate::scene::evaluate::{Resolved, values};
use crate::scene::model::OutputKind;

/// 2π in double-double (hi: `TAU`, lo: the remainder).
const TAU_DD: DoubleDouble = DoubleDouble {
    hi: TAU,
    lo: 2.449_293_598_294_706_4e-16,
};

/// The scene's outputs: the resolved points, and per output whether it is an angle.
struct Outputs<'s> {
    resolved: Vec<Resolved<'s>>,
    /// Per column: is it an angle (compared up to whole turns).
    angle: Vec<bool>,
    /// Column names (`x_P`, `y_P` for a point).
    names: Vec<String>,
}

impl<'s> Outputs<'s> {
    fn new(scene: &'s Scene, mechanism: &Mechanism) -> Result<Self, Error> {
        let mut outputs = Outputs {
            resolved: Vec::new(),
            angle: Vec::new(),
            names: Vec::new(),
        };
        for output in &scene.outputs {
            outputs
                .resolved
                .push(Resolved::new(scene, mechanism, output)?);
            match &output.kind {
                OutputKind::Point(name) => {
                    outputs
                        .names
                        .extend([format!("x_{name}"), format!("y_{name}")]);
                    outputs.angle.extend([false, false]);
                }
                OutputKind::Angle { .. } => {
                    outputs.names.push(format!("{} [rad]", output.name));
                    outputs.angle.push(true);
                }
                OutputKind::Slider { .. } => {
                    outputs.names.push(output.name.clone());
                    outputs.angle.push(false);
                }
            }
        }
        Ok(outputs)
    }

    /// Every column's value in the pose `q`, in any scalar.
    fn values<D: mechdiff_core::Scalar>(&self, q: &[D]) -> Vec<D> {
        self.resolved
            .iter()
            .flat_map(|r| values(r.output, |i| r.points()[i].position_in(q)))
            .collect()
    }
}

/// `value` moved by whole turns to within half a turn of `target` (unchanged, exactly,
/// when it already is).
fn near(value: f64, target: f64) -> f64 {
    let turns = ((target - value) / TAU).round();
    if turns == 0.0 {
        value
    } else {
        value + turns * TAU
    }
}

/// The error of a tracker at `phi` as the report's method error.
fn failed(method: &str, phi: f64) -> impl Fn(mechdiff_core::Error) -> Error + '_ {
    move |source| Error::Method {
        method: method.to_owned(),
        phi,
        source,
    }
}

/// The reference of one position: the closed forms in `Dual3<DoubleDouble>`, every column's
/// value and derivatives; angles on the turn nearest to `previous` (the last position's
/// reference, so that angles are continuous along the sweep).
fn reference_at(
    tracker: &Tracker<'_>,
    outputs: &Outputs<'_>,
    phi: f64,
    previous: Option<&Vec<[Reference; MAX_ORDER + 1]>>,
) -> Result<Vec<[Reference; MAX_ORDER + 1]>, mechdiff_core::Error> {
    let one = DoubleDouble::new(1.0);
    let zero = DoubleDouble::new(0.0);
    let x = Dual3::new(DoubleDouble::new(phi), one, zero, zero);
    let q = tracker.closed_form_pose(x)?;
    Ok(outputs
        .values(&q)
        .into_iter()
        .zip(&outputs.angle)
        .enumerate()
        .map(|(k, (v, &angle))| {
            let mut value = v.re;
            if let (true, Some(previous)) = (angle, previous) {
                let turns = ((previous[k][0].hi - value.hi) / TAU).round();
                value += TAU_DD * turns;
            }
            [value, v.v1, v.v2, v.v3]
        })
        .collect())
}

/// The accuracy case of a mechanism scene (see the module's documentation); `mechanism` is
/// the scene's model ([`crate::scene::build::mechanism`]).
///
/// # Errors
/// [`Error::Reference`] for a scene without geometric outputs, a loop without a closed form
/// (named), or a reference that is not finite; the solver's error where the sweep cannot be
/// walked (for a sweep of an output's values, `[sweep] of`, `mechdiff run`'s errors).
pub fn case<'a>(scene: &'a Scene, mechanism: &'a Mechanism) -> Result<Case<'a>, Error> {
    let refuse = |reason: String| Error::Reference {
        what: scene.file.clone(),
        reason,
    };
    if scene.drive.cam.is_some() {
        return Err(refuse(
            "a cam-driven joint ([drive] cam) is not measured: the report differentiates with \
             respect to the driven joint's position; drive the joint itself to measure the \
             linkage"
                .into(),
        ));
    }
    // A sweep of an output's values (`[sweep] of`): the drive positions `mechdiff run`
    // solves for, in increasing order.
    let mut positions = if scene.sweep_of.is_some() {
        crate::scene::run(scene)?
            .rows
            .iter()
            .map(|row| row[0])
            .collect()
    } else {
        scene.positions.to_vec()?
    };
    positions.sort_by(f64::total_cmp);
    positions.dedup();
    let outputs = Outputs::new(scene, mechanism)?;
    if outputs.names.is_empty() {
        return Err(refuse(
            "the scene has no `[[output]]` (a point, angle or slider) to measure; the report \
             covers the geometric outputs and their derivatives, not forces or torques"
                .into(),
        ));
    }
    let mut tracker = Solver::default()
        .track(mechanism)
        .map_err(|e| crate::scene::run::solver_error(scene, e))?;
    let mut reference = Vec::with_capacity(positions.len());
    for &phi in &positions {
        tracker
            .move_to(phi)
            .map_err(|e| crate::scene::run::solver_error(scene, e))?;
        let row = reference_at(&tracker, &outputs, phi, reference.last()).map_err(|e| {
            refuse(format!(
                "{e}; `mechdiff accuracy` takes mechanism scenes whose every loop has a \
                 closed form (see `mechdiff check`)"
            ))
        })?;
        if let Some(k) = row.iter().position(|r| r.iter().any(|x| !x.is_finite())) {
            return Err(refuse(format!(
                "output `{}` is not finite at drive position {} in double-double precision",
                outputs.names[k],
                scene.drive_text(phi)
            )));
        }
        reference.push(row);
    }
    let targets: Vec<Vec<f64>> = reference
        .iter()
        .map(|row| row.iter().map(|r| r[0].hi).collect())
        .collect();
    let outputs = std::rc::Rc::new(outputs);
    let targets = std::rc::Rc::new(targets);
    let positions_rc = std::rc::Rc::new(positions.clone());
    let methods = vec![
        geometry(
            "geometry closed form",
            mechanism,
            true,
            &outputs,
            &targets,
            &positions_rc,
        ),
        geometry(
            "geometry Newton + implicit",
            mechanism,
            false,
            &outputs,
            &targets,
            &positions_rc,
        ),
    ];
    let differences = RefCell::new(tracker);
    let (f_outputs, f_targets, f_positions) = (outputs.clone(), targets.clone(), positions_rc);
    Ok(Case {
        title: format!(
            "{}: {} over the scene's sweep, {} positions; reference: the closed forms in \
             double-double",
            scene.title.as_deref().unwrap_or(&scene.file),
            outputs.names.join(", "),
            positions.len()
        ),
        outputs: outputs.names.clone(),
        positions,
        reference,
        condition: None,
        relative: false,
        methods,
        positions_f64: Box::new(move |phi, out| {
            let mut tracker = differences.borrow_mut();
            tracker
                .move_to(phi)
                .map_err(failed("finite differences", phi))?;
            let q = tracker.coordinates();
            let nearest = nearest(&f_positions, phi);
            for (k, v) in f_outputs.values(q).into_iter().enumerate() {
                out[k] = if f_outputs.angle[k] {
                    near(v, f_targets[nearest][k])
                } else {
                    v
                };
            }
            Ok(())
        }),
    })
}

/// The index of the sweep position nearest to `phi`.
fn nearest(positions: &[f64], phi: f64) -> usize {
    let i = positions.partition_point(|&p| p < phi);
    match (i.checked_sub(1), positions.get(i)) {
        (Some(below), Some(&above)) if phi - positions[below] < above - phi => below,
        (Some(below), None) => below,
        _ => i,
    }
}

/// The geometry solver's path (closed form or Newton) as a method. A repeated sweep starts
/// again from a copy of the tracker at the first position (the walk back is not timed as a
/// position).
fn geometry<'a>(
    name: &str,
    mechanism: &'a Mechanism,
    closed_form: bool,
    outputs: &std::rc::Rc<Outputs<'a>>,
    targets: &std::rc::Rc<Vec<Vec<f64>>>,
    positions: &std::rc::Rc<Vec<f64>>,
) -> Method<'a> {
    let name_owned = name.to_owned();
    let solver = Solver::default().with_closed_form(closed_form);
    let (outputs, targets, positions) = (outputs.clone(), targets.clone(), positions.clone());
    let mut tracker: Option<Tracker<'a>> = None;
    let mut start: Option<Tracker<'a>> = None;
    let mut last = f64::NEG_INFINITY;
    Method::exact(name, MAX_ORDER, move |phi, out: &mut [Values]| {
        let fail = failed(&name_owned, phi);
        if tracker.is_none() {
            tracker = Some(solver.track(mechanism).map_err(&fail)?);
        }
        if phi < last
            && let Some(first) = &start
        {
            tracker = Some(first.clone());
        }
        let t = tracker.as_mut().expect("set above");
        t.move_to(phi).map_err(&fail)?;
        if start.is_none() {
            start = Some(t.clone());
        }
        last = phi;
        let kinematics = t.kinematics::<3>().map_err(&fail)?;
        let q: Vec<Dual3_64> = kinematics
            .coordinates
            .iter()
            .map(|j| {
                Dual3_64::new(
                    j.value,
                    j.derivatives[0],
                    j.derivatives[1],
                    j.derivatives[2],
                )
            })
            .collect();
        let i = nearest(&positions, phi);
        for (k, v) in outputs.values(&q).into_iter().enumerate() {
            let value = if outputs.angle[k] {
                near(v.re, targets[i][k])
            } else {
                v.re
            };
            out[k] = [value, v.v1, v.v2, v.v3];
        }
        Ok(())
    })
}
