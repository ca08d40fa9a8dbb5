//! The loops of the `geometry_solver` bench, run a given number of times, for counting the
//! instructions they execute with callgrind (independent of the machine's load, unlike the
//! bench's wall-clock times). BENCHMARKS.md reports instructions per drive position as
//! (count with 10 repetitions − count with 0) / (10 × 720):
//!
//! ```sh
//! cargo build --release --example instructions_per_position
//! for reps in 10 0; do
//!   valgrind --tool=callgrind --callgrind-out-file=/dev/null \
//!     target/release/examples/instructions_per_position geometry $reps 2>&1 | grep Collected
//! done
//! ```
//!
//! Loops (the first argument): `geometry` (Whitworth by geometry only: `move_to` + read ψ,
//! ψ′, ψ″), `newton` (the same with `Solver::with_closed_form(false)`), `psi` (the Whitworth
//! module's closed-form ψ in `Dual2`), `pose` (its whole pose in `Dual2`), `rack` (mechanism
//! 001 from `scenes/rack_slotted_link.toml`: `move_to` + read θ3, θ3′, θ3″), `four_bar`
//! (`scenes/four_bar.toml`: `move_to` + read the rocker's angle ψ, ψ′, ψ″), `hand` (the
//! hand-derived ψ, ψ′, ψ″), `generated` (ψ, ψ′, ψ″ generated from the scene, with guards),
//! `hand_pose` (the hand-derived whole pose: ψ, A, C, S1, S2, S3 with ′ and ″),
//! `generated_pose` (the same generated from `tests/data/whitworth_pose.toml`, with guards),
//! `program` (the Whitworth ψ graph by the run-time evaluator, `trace::Program`), `jit`
//! (the same program compiled to native code, `trace::JitProgram`).

use mechdiff::core::geometry::{ScalarOutput, Solver, Tracker};
use mechdiff::core::method::{Differentiator, Dual2};
use mechdiff::mechanisms::whitworth::Whitworth;
use mechdiff::mechanisms::whitworth::hand;
use std::hint::black_box;
use std::process::ExitCode;

/// Whitworth's ψ, ψ′, ψ″ generated from `tests/data/whitworth_psi.toml` at compile time
/// (`mechdiff_scene!`: the module `mechdiff codegen` prints, see `tests/scene_codegen.rs`).
#[allow(dead_code, clippy::all)]
mod generated_psi {
    mechdiff_scene_macros::mechdiff_scene!("tests/data/whitworth_psi.toml");
}

/// Whitworth's whole pose (ψ, A, C, S1, S2, S3 with ′ and ″) generated from
/// `tests/data/whitworth_pose.toml`.
#[allow(dead_code, clippy::all)]
mod generated_pose {
    mechdiff_scene_macros::mechdiff_scene!("tests/data/whitworth_pose.toml");
}

/// The sum of every value and derivative of a hand-derived whole pose.
fn hand_pose_sum(shaper: &Whitworth, phi: f64) -> f64 {
    let mut acc = 0.0;
    hand::pose(shaper, phi).map(|j| acc += j.value + j.derivatives[0] + j.derivatives[1]);
    acc
}

/// Walks a copy of `start` through `positions`, reading `output` to second order.
fn walk(start: &Tracker<'_>, positions: &[f64], output: &ScalarOutput) -> f64 {
    let mut t = start.clone();
    let mut acc = 0.0;
    for &phi in positions {
        if t.move_to(black_box(phi)).is_err() {
            return f64::NAN;
        }
        let x = t.value(output);
        acc += x.value + x.d1() + x.d2();
    }
    acc
}

