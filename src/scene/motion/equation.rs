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
/// and the relation between the motor's torque and the kinetostatic drive torque; the gearbox
/// and the rotor's inertia reduced to the drive; `inertia`, a line of J(φ)'s range; what each
/// analysis finds and where it stops; the integration's tolerances and events.
pub fn describe(scene: &Scene, motion: &SceneMotion, effects: &Effects, inertia: &str) -> String {
    let units = &scene.units;
    let q =
        |v: f64, d: Dimension| format!("{} {}", significant(units.from_si(v, d)), units.symbol(d));
    let drive = scene.drive.kind;
    let inertia_unit = match drive {
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
    let gearbox = motor.map(|m| {
        format!(
            "  gearbox: τ = {} (drive speed / motor speed), η = {}; the rotor's J_d enters \
             the drive as J_d/τ² = {}\n",
            significant(m.ratio),
            significant(m.efficiency),
            q(m.rotor_inertia / (m.ratio * m.ratio), inertia_unit)
        )
    });
    if motion.flywheel > 0.0 {
        j.push(format!(
            "J_f (flywheel {})",
            q(motion.flywheel, inertia_unit)
        ));
    }
    out.push_str(&format!("  J = {}\n", j.join(" + ")));
    if let Some(g) = gearbox {
        out.push_str(&g);
    }
    out.push_str(inertia);
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
        Characteristic::Table(t) => {
            let points: Vec<String> = (t.points())
                .map(|(w, m)| format!("{} → {}", speed(w), torque(m)))
                .collect();
            format!(
                "a torque–speed table, interpolated linearly and its end segments extended \
                 ({})",
                points.join(", ")
            )
        }
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
    for f in &motion.find {
        let ratio = motor.map_or(1.0, |m| m.ratio);
        out.push_str(&format!("    {}\n", find_line(scene, motion, ratio, *f)));
    }
    let t = &motion.tolerances;
    let mut events = Vec::new();
    if effects.loads {
        let switches: Vec<String> = (d.data.loads.iter())
            .filter_map(|l| l.active)
            .flatten()
            .map(|a| q(a, drive.dimension()))
            .collect();
        if !switches.is_empty() {
            events.push(format!("load switches at {}", switches.join(", ")));
        }
    }
    if drive == DriveKind::Angle {
        events.push("turn ends".to_owned());
    }
    if motion.finds(Find::StartUp) {
        events.push("the start-up's speed".to_owned());
    }
    events.push("rest".to_owned());
    out.push_str(&format!(
        "  integration: relative tolerance {:e} and absolute {:e} per step, at most {} steps a \
         run; located as events (never stepped over): {}\n",
        t.relative,
        t.absolute,
        t.max_steps,
        events.join(", ")
    ));
    out
}

/// What the analysis `find` does and where it stops, in the scene's units.
fn find_line(scene: &Scene, motion: &SceneMotion, ratio: f64, find: Find) -> String {
    let units = &scene.units;
    let drive = scene.drive.kind;
    let q =
        |v: f64, d: Dimension| format!("{} {}", significant(units.from_si(v, d)), units.symbol(d));
    let start = q(motion.start, drive.dimension());
    let time = significant(motion.time);
    match find {
        Find::StartUp => {
            let speed = match motion.speed {
                Some(w) => q(w, drive.speed_dimension()),
                None => match start_up_speed(motion, ratio) {
                    Some(w) => format!(
                        "{} (0.95 × the motor's no-load speed through the gearbox)",
                        q(w, drive.speed_dimension())
                    ),
                    None => "the motor's no-load speed (none: give `speed`)".to_owned(),
                },
            };
            format!(
                "start-up: from rest at {start} until the drive turns at {speed}, within \
                 {time} s (time to speed, peak motor torque)"
            )
        }
        Find::SteadyState => format!(
            "steady state: the periodic turn through {start}, by shooting on its start energy \
             E = ½·J·φ̇² in the energy form (over φ), at most {} turns; ω(φ), t(φ), period, \
             ω_min, ω_max, δ against the time mean 2π/T and the mid-range; checked by the same \
             turn integrated in time",
            motion.turns
        ),
        Find::CoastDown => format!(
            "coast-down: the motor off, from where the start-up ended (or from the steady \
             state) until rest, within {time} s"
        ),
        Find::Flywheel => {
            let mean = match motion.mean {
                mechdiff_core::machine::MeanSpeed::MidRange => "the mid-range (ω_max + ω_min)/2",
                _ => "the time mean 2π/T",
            };
            format!(
                "flywheel: on the drive shaft, for δ = {} against {mean}; exactly (the \
                 periodic solution iterated, each iteration at most {} turns) and by the \
                 classic energy method",
                significant(motion.delta.unwrap_or(0.02)),
                motion.turns
            )
        }
    }
}

/// The speed a start-up runs to when `[simulate] speed` is not given: 0.95 of the motor's
/// no-load speed through the gearbox (none for a characteristic without one);
/// `ratio` is the gearbox's τ (1 without a motor), as [`mechdiff_core::machine::Machine::ratio`].
pub(crate) fn start_up_speed(motion: &SceneMotion, ratio: f64) -> Option<f64> {
    let no_load = motion.characteristic.no_load_speed()?;
    Some(0.95 * no_load * ratio.abs())
}
