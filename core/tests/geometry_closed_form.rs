//! The closed-form loop solutions (`Solver::with_closed_form`) against the Newton path and
//! against hand-written closed forms, and their errors.

use crate::common;

use common::{
    four_bar, four_bar_pin, gear_pair, rack_slotted_link, revolution, scaled_error, slider_crank,
    whitworth,
};
use mechdiff_core::geometry::{Drive, Mechanism, Solver};
use mechdiff_core::{Error, Jet};
use std::f64::consts::{FRAC_PI_2, PI};

/// Sweeps `m` over `phis` with the closed forms and with Newton forced, and returns the
/// largest difference over every coordinate and derivative order 0..=3, scaled per order by
/// the largest magnitude of that order over all coordinates and the sweep (coordinates that
/// stay zero, like a slider's angle, would make a per-coordinate scale meaningless).
fn closed_form_vs_newton(m: &Mechanism, phis: &[f64]) -> f64 {
    let fast = Solver::default().sweep::<3>(m, phis).unwrap();
    let newton = Solver::default()
        .with_closed_form(false)
        .sweep::<3>(m, phis)
        .unwrap();
    let pick = |j: &Jet<3>, order: usize| {
        if order == 0 {
            j.value
        } else {
            j.derivatives[order - 1]
        }
    };
    let mut worst: f64 = 0.0;
    for order in 0..4 {
        let pairs: Vec<(f64, f64)> = fast
            .iter()
            .zip(&newton)
            .flat_map(|(a, b)| a.coordinates.iter().zip(&b.coordinates))
            .map(|(a, b)| (pick(a, order), pick(b, order)))
            .collect();
        worst = worst.max(scaled_error(&pairs));
    }
    worst
}

/// Scotch yoke: crank r from O = (0, 0); the yoke translates along the x axis and carries a
/// vertical slot through the crank pin A. Sketched at crank angle `phi0`. With `drive_yoke`
/// the yoke's displacement (x of the slot) drives it, else the crank angle.
fn scotch_yoke(r: f64, phi0: f64, drive_yoke: bool) -> Result<Mechanism, Error> {
    let a = [r * phi0.cos(), r * phi0.sin()];
    let b = Mechanism::builder()
        .point("O", [0.0, 0.0])
        .point("X", [1.0, 0.0])
        .point("A", a)
        .point("Y0", [a[0], 0.0])
        .point("Y1", [a[0], 1.0])
        .ground(["O", "X"])
        .link("crank", ["O", "A"])
        .link("yoke", ["Y0", "Y1"])
        .revolute("O", "ground", "crank", "O")
        .prismatic("guide", "ground", ["O", "X"], "yoke", "Y0")
        .pin_in_slot("slot", "yoke", ["Y0", "Y1"], "crank", "A");
    if drive_yoke {
        b.drive(Drive::displacement("guide")).build()
    } else {
        b.drive(Drive::angle("O").at_sketch(phi0)).build()
    }
}

/// A crank from O = (0, 0) carrying a slot along itself; a lever hinged at B0 = (0.3, 0)
/// has its pin P (0.5 m from B0) in the slot. Sketched at φ = π/2 (P = (0, 0.4)). B0 is
/// inside the pin's circle, so the lever turns fully as the crank does.
fn crank_with_slot_and_lever() -> Result<Mechanism, Error> {
    Mechanism::builder()
        .point("O", [0.0, 0.0])
        .point("S", [0.0, 1.0])
        .point("B0", [0.3, 0.0])
        .point("P", [0.0, 0.4])
        .ground(["O", "B0"])
        .link("crank", ["O", "S"])
        .link("lever", ["B0", "P"])
        .revolute("O", "ground", "crank", "O")
        .revolute("B0", "ground", "lever", "B0")
        .pin_in_slot("slot", "crank", ["O", "S"], "lever", "P")
        .drive(Drive::angle("O").at_sketch(FRAC_PI_2))
        .build()
}