fn main() -> Result<ExitCode, Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let (Some(which), Some(reps)) = (args.get(1), args.get(2)) else {
        eprintln!(
            "usage: instructions_per_position \
             geometry|newton|psi|pose|rack|four_bar|hand|generated|hand_pose|generated_pose|program|jit \
             REPETITIONS"
        );
        return Ok(ExitCode::FAILURE);
    };
    let reps: usize = reps.parse()?;
    let shaper = Whitworth::reference();
    let linkage = shaper.linkage([0.0, 0.0])?;
    let rocker = linkage.rotation_output("rocker")?;
    let phis: Vec<f64> = (1..=720)
        .map(|i| (f64::from(i) * 0.5).to_radians())
        .collect();
    let scene = mechdiff::scene::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenes/rack_slotted_link.toml"
    ))?;
    let rack = mechdiff::scene::check(&scene)?.mechanism;
    let theta3 = rack.rotation_output("slotted_link")?;
    let travel: Vec<f64> = (0..720)
        .map(|i| 0.32 + 0.2 * f64::from(i) / 720.0)
        .collect();
    let four_bar_scene =
        mechdiff::scene::load(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/four_bar.toml"))?;
    let four_bar = mechdiff::scene::check(&four_bar_scene)?.mechanism;
    let four_bar_rocker = four_bar.rotation_output("rocker")?;
    let solver = Solver::default();
    let (geometry, newton) = (
        solver.track(&linkage)?,
        solver.with_closed_form(false).track(&linkage)?,
    );
    let rack_start = solver.track(&rack)?;
    let four_bar_start = solver.track(&four_bar)?;
    let rocker_angle = shaper.rocker();
    let lambda = shaper.lambda();
    let psi_scene = mechdiff::scene::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/whitworth_psi.toml"
    ))?;
    let psi_code = mechdiff::codegen::scene::SceneCode::of(&psi_scene)?;
    let program = psi_code.program(&psi_scene)?;
    let (mut registers, mut out) = (program.registers(), vec![0.0; program.outputs()]);
    let jit = mechdiff::core::trace::JitProgram::compile(&program)?;
    let mut acc = 0.0;
    for _ in 0..reps {
        acc += match which.as_str() {
            "geometry" => walk(&geometry, &phis, &rocker),
            "newton" => walk(&newton, &phis, &rocker),
            "rack" => walk(&rack_start, &travel, &theta3),
            "four_bar" => walk(&four_bar_start, &phis, &four_bar_rocker),
            "psi" => phis
                .iter()
                .map(|&phi| {
                    let psi = Dual2.jets(&rocker_angle, black_box(phi));
                    psi.value + psi.d1() + psi.d2()
                })
                .sum(),
            "pose" => phis
                .iter()
                .map(|&phi| {
                    let psi = Dual2.jets(&shaper, black_box(phi)).psi;
                    psi.value + psi.d1() + psi.d2()
                })
                .sum(),
            "hand" => phis
                .iter()
                .map(|&phi| {
                    let psi = hand::rocker_angle(black_box(lambda), black_box(phi));
                    psi.value + psi.d1() + psi.d2()
                })
                .sum(),
            "generated" => phis
                .iter()
                .map(|&phi| match generated_psi::pose(black_box(phi)) {
                    Ok([[psi, psi1, psi2]]) => psi + psi1 + psi2,
                    Err(_) => f64::NAN,
                })
                .sum(),
            "hand_pose" => phis
                .iter()
                .map(|&phi| hand_pose_sum(black_box(&shaper), black_box(phi)))
                .sum(),
            "generated_pose" => phis
                .iter()
                .map(|&phi| match generated_pose::pose(black_box(phi)) {
                    Ok(rows) => rows.iter().flatten().sum(),
                    Err(_) => f64::NAN,
                })
                .sum(),
            "program" => phis
                .iter()
                .map(|&phi| {
                    program.evaluate(black_box(phi), &mut registers, &mut out);
                    match psi_code.read(&out) {
                        Ok(v) => v[0] + v[1] + v[2],
                        Err(_) => f64::NAN,
                    }
                })
                .sum(),
            "jit" => phis
                .iter()
                .map(|&phi| {
                    jit.evaluate(black_box(phi), &mut out);
                    match psi_code.read(&out) {
                        Ok(v) => v[0] + v[1] + v[2],
                        Err(_) => f64::NAN,
                    }
                })
                .sum(),
            other => {
                eprintln!(
                    "unknown loop `{other}`: geometry, newton, psi, pose, rack, four_bar, hand, \
                     generated, hand_pose, generated_pose, program or jit"
                );
                return Ok(ExitCode::FAILURE);
            }
        };
    }
    println!("{acc}");
    Ok(ExitCode::SUCCESS)
}
