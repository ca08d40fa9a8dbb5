//! What does code generated from a scene file cost, against the hand-derived formulas?
//!
//! The Whitworth shaping machine from `scenes/whitworth.toml`: its generated module
//! (`mechdiff_scene!`, ψ and x_C with derivatives 1 and 2 and every loop's guard), the
//! same for ψ alone (`tests/data/whitworth_psi.toml`), the run-time
//! evaluator of the same graph, the hand-derived formulas (1.35), (1.36), (1.39), (1.41),
//! and Dual2 through the closed-form ψ, in one run; and the whole pose (ψ, A, C, S1, S2, S3
//! with ′ and ″) generated from `tests/data/whitworth_pose.toml` against the hand-derived
//! `whitworth::hand::pose`.
//!
//! The evaluator's program compiled to native code (`trace::JitProgram`, cranelift) beside
//! the interpreter, and what compiling each costs for ψ.
//!
//! Then the sweep of `mechdiff run` in process on the same scene (10⁴ positions over a
//! turn, every column of the scene to second order): `Sweeper::row` by the solver and by
//! the run-time evaluator interpreted and compiled (`--evaluator
//! solver|interpreter|jit`), and what setting up each sweep costs (the program's: trace,
//! differentiate, compile) — where `auto` would start to pay, and from how many positions
//! `--evaluator program` compiles (`evaluator::JIT_FROM_POSITIONS`).
//!
//! Last, a mixed plan (`tests/data/triad_slider.toml`: the triad by Newton, the crank and
//! a slider dyad in closed form), its sweep at 0.05° (1501 positions): the solver, the
//! run-time evaluator (Newton inside it) and the generated `Tracker`.
//!
//! ```sh
//! cargo bench -p mechdiff --bench scene_codegen -- --warm-up-time 1 --measurement-time 4
//! ```

use criterion::measurement::WallTime;
use criterion::{
    BatchSize, BenchmarkGroup, Criterion, Throughput, criterion_group, criterion_main,
};
use mechdiff::codegen::scene::SceneCode;
use mechdiff::evaluator::Evaluator;
use mechdiff::scene::{Plan, RunOptions, Scene, Setup, Sweeper};
use mechdiff_core::method::{Differentiator, Dual2};
use mechdiff_core::trace::JitProgram;
use mechdiff_mechanisms::Whitworth;
use mechdiff_mechanisms::whitworth::hand;
use std::hint::black_box;

#[allow(dead_code, clippy::all)]
mod generated {
    mechdiff_scene_macros::mechdiff_scene!("scenes/whitworth.toml");
}

#[allow(dead_code, clippy::all)]
mod generated_psi {
    mechdiff_scene_macros::mechdiff_scene!("tests/data/whitworth_psi.toml");
}

#[allow(dead_code, clippy::all)]
mod generated_pose {
    mechdiff_scene_macros::mechdiff_scene!("tests/data/whitworth_pose.toml");
}

#[allow(dead_code, clippy::all)]
mod generated_triad_slider {
    mechdiff_scene_macros::mechdiff_scene!("tests/data/triad_slider.toml");
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
    let psi_scene = mechdiff::scene::load("tests/data/whitworth_psi.toml").unwrap();
    let psi_code = SceneCode::of(&psi_scene).unwrap();
    let psi_program = psi_code.program(&psi_scene).unwrap();
    let (mut psi_registers, mut psi_out) =
        (psi_program.registers(), vec![0.0; psi_program.outputs()]);
    let jit = JitProgram::compile(&program).unwrap();
    let psi_jit = JitProgram::compile(&psi_program).unwrap();
    let (mut jit_out, mut psi_jit_out) = (out.clone(), psi_out.clone());

