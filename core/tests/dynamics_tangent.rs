//! Exact derivatives of the dynamics with respect to a parameter (`dynamics::tangent`),
//! against independent references: the drive torque, kinetic energy and shaking force of a
//! slider-crank written by hand (virtual work on hand-written positions, differentiated with
//! num-dual), and the joint reactions against central differences of the `f64` run. The
//! parameter moves the effects' data (masses, centre, moment, gravity, load, ω, α) and, through
//! `geometry::Parametric`, the crank's length.

use crate::common;

use common::slider_crank_parts;
use mechdiff_core::dynamics::{
    Dynamics, Effects, EffectsTangent, Friction, Gravity, Load, LoadKind, ModelTangent, Motor,
    NotCarried, TangentError, carried, kinetostatics,
};
use mechdiff_core::geometry::{
    DataTangent, Drive, Equations, Inertia, Mechanism, Parametric, Solver,
};
use mechdiff_core::{DriveState, atan2};
use nalgebra::DMatrix;
use num_dual::{Dual2, Dual3, Dual64, DualNum};

const R: f64 = 0.1;
const L: f64 = 0.35;
const PHI0: f64 = 0.6;

/// The numbers a parameter p moves, at p = 0, and their rates d/dp: the rod's mass, centre
/// and moment, the crank's mass, gravity, the load on the slider, the drive's ω and α.
#[derive(Clone, Copy)]
struct Data<T> {
    rod_mass: T,
    rod_center: [T; 2],
    rod_moment: T,
    crank_mass: T,
    g: T,
    load: T,
    omega: T,
    alpha: T,
}

/// Sketch positions (at φ = φ0) of the crank pin A and the slider pin B for crank length `r`.
fn sketch_pins<T: DualNum<Primitive = f64> + Copy>(r: T) -> ([T; 2], [T; 2]) {
    let a = [r * PHI0.cos(), r * PHI0.sin()];
    (
        a,
        [a[0] + (a[1] * a[1] * -1.0 + L * L).sqrt(), T::from(0.0)],
    )
}

/// The data at parameter value p (the rod's centre is given at the sketch, so it does not
/// follow the crank's length).
fn values(p: f64) -> Data<f64> {
    let (a, b) = sketch_pins(R);
    Data {
        rod_mass: 2.0 + p,
        rod_center: [
            (a[0] + b[0]) / 2.0 + 0.01 + 0.01 * p,
            a[1] / 2.0 + 0.02 + 0.03 * p,
        ],
        rod_moment: 0.02 + 0.005 * p,
        crank_mass: 0.8 + 0.4 * p,
        g: 9.81 + 0.5 * p,
        load: 150.0 + 20.0 * p,
        omega: 12.0 + 3.0 * p,
        alpha: 4.0 - 2.0 * p,
    }
}

/// The rates d/dp of [`values`].
fn rates() -> Data<f64> {
    Data {
        rod_mass: 1.0,
        rod_center: [0.01, 0.03],
        rod_moment: 0.005,
        crank_mass: 0.4,
        g: 0.5,
        load: 20.0,
        omega: 3.0,
        alpha: -2.0,
    }
}

const CRANK_CENTER: [f64; 2] = [0.04, 0.03];
const CRANK_MOMENT: f64 = 0.002;
const SLIDER_MASS: f64 = 1.5;

/// The slider-crank with crank length `r` and data `d`; the slider's centre is its pin B.
fn mechanism(r: f64, d: &Data<f64>) -> Mechanism {
    let (_, b) = sketch_pins(r);
    slider_crank_parts(r, L, PHI0)
        .inertia(
            "crank",
            Inertia {
                mass: d.crank_mass,
                center: CRANK_CENTER,
                moment: CRANK_MOMENT,
            },
        )
        .inertia(
            "rod",
            Inertia {
                mass: d.rod_mass,
                center: d.rod_center,
                moment: d.rod_moment,
            },
        )
        .inertia(
            "slider",
            Inertia {
                mass: SLIDER_MASS,
                center: b,
                moment: 0.0,
            },
        )
        .drive(Drive::angle("O").at_sketch(PHI0))
        .build()
        .unwrap()
}

