//! The plan of a run with `[simulate]`: the equation of motion with exactly the terms the
//! scene gives, in its words and units.

use mechdiff_core::dynamics::Effects;
use mechdiff_core::machine::Characteristic;

use crate::scene::model::{DriveKind, Scene};
use crate::scene::units::Dimension;

use super::format::Find;
use super::model::SceneMotion;
use super::words::significant;

/// The equation of motion the run integrates, one line per term the scene gives (masses,
/// rotor, flywheel; weights, loads with their ranges, friction, efficiencies; the motor),
/// and the relation between the motor's torque and the kinetostatic drive torque.
pub fn describe(scene: &Scene, motion: &SceneMotion, effects: &Effects) -> String {
    let units = &scene.units;
    let q =
        |v: f64, d: Dimension| format!("{} {}", significant(units.from_si(v, d)), units.symbol(d));
    let drive = scene.drive.kind;
    let inertia = match drive {
        DriveKind::Angle => Dimension::MomentOfInertia,
        DriveKind::Displacement => Dimension::Mass,
    };
    let Some(d) = &scene.dynamics else {
        return String::new();
    };
    let mut out = String::from(
        "the machine in motion: J(φ)·φ̈ + ½·J′(φ)·φ̇² = M_motor(φ̇/τ)/τ − M_res(φ, φ̇), \
         integrated by DOP853",
    );
    out.push_str(&format!(
        " (tolerance {:e} per step, at most {} steps a run)\n",
        motion.tolerances.relative, motion.tolerances.max_steps
    ));
    let mut j = Vec::new();
    if effects.inertia {
        let links: Vec<&str> = d.masses.iter().map(|(l, _)| l.as_str()).collect();
        j.push(format!("J_m(φ) of the masses of {}", links.join(", ")));
    }
    let motor = d.data.motor.filter(|_| effects.motor);
    if let Some(m) = motor {
        j.push(format!(
            "J_d/τ² (rotor {}, τ = {})",
            q(m.rotor_inertia, Dimension::MomentOfInertia),
            significant(m.ratio)
        ));
    }
    if motion.flywheel > 0.0 {
        j.push(format!("J_f (flywheel {})", q(motion.flywheel, inertia)));
    }
    out.push_str(&format!("  J = {}\n", j.join(" + ")));
    let mut res = Vec::new();
    if effects.gravity
        && let Some(g) = &d.data.gravity
    {
        res.push(format!(
            "weights (g = {})",
            q(g.g[0].hypot(g.g[1]), Dimension::Acceleration)
        ));
    }
    if effects.loads {
        for l in &d.data.loads {
            let at = l
                .point
                .as_ref()
                .map_or(String::new(), |p| format!(" at `{p}`"));
            let range = match l.active {
                Some([a, b]) => format!(
                    ", acting for drive positions from {} to {}",
                    q(a, drive.dimension()),
                    q(b, drive.dimension())
                ),
                None => String::new(),
            };
            res.push(format!("a load on `{}`{at}{range}", l.link));
        }
    }
    if effects.friction {
        let joints: Vec<&str> = d.data.friction.iter().map(|f| f.joint.as_str()).collect();
        res.push(format!("Coulomb friction in {}", joints.join(", ")));
    }
    if effects.efficiency {
        let mut e: Vec<String> = (d.data.efficiency.iter())
            .map(|e| format!("`{}` η = {}", e.joint, significant(e.efficiency)))
            .collect();
        if let Some(m) = motor.filter(|m| m.efficiency < 1.0) {
            e.push(format!("the gearbox η = {}", significant(m.efficiency)));
        }
        res.push(format!(
            "efficiencies {} (losses against the power flow: 1/η driving, η driven back)",
            e.join(", ")
        ));
    }
    if effects.inertia {
        res.push("½·J_m′(φ)·φ̇² from the exact ψ″ (in the kinetostatics)".to_owned());
    }
    if res.is_empty() {
        out.push_str("  M_res = 0 (no weights, loads, friction or efficiencies)\n");
    } else {
        out.push_str(&format!("  M_res: {}\n", res.join("; ")));
    }
    let torque = |v: f64| q(v, Dimension::Torque);
    let speed = |v: f64| q(v, Dimension::AngularVelocity);
    let characteristic = match &motion.characteristic {
        Characteristic::ConstantTorque { torque: m } => format!("a constant torque {}", torque(*m)),
        Characteristic::Linear {
            stall_torque,
            no_load_speed,
        } => format!(
            "linear (DC shunt): {} at standstill, 0 at {}",
            torque(*stall_torque),
            speed(*no_load_speed)
        ),
        Characteristic::Induction {
            synchronous_speed,
            breakdown_torque,
            breakdown_slip,
        } => format!(
            "induction by Kloss: synchronous speed {}, breakdown torque {} at slip {}",
            speed(*synchronous_speed),
            torque(*breakdown_torque),
            significant(*breakdown_slip)
        ),
        Characteristic::Table(_) => "a torque–speed table, interpolated linearly".to_owned(),
        _ => "a characteristic".to_owned(),
    };
    out.push_str(&format!(
        "  M_motor: {characteristic}, on the motor shaft; the kinetostatic M_drive leaves out \
         the rotor's inertia torque: M_motor = J_d·φ̈/τ + τ·f·(M_drive + J_f·φ̈)\n"
    ));
    let finds: Vec<&str> = (motion.find.iter())
        .map(|f| match f {
            Find::StartUp => "start-up",
            Find::SteadyState => "steady state",
            Find::CoastDown => "coast-down",
            Find::Flywheel => "flywheel",
        })
        .collect();
    out.push_str(&format!("  finds: {}\n", finds.join(", ")));
    out
}
