//! What does a plan cost? The same Whitworth sweep (360 positions, one revolution) run for
//! positions only, for kinematics (accelerations), and for full dynamics (inertia, gravity, a
//! cutting force on the forward stroke: reactions, drive torque, power balance).

use criterion::{Criterion, criterion_group, criterion_main};
use mechdiff_core::DriveState;
use mechdiff_core::dynamics::run::run;
use mechdiff_core::dynamics::{Dynamics, Friction, Gravity, Load, Plan, Request};
use mechdiff_core::geometry::{Drive, Inertia, Mechanism, Solver};
use std::hint::black_box;

const L0: f64 = 0.4;
const L1: f64 = 0.15;
const H: f64 = 0.65;

fn whitworth() -> Mechanism {
    Mechanism::builder()
        .point("O", [0.0, L0])
        .point("B0", [0.0, 0.0])
        .point("A", [0.0, L0 - L1])
        .point("S", [0.0, H])
        .point("C", [0.0, H])
        .point("H0", [0.0, H])
        .point("H1", [1.0, H])
        .ground(["O", "B0", "H0", "H1"])
        .link("crank", ["O", "A"])
        .link("rocker", ["B0", "S"])
        .link("ram", ["C"])
        .inertia(
            "crank",
            Inertia {
                mass: 15.0,
                center: [0.0, L0 - 0.04],
                moment: 0.05,
            },
        )
        .inertia(
            "rocker",
            Inertia {
                mass: 30.0,
                center: [0.0, 0.15],
                moment: 1.2,
            },
        )
        .inertia(
            "ram",
            Inertia {
                mass: 50.0,
                center: [0.0, H],
                moment: 0.0,
            },
        )
        .revolute("O", "ground", "crank", "O")
        .revolute("B0", "ground", "rocker", "B0")
        .pin_in_slot("slot A", "rocker", ["B0", "S"], "crank", "A")
        .prismatic("ram guide", "ground", ["H0", "H1"], "ram", "C")
        .pin_in_slot("slot C", "rocker", ["B0", "S"], "ram", "C")
        .drive(Drive::angle("O"))
        .build()
        .unwrap()
}

fn plans(c: &mut Criterion) {
    let m = whitworth();
    let d = Dynamics::new()
        .with_gravity(Gravity::down(9.81))
        .with_load(Load::force("ram", "C", [-2000.0, 0.0]).active_between(5.0968, 1.1864));
    let model = d.compile(&m).unwrap();
    let available = d.available(&m);
    let phis: Vec<f64> = (1..=360).map(|i| f64::from(i).to_radians()).collect();
    let solver = Solver::default();
    let drive = |_| DriveState::constant_speed(10.471975511965978);
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
