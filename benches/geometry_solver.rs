//! Cost of the geometry-only Whitworth per drive position against its closed form.
//!
//! - `whitworth ψ,ψ′,ψ″, 720 positions: geometry vs closed form` — one
//!   revolution at 0.5° steps; the geometry path solves every loop of the model in closed
//!   form in `Dual2_64` (the solver's default: all three Whitworth loops match a pattern)
//!   and reads ψ (resolved once with `Mechanism::rotation_output`, read with
//!   `Tracker::value`: no `Kinematics` built); "Newton forced"
//!   (`Solver::with_closed_form(false)`) is a warm-started Newton solve plus the implicit
//!   lift to second order. The closed-form Dual2 paths are the Whitworth module's own,
//!   through the `Dual2` differentiator: ψ alone (`Whitworth::rocker`, the strict
//!   comparison: the output asked for) and the whole pose (`Whitworth` itself: ψ, A, C,
//!   S1, S2, S3, as the solver places every link).
//! - `rack-driven slotted link (001), 720 positions` — `scenes/rack_slotted_link.toml`
//!   swept over 0.2 m of rack travel reading θ3, θ3′, θ3″: every loop in closed form (the
//!   default) against Newton forced.
//! - `whitworth lift q′,q″ at one pose: one LU + Dual2 vs num-dual implicit_derivative_vec`
//!   — the two exact ways to differentiate the solved pose.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use mechdiff_core::geometry::{Equations, Mechanism, ScalarOutput, Solver, Tracker, implicit};
use mechdiff_core::method::{Differentiator, Dual2};
use mechdiff_mechanisms::whitworth::Whitworth;
use nalgebra::{SVector, U9};
use num_dual::{Dual2_64, DualVec, implicit_derivative_vec};
use std::hint::black_box;

/// The reference Whitworth of whitworth_000.md by geometry only.
fn whitworth() -> Mechanism {
    Whitworth::reference()
        .linkage([0.0, 0.0])
        .expect("the reference geometry assembles")
}

/// Walks a copy of `start` through `positions`, reading `output` to second order at each:
/// the loop every geometry-side measurement times.
fn walk(start: &Tracker<'_>, positions: &[f64], output: &ScalarOutput) -> f64 {
    let mut t = start.clone();
    let mut acc = 0.0;
    for &phi in positions {
        t.move_to(black_box(phi)).expect("assembles");
        let x = t.value(output);
        acc += x.value + x.d1() + x.d2();
    }
    acc
}

fn per_drive_position(c: &mut Criterion) {
    let m = whitworth();
    let phis: Vec<f64> = (1..=720).map(|i| (i as f64 * 0.5).to_radians()).collect();
    let start = Solver::default().track(&m).expect("assembles");
    let rocker = m.rotation_output("rocker").expect("link exists");
    let shaper = Whitworth::reference();
    let rocker_angle = shaper.rocker();
    // Both sides give the same ψ, ψ′, ψ″ before they are timed (the rocker turns by −ψ;
    // both exact: 1e-12 on values of order 1).
    let mut check = start.clone();
    for &phi in &phis {
        check.move_to(phi).expect("assembles");
        let (ours, closed) = (check.value(&rocker), Dual2.jets(&rocker_angle, phi));
        let same = [
            ours.value + closed.value,
            ours.d1() + closed.d1(),
            ours.d2() + closed.d2(),
        ];
        assert!(
            same.iter().all(|e| e.abs() < 1e-12),
            "ψ differs at {phi} rad"
        );
    }
    let mut group = c.benchmark_group("whitworth ψ,ψ′,ψ″, 720 positions: geometry vs closed form");
    group.throughput(Throughput::Elements(phis.len() as u64));
    group.bench_function(
        BenchmarkId::from_parameter("geometry: solve + read ψ"),
        |b| b.iter(|| walk(&start, &phis, &rocker)),
    );
    let newton = Solver::default()
        .with_closed_form(false)
        .track(&m)
        .expect("assembles");
    group.bench_function(
        BenchmarkId::from_parameter("geometry, Newton forced: solve + read ψ"),
        |b| b.iter(|| walk(&newton, &phis, &rocker)),
    );
    group.bench_function(BenchmarkId::from_parameter("geometry: solve only"), |b| {
        b.iter(|| {
            let mut t = start.clone();
            for &phi in &phis {
                t.move_to(black_box(phi)).expect("assembles");
            }
            t.phi()
        })
    });
    group.bench_function(
        BenchmarkId::from_parameter("closed form, Dual2: ψ alone"),
        |b| {
            b.iter(|| {
                let mut acc = 0.0;
                for &phi in &phis {
                    let psi = Dual2.jets(&rocker_angle, black_box(phi));
                    acc += psi.value + psi.d1() + psi.d2();
                }
                acc
            })
        },
    );
    group.bench_function(
        BenchmarkId::from_parameter("closed form, Dual2: whole pose"),
        |b| {
            b.iter(|| {
                let mut acc = 0.0;
                for &phi in &phis {
                    let pose = Dual2.jets(&shaper, black_box(phi));
                    acc += pose.psi.value + pose.psi.d1() + pose.psi.d2();
                }
                acc
            })
        },
    );
    group.finish();
}