    let mut group =
        c.benchmark_group("whitworth from its scene, ψ,ψ′,ψ″: hand vs generated vs dual2");
    group.bench_function("hand ψ", |b| {
        b.iter(|| hand::rocker_angle(black_box(lambda), black_box(PHI)))
    });
    group.bench_function("generated ψ (+ guards)", |b| {
        b.iter(|| generated_psi::pose(black_box(PHI)))
    });
    group.bench_function("run-time evaluator ψ (+ guards)", |b| {
        b.iter(|| {
            psi_program.evaluate(black_box(PHI), &mut psi_registers, &mut psi_out);
            psi_code.read(&psi_out).map(|v| v[0] + v[1] + v[2]).ok()
        })
    });
    group.bench_function("JIT ψ (+ guards)", |b| {
        b.iter(|| {
            psi_jit.evaluate(black_box(PHI), &mut psi_jit_out);
            psi_code.read(&psi_jit_out).map(|v| v[0] + v[1] + v[2]).ok()
        })
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
    group.bench_function("JIT ψ, x_C (+ guards)", |b| {
        b.iter(|| {
            jit.evaluate(black_box(PHI), &mut jit_out);
            code.read(&jit_out).map(|v| v[0] + v[3]).ok()
        })
    });
    group.finish();

    let mut group = c.benchmark_group("whitworth ψ,ψ′,ψ″ evaluator set-up: interpreter vs JIT");
    group.bench_function("interpreter (Program::compile)", |b| {
        b.iter(|| psi_code.program(black_box(&psi_scene)).unwrap().outputs())
    });
    group.bench_function("JIT (Program::compile, then JitProgram::compile)", |b| {
        b.iter(|| {
            let program = psi_code.program(black_box(&psi_scene)).unwrap();
            JitProgram::compile(&program).unwrap().outputs()
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

/// Positions of the in-process sweeps.
const POSITIONS: usize = 10_000;

fn whitworth_sweep() -> Scene {
    let text = std::fs::read_to_string("scenes/whitworth.toml").unwrap();
    let step = 360.0 / POSITIONS as f64;
    let text = text.replace("step = 0.5\n", &format!("step = {step}\n"));
    let scene = mechdiff::scene::parse("whitworth.toml", &text).unwrap();
    assert!(
        scene.positions.len() > POSITIONS,
        "the sweep's step was not replaced"
    );
    scene
}

fn sweep_solver_vs_program(c: &mut Criterion) {
    let mut group = c.benchmark_group(
        "whitworth.toml sweep rows in process, 10^4 positions: solver vs run-time evaluator",
    );
    group.throughput(Throughput::Elements(POSITIONS as u64 + 1));
    for (name, evaluator) in [
        ("solver", Evaluator::Solver),
        ("interpreter", Evaluator::Interpreter),
        ("JIT (what `program` chooses at 10^4)", Evaluator::Jit),
    ] {
        bench_rows(&mut group, name, &whitworth_sweep(), evaluator);
    }
    group.finish();
    let mut group = c.benchmark_group("whitworth.toml sweep set-up: solver vs run-time evaluator");
    for (name, evaluator) in [
        ("solver", Evaluator::Solver),
        (
            "interpreter (trace, differentiate, compile)",
            Evaluator::Interpreter,
        ),
        (
            "JIT (trace, differentiate, compile, cranelift)",
            Evaluator::Jit,
        ),
    ] {
        let scene = whitworth_sweep();
        let setup = Setup::of(&scene, &RunOptions { evaluator }).unwrap();
        let plan = Plan::of(&setup);
        group.bench_function(name, |b| {
            b.iter(|| Sweeper::new(&setup, &plan).unwrap().loops().len())
        });
    }
    group.finish();
}

/// `mechdiff run`'s rows of `scene` in process, its positions evaluated by `evaluator`
/// (`Sweeper::row` at every drive position; the sweeper's set-up outside the measurement),
/// as `rows, {name}`.
fn bench_rows(
    group: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    scene: &Scene,
    evaluator: Evaluator,
) {
    let setup = Setup::of(scene, &RunOptions { evaluator }).unwrap();
    let plan = Plan::of(&setup);
    group.bench_function(format!("rows, {name}"), |b| {
        b.iter_batched(
            || Sweeper::new(&setup, &plan).unwrap(),
            |mut sweeper| {
                let mut row = Vec::new();
                let mut sum = 0.0;
                for phi in scene.positions.iter() {
                    sweeper.row(black_box(phi), &mut row).unwrap();
                    sum += row[1];
                }
                sum
            },
            BatchSize::PerIteration,
        )
    });
}

fn mixed_plan_sweep(c: &mut Criterion) {
    let text = std::fs::read_to_string("tests/data/triad_slider.toml").unwrap();
    let text = text.replace("step = 2.5\n", "step = 0.05\n");
    let scene = mechdiff::scene::parse("triad_slider.toml", &text).unwrap();
    assert_eq!(
        scene.positions.len(),
        1501,
        "the sweep's step was not replaced"
    );
    let mut group = c.benchmark_group(
        "triad_slider.toml (mixed plan) sweep rows, 1501 positions: solver vs run-time \
         evaluator vs generated Tracker",
    );
    group.throughput(Throughput::Elements(scene.positions.len() as u64));
    for (name, evaluator) in [
        ("solver", Evaluator::Solver),
        ("program", Evaluator::Program),
    ] {
        bench_rows(&mut group, name, &scene, evaluator);
    }
    group.bench_function(
        "generated Tracker::pose (SI values, no row formatting)",
        |b| {
            b.iter_batched(
                || generated_triad_slider::Tracker::new().unwrap(),
                |mut tracker| {
                    let mut sum = 0.0;
                    for phi in scene.positions.iter() {
                        sum += tracker.pose(black_box(phi)).unwrap()[0][0];
                    }
                    sum
                },
                BatchSize::PerIteration,
            )
        },
    );
    group.finish();
}

criterion_group!(
    benches,
    whitworth_from_scene,
    sweep_solver_vs_program,
    mixed_plan_sweep
);
criterion_main!(benches);
