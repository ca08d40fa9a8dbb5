//! The Whitworth defined by geometry only against its closed form and the 30-digit reference.

use crate::common;
#[path = "data/whitworth_sweep_30digits.rs"]
mod reference;

use common::{H, L0, L1, revolution, scaled_error, whitworth};
use mechdiff_core::geometry::Solver;
use num_dual::{Dual3_64, DualNum};

/// Closed form of whitworth_000.md: ψ = atan2(λ sin φ, 1 − λ cos φ), x_C = h tan ψ, evaluated
/// with third-order dual numbers (exact derivatives up to rounding).
fn closed_form(phi: f64) -> (Dual3_64, Dual3_64) {
    let lambda = L1 / L0;
    let phi = Dual3_64::new(phi, 1.0, 0.0, 0.0);
    let psi = (phi.sin() * lambda).atan2(-phi.cos() * lambda + 1.0);
    (psi, psi.tan() * H)
}

/// The hand-derived formulas (1.35), (1.36) of the source for ψ′, ψ″.
fn hand_derived(phi: f64) -> (f64, f64) {
    let lambda = L1 / L0;
    let d = 1.0 - 2.0 * lambda * phi.cos() + lambda * lambda;
    (
        lambda * (phi.cos() - lambda) / d,
        -lambda * phi.sin() * (1.0 - lambda * lambda) / (d * d),
    )
}

fn dead_positions() -> [f64; 2] {
    let a = (L1 / L0).acos();
    [a, 2.0 * std::f64::consts::PI - a]
}

#[test]
fn full_revolution_at_half_degree_steps_matches_the_closed_form_to_1e_12() {
    let m = whitworth().unwrap();
    let phis = revolution(0.5, &dead_positions());
    let sweep = Solver::default().sweep::<3>(&m, &phis).unwrap();
    // Columns: ψ, ψ′, ψ″, ψ‴, x_C, x_C′, x_C″, x_C‴ as (geometry, closed form).
    let mut cols: Vec<Vec<(f64, f64)>> = vec![Vec::new(); 8];
    for k in &sweep {
        let rot = k.rotation("rocker").unwrap();
        let x = k.displacement("ram guide").unwrap();
        let (psi, xc) = closed_form(k.phi);
        let geo = [
            -rot.value,
            -rot.d1(),
            -rot.d2(),
            -rot.d3(),
            x.value,
            x.d1(),
            x.d2(),
            x.d3(),
        ];
        let exact = [psi.re, psi.v1, psi.v2, psi.v3, xc.re, xc.v1, xc.v2, xc.v3];
        for i in 0..8 {
            cols[i].push((geo[i], exact[i]));
        }
    }
    // 1e-12 of the quantity's largest magnitude over the revolution (the criterion):
    // both sides are exact up to f64 rounding, and the Newton residual is ≤ 1e-13 m.
    let names = ["ψ", "ψ′", "ψ″", "ψ‴", "x_C", "x_C′", "x_C″", "x_C‴"];
    for (name, col) in names.iter().zip(&cols) {
        let e = scaled_error(col);
        println!("closed form, {name}: scaled error {e:.1e}");
        assert!(e <= 1e-12, "{name}: scaled error {e:e}");
    }
    // And against the source's own formulas (1.35), (1.36).
    for k in &sweep {
        let rot = k.rotation("rocker").unwrap();
        let (p1, p2) = hand_derived(k.phi);
        assert!((-rot.d1() - p1).abs() <= 1e-12 * 0.6, "ψ′ at φ = {}", k.phi);
        assert!((-rot.d2() - p2).abs() <= 1e-12 * 0.7, "ψ″ at φ = {}", k.phi);
    }
}

#[test]
fn dead_positions_solve_with_zero_velocity_coefficient() {
    let m = whitworth().unwrap();
    let mut t = Solver::default().track(&m).unwrap();
    for phi in dead_positions() {
        t.move_to(phi).unwrap();
        let k = t.kinematics::<2>().unwrap();
        let psi = k.rotation("rocker").unwrap();
        // ψ′ = 0 exactly in exact arithmetic; ψ′ is O(1), so 1e-14 absolute is rounding.
        assert!(psi.d1().abs() < 1e-14, "ψ′ = {:e} at φ = {phi}", psi.d1());
        // ψ″ = ∓λ/√(1−λ²) = ∓0.404519917477945 (whitworth_000.md).
        assert!((psi.d2().abs() - 0.404519917477945).abs() < 1e-13);
    }
}

#[test]
fn matches_the_30_digit_reference_sweep() {
    let m = whitworth().unwrap();
    let phis: Vec<f64> = reference::WHITWORTH_SWEEP_30DIGITS
        .iter()
        .map(|r| r[0])
        .collect();
    let mut sorted = phis.clone();
    sorted.sort_by(f64::total_cmp);
    let sweep = Solver::default().sweep::<3>(&m, &sorted).unwrap();
    let mut cols: Vec<Vec<(f64, f64)>> = vec![Vec::new(); 8];
    for k in &sweep {
        let row = reference::WHITWORTH_SWEEP_30DIGITS
            .iter()
            .find(|r| r[0] == k.phi)
            .unwrap();
        let rot = k.rotation("rocker").unwrap();
        let x = k.displacement("ram guide").unwrap();
        let geo = [
            -rot.value,
            -rot.d1(),
            -rot.d2(),
            -rot.d3(),
            x.value,
            x.d1(),
            x.d2(),
            x.d3(),
        ];
        for i in 0..8 {
            cols[i].push((geo[i], row[i + 1]));
        }
    }
    // The reference is exact to 30 digits, so this measures the solver's own error:
    // 1e-14 of each quantity's largest magnitude (measured: ≤ 1e-15).
    for (i, col) in cols.iter().enumerate() {
        let e = scaled_error(col);
        println!("30-digit reference, column {i}: scaled error {e:.1e}");
        assert!(e <= 1e-14, "column {i}: scaled error {e:e}");
    }
}

#[test]
fn crank_centre_of_gravity_moves_on_its_circle() {
    // S1 at l_S1 = 0.04 m from O (whitworth_000.md): y_S1 = l0 − l_S1 cos φ, ÿ_S1(0) = ω² l_S1.
    let m = whitworth().unwrap();
    let mut t = Solver::default().track(&m).unwrap();
    t.move_to(0.3).unwrap();
    let [x, y] = t
        .kinematics::<2>()
        .unwrap()
        .center_of_gravity("crank")
        .unwrap();
    let (s, c) = 0.3f64.sin_cos();
    // Values of size 0.04..0.4 m; 1e-15 absolute is a few ulps.
    assert!((x.value - 0.04 * s).abs() < 1e-15 && (y.value - (L0 - 0.04 * c)).abs() < 1e-15);
    assert!((x.d2() + 0.04 * s).abs() < 1e-15 && (y.d2() - 0.04 * c).abs() < 1e-15);
}
