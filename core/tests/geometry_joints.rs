//! Every joint kind against a closed form, and the branch kept over full revolutions.

use crate::common;

use common::{
    four_bar, four_bar_pin, four_bar_rocker_pin, gear_pair, revolution, scaled_error, slider_crank,
};
use mechdiff_core::geometry::{Drive, Equations, Mechanism, Solver};
use nalgebra::DMatrix;
use num_dual::{Dual3_64, Dual64, DualNum};
use proptest::prelude::*;

#[test]
fn slider_crank_matches_its_closed_form_to_third_order() {
    let (r, l) = (0.1, 0.35);
    let m = slider_crank(r, l, 0.0, false).unwrap();
    let sweep = Solver::default()
        .sweep::<3>(&m, &revolution(2.0, &[]))
        .unwrap();
    let mut cols = vec![Vec::new(); 4];
    for k in &sweep {
        let s = k.displacement("guide").unwrap();
        // x = r cos φ + √(l² − r² sin² φ) with exact dual derivatives.
        let phi = Dual3_64::new(k.phi, 1.0, 0.0, 0.0);
        let x = phi.cos() * r + (-(phi.sin() * r).powi(2) + l * l).sqrt();
        for (i, (g, e)) in [
            (s.value, x.re),
            (s.d1(), x.v1),
            (s.d2(), x.v2),
            (s.d3(), x.v3),
        ]
        .into_iter()
        .enumerate()
        {
            cols[i].push((g, e));
        }
    }
    // 1e-13 of each quantity's largest magnitude: both sides exact up to rounding.
    for (i, col) in cols.iter().enumerate() {
        assert!(
            scaled_error(col) <= 1e-13,
            "order {i}: {:e}",
            scaled_error(col)
        );
    }
}

#[test]
fn grashof_crank_rocker_stays_on_its_branch_over_a_full_revolution() {
    // a + d ≤ b + c with the crank shortest: a full-rotating crank (Grashof).
    let (a, b, c, d) = (0.2, 0.6, 0.5, 0.7);
    for up in [true, false] {
        let m = four_bar(a, b, c, d, 0.0, up).unwrap();
        let mut t = Solver::default().track(&m).unwrap();
        let start = t.loops();
        let mut cols = vec![Vec::new(); 6];
        for phi in revolution(1.0, &[]).into_iter().chain(
            revolution(1.0, &[])
                .into_iter()
                .map(|p| p + std::f64::consts::TAU),
        ) {
            t.move_to(phi).unwrap();
            let k = t.kinematics::<2>().unwrap();
            let [x, y] = k.point("rocker", "B").unwrap();
            let [ex, ey] = four_bar_pin(a, b, c, d, phi, up);
            for (i, (g, e)) in [
                (x.value, ex.re),
                (x.d1(), ex.v1),
                (x.d2(), ex.v2),
                (y.value, ey.re),
                (y.d1(), ey.v1),
                (y.d2(), ey.v2),
            ]
            .into_iter()
            .enumerate()
            {
                cols[i].push((g, e));
            }
        }
        // Two revolutions on the sketch's branch: certificates unchanged, and the pin
        // follows the closed form of that branch (1e-12 of each quantity's magnitude).
        assert_eq!(t.loops(), start);
        for (i, col) in cols.iter().enumerate() {
            assert!(
                scaled_error(col) <= 1e-12,
                "up = {up}, column {i}: {:e}",
                scaled_error(col)
            );
        }
    }
}

