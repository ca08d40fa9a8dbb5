//! Bad input to the dynamics, and self-locking: each a typed error, none a panic.

use mechdiff_core::dynamics::{Dynamics, Efficiency, Friction, Load, Motor, kinetostatics};
use mechdiff_core::geometry::{Drive, Inertia, Mechanism, Solver};

const H: f64 = 0.2;
use mechdiff_core::{DriveState, Error};

/// A rocker pivoted at the origin drives, through a pin in its slot, a slider on the line
/// y = h; the rocker is sketched at angle `psi0` from +x. The smaller the angle, the more the
/// slot's normal force presses the slider into its guide instead of pushing it along.
fn wedge(psi0: f64) -> Mechanism {
    let h = H;
    let (s, c) = psi0.sin_cos();
    Mechanism::builder()
        .point("O", [0.0, 0.0])
        .point("S", [c, s])
        .point("P", [h * c / s, h])
        .point("G0", [0.0, h])
        .point("G1", [1.0, h])
        .ground(["O", "G0", "G1"])
        .link("rocker", ["O", "S"])
        .link("slider", ["P"])
        .revolute("O", "ground", "rocker", "O")
        .pin_in_slot("slot", "rocker", ["O", "S"], "slider", "P")
        .prismatic("guide", "ground", ["G0", "G1"], "slider", "P")
        .drive(Drive::angle("O"))
        .build()
        .unwrap()
}

fn wedge_solution(psi0: f64, f: f64) -> Result<f64, Error> {
    let m = wedge(psi0);
    let d = Dynamics::new()
        .with_load(Load::force("slider", "P", [100.0, 0.0]))
        .with_friction(Friction::sliding("slot", f))
        .with_friction(Friction::sliding("guide", f));
    let model = d.compile(&m)?;
    let k = Solver::default().track(&m)?.kinematics::<2>()?;
    let s = kinetostatics::solve(
        &model,
        &d.available(&m),
        &k,
        &DriveState::constant_speed(1.0),
    )?;
    Ok(s.drive_torque)
}

/// Massless slider, load 100 N along +x, the slider moving towards −x (ψ̇ = 1 rad/s). With
/// f in the slot and the guide, the slot's normal force is
/// N = 100 / ((1 − f²) sin ψ − 2 f cos ψ), positive only for ψ > 2 atan f (33.4° for
/// f = 0.3): below, no finite drive torque moves the slider. 34° and 33° bracket the limit.
#[test]
fn wedge_self_locks_below_twice_the_friction_angle() {
    let f: f64 = 0.3;
    for psi in [34.0f64, 40.0, 60.0, 80.0] {
        let p = psi.to_radians();
        let n = 100.0 / ((1.0 - f * f) * p.sin() - 2.0 * f * p.cos());
        let torque = H / p.sin() * n;
        let got = wedge_solution(p, f).unwrap();
        // 1e-12 relative: a 6×6 solve, exact up to rounding.
        assert!(
            (got - torque).abs() <= 1e-12 * torque,
            "ψ = {psi}°: {got} vs {torque}"
        );
    }
    for psi in [33.0f64, 30.0, 20.0, 5.0] {
        match wedge_solution(psi.to_radians(), f) {
            Err(Error::SelfLocking { joints, .. }) => assert_eq!(joints, ["slot", "guide"]),
            other => panic!("ψ = {psi}°: expected self-locking, got {other:?}"),
        }
    }
}

fn crank() -> Mechanism {
    Mechanism::builder()
        .point("O", [0.0, 0.0])
        .point("A", [1.0, 0.0])
        .ground(["O"])
        .link("crank", ["O", "A"])
        .inertia(
            "crank",
            Inertia {
                mass: 1.0,
                center: [0.5, 0.0],
                moment: 0.1,
            },
        )
        .revolute("O", "ground", "crank", "O")
        .drive(Drive::angle("O"))
        .build()
        .unwrap()
}

fn compile_error(d: Dynamics) -> String {
    let m = crank();
    let e = d.compile(&m).unwrap_err();
    e.to_string()
}

#[test]
fn negative_friction_coefficient_is_rejected() {
    let e = compile_error(Dynamics::new().with_friction(Friction::revolute("O", -0.1, 0.01)));
    assert!(
        e.contains("friction coefficient of joint `O`") && e.contains("-0.1"),
        "{e}"
    );
}

#[test]
fn efficiency_outside_0_1_is_rejected() {
    let e = compile_error(Dynamics::new().with_motor(Motor {
        rotor_inertia: 0.0,
        ratio: 0.1,
        efficiency: 1.2,
    }));
    assert!(
        e.contains("gearbox efficiency") && e.contains("(0, 1]"),
        "{e}"
    );
    let e = compile_error(Dynamics::new().with_motor(Motor {
        rotor_inertia: 0.0,
        ratio: 0.1,
        efficiency: 0.0,
    }));
    assert!(e.contains("(0, 1]"), "{e}");
    // An efficiency on a revolute joint is a modelling error, named as such.
    let e = compile_error(Dynamics::new().with_efficiency(Efficiency::new("O", 0.9)));
    assert!(e.contains("rack-and-pinion or gear"), "{e}");
}

#[test]
fn negative_mass_or_inertia_is_rejected() {
    for (mass, moment) in [(-1.0, 0.1), (1.0, -0.1)] {
        let r = Mechanism::builder()
            .point("O", [0.0, 0.0])
            .point("A", [1.0, 0.0])
            .ground(["O"])
            .link("crank", ["O", "A"])
            .inertia(
                "crank",
                Inertia {
                    mass,
                    center: [0.5, 0.0],
                    moment,
                },
            )
            .revolute("O", "ground", "crank", "O")
            .drive(Drive::angle("O"))
            .build();
        let e = r.unwrap_err().to_string();
        assert!(e.contains("link `crank`") && e.contains("≥ 0"), "{e}");
    }
    let e = compile_error(Dynamics::new().with_motor(Motor {
        rotor_inertia: -1.0,
        ratio: 0.1,
        efficiency: 1.0,
    }));
    assert!(e.contains("rotor inertia"), "{e}");
}

#[test]
fn load_on_unknown_point_or_link_is_rejected() {
    let e = compile_error(Dynamics::new().with_load(Load::force("crank", "Z", [1.0, 0.0])));
    assert!(
        e.contains("unknown point `Z`") && e.contains("load 1"),
        "{e}"
    );
    let e = compile_error(Dynamics::new().with_load(Load::torque("arm", 1.0)));
    assert!(e.contains("unknown link `arm`"), "{e}");
    // A point that exists but is not on the loaded link.
    let e = compile_error(Dynamics::new().with_load(Load::force("ground", "A", [1.0, 0.0])));
    assert!(e.contains("not on link `ground`"), "{e}");
    let e = compile_error(Dynamics::new().with_friction(Friction::sliding("Q", 0.1)));
    assert!(e.contains("unknown joint `Q`"), "{e}");
}
