//! `mechdiff run --evaluator solver|program|auto`: the run-time evaluator of a scene's
//! traced closed forms gives the solver's results (to rounding) and the solver's errors
//! (exactly), and the plan line says which path evaluates each loop.

use std::path::Path;

use mechdiff::evaluator::cost::Costs;
use mechdiff::evaluator::{Evaluator, LoopPath};
use mechdiff::scene::{self, Report, Scene};
use mechdiff::{Error, Result, RunOptions};
use mechdiff_core::trace::Backend;

use crate::common;
use common::{mechdiff, stderr, stdout, temp_file};

/// Runs `scene` with its positions evaluated by `evaluator` (`mechdiff run --evaluator`).
fn run_by(scene: &Scene, evaluator: Evaluator) -> Result<Report> {
    scene::run_with(scene, &RunOptions { evaluator })
}

/// Every linkage scene file of `scenes/`.
fn linkage_scenes() -> Vec<String> {
    let mut paths: Vec<String> = std::fs::read_dir("scenes")
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .filter(|p| scene::kind(&std::fs::read_to_string(p).unwrap()) == scene::Kind::Linkage)
        .map(|p| p.display().to_string())
        .collect();
    paths.sort();
    paths
}

/// Asserts that two reports of one scene agree: same columns, same rows, every value to
/// 1e-13 of its column's largest magnitude. Both evaluate the same closed forms in f64, the
/// solver in dual numbers and the program through their symbolic derivatives, so they
/// round differently: a few ulps per operation amplified by the loops' conditioning (the
/// generated code, the same graph, is measured within 2e-15 of the solver over these
/// sweeps in tests/scene_codegen.rs); 1e-13 is issue 15's bound. Angles are compared as
/// they are (both kept continuous along the sweep from the sketch's turn), not modulo 2π.
fn assert_agree(path: &str, solver: &Report, program: &Report) -> usize {
    assert_eq!(solver.columns, program.columns, "{path}");
    assert_eq!(solver.rows.len(), program.rows.len(), "{path}");
    let mut compared = 0;
    for (c, column) in solver.columns.iter().enumerate() {
        let largest = (solver.rows.iter()).fold(0.0f64, |m, r| m.max(r[c].abs()));
        for (a, b) in solver.rows.iter().zip(&program.rows) {
            let gap = (a[c] - b[c]).abs();
            assert!(
                gap <= 1e-13 * largest,
                "{path}: {} at φ = {}: solver {} program {} (gap {gap:e}, scale {largest:e})",
                column.name,
                a[0],
                a[c],
                b[c]
            );
            compared += 1;
        }
    }
    compared
}

/// Asserts that two reports of one scene by the run-time evaluator, interpreted and
/// compiled, are the same: the same values to the bit (both round each operation once, in
/// the same order, and call the same functions), the same plan but for the back end, and
/// the same warnings.
fn assert_same_bits(path: &str, interpreted: &Report, compiled: &Report) {
    assert_eq!(
        interpreted.plan.backend,
        Some(Backend::Interpreter),
        "{path}"
    );
    assert_eq!(compiled.plan.backend, Some(Backend::Jit), "{path}");
    let mut plan = compiled.plan.clone();
    plan.backend = interpreted.plan.backend;
    assert_eq!(interpreted.plan, plan, "{path}");
    assert_eq!(interpreted.warnings, compiled.warnings, "{path}");
    assert_eq!(interpreted.rows.len(), compiled.rows.len(), "{path}");
    for (a, b) in interpreted.rows.iter().zip(&compiled.rows) {
        let bits = |r: &[f64]| r.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(a), bits(b), "{path} at φ = {}", a[0]);
    }
}

