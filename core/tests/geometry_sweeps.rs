//! Sweeps that never lie: steps that straddle a blocked range, limit positions, change
//! points, and verdicts that do not depend on unrelated points or on the scale.

use crate::common;

use common::{four_bar, four_bar_rocker_pin};
use mechdiff_core::Error;
use mechdiff_core::geometry::{Drive, LimitKind, Mechanism, Solver};
use std::f64::consts::PI;

/// Offset slider-crank: crank `r` about O = (0, 0), rod `l`, slider on the line y = `e`,
/// sketched at φ = 0 (B to the right of A), all lengths times `scale`; an extra ground
/// point at `far` (m) if given.
fn offset_slider_crank(r: f64, l: f64, e: f64, scale: f64, far: Option<f64>) -> Mechanism {
    let b = r + (l * l - e * e).sqrt();
    let mut builder = Mechanism::builder()
        .point("O", [0.0, 0.0])
        .point("A", [r * scale, 0.0])
        .point("B", [b * scale, e * scale])
        .point("G0", [0.0, e * scale])
        .point("G1", [scale, e * scale]);
    let mut ground = vec!["O", "G0", "G1"];
    if let Some(x) = far {
        builder = builder.point("FAR", [x, 0.0]);
        ground.push("FAR");
    }
    builder
        .ground(ground)
        .link("crank", ["O", "A"])
        .link("rod", ["A", "B"])
        .link("slider", ["B"])
        .revolute("O", "ground", "crank", "O")
        .revolute("A", "crank", "rod", "A")
        .revolute("B", "rod", "slider", "B")
        .prismatic("guide", "ground", ["G0", "G1"], "slider", "B")
        .drive(Drive::angle("O"))
        .build()
        .unwrap()
}

fn degrees(step: f64, to: f64) -> Vec<f64> {
    let n = (to / step).round() as usize;
    (0..=n).map(|i| (i as f64 * step).to_radians()).collect()
}

#[test]
fn a_20_degree_sweep_does_not_jump_the_blocked_range_of_an_offset_slider_crank() {
    // r = 1, e = 0.5, l = 1.49: the rod reaches the guide only while |sin φ − e| ≤ l, i.e.
    // r sin φ + (−e) ≥ −l: blocked where sin φ < −0.99, between π + asin 0.99 and
    // 2π − asin 0.99 (≈ 261.89°–278.11°). A 20° sweep steps from 260° to 280°.
    let m = offset_slider_crank(1.0, 1.49, 0.5, 1.0, None);
    let err = Solver::default()
        .sweep::<1>(&m, &degrees(20.0, 360.0))
        .unwrap_err();
    let Error::Blocked {
        from,
        to,
        limit,
        joints,
    } = &err
    else {
        panic!("expected Blocked, got {err:?}")
    };
    // 1e-12 relative: the positions are 13·20° and 14·20° converted the same way here.
    assert!((from - 260f64.to_radians()).abs() < 1e-12, "{from}");
    assert!((to - 280f64.to_radians()).abs() < 1e-12, "{to}");
    // The limit position against the closed form sin φ = (e − l)/r, to 1e-12 (asin of an
    // exact 0.99 and the solver's Newton on the loop's margin are both at rounding level).
    let exact = PI + 0.99f64.asin();
    assert!((limit - exact).abs() < 1e-12, "{limit} vs {exact}");
    assert_eq!(joints, &["A", "B", "guide"]);
    let text = err.to_string();
    assert!(text.starts_with("cannot assemble between"), "{text}");
    assert!(text.contains("first fails at φ = 4.5708"), "{text}");
    // At 10° the same range is reported the same way (a position inside it is asked for).
    let err = Solver::default()
        .sweep::<1>(&m, &degrees(10.0, 360.0))
        .unwrap_err();
    let Error::Blocked { limit, .. } = err else {
        panic!("{err:?}")
    };
    assert!((limit - exact).abs() < 1e-12);
}