/// A Whitworth-like quick return with the general geometry: the rocker's slot is offset by
/// 0.05 m from its pivot (c ≠ 0 in the rocker formula), the ram's guide is inclined by 0.2
/// rad, and the ram's pin C is offset from its guide line.
fn offset_quick_return() -> Result<Mechanism, Error> {
    let (l0, l1, e) = (0.4, 0.15, 0.05);
    // Rocker pivot B0 = (0, 0), slot parallel to y at x = e; crank pivot O = (e, l0); the
    // crank pin A = (e, l0 − l1) is on the slot.
    let u = [0.2f64.cos(), 0.2f64.sin()];
    let c = [e, 0.7];
    // Guide line through H0 = C − 0.03 n (n ⟂ u), i.e. C is 0.03 m off the line.
    let h0 = [c[0] + 0.03 * u[1], c[1] - 0.03 * u[0]];
    Mechanism::builder()
        .point("O", [e, l0])
        .point("B0", [0.0, 0.0])
        .point("A", [e, l0 - l1])
        .point("S0", [e, 0.0])
        .point("S", [e, 1.0])
        .point("C", c)
        .point("H0", h0)
        .point("H1", [h0[0] + u[0], h0[1] + u[1]])
        .ground(["O", "B0", "H0", "H1"])
        .link("crank", ["O", "A"])
        .link("rocker", ["B0", "S0", "S"])
        .link("ram", ["C", "H0"])
        .revolute("O", "ground", "crank", "O")
        .revolute("B0", "ground", "rocker", "B0")
        .pin_in_slot("slot A", "rocker", ["S0", "S"], "crank", "A")
        .prismatic("ram guide", "ground", ["H0", "H1"], "ram", "C")
        .pin_in_slot("slot C", "rocker", ["S0", "S"], "ram", "C")
        .drive(Drive::angle("O"))
        .build()
}

#[test]
fn whitworth_is_solved_in_closed_form_and_matches_newton_over_a_revolution() {
    let m = whitworth().unwrap();
    let t = Solver::default().track(&m).unwrap();
    assert_eq!(t.closed_form_loops(), vec![true, true, true]);
    let forced = Solver::default().with_closed_form(false).track(&m).unwrap();
    assert_eq!(forced.closed_form_loops(), vec![false, false, false]);
    // Both paths are exact up to rounding: 1e-13 of each coordinate's (and derivative's)
    // largest magnitude over the revolution.
    let e = closed_form_vs_newton(&m, &revolution(0.5, &[]));
    assert!(e <= 1e-13, "scaled difference {e:e}");
}

#[test]
fn offset_slot_and_inclined_guide_match_newton() {
    let m = offset_quick_return().unwrap();
    let t = Solver::default().track(&m).unwrap();
    assert_eq!(t.closed_form_loops(), vec![true, true, true]);
    // 1e-13 scaled: both exact up to rounding (see above).
    let e = closed_form_vs_newton(&m, &revolution(0.5, &[]));
    assert!(e <= 1e-13, "scaled difference {e:e}");
}

#[test]
fn lever_pin_in_a_turning_slot_matches_newton_and_its_own_closed_form() {
    let m = crank_with_slot_and_lever().unwrap();
    let t = Solver::default().track(&m).unwrap();
    assert_eq!(t.closed_form_loops(), vec![true, true]);
    // Two full turns from the sketch: the lever's angle must stay continuous (unwrapped).
    let phis: Vec<f64> = (0..=1440)
        .map(|i| FRAC_PI_2 + i as f64 * PI / 360.0)
        .collect();
    let e = closed_form_vs_newton(&m, &phis);
    assert!(e <= 1e-13, "scaled difference {e:e}");
    let sweep = Solver::default().sweep::<1>(&m, &phis).unwrap();
    for k in &sweep {
        // P on the line through O at angle φ, 0.5 m from B0 = (0.3, 0), on the far side:
        // t = 0.3 cos φ + √(0.25 − 0.09 sin² φ). 1e-14 m: rounding on 0.5 m.
        let (s, c) = k.phi.sin_cos();
        let along = 0.3 * c + (0.25 - 0.09 * s * s).sqrt();
        let [x, y] = k.point("lever", "P").unwrap();
        assert!((x.value - along * c).abs() < 1e-14 && (y.value - along * s).abs() < 1e-14);
    }
    let last = sweep.last().unwrap().rotation("lever").unwrap().value;
    // Two turns of the crank turn the lever twice (continuous angle, not wrapped).
    assert!((last - 2.0 * std::f64::consts::TAU).abs() < 1e-12, "{last}");
}

