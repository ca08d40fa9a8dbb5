//! A crank-rocker four-bar with gravity and external loads: the drive torque from the
//! equilibrium equations against the power balance over full revolutions, ideal and with a
//! gear pair of efficiency η whose power flow reverses during the revolution.

use crate::common;

use common::{four_bar_rocker_pin, revolution, scaled_error};
use mechdiff_core::DriveState;
use mechdiff_core::dynamics::{
    Dynamics, Efficiency, Friction, Gravity, Load, Motor, kinetostatics,
};
use mechdiff_core::geometry::{Drive, Inertia, Mechanism, Solver};

/// Crank 0.1 m, coupler 0.35 m with a coupler point K, rocker 0.3 m, frame 0.4 m (Grashof:
/// 0.1 + 0.4 < 0.35 + 0.3, the crank turns fully), sketched at φ = 0. With `gear`, a pinion
/// at (−0.2, 0) drives the crank through an external mesh of ratio −1/2 and φ is the
/// pinion's angle.
fn four_bar(gear: bool) -> Mechanism {
    let a = [0.1, 0.0];
    let b = four_bar_rocker_pin(a, 0.35, 0.3, 0.4, true).unwrap();
    let k = [(a[0] + b[0]) / 2.0 + 0.05, (a[1] + b[1]) / 2.0 + 0.08];
    let mut builder = Mechanism::builder()
        .point("A0", [0.0, 0.0])
        .point("B0", [0.4, 0.0])
        .point("A", a)
        .point("B", b)
        .point("K", k)
        .ground(["A0", "B0"])
        .link("crank", ["A0", "A"])
        .link("coupler", ["A", "B", "K"])
        .link("rocker", ["B0", "B"])
        .inertia(
            "crank",
            Inertia {
                mass: 0.8,
                center: [0.04, 0.01],
                moment: 0.002,
            },
        )
        .inertia(
            "coupler",
            Inertia {
                mass: 2.0,
                center: k,
                moment: 0.03,
            },
        )
        .inertia(
            "rocker",
            Inertia {
                mass: 1.5,
                center: [(0.4 + b[0]) / 2.0, b[1] / 2.0],
                moment: 0.015,
            },
        )
        .revolute("A0", "ground", "crank", "A0")
        .revolute("A", "crank", "coupler", "A")
        .revolute("B", "coupler", "rocker", "B")
        .revolute("B0", "ground", "rocker", "B0");
    if gear {
        builder = builder
            .point("G", [-0.2, 0.0])
            .ground(["G"])
            .link("pinion", ["G"])
            .revolute("G", "ground", "pinion", "G")
            .gear("mesh", "G", "A0", -0.5)
            .drive(Drive::angle("G"));
    } else {
        builder = builder.drive(Drive::angle("A0"));
    }
    builder.build().unwrap()
}

fn loads(d: Dynamics) -> Dynamics {
    d.with_gravity(Gravity::down(9.81))
        .with_load(Load::torque("rocker", -15.0))
        .with_load(Load::force("coupler", "K", [40.0, -25.0]).active_between(1.0, 4.0))
}

#[test]
fn drive_torque_equals_power_balance_torque_with_gravity_and_loads() {
    let m = four_bar(false);
    let d = loads(Dynamics::new());
    let model = d.compile(&m).unwrap();
    let effects = d.available(&m);
    let sweep = Solver::default()
        .sweep::<2>(&m, &revolution(1.0, &[]))
        .unwrap();
    for drive in [
        DriveState::constant_speed(20.0),
        DriveState::accelerating(20.0, 150.0),
        DriveState::accelerating(-8.0, 40.0),
    ] {
        let pairs: Vec<(f64, f64)> = sweep
            .iter()
            .map(|k| {
                let s = kinetostatics::solve(&model, &effects, k, &drive).unwrap();
                (s.drive_torque, s.balance.torque.unwrap())
            })
            .collect();
        let e = scaled_error(&pairs);
        println!(
            "ω = {}, α = {}: scaled error {e:.1e}",
            drive.omega, drive.alpha
        );
        // 1e-9 of the largest torque over the revolution (the torque crosses zero).
        assert!(e <= 1e-9, "scaled error {e:e}");
    }
}