fn dynamics(d: &Data<f64>) -> Dynamics {
    Dynamics::new()
        .with_gravity(Gravity::down(d.g))
        .with_load(Load::force("slider", "B", [-d.load, 0.0]))
}

/// The hand reference at crank angle φ when p moves the data at `rates()` (`data`) and the
/// crank length at rate `dr`: `(M, T, ΣF)`, with every number a `Dual64` whose eps is d/dp.
/// Positions are written by hand (φ as a `Dual2` for r′, r″); the drive torque is virtual
/// work, `M = Σ [m a_G·r_G′ + J θ̈ θ′] − Σ m g·r_G′ − F·r_B′`, with `a = α r′ + ω² r″`: no
/// equilibrium equations, no LU.
fn hand(phi: f64, data: bool, dr: f64) -> (Dual64, Dual64, [Dual64; 2]) {
    let v = values(0.0);
    let t = if data { rates() } else { values_zero() };
    let d = |x: f64, dx: f64| Dual64::new(x, dx);
    let c = |x: Dual64| Dual2::from_re(x);
    let r = d(R, dr);
    let x = Dual2::new(Dual64::from(phi), Dual64::from(1.0), Dual64::from(0.0));
    let (sa, sb) = sketch_pins(r);
    // The crank turns by φ − φ0 about O; A on the crank, B on the x axis at distance L from A.
    let rot = |angle: Dual2<Dual64>, p: [Dual2<Dual64>; 2]| {
        let (s, co) = angle.sin_cos();
        [co * p[0] - s * p[1], s * p[0] + co * p[1]]
    };
    let turn = x - PHI0;
    let a = [x.cos() * c(r), x.sin() * c(r)];
    let b = [a[0] + (a[1] * a[1] * -1.0 + L * L).sqrt(), Dual2::from(0.0)];
    let beta = |a: [Dual2<Dual64>; 2], b: [Dual2<Dual64>; 2]| atan2(b[1] - a[1], b[0] - a[0]);
    let beta0 = beta([c(sa[0]), c(sa[1])], [c(sb[0]), c(sb[1])]);
    let rod_turn = beta(a, b) - beta0;
    let g1 = rot(turn, [c(CRANK_CENTER[0].into()), c(CRANK_CENTER[1].into())]);
    // The rod's centre relative to A, unrotated, at the sketch.
    let rod_local = [
        c(d(v.rod_center[0], t.rod_center[0]) - sa[0]),
        c(d(v.rod_center[1], t.rod_center[1]) - sa[1]),
    ];
    let arm = rot(rod_turn, rod_local);
    let g2 = [a[0] + arm[0], a[1] + arm[1]];
    let (omega, alpha) = (d(v.omega, t.omega), d(v.alpha, t.alpha));
    let g = d(v.g, t.g);
    // (mass, moment, centre, rotation) of each link.
    let links = [
        (
            d(v.crank_mass, t.crank_mass),
            Dual64::from(CRANK_MOMENT),
            g1,
            turn,
        ),
        (
            d(v.rod_mass, t.rod_mass),
            d(v.rod_moment, t.rod_moment),
            g2,
            rod_turn,
        ),
        (
            Dual64::from(SLIDER_MASS),
            Dual64::from(0.0),
            b,
            Dual2::from(0.0),
        ),
    ];
    let mut torque = Dual64::from(0.0);
    let mut reduced = Dual64::from(0.0);
    let mut shaking = [Dual64::from(0.0); 2];
    for (m, j, r, theta) in links {
        let r1 = [r[0].v1, r[1].v1];
        let acc = [
            alpha * r1[0] + omega * omega * r[0].v2,
            alpha * r1[1] + omega * omega * r[1].v2,
        ];
        let theta_dd = alpha * theta.v1 + omega * omega * theta.v2;
        torque += m * (acc[0] * r1[0] + acc[1] * r1[1]) + j * theta_dd * theta.v1;
        torque += m * g * r1[1]; // −m g·r′ with g = (0, −g)
        reduced += m * (r1[0] * r1[0] + r1[1] * r1[1]) + j * theta.v1 * theta.v1;
        shaking = [shaking[0] - m * acc[0], shaking[1] - m * acc[1]];
    }
    torque += d(v.load, t.load) * b[0].v1; // −F·r_B′ with F = (−load, 0)
    (torque, reduced * omega * omega * 0.5, shaking)
}