#[test]
fn scotch_yoke_matches_newton_and_x_equals_r_cos_phi() {
    let r = 0.2;
    let m = scotch_yoke(r, 0.3, false).unwrap();
    let t = Solver::default().track(&m).unwrap();
    assert_eq!(t.closed_form_loops(), vec![true, true]);
    let phis = revolution(1.0, &[]);
    let e = closed_form_vs_newton(&m, &phis);
    assert!(e <= 1e-13, "scaled difference {e:e}");
    for k in Solver::default().sweep::<3>(&m, &phis).unwrap() {
        let x = k.displacement("guide").unwrap();
        let (s, c) = k.phi.sin_cos();
        // x = r cos φ and its derivatives, to rounding (1e-15 m on 0.2 m).
        let exact = [r * c, -r * s, -r * c, r * s];
        let got = [x.value, x.d1(), x.d2(), x.d3()];
        for (g, e) in got.iter().zip(exact) {
            assert!((g - e).abs() < 1e-15, "φ = {}: {g} vs {e}", k.phi);
        }
    }
}

#[test]
fn yoke_driven_crank_matches_newton_and_reports_dead_ends() {
    let r = 0.2;
    let m = scotch_yoke(r, 1.0, true).unwrap();
    let t = Solver::default().track(&m).unwrap();
    assert_eq!(t.closed_form_loops(), vec![true, true]);
    // The yoke from x = r cos 1 down to −0.18 m (the crank stays on the upper half; the
    // derivatives of θ = acos(x/r) grow like 1/sin³θ towards the toggle at x = −r).
    let x0 = r * 1.0f64.cos();
    let phis: Vec<f64> = (0..=200)
        .map(|i| x0 - i as f64 * (x0 + 0.18) / 200.0)
        .collect();
    for k in Solver::default().sweep::<2>(&m, &phis).unwrap() {
        // θ = acos(x/r) − 1 (rotation since the sketch), θ′ = −1/(r sin θ),
        // θ″ = −cos θ/(r² sin³ θ): to rounding, 1e-13 relative (at least 1e-13 absolute).
        let th = k.rotation("crank").unwrap();
        let exact_th = (k.phi / r).acos();
        let (s, c) = exact_th.sin_cos();
        let exact = [exact_th - 1.0, -1.0 / (r * s), -c / (r * r * s * s * s)];
        let got = [th.value, th.d1(), th.d2()];
        for (g, e) in got.iter().zip(exact) {
            assert!(
                (g - e).abs() <= 1e-13 * e.abs().max(1.0),
                "x = {}: {g} vs {e}",
                k.phi
            );
        }
    }
    // Against Newton: here the Newton path itself is off by up to 6e-14 in θ′ and 7e-13 in
    // θ″ near the sketch (measured against the acos above, where the closed form is within
    // 2e-15 and 1e-14), so the bound is that of Newton's error: 5e-12 scaled.
    let e = closed_form_vs_newton(&m, &phis);
    assert!(e <= 5e-12, "scaled difference {e:e}");

    // Past the crank's reach: the loop (crank hinge + slot) cannot assemble.
    let mut t = Solver::default().track(&m).unwrap();
    let from = t.phi();
    match t.move_to(0.25).unwrap_err() {
        Error::Blocked {
            from: start,
            to,
            limit,
            joints,
        } => {
            assert_eq!((start, to), (from, 0.25));
            // The limit position is the crank's reach x = r, located by Newton on the
            // loop's margin: to 4e-16 (two ulps of 0.2; r is exact in the model).
            assert!((limit - r).abs() <= 4e-16, "{limit}");
            // The tracker stays at the last position accepted, before the limit.
            assert!(t.phi() < r && t.phi() > from, "{}", t.phi());
            assert_eq!(joints, vec!["O".to_string(), "slot".to_string()]);
        }
        other => panic!("expected Blocked, got {other:?}"),
    }
    // The tracker is left at its last pose and still works.
    t.move_to(0.0).unwrap();
    // Exactly at the crank's reach the crank is at a toggle (dx/dθ = 0).
    match t.move_to(r).unwrap_err() {
        Error::Singular { phi, joints, .. } => {
            assert_eq!(phi, r);
            assert_eq!(joints, vec!["O".to_string(), "slot".to_string()]);
        }
        other => panic!("expected Singular, got {other:?}"),
    }
}

