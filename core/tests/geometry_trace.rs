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

/// A crank-rocker four-bar (crank 1, coupler 3.5, rocker 3, ground 4: Grashof, the crank
/// turns fully), sketched with the crank pointing away from the rocker's pivot, where the
/// dyad's discriminant is larger than over about half of the turn.
fn four_bar() -> Mechanism {
    let x: f64 = (3.25 + 15.0) / 10.0;
    let b = [x, (9.0 - (x - 4.0) * (x - 4.0)).sqrt()];
    Mechanism::builder()
        .point("A0", [0.0, 0.0])
        .point("B0", [4.0, 0.0])
        .point("A", [-1.0, 0.0])
        .point("B", b)
        .ground(["A0", "B0"])
        .link("crank", ["A0", "A"])
        .link("coupler", ["A", "B"])
        .link("rocker", ["B0", "B"])
        .revolute("A0", "ground", "crank", "A0")
        .revolute("A", "crank", "coupler", "A")
        .revolute("B", "coupler", "rocker", "B")
        .revolute("B0", "rocker", "ground", "B0")
        .drive(Drive::angle("A0"))
        .build()
        .unwrap()
}

/// `amplification_over(floor)` (which passes over loops whose margin shows them below the
/// worst so far) gives `amplification()`'s result, value and loop, bit for bit, wherever
/// that is above `floor`, and at most `floor` elsewhere: at 360 positions of a four-bar
/// whose margin falls below the sketch's (amplification above 1), for floors just below,
/// at and above the pose's own amplification, and none (NaN).
#[test]
fn the_amplification_over_a_floor_is_the_amplification_where_it_exceeds_it() {
    let m = four_bar();
    let tip = m.point_output("rocker", "B").unwrap();
    let t = Solver::default().track(&m).unwrap();
    let mut traced = trace::trace(&t, |pose| pose.point(&tip).to_vec()).unwrap();
    let x = traced.outputs[0];
    let mut walk =
        trace::ProgramTracker::new(&t, &mut traced, &[x], trace::Backend::Interpreter).unwrap();
    let (mut above_one, mut exact) = (0, 0);
    let start = walk.phi();
    for i in 1..=360 {
        let phi = start + f64::from(i).to_radians();
        assert!(walk.move_to(phi).is_some(), "φ = {phi}");
        let (k, l) = walk.amplification();
        above_one += usize::from(k > 1.0);
        for floor in [
            f64::NAN,
            0.5,
            1.0,
            k * (1.0 - 1e-12),
            k,
            k * (1.0 + 1e-12),
            2.0 * k,
        ] {
            let (over, loop_over) = walk.amplification_over(floor);
            if k > floor || floor.is_nan() || floor < 1.0 {
                assert_eq!((over.to_bits(), loop_over), (k.to_bits(), l), "φ = {phi}");
                exact += 1;
            } else {
                assert!(over <= floor, "φ = {phi}: {over} over the floor {floor}");
            }
        }
    }
    assert!(
        above_one > 30,
        "the margin fell below the sketch's at {above_one} positions"
    );
    assert!(exact > 360 * 3, "{exact}");
}
