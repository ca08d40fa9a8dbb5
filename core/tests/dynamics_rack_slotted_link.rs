//! Mechanism 001 (gear rack, slotted link, coupler rod, slider on an incline) with the dynamic
//! data of rack_slotted_link_001.json (`dynamics_example_data`): the 12 unknowns and the power
//! terms of the worked example, from the generic effects.
//!
//! How the example's pieces map onto the generic model:
//! - motor + gearbox T1 (J_d, τ1, η1): a [`Motor`] at the drive joint (the gear wheel's
//!   revolute `W`); the kinetostatics give the wheel torque M′_d, the motor turns it into M_d;
//! - gear wheel and rack T2 (R, η2): a rack-and-pinion joint `mesh` with an [`Efficiency`]
//!   driven from the pinion;
//! - pin A in the slot: a massless block hinged to the rack (revolute `A`) sliding in the
//!   link's slot (prismatic `slot`), so ρ3 is the slot's displacement; friction f_k1 there;
//! - slider on the incline: prismatic `incline` with friction f_k2 acting h_D below D
//!   (contact offset −h_D along n8); its reaction couple is M_1;
//! - F: an external force −F u8 at the slider's point E = D + e_E n8.

use mechdiff_core::DriveState;
use mechdiff_core::dynamics::{
    Dynamics, Efficiency, Friction, Gravity, Load, Motor, Plan, Request, Solution, energy,
    kinetostatics,
};
use mechdiff_core::geometry::{Drive, Inertia, Mechanism, Solver};

// Table 1 of the source and the assumptions of rack_slotted_link_001.json.
const RHO1: f64 = 0.332;
const RHO2: f64 = 0.25;
/// ρ4 at θ3 = 63° (`rho4_m_30digits`).
const RHO4: f64 = 0.419162449232150365090550694535;
const RHO5: f64 = 1.065;
const RHO6: f64 = 0.723;
const RHO7: f64 = 0.458;
const RHO9: f64 = 0.234;
const R: f64 = 0.04;
const H_D: f64 = 0.04;
const E_E: f64 = 0.06;
const F: f64 = 200.0;

/// The reference unknowns (`dynamics.unknowns`).
const M_D: f64 = 0.9981773363503413;
const H_B: f64 = -268.8517356872072;
const V_B: f64 = 471.08699787976;
const H_C: f64 = -369.30708370188097;
const V_C: f64 = -199.1017823427619;
const H_DD: f64 = 369.30708370188097;
const V_D: f64 = 199.1017823427619;
const N_A: f64 = -665.3467565761739;
const T_A: f64 = 99.80201348642608;
const N_1: f64 = 279.13842511199397;
const T_1: f64 = -55.827685022398796;
const M_1: f64 = -9.766892599104049;

/// Mechanism 001 sketched at θ3 = 63°, primary closure (slider beyond C), driven by the
/// gear wheel's angle, with the masses of the example: link 6 kg, J_G1 = 0.55 kg·m² at G1;
/// slider 12 kg at D; rack 10 kg; rod, block and wheel massless.
fn mechanism() -> Mechanism {
    let th3 = 63f64.to_radians();
    let (th7, th8) = (285f64.to_radians(), 60f64.to_radians());
    let b = [RHO2, -RHO1];
    let e3 = [th3.cos(), th3.sin()];
    let u8 = [th8.cos(), th8.sin()];
    let n8 = [-u8[1], u8[0]];
    let c = [b[0] + RHO5 * e3[0], b[1] + RHO5 * e3[1]];
    let g1 = [b[0] + RHO9 * e3[0], b[1] + RHO9 * e3[1]];
    let p = [b[0] + RHO7 * th7.cos(), b[1] + RHO7 * th7.sin()];
    let cp = [c[0] - p[0], c[1] - p[1]];
    let proj = cp[0] * u8[0] + cp[1] * u8[1];
    let rho8 = proj + (proj * proj - (cp[0] * cp[0] + cp[1] * cp[1]) + RHO6 * RHO6).sqrt();
    let d = [p[0] + rho8 * u8[0], p[1] + rho8 * u8[1]];
    let e = [d[0] + E_E * n8[0], d[1] + E_E * n8[1]];
    Mechanism::builder()
        .point("O'", [0.0, 0.0])
        .point("X", [1.0, 0.0])
        .point("A", [RHO4, 0.0])
        .point("B", b)
        .point("C", c)
        .point("G1", g1)
        .point("P", p)
        .point("P2", [p[0] + u8[0], p[1] + u8[1]])
        .point("D", d)
        .point("E", e)
        .point("W", [RHO4, R])
        .ground(["O'", "X", "B", "P", "P2", "W"])
        .link("rack", ["A"])
        .link("block", ["A"])
        .link("slotted link", ["B", "C", "G1"])
        .link("rod", ["C", "D"])
        .link("slider", ["D", "E"])
        .link("pinion", ["W"])
        .inertia(
            "slotted link",
            Inertia {
                mass: 6.0,
                center: g1,
                moment: 0.55,
            },
        )
        .inertia(
            "slider",
            Inertia {
                mass: 12.0,
                center: d,
                moment: 0.0,
            },
        )
        .inertia(
            "rack",
            Inertia {
                mass: 10.0,
                center: [RHO4, 0.0],
                moment: 0.0,
            },
        )
        .prismatic("rack guide", "ground", ["O'", "X"], "rack", "A")
        .revolute("A", "rack", "block", "A")
        .prismatic("slot", "slotted link", ["B", "C"], "block", "A")
        .revolute("B", "ground", "slotted link", "B")
        .revolute("C", "slotted link", "rod", "C")
        .revolute("D", "rod", "slider", "D")
        .prismatic("incline", "ground", ["P", "P2"], "slider", "D")
        .revolute("W", "ground", "pinion", "W")
        .rack_pinion("mesh", "W", "rack guide", R)
        .drive(Drive::angle("W"))
        .build()
        .unwrap()
}