#[test]
fn rocker_whose_offset_slot_misses_the_pin_is_unassemblable() {
    // The rocker's slot is the line x = e, at e = 0.06 m from its pivot B0 = (0, 0); the
    // crank (pivot O = (e, l0), l1 = 0.45 > |O|) brings its pin A to within
    // l1 − |O| = 0.0455 m of B0, less than e: there the slot cannot reach the pin.
    let (l0, l1, e) = (0.4, 0.45, 0.06);
    let m = Mechanism::builder()
        .point("O", [e, l0])
        .point("B0", [0.0, 0.0])
        .point("A", [e, l0 - l1])
        .point("S0", [e, 0.0])
        .point("S", [e, 1.0])
        .ground(["O", "B0"])
        .link("crank", ["O", "A"])
        .link("rocker", ["B0", "S0", "S"])
        .revolute("O", "ground", "crank", "O")
        .revolute("B0", "ground", "rocker", "B0")
        .pin_in_slot("slot", "rocker", ["S0", "S"], "crank", "A")
        .drive(Drive::angle("O"))
        .build()
        .unwrap();
    let mut t = Solver::default().track(&m).unwrap();
    assert_eq!(t.closed_form_loops(), vec![true, true]);
    // A = O + l1 (sin φ, −cos φ) is closest to B0 where (sin φ, −cos φ) points from O to B0.
    let closest = (-e).atan2(l0);
    match t.move_to(closest).unwrap_err() {
        Error::Blocked {
            to, limit, joints, ..
        } => {
            assert_eq!(to, closest);
            assert_eq!(joints, vec!["B0".to_string(), "slot".to_string()]);
            // The limit: |A − B0| = e, i.e. e sin φ − l0 cos φ = −(l0² + l1²)/(2 l1):
            // φ = β + asin(k), β = atan2(l0, e), k = −(l0² + l1²)/(2 l1 √(e² + l0²)).
            // 1e-14: the closed form's own rounding (asin near its steep end) and the
            // solver's Newton both at rounding level.
            let k = -(l0 * l0 + l1 * l1) / (2.0 * l1 * e.hypot(l0));
            let exact = l0.atan2(e) + k.asin();
            assert!((limit - exact).abs() < 1e-14, "{limit} vs {exact}");
            assert!(t.phi() > limit && t.phi() < 0.0);
        }
        other => panic!("expected Blocked, got {other:?}"),
    }
}

#[test]
fn four_bar_rrr_dyad_matches_its_closed_form_and_newton_on_both_closures() {
    let (a, b, c, d) = (0.1, 0.35, 0.3, 0.3);
    for up in [true, false] {
        let m = four_bar(a, b, c, d, 0.4, up).unwrap();
        let t = Solver::default().track(&m).unwrap();
        assert_eq!(t.closed_form_loops(), vec![true, true]);
        // Two revolutions: the rocker's and coupler's angles stay continuous.
        let phis: Vec<f64> = (0..=720).map(|i| 0.4 + i as f64 * PI / 180.0).collect();
        let mut pairs = vec![Vec::new(); 8];
        for k in Solver::default().sweep::<3>(&m, &phis).unwrap() {
            let got = k.point("rocker", "B").unwrap();
            let exact = four_bar_pin(a, b, c, d, k.phi, up);
            for i in 0..2 {
                let (g, e) = (got[i], exact[i]);
                pairs[4 * i].push((g.value, e.re));
                pairs[4 * i + 1].push((g.d1(), e.v1));
                pairs[4 * i + 2].push((g.d2(), e.v2));
                pairs[4 * i + 3].push((g.d3(), e.v3));
            }
        }
        // Against the hand-written closed form: 1e-14 scaled (both exact to rounding).
        for p in &pairs {
            let e = scaled_error(p);
            assert!(e <= 1e-14, "up = {up}: scaled error {e:e}");
        }
        // Against Newton: the Newton path's q′, q″, q‴ are off by up to 5e-13 scaled here
        // (the closed form is within 1e-14 of the hand-written one, above).
        let e = closed_form_vs_newton(&m, &phis);
        assert!(e <= 1e-12, "up = {up}: scaled difference {e:e}");
    }
}

