//! The plan: the derivative order and the effects the requested outputs need, and the proof
//! (the run's trace) that nothing else is evaluated.

use crate::common;
use mechdiff_core::DriveState;

use common::slider_crank_parts;
use mechdiff_core::dynamics::run::run;
use mechdiff_core::dynamics::{Dynamics, Effects, Friction, Gravity, Load, Plan, Request};
use mechdiff_core::geometry::{Drive, Inertia, Mechanism, Solver};

/// A slider-crank with masses, gravity, a load and friction data: every effect available.
fn slider_crank() -> (Mechanism, Dynamics) {
    let m = slider_crank_parts(0.1, 0.4, 0.0)
        .inertia(
            "crank",
            Inertia {
                mass: 1.0,
                center: [0.05, 0.0],
                moment: 0.001,
            },
        )
        .inertia(
            "rod",
            Inertia {
                mass: 2.0,
                center: [0.3, 0.0],
                moment: 0.03,
            },
        )
        .inertia(
            "slider",
            Inertia {
                mass: 1.5,
                center: [0.5, 0.0],
                moment: 0.0,
            },
        )
        .drive(Drive::angle("O"))
        .build()
        .unwrap();
    let d = Dynamics::new()
        .with_gravity(Gravity::down(9.81))
        .with_load(Load::force("slider", "B", [-50.0, 0.0]))
        .with_friction(Friction::sliding("guide", 0.1));
    (m, d)
}

fn phis() -> Vec<f64> {
    (1..=36)
        .map(|i| f64::from(i) * 10f64.to_radians())
        .collect()
}

#[test]
fn plan_names_the_order_and_the_effects() {
    let (m, d) = slider_crank();
    let available = d.available(&m);
    assert_eq!(
        available,
        Effects {
            inertia: true,
            gravity: true,
            loads: true,
            friction: true,
            ..Effects::none()
        }
    );
    let p = |r: &[Request]| Plan::for_requests(r, available);
    assert_eq!(p(&[Request::Positions]).order, 0);
    assert_eq!(p(&[Request::Velocities, Request::KineticEnergy]).order, 1);
    assert_eq!(p(&[Request::Jerk]).order, 3);
    assert_eq!(
        p(&[Request::ShakingForce]).to_string(),
        "order 2; effects: inertia; not computed: gravity, loads, friction, efficiency, motor"
    );
    assert_eq!(
        p(&[Request::DriveTorque]).to_string(),
        "order 2; effects: inertia, gravity, loads, friction; not computed: efficiency, motor"
    );
    // Forces without masses need velocities only (friction directions, powers).
    let no_mass = Effects {
        inertia: false,
        ..available
    };
    assert_eq!(Plan::for_requests(&[Request::Reactions], no_mass).order, 1);
}

#[test]
fn unrequested_effects_are_not_evaluated() {
    let (m, d) = slider_crank();
    let model = d.compile(&m).unwrap();
    let available = d.available(&m);
    let drive = |_| DriveState::constant_speed(10.0);
    let go = |requests: &[Request]| {
        let plan = Plan::for_requests(requests, available);
        run(&plan, &model, &Solver::default(), &phis(), drive).unwrap()
    };
    let n = phis().len();
    // Positions only: no derivative, no effect.
    let t = go(&[Request::Positions]).trace;
    assert_eq!(
        (t.positions, t.derivatives, t.inertia, t.equilibrium_solves),
        (n, 0, 0, 0)
    );
    // Accelerations: derivatives, still no effect.
    let t = go(&[Request::Accelerations]).trace;
    assert_eq!(
        (t.derivatives, t.inertia, t.gravity, t.equilibrium_solves),
        (n, 0, 0, 0)
    );
    // Shaking force: inertia only, no equilibrium solve, no gravity, loads or friction.
    let r = go(&[Request::ShakingForce]);
    let t = r.trace;
    assert_eq!(
        (
            t.shaking,
            t.inertia,
            t.gravity,
            t.loads,
            t.friction,
            t.equilibrium_solves
        ),
        (n, n, 0, 0, 0, 0)
    );
    assert!(
        r.steps
            .iter()
            .all(|s| s.shaking.is_some() && s.solution.is_none() && s.energy.is_none())
    );
    // Drive torque: every available effect, friction iterating (more solves than positions).
    let r = go(&[Request::DriveTorque]);
    let t = r.trace;
    assert_eq!(
        (t.inertia, t.gravity, t.loads, t.efficiency, t.motor),
        (n, n, n, 0, 0)
    );
    assert!(t.friction >= n && t.equilibrium_solves > n, "{t:?}");
    // The balance closes with every effect on (1e-9 of the largest power term).
    for s in r.steps.iter().map(|s| s.solution.as_ref().unwrap()) {
        assert!(s.balance.residual.abs() <= 1e-9 * s.balance.scale());
    }
}

#[test]
fn kinetic_energy_at_order_one_has_no_derivative_terms() {
    let (m, d) = slider_crank();
    let model = d.compile(&m).unwrap();
    let plan = Plan::for_requests(&[Request::KineticEnergy], d.available(&m));
    let r = run(&plan, &model, &Solver::default(), &phis(), |_| {
        DriveState::constant_speed(10.0)
    })
    .unwrap();
    let full = Plan::for_requests(&[Request::ReducedInertia], d.available(&m));
    let r2 = run(&full, &model, &Solver::default(), &phis(), |_| {
        DriveState::constant_speed(10.0)
    })
    .unwrap();
    for (a, b) in r.steps.iter().zip(&r2.steps) {
        let (a, b) = (a.energy.unwrap(), b.energy.unwrap());
        assert!(a.reduced_inertia_derivative.is_none() && b.reduced_inertia_derivative.is_some());
        // Same J_red from first-order and second-order jets (identical arithmetic).
        assert_eq!(a.reduced_inertia, b.reduced_inertia);
    }
}

#[test]
fn reduced_inertia_derivative_matches_a_central_difference() {
    // dJ_red/dφ against (J(φ+h) − J(φ−h))/2h with h = 1e-5: truncation ~h²·J‴ ≈ 1e-10 of J,
    // rounding ~1e-16/h ≈ 1e-11; 1e-8 relative to max |J′| leaves margin.
    let (m, d) = slider_crank();
    let model = d.compile(&m).unwrap();
    let plan = Plan::for_requests(&[Request::ReducedInertia], d.available(&m));
    let h = 1e-5;
    let mut pairs = Vec::new();
    for phi in phis() {
        let r = run(
            &plan,
            &model,
            &Solver::default(),
            &[phi - h, phi, phi + h],
            |_| DriveState::constant_speed(1.0),
        )
        .unwrap();
        let e: Vec<_> = r.steps.iter().map(|s| s.energy.unwrap()).collect();
        let fd = (e[2].reduced_inertia - e[0].reduced_inertia) / (2.0 * h);
        pairs.push((e[1].reduced_inertia_derivative.unwrap(), fd));
    }
    let scale = pairs.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
    let err = pairs.iter().map(|p| (p.0 - p.1).abs()).fold(0.0, f64::max) / scale;
    assert!(err <= 1e-8, "{err:e}");
}