/// Rates of a parameter that moves none of the data.
fn values_zero() -> Data<f64> {
    Data {
        rod_mass: 0.0,
        rod_center: [0.0; 2],
        rod_moment: 0.0,
        crank_mass: 0.0,
        g: 0.0,
        load: 0.0,
        omega: 0.0,
        alpha: 0.0,
    }
}

/// The f64 pose and Φ_q at crank angle φ lifted to duals with zero eps: the pose tangent of
/// a parameter that moves no point (built here without `geometry::Parametric`).
fn pose_and_jacobian(m: &Mechanism, phi: f64) -> (Vec<Dual3<Dual64>>, DMatrix<Dual64>) {
    let mut tracker = Solver::default().track(m).unwrap();
    tracker.move_to(phi).unwrap();
    let k = tracker.kinematics::<2>().unwrap();
    let pose = (k.coordinates.iter())
        .map(|j| {
            Dual3::new(
                j.value.into(),
                j.derivatives[0].into(),
                j.derivatives[1].into(),
                0.0.into(),
            )
        })
        .collect::<Vec<_>>();
    let q: Vec<f64> = k.coordinates.iter().map(|j| j.value).collect();
    let mut jac = DMatrix::zeros(q.len(), q.len());
    Equations::new(m).jacobian(&q, &mut jac);
    (pose, jac.map(Dual64::from))
}

/// The pose and Φ_q with their d/dp from `geometry::Parametric`.
fn parametric_pose(
    m: &Mechanism,
    data: &DataTangent,
    phi: f64,
) -> (Vec<Dual3<Dual64>>, DMatrix<Dual64>) {
    let exact = Parametric::new(m, data).unwrap();
    let mut tracker = Solver::default().track(m).unwrap();
    tracker.move_to(phi).unwrap();
    let pose = exact.pose(&tracker.kinematics::<2>().unwrap()).unwrap();
    let jac = exact.jacobian(&pose);
    (pose, jac)
}

fn effects_tangent(d: &Dynamics, data: bool) -> EffectsTangent {
    let t = if data { rates() } else { values_zero() };
    EffectsTangent {
        gravity: [0.0, -t.g],
        loads: vec![LoadKind::Force([-t.load, 0.0])],
        omega: t.omega,
        alpha: t.alpha,
        ..EffectsTangent::zero(d)
    }
}

/// d/dp of every point and every link's inertia (ground, crank, rod, slider) when p moves the
/// data at `rates()` (`data`) and the crank length at rate `dr`: A and B move with the crank
/// length, and so does the slider's centre (B).
fn data_tangent(m: &Mechanism, data: bool, dr: f64) -> DataTangent {
    let t = if data { rates() } else { values_zero() };
    let (a, b) = sketch_pins(Dual64::new(R, dr));
    let mut tangent = DataTangent::zero(m);
    tangent.points[m.point_index("A").unwrap()] = [a[0].eps, a[1].eps];
    tangent.points[m.point_index("B").unwrap()] = [b[0].eps, b[1].eps];
    let zero = Inertia {
        mass: 0.0,
        center: [0.0; 2],
        moment: 0.0,
    };
    tangent.inertias = vec![
        None,
        Some(Inertia {
            mass: t.crank_mass,
            ..zero
        }),
        Some(Inertia {
            mass: t.rod_mass,
            center: t.rod_center,
            moment: t.rod_moment,
        }),
        Some(Inertia {
            center: [b[0].eps, b[1].eps],
            ..zero
        }),
    ];
    tangent
}

