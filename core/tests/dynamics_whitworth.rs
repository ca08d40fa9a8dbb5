//! Dynamics of the Whitworth shaping machine defined by geometry: the inertial forces on the
//! foundation against whitworth_000.json, and the drive torque from the equilibrium equations
//! against the power balance over full revolutions.

use crate::common;
#[path = "data/whitworth_inertial_forces.rs"]
mod reference;

use common::revolution;
use mechdiff_core::DriveState;
use mechdiff_core::dynamics::{
    Dynamics, Effects, Friction, Gravity, Load, Plan, Request, ShakingSummary, kinetostatics,
    shaking_force,
};
use mechdiff_core::geometry::{Mechanism, Solver};

/// ω = 100 rpm = 10π/3 rad/s (whitworth_000.json `given.omega_rad_s`).
const OMEGA: f64 = 10.471975511965978;

/// The Whitworth of whitworth_000.md with its masses and the given moments of inertia of
/// crank and rocker (see `common::whitworth_with_moments`).
fn whitworth(moments: [f64; 2]) -> Mechanism {
    common::whitworth_with_moments(moments).expect("the reference geometry assembles")
}

#[test]
fn inertial_force_table_matches_whitworth_000_to_1e_9() {
    let m = whitworth([0.0, 0.0]);
    let model = Dynamics::new().compile(&m).unwrap();
    let drive = DriveState::constant_speed(OMEGA);
    let mut phis: Vec<f64> = reference::TABLE.iter().map(|r| r[0]).collect();
    phis.sort_by(f64::total_cmp);
    let sweep = Solver::default().sweep::<2>(&m, &phis).unwrap();
    // The largest force of the table (ΣF_x at the dead positions) scales the zero cells.
    let scale = 1923.6870803851873;
    for k in &sweep {
        let row = reference::TABLE.iter().find(|r| r[0] == k.phi).unwrap();
        let s = shaking_force(&model, k.phi, &k.coordinates, &drive);
        let [c, r, ram] = [&s.links[0], &s.links[1], &s.links[2]];
        let got = [
            c.force[0],
            c.force[1],
            r.force[0],
            r.force[1],
            ram.force[0],
            s.force[0],
            s.force[1],
        ];
        let names = ["F_x1", "F_y1", "F_x2", "F_y2", "F_x3", "ΣF_x", "ΣF_y"];
        for i in 0..7 {
            let want = row[i + 1];
            // 1e-9 relative (the criterion); a cell that is exactly 0 is held to
            // 1e-9 of the table's largest force. Both the solver and the reference are exact
            // up to rounding (the geometry is solved to 1e-13 m).
            let err = (got[i] - want).abs();
            let tol = 1e-9 * if want == 0.0 { scale } else { want.abs() };
            println!(
                "φ = {:.6}, {}: {} (reference {}), error {err:.1e}",
                k.phi, names[i], got[i], want
            );
            assert!(
                err <= tol,
                "{} at φ = {}: got {}, want {}",
                names[i],
                k.phi,
                got[i],
                want
            );
        }
        // The ram translates horizontally: no vertical inertial force (exact).
        assert_eq!(ram.force[1], 0.0);
    }
}

#[test]
fn shaking_force_over_a_revolution_matches_the_reference_sweep_and_is_symmetric() {
    let m = whitworth([0.0, 0.0]);
    let model = Dynamics::new().compile(&m).unwrap();
    let drive = DriveState::constant_speed(OMEGA);
    let mut phis: Vec<f64> = reference::SWEEP.iter().map(|r| r[0]).collect();
    phis.sort_by(f64::total_cmp);
    let sweep = Solver::default().sweep::<2>(&m, &phis).unwrap();
    let mut pairs = [Vec::new(), Vec::new()];
    for k in &sweep {
        let row = reference::SWEEP.iter().find(|r| r[0] == k.phi).unwrap();
        let s = shaking_force(&model, k.phi, &k.coordinates, &drive);
        pairs[0].push((s.force[0], row[1]));
        pairs[1].push((s.force[1], row[2]));
    }
    // 1e-9 of each component's largest magnitude over the revolution (the criterion;
    // ΣF_x crosses zero, so a pointwise relative error is meaningless there).
    for (name, p) in ["ΣF_x", "ΣF_y"].iter().zip(&pairs) {
        let e = scaled_error(p);
        println!("{name} over the reference sweep: scaled error {e:.1e}");
        assert!(e <= 1e-9, "{name}: scaled error {e:e}");
    }
    // Extremes on a 0.25° grid: φ ↦ 2π − φ mirrors the mechanism about the y axis at
    // constant ω, so max ΣF_x = −min ΣF_x at mirrored angles (1e-9 relative).
    let fine = Solver::default()
        .sweep::<2>(&m, &revolution(0.25, &[]))
        .unwrap();
    let forces: Vec<_> = fine
        .iter()
        .map(|k| shaking_force(&model, k.phi, &k.coordinates, &drive))
        .collect();
    let s = ShakingSummary::of(&forces).unwrap();
    println!("{s:?}");
    assert!((s.force_x[1].value + s.force_x[0].value).abs() <= 1e-9 * s.force_x[1].value);
    assert!((s.force_x[1].phi + s.force_x[0].phi - std::f64::consts::TAU).abs() < 1e-12);
    // The largest |ΣF_x| exceeds the dead-position value of the table (the ram's acceleration
    // peaks away from its dead positions).
    assert!(s.force_x[1].value > 1923.6870803851873);
}

