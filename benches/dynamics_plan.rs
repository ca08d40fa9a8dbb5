//! What does a plan cost? The same Whitworth sweep (360 positions, one revolution) run for
//! positions only, for kinematics (accelerations), and for full dynamics (inertia, gravity, a
//! cutting force on the forward stroke: reactions, drive torque, power balance), and what
//! the exact derivative of every dynamic result with respect to one parameter adds.

use criterion::{Criterion, criterion_group, criterion_main};
use mechdiff_core::dynamics::run::run;
use mechdiff_core::dynamics::{
    Dynamics, EffectsTangent, Friction, Gravity, Load, ModelTangent, Plan, Request,
};
use mechdiff_core::geometry::{DataTangent, Parametric, Solver};
use mechdiff_mechanisms::whitworth::Whitworth;
use std::hint::black_box;

fn plans(c: &mut Criterion) {
    // The reference Whitworth by geometry only, with moments of inertia for the crank and
    // the rocker (the source gives none).
    let shaper = Whitworth::reference();
    let m = shaper
        .linkage([0.05, 1.2])
        .expect("the reference geometry assembles");
    let d = Dynamics::new()
        .with_gravity(Gravity::down(9.81))
        .with_load(Load::force("ram", "C", [-2000.0, 0.0]).active_between(5.0968, 1.1864));
    let model = d.compile(&m).unwrap();
    let available = d.available(&m);
    let phis: Vec<f64> = (1..=360).map(|i| f64::from(i).to_radians()).collect();
    let solver = Solver::default();
    let drive = |_| shaper.drive();
    let mut group =
        c.benchmark_group("whitworth 360-position sweep: positions vs kinematics vs dynamics");
    for (name, requests) in [
        ("positions only (order 0)", vec![Request::Positions]),
        ("kinematics (order 2)", vec![Request::Accelerations]),
        (
            "full dynamics (order 2; inertia, gravity, loads)",
            vec![
                Request::Reactions,
                Request::DriveTorque,
                Request::PowerBalance,
            ],
        ),
    ] {
        let plan = Plan::for_requests(&requests, available);
        group.bench_function(name, |b| {
            b.iter(|| run(black_box(&plan), &model, &solver, black_box(&phis), drive).unwrap())
        });
    }
    // The same sweep with, at each position, the exact d/dp of every dynamic result for a
    // parameter that moves the crank pin A's sketch down and adds mass to the ram: the parametric pose (q, q′, q″ and their d/dp), Φ_q with its d/dp, and the
    // equilibrium's derivative (one more back-substitution), on top of the f64 dynamics.
    let mut data = DataTangent::zero(&m);
    data.points[m.point_index("A").unwrap()] = [0.0, -1.0];
    for (k, l) in m.links().iter().enumerate() {
        if l.inertia.is_some() {
            data.inertias[k] = Some(mechdiff_core::geometry::Inertia {
                mass: f64::from(u8::from(l.name == "ram")),
                center: [0.0; 2],
                moment: 0.0,
            });
        }
    }
    let exact = Parametric::new(&m, &data).unwrap();
    let full = Plan::for_requests(
        &[
            Request::Reactions,
            Request::DriveTorque,
            Request::PowerBalance,
        ],
        available,
    );
    let state = shaper.drive();
    let tangent = ModelTangent::new(
        &model,
        &full.effects,
        &data,
        &EffectsTangent::zero(&d),
        state.omega,
        state.alpha,
    )
    .unwrap();
    group.bench_function(
        "full dynamics and its exact d/dp for one parameter (order 2; inertia, gravity, loads)",
        |b| {
            b.iter(|| {
                let mut tracker = solver.track(&m).unwrap();
                let mut torque = 0.0;
                for &phi in black_box(&phis) {
                    tracker.move_to(phi).unwrap();
                    let k = tracker.kinematics::<2>().unwrap();
                    let s = mechdiff_core::dynamics::kinetostatics::solve(
                        &model,
                        &full.effects,
                        &k,
                        &state,
                    )
                    .unwrap();
                    let pose = exact.pose(&k).unwrap();
                    let jac = exact.jacobian(&pose);
                    let t = tangent.solve(phi, &pose, &jac).unwrap();
                    torque += s.drive_torque + t.drive_torque.eps;
                }
                torque
            })
        },
    );
    // The parametric pose and Φ_q alone (the geometry's part of the line above).
    group.bench_function("parametric pose and Φ_q with their d/dp (order 2)", |b| {
        b.iter(|| {
            let mut tracker = solver.track(&m).unwrap();
            let mut sum = 0.0;
            for &phi in black_box(&phis) {
                tracker.move_to(phi).unwrap();
                let pose = exact.pose(&tracker.kinematics::<2>().unwrap()).unwrap();
                sum += exact.jacobian(&pose)[(0, 0)].eps;
            }
            sum
        })
    });
    // Every effect the Whitworth can have: friction circles in the two bearings and Coulomb
    // friction in both slots and the ram guide, resolved by iteration at each position.
    let with_friction = d
        .clone()
        .with_friction(Friction::revolute("O", 0.1, 0.03))
        .with_friction(Friction::revolute("B0", 0.1, 0.03))
        .with_friction(Friction::sliding("slot A", 0.12))
        .with_friction(Friction::sliding("slot C", 0.12))
        .with_friction(Friction::sliding("ram guide", 0.08));
    let friction_model = with_friction.compile(&m).unwrap();
    let plan = Plan::for_requests(
        &[
            Request::Reactions,
            Request::DriveTorque,
            Request::PowerBalance,
        ],
        with_friction.available(&m),
    );
    group.bench_function(
        "full dynamics with friction (order 2; inertia, gravity, loads, friction)",
        |b| {
            b.iter(|| {
                run(
                    black_box(&plan),
                    &friction_model,
                    &solver,
                    black_box(&phis),
                    drive,
                )
                .unwrap()
            })
        },
    );
    group.finish();
}

criterion_group!(benches, plans);
criterion_main!(benches);
