//! The drive torque of a slider-crank press over one revolution: masses, gravity, a pressing
//! force on part of the stroke and friction in the guide, with the torque checked against the
//! power balance. Run with `cargo run --release --example drive_torque`.

use mechdiff::core::DriveState;
use mechdiff::core::dynamics::run::run;
use mechdiff::core::dynamics::{Dynamics, Friction, Gravity, Load, Plan, Request};
use mechdiff::core::geometry::{Drive, Inertia, Mechanism, Solver};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // Crank O–A 0.1 m, rod A–B 0.4 m, slider B on the x axis; sketched at φ = 0.
    let m = Mechanism::builder()
        .point("O", [0.0, 0.0])
        .point("A", [0.1, 0.0])
        .point("B", [0.5, 0.0])
        .point("X", [1.0, 0.0])
        .ground(["O", "X"])
        .link("crank", ["O", "A"])
        .link("rod", ["A", "B"])
        .link("slider", ["B"])
        .inertia(
            "crank",
            Inertia {
                mass: 3.0,
                center: [0.03, 0.0],
                moment: 0.01,
            },
        )
        .inertia(
            "rod",
            Inertia {
                mass: 4.0,
                center: [0.25, 0.0],
                moment: 0.06,
            },
        )
        .inertia(
            "slider",
            Inertia {
                mass: 6.0,
                center: [0.5, 0.0],
                moment: 0.0,
            },
        )
        .revolute("O", "ground", "crank", "O")
        .revolute("A", "crank", "rod", "A")
        .revolute("B", "rod", "slider", "B")
        .prismatic("guide", "ground", ["O", "X"], "slider", "B")
        .drive(Drive::angle("O"))
        .build()?;
    // 2 kN against the slider while the crank turns from 200° to 330° (the pressing stroke).
    let dynamics = Dynamics::new()
        .with_gravity(Gravity::down(9.81))
        .with_load(
            Load::force("slider", "B", [-2000.0, 0.0])
                .active_between(200f64.to_radians(), 330f64.to_radians()),
        )
        .with_friction(Friction::sliding("guide", 0.1))
        .with_friction(Friction::revolute("O", 0.08, 0.02));
    let model = dynamics.compile(&m)?;
    let plan = Plan::for_requests(
        &[Request::DriveTorque, Request::PowerBalance],
        dynamics.available(&m),
    );
    println!("plan: {plan}");
    let phis: Vec<f64> = (0..=360).map(|d| f64::from(d).to_radians()).collect();
    let drive = DriveState::from_rpm(120.0);
    let result = run(&plan, &model, &Solver::default(), &phis, |_| drive)?;
    println!(" φ [°]   M [N m]   M from power balance [N m]");
    let mut peak = (0.0, 0.0f64);
    let mut worst = 0.0f64;
    for (deg, step) in result.steps.iter().enumerate() {
        let s = step.solution.as_ref().expect("planned");
        let balance = s.balance.torque.expect("ω ≠ 0");
        worst = worst.max((s.drive_torque - balance).abs());
        if s.drive_torque.abs() > peak.1.abs() {
            peak = (deg as f64, s.drive_torque);
        }
        if deg % 30 == 0 {
            println!("{deg:>5}  {:>9.3}  {balance:>9.3}", s.drive_torque);
        }
    }
    println!("peak drive torque {:.3} N m at φ = {}°", peak.1, peak.0);
    println!("largest difference between the two torques: {worst:.1e} N m");
    println!("evaluated: {:?}", result.trace);
    Ok(())
}
