//! `mechdiff_scene!` in a crate: the module it expands to computes what the run-time
//! evaluator of the same graph computes (bit for bit), agrees with the solver, and reports
//! the solver's guard failures. (A scene it cannot read is a compile error: the error path is
//! tested in `src/expand.rs`; a trybuild case would rebuild the whole `mechdiff` library in
//! trybuild's own target folder, minutes of CI for one message.)

use mechdiff::codegen::scene::SceneCode;
use mechdiff::scene;

mod whitworth {
    mechdiff_scene_macros::mechdiff_scene!("../scenes/whitworth.toml");
}

mod four_bar_unassemblable {
    mechdiff_scene_macros::mechdiff_scene!("../tests/data/four_bar_unassemblable.toml");
}

// A mixed plan (the triad by Newton, a slider dyad in closed form after it).
mod triad_slider {
    mechdiff_scene_macros::mechdiff_scene!("../tests/data/triad_slider.toml");
}

/// The scene file at `path`, relative to the workspace's root.
fn load(path: &str) -> scene::Scene {
    scene::load(format!("{}/../{path}", env!("CARGO_MANIFEST_DIR"))).unwrap()
}

#[test]
fn the_macros_mixed_plan_is_the_run_time_evaluator_bit_for_bit() {
    // Bit for bit, walking the same drive positions in the same order: the evaluator's
    // programs compute the same graph's operations in the same order as the emitted Rust,
    // with the same Newton steps and Gaussian elimination (tests/scene_codegen.rs checks
    // every scene so). The walk ends past the triad's limit position (91.17°): there the
    // macro's tracker fails and the evaluator leaves the step to the solver.
    assert_eq!(
        triad_slider::PATHS,
        ["closed form", "Newton", "closed form"]
    );
    let scene = load("tests/data/triad_slider.toml");
    let code = SceneCode::of(&scene).unwrap();
    let m = scene::build::mechanism(&scene).unwrap();
    let solver = mechdiff::core::geometry::Solver::default()
        .track(&m)
        .unwrap();
    let values: Vec<_> = code.jets.iter().flatten().copied().collect();
    let mut evaluator =
        mechdiff::core::trace::MixedTracker::new(&solver, &code.position, &values).unwrap();
    let mut tracker = triad_slider::Tracker::new().unwrap();
    let (mut failed, mut assembled) = (0, 0);
    for k in 0..=100 {
        let phi = (1.0 + k as f64).to_radians();
        match (tracker.pose(phi), evaluator.move_to(phi)) {
            (Ok(rows), Some(values)) => {
                let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&rows.concat()), bits(values), "φ = {phi}");
                assembled += 1;
            }
            (Err(_), None) => failed += 1,
            (x, y) => panic!("φ = {phi}: macro {x:?}, evaluator {y:?}"),
        }
    }
    assert!(
        failed > 5 && assembled > 80,
        "{failed} failed, {assembled} assembled"
    );
}

#[test]
fn the_macros_whitworth_is_the_run_time_evaluator_bit_for_bit() {
    // Bit for bit: the evaluator computes the same graph's operations in the same order
    // (sin_cos, powi, the engine's f64 arithmetic) as the emitted Rust.
    let scene = load("scenes/whitworth.toml");
    let code = SceneCode::of(&scene).unwrap();
    assert_eq!(code.names, whitworth::OUTPUTS);
    let program = code.program(&scene).unwrap();
    let (mut registers, mut out) = (program.registers(), vec![0.0; program.outputs()]);
    for k in 0..=720 {
        let phi = -6.0 + k as f64 / 60.0;
        program.evaluate(phi, &mut registers, &mut out);
        let values = code.read(&out).unwrap();
        let rows = whitworth::pose(phi).unwrap();
        let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&rows.concat()), bits(values), "φ = {phi}");
    }
}

#[test]
fn the_macros_whitworth_agrees_with_the_solver() {
    // 1e-13 relative (absolute below 1), as tests/scene_codegen.rs checks every generated
    // module: the same closed forms in f64, rounded differently by the solver's dual
    // numbers (measured 2e-15 at worst); ψ modulo 2π (the module has no sweep to follow).
    let scene = scene::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../scenes/whitworth.toml"
    ))
    .unwrap();
    let report = scene::run(&scene).unwrap();
    let column = |name: &str| report.columns.iter().position(|c| c.name == name).unwrap();
    let columns = [["psi", "psi'", "psi''"], ["x_C", "x_C'", "x_C''"]].map(|r| r.map(column));
    let mut compared = 0;
    for row in &report.rows {
        let pose = whitworth::pose(row[0]).unwrap();
        for (values, columns) in pose.iter().zip(&columns) {
            for (order, (&value, &c)) in values.iter().zip(columns).enumerate() {
                let mut gap = value - row[c];
                if c == columns[0] && order == 0 && columns[0] == column("psi") {
                    gap -= (gap / std::f64::consts::TAU).round() * std::f64::consts::TAU;
                }
                assert!(
                    gap.abs() <= 1e-13 * row[c].abs().max(1.0),
                    "φ = {}: {gap:e}",
                    row[0]
                );
                compared += 1;
            }
        }
    }
    assert!(compared > 4_000, "{compared}");
}

#[test]
fn the_macros_guards_report_where_the_solver_cannot_assemble() {
    // The four-bar cannot assemble with its crank at 180° (A 0.75 m from O4, coupler +
    // rocker 0.703 m), assembles at 90°.
    assert!(four_bar_unassemblable::pose(90f64.to_radians()).is_ok());
    match four_bar_unassemblable::pose(std::f64::consts::PI) {
        Err(four_bar_unassemblable::LoopFailure::Unassemblable { loop_index, .. }) => {
            assert_eq!(four_bar_unassemblable::LOOPS[loop_index], "A, B, O4");
        }
        other => panic!("{other:?}"),
    }
}