#[test]
fn every_scene_runs_the_same_by_the_program_and_by_the_solver() {
    let mut programs = 0;
    for path in linkage_scenes() {
        let scene = scene::load(&path).unwrap();
        let solver = run_by(&scene, Evaluator::Solver).unwrap();
        assert!(
            solver
                .plan
                .loops
                .iter()
                .all(|l| l.path != LoopPath::Program),
            "{path}"
        );
        match run_by(&scene, Evaluator::Interpreter) {
            Ok(program) => {
                assert!(
                    program
                        .plan
                        .loops
                        .iter()
                        .all(|l| l.path == LoopPath::Program),
                    "{path}: {:?}",
                    program.plan.loops
                );
                assert_agree(&path, &solver, &program);
                assert_eq!(solver.warnings, program.warnings, "{path}");
                // The compiled program: the interpreter's rows, bit for bit.
                let jit = run_by(&scene, Evaluator::Jit).unwrap();
                assert_same_bits(&path, &program, &jit);
                programs += 1;
            }
            // A cam-driven linkage: the program would be a function of the follower's
            // position, not of the cam angle; refused by name, never mislabelled.
            Err(Error::NoEvaluator { reason, .. }) => {
                assert!(scene.drive.cam.is_some(), "{path}: {reason}");
                assert!(reason.contains("cam"), "{path}: {reason}");
                // The error names the option's value the user gave.
                let e = run_by(&scene, Evaluator::Jit).unwrap_err();
                assert!(
                    e.to_string().contains("--evaluator jit cannot evaluate"),
                    "{path}: {e}"
                );
            }
            Err(e) => panic!("{path}: {e}"),
        }
    }
    assert!(programs >= 11, "only {programs} scenes ran by the program");
}

/// The four-bar of tests/data cannot assemble with its crank near 180°.
fn unassemblable(sweep: &str) -> Scene {
    let text = std::fs::read_to_string("tests/data/four_bar_unassemblable.toml").unwrap();
    let text = text.replace("from = 90\nto = 120\nstep = 5\n", sweep);
    assert!(text.contains(sweep), "the sweep was not replaced");
    scene::parse("four_bar_unassemblable.toml", &text).unwrap()
}

/// Runs `scene` both ways: the solver's result and the program's (interpreted and
/// compiled to native code: the same results, checked here, errors word for word).
fn both(scene: &Scene) -> [Result<Report>; 2] {
    let [solver, interpreted, compiled] =
        [Evaluator::Solver, Evaluator::Interpreter, Evaluator::Jit].map(|e| run_by(scene, e));
    match (&interpreted, &compiled) {
        (Ok(a), Ok(b)) => assert_same_bits("both", a, b),
        (a, b) => assert_eq!(
            a.as_ref().map_err(ToString::to_string).err(),
            b.as_ref().map_err(ToString::to_string).err()
        ),
    }
    [solver, interpreted]
}

#[test]
fn a_sweep_into_an_unassemblable_range_stops_with_the_solvers_error() {
    // Steps of 2° into the blocked range; one step of 170° over it (the solver subdivides
    // it and locates the limit position); a position exactly inside it; and a sweep in
    // the other direction. Each time the program proves no step past the limit, the solver
    // takes that step and reports: the same error, word for word.
    for sweep in [
        "from = 90\nto = 270\nstep = 2\n",
        "from = 90\nto = 260\nstep = 170\n",
        "positions = [100, 180]\n",
        "from = 120\nto = -100\nstep = -4\n",
    ] {
        let scene = unassemblable(sweep);
        let [solver, program] = both(&scene);
        let (solver, program) = (solver.unwrap_err(), program.unwrap_err());
        assert!(
            matches!(solver, Error::Blocked { .. } | Error::Unassemblable { .. }),
            "{sweep}: {solver}"
        );
        assert_eq!(solver.to_string(), program.to_string(), "{sweep}");
    }
}

#[test]
fn the_cli_reports_the_limit_position_the_same_both_ways() {
    // Steps of 0.5° up to 270°: the loop A, B, O4 reaches its limit position inside the
    // step from 139° to 139.5°; the program proves no step past it, the solver locates it.
    let text = std::fs::read_to_string("tests/data/four_bar_unassemblable.toml")
        .unwrap()
        .replace("to = 120\nstep = 5\n", "to = 270\nstep = 0.5\n");
    let file = temp_file("four_bar_blocked.toml");
    std::fs::write(&file, text).unwrap();
    let run = |how: &str| mechdiff(&["run", file.to_str().unwrap(), "--evaluator", how]);
    let (solver, program, jit) = (run("solver"), run("program"), run("jit"));
    std::fs::remove_file(&file).unwrap();
    assert!(!solver.status.success() && !program.status.success() && !jit.status.success());
    for other in [&program, &jit] {
        assert_eq!(stderr(&solver), stderr(other));
        assert_eq!(stdout(&solver), stdout(other));
    }
    let message = stderr(&program);
    assert!(
        message.contains("cannot assemble between drive positions 139 deg and 139.5 deg")
            && message.contains("the loop of joints A, B, O4 first fails at 139.1715"),
        "{message}"
    );
}

