//! `mechdiff_scene!` in a crate: the module it expands to is the one `mechdiff codegen`
//! prints (bit for bit the same numbers), agrees with the solver, and reports the
//! solver's guard failures. (A scene it cannot read is a compile error: the error path is
//! tested in `src/expand.rs`; a trybuild case would rebuild the whole `mechdiff` library in
//! trybuild's own target folder, minutes of CI for one message.)

use mechdiff::scene;

mod whitworth {
    mechdiff_scene_macros::mechdiff_scene!("../scenes/whitworth.toml");
}

mod four_bar_unassemblable {
    mechdiff_scene_macros::mechdiff_scene!("../tests/data/four_bar_unassemblable.toml");
}

#[allow(dead_code, clippy::all)]
mod printed {
    include!("../../tests/generated/whitworth.rs");
}

// A mixed plan (the triad by Newton, a slider dyad in closed form after it).
mod triad_slider {
    mechdiff_scene_macros::mechdiff_scene!("../tests/data/triad_slider.toml");
}

#[allow(dead_code, clippy::all)]
mod printed_triad_slider {
    include!("../../tests/generated/triad_slider.rs");
}

#[test]
fn the_macro_expands_a_mixed_plan_to_the_printed_module() {
    // Bit for bit, walking the same drive positions in the same order: the same source
    // (with its Newton solver and state) compiled in two crates. The walk ends past the
    // triad's limit position (91.17°): both fail there with the same error.
    assert_eq!(triad_slider::LOOPS, printed_triad_slider::LOOPS);
    assert_eq!(
        triad_slider::PATHS,
        ["closed form", "Newton", "closed form"]
    );
    let mut a = triad_slider::Tracker::new().unwrap();
    let mut b = printed_triad_slider::Tracker::new().unwrap();
    for k in 0..=100 {
        let phi = (1.0 + k as f64).to_radians();
        match (a.pose(phi), b.pose(phi)) {
            (Ok(x), Ok(y)) => {
                let bits = |rows: [[f64; 3]; 3]| rows.map(|r| r.map(f64::to_bits));
                assert_eq!(bits(x), bits(y), "φ = {phi}");
            }
            (Err(x), Err(y)) => assert_eq!(format!("{x:?}"), format!("{y:?}"), "φ = {phi}"),
            (x, y) => panic!("φ = {phi}: macro {x:?}, printed {y:?}"),
        }
    }
}

#[test]
fn the_macro_expands_to_the_printed_module() {
    // Bit for bit: the same source, compiled in two crates.
    assert_eq!(whitworth::OUTPUTS, printed::OUTPUTS);
    assert_eq!(whitworth::LOOPS, printed::LOOPS);
    for k in 0..=720 {
        let phi = -6.0 + k as f64 / 60.0;
        let (a, b) = (whitworth::pose(phi).unwrap(), printed::pose(phi).unwrap());
        let bits = |rows: [[f64; 3]; 2]| rows.map(|r| r.map(f64::to_bits));
        assert_eq!(bits(a), bits(b), "φ = {phi}");
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