#[test]
fn shaper_slot_on_a_translating_ram_matches_its_closed_form() {
    // shaper_003.md: crank l1 = 0.1 m about A = (0, 0); lever pivot C = (0, −0.315), length
    // 0.48 m; crank pin B slides in the lever's slot; the lever's end D slides in a vertical
    // slot of the ram, which translates along y = l5 = 0.18 m. s5 = x_D = l3 cos φ3 with
    // φ3 the direction of C → B = (l1 cos φ1, l1 sin φ1 + l0).
    let (l1, l0, l3, l5) = (0.1, 0.315, 0.48, 0.18);
    let phi3 = (l0 + l1 * 0.0f64.sin()).atan2(l1);
    let dp = [l3 * phi3.cos(), -l0 + l3 * phi3.sin()];
    let m = Mechanism::builder()
        .point("A", [0.0, 0.0])
        .point("B", [l1, 0.0])
        .point("C", [0.0, -l0])
        .point("D", dp)
        .point("R", [dp[0], l5])
        .point("R2", [dp[0], l5 - 0.1])
        .point("G", [0.0, l5])
        .point("G2", [1.0, l5])
        .ground(["A", "C", "G", "G2"])
        .link("crank", ["A", "B"])
        .link("lever", ["C", "D"])
        .link("ram", ["R", "R2"])
        .revolute("A", "ground", "crank", "A")
        .revolute("C", "ground", "lever", "C")
        .pin_in_slot("block 2", "lever", ["C", "D"], "crank", "B")
        .pin_in_slot("block 4", "ram", ["R", "R2"], "lever", "D")
        .prismatic("ram guide", "ground", ["G", "G2"], "ram", "R")
        .drive(Drive::angle("A"))
        .build()
        .unwrap();
    let sweep = Solver::default()
        .sweep::<2>(&m, &revolution(5.0, &[]))
        .unwrap();
    let mut cols = vec![Vec::new(); 3];
    for k in &sweep {
        let s5 = k.displacement("ram guide").unwrap();
        let phi = Dual3_64::new(k.phi, 1.0, 0.0, 0.0);
        // cos φ3 = l1 cos φ1 / |CB| (no atan2: num-dual 0.15's atan2 differentiates
        // atan(y/x) and loses its derivatives where x = l1 cos φ1 passes through 0).
        let (bx, by) = (phi.cos() * l1, phi.sin() * l1 + l0);
        let x = bx / (bx * bx + by * by).sqrt() * l3;
        for (i, (g, e)) in [(s5.value, x.re), (s5.d1(), x.v1), (s5.d2(), x.v2)]
            .into_iter()
            .enumerate()
        {
            cols[i].push((g, e));
        }
    }
    // 1e-12 of each quantity's magnitude (exact both sides; the ram's slot is vertical).
    for (i, col) in cols.iter().enumerate() {
        assert!(
            scaled_error(col) <= 1e-12,
            "order {i}: {:e}",
            scaled_error(col)
        );
    }
}

#[test]
fn gear_pair_and_rigid_attachment_follow_their_ratios() {
    // Gear wheel 1 driven about O1; wheel 2 about O2 meshes externally (ratio −2); a plate
    // welded to wheel 2 carries point P at 0.3 m from O2.
    let m = gear_pair(false, true);
    let mut t = Solver::default().track(&m).unwrap();
    t.move_to(0.7).unwrap();
    let k = t.kinematics::<3>().unwrap();
    let w2 = k.rotation("wheel 2").unwrap();
    let plate = k.rotation("plate").unwrap();
    // θ2 = −2φ exactly; the weld copies it (1e-15: rounding of linear relations).
    assert!((w2.value + 1.4).abs() < 1e-15 && (w2.d1() + 2.0).abs() < 1e-15);
    assert!(w2.d2().abs() < 1e-15 && w2.d3().abs() < 1e-15);
    assert!((plate.value - w2.value).abs() < 1e-15);
    let [x, y] = k.point("plate", "P").unwrap();
    // P = O2 + 0.3 (−sin θ2, cos θ2) with θ2 = −2φ: x′ = 0.6 cos θ2.
    let th = -1.4f64;
    assert!((x.value - (0.3 - 0.3 * th.sin())).abs() < 1e-15);
    assert!((y.value - 0.3 * th.cos()).abs() < 1e-15);
    assert!((x.d1() - 0.6 * th.cos()).abs() < 1e-14);
    // y = 0.3 cos 2φ, so y‴ = 2.4 sin 2φ = −2.4 sin θ2.
    assert!((y.d3() + 2.4 * th.sin()).abs() < 1e-13);
}

/// A model using every joint kind, with moving guides, for the Jacobian check.
fn every_joint() -> Mechanism {
    Mechanism::builder()
        .point("O", [0.0, 0.0])
        .point("X", [1.0, 0.0])
        .point("A", [0.2, 0.1])
        .point("B", [0.6, 0.3])
        .point("C", [0.9, -0.1])
        .point("W", [0.2, 0.5])
        .point("V", [0.5, 0.5])
        .ground(["O", "X", "W", "V"])
        .link("crank", ["O", "A"])
        .link("slotted", ["A", "B"])
        .link("slider", ["C", "B"])
        .link("wheel", ["W"])
        .link("wheel 2", ["V"])
        .link("weld", ["C"])
        .revolute("O", "ground", "crank", "O")
        .revolute("A", "crank", "slotted", "A")
        .prismatic("p", "slotted", ["A", "B"], "slider", "C")
        .pin_in_slot("rp", "slotted", ["A", "B"], "crank", "A")
        .revolute("W", "ground", "wheel", "W")
        .revolute("V", "ground", "wheel 2", "V")
        .rack_pinion("rack", "W", "p", 0.05)
        .gear("g", "W", "V", -1.5)
        .rigid("w", "slider", "weld")
        .drive(Drive::angle("O"))
        .build()
        .unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    /// The analytic Φ_q equals the dual-number derivative of the generic Φ, column by column,
    /// at arbitrary (not necessarily assembled) coordinates: 1e-13 absolute on entries O(1).
    #[test]
    fn analytic_jacobian_equals_dual_number_jacobian(q in prop::collection::vec(-2.0f64..2.0, 18)) {
        let eq = Equations::new(&every_joint());
        let mut jac = DMatrix::zeros(eq.rows(), eq.coordinates());
        eq.jacobian(&q, &mut jac);
        for c in 0..eq.coordinates() {
            let x: Vec<Dual64> = q.iter().enumerate()
                .map(|(i, &v)| Dual64::new(v, if i == c { 1.0 } else { 0.0 })).collect();
            let mut out = vec![Dual64::from(0.0); eq.rows()];
            eq.evaluate(&x, Dual64::from(0.3), &mut out);
            for r in 0..eq.rows() {
                prop_assert!((jac[(r, c)] - out[r].eps).abs() < 1e-13, "({r}, {c})");
            }
        }
    }
}