/// Drive positions over a revolution (the slider-crank with L > R has no singular position
/// when the crank drives).
const PHIS: [f64; 6] = [0.6, 1.3, 2.2, 3.1, 4.4, 5.9];

/// The drive torque, power-balance torque, kinetic energy and shaking force and their d/dp
/// agree with the hand reference to 1e-12 of `|x| + 1`: both are exact in f64 (the exact
/// route has one 9×9 LU, the hand form a few dozen flops; the quantities are O(1–100) here,
/// so this is a few hundred ulp; measured below 2e-15 absolute for the data parameter).
fn check_against_hand(data: bool, dr: f64) {
    let v = values(0.0);
    let m = mechanism(R, &v);
    let dyn_data = dynamics(&v);
    let model = dyn_data.compile(&m).unwrap();
    let effects = dyn_data.available(&m);
    let tangent_data = data_tangent(&m, data, dr);
    let tangent = ModelTangent::new(
        &model,
        &effects,
        &tangent_data,
        &effects_tangent(&dyn_data, data),
        v.omega,
        v.alpha,
    )
    .unwrap();
    let close = |what: &str, phi: f64, got: Dual64, want: Dual64| {
        let scale = [want.re.abs() + 1.0, want.eps.abs() + 1.0];
        assert!(
            (got.re - want.re).abs() <= 1e-12 * scale[0],
            "{what} at φ = {phi}: {} vs hand {}",
            got.re,
            want.re
        );
        assert!(
            (got.eps - want.eps).abs() <= 1e-12 * scale[1],
            "d{what}/dp at φ = {phi}: {} vs hand {}",
            got.eps,
            want.eps
        );
    };
    for phi in PHIS {
        let (pose, jac) = if dr == 0.0 {
            pose_and_jacobian(&m, phi)
        } else {
            parametric_pose(&m, &tangent_data, phi)
        };
        let s = tangent.solve(phi, &pose, &jac).unwrap();
        let (torque, kinetic, shaking) = hand(phi, data, dr);
        assert!(torque.eps.abs() > 1e-2, "a vacuous derivative at φ = {phi}");
        close("M", phi, s.drive_torque, torque);
        // The power balance's drive torque is the same number a second way.
        close("M_balance", phi, s.balance.torque.unwrap(), torque);
        close("T", phi, tangent.energy(&pose).unwrap().kinetic, kinetic);
        let f = tangent.shaking_force(phi, &pose).unwrap();
        for (got, want) in f.force.into_iter().zip(shaking) {
            close("ΣF", phi, got, want);
        }
        // The real parts are the f64 run's, to rounding.
        let k = {
            let mut tr = Solver::default().track(&m).unwrap();
            tr.move_to(phi).unwrap();
            tr.kinematics::<2>().unwrap()
        };
        let drive = DriveState::accelerating(v.omega, v.alpha);
        let f64_run = kinetostatics::solve(&model, &effects, &k, &drive).unwrap();
        assert!(
            (f64_run.drive_torque - s.drive_torque.re).abs() <= 1e-12 * (torque.re.abs() + 1.0)
        );
    }
}

/// p moves the masses, the rod's centre and moment, gravity, the load, ω and α (no point:
/// the pose tangent is zero, built without `Parametric`).
#[test]
fn data_derivatives_match_hand_virtual_work() {
    check_against_hand(true, 0.0);
}

/// p moves the crank's length only (the pins A and B, the slider's centre), through
/// `Parametric::pose` and `Parametric::jacobian`.
#[test]
fn crank_length_derivatives_match_hand_virtual_work() {
    check_against_hand(false, 1.0);
}

/// p moves both at once (crank length at rate 0.7).
#[test]
fn combined_derivatives_match_hand_virtual_work() {
    check_against_hand(true, 0.7);
}

