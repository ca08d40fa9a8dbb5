//! Kinetostatics through the joint kinds not covered by the reference mechanisms: a rigid
//! (welded) joint and a displacement drive.

use crate::common;

use common::slider_crank_parts;
use mechdiff_core::DriveState;
use mechdiff_core::dynamics::{Dynamics, Gravity, Load, kinetostatics};
use mechdiff_core::geometry::{Drive, Inertia, Mechanism, Solver};

const G: f64 = 9.81;

/// A crank O–A of 0.3 m as one link, or as two links O–M and M–A welded at M, each half with
/// 1 kg at its middle and J = m l²/12 about it.
fn crank(welded: bool) -> Mechanism {
    let b = Mechanism::builder()
        .point("O", [0.0, 0.0])
        .point("M", [0.15, 0.0])
        .point("A", [0.3, 0.0])
        .ground(["O"]);
    let half = |c: f64| Inertia {
        mass: 1.0,
        center: [c, 0.0],
        moment: 0.15 * 0.15 / 12.0,
    };
    let b = if welded {
        b.link("inner", ["O", "M"])
            .link("outer", ["M", "A"])
            .inertia("inner", half(0.075))
            .inertia("outer", half(0.225))
            .revolute("O", "ground", "inner", "O")
            .rigid("weld", "inner", "outer")
    } else {
        // The same body: 2 kg at 0.15 m, J = 2·(0.15²/12 + 0.075²) about the centre.
        b.link("crank", ["O", "M", "A"])
            .inertia(
                "crank",
                Inertia {
                    mass: 2.0,
                    center: [0.15, 0.0],
                    moment: 2.0 * (0.15 * 0.15 / 12.0 + 0.075 * 0.075),
                },
            )
            .revolute("O", "ground", "crank", "O")
    };
    b.drive(Drive::angle("O")).build().unwrap()
}

#[test]
fn a_welded_crank_needs_the_torque_of_the_single_body_and_the_weld_carries_the_outer_half() {
    let (single, welded) = (crank(false), crank(true));
    let d = Dynamics::new().with_gravity(Gravity::down(G));
    let (ms, mw) = (d.compile(&single).unwrap(), d.compile(&welded).unwrap());
    let effects = d.available(&welded);
    let drive = DriveState::accelerating(7.0, 30.0);
    let phis: Vec<f64> = (0..36).map(|i| f64::from(i) * 10f64.to_radians()).collect();
    let a = Solver::default().sweep::<2>(&single, &phis).unwrap();
    let b = Solver::default().sweep::<2>(&welded, &phis).unwrap();
    for (ka, kb) in a.iter().zip(&b) {
        let sa = kinetostatics::solve(&ms, &effects, ka, &drive).unwrap();
        let sb = kinetostatics::solve(&mw, &effects, kb, &drive).unwrap();
        // 1e-12 of the largest torque term (m g l ≈ 2.9 N·m, J α ≈ 1.4 N·m): rounding only.
        assert!(
            (sa.drive_torque - sb.drive_torque).abs() <= 1e-12 * 3.0,
            "φ = {}",
            ka.phi
        );
        // The weld's force on the outer half is what the outer half's motion and weight need:
        // F = m (a_G − g) with m = 1 kg and G at r = 0.225 m from O (closed form); 1e-12 of
        // the largest term (ω² r m ≈ 11 N plus the weight).
        let (s, c) = ka.phi.sin_cos();
        let (w, al) = (drive.omega, drive.alpha);
        let r = 0.225;
        let a_g = [-r * (al * s + w * w * c), r * (al * c - w * w * s)];
        let weld = sb.reactions.iter().find(|r| r.joint == "weld").unwrap();
        let want = [a_g[0], a_g[1] + G];
        for i in 0..2 {
            assert!(
                (weld.force[i] - want[i]).abs() <= 1e-12 * 15.0,
                "φ = {}: {:?} vs {want:?}",
                ka.phi,
                weld.force
            );
        }
    }
}

/// A slider-crank driven by its slider: crank 0.1 m, rod 0.4 m, masses on all three links,
/// gravity and a torque on the crank. The drive force from the equilibrium against the
/// power balance over the stroke, away from the dead centres (where ẋ = 0 fixes no speed).
#[test]
fn displacement_drive_force_equals_the_power_balance_force() {
    let (r, l) = (0.1, 0.4);
    let phi0: f64 = 1.0;
    let a = [r * phi0.cos(), r * phi0.sin()];
    let x = a[0] + (l * l - a[1] * a[1]).sqrt();
    let m = slider_crank_parts(r, l, phi0)
        .inertia(
            "crank",
            Inertia {
                mass: 0.5,
                center: [a[0] / 2.0, a[1] / 2.0],
                moment: 4e-4,
            },
        )
        .inertia(
            "rod",
            Inertia {
                mass: 1.2,
                center: [(a[0] + x) / 2.0, a[1] / 2.0],
                moment: 0.016,
            },
        )
        .inertia(
            "slider",
            Inertia {
                mass: 2.0,
                center: [x, 0.0],
                moment: 0.0,
            },
        )
        .drive(Drive::displacement("guide"))
        .build()
        .unwrap();
    let d = Dynamics::new()
        .with_gravity(Gravity::down(G))
        .with_load(Load::torque("crank", -3.0));
    let model = d.compile(&m).unwrap();
    let effects = d.available(&m);
    // From x at φ = 1 rad towards the outer dead centre l + r = 0.5 m, stopping 5 mm short.
    let xs: Vec<f64> = (0..=40)
        .map(|i| x + (0.495 - x) * f64::from(i) / 40.0)
        .collect();
    let sweep = Solver::default().sweep::<2>(&m, &xs).unwrap();
    let drive = DriveState::accelerating(0.8, -2.0);
    let mut worst: f64 = 0.0;
    let mut scale: f64 = 0.0;
    for k in &sweep {
        let s = kinetostatics::solve(&model, &effects, k, &drive).unwrap();
        worst = worst.max((s.drive_torque - s.balance.torque.unwrap()).abs());
        scale = scale.max(s.drive_torque.abs());
    }
    println!(
        "displacement drive: force error {:.1e} of {scale:.3} N",
        worst / scale
    );
    // 1e-9 of the largest drive force over the range (the criterion).
    assert!(worst <= 1e-9 * scale, "{:e}", worst / scale);
}