/// max |a − b| over the sweep / max |b|: the drive torque crosses zero, so its error is
/// measured against its largest magnitude over the revolution.
fn scaled_error(pairs: &[(f64, f64)]) -> f64 {
    common::scaled_error(pairs)
}

#[test]
fn drive_torque_equals_power_balance_torque_over_a_revolution() {
    // Inertia (with moments of inertia), gravity, and a 2 kN cutting force on the ram on the
    // forward stroke (φ from 292.02° to 67.98°, where the ram moves towards +x), with the
    // crank accelerating: every term of the balance is non-zero somewhere.
    let m = whitworth([0.05, 1.2]);
    let dead = [reference::TABLE[2][0], reference::TABLE[3][0]];
    let dynamics = Dynamics::new()
        .with_gravity(Gravity::down(9.81))
        .with_load(Load::force("ram", "C", [-2000.0, 0.0]).active_between(dead[1], dead[0]));
    let model = dynamics.compile(&m).unwrap();
    let plan = Plan::for_requests(&[Request::PowerBalance], dynamics.available(&m));
    assert_eq!(
        plan.effects,
        Effects {
            inertia: true,
            gravity: true,
            loads: true,
            ..Effects::none()
        }
    );
    let sweep = Solver::default()
        .sweep::<2>(&m, &revolution(1.0, &dead))
        .unwrap();
    for drive in [
        DriveState::constant_speed(OMEGA),
        DriveState::accelerating(OMEGA, -3.0),
    ] {
        let mut pairs = Vec::new();
        let mut max_load_power: f64 = 0.0;
        for k in &sweep {
            let s = kinetostatics::solve(&model, &plan.effects, k, &drive).unwrap();
            let b = s.balance;
            pairs.push((b.torque.unwrap(), s.drive_torque));
            max_load_power = max_load_power.max(b.loads.abs());
            assert_eq!(s.iterations, 1, "no friction: one solve");
        }
        let e = scaled_error(&pairs);
        println!(
            "ω = {}, α = {}: kinetostatic vs power-balance torque, scaled error {e:.1e}",
            drive.omega, drive.alpha
        );
        // 1e-9 (the criterion); both are exact up to rounding of a 9×9 LU.
        assert!(e <= 1e-9, "scaled error {e:e}");
        assert!(
            max_load_power > 1000.0,
            "the cutting force must do work on the forward stroke"
        );
    }
}

#[test]
fn friction_in_every_joint_closes_the_power_balance() {
    // Friction circles in the three revolute joints, Coulomb friction in both slots and the
    // ram guide; the balance P_drive + P_g + P_loads + P_friction = dT/dt then holds only if
    // the friction forces are consistent with the reactions they come from.
    let m = whitworth([0.05, 1.2]);
    let dead = [reference::TABLE[2][0], reference::TABLE[3][0]];
    let dynamics = Dynamics::new()
        .with_gravity(Gravity::down(9.81))
        .with_load(Load::force("ram", "C", [-2000.0, 0.0]).active_between(dead[1], dead[0]))
        .with_friction(Friction::revolute("O", 0.1, 0.03))
        .with_friction(Friction::revolute("B0", 0.1, 0.03))
        .with_friction(Friction::sliding("slot A", 0.12))
        .with_friction(Friction::sliding("slot C", 0.12))
        .with_friction(Friction::sliding("ram guide", 0.08));
    let model = dynamics.compile(&m).unwrap();
    let effects = dynamics.available(&m);
    let sweep = Solver::default()
        .sweep::<2>(&m, &revolution(2.0, &[]))
        .unwrap();
    let drive = DriveState::accelerating(OMEGA, 2.0);
    let mut worst: f64 = 0.0;
    let mut lost: f64 = 0.0;
    for k in &sweep {
        let s = kinetostatics::solve(&model, &effects, k, &drive).unwrap();
        let b = s.balance;
        worst = worst.max(b.residual.abs() / b.scale());
        lost = lost.min(b.friction);
        for r in &s.reactions {
            assert!(r.power_loss <= 0.0, "friction must dissipate: {r:?}");
        }
    }
    println!(
        "friction power balance: worst residual {worst:.1e} of the largest term; max friction loss {lost:.1} W"
    );
    // 1e-9 relative to the largest power term (the criterion).
    assert!(worst <= 1e-9, "residual {worst:e}");
    assert!(lost < -10.0, "friction must cost power somewhere");
}