/// The reactions of the f64 run at parameter value p (crank length `R + dr·p`).
fn reactions_at(p: f64, dr: f64, phi: f64) -> Vec<f64> {
    let v = values(p);
    let m = mechanism(R + dr * p, &v);
    let d = dynamics(&v);
    let model = d.compile(&m).unwrap();
    let mut tracker = Solver::default().track(&m).unwrap();
    tracker.move_to(phi).unwrap();
    let k = tracker.kinematics::<2>().unwrap();
    let s = kinetostatics::solve(
        &model,
        &d.available(&m),
        &k,
        &DriveState::accelerating(v.omega, v.alpha),
    )
    .unwrap();
    s.reactions
        .iter()
        .flat_map(|r| [r.force[0], r.force[1], r.couple, r.normal])
        .collect()
}

/// Every reaction's d/dp (p moving the data and the crank length at rate 0.7) agrees with
/// central differences of the f64 run, the mechanism rebuilt at p ± h. The differences'
/// error is O(h²) truncation plus O(ε/h) rounding: about 1e-7 of the scale at h = 1e-4 (measured), and
/// it must shrink at least 20× from h = 1e-3 to h = 1e-4 (checked, so the agreement is the
/// derivative's and not a coincidence): tolerance 1e-6 of the largest derivative.
#[test]
fn reaction_derivatives_match_central_differences() {
    let dr = 0.7;
    let v = values(0.0);
    let m = mechanism(R, &v);
    let d = dynamics(&v);
    let model = d.compile(&m).unwrap();
    let effects = d.available(&m);
    let data = data_tangent(&m, true, dr);
    let tangent = ModelTangent::new(
        &model,
        &effects,
        &data,
        &effects_tangent(&d, true),
        v.omega,
        v.alpha,
    )
    .unwrap();
    for phi in [1.3, 4.4] {
        let (pose, jac) = parametric_pose(&m, &data, phi);
        let s = tangent.solve(phi, &pose, &jac).unwrap();
        let exact: Vec<f64> = (s.reactions.iter())
            .flat_map(|r| [r.force[0], r.force[1], r.couple, r.normal])
            .map(|x| x.eps)
            .collect();
        let central = |h: f64| -> Vec<f64> {
            let (up, down) = (reactions_at(h, dr, phi), reactions_at(-h, dr, phi));
            up.iter()
                .zip(&down)
                .map(|(a, b)| (a - b) / (2.0 * h))
                .collect()
        };
        let scale = exact.iter().fold(1.0f64, |a, x| a.max(x.abs()));
        let error = |approx: &[f64]| {
            (approx.iter().zip(&exact))
                .map(|(a, e)| (a - e).abs())
                .fold(0.0, f64::max)
        };
        let (coarse, fine) = (error(&central(1e-3)), error(&central(1e-4)));
        assert!(fine <= 1e-6 * scale, "φ = {phi}: {fine:e} of scale {scale}");
        assert!(
            fine <= coarse / 20.0,
            "φ = {phi}: no O(h²) convergence ({coarse:e} → {fine:e})"
        );
    }
}

/// Friction is not carried: named by `solve`, not differentiated silently; the shaking force,
/// which does not read the equilibrium, stays exact. A tangent of the wrong length is a
/// named error.
#[test]
fn friction_is_reported_as_not_carried() {
    let v = values(0.0);
    let m = mechanism(R, &v);
    let d = dynamics(&v).with_friction(Friction::sliding("guide", 0.1));
    let model = d.compile(&m).unwrap();
    let effects = d.available(&m);
    assert_eq!(
        carried(&model, &effects),
        Err(NotCarried::Friction {
            joint: "guide".to_owned()
        })
    );
    // Without friction in the plan, the same model is carried.
    let without = Effects {
        friction: false,
        ..effects
    };
    assert_eq!(carried(&model, &without), Ok(()));
    let data = data_tangent(&m, true, 0.0);
    let tangent = ModelTangent::new(
        &model,
        &effects,
        &data,
        &effects_tangent(&d, true),
        v.omega,
        v.alpha,
    )
    .unwrap();
    let (pose, jac) = pose_and_jacobian(&m, 1.0);
    let error = tangent.solve(1.0, &pose, &jac).unwrap_err();
    assert!(
        error.to_string().contains("friction (joint `guide`)"),
        "{error}"
    );
    assert!(tangent.shaking_force(1.0, &pose).is_ok());
    let mut short = data.clone();
    short.points.pop();
    let error = ModelTangent::new(
        &model,
        &without,
        &short,
        &effects_tangent(&d, true),
        v.omega,
        v.alpha,
    )
    .unwrap_err();
    assert!(
        matches!(error, TangentError::Length { what: "points", .. }),
        "{error:?}"
    );
}