#[test]
fn slider_crank_rrp_dyad_matches_newton_and_its_closed_form() {
    let (r, l) = (0.1, 0.35);
    for phi0 in [0.3, 2.0] {
        let m = slider_crank(r, l, phi0, false).unwrap();
        let t = Solver::default().track(&m).unwrap();
        assert_eq!(t.closed_form_loops(), vec![true, true]);
        let phis: Vec<f64> = (0..=720).map(|i| phi0 + i as f64 * PI / 180.0).collect();
        let e = closed_form_vs_newton(&m, &phis);
        // 1e-13 scaled: both exact up to rounding.
        assert!(e <= 1e-13, "φ₀ = {phi0}: scaled difference {e:e}");
        for k in Solver::default().sweep::<1>(&m, &phis).unwrap() {
            // x_B = r cos φ + √(l² − r² sin² φ), to rounding (1e-15 m on 0.35 m).
            let (s, c) = k.phi.sin_cos();
            let x = k.displacement("guide").unwrap();
            let exact = r * c + (l * l - r * r * s * s).sqrt();
            assert!((x.value - exact).abs() < 1e-15, "φ = {}", k.phi);
        }
    }
}

#[test]
fn dyads_report_unassemblable_and_toggle_through_the_closed_form() {
    // Four-bar whose coupler (0.12) is too short: at φ = π the crank pin is 0.4 m from B0,
    // more than coupler + rocker = 0.37 m.
    let m = four_bar(0.1, 0.12, 0.25, 0.3, 0.0, true).unwrap();
    let mut t = Solver::default().track(&m).unwrap();
    assert_eq!(t.closed_form_loops(), vec![true, true]);
    match t.move_to(PI).unwrap_err() {
        Error::Blocked {
            from,
            to,
            limit,
            joints,
        } => {
            assert_eq!((from, to), (0.0, PI));
            assert_eq!(joints, vec!["A", "B", "B0"]);
            // |A − B0|² = a² + d² − 2ad cos φ reaches 0.37² at the limit position; 1e-14:
            // acos of a value rounded to 1e-16 near cos = −0.6 (slope 1.25), and the
            // solver's Newton on the margin at rounding level.
            let exact = ((0.01 + 0.09 - 0.37f64 * 0.37) / 0.06).acos();
            assert!((limit - exact).abs() < 1e-14, "{limit} vs {exact}");
            assert!(t.phi() < exact);
        }
        other => panic!("expected Blocked, got {other:?}"),
    }
    // Slider-crank driven by its slider into the dead centre x = r + l: the crank and rod
    // are aligned (the RRR dyad crank–rod, between O and the slider's pin B, is at its
    // toggle).
    let (r, l) = (0.1, 0.35);
    let m = slider_crank(r, l, 1.0, true).unwrap();
    let mut t = Solver::default().track(&m).unwrap();
    assert_eq!(t.closed_form_loops(), vec![true, true]);
    match t.move_to(r + l).unwrap_err() {
        Error::Singular { phi, joints, .. } => {
            assert_eq!(phi, r + l);
            assert_eq!(joints, vec!["O", "A", "B"]);
        }
        other => panic!("expected Singular, got {other:?}"),
    }
}

#[test]
fn rack_pinion_and_rpr_dyad_of_001_are_closed_form_and_match_newton() {
    // Mechanism 001 driven by the rack (the pinion follows: a rolling angle) and by the
    // pinion (the rack follows: a rolling displacement), on both closures of the rod–slider
    // dyad. The block sliding in the turning slotted link is the RPR dyad: the slotted link
    // turns like a slotted rocker whose line passes through the block's hinge A, and the
    // block follows at A.
    let x0 = common::rack001::RHO4;
    for closure in [common::Closure001::Primary, common::Closure001::Other] {
        for pinion in [false, true] {
            let m = rack_slotted_link(closure, pinion).unwrap();
            let t = Solver::default().track(&m).unwrap();
            assert!(
                t.closed_form_loops().iter().all(|&c| c),
                "{closure:?} {pinion}"
            );
            // ±0.1 m of rack travel about the instant: ±2.5 rad of the 0.04 m pinion.
            let phis: Vec<f64> = (0..=100)
                .map(|i| -0.1 + 0.002 * i as f64)
                .map(|d| if pinion { d / 0.04 } else { x0 + d })
                .collect();
            let e = closed_form_vs_newton(&m, &phis);
            // Both exact: the Newton side lifts q′, q″, q‴ by implicit differentiation at a
            // pose converged to ~1e-15; the largest difference measured is 1.3e-13 scaled.
            assert!(e <= 1e-12, "{closure:?} {pinion}: scaled difference {e:e}");
        }
    }
}

