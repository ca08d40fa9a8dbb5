//! Property test: for random crank-rocker four-bars with random masses, gravity and loads, the
//! drive torque from the equilibrium equations equals the one from the power balance.

use crate::common;

use common::four_bar_rocker_pin;
use mechdiff_core::DriveState;
use mechdiff_core::dynamics::{Dynamics, Gravity, Load, kinetostatics};
use mechdiff_core::geometry::{Drive, Inertia, Mechanism, Solver};
use proptest::prelude::*;

/// A four-bar with crank `a`, coupler `b`, rocker `c`, frame `d`; `None` if it does not
/// assemble at φ = 0.
fn four_bar(a: f64, b: f64, c: f64, d: f64, masses: [f64; 3], offset: f64) -> Option<Mechanism> {
    let pa = [a, 0.0];
    let pb = four_bar_rocker_pin(pa, b, c, d, true)?;
    let mid = |p: [f64; 2], q: [f64; 2]| [(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0 + offset];
    Mechanism::builder()
        .point("A0", [0.0, 0.0])
        .point("B0", [d, 0.0])
        .point("A", pa)
        .point("B", pb)
        .ground(["A0", "B0"])
        .link("crank", ["A0", "A"])
        .link("coupler", ["A", "B"])
        .link("rocker", ["B0", "B"])
        .inertia(
            "crank",
            Inertia {
                mass: masses[0],
                center: mid([0.0, 0.0], pa),
                moment: 0.01 * masses[0] * a * a,
            },
        )
        .inertia(
            "coupler",
            Inertia {
                mass: masses[1],
                center: mid(pa, pb),
                moment: masses[1] * b * b / 12.0,
            },
        )
        .inertia(
            "rocker",
            Inertia {
                mass: masses[2],
                center: mid([d, 0.0], pb),
                moment: masses[2] * c * c / 12.0,
            },
        )
        .revolute("A0", "ground", "crank", "A0")
        .revolute("A", "crank", "coupler", "A")
        .revolute("B", "coupler", "rocker", "B")
        .revolute("B0", "ground", "rocker", "B0")
        .drive(Drive::angle("A0"))
        .build()
        .ok()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn kinetostatic_torque_equals_power_balance_torque(
        a in 0.05f64..0.15,
        b in 0.35f64..0.6,
        c in 0.3f64..0.5,
        d in 0.45f64..0.6,
        masses in prop::array::uniform3(0.1f64..5.0),
        offset in -0.05f64..0.05,
        phi in 0.0f64..std::f64::consts::TAU,
        omega in -30.0f64..30.0,
        alpha in -200.0f64..200.0,
        torque in -20.0f64..20.0,
    ) {
        // Grashof with the crank shortest: a + longest < sum of the other two.
        let longest = b.max(c).max(d);
        prop_assume!(a + longest < b + c + d - longest && omega.abs() > 0.5);
        let Some(m) = four_bar(a, b, c, d, masses, offset) else { return Ok(()) };
        let dynamics = Dynamics::new()
            .with_gravity(Gravity::down(9.81))
            .with_load(Load::torque("rocker", torque));
        let model = dynamics.compile(&m).unwrap();
        let mut t = Solver::default().track(&m).unwrap();
        // Crank-rockers turn fully, but step so that every move is small.
        for k in 1..=8 {
            t.move_to(phi * f64::from(k) / 8.0).unwrap();
        }
        let k = t.kinematics::<2>().unwrap();
        let s = kinetostatics::solve(&model, &dynamics.available(&m), &k, &DriveState::accelerating(omega, alpha)).unwrap();
        let b = s.balance;
        // 1e-9 relative to the largest power term, divided by ω for a torque.
        let tol = 1e-9 * b.scale() / omega.abs();
        prop_assert!((s.drive_torque - b.torque.unwrap()).abs() <= tol.max(1e-12),
            "{} vs {}", s.drive_torque, b.torque.unwrap());
    }
}
