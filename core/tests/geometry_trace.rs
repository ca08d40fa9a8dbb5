//! Tracing a mechanism's closed forms into the symbolic engine (`trace`).

use mechdiff_core::Error;
use mechdiff_core::geometry::{Drive, Mechanism, Solver};
use mechdiff_core::trace;

fn crank() -> Mechanism {
    Mechanism::builder()
        .point("O", [0.0, 0.0])
        .point("A", [2.0, 0.0])
        .ground(["O"])
        .link("crank", ["O", "A"])
        .revolute("O", "ground", "crank", "O")
        .drive(Drive::angle("O"))
        .build()
        .unwrap()
}

#[test]
fn a_loop_on_newton_is_traced_as_a_newton_block() {
    // The crank solved by Newton (closed forms off): its coordinates (x, y, θ) are symbols,
    // and the chain rule through their derivative symbols gives the tip's jet. Bound to the
    // exact pose (x = y = 0, θ = φ; θ′ = 1, the rest 0), the residual vanishes, Φ_q q′ = −R₁
    // and Φ_q q″ = −R₂ hold, and x = 2 cos φ with its derivatives, to 1e-15 absolute
    // (values of size 2, a few roundings).
    let m = crank();
    let tip = m.point_output("crank", "A").unwrap();
    let t = Solver::default().with_closed_form(false).track(&m).unwrap();
    let mut traced = trace::trace(&t, |pose| vec![pose.point(&tip)[0]]).unwrap();
    let jets = traced.jets(2).unwrap();
    assert!(traced.guards.is_empty());
    let block = &traced.newton[0];
    assert_eq!(block.joints, t.loops()[0].0);
    let mut columns = block.columns.clone();
    columns.sort();
    assert_eq!(columns, [0, 1, 2]);
    for phi in [-2.0, 0.3, 1.7] {
        let q = [[0.0, 0.0, phi], [0.0, 0.0, 1.0], [0.0; 3]];
        let names: Vec<String> = (0..3)
            .flat_map(|k| (0..3).map(move |c| trace::coordinate_symbol(c, k)))
            .collect();
        let mut bindings: Vec<(&str, f64)> = (names.iter().map(String::as_str))
            .zip(q.iter().flatten().copied())
            .collect();
        bindings.push((trace::DRIVE, phi));
        let eval = |ids: &[_]| traced.graph.evaluate_f64(ids, &bindings).unwrap();
        assert!(eval(&block.residual).iter().all(|r| r.abs() <= 1e-15));
        let jacobian = eval(&block.jacobian);
        for (k, derivative) in q.iter().enumerate().skip(1) {
            let rhs = eval(&block.derivatives[k - 1]);
            for (row, r) in jacobian.chunks(3).zip(&rhs) {
                let lhs: f64 = (row.iter().zip(&block.columns))
                    .map(|(a, &c)| a * derivative[c])
                    .sum();
                assert!((lhs + r).abs() <= 1e-15, "φ = {phi}, order {k}");
            }
        }
        let x = eval(&jets[0]);
        let expected = [2.0 * phi.cos(), -2.0 * phi.sin(), -2.0 * phi.cos()];
        for k in 0..3 {
            assert!((x[k] - expected[k]).abs() <= 1e-15, "φ = {phi}, order {k}");
        }
    }
    // The run-time evaluator takes closed forms only: refused, naming the loop.
    match trace::ProgramTracker::new(&t, &mut traced, &jets[0], trace::Backend::Interpreter) {
        Err(Error::NoClosedForm { joints, .. }) => assert_eq!(joints, t.loops()[0].0),
        other => panic!("expected NoClosedForm, got {other:?}"),
    }
}

#[test]
fn traced_crank_tip_and_its_derivatives_are_exact() {
    // x = 2 cos φ: the traced graph's value and derivatives against the formula, 1e-15
    // absolute (values of size 2, a few roundings of sin/cos).
    let m = crank();
    let tip = m.point_output("crank", "A").unwrap();
    let t = Solver::default().track(&m).unwrap();
    let mut traced = trace::trace(&t, |pose| vec![pose.point(&tip)[0]]).unwrap();
    let jets = traced.jets(2).unwrap();
    let program = trace::Program::compile(&traced.graph, &jets[0], trace::DRIVE).unwrap();
    let (mut registers, mut out) = (program.registers(), [0.0; 3]);
    for phi in [-2.0, 0.3, 1.7, 3.1] {
        program.evaluate(phi, &mut registers, &mut out);
        let expected = [
            2.0 * f64::cos(phi),
            -2.0 * f64::sin(phi),
            -2.0 * f64::cos(phi),
        ];
        for k in 0..3 {
            assert!(
                (out[k] - expected[k]).abs() <= 1e-15,
                "φ = {phi}, order {k}"
            );
        }
    }
}