fn dynamics() -> Dynamics {
    let u8 = [60f64.to_radians().cos(), 60f64.to_radians().sin()];
    Dynamics::new()
        .with_gravity(Gravity::down(9.81))
        .with_load(Load::force("slider", "E", [-F * u8[0], -F * u8[1]]))
        .with_friction(Friction::sliding("slot", 0.15))
        .with_friction(Friction::sliding("incline", 0.20).with_contact_offset(-H_D))
        .with_efficiency(Efficiency::new("mesh", 0.95))
        .with_motor(Motor {
            rotor_inertia: 0.002,
            ratio: 1.0 / 30.0,
            efficiency: 0.90,
        })
}

/// ω1 = v_A/R = 1.25 rad/s, ω̇1 = a_A/R = 0.05 rad/s² (`dynamics.gear`).
const DRIVE: DriveState = DriveState::accelerating(1.25, 0.05);

fn solve() -> Solution {
    let m = Box::leak(Box::new(mechanism()));
    let d = dynamics();
    let model = Box::leak(Box::new(d.compile(m).unwrap()));
    let plan = Plan::for_requests(&[Request::Reactions, Request::DriveTorque], d.available(m));
    let t = Solver::default().track(m).unwrap();
    kinetostatics::solve(model, &plan.effects, &t.kinematics::<2>().unwrap(), &DRIVE).unwrap()
}

/// 1e-6 relative (the criterion for reference 001).
fn close(name: &str, got: f64, want: f64) {
    let err = (got - want).abs() / want.abs();
    println!("{name}: {got} (reference {want}), relative error {err:.1e}");
    assert!(
        err <= 1e-6,
        "{name}: got {got}, want {want}, relative error {err:e}"
    );
}

#[test]
fn twelve_unknowns_match_the_worked_example() {
    let s = solve();
    let r = |name: &str| {
        s.reactions
            .iter()
            .find(|r| r.joint == name)
            .unwrap()
            .clone()
    };
    let motor = s.motor.unwrap();
    close("M_d", motor.torque, M_D);
    close("M'_d (wheel)", s.drive_torque, 26.869788081459216);
    // Ground on link at B: the revolute's force on its link b.
    close("H_B", r("B").force[0], H_B);
    close("V_B", r("B").force[1], V_B);
    // Rod on link at C: minus the force of the link (a) on the rod (b).
    close("H_C", -r("C").force[0], H_C);
    close("V_C", -r("C").force[1], V_C);
    // Rod on slider at D: the revolute's force on the slider (b).
    close("H_D", r("D").force[0], H_DD);
    close("V_D", r("D").force[1], V_D);
    // Pin on link, along n3 and e3: minus the link's normal and friction force on the block.
    close("N_A", -r("slot").normal, N_A);
    close("T_A", -r("slot").friction, T_A);
    // Plane on slider: the prismatic joint's normal force, friction and couple on the slider.
    close("N_1", r("incline").normal, N_1);
    close("T_1", r("incline").friction, T_1);
    close("M_1", r("incline").couple, M_1);
    // Tooth force on the rack: η2 M′_d / R (`newton_euler_check.F_gear_on_rack_N`).
    close("F_gear_on_rack", r("mesh").normal, 638.1574669346563);
}