#[test]
fn the_plan_line_names_each_loops_path() {
    let run = |how: &str| {
        let output = mechdiff(&["run", "scenes/whitworth.toml", "--evaluator", how]);
        assert!(output.status.success(), "{}", stderr(&output));
        stdout(&output)
    };
    // `program` interprets this short sweep; `jit` compiles it: the plan line says which,
    // and the rest (title, table) is the same, bit for bit.
    let program = run("program");
    let jit = run("jit");
    for (output, how) in [(&program, "interpreted"), (&jit, "compiled to native code")] {
        let line = format!(
            "by the run-time evaluator of the traced closed forms ({how}; exact; a step it \
             cannot prove is taken by the geometry solver): loops [crank_bearing, drive \
             `crank_bearing`] program, [rocker_bearing, crank_pin] program, [ram_pin, \
             ram_guide] program;"
        );
        assert!(output.contains(&line), "{output}");
    }
    let without_plan = |s: &str| -> Vec<String> {
        (s.lines())
            .filter(|l| !l.starts_with("plan:"))
            .map(str::to_owned)
            .collect()
    };
    assert_eq!(without_plan(&program), without_plan(&jit));
    // `auto` is the solver while the program is not measured faster.
    for how in ["solver", "auto"] {
        let solver = run(how);
        assert!(
            solver.contains(
                "by the geometry solver (exact): loops [crank_bearing, drive `crank_bearing`] \
                 closed form, [rocker_bearing, crank_pin] closed form, [ram_pin, ram_guide] \
                 closed form;"
            ),
            "{how}: {solver}"
        );
    }
}

#[test]
fn a_long_sweep_by_the_program_agrees_with_the_solver() {
    // 7 201 positions (0.05°): the program's steps are each checked; `auto` compiles the
    // program, the cost model finding its set-up repaid (`evaluator::cost`).
    let text = std::fs::read_to_string("scenes/slider_crank.toml")
        .unwrap()
        .replace("step = 5\n", "step = 0.05\n");
    let scene = scene::parse("slider_crank.toml", &text).unwrap();
    let solver = run_by(&scene, Evaluator::Solver).unwrap();
    assert!(
        solver
            .plan
            .loops
            .iter()
            .all(|l| l.path == LoopPath::ClosedForm),
        "{:?}",
        solver.plan.loops
    );
    let program = run_by(&scene, Evaluator::Program).unwrap();
    assert_agree("slider_crank.toml at 0.05°", &solver, &program);
    // 7 201 positions: `program` compiles to native code (JIT_FROM_POSITIONS); the same
    // bits as the interpreter.
    assert!(scene.positions.len() >= mechdiff::evaluator::JIT_FROM_POSITIONS);
    let interpreted = run_by(&scene, Evaluator::Interpreter).unwrap();
    assert_same_bits("slider_crank.toml at 0.05°", &interpreted, &program);
    // `auto` runs the same compiled program: the same plan and bits.
    let auto = scene::run(&scene).unwrap();
    assert_eq!(auto.plan, program.plan);
    assert_same_bits("slider_crank.toml at 0.05°, auto", &interpreted, &auto);
}

/// A triad (a class-III group) matches no closed form: its loop is solved by Newton.
fn triad() -> String {
    common::triad(
        r#"
[sweep]
from = 90
to = 91
step = 0.5
[[output]]
point = "C"
quantities = ["position"]
"#,
    )
}

