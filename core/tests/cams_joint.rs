//! A cam inside a linkage: a cam program drives the slider of a slider-crank (the slider is
//! the cam's translating follower, the crank the output). The kinematics and the cam-shaft
//! torque are checked against a closed form written here: the crank angle from the triangle
//! O–A–B as a function of the slider position, the slider position from the laws' own
//! formulas, differentiated by dual numbers in the cam angle, and the torque from the power
//! balance of that closed form.

use crate::common;

use std::f64::consts::{PI, TAU};

use common::slider_crank_parts;
use mechdiff_core::DriveState;
use mechdiff_core::cams::{CamJoint, CamProgram, MotionLaw, Segment, joint};
use mechdiff_core::dynamics::{Dynamics, Gravity, Load, Plan, Request};
use mechdiff_core::geometry::{Drive, Inertia, Mechanism, Solver};
use num_dual::{Dual3_64, DualNum};

const G: f64 = 9.81;
/// Crank and rod lengths (m), crank angle at the sketch (rad).
const R: f64 = 0.1;
const L: f64 = 0.4;
const PHI0: f64 = 1.2;
/// The cam's lift (m) and the extents of rise, dwell, return, dwell (rad).
const LIFT: f64 = 0.04;
const EXTENTS: [f64; 4] = [2.0 * PI / 3.0, PI / 3.0, 2.0 * PI / 3.0, PI / 3.0];
/// Torque on the crank (N·m).
const CRANK_TORQUE: f64 = -3.0;
/// Masses (kg) and moments of inertia about the centres of gravity (kg·m²).
const MASSES: [(f64, f64); 3] = [(0.5, 4e-4), (1.2, 0.016), (2.0, 0.0)];

/// The slider's position at the sketch (m).
fn sketch_slider() -> f64 {
    let a = [R * PHI0.cos(), R * PHI0.sin()];
    a[0] + (L * L - a[1] * a[1]).sqrt()
}

fn program() -> CamProgram {
    CamProgram::new(
        vec![
            Segment::law(MotionLaw::Cycloidal, LIFT, EXTENTS[0]),
            Segment::law(MotionLaw::Dwell, 0.0, EXTENTS[1]),
            Segment::law(MotionLaw::Polynomial345, -LIFT, EXTENTS[2]),
            Segment::law(MotionLaw::Dwell, 0.0, EXTENTS[3]),
        ],
        sketch_slider(),
    )
    .unwrap()
}

/// The slider position from the laws as textbooks write them (Norton, *Design of
/// Machinery*, cycloidal and 3-4-5 polynomial), not from the cam program.
fn slider(theta: Dual3_64) -> Dual3_64 {
    let s0 = sketch_slider();
    let (rise_end, dwell_end) = (EXTENTS[0], EXTENTS[0] + EXTENTS[1]);
    let return_end = dwell_end + EXTENTS[2];
    let t = theta.re;
    if t < rise_end {
        let u = theta / rise_end;
        (u - (u * TAU).sin() / TAU) * LIFT + s0
    } else if t < dwell_end {
        theta * 0.0 + s0 + LIFT
    } else if t < return_end {
        let u = (theta - dwell_end) / EXTENTS[2];
        let f = u.powi(3) * 10.0 - u.powi(4) * 15.0 + u.powi(5) * 6.0;
        (-f + 1.0) * LIFT + s0
    } else {
        theta * 0.0 + s0
    }
}

/// Closed form: the crank angle, the crank pin A, the rod angle, with their θ-derivatives.
struct Pose {
    crank: Dual3_64,
    a: [Dual3_64; 2],
    b: Dual3_64,
    rod: Dual3_64,
}

fn pose(theta: f64) -> Pose {
    let b = slider(Dual3_64::from(theta).derivative());
    // Triangle O–A–B: l² = r² + x² − 2 r x cos φ, A above the x axis (φ in (0, π)).
    let crank = ((b * b + R * R - L * L) / (b * (2.0 * R))).acos();
    let a = [crank.cos() * R, crank.sin() * R];
    let rod = (-a[1]).atan2(b - a[0]);
    Pose { crank, a, b, rod }
}

fn mechanism() -> Mechanism {
    let a = [R * PHI0.cos(), R * PHI0.sin()];
    let x = sketch_slider();
    let inertia = |(mass, moment): (f64, f64), center: [f64; 2]| Inertia {
        mass,
        center,
        moment,
    };
    slider_crank_parts(R, L, PHI0)
        .inertia("crank", inertia(MASSES[0], [a[0] / 2.0, a[1] / 2.0]))
        .inertia("rod", inertia(MASSES[1], [(a[0] + x) / 2.0, a[1] / 2.0]))
        .inertia("slider", inertia(MASSES[2], [x, 0.0]))
        .drive(Drive::displacement("guide"))
        .build()
        .unwrap()
}