#[test]
fn power_terms_match_the_worked_example_and_the_balance_closes() {
    let s = solve();
    let b = s.balance;
    let motor = s.motor.unwrap();
    let mesh = s.reactions.iter().find(|r| r.joint == "mesh").unwrap();
    close("W_d", b.drive, 37.4316501131378);
    close("W_e1", motor.gearbox_input, 37.3191501131378);
    close("W_lost1", motor.gearbox_loss, -3.73191501131378);
    close("W_lost2", mesh.power_loss, -1.679361755091201);
    close("W_lost3 (friction)", b.friction, -7.016782674342553);
    close("W_r (F, weights)", b.loads + b.gravity, -24.950306305786217);
    close("W_i", -b.kinetic_rate, -0.053284366604046174);
    // The balance (1.30) closes up to rounding: 1e-12 of the drive power.
    assert!(
        b.residual.abs() <= 1e-12 * b.drive,
        "residual {}",
        b.residual
    );
    close("M_d from the power balance", b.torque.unwrap(), M_D);
}

#[test]
fn kinetic_energy_and_reduced_inertia() {
    let m = mechanism();
    let d = dynamics();
    let model = d.compile(&m).unwrap();
    let k = Solver::default()
        .track(&m)
        .unwrap()
        .kinematics::<2>()
        .unwrap();
    let e = energy(&model, &k.coordinates, &DRIVE);
    close("T", e.kinetic, 1.4684885471242257);
    close("dT/dt", e.kinetic_rate.unwrap(), 0.053284366604046174);
}

#[test]
fn friction_and_efficiency_not_in_the_plan_are_not_evaluated() {
    let m = mechanism();
    let d = dynamics();
    let model = d.compile(&m).unwrap();
    let k = Solver::default()
        .track(&m)
        .unwrap()
        .kinematics::<2>()
        .unwrap();
    let available = d.available(&m);
    let full = kinetostatics::solve(&model, &available, &k, &DRIVE).unwrap();
    assert!(full.trace.friction > 0 && full.trace.efficiency > 0 && full.trace.gravity == 1);
    // Inertia only: nothing else is evaluated, one solve.
    let plan = Plan::for_requests(&[Request::ShakingForce], available);
    let only = kinetostatics::solve(&model, &plan.effects, &k, &DRIVE).unwrap();
    let t = only.trace;
    assert_eq!(
        (
            t.inertia,
            t.gravity,
            t.loads,
            t.friction,
            t.efficiency,
            t.motor
        ),
        (1, 0, 0, 0, 0, 0)
    );
    assert_eq!(t.equilibrium_solves, 1);
    assert!(only.motor.is_none());
    // Without friction and efficiency (and no motor), the balance holds with no losses.
    assert_eq!((only.balance.friction, only.balance.efficiency), (0.0, 0.0));
}

#[test]
fn wheel_bearing_carries_the_tooth_force() {
    // The massless wheel is held by its bearing against the rack's tangential tooth force
    // M′_d/R (before η2: the wheel is the mesh's driving side), horizontal.
    let s = solve();
    let w = s.reactions.iter().find(|r| r.joint == "W").unwrap();
    let want = 26.869788081459216 / R;
    // 1e-12 relative: one LU solve, exact up to rounding.
    assert!(
        (w.force[0] - want).abs() <= 1e-12 * want,
        "{:?} vs {want}",
        w.force
    );
    assert!(w.force[1].abs() <= 1e-12 * want, "{:?}", w.force);
}

#[test]
fn friction_circle_in_the_wheel_bearing_closes_the_power_balance() {
    // Friction in the pinion's bearing depends on the tooth force it carries; the balance
    // closes only if the equilibrium uses the same |R| as the reported loss.
    let m = mechanism();
    let d = dynamics().with_friction(Friction::revolute("W", 0.1, 0.01));
    let model = d.compile(&m).unwrap();
    let mut t = Solver::default().track(&m).unwrap();
    for phi in [0.0, -0.5, -1.0, 0.5, 1.0] {
        t.move_to(phi).unwrap();
        let s = kinetostatics::solve(
            &model,
            &d.available(&m),
            &t.kinematics::<2>().unwrap(),
            &DRIVE,
        )
        .unwrap();
        let b = s.balance;
        let w = s.reactions.iter().find(|r| r.joint == "W").unwrap();
        // The bearing's loss is f·r·|R|·ω with |R| the tooth-force-carrying reaction.
        let loss = 0.1 * 0.01 * w.force[0].hypot(w.force[1]) * DRIVE.omega;
        assert!(
            (w.power_loss + loss).abs() <= 1e-12 * loss,
            "{} vs {loss}",
            w.power_loss
        );
        // 1e-9 relative to the largest power term (the criterion).
        assert!(
            b.residual.abs() <= 1e-9 * b.scale(),
            "φ = {phi}: residual {}",
            b.residual
        );
    }
}
