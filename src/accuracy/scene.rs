//! Mechanism scenes (`scenes/four_bar.toml`, …) in the accuracy report: the scene's outputs
//! over its sweep by the geometry solver's two paths, the traced closed forms in the
//! symbolic run-time evaluator, and finite differences, against a reference computed in
//! double-double precision.
//!
//! | method | order | what runs |
//! |---|---|---|
//! | geometry closed form | 3 | the solver's closed-form path (formulas in `Dual2_64`, ‴ in `Dual3_64`) |
//! | geometry Newton + implicit | 3 | the same model with the closed forms off: Newton, then implicit differentiation |
//! | symbolic (run-time evaluator) | 3 | the closed forms traced into the symbolic engine, differentiated, compiled to an instruction list ([`super::evaluator`]) |
//! | central, forward, Richardson | 3 | differences of the solver's positions in `f64` |
//!
//! **Reference.** Where every loop has a closed form, the solver's closed forms (written
//! once, generic over the scalar, [`mechdiff_core::Scalar`]) are evaluated by
//! [`Tracker::closed_form_pose`] in `Dual3<DoubleDouble>` ([`DoubleDouble`]: ≈ 32 digits,
//! its functions from 256-bit arithmetic) at the exact `f64` drive position, so value, ′, ″
//! and ‴ come from higher-precision arithmetic and forward-mode differentiation, with no
//! rounding of `f64` and no finite step. Where a loop is solved by Newton only, the position
//! solve and the implicit derivatives are carried out in double-double instead
//! ([`super::extended_newton`]). The outputs (points, angles, slider displacements) are read
//! from that pose by the same generic code as `mechdiff run`.
//!
//! **Cam-driven joints** (`[drive] cam`): the sweep is over the cam angle θ, the driven
//! joint at its sketch value plus the follower's s(θ). The reference runs the same chain in
//! double-double: s(θ) from the cam program in `Dual3<DoubleDouble>` is the drive jet given
//! to the closed forms (or the Newton solve), so the outputs' derivatives are d/dθ by
//! forward mode; the geometry methods compose the linkage's derivatives d/ds with s′, s″,
//! s‴ as the solver's runs do ([`mechdiff_core::cams::CamJoint::compose`]). At a cam joint
//! where s′, s″ or s‴ jumps, every method and the reference take the right-hand limit, and
//! finite differences are not counted at the orders that jump ([`Case::jumps`]).
//!
//! Angles are compared on the turn of the reference at the same position (an angle is
//! defined up to whole turns; the reference is kept continuous along the sweep, and a
//! method's value is moved by whole turns only where it is more than half a turn away).

use std::cell::RefCell;
use std::f64::consts::TAU;
use std::rc::Rc;

use mechdiff_core::Jet;
use mechdiff_core::cams::{ContinuityReport, Side};
use mechdiff_core::geometry::{Equations, GROUND, Mechanism, Solver, Tracker};
use mechdiff_core::num_dual::{Dual3, Dual3_64};