#[test]
fn a_loop_without_a_closed_form_is_solved_by_newton_in_the_program() {
    // The solver runs a mixed plan wholly by Newton; the program evaluates the crank's
    // closed form and solves the triad by Newton itself (traced residual and Jacobian).
    let scene = scene::parse("triad.toml", &triad()).unwrap();
    let auto = scene::run(&scene).unwrap();
    assert!(
        auto.plan.loops.iter().all(|l| l.path == LoopPath::Newton),
        "{:?}",
        auto.plan.loops
    );
    assert!(
        auto.plan
            .describe(&scene)
            .contains("by the geometry solver (exact; Newton with implicit differentiation)")
    );
    let program = run_by(&scene, Evaluator::Program).unwrap();
    let paths: Vec<LoopPath> = program.plan.loops.iter().map(|l| l.path).collect();
    assert_eq!(paths, [LoopPath::Program, LoopPath::NewtonInProgram]);
    let line = program.plan.describe(&scene);
    for part in [
        "Newton in program",
        "[A, B, C, D, G2, G3] Newton in program",
    ] {
        assert!(line.contains(part), "`{part}` missing from: {line}");
    }
    assert_agree("triad.toml", &auto, &program);
    // `--evaluator jit` on a mixed plan: its programs (inputs: the drive and the Newton
    // loop's coordinates) are interpreted, the same values bit for bit, and a warning says so.
    let jit = run_by(&scene, Evaluator::Jit).unwrap();
    assert_eq!(jit.rows, program.rows);
    assert!(
        jit.warnings
            .iter()
            .any(|w| w.contains("--evaluator jit") && w.contains("interpreted")),
        "{:?}",
        jit.warnings
    );
    assert!(
        !program
            .warnings
            .iter()
            .any(|w| w.contains("--evaluator jit"))
    );
}

#[test]
fn mixed_plans_run_the_same_by_the_program_and_by_the_solver() {
    // The mixed scenes of tests/data (the triad; the triad driving a slider, a closed-form
    // loop after the Newton loop) over 10°–85°, with ′ and ″ (see `assert_agree`: 1e-13
    // of each column's largest magnitude; both solve the triad by Newton to rounding and lift
    // it by implicit differentiation, the generated code of the same graph is measured
    // within 3e-14 of the solver in tests/scene_codegen.rs).
    for path in [
        "tests/data/triad_codegen.toml",
        "tests/data/triad_slider.toml",
    ] {
        let scene = scene::load(path).unwrap();
        let solver = run_by(&scene, Evaluator::Solver).unwrap();
        let program = run_by(&scene, Evaluator::Program).unwrap();
        assert!(
            (program.plan.loops.iter()).any(|l| l.path == LoopPath::NewtonInProgram),
            "{path}"
        );
        assert!(assert_agree(path, &solver, &program) > 250, "{path}");
    }
    // With jerk coefficients (order 3: q‴ of the Newton loop from R₃ and the same
    // factorisation), the same bound.
    let text = std::fs::read_to_string("tests/data/triad_slider.toml").unwrap();
    let text = text.replace(
        r#""acceleration_coefficient"]"#,
        r#""acceleration_coefficient", "jerk_coefficient"]"#,
    );
    let scene = scene::parse("triad_slider.toml", &text).unwrap();
    let solver = run_by(&scene, Evaluator::Solver).unwrap();
    let program = run_by(&scene, Evaluator::Program).unwrap();
    assert!(solver.columns.iter().any(|c| c.name == "theta'''"));
    assert!(assert_agree("triad_slider.toml (jerk)", &solver, &program) > 350);
}

#[test]
fn a_mixed_plan_past_its_limit_position_fails_as_the_solver_does() {
    // The triad's limit position (91.17°) inside the sweep: the program cannot prove the
    // step there, the solver takes it and reports the toggle, the same error either way.
    let text = common::triad(
        r#"
[sweep]
from = 80
to = 100
step = 1
[[output]]
point = "C"
quantities = ["position", "velocity_coefficient"]
"#,
    );
    let scene = scene::parse("triad.toml", &text).unwrap();
    let solver = run_by(&scene, Evaluator::Solver).unwrap_err();
    let program = run_by(&scene, Evaluator::Program).unwrap_err();
    assert!(
        matches!(solver, Error::Singular { .. } | Error::Unassemblable { .. }),
        "{solver}"
    );
    // The same error at the same position; the condition number is printed from the pose
    // each reached the toggle by (the program hands the solver its last position, so their
    // routes there differ), and agrees only to a few digits that close to a toggle.
    let text = |e: &Error| {
        let t = e.to_string();
        t[..t.find("(condition number").unwrap_or(t.len())].to_owned()
    };
    assert_eq!(text(&solver), text(&program));
}

