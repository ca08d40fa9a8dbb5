//! Define a four-bar by its sketch alone, sweep the crank, and print the rocker's angle,
//! angular velocity and angular acceleration at 120 rpm, with exact derivatives.
//!
//! Run with `cargo run -p mechdiff-core --example define_a_four_bar`.

use mechdiff_core::DriveState;
use mechdiff_core::geometry::{Drive, Mechanism, Solver, check_mobility};

fn main() -> Result<(), mechdiff_core::Error> {
    // Ground pivots A0, B0; crank A0–A (0.2 m), coupler A–B (0.6 m), rocker B0–B (0.5 m).
    // B is drawn above the line A–B0: that fixes the assembly branch.
    let m = Mechanism::builder()
        .point("A0", [0.0, 0.0])
        .point("B0", [0.7, 0.0])
        .point("A", [0.2, 0.0])
        .point("B", [0.56, 0.48]) // |AB| = 0.6, |B0B| = 0.5
        .ground(["A0", "B0"])
        .link("crank", ["A0", "A"])
        .link("coupler", ["A", "B"])
        .link("rocker", ["B0", "B"])
        .revolute("A0", "ground", "crank", "A0")
        .revolute("A", "crank", "coupler", "A")
        .revolute("B", "coupler", "rocker", "B")
        .revolute("B0", "ground", "rocker", "B0")
        .drive(Drive::angle("A0"))
        .build()?;
    let mobility = check_mobility(&m)?;
    println!(
        "{} coordinates, Grübler F = {}",
        mobility.coordinates, mobility.degrees_of_freedom
    );

    let drive = DriveState::from_rpm(120.0);
    let phis: Vec<f64> = (0..=12).map(|i| (30.0 * i as f64).to_radians()).collect();
    println!("   φ (°)    ψ (°)   ψ̇ (rad/s)   ψ̈ (rad/s²)");
    for k in Solver::default().sweep::<2>(&m, &phis)? {
        let psi = k.angle("rocker", "B0", "B")?.motion(&drive);
        println!(
            "{:8.1} {:8.3} {:11.5} {:12.5}",
            k.phi.to_degrees(),
            psi.position.to_degrees(),
            psi.velocity,
            psi.acceleration
        );
    }
    Ok(())
}
