//! What does the machine in motion cost against today's prescribed-speed dynamics? One
//! evaluation of the equation of motion (position solve, lift, J and J′, one kinetostatic
//! solve at φ̈ = 0) against one prescribed-speed step (position solve, lift, kinetostatics),
//! and a simulated turn (DOP853 at 1e-10) against a prescribed-speed sweep of 360 positions,
//! for the slider-crank with a motor behind a gearbox and a switched load.
//!
//! `cargo bench -p mechdiff-core --features simulate --bench machine_motion -- --warm-up-time 1 --measurement-time 3`

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use mechdiff_core::DriveState;
use mechdiff_core::dynamics::{Dynamics, Effects, Load, Motor, kinetostatics};
use mechdiff_core::geometry::{Drive, Inertia, Mechanism, Solver};
use mechdiff_core::machine::{Characteristic, Machine, Start, Stop, Tolerances, simulate};

fn slider_crank() -> Mechanism {
    let (r, l) = (0.1, 0.4);
    let inertia = |mass, center, moment| Inertia {
        mass,
        center,
        moment,
    };
    Mechanism::builder()
        .point("O", [0.0, 0.0])
        .point("A", [r, 0.0])
        .point("B", [r + l, 0.0])
        .point("X", [1.0, 0.0])
        .ground(["O", "X"])
        .link("crank", ["O", "A"])
        .link("rod", ["A", "B"])
        .link("slider", ["B"])
        .inertia("crank", inertia(1.0, [0.03, 0.0], 0.001))
        .inertia("rod", inertia(1.0, [r + 0.15, 0.0], 0.012))
        .inertia("slider", inertia(2.0, [r + l, 0.0], 0.0))
        .revolute("O", "ground", "crank", "O")
        .revolute("A", "crank", "rod", "A")
        .revolute("B", "rod", "slider", "B")
        .prismatic("guide", "ground", ["O", "X"], "slider", "B")
        .drive(Drive::angle("O"))
        .build()
        .expect("a valid slider-crank")
}

fn per_step(c: &mut Criterion) {
    let m = slider_crank();
    let model = Dynamics::new()
        .with_motor(Motor {
            rotor_inertia: 1e-3,
            ratio: 1.0 / 3.0,
            efficiency: 1.0,
        })
        .with_load(Load::force("slider", "B", [-100.0, 0.0]).active_between(3.5, 5.5))
        .compile(&m)
        .expect("valid effects");
    let effects = Effects {
        inertia: true,
        loads: true,
        motor: true,
        ..Effects::none()
    };
    let machine = Machine::new(&model, effects).with_motor(Characteristic::Linear {
        stall_torque: 20.0,
        no_load_speed: 300.0,
    });
    let phis: Vec<f64> = (0..360).map(|i| f64::from(i).to_radians()).collect();
    let mut group = c.benchmark_group("slider-crank under a motor vs at prescribed speed");
    group.bench_function(
        "prescribed speed: 360 positions (solve, lift, kinetostatics)",
        |b| {
            let mut tracker = Solver::default().track(&m).expect("assembles");
            b.iter(|| {
                let mut sum = 0.0;
                for &phi in &phis {
                    tracker.move_to(black_box(phi)).expect("moves");
                    let k = tracker.kinematics::<2>().expect("lifts");
                    let d = DriveState::constant_speed(95.0);
                    sum += kinetostatics::solve(&model, &effects, &k, &d)
                        .expect("solves")
                        .drive_torque;
                }
                sum
            });
        },
    );
    group.bench_function(
        "equation of motion: 360 states (solve, lift, J, J′, kinetostatics)",
        |b| {
            let mut tracker = machine.tracker().expect("assembles");
            b.iter(|| {
                let mut sum = 0.0;
                for &phi in &phis {
                    sum += machine
                        .state(&mut tracker, black_box(phi), 95.0)
                        .expect("state")
                        .alpha;
                }
                sum
            });
        },
    );
    group.bench_function(
        "simulated turn at ~95 rad/s (DOP853, tolerance 1e-10)",
        |b| {
            let stop = Stop {
                turns: Some(1.0),
                ..Stop::default()
            };
            let start = Start {
                time: 0.0,
                phi: 0.0,
                omega: 95.0,
            };
            b.iter(|| {
                simulate(
                    &machine,
                    black_box(start),
                    &stop,
                    &Tolerances::default(),
                    &mut |_| {},
                )
                .expect("runs")
                .evaluations
            });
        },
    );
    group.finish();
    let s = simulate(
        &machine,
        Start {
            time: 0.0,
            phi: 0.0,
            omega: 95.0,
        },
        &Stop {
            turns: Some(1.0),
            ..Stop::default()
        },
        &Tolerances::default(),
        &mut |_| {},
    )
    .expect("runs");
    println!(
        "one turn: {} steps, {} evaluations, {} stretches",
        s.steps, s.evaluations, s.stretches
    );
}

criterion_group!(benches, per_step);
criterion_main!(benches);
