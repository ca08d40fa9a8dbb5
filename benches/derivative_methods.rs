//! What does each derivative method cost on the Whitworth shaping machine?
//!
//! Every method is run through the same `Differentiator` interface, monomorphised, on the
//! same position function, so the groups compare methods side by side in one run. To add a
//! method, add one `at_one_angle` / `full_revolution` line per group below.
//!
//! ```sh
//! CARGO_TARGET_DIR=target cargo bench --bench derivative_methods -- --warm-up-time 1 --measurement-time 3
//! ```

use criterion::{
    BenchmarkGroup, Criterion, criterion_group, criterion_main, measurement::WallTime,
};
use mechdiff_core::method::{
    CentralDifference, Differentiator, Dual2, Dual3, HandDerived, HyperDual,
};
use mechdiff_core::{Jet, PositionFunction};
use mechdiff_mechanisms::Whitworth;
use mechdiff_mechanisms::whitworth::{Pose, RockerAngle, hand};
use std::f64::consts::TAU;
use std::hint::black_box;

// Group names are the questions. criterion shows "group/method" cut to 100 bytes: keep each
// name ≤ 87 bytes so that the method names stay visible.

/// ψ, ψ′, ψ″ at one crank angle: the fair comparison of the methods (ψ alone, no pose).
const ONE_ANGLE: &str =
    "whitworth ψ,ψ′,ψ″ at one crank angle: hand vs dual2 vs hyperdual vs central-diff";
/// ψ, ψ′, ψ″ at 360 crank angles: what a table or a plot of one revolution costs.
const REVOLUTION: &str =
    "whitworth revolution at 1°, ψ,ψ′,ψ″: hand vs dual2 vs hyperdual vs central-diff";
/// The whole pose (ψ, A, C, S1, S2, S3) with first and second derivatives: what the inertial
/// forces need.
const POSE: &str = "whitworth pose x′,x″ at one angle: hand vs dual2/hyperdual/dual3/central-diff";

/// The crank angle of the one-angle groups (rad): a generic position, no symmetry.
const PHI: f64 = 1.0;
/// Step of the central differences (rad): the best for second derivatives (see CentralDifference).
const STEP: f64 = 1e-4;

/// Benchmarks the value and first two derivatives of `f` at [`PHI`] by `method`.
fn at_one_angle<F: PositionFunction>(
    group: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    f: &F,
    method: &impl Differentiator<F, 2>,
) {
    group.bench_function(name, |b| {
        b.iter(|| method.jets(black_box(f), black_box(PHI)))
    });
}

/// Benchmarks ψ, ψ′, ψ″ at every whole degree of a revolution (360 evaluations) by `method`.
fn full_revolution(
    group: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    rocker: &RockerAngle,
    method: &impl Differentiator<RockerAngle, 2>,
) {
    group.bench_function(name, |b| {
        b.iter(|| {
            let mut sum = Jet::<2>::from(0.0);
            for k in 0..360 {
                let psi = method.jets(black_box(rocker), black_box(f64::from(k) * TAU / 360.0));
                sum.value += psi.value;
                sum.derivatives[0] += psi.d1();
                sum.derivatives[1] += psi.d2();
            }
            sum
        })
    });
}

/// Dual3 seen as a second-order method (its third derivative dropped), for the pose group.
struct Dual3AsOrder2;

impl<F: PositionFunction> Differentiator<F, 2> for Dual3AsOrder2 {
    fn jets(&self, f: &F, phi: f64) -> F::Output<Jet<2>> {
        F::map(Dual3.jets(f, phi), |x: Jet<3>| x.truncate())
    }
}

fn rocker_angle(c: &mut Criterion) {
    let shaper = Whitworth::reference();
    let rocker = shaper.rocker();
    let lambda = shaper.lambda();
    let by_hand = HandDerived(|phi| hand::rocker_angle(lambda, phi));

    let mut group = c.benchmark_group(ONE_ANGLE);
    // Not a derivative method: ψ alone in f64, the floor set by sin, cos and atan.
    group.bench_function("value-only", |b| {
        b.iter(|| black_box(&rocker).evaluate(black_box(PHI)))
    });
    at_one_angle(&mut group, "hand", &rocker, &by_hand);
    at_one_angle(&mut group, "dual2", &rocker, &Dual2);
    at_one_angle(&mut group, "hyperdual", &rocker, &HyperDual);
    at_one_angle(
        &mut group,
        "central-diff",
        &rocker,
        &CentralDifference::new(STEP),
    );
    group.finish();

    let mut group = c.benchmark_group(REVOLUTION);
    full_revolution(&mut group, "hand", &rocker, &by_hand);
    full_revolution(&mut group, "dual2", &rocker, &Dual2);
    full_revolution(&mut group, "hyperdual", &rocker, &HyperDual);
    full_revolution(
        &mut group,
        "central-diff",
        &rocker,
        &CentralDifference::new(STEP),
    );
    group.finish();
}

fn pose(c: &mut Criterion) {
    let shaper = Whitworth::reference();
    let by_hand = HandDerived(|phi| -> Pose<Jet<2>> { hand::pose(&shaper, phi) });
    let mut group = c.benchmark_group(POSE);
    at_one_angle(&mut group, "hand", &shaper, &by_hand);
    at_one_angle(&mut group, "dual2", &shaper, &Dual2);
    at_one_angle(&mut group, "hyperdual", &shaper, &HyperDual);
    at_one_angle(&mut group, "dual3", &shaper, &Dual3AsOrder2);
    at_one_angle(
        &mut group,
        "central-diff",
        &shaper,
        &CentralDifference::new(STEP),
    );
    group.finish();
}

criterion_group!(benches, rocker_angle, pose);
criterion_main!(benches);