#[test]
fn a_blocked_range_narrower_than_a_sub_step_is_not_jumped() {
    // l = 1.499: blocked where sin φ < −0.999, 267.44°–272.56° (5.1° wide). The 20° step
    // from 260° is checked in sub-steps of 1/8 rad (7.16°): 267.16° and 274.33° both
    // assemble, so only the check of the margin between them finds the range.
    let m = offset_slider_crank(1.0, 1.499, 0.5, 1.0, None);
    let err = Solver::default()
        .sweep::<1>(&m, &degrees(20.0, 360.0))
        .unwrap_err();
    let Error::Blocked { limit, .. } = err else {
        panic!("expected Blocked, got {err:?}")
    };
    // The closed form π + asin 0.999, to 1e-12 as above.
    let exact = PI + 0.999f64.asin();
    assert!((limit - exact).abs() < 1e-12, "{limit} vs {exact}");
}

#[test]
fn the_motion_range_of_an_offset_slider_crank_is_its_two_limit_positions() {
    let m = offset_slider_crank(1.0, 1.49, 0.5, 1.0, None);
    let range = Solver::default().track(&m).unwrap().motion_range().unwrap();
    let (lower, upper) = (range.lower.unwrap(), range.upper.unwrap());
    // r sin φ − e = −l on both sides of the blocked range, to 1e-12 as above.
    assert!(
        (upper.phi - (PI + 0.99f64.asin())).abs() < 1e-12,
        "{upper:?}"
    );
    assert!((lower.phi + 0.99f64.asin()).abs() < 1e-12, "{lower:?}");
    assert_eq!(
        (lower.kind, upper.kind),
        (LimitKind::Limit, LimitKind::Limit)
    );
}

#[test]
fn a_non_grashof_four_bar_given_160_and_200_degrees_reports_its_limit() {
    // Ground 0.4, crank 0.3, coupler 0.395, rocker 0.3: shortest + longest = 0.7 > 0.695,
    // non-Grashof. The crank pin is 0.7 m from B0 at φ = π, more than coupler + rocker =
    // 0.695: blocked where a² + d² − 2ad cos φ > 0.695², ≈ 166.15°–193.85°.
    let (a, b, c, d) = (0.3, 0.395, 0.3, 0.4);
    let m = four_bar(a, b, c, d, PI / 2.0, true).unwrap();
    let phis = [160f64.to_radians(), 200f64.to_radians()];
    let err = Solver::default().sweep::<1>(&m, &phis).unwrap_err();
    let Error::Blocked { to, limit, .. } = err else {
        panic!("expected Blocked, got {err:?}")
    };
    assert_eq!(to, phis[1]);
    let exact = ((a * a + d * d - (b + c) * (b + c)) / (2.0 * a * d)).acos();
    // 1e-12: acos near −0.97 (slope 4) of a value rounded to 1e-16, and Newton's rounding.
    assert!((limit - exact).abs() < 1e-12, "{limit} vs {exact}");
    // Started at 160° the step to 200° straddles the whole range.
    let m = four_bar(a, b, c, d, phis[0], true).unwrap();
    let err = Solver::default().sweep::<1>(&m, &phis).unwrap_err();
    let Error::Blocked {
        from, to, limit, ..
    } = err
    else {
        panic!("expected Blocked, got {err:?}")
    };
    assert_eq!((from, to), (phis[0], phis[1]));
    assert!((limit - exact).abs() < 1e-12, "{limit} vs {exact}");
}

/// The four-bar with the rocker pin on the closure nearest to `target` (a point of the
/// sketch the wanted assembly passes through).
fn four_bar_closure(a: f64, b: f64, c: f64, d: f64, phi0: f64, target: [f64; 2]) -> Mechanism {
    let pa = [a * phi0.cos(), a * phi0.sin()];
    let up = [true, false]
        .into_iter()
        .min_by(|&x, &y| {
            let dist = |u| {
                let p = four_bar_rocker_pin(pa, b, c, d, u).unwrap();
                (p[0] - target[0]).hypot(p[1] - target[1])
            };
            dist(x).total_cmp(&dist(y))
        })
        .unwrap();
    four_bar(a, b, c, d, phi0, up).unwrap()
}