/// Cam angles inside the rise, the dwell, the return and the last dwell (away from the
/// boundaries, where the closed form above takes no one-sided limits).
fn thetas() -> Vec<f64> {
    (0..48)
        .map(|i| (f64::from(i) + 0.37) * TAU / 48.0)
        .collect()
}

/// The crank angle and its first three cam-angle derivatives from the geometry solver at
/// s(θ), composed by the cam joint, equal the closed form.
#[test]
fn crank_angle_and_its_cam_angle_derivatives_equal_the_closed_form() {
    let m = mechanism();
    let cam = CamJoint::new(program());
    let mut tracker = Solver::default().track(&m).unwrap();
    let mut worst = 0.0_f64;
    for theta in thetas() {
        let (s, _) = cam.drive_at(theta, &DriveState::constant_speed(1.0));
        tracker.move_to(s).unwrap();
        let k = tracker.kinematics::<3>().unwrap();
        // rotation since the sketch, plus the sketch angle: the crank angle.
        let of_s = k.rotation("crank").unwrap();
        let of_theta = cam.compose(theta, &of_s);
        let want = pose(theta).crank;
        let got = [of_theta.value + PHI0, of_theta.derivatives[0]];
        let want_all = [want.re, want.v1, want.v2, want.v3];
        let got_all = [
            got[0],
            got[1],
            of_theta.derivatives[1],
            of_theta.derivatives[2],
        ];
        for (g, w) in got_all.iter().zip(want_all) {
            // Relative to the order's scale over the turn (≥ 1e-3 rad per rad^k): a derivative
            // is 0 in the dwells.
            worst = worst.max((g - w).abs() / w.abs().max(1e-1));
        }
    }
    // 1e-11: the solver's derivatives come from linear solves with condition ~10 (the rod is
    // 4 crank lengths) and the third derivative of the law is ~(2π/β)³ ≈ 30 times its lift;
    // rounding of a few hundred operations on values ~1.
    assert!(worst < 1e-11, "worst relative difference {worst:e}");
}

/// The cam-shaft torque of the cam joint, with inertia, gravity and a torque on the crank,
/// equals the torque from the closed form's power balance (T ω = dE/dt − P_gravity −
/// P_load), and the library's own power balance (with the reactions of the equilibrium)
/// closes, at constant and at changing cam speed.
#[test]
fn cam_torque_satisfies_the_power_balance() {
    let m = mechanism();
    let d = Dynamics::new()
        .with_gravity(Gravity::down(G))
        .with_load(Load::torque("crank", CRANK_TORQUE));
    let model = d.compile(&m).unwrap();
    let plan = Plan::for_requests(
        &[
            Request::DriveTorque,
            Request::Reactions,
            Request::PowerBalance,
        ],
        d.available(&m),
    );
    let cam = CamJoint::new(program());
    let thetas = thetas();
    for drive in [
        DriveState::constant_speed(12.0),
        DriveState::accelerating(8.0, -30.0),
    ] {
        let run = joint::run(&cam, &plan, &model, &Solver::default(), &thetas, |_| drive).unwrap();
        assert_eq!(run.steps.len(), thetas.len());
        for step in &run.steps {
            let p = pose(step.theta);
            let (w, al) = (drive.omega, drive.alpha);
            // Velocity and acceleration of a quantity x(θ): x′ω, x′α + x″ω².
            let vel = |x: Dual3_64| x.v1 * w;
            let acc = |x: Dual3_64| x.v1 * al + x.v2 * w * w;
            let half = |x: Dual3_64, y: Dual3_64| (x + y) * 0.5;
            let centres = [
                [half(p.a[0], p.a[0] * 0.0), half(p.a[1], p.a[1] * 0.0)],
                [half(p.a[0], p.b), half(p.a[1], p.a[1] * 0.0)],
                [p.b, p.b * 0.0],
            ];
            let angles = [p.crank, p.rod, p.b * 0.0];
            let mut kinetic_rate = 0.0;
            let mut gravity = 0.0;
            for ((c, angle), (mass, moment)) in centres.iter().zip(angles).zip(MASSES) {
                kinetic_rate += mass * (vel(c[0]) * acc(c[0]) + vel(c[1]) * acc(c[1]))
                    + moment * vel(angle) * acc(angle);
                gravity -= mass * G * vel(c[1]);
            }
            let load = CRANK_TORQUE * vel(p.crank);
            let want = (kinetic_rate - gravity - load) / w;
            let torque = step.torque.unwrap();
            let scale = [kinetic_rate, gravity, load]
                .iter()
                .fold(0.0_f64, |a, v| a.max(v.abs()))
                / w;
            // 1e-12 relative to the largest power term: both sides are a few dozen
            // operations from exact f64 data.
            assert!(
                (torque - want).abs() <= 1e-12 * scale,
                "θ = {}: torque {torque} vs closed form {want}",
                step.theta
            );
            // The library's balance in the follower's terms: F_s ṡ = T ω, and it closes.
            let solution = step.step.solution.as_ref().unwrap();
            let b = &solution.balance;
            assert!(
                (b.drive - step.power().unwrap()).abs() <= 1e-12 * scale * w,
                "θ = {}: F_s ṡ = {} vs T ω = {:?}",
                step.theta,
                b.drive,
                step.power()
            );
            assert!(
                b.residual.abs() <= 1e-12 * b.scale(),
                "θ = {}: residual {}",
                step.theta,
                b.residual
            );
        }
    }
}

