//! The Whitworth shaping machine in the accuracy report: ψ and x_C by every method the
//! project has for it.
//!
//! | method | order | what runs |
//! |---|---|---|
//! | hand-derived | 2 | [`hand::pose`], the source's formulas |
//! | symbolic (generated) | 3 | `rocker_angle_jet3`, `ram_position_jet3` of [`symbolic`] |
//! | Dual1, Dual2, HyperDual, Dual3 | 1, 2, 2, 3 | the generic [`Whitworth`] pose |
//! | geometry closed form | 3 | the solver's closed-form path on [`Whitworth::linkage`] |
//! | geometry Newton + implicit | 3 | the same linkage with the closed forms off |
//!
//! The reference is tan ψ = l1 sin φ / (l0 − l1 cos φ) and x_C = h tan ψ, differentiated by
//! the symbolic engine and evaluated at 256 bits with the exact `f64` inputs (l0, l1, h and φ
//! as the methods see them). The sweep is φ = 0°, 10°, …, 350° and both dead positions
//! cos φ = λ, where ψ′ = 0.

use std::f64::consts::TAU;

use mechdiff_core::geometry::{Mechanism, Solver};
use mechdiff_core::method::{Differentiator, Dual1, Dual2, Dual3, HyperDual};
use mechdiff_core::symbolic::Graph;
use mechdiff_core::{Jet, PositionFunction};
use mechdiff_mechanisms::Whitworth;
use mechdiff_mechanisms::whitworth::{Pose, hand, symbolic};

use super::reference::Formulas;
use super::{Case, MAX_ORDER, Method, Values};
use crate::Error;

/// The outputs: the rocker angle ψ (rad) and the ram position x_C (m).
pub const OUTPUTS: [&str; 2] = ["psi [rad]", "x_C [m]"];

/// The reference formulas of ψ and x_C in the symbols `phi`, `l0`, `l1`, `h`.
pub fn formulas() -> Formulas {
    let mut graph = Graph::new();
    let psi = graph
        .parse_infix("atan2(l1*sin(phi), l0 - l1*cos(phi))")
        .expect("the formula parses");
    let x_c = graph
        .parse_infix("h*l1*sin(phi)/(l0 - l1*cos(phi))")
        .expect("the formula parses");
    Formulas::new(graph, &[psi, x_c], "phi", &["l0", "l1", "h"])
}

/// The sweep: every 10° and both dead positions (cos φ = λ), increasing.
pub fn positions(shaper: &Whitworth) -> Vec<f64> {
    let dead = shaper.lambda().acos();
    let mut positions: Vec<f64> = (0..36).map(|k| f64::from(k * 10).to_radians()).collect();
    positions.extend([dead, TAU - dead]);
    positions.sort_by(f64::total_cmp);
    positions
}

fn write<const N: usize>(out: &mut Values, jet: Jet<N>) {
    out[0] = jet.value;
    out[1..=N].copy_from_slice(&jet.derivatives);
}

fn from_pose<const N: usize>(pose: Pose<Jet<N>>, out: &mut [Values]) {
    write(&mut out[0], pose.psi);
    write(&mut out[1], pose.c.x);
}