#[test]
fn a_parallelogram_reports_its_change_point_as_a_bifurcation() {
    // Ground d = 0.5, crank a = 0.2, coupler 0.5, rocker 0.2, drawn as a parallelogram
    // (B = A + (d, 0)): at φ = 0 the four links are collinear and the parallelogram and
    // antiparallelogram branches meet (the dyad's discriminant is a²b² sin²φ: a double
    // root). A sweep across it must stop there, never print ψ′ ≈ 1e15 or jump.
    let (a, d) = (0.2, 0.5);
    let phi0: f64 = 1.0;
    let pa = [a * phi0.cos(), a * phi0.sin()];
    let m = four_bar_closure(a, d, a, d, phi0, [pa[0] + d, pa[1]]);
    let phis: Vec<f64> = (0..=8).map(|i| phi0 - 0.25 * i as f64).collect();
    let err = Solver::default().sweep::<1>(&m, &phis).unwrap_err();
    let Error::ChangePoint { phi, joints } = &err else {
        panic!("expected ChangePoint, got {err:?}")
    };
    // φ = 0 to 1e-12 (Newton on the margin's derivative, linear there, at rounding level).
    assert!(phi.abs() < 1e-12, "{phi}");
    assert_eq!(joints, &["A", "B", "B0"]);
    assert!(
        err.to_string().contains("change point (bifurcation)"),
        "{err}"
    );
    // Up to it, ψ′ stays that of the parallelogram (the rocker turns with the crank: 1).
    let mut t = Solver::default().track(&m).unwrap();
    for &p in phis.iter().take_while(|&&p| p > 0.0) {
        t.move_to(p).unwrap();
        let k = t.kinematics::<1>().unwrap();
        // 1e-12: ψ′ = 1 exactly for a parallelogram; closed form at rounding.
        assert!((k.rotation("rocker").unwrap().d1() - 1.0).abs() < 1e-12);
    }
    let range = t.motion_range().unwrap();
    let upper = range.upper.unwrap();
    // The other change point, at φ = π (the four links collinear again); the walk
    // starts at 0.25.
    assert_eq!(upper.kind, LimitKind::ChangePoint);
    assert!((upper.phi - PI).abs() < 1e-12, "{upper:?}");
}

#[test]
fn a_kite_reports_its_change_point_as_a_bifurcation() {
    // Ground = crank = 0.4, coupler = rocker = 0.3: at φ = 0 the crank pin A lands on the
    // rocker pivot B0, where the coupler–rocker dyad's two pivots coincide and its
    // branches meet (discriminant d²(b² − d²/4), d² = 2a²(1 − cos φ): a double root).
    let (a, b) = (0.4, 0.3);
    let m = four_bar(a, b, b, a, 1.2, true).unwrap();
    let phis: Vec<f64> = (0..=6).map(|i| 1.2 - 0.4 * i as f64).collect();
    let err = Solver::default().sweep::<1>(&m, &phis).unwrap_err();
    let Error::ChangePoint { phi, .. } = err else {
        panic!("expected ChangePoint, got {err:?}")
    };
    // 1e-12 as for the parallelogram.
    assert!(phi.abs() < 1e-12, "{phi}");
}

#[test]
fn an_unrelated_far_point_or_the_scale_changes_no_verdict_and_no_result() {
    // The blocked slider-crank and a regular one, with a ground point 3e4 m or 1e6 m away,
    // or scaled by 1e-3 and 1e3: the same limit, and the same positions to rounding.
    for (r, l, e) in [(1.0, 1.49, 0.5), (0.1, 0.35, 0.0)] {
        let reference = offset_slider_crank(r, l, e, 1.0, None);
        let phis = degrees(5.0, 360.0);
        let expect = Solver::default().sweep::<1>(&reference, &phis);
        for (scale, far) in [
            (1.0, Some(3e4)),
            (1.0, Some(1e6)),
            (1e-3, None),
            (1e3, None),
        ] {
            let m = offset_slider_crank(r, l, e, scale, far);
            let got = Solver::default().sweep::<1>(&m, &phis);
            match (&expect, &got) {
                (Ok(x), Ok(y)) => {
                    for (x, y) in x.iter().zip(y) {
                        let (sx, sy) = (
                            x.displacement("guide").unwrap(),
                            y.displacement("guide").unwrap(),
                        );
                        // 1e-13 relative: the same formulas on scaled inputs.
                        assert!(
                            (sy.value / scale - sx.value).abs() < 1e-13 * (1.0 + sx.value.abs())
                        );
                        assert!((sy.d1() / scale - sx.d1()).abs() < 1e-12 * (1.0 + sx.d1().abs()));
                    }
                }
                (Err(Error::Blocked { limit: a, .. }), Err(Error::Blocked { limit: b, .. })) => {
                    assert!((a - b).abs() < 1e-12, "{a} vs {b}")
                }
                other => panic!("scale {scale}, far {far:?}: {other:?}"),
            }
        }
    }
}

