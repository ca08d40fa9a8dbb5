//! What does code generated from a scene file cost, against the hand-derived formulas?
//!
//! The Whitworth shaping machine from `scenes/whitworth.toml`: its generated module
//! (`tests/generated/whitworth.rs`, ψ and x_C with derivatives 1 and 2 and every loop's
//! guard), the same for ψ alone (`tests/generated/whitworth_psi.rs`), the run-time
//! evaluator of the same graph, the hand-derived formulas (1.35), (1.36), (1.39), (1.41),
//! and Dual2 through the closed-form ψ, in one run; and the whole pose (ψ, A, C, S1, S2, S3
//! with ′ and ″) generated from `tests/data/whitworth_pose.toml` against the hand-derived
//! `whitworth::hand::pose`.
//!
//! ```sh
//! cargo bench -p mechdiff --bench scene_codegen -- --warm-up-time 1 --measurement-time 3
//! ```

use criterion::{Criterion, criterion_group, criterion_main};
use mechdiff::codegen::scene::SceneCode;
use mechdiff_core::method::{Differentiator, Dual2};
use mechdiff_mechanisms::Whitworth;
use mechdiff_mechanisms::whitworth::hand;
use std::hint::black_box;

#[allow(dead_code, clippy::all)]
mod generated {
    include!("../tests/generated/whitworth.rs");
}

#[allow(dead_code, clippy::all)]
mod generated_psi {
    include!("../tests/generated/whitworth_psi.rs");
}

#[allow(dead_code, clippy::all)]
mod generated_pose {
    include!("../tests/generated/whitworth_pose.rs");
}

/// The crank angle (rad): a generic position, as in `derivative_methods`.
const PHI: f64 = 1.0;

fn whitworth_from_scene(c: &mut Criterion) {
    let shaper = Whitworth::reference();
    let (lambda, h) = (shaper.lambda(), shaper.parameters().h);
    let rocker = shaper.rocker();
    let scene = mechdiff::scene::load("scenes/whitworth.toml").unwrap();
    let code = SceneCode::of(&scene).unwrap();
    let program = code.program(&scene).unwrap();
    let (mut registers, mut out) = (program.registers(), vec![0.0; program.outputs()]);

    let mut group =
        c.benchmark_group("whitworth from its scene, ψ,ψ′,ψ″: hand vs generated vs dual2");
    group.bench_function("hand ψ", |b| {
        b.iter(|| hand::rocker_angle(black_box(lambda), black_box(PHI)))
    });
    group.bench_function("generated ψ (+ guards)", |b| {
        b.iter(|| generated_psi::pose(black_box(PHI)))
    });
    group.bench_function("dual2 ψ (closed form)", |b| {
        b.iter(|| Dual2.jets(black_box(&rocker), black_box(PHI)))
    });
    group.finish();

    let mut group = c.benchmark_group(
        "whitworth from its scene, ψ and x_C with ′,″: hand vs generated vs run time",
    );
    group.bench_function("hand ψ, x_C", |b| {
        b.iter(|| {
            let phi = black_box(PHI);
            let psi = hand::rocker_angle(black_box(lambda), phi);
            let x = h * psi.value.tan();
            let x1 = hand::ram_velocity_coefficient(black_box(&shaper), phi);
            let x2 = hand::ram_acceleration_coefficient(black_box(&shaper), phi);
            (psi, [x, x1, x2])
        })
    });
    group.bench_function("generated ψ, x_C (+ guards)", |b| {
        b.iter(|| generated::pose(black_box(PHI)))
    });
    group.bench_function("run-time evaluator ψ, x_C (+ guards)", |b| {
        b.iter(|| {
            program.evaluate(black_box(PHI), &mut registers, &mut out);
            code.read(&out).map(|v| v[0] + v[3]).ok()
        })
    });
    group.finish();

    let mut group = c.benchmark_group(
        "whitworth whole pose (ψ, A, C, S1, S2, S3 with ′, ″): hand vs generated vs dual2",
    );
    group.bench_function("hand pose", |b| {
        b.iter(|| hand::pose(black_box(&shaper), black_box(PHI)))
    });
    group.bench_function("generated pose (+ guards)", |b| {
        b.iter(|| generated_pose::pose(black_box(PHI)))
    });
    group.bench_function("dual2 pose (closed form)", |b| {
        b.iter(|| Dual2.jets(black_box(&shaper), black_box(PHI)))
    });
    group.finish();
}

criterion_group!(benches, whitworth_from_scene);
criterion_main!(benches);