/// A crank O–A (0.15 m, driven) carrying a block hinged at A, and a lever hinged at
/// B = (0, −0.4); block and lever slide on each other along a direction 0.1 rad off B→A, so
/// that neither hinge is on the other's line (the RPR dyad with offsets). The prismatic
/// pair's line is on the lever (through B, the block's point A sliding on it) or on the
/// block (through A, the lever's point B sliding on it): the same motion either way.
fn crank_block_lever(line_on_lever: bool) -> Mechanism {
    // Sketch at φ = 1 rad.
    let a = [0.15 * 1f64.cos(), 0.15 * 1f64.sin()];
    let along = (a[1] + 0.4).atan2(a[0]) + 0.1;
    let u = [along.cos(), along.sin()];
    let b = Mechanism::builder()
        .point("O", [0.0, 0.0])
        .point("B", [0.0, -0.4])
        .point("A", a)
        .point("T", [0.5 * u[0], -0.4 + 0.5 * u[1]])
        .point("U", [a[0] + 0.3 * u[0], a[1] + 0.3 * u[1]])
        .point("M", [a[0] - 0.05 * u[1], a[1] + 0.05 * u[0]])
        .point("N", [0.07 * u[1], -0.4 - 0.07 * u[0]])
        .ground(["O", "B"])
        .link("crank", ["O", "A"])
        // Each link's first point is its reference point: here off the line and off the
        // hinge, so that the hinges' local coordinates enter the dyad's formula.
        .link("block", ["M", "A", "U"])
        .link("lever", ["N", "B", "T"])
        .revolute("O", "ground", "crank", "O")
        .revolute("A", "crank", "block", "A")
        .revolute("B", "ground", "lever", "B");
    let b = if line_on_lever {
        b.prismatic("slide", "lever", ["B", "T"], "block", "A")
    } else {
        b.prismatic("slide", "block", ["A", "U"], "lever", "B")
    };
    b.drive(Drive::angle("O").at_sketch(1.0)).build().unwrap()
}

#[test]
fn rpr_dyad_with_the_line_on_either_link_matches_newton() {
    let lever_angle = |m: &Mechanism, phi: f64| {
        let mut t = Solver::default().track(m).unwrap();
        t.move_to(phi).unwrap();
        t.kinematics::<2>().unwrap().rotation("lever").unwrap()
    };
    for line_on_lever in [true, false] {
        let m = crank_block_lever(line_on_lever);
        let t = Solver::default().track(&m).unwrap();
        assert_eq!(t.closed_form_loops(), vec![true, true], "{line_on_lever}");
        let e = closed_form_vs_newton(&m, &revolution(1.0, &[]));
        // Both exact: 1e-12 scaled (as for mechanism 001's RPR dyad).
        assert!(e <= 1e-12, "{line_on_lever}: scaled difference {e:e}");
    }
    // Which link carries the line does not change the motion: the lever turns alike, to
    // rounding (1e-14 on values and derivatives of order 1).
    let (on_lever, on_block) = (crank_block_lever(true), crank_block_lever(false));
    for phi in [0.0, 1.0, 2.5, 4.0, 5.5] {
        let (x, y) = (lever_angle(&on_lever, phi), lever_angle(&on_block, phi));
        let gaps = [x.value - y.value, x.d1() - y.d1(), x.d2() - y.d2()];
        assert!(gaps.iter().all(|g| g.abs() < 1e-14), "{phi}: {gaps:?}");
    }
}

/// A pinion of pitch radius 0.05 m about W = (0, 0.05) on a rack sliding along the x axis,
/// driven by the rack's travel or by the pinion's angle. The mesh relates the travel to the
/// pinion joint's angle (its second link relative to its first): with the joint's links
/// `reversed` (pinion first) that angle is minus the pinion's rotation.
fn rack_and_pinion(drive_pinion: bool, reversed: bool) -> Mechanism {
    let hinge = if reversed {
        ["pinion", "ground"]
    } else {
        ["ground", "pinion"]
    };
    Mechanism::builder()
        .point("O", [0.0, 0.0])
        .point("X", [1.0, 0.0])
        .point("W", [0.0, 0.05])
        .point("A", [0.2, 0.0])
        .ground(["O", "X", "W"])
        .link("pinion", ["W"])
        .link("rack", ["A"])
        .revolute("W", hinge[0], hinge[1], "W")
        .prismatic("guide", "ground", ["O", "X"], "rack", "A")
        .rack_pinion("mesh", "W", "guide", 0.05)
        .drive(if drive_pinion {
            Drive::angle("W")
        } else {
            Drive::displacement("guide")
        })
        .build()
        .unwrap()
}

