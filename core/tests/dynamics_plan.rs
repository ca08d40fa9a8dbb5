//! The plan: the derivative order and the effects the requested outputs need, and the proof
//! (the run's trace) that nothing else is evaluated.

use crate::common;
use mechdiff_core::DriveState;

use common::slider_crank_parts;
use mechdiff_core::Error;
use mechdiff_core::balancing::{Counterweight, LinkageBalancing, balance_linkage};
use mechdiff_core::dynamics::run::{run, step_at};
use mechdiff_core::dynamics::{
    CompiledModel, Dynamics, Effects, Friction, Gravity, Load, Plan, Request, Trace,
};
use mechdiff_core::geometry::{Drive, Inertia, Mechanism, Solver, Tracker};
use mechdiff_core::sweep::{Collect, Consumer, Stream, Sweep};

/// A slider-crank with masses, gravity, a load and friction data: every effect available.
fn slider_crank() -> (Mechanism, Dynamics) {
    let m = slider_crank_parts(0.1, 0.4, 0.0)
        .inertia(
            "crank",
            Inertia {
                mass: 1.0,
                center: [0.05, 0.0],
                moment: 0.001,
            },
        )
        .inertia(
            "rod",
            Inertia {
                mass: 2.0,
                center: [0.3, 0.0],
                moment: 0.03,
            },
        )
        .inertia(
            "slider",
            Inertia {
                mass: 1.5,
                center: [0.5, 0.0],
                moment: 0.0,
            },
        )
        .drive(Drive::angle("O"))
        .build()
        .unwrap();
    let d = Dynamics::new()
        .with_gravity(Gravity::down(9.81))
        .with_load(Load::force("slider", "B", [-50.0, 0.0]))
        .with_friction(Friction::sliding("guide", 0.1));
    (m, d)
}

fn phis() -> Vec<f64> {
    (1..=36)
        .map(|i| f64::from(i) * 10f64.to_radians())
        .collect()
}

#[test]
fn plan_names_the_order_and_the_effects() {
    let (m, d) = slider_crank();
    let available = d.available(&m);
    assert_eq!(
        available,
        Effects {
            inertia: true,
            gravity: true,
            loads: true,
            friction: true,
            ..Effects::none()
        }
    );
    let p = |r: &[Request]| Plan::for_requests(r, available);
    assert_eq!(p(&[Request::Positions]).order, 0);
    assert_eq!(p(&[Request::Velocities, Request::KineticEnergy]).order, 1);
    assert_eq!(p(&[Request::Jerk]).order, 3);
    assert_eq!(
        p(&[Request::ShakingForce]).to_string(),
        "order 2; effects: inertia; not computed: gravity, loads, friction, efficiency, motor"
    );
    assert_eq!(
        p(&[Request::DriveTorque]).to_string(),
        "order 2; effects: inertia, gravity, loads, friction; not computed: efficiency, motor"
    );
    // Forces without masses need velocities only (friction directions, powers).
    let no_mass = Effects {
        inertia: false,
        ..available
    };
    assert_eq!(Plan::for_requests(&[Request::Reactions], no_mass).order, 1);
}

#[test]
fn unrequested_effects_are_not_evaluated() {
    let (m, d) = slider_crank();
    let model = d.compile(&m).unwrap();
    let available = d.available(&m);
    let drive = |_| DriveState::constant_speed(10.0);
    let go = |requests: &[Request]| {
        let plan = Plan::for_requests(requests, available);
        run(&plan, &model, &Solver::default(), &phis(), drive).unwrap()
    };
    let n = phis().len();
    // Positions only: no derivative, no effect.
    let t = go(&[Request::Positions]).trace;
    assert_eq!(
        (t.positions, t.derivatives, t.inertia, t.equilibrium_solves),
        (n, 0, 0, 0)
    );
    // Accelerations: derivatives, still no effect.
    let t = go(&[Request::Accelerations]).trace;
    assert_eq!(
        (t.derivatives, t.inertia, t.gravity, t.equilibrium_solves),
        (n, 0, 0, 0)
    );
    // Shaking force: inertia only, no equilibrium solve, no gravity, loads or friction.
    let r = go(&[Request::ShakingForce]);
    let t = r.trace;
    assert_eq!(
        (
            t.shaking,
            t.inertia,
            t.gravity,
            t.loads,
            t.friction,
            t.equilibrium_solves
        ),
        (n, n, 0, 0, 0, 0)
    );
    assert!(
        r.steps
            .iter()
            .all(|s| s.shaking.is_some() && s.solution.is_none() && s.energy.is_none())
    );
    // Drive torque: every available effect, friction iterating (more solves than positions).
    let r = go(&[Request::DriveTorque]);
    let t = r.trace;
    assert_eq!(
        (t.inertia, t.gravity, t.loads, t.efficiency, t.motor),
        (n, n, n, 0, 0)
    );
    assert!(t.friction >= n && t.equilibrium_solves > n, "{t:?}");
    // The balance closes with every effect on (1e-9 of the largest power term).
    for s in r.steps.iter().map(|s| s.solution.as_ref().unwrap()) {
        assert!(s.balance.residual.abs() <= 1e-9 * s.balance.scale());
    }
}