#[test]
fn gear_efficiency_and_friction_close_the_balance_in_both_flow_directions() {
    let m = four_bar(true);
    let d = loads(Dynamics::new())
        .with_efficiency(Efficiency::new("mesh", 0.9))
        .with_friction(Friction::revolute("A", 0.15, 0.008))
        .with_friction(Friction::revolute("B0", 0.15, 0.008))
        // The gears' bearings carry the tooth force: their friction depends on it.
        .with_friction(Friction::revolute("G", 0.1, 0.01))
        .with_friction(Friction::revolute("A0", 0.1, 0.012))
        .with_motor(Motor {
            rotor_inertia: 1e-4,
            ratio: 0.25,
            efficiency: 0.95,
        });
    let model = d.compile(&m).unwrap();
    let effects = d.available(&m);
    // The pinion turns −2 rad per crank radian: a crank revolution is φ ∈ [0, −4π].
    let phis: Vec<f64> = revolution(1.0, &[]).iter().map(|p| -2.0 * p).collect();
    let sweep = Solver::default().sweep::<2>(&m, &phis).unwrap();
    let drive = DriveState::accelerating(-30.0, 100.0);
    let (mut direct, mut reverse, mut worst) = (0, 0, 0.0f64);
    for k in &sweep {
        let s = kinetostatics::solve(&model, &effects, k, &drive).unwrap();
        let b = s.balance;
        worst = worst.max(b.residual.abs() / b.scale());
        let mesh = s.reactions.iter().find(|r| r.joint == "mesh").unwrap();
        assert!(mesh.power_loss <= 0.0);
        if s.motor.unwrap().direct_flow {
            direct += 1
        } else {
            reverse += 1
        }
        // The two motor torques differ by rounding only: 1e-9 of the largest power term
        // divided by the motor speed |ω/τ| = 120 rad/s.
        let t = b.torque.unwrap();
        assert!((t - b.kinetostatic_torque).abs() <= 1e-9 * b.scale() / (drive.omega / 0.25).abs());
    }
    println!(
        "power balance with η and friction: worst residual {worst:.1e}; {direct} direct, {reverse} reverse"
    );
    // 1e-9 relative to the largest power term (the criterion).
    assert!(worst <= 1e-9, "{worst:e}");
    assert!(
        direct > 0 && reverse > 0,
        "the power flow must reverse during the revolution"
    );
}

#[test]
fn the_pinion_bearing_carries_the_tooth_force() {
    // Pinion at G = (−0.2, 0), crank gear at A0 = (0, 0), ratio −1/2: pitch radii
    // r1 = 0.2·0.5/1.5 and r2 = 0.2/1.5, pitch point on the x axis. The massless pinion is held
    // by its bearing against the tangential tooth force |M_drive|/r1, vertical.
    let m = four_bar(true);
    let d = loads(Dynamics::new());
    let model = d.compile(&m).unwrap();
    let phis: Vec<f64> = revolution(10.0, &[]).iter().map(|p| -2.0 * p).collect();
    let r1 = 0.2 * 0.5 / 1.5;
    for k in Solver::default().sweep::<2>(&m, &phis).unwrap() {
        let s = kinetostatics::solve(
            &model,
            &d.available(&m),
            &k,
            &DriveState::accelerating(-30.0, 100.0),
        )
        .unwrap();
        let g = s.reactions.iter().find(|r| r.joint == "G").unwrap();
        let want = s.drive_torque.abs() / r1;
        // 1e-12 of the tooth force (rounding of one solve).
        assert!(
            g.force[0].abs() <= 1e-12 * want,
            "φ = {}: {:?}",
            k.phi,
            g.force
        );
        assert!(
            (g.force[1].abs() - want).abs() <= 1e-12 * want,
            "φ = {}: {:?} vs {want}",
            k.phi,
            g.force
        );
    }
}