#[test]
fn four_bar_rocker_pin_helper_is_consistent() {
    // Guards the test helper itself: |B − A| = b and |B − B0| = c.
    let p = four_bar_rocker_pin([0.2, 0.0], 0.6, 0.5, 0.7, true).unwrap();
    assert!(((p[0] - 0.2).hypot(p[1]) - 0.6).abs() < 1e-15);
    assert!(((p[0] - 0.7).hypot(p[1]) - 0.5).abs() < 1e-15);
}

#[test]
fn one_long_step_lands_on_the_sketch_closure() {
    // A whole revolution asked in one step: the Taylor predictor is useless that far, so
    // Newton may converge to either closure; the certificate check (subdividing when it
    // flips) must bring the tracker back to the sketch's closure: the pose of φ = 0.
    let (a, b, c, d) = (0.2, 0.6, 0.5, 0.7);
    for up in [true, false] {
        let m = four_bar(a, b, c, d, 0.0, up).unwrap();
        let mut t = Solver::default().track(&m).unwrap();
        let start = t.kinematics::<1>().unwrap().point("rocker", "B").unwrap();
        t.move_to(std::f64::consts::TAU).unwrap();
        let end = t.kinematics::<1>().unwrap().point("rocker", "B").unwrap();
        // Same pose to rounding (1e-13 m on a 0.5 m rocker).
        for i in 0..2 {
            assert!((end[i].value - start[i].value).abs() < 1e-13, "up = {up}");
        }
    }
}

#[test]
fn a_step_that_lands_on_the_other_closure_is_rejected_and_subdivided() {
    // Four-bar a = 0.1, b = c = d = 0.3 asked to go from φ = 0 to φ = 3 rad in one step.
    // Newton from a far extrapolated predictor converged to the other closure (the
    // certificate flipped and the step was halved); steps are now capped at 1/8 rad, so
    // the move takes 24 sub-steps and every landing is checked: the pose found is the
    // sketch's closure.
    let (a, b, c, d) = (0.1, 0.3, 0.3, 0.3);
    for up in [true, false] {
        let m = four_bar(a, b, c, d, 0.0, up).unwrap();
        // (The Newton path: the closed-form dyad would place the sketch's closure at once.)
        let mut t = Solver::default().with_closed_form(false).track(&m).unwrap();
        let report = t.move_to(3.0).unwrap();
        // 3 rad in sub-steps of at most 1/8 rad.
        assert!(report.steps >= 24, "{report:?}");
        let [x, y] = t.kinematics::<1>().unwrap().point("rocker", "B").unwrap();
        let [ex, ey] = four_bar_pin(a, b, c, d, 3.0, up);
        // The sketch's closure to rounding (1e-14 m on 0.3 m links).
        assert!(
            (x.value - ex.re).abs() < 1e-14 && (y.value - ey.re).abs() < 1e-14,
            "up = {up}"
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    /// Over random slider-cranks (rod longer than crank) and random crank angles, the solved
    /// slider displacement and its first three derivatives equal the closed form
    /// x = r cos φ + √(l² − r² sin² φ) in dual numbers: 1e-12 of the stroke scale (r + l).
    #[test]
    fn random_slider_cranks_match_the_closed_form(
        r in 0.05f64..0.5,
        ratio in 1.3f64..5.0,
        phi0 in -3.0f64..3.0,
        dphi in -2.0f64..2.0,
    ) {
        let l = r * ratio;
        let m = slider_crank(r, l, phi0, false).unwrap();
        let mut t = Solver::default().track(&m).unwrap();
        let phi = phi0 + dphi;
        t.move_to(phi).unwrap();
        let s = t.kinematics::<3>().unwrap().displacement("guide").unwrap();
        let p = Dual3_64::new(phi, 1.0, 0.0, 0.0);
        let x = p.cos() * r + (-(p.sin() * r).powi(2) + l * l).sqrt();
        let scale = r + l;
        for (g, e) in [(s.value, x.re), (s.d1(), x.v1), (s.d2(), x.v2), (s.d3(), x.v3)] {
            prop_assert!((g - e).abs() <= 1e-12 * scale, "{g} vs {e}");
        }
    }
}