/// With a motor behind a gearbox (rotor J_d, ratio τ, efficiency η, each moved by p as well
/// as the data): the motor torque `M_d = J_d α/τ + M τ/η` (`M τ η` where power flows back,
/// M ω < 0) and the kinetic energy with the rotor's `½ J_d ω²/τ²`, from the hand drive
/// torque, agree with the exact route to 1e-12 of |x| + 1 (both exact in f64; the direction
/// of flow is the nominal run's on both sides).
#[test]
fn motor_torque_derivative_matches_hand_virtual_work() {
    let v = values(0.0);
    let m = mechanism(R, &v);
    let motor = Motor {
        rotor_inertia: 0.002,
        ratio: 1.0 / 30.0,
        efficiency: 0.9,
    };
    let rate = Motor {
        rotor_inertia: 0.001,
        ratio: 0.002,
        efficiency: -0.05,
    };
    let d = dynamics(&v).with_motor(motor);
    let model = d.compile(&m).unwrap();
    let effects = d.available(&m);
    assert!(effects.motor && effects.efficiency);
    let tangent = ModelTangent::new(
        &model,
        &effects,
        &data_tangent(&m, true, 0.0),
        &EffectsTangent {
            motor: Some(rate),
            ..effects_tangent(&d, true)
        },
        v.omega,
        v.alpha,
    )
    .unwrap();
    let t = rates();
    let dual = |x: f64, dx: f64| Dual64::new(x, dx);
    let (omega, alpha) = (dual(v.omega, t.omega), dual(v.alpha, t.alpha));
    let (j_d, tau, eta) = (
        dual(motor.rotor_inertia, rate.rotor_inertia),
        dual(motor.ratio, rate.ratio),
        dual(motor.efficiency, rate.efficiency),
    );
    let mut flows = [false, false];
    for phi in PHIS {
        let (pose, jac) = pose_and_jacobian(&m, phi);
        let s = tangent.solve(phi, &pose, &jac).unwrap();
        let (torque, kinetic, _) = hand(phi, true, 0.0);
        let direct = torque.re * omega.re >= 0.0;
        flows[usize::from(direct)] = true;
        let gearbox = if direct { tau / eta } else { tau * eta };
        let want = j_d * alpha / tau + torque * gearbox;
        let got = s.motor.unwrap().torque;
        for (g, w) in [(got.re, want.re), (got.eps, want.eps)] {
            assert!(
                (g - w).abs() <= 1e-12 * (w.abs() + 1.0),
                "M_d at φ = {phi}: {g} vs {w}"
            );
        }
        let want = kinetic + j_d / (tau * tau) * omega * omega * 0.5;
        let got = tangent.energy(&pose).unwrap().kinetic;
        for (g, w) in [(got.re, want.re), (got.eps, want.eps)] {
            assert!(
                (g - w).abs() <= 1e-12 * (w.abs() + 1.0),
                "T at φ = {phi}: {g} vs {w}"
            );
        }
    }
    assert_eq!(flows, [true, true], "both directions of power flow are met");
}

/// Two gear wheels on the frame: the tooth force goes through the bearings (see
/// `JointReaction`), which the exact route does not carry: named, with the mesh.
#[test]
fn tooth_forces_in_bearings_are_reported_as_not_carried() {
    let m = common::gear_pair(false, false);
    let d = Dynamics::new();
    let model = d.compile(&m).unwrap();
    assert_eq!(
        carried(&model, &Effects::none()),
        Err(NotCarried::ToothForces {
            joint: "mesh".to_owned()
        })
    );
}