#[test]
fn a_cam_scene_refuses_the_option() {
    let cams = Path::new("scenes/cams");
    let cam = std::fs::read_dir(cams)
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|e| e == "toml"))
        .unwrap();
    let output = mechdiff(&["run", cam.to_str().unwrap(), "--evaluator", "program"]);
    assert!(!output.status.success());
    assert!(
        stderr(&output).contains("--evaluator"),
        "{}",
        stderr(&output)
    );
}

/// With the run-time evaluator giving the kinematic rows, `[[dynamics]]` still reads the
/// sweep's tracker, which follows the evaluator position by position: the dynamic columns
/// are the solver run's bit for bit (the same tracker walk), each position is moved to once
/// and evaluated once by the program, and the counts say so (exact integers).
#[test]
fn dynamics_under_the_run_time_evaluator_read_the_tracker_that_follows_it() {
    let scene = scene::load("scenes/whitworth_forces.toml").unwrap();
    let n = scene.positions.len();
    let solver = scene::run(&scene).unwrap();
    let program = run_by(&scene, Evaluator::Interpreter).unwrap();
    assert!(program.plan.backend.is_some());
    let s = program.stats.sweep;
    assert_eq!((s.rows, s.program_steps, s.solves), (n, n, n));
    let first = solver
        .columns
        .iter()
        .position(|c| c.name == "Fx_crank")
        .unwrap();
    for (a, b) in solver.rows.iter().zip(&program.rows) {
        let bits = |r: &[f64]| r[first..].iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(a), bits(b), "φ = {}", a[0]);
    }
}

/// `scene` with its `[sweep]` of steps spread over the same range in `count` positions.
fn with_count(scene: &Scene, count: usize) -> Scene {
    let mut scene = scene.clone();
    if let scene::Positions::Steps {
        step, count: old, ..
    } = &mut scene.positions
    {
        *step *= (*old - 1) as f64 / (count - 1) as f64;
        *old = count;
    }
    scene
}

/// `auto`, the default evaluator, runs a sweep by the solver or by the run-time evaluator
/// compiled to native code, whichever the cost model says costs it less
/// (`evaluator::cost`): on every linkage scene of `scenes/` swept by steps, a short sweep
/// (24 positions, below every scene's break-even) stays on the solver, and a long one (twice
/// the scene's break-even) is compiled wherever every loop has a closed form and no
/// `[[dynamics]]`, `[balancing]` or cam drive reads the solver's pose anyway; either way its
/// rows agree with the solver's to 1e-13 of each column's scale (`assert_agree`) and it
/// warns as the solver does.
#[test]
fn auto_compiles_the_program_where_the_cost_model_says_it_pays() {
    let mut compiled = 0;
    for path in linkage_scenes() {
        let scene = scene::load(&path).unwrap();
        if !matches!(scene.positions, scene::Positions::Steps { .. }) || scene.sweep_of.is_some() {
            continue;
        }
        let solver = run_by(&scene, Evaluator::Solver).unwrap();
        let closed = (solver.plan.loops.iter()).all(|l| l.path == LoopPath::ClosedForm);
        let plain = closed
            && scene.drive.cam.is_none()
            && scene.dynamics.is_none()
            && scene.balancing.is_none();
        let values = (scene.outputs.iter())
            .map(|o| match o.kind {
                scene::model::OutputKind::Point(_) => 2,
                _ => 1,
            })
            .sum();
        let costs = Costs::estimate(solver.plan.loops.len(), values);
        let even = costs.break_even();
        assert!(even > 24 && even < 20_000, "{path}: break-even {even}");
        for count in [24, 2 * even] {
            let scene = with_count(&scene, count);
            let auto = scene::run(&scene).unwrap();
            let want = (plain && costs.program_pays(count)).then_some(Backend::Jit);
            assert_eq!(auto.plan.backend, want, "{path} at {count} positions");
            assert_eq!(want.is_some(), plain && count > 24, "{path} at {count}");
            let solver = run_by(&scene, Evaluator::Solver).unwrap();
            assert_agree(&path, &solver, &auto);
            assert_eq!(solver.warnings, auto.warnings, "{path}");
            compiled += usize::from(want.is_some());
        }
    }
    assert!(compiled >= 5, "only {compiled} long sweeps compiled");
}