use super::double_double::DoubleDouble;
use super::extended_newton;
use super::reference::Reference;
use super::{Case, MAX_ORDER, Method, Values};
use crate::Error;
use crate::scene::Scene;
use crate::scene::evaluate::{Resolved, values};
use crate::scene::model::{DriveCam, OutputKind};

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
            outputs.resolved.push(Resolved::in_model(
                &scene.error_context(),
                &scene.links,
                &scene.points,
                mechanism,
                output,
            )?);
            match &output.kind {
                OutputKind::Point(name) => {
                    outputs
                        .names
                        .extend([format!("x_{name}"), format!("y_{name}")]);
                    outputs.angle.extend([false, false]);
                }
                OutputKind::Angle { .. } | OutputKind::Transmission { .. } => {
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
pub(super) fn near(value: f64, target: f64) -> f64 {
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

/// A drive jet in double-double.
type DdJet = Dual3<DoubleDouble>;

/// The sweep's drive: the linkage's driven joint at a sweep position, directly or through a
/// cam (`[drive] cam`).
#[derive(Clone, Copy)]
struct Drive<'s> {
    scene: &'s Scene,
    cam: Option<&'s DriveCam>,
}

impl<'s> Drive<'s> {
    fn new(scene: &'s Scene) -> Self {
        Drive {
            scene,
            cam: scene.drive.cam.as_ref(),
        }
    }

    /// The driven joint's position (as the solver's runs compute it).
    fn joint(&self, phi: f64) -> f64 {
        self.scene.drive.joint_position(phi)
    }

    /// The driven joint's position as a jet in the sweep variable, in double-double: φ
    /// itself, or the sketch's value plus the cam program's s(θ) (right-hand limits, as
    /// [`mechdiff_core::cams::CamJoint::new`] takes them).
    fn joint_jet(&self, phi: f64) -> DdJet {
        let (one, zero) = (DoubleDouble::new(1.0), DoubleDouble::new(0.0));
        let x = Dual3::new(DoubleDouble::new(phi), one, zero, zero);
        match self.cam {
            None => x,
            Some(c) => c.joint.program().displacement(x, Side::Right) + self.scene.drive.at_sketch,
        }
    }

    /// A jet with respect to the driven joint as a jet in the sweep variable.
    fn compose(&self, phi: f64, jet: Dual3_64) -> Dual3_64 {
        match self.cam {
            None => jet,
            Some(c) => {
                let j = c
                    .joint
                    .compose(phi, &Jet::new(jet.re, [jet.v1, jet.v2, jet.v3]));
                Dual3_64::new(
                    j.value,
                    j.derivatives[0],
                    j.derivatives[1],
                    j.derivatives[2],
                )
            }
        }
    }

    /// Per sweep position, the lowest order of the cam's s that jumps there (none without
    /// a cam): see [`Case::jumps`].
    fn jumps(&self, positions: &[f64]) -> Vec<Option<usize>> {
        let Some(cam) = self.cam else {
            return Vec::new();
        };
        let report = ContinuityReport::new(cam.joint.program());
        positions
            .iter()
            .map(|&theta| {
                report
                    .boundaries
                    .iter()
                    .filter(|b| {
                        let d = (theta - b.angle).rem_euclid(TAU);
                        d.min(TAU - d) <= 1e-9
                    })
                    .filter_map(|b| b.first_jump())
                    .min()
                    .map(|order| order.max(1))
            })
            .collect()
    }
}

/// The pose jet in double-double at the tracker's position: the closed forms, or (a loop
/// solved by Newton) the double-double Newton solve from the tracker's `f64` jet.
fn reference_pose(
    tracker: &Tracker<'_>,
    equations: Option<&Equations>,
    drive: &Drive<'_>,
    phi: f64,
) -> Result<Vec<DdJet>, String> {
    let x = drive.joint_jet(phi);
    let Some(equations) = equations else {
        return tracker.closed_form_pose(x).map_err(|e| e.to_string());
    };
    let kinematics = tracker.kinematics::<3>().map_err(|e| e.to_string())?;
    let start: Vec<DdJet> = kinematics
        .coordinates
        .iter()
        .map(|j| {
            let d = drive.compose(
                phi,
                Dual3_64::new(
                    j.value,
                    j.derivatives[0],
                    j.derivatives[1],
                    j.derivatives[2],
                ),
            );
            extended_newton::lift(d.re, [d.v1, d.v2, d.v3])
        })
        .collect();
    extended_newton::solve(equations, &start, x)
}

/// The reference of one position: every column's value and derivatives from the pose jet;
/// angles on the turn nearest to `previous` (the last position's reference, so that angles
/// are continuous along the sweep).
fn reference_at(
    outputs: &Outputs<'_>,
    q: &[DdJet],
    previous: Option<&Vec<[Reference; MAX_ORDER + 1]>>,
) -> Vec<[Reference; MAX_ORDER + 1]> {
    outputs
        .values(q)
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
        .collect()
}

/// The accuracy case of a mechanism scene (see the module's documentation); `mechanism` is
/// the scene's model ([`crate::scene::build::mechanism`]).
///
/// # Errors
/// [`Error::Reference`] for a scene without geometric outputs, or a reference that cannot
/// be computed or is not finite (the drive position named); the solver's error where the
/// sweep cannot be walked (for a sweep of an output's values, `[sweep] of`, `mechdiff run`'s
/// errors).
pub fn case<'a>(scene: &'a Scene, mechanism: &'a Mechanism) -> Result<Case<'a>, Error> {
    case_at(scene, mechanism, None)
}

/// [`case`] at no more than `count` of the sweep's drive positions (every k-th, the last
/// kept: [`super::thin`]), chosen before the reference is computed; all of them for `None`.
///
/// # Errors
/// As [`case`].
pub fn case_at<'a>(
    scene: &'a Scene,
    mechanism: &'a Mechanism,
    count: Option<usize>,
) -> Result<Case<'a>, Error> {
    let refuse = |reason: String| Error::Reference {
        what: scene.file.clone(),
        reason,
    };
    let drive = Drive::new(scene);
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
    let all = positions.len();
    if let Some(count) = count {
        positions = super::thin(all, count.max(1))
            .into_iter()
            .map(|i| positions[i])
            .collect();
    }
    let outputs = Outputs::new(scene, mechanism)?;
    if outputs.names.is_empty() {
        return Err(refuse(
            "the scene has no `[[output]]` (a point, angle or slider) to measure; the report \
             covers the geometric outputs and their derivatives, not forces or torques"
                .into(),
        ));
    }
    let mut tracker = scene
        .solver
        .track(mechanism)
        .map_err(|e| scene.error_context().solver_error(e))?;
    let loops = tracker.closed_form_loops();
    let all_closed = loops.iter().all(|&c| c);
    let equations = (!all_closed).then(|| Equations::new(mechanism));
    let mut reference = Vec::with_capacity(positions.len());
    // The tracker at each sweep position: finite differences start from the nearest one.
    let mut trackers = Vec::with_capacity(positions.len());
    let mut previous = None;
    for &phi in &positions {
        match (drive.cam, previous) {
            // Along the cam from the previous position: every displacement the follower
            // passes is proven (the other walks below then stay within what this one
            // proved).
            (Some(cam), Some(from)) => (cam.joint)
                .move_tracker(&mut tracker, scene.drive.at_sketch, from, phi)
                .map_err(|e| scene.error_context().cam_error(e))?,
            _ => (tracker.move_to(drive.joint(phi)))
                .map(drop)
                .map_err(|e| scene.error_context().solver_error(e))?,
        }
        previous = Some(phi);
        trackers.push(tracker.clone());
        let q = reference_pose(&tracker, equations.as_ref(), &drive, phi).map_err(|e| {
            refuse(format!(
                "no double-double reference at drive position {}: {e}",
                scene.drive_text(phi)
            ))
        })?;
        let row = reference_at(&outputs, &q, reference.last());
        if let Some(k) = row.iter().position(|r| r.iter().any(|x| !x.is_finite())) {
            return Err(refuse(format!(
                "output `{}` is not finite at drive position {} in double-double precision",
                outputs.names[k],
                scene.drive_text(phi)
            )));
        }
        reference.push(row);
    }
    let mut notes = vec![if all_closed {
        "reference: the solver's closed forms in double-double (Dual3<DoubleDouble>) at the \
         exact f64 drive positions"
            .to_owned()
    } else {
        let newton: Vec<String> = tracker
            .loops()
            .into_iter()
            .zip(&loops)
            .filter(|(_, closed)| !**closed)
            .map(|((joints, _), _)| joints.join(", "))
            .collect();
        format!(
            "reference: Newton and implicit derivatives in double-double (Dual3<DoubleDouble>; \
             loop(s) [{}] have no closed form)",
            newton.join("; ")
        )
    }];
    if let Some(cam) = drive.cam {
        notes.push(format!(
            "drive: the cam angle θ; the joint moves by the follower's s(θ) of {} (the \
             reference runs the cam program and the linkage in double-double)",
            cam.file
        ));
    }
    let jumps = drive.jumps(&positions);
    if jumps.iter().any(Option::is_some) {
        notes.push(
            "at the cam's joints where s′, s″ or s‴ jumps, every method and the reference take \
             the right-hand limit; finite differences straddle the jump and are not counted \
             there at the orders that jump"
                .to_owned(),
        );
    }
    let targets: Vec<Vec<f64>> = reference
        .iter()
        .map(|row| row.iter().map(|r| r[0].hi).collect())
        .collect();
    let outputs = Rc::new(outputs);
    let targets = Rc::new(targets);
    let positions_rc = Rc::new(positions.clone());
    let shared = Shared {
        mechanism,
        solver: scene.solver,
        drive,
        outputs: outputs.clone(),
        targets: targets.clone(),
        positions: positions_rc.clone(),
    };
    let mut methods = Vec::new();
    if all_closed {
        methods.push(geometry("geometry closed form", true, &shared));
    } else if loops.iter().any(|&c| c) {
        methods.push(geometry(
            "geometry closed form + Newton (mixed)",
            true,
            &shared,
        ));
    }
    methods.push(geometry("geometry Newton + implicit", false, &shared));
    match super::evaluator::method(scene, &shared.outputs.angle, &targets, &positions_rc) {
        Ok(method) => methods.push(method),
        Err(reason) => notes.push(format!(
            "symbolic (run-time evaluator): not measured: {reason}"
        )),
    }
    let differences = RefCell::new((tracker, usize::MAX));
    let (f_outputs, f_targets, f_positions) = (outputs.clone(), targets, positions_rc);
    Ok(Case {
        title: format!(
            "{}: {} over the scene's sweep, {} positions{}",
            scene.title.as_deref().unwrap_or(&scene.file),
            outputs.names.join(", "),
            positions.len(),
            thinned_from(all, positions.len())
        ),
        outputs: outputs.names.clone(),
        positions,
        reference,
        condition: None,
        relative: false,
        jumps,
        notes,
        methods,
        positions_f64: Box::new(move |phi, out| {
            let mut working = differences.borrow_mut();
            let (tracker, from) = &mut *working;
            // A stencil's samples start from the tracker at the nearest sweep position, so
            // that the walk between samples is short (a long walk back may not get past a
            // limit position the sweep went round).
            let nearest = nearest(&f_positions, phi);
            if *from != nearest {
                *tracker = trackers[nearest].clone();
                *from = nearest;
            }
            tracker
                .move_to(drive.joint(phi))
                .map_err(failed("finite differences", phi))?;
            let q = tracker.coordinates();
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

/// Gives a scene without `[[output]]` (a balancing or dynamics scene) one point output per
/// point of its moving links (every point not on the ground), so that the report measures
/// the motion its forces come from; returns the note the report prints, `None` for a scene
/// that has outputs (left as it is).
pub fn default_outputs(scene: &mut Scene) -> Option<String> {
    if !scene.outputs.is_empty() {
        return None;
    }
    let on_ground = |point: &String| {
        scene
            .links
            .iter()
            .any(|l| l.name == GROUND && l.points.contains(point))
    };
    let mut points: Vec<String> = Vec::new();
    for link in scene.links.iter().filter(|l| l.name != GROUND) {
        for point in &link.points {
            if !on_ground(point) && !points.contains(point) {
                points.push(point.clone());
            }
        }
    }
    let location = scene.drive.location.clone();
    scene.outputs = points
        .iter()
        .map(|p| crate::scene::model::Output {
            name: p.clone(),
            kind: OutputKind::Point(p.clone()),
            quantities: vec![crate::scene::format::Quantity::Position],
            dead_positions: false,
            location: location.clone(),
        })
        .collect();
    Some(format!(
        "the scene has no [[output]]: measured every point of its moving links ({})",
        points.join(", ")
    ))
}

/// " of N (every k-th, --positions)" when the sweep was thinned.
pub(super) fn thinned_from(all: usize, kept: usize) -> String {
    if kept < all {
        format!(" of {all} (every k-th, --positions)")
    } else {
        String::new()
    }
}

/// The index of the sweep position nearest to `phi`.
pub(super) fn nearest(positions: &[f64], phi: f64) -> usize {
    let i = positions.partition_point(|&p| p < phi);
    match (i.checked_sub(1), positions.get(i)) {
        (Some(below), Some(&above)) if phi - positions[below] < above - phi => below,
        (Some(below), None) => below,
        _ => i,
    }
}

/// What the geometry methods share: the model, the drive, the outputs and the reference's
/// angles (to compare angles on the reference's turn).
struct Shared<'a> {
    mechanism: &'a Mechanism,
    /// The scene's solver (`[solver]`); each method sets its path.
    solver: Solver,
    drive: Drive<'a>,
    outputs: Rc<Outputs<'a>>,
    targets: Rc<Vec<Vec<f64>>>,
    positions: Rc<Vec<f64>>,
}

/// The geometry solver's path (closed form or Newton) as a method. A repeated sweep starts
/// again from a copy of the tracker at the first position (the walk back is not timed as a
/// position).
fn geometry<'a>(name: &str, closed_form: bool, shared: &Shared<'a>) -> Method<'a> {
    let name_owned = name.to_owned();
    let solver = shared.solver.with_closed_form(closed_form);
    let (outputs, targets, positions) = (
        shared.outputs.clone(),
        shared.targets.clone(),
        shared.positions.clone(),
    );
    let (mechanism, drive) = (shared.mechanism, shared.drive);
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
        t.move_to(drive.joint(phi)).map_err(&fail)?;
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
            let v = drive.compose(phi, v);
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