/// The geometry solver's path (closed form or Newton) as a method: the tracker walks the
/// sweep; when a repeated sweep starts again below the last position, the drive carries on
/// one turn further (the mechanism is periodic in φ), so the tracker never jumps back.
fn geometry<'a>(name: &str, linkage: &'a Mechanism, closed_form: bool) -> Method<'a> {
    let name_owned = name.to_owned();
    let solver = Solver::default().with_closed_form(closed_form);
    let mut turns = 0.0;
    let mut last = f64::NEG_INFINITY;
    let mut tracker = None;
    Method::exact(name, MAX_ORDER, move |phi, out| {
        let fail = |source| Error::Method {
            method: name_owned.clone(),
            phi,
            source,
        };
        if tracker.is_none() {
            tracker = Some(solver.track(linkage).map_err(fail)?);
        }
        let tracker = tracker.as_mut().expect("set above");
        if phi < last {
            turns += TAU;
        }
        last = phi;
        tracker.move_to(phi + turns).map_err(fail)?;
        let kinematics = tracker.kinematics::<3>().map_err(fail)?;
        let rocker = kinematics.rotation("rocker").map_err(fail)?;
        // ψ is measured from +y towards +x: the rocker's rotation is −ψ, up to whole
        // turns: the Newton path can land on the rocker's pose one or two turns away when
        // its predictor overshoots (λ = 0.99, where ψ′(0) = 99), the same pose with a
        // rotation 4π off. Compared as an angle, in (−π, π].
        let angle = -rocker.value;
        out[0] = [
            angle - TAU * (angle / TAU).round(),
            -rocker.derivatives[0],
            -rocker.derivatives[1],
            -rocker.derivatives[2],
        ];
        let [x, _] = kinematics.point("ram", "C").map_err(fail)?;
        write(&mut out[1], x);
        Ok(())
    })
}

/// The machine by geometry only ([`Whitworth::linkage`]), for the geometry methods of
/// [`case`] to borrow.
///
/// # Errors
/// [`Error::Method`] if the linkage cannot be built.
pub fn linkage(shaper: &Whitworth) -> Result<Mechanism, Error> {
    shaper.linkage([0.0, 0.0]).map_err(|source| Error::Method {
        method: "geometry".to_owned(),
        phi: 0.0,
        source,
    })
}

/// The accuracy case of a Whitworth machine: every method, the reference and the sweep.
///
/// `linkage` is the machine by geometry only (see [`linkage`]).
///
/// # Errors
/// [`Error::Reference`] if the reference does not evaluate.
pub fn case<'a>(shaper: &Whitworth, linkage: &'a Mechanism) -> Result<Case<'a>, Error> {
    let shaper = *shaper;
    let p = *shaper.parameters();
    let lambda = shaper.lambda();
    let formulas = formulas();
    let positions = positions(&shaper);
    let mut reference = Vec::new();
    let mut condition = Vec::new();
    for &phi in &positions {
        let (r, c) = formulas.reference(phi, &[p.l0, p.l1, p.h])?;
        reference.push(r);
        condition.push(c);
    }
    let methods = vec![
        Method::exact("hand-derived", 2, move |phi, out| {
            from_pose(hand::pose(&shaper, phi), out);
            Ok(())
        }),
        Method::exact("symbolic (generated)", 3, move |phi, out| {
            write(&mut out[0], symbolic::rocker_angle_jet3(phi, lambda));
            write(&mut out[1], symbolic::ram_position_jet3(phi, lambda, p.h));
            Ok(())
        }),
        Method::exact("Dual1", 1, move |phi, out| {
            from_pose(Dual1.jets(&shaper, phi), out);
            Ok(())
        }),
        Method::exact("Dual2", 2, move |phi, out| {
            from_pose(Dual2.jets(&shaper, phi), out);
            Ok(())
        }),
        Method::exact("HyperDual", 2, move |phi, out| {
            from_pose(HyperDual.jets(&shaper, phi), out);
            Ok(())
        }),
        Method::exact("Dual3", 3, move |phi, out| {
            from_pose(Dual3.jets(&shaper, phi), out);
            Ok(())
        }),
        geometry("geometry closed form", linkage, true),
        geometry("geometry Newton + implicit", linkage, false),
    ];
    Ok(Case {
        title: format!(
            "Whitworth shaping machine, λ = l1/l0 = {lambda}: ψ and x_C over φ = 0°, 10°, …, \
             350° and both dead positions (cos φ = λ), {} positions; reference: 256-bit symbolic",
            positions.len()
        ),
        outputs: OUTPUTS.map(String::from).to_vec(),
        positions,
        reference,
        condition: Some(condition),
        relative: false,
        jumps: Vec::new(),
        notes: Vec::new(),
        methods,
        positions_f64: Box::new(move |phi, out| {
            let pose = shaper.evaluate(phi);
            out[0] = pose.psi;
            out[1] = pose.c.x;
            Ok(())
        }),
    })
}