#[test]
fn gear_and_rack_pinion_follow_their_ratios_in_closed_form() {
    for drive_second in [false, true] {
        let m = gear_pair(drive_second, false);
        let mut t = Solver::default().track(&m).unwrap();
        assert_eq!(t.closed_form_loops(), vec![true, true]);
        // θ₂ = −2 θ₁, whichever wheel is driven: exact linear relations, 1e-15 for the
        // rounding of one product; the second derivatives are exactly 0.
        t.move_to(0.7).unwrap();
        let k = t.kinematics::<3>().unwrap();
        let (w1, w2) = (
            k.rotation("wheel 1").unwrap(),
            k.rotation("wheel 2").unwrap(),
        );
        assert!((w2.value + 2.0 * w1.value).abs() < 1e-15);
        assert!((w2.d1() + 2.0 * w1.d1()).abs() < 1e-15);
        assert!(w2.d2() == 0.0 && w1.d3() == 0.0);
        let e = closed_form_vs_newton(&m, &revolution(5.0, &[]));
        assert!(e <= 1e-12, "scaled difference {e:e}");
    }
    for (drive_pinion, reversed) in [(false, false), (true, false), (false, true), (true, true)] {
        let m = rack_and_pinion(drive_pinion, reversed);
        let sign = if reversed { -1.0 } else { 1.0 };
        let mut t = Solver::default().track(&m).unwrap();
        assert_eq!(t.closed_form_loops(), vec![true, true]);
        let travel = m.displacement_output("guide").unwrap();
        let turn = m.rotation_output("pinion").unwrap();
        // Δs = ±0.05 Δθ (radius 0.05 m; − with the joint reversed): 1e-15, the rounding of
        // one product or quotient.
        let phis: Vec<f64> = (-20..=20).map(|i| 0.02 * f64::from(i)).collect();
        for &phi in &phis {
            t.move_to(phi).unwrap();
            let (s, theta) = (t.value(&travel), t.value(&turn));
            assert!(
                (s.value - 0.2 - sign * 0.05 * theta.value).abs() < 1e-15,
                "{phi}"
            );
            assert!((s.d1() - sign * 0.05 * theta.d1()).abs() < 1e-15, "{phi}");
            assert!(s.d2() == 0.0 && theta.d2() == 0.0, "{phi}");
        }
        let e = closed_form_vs_newton(&m, &phis);
        assert!(e <= 1e-12, "scaled difference {e:e}");
    }
}

#[test]
fn mixed_closed_form_and_newton_loops_match_newton() {
    // The weld has no pattern: it is solved by Newton, the gear loops seed its predictor.
    let m = gear_pair(false, true);
    let t = Solver::default().track(&m).unwrap();
    let closed = t.closed_form_loops();
    assert_eq!(closed.iter().filter(|&&c| c).count(), 2, "{closed:?}");
    assert_eq!(closed.len(), 3);
    let e = closed_form_vs_newton(&m, &revolution(5.0, &[]));
    // Both exact (the weld is Newton on both sides): 1e-12 scaled.
    assert!(e <= 1e-12, "scaled difference {e:e}");
}