#[test]
fn a_slotted_lever_whose_pin_passes_near_its_hinge_is_computed_and_flagged() {
    // Crank l1 about O = (0, l0), its pin A in the slot of a lever hinged at B0 = (0, 0);
    // l1/l0 = 0.999999: at φ = 0 the pin passes (l0 − l1) = 1e-6 l0 from the hinge, and
    // the lever turns with ψ′ = −l1/(l0 − l1) ≈ −1e6: regular, ill-conditioned.
    let (l0, l1) = (1.0, 0.999999);
    let m = Mechanism::builder()
        .point("O", [0.0, l0])
        .point("B0", [0.0, 0.0])
        .point("A", [0.0, l0 + l1])
        .point("S", [0.0, 1.0])
        .ground(["O", "B0"])
        .link("crank", ["O", "A"])
        .link("lever", ["B0", "S"])
        .revolute("O", "ground", "crank", "O")
        .revolute("B0", "ground", "lever", "B0")
        .pin_in_slot("slot", "lever", ["B0", "S"], "crank", "A")
        .drive(Drive::angle("O").at_sketch(PI))
        .build()
        .unwrap();
    let mut t = Solver::default().track(&m).unwrap();
    t.move_to(0.0).unwrap();
    let k = t.kinematics::<1>().unwrap();
    let psi1 = k.rotation("lever").unwrap().d1();
    // ψ′ = l1 (l1 − l0 cos φ)/ρ², ρ² = l0² + l1² − 2 l0 l1 cos φ, at φ = 0: −l1/(l0 − l1).
    // Expected relative error ~ amplification × ε ≈ 4e-10; 1e-8 allows 25×.
    let exact = -l1 / (l0 - l1);
    assert!((psi1 / exact - 1.0).abs() < 1e-8, "{psi1} vs {exact}");
    let (amplification, joints) = t.amplification();
    // The lever's length |A − B0| was l0 + l1 in the sketch and is l0 − l1 now.
    let ratio = (l0 + l1) / (l0 - l1);
    assert!(
        (amplification / ratio - 1.0).abs() < 1e-6,
        "{amplification:e}"
    );
    assert_eq!(joints, ["B0", "slot"]);
    // Swept through it in 10° steps: no error, no change point.
    let phis = degrees(10.0, 360.0);
    assert!(Solver::default().sweep::<1>(&m, &phis).is_ok());
}

#[test]
fn the_newton_path_does_not_jump_a_blocked_range_wider_than_its_step_cap() {
    // Newton forced: steps are capped at 1/8 rad (7.16°) as on the closed-form path, so a
    // sub-step of the 20° step from 260° lands inside the 16° blocked range and the sweep
    // ends in an error at it (Newton's loops are not located to full precision).
    let m = offset_slider_crank(1.0, 1.49, 0.5, 1.0, None);
    let err = Solver::default()
        .with_closed_form(false)
        .sweep::<1>(&m, &degrees(20.0, 360.0))
        .unwrap_err();
    match err {
        Error::Unassemblable { last_assembled, .. } => {
            // The halvings stop within 2⁻²⁴ of the 7.16° sub-step before the limit.
            let limit = PI + 0.99f64.asin();
            assert!(last_assembled <= limit && limit - last_assembled < 1e-6);
        }
        Error::Singular { phi, .. } => assert!((phi - (PI + 0.99f64.asin())).abs() < 1e-6),
        other => panic!("expected an error at the limit, got {other:?}"),
    }
}

#[test]
fn a_move_of_1e12_radians_is_refused_not_run_for_hours() {
    // 1e12 rad in checked steps of 1/8 rad would take 8e12 steps: refused after 10⁵.
    let m = offset_slider_crank(0.1, 0.35, 0.0, 1.0, None);
    for closed_form in [true, false] {
        let mut t = Solver::default()
            .with_closed_form(closed_form)
            .track(&m)
            .unwrap();
        match t.move_to(1e12).unwrap_err() {
            Error::MoveTooLong { to, steps, .. } => assert_eq!((to, steps), (1e12, 100_000)),
            other => panic!("expected MoveTooLong, got {other:?}"),
        }
    }
}