#[test]
fn kinetic_energy_at_order_one_has_no_derivative_terms() {
    let (m, d) = slider_crank();
    let model = d.compile(&m).unwrap();
    let plan = Plan::for_requests(&[Request::KineticEnergy], d.available(&m));
    let r = run(&plan, &model, &Solver::default(), &phis(), |_| {
        DriveState::constant_speed(10.0)
    })
    .unwrap();
    let full = Plan::for_requests(&[Request::ReducedInertia], d.available(&m));
    let r2 = run(&full, &model, &Solver::default(), &phis(), |_| {
        DriveState::constant_speed(10.0)
    })
    .unwrap();
    for (a, b) in r.steps.iter().zip(&r2.steps) {
        let (a, b) = (a.energy.unwrap(), b.energy.unwrap());
        assert!(a.reduced_inertia_derivative.is_none() && b.reduced_inertia_derivative.is_some());
        // Same J_red from first-order and second-order jets (identical arithmetic).
        assert_eq!(a.reduced_inertia, b.reduced_inertia);
    }
}

#[test]
fn reduced_inertia_derivative_matches_a_central_difference() {
    // dJ_red/dφ against (J(φ+h) − J(φ−h))/2h with h = 1e-5: truncation ~h²·J‴ ≈ 1e-10 of J,
    // rounding ~1e-16/h ≈ 1e-11; 1e-8 relative to max |J′| leaves margin.
    let (m, d) = slider_crank();
    let model = d.compile(&m).unwrap();
    let plan = Plan::for_requests(&[Request::ReducedInertia], d.available(&m));
    let h = 1e-5;
    let mut pairs = Vec::new();
    for phi in phis() {
        let r = run(
            &plan,
            &model,
            &Solver::default(),
            &[phi - h, phi, phi + h],
            |_| DriveState::constant_speed(1.0),
        )
        .unwrap();
        let e: Vec<_> = r.steps.iter().map(|s| s.energy.unwrap()).collect();
        let fd = (e[2].reduced_inertia - e[0].reduced_inertia) / (2.0 * h);
        pairs.push((e[1].reduced_inertia_derivative.unwrap(), fd));
    }
    let scale = pairs.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
    let err = pairs.iter().map(|p| (p.0 - p.1).abs()).fold(0.0, f64::max) / scale;
    assert!(err <= 1e-8, "{err:e}");
}

/// The drive torque of a planned step at the pose a [`Sweep`] solved.
struct DriveTorque<'a, 'm> {
    plan: &'a Plan,
    model: &'a CompiledModel<'m>,
    drive: DriveState,
    trace: Trace,
}

impl Consumer for DriveTorque<'_, '_> {
    fn at(&mut self, t: &Tracker<'_>, phi: f64, row: &mut Vec<f64>) -> Result<(), Error> {
        let step = step_at(self.plan, self.model, t, phi, self.drive, &mut self.trace)?;
        row.push(step.solution.expect("planned").drive_torque);
        Ok(())
    }
}

/// One sweep feeds the planned dynamics and a counterweight being sized: 36 positions, 36
/// moves of the tracker (counted, exact), 36 steps evaluated; the numbers are bit for bit
/// those of the planned run and of `balance_linkage` walking the positions on their own
/// (each with a tracker of its own): lifting a solved pose again gives the same jets.
#[test]
fn one_sweep_feeds_the_dynamics_and_the_counterweights_each_position_once() {
    let (m, d) = slider_crank();
    let plan = Plan::for_requests(&[Request::DriveTorque], d.available(&m));
    let model = d.compile(&m).unwrap();
    let drive = DriveState::constant_speed(10.0);
    let counterweights = [Counterweight {
        link: "crank".to_owned(),
        line: ["O".to_owned(), "A".to_owned()],
        radius: 0.05,
    }];
    let mut torque = DriveTorque {
        plan: &plan,
        model: &model,
        drive,
        trace: Trace::default(),
    };
    let mut balancing = LinkageBalancing::new(&m, &d, &counterweights, drive).unwrap();
    let mut rows = Collect::default();
    let report = Sweep::new(&m, &Solver::default())
        .unwrap()
        .with(&mut torque)
        .with(&mut balancing)
        .run(phis(), &mut rows)
        .unwrap();
    assert_eq!((report.rows, report.solves), (36, 36));
    assert_eq!((torque.trace.positions, torque.trace.derivatives), (36, 36));
    let alone = run(&plan, &model, &Solver::default(), &phis(), |_| drive).unwrap();
    for (row, step) in rows.rows.iter().zip(&alone.steps) {
        assert_eq!(row.len(), 2, "the drive position, the torque");
        let want = step.solution.as_ref().unwrap().drive_torque;
        assert_eq!(row[1].to_bits(), want.to_bits(), "φ = {}", row[0]);
    }
    let sized = balancing.finish().unwrap();
    let solver = Solver::default();
    let own = balance_linkage(&m, &d, &counterweights, &phis(), drive, &solver).unwrap();
    assert_eq!(sized, own);
    assert!(sized.after.max_force() < sized.before.max_force());
}

/// Rows stream through a [`Stream`] sink as they come; a sink's error stops the sweep at
/// its row, after the rows before it.
#[test]
fn a_streaming_sink_sees_each_row_and_its_error_stops_the_sweep() {
    let (m, _) = slider_crank();
    let mut seen = Vec::new();
    let mut sink = Stream(|row: &[f64]| {
        seen.push(row[0]);
        if seen.len() == 3 {
            return Err(Error::MissingData {
                what: "the test's sink".to_owned(),
                missing: "room".to_owned(),
            });
        }
        Ok(())
    });
    let e = Sweep::new(&m, &Solver::default())
        .unwrap()
        .run(phis(), &mut sink)
        .unwrap_err();
    assert!(matches!(e, Error::MissingData { .. }), "{e:?}");
    assert_eq!(seen, phis()[..3]);
}