/// `Tracker::pose_jets` reads the pose as the move solved it (the solver's own sines and
/// cosines, differentiated through θ′, θ″, θ‴; a link's rotation from its angle): the same
/// outputs as a `Kinematics::<3>` (whose points turn with `sin_cos` of θ in `Dual3_64`), on
/// both paths, and a slot's travel equal to the law of cosines, with exactly the derivatives
/// its scalar carries.
#[test]
fn outputs_read_from_the_solved_pose_agree_with_the_kinematics_and_the_law_of_cosines() {
    use common::{L0, L1};
    use mechdiff_core::JetDual;
    use mechdiff_core::num_dual::{Dual2_64, Dual3_64, DualNum};
    let m = whitworth().unwrap();
    let psi = m.rotation_output("rocker").unwrap();
    let ram = m.displacement_output("ram guide").unwrap();
    let pin = m.point_output("crank", "A").unwrap();
    // The crank pin's distance from B0 along the slot B0 → S: |A − B0|, with A = O + L1
    // (sin φ, −cos φ) and O = (0, L0): √(L0² + L1² − 2 L0 L1 cos φ).
    let slot = m.slide_output("rocker", ["B0", "S"], "crank", "A").unwrap();
    let law_of_cosines = |phi: f64| {
        let phi = Dual3_64::new(phi, 1.0, 0.0, 0.0);
        (phi.cos() * (-2.0 * L0 * L1) + (L0 * L0 + L1 * L1)).sqrt()
    };
    // Lengths of O(1) m, angles of O(1) rad, their derivatives up to ~10: a few ulps of
    // each (the sine and cosine of either route are correctly rounded to an ulp), so 1e-13
    // of max(1, |x|) leaves a margin of ~100, and a wrong term of the chain rule is O(1).
    let close = |a: [f64; 4], b: [f64; 4], what: &str, phi: f64| {
        for (k, (x, y)) in a.iter().zip(b).enumerate() {
            assert!(
                (x - y).abs() <= 1e-13 * y.abs().max(1.0),
                "{what}, φ = {phi}, derivative {k}: {x:e} against {y:e}"
            );
        }
    };
    for closed_form in [true, false] {
        let mut t = Solver::default()
            .with_closed_form(closed_form)
            .track(&m)
            .unwrap();
        let mut dddq = Vec::new();
        for phi in revolution(7.5, &[]) {
            t.move_to(phi).unwrap();
            t.third_derivatives(&mut dddq).unwrap();
            let k = t.kinematics::<3>().unwrap();
            let pose = t.pose_jets_with(&dddq);
            let parts = |j: Jet<3>| [j.value, j.d1(), j.d2(), j.d3()];
            // A rotation is the link's angle itself: bit for bit.
            assert_eq!(pose.value::<Dual3_64>(&psi).jet::<3>(), k.value(&psi));
            let ram3 = pose.value::<Dual3_64>(&ram);
            close(ram3.derivatives(), parts(k.value(&ram)), "x_C", phi);
            let [x, y] = pose.position::<Dual3_64>(&pin);
            let [kx, ky] = k.position(&pin);
            close(x.derivatives(), parts(kx), "x_A", phi);
            close(y.derivatives(), parts(ky), "y_A", phi);
            let travel = pose.value::<Dual3_64>(&slot).derivatives();
            close(travel, law_of_cosines(phi).derivatives(), "|B0A|", phi);
            // Order 2 carries x, x′, x″ (the same to rounding) and nothing beyond.
            let ram2 = t.pose_jets().value::<Dual2_64>(&ram).derivatives();
            assert_eq!(ram2[3], 0.0);
            close(
                ram2,
                [ram3.re, ram3.v1, ram3.v2, 0.0],
                "x_C in Dual2_64",
                phi,
            );
        }
    }
}

/// `Tracker::value` and `Tracker::position` (read straight from the tracker) give the same
/// outputs as a `Kinematics::<2>` built at the same pose, on both paths; on the closed-form
/// path `move_to` does not evaluate Φ (`residual` is `None`) and `Tracker::residual`
/// evaluates it on request.
#[test]
fn outputs_read_from_the_tracker_equal_the_kinematics() {
    let m = whitworth().unwrap();
    let psi = m.rotation_output("rocker").unwrap();
    let ram = m.displacement_output("ram guide").unwrap();
    let pin = m.point_output("crank", "A").unwrap();
    for closed_form in [true, false] {
        let mut t = Solver::default()
            .with_closed_form(closed_form)
            .track(&m)
            .unwrap();
        for phi in revolution(7.5, &[]) {
            let report = t.move_to(phi).unwrap();
            let k = t.kinematics::<2>().unwrap();
            // Exactly equal: the same arithmetic on the same q, q′, q″.
            assert_eq!(t.value(&psi), k.value(&psi));
            assert_eq!(t.value(&ram), k.value(&ram));
            assert_eq!(t.position(&pin), k.position(&pin));
            // The loops close to rounding on either path: lengths of O(1) m and angles of
            // O(1) rad, a few ulps each, so 1e-14 (m or rad) leaves a margin of ~10.
            assert!(t.residual() <= 1e-14, "φ = {phi}: Φ = {}", t.residual());
            match report.residual {
                None => assert!(closed_form, "Newton reports its residual"),
                Some(r) => assert!(!closed_form && r <= 1e-14, "φ = {phi}: Φ = {r}"),
            }
        }
    }
}