fn rack_slotted_link(c: &mut Criterion) {
    let scene = mechdiff::scene::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenes/rack_slotted_link.toml"
    ))
    .expect("the scene loads");
    let m = mechdiff::scene::check(&scene)
        .expect("the scene checks")
        .mechanism;
    let theta3 = m.rotation_output("slotted_link").expect("link exists");
    let travel: Vec<f64> = (0..720)
        .map(|i| 0.32 + 0.2 * f64::from(i) / 720.0)
        .collect();
    let mut group = c.benchmark_group("rack-driven slotted link (001), 720 positions");
    for (name, closed_form) in [("closed forms", true), ("Newton forced", false)] {
        let start = Solver::default()
            .with_closed_form(closed_form)
            .track(&m)
            .expect("assembles");
        group.bench_function(BenchmarkId::from_parameter(name), |b| {
            b.iter(|| walk(&start, &travel, &theta3))
        });
    }
    group.finish();
}

fn lift(c: &mut Criterion) {
    let m = whitworth();
    let eq = Equations::new(&m);
    let mut t = Solver::default().track(&m).expect("assembles");
    let phi = 1.0;
    t.move_to(phi).expect("assembles");
    let q = t.coordinates().to_vec();
    let x = SVector::<f64, 9>::from_column_slice(&q);
    // Both must agree before they are timed (exact methods: 1e-12 on O(1) values).
    let ours = implicit::lift(&eq, &q, phi, 2).expect("regular");
    let theirs = lift_num_dual(&eq, x, phi);
    for i in 0..9 {
        assert!(
            (ours[0][i] - theirs[i].v1).abs() < 1e-12 && (ours[1][i] - theirs[i].v2).abs() < 1e-12
        );
    }
    let mut group = c.benchmark_group(
        "whitworth lift q′,q″ at one pose: one LU + Dual2 vs num-dual implicit_derivative_vec",
    );
    group.bench_function("one LU + Dual2 (mechdiff)", |b| {
        b.iter(|| implicit::lift(&eq, black_box(&q), black_box(phi), 2))
    });
    group.bench_function("implicit_derivative_vec (num-dual)", |b| {
        b.iter(|| lift_num_dual(&eq, black_box(x), black_box(phi)))
    });
    group.finish();
}

fn lift_num_dual(eq: &Equations, x: SVector<f64, 9>, phi: f64) -> SVector<Dual2_64, 9> {
    let arg = Dual2_64::new(phi, 1.0, 0.0);
    implicit_derivative_vec(
        |q: SVector<DualVec<Dual2_64, U9>, 9>, phi: &DualVec<Dual2_64, U9>| {
            let mut out = [DualVec::from_re(Dual2_64::from(0.0)); 9];
            eq.evaluate(q.as_slice(), *phi, &mut out);
            SVector::from(out)
        },
        x,
        &arg,
    )
}

criterion_group!(benches, per_drive_position, rack_slotted_link, lift);
criterion_main!(benches);
