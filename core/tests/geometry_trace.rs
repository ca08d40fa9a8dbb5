//! Tracing a mechanism's closed forms into the symbolic engine (`geometry::trace`).

use mechdiff_core::Error;
use mechdiff_core::geometry::{Drive, Mechanism, Solver, trace};

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
fn a_loop_on_newton_is_refused_with_its_joints() {
    let m = crank();
    let t = Solver::default().with_closed_form(false).track(&m).unwrap();
    let joints = t.loops()[0].0.clone();
    match trace::trace(&t, |_| Vec::new()) {
        Err(Error::NoClosedForm { joints: named, .. }) => assert_eq!(named, joints),
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