/// In a dwell the follower stands still: no cam torque is needed whatever the linkage's
/// loads (s′ = 0), while the follower's drive still holds the loads (F_s ≠ 0).
#[test]
fn a_dwell_needs_no_cam_torque() {
    let m = mechanism();
    let d = Dynamics::new()
        .with_gravity(Gravity::down(G))
        .with_load(Load::torque("crank", CRANK_TORQUE));
    let model = d.compile(&m).unwrap();
    let plan = Plan::for_requests(&[Request::DriveTorque], d.available(&m));
    let cam = CamJoint::new(program());
    let theta = EXTENTS[0] + 0.5 * EXTENTS[1];
    let run = joint::run(&cam, &plan, &model, &Solver::default(), &[theta], |_| {
        DriveState::constant_speed(5.0)
    })
    .unwrap();
    let step = &run.steps[0];
    // Exactly 0: s′ is exactly 0 in a dwell and T = F_s s′.
    assert_eq!(step.torque, Some(0.0));
    // The crank torque of 3 N·m needs a force of ~3/(0.1 m) order on the slider.
    assert!(step.step.solution.as_ref().unwrap().drive_torque.abs() > 1.0);
}

/// A motor on the follower's drive is refused: it belongs on the cam shaft.
#[test]
fn a_motor_on_the_follower_is_refused() {
    let m = mechanism();
    let d = Dynamics::new().with_motor(mechdiff_core::dynamics::Motor {
        ratio: 1.0,
        rotor_inertia: 0.0,
        efficiency: 1.0,
    });
    let model = d.compile(&m).unwrap();
    let plan = Plan::for_requests(&[Request::DriveTorque], d.available(&m));
    let cam = CamJoint::new(program());
    let error = joint::run(&cam, &plan, &model, &Solver::default(), &[0.1], |_| {
        DriveState::constant_speed(5.0)
    })
    .unwrap_err();
    assert!(error.to_string().contains("motor"), "{error}");
}

/// A cam that pushes the slider past the crank's reach (R + L from O) and back between two
/// cam angles of the run: the run is refused with the blocked range between them, and the
/// limit is the cam angle where the harmonic rise reaches R + L, solved by hand:
/// s = x₀ + H (1 − cos θ)/2 = R + L.
#[test]
fn a_blocked_range_between_two_cam_angles_is_reported_at_its_cam_angle() {
    let m = mechanism();
    let d = Dynamics::new();
    let model = d.compile(&m).unwrap();
    let plan = Plan::for_requests(&[Request::Positions], d.available(&m));
    let x0 = sketch_slider();
    // 10 µm past the reach.
    let lift = R + L - x0 + 1e-5;
    let program = CamProgram::new(
        vec![
            Segment::law(MotionLaw::SimpleHarmonic, lift, PI),
            Segment::law(MotionLaw::SimpleHarmonic, -lift, PI),
        ],
        x0,
    )
    .unwrap();
    let cam = CamJoint::new(program);
    let (a, b) = (PI - 0.1, PI + 0.1);
    // Both cam angles are within reach (the peak lies between them).
    for t in [a, b] {
        assert!(cam.svaj(t).value < R + L - 1e-4, "θ = {t}");
    }
    let error = joint::run(&cam, &plan, &model, &Solver::default(), &[a, b], |_| {
        DriveState::constant_speed(1.0)
    })
    .unwrap_err();
    let mechdiff_core::Error::Blocked {
        from, to, limit, ..
    } = error
    else {
        panic!("expected a blocked range, got {error}");
    };
    assert_eq!((from, to), (a, b));
    let want = (1.0 - 2.0 * (R + L - x0) / lift).acos();
    // 1e-9 rad: the limit in s is the root of the dyad's margin to rounding (1e-17 m) and
    // s′ = H sin θ / 2 ≈ 3e-4 m/rad there: ~1e-13 rad.
    assert!((limit - want).abs() < 1e-9, "{limit} vs {want}");
}
