//! The machine in motion under its motor (`machine`, feature `simulate`), checked against a
//! slider-crank's reduced equation of motion derived by hand and integrated here by the
//! classical fixed-step Runge–Kutta method (an independent integration: hand-written
//! position formulas, their φ-derivatives written out, J′ by a dual number of the hand
//! formula; nothing of the engine's geometry solver, kinetostatics or integrator).
#![cfg(feature = "simulate")]

use mechdiff_core::DriveState;
use mechdiff_core::Scalar;
use mechdiff_core::dynamics::{Dynamics, Effects, Load, Motor, energy, kinetostatics};
use mechdiff_core::geometry::{Drive, Inertia, Mechanism, Solver};
use mechdiff_core::machine::{
    Characteristic, EventKind, Machine, MeanSpeed, MotionError, Record, Start, SteadySettings,
    Stop, Tolerances, coast_down, flywheel, simulate, simulate_collect, start_up, steady_state,
};
use num_dual::Dual64;
use std::f64::consts::TAU;

/// Crank radius, rod length (m).
const R: f64 = 0.1;
const L: f64 = 0.4;
/// Crank: mass, centre on the crank, moment about the centre.
const M1: f64 = 1.0;
const C1: f64 = 0.03;
const I1: f64 = 0.001;
/// Rod: mass, centre from A along the rod, moment about the centre.
const M2: f64 = 1.0;
const C2: f64 = 0.15;
const I2: f64 = 0.012;
/// Slider mass.
const M3: f64 = 2.0;
/// Motor: rotor inertia, gear ratio τ = φ̇/ω_motor, linear characteristic.
const ROTOR: f64 = 1e-3;
const RATIO: f64 = 1.0 / 3.0;
const STALL: f64 = 20.0;
const NO_LOAD: f64 = 300.0;
/// A force against the slider, −F along x, on the crank range [FROM, TO].
const F: f64 = 100.0;
const FROM: f64 = 3.5;
const TO: f64 = 5.5;

/// The in-line slider-crank (guide through O along x), sketched at φ = 0.
fn slider_crank() -> Mechanism {
    Mechanism::builder()
        .point("O", [0.0, 0.0])
        .point("A", [R, 0.0])
        .point("B", [R + L, 0.0])
        .point("X", [1.0, 0.0])
        .ground(["O", "X"])
        .link("crank", ["O", "A"])
        .link("rod", ["A", "B"])
        .link("slider", ["B"])
        .inertia(
            "crank",
            Inertia {
                mass: M1,
                center: [C1, 0.0],
                moment: I1,
            },
        )
        .inertia(
            "rod",
            Inertia {
                mass: M2,
                center: [R + C2, 0.0],
                moment: I2,
            },
        )
        .inertia(
            "slider",
            Inertia {
                mass: M3,
                center: [R + L, 0.0],
                moment: 0.0,
            },
        )
        .revolute("O", "ground", "crank", "O")
        .revolute("A", "crank", "rod", "A")
        .revolute("B", "rod", "slider", "B")
        .prismatic("guide", "ground", ["O", "X"], "slider", "B")
        .drive(Drive::angle("O"))
        .build()
        .unwrap()
}

/// The effect data: the motor behind its gearbox and, with `load`, the switched force.
fn dynamics(load: bool) -> Dynamics {
    let d = Dynamics::new().with_motor(Motor {
        rotor_inertia: ROTOR,
        ratio: RATIO,
        efficiency: 1.0,
    });
    if load {
        d.with_load(Load::force("slider", "B", [-F, 0.0]).active_between(FROM, TO))
    } else {
        d
    }
}

fn linear_motor() -> Characteristic {
    Characteristic::Linear {
        stall_torque: STALL,
        no_load_speed: NO_LOAD,
    }
}

const ALL: Effects = Effects {
    inertia: true,
    gravity: false,
    loads: true,
    friction: false,
    efficiency: false,
    motor: true,
};

/// The slider's velocity coefficient x_B′ = −r sin φ − r² sin φ cos φ / √(l² − r² sin² φ).
fn slider_coefficient<T: Scalar>(phi: T) -> T {
    let (s, c) = phi.sin_cos();
    let w = (s * s * (-R * R) + L * L).sqrt();
    s * (-R) - s * c * (R * R) / w
}

/// The mechanism's reduced moment of inertia by hand: crank about O, rod centre
/// G = (1 − k)A + kB (k = c₂/l) with A′ = r(−sin φ, cos φ), B′ = (x_B′, 0), the rod's
/// angular coefficient β′ = −r cos φ / √(l² − r² sin² φ), the slider.
fn j_mechanism<T: Scalar>(phi: T) -> T {
    let (s, c) = phi.sin_cos();
    let w = (s * s * (-R * R) + L * L).sqrt();
    let xb = slider_coefficient(phi);
    let k = C2 / L;
    let gx = s * (-R * (1.0 - k)) + xb * k;
    let gy = c * (R * (1.0 - k));
    let beta = c * (-R) / w;
    T::from(M1 * C1 * C1 + I1) + (gx * gx + gy * gy) * M2 + beta * beta * I2 + xb * xb * M3
}

/// An event function of the reference integration, `g(φ, φ̇)`.
type EventFunction<'a> = dyn Fn([f64; 2]) -> f64 + 'a;

/// The hand model: J(φ) with the rotor (and a flywheel `fly`), J′(φ), and the reduced
/// torque `M_char(φ̇/τ)/τ + Q_load(φ)` with the load on or off.
struct Hand {
    fly: f64,
    motor: bool,
}

impl Hand {
    fn j(&self, phi: f64) -> f64 {
        let rotor = if self.motor {
            ROTOR / (RATIO * RATIO)
        } else {
            0.0
        };
        j_mechanism(phi) + rotor + self.fly
    }

    fn dj(&self, phi: f64) -> f64 {
        j_mechanism(Dual64::from(phi).derivative()).eps
    }

    fn torque(&self, phi: f64, omega: f64, load: bool) -> f64 {
        let motor = if self.motor {
            STALL * (1.0 - omega / RATIO / NO_LOAD) / RATIO
        } else {
            0.0
        };
        // The force −F along x has power −F ẋ_B = −F x_B′ φ̇.
        let q = if load {
            -F * slider_coefficient(phi)
        } else {
            0.0
        };
        motor + q
    }

    /// φ̈ from J φ̈ + ½ J′ φ̇² = M.
    fn alpha(&self, phi: f64, omega: f64, load: bool) -> f64 {
        (self.torque(phi, omega, load) - 0.5 * self.dj(phi) * omega * omega) / self.j(phi)
    }

    /// One classical Runge–Kutta step in time.
    fn rk4_time(&self, y: [f64; 2], h: f64, load: bool) -> [f64; 2] {
        let f = |y: [f64; 2]| [y[1], self.alpha(y[0], y[1], load)];
        let k1 = f(y);
        let k2 = f([y[0] + 0.5 * h * k1[0], y[1] + 0.5 * h * k1[1]]);
        let k3 = f([y[0] + 0.5 * h * k2[0], y[1] + 0.5 * h * k2[1]]);
        let k4 = f([y[0] + h * k3[0], y[1] + h * k3[1]]);
        [
            y[0] + h / 6.0 * (k1[0] + 2.0 * k2[0] + 2.0 * k3[0] + k4[0]),
            y[1] + h / 6.0 * (k1[1] + 2.0 * k2[1] + 2.0 * k3[1] + k4[1]),
        ]
    }

    /// Integrates in time from `y` at time 0 with steps of at most `h` until `stop(y)`
    /// changes sign; the last step is shortened (secant on its length) so that it ends on
    /// `stop = 0`. The load switches at FROM and TO are met the same way, exactly.
    fn time_until(
        &self,
        mut y: [f64; 2],
        h: f64,
        stop: impl Fn([f64; 2]) -> f64,
    ) -> (f64, [f64; 2]) {
        let mut t = 0.0;
        let load_at = |phi: f64| {
            let p = phi.rem_euclid(TAU);
            (FROM..=TO).contains(&p)
        };
        loop {
            let load = load_at(y[0] + 1e-9);
            let full = self.rk4_time(y, h, load);
            // The next angle where the load switches.
            let turn = (y[0] / TAU).floor() * TAU;
            let switch = [FROM, TO, FROM + TAU]
                .into_iter()
                .map(|a| turn + a)
                .find(|&a| a > y[0] + 1e-12)
                .unwrap_or(f64::INFINITY);
            let at_switch = |y: [f64; 2]| y[0] - switch;
            // (whether it is the stop, its function)
            let g: [(bool, &EventFunction); 2] = [(false, &at_switch), (true, &stop)];
            let mut hit: Option<(f64, bool)> = None;
            for (which, gf) in &g {
                if gf(y).signum() != gf(full).signum() && gf(y) != 0.0 {
                    // Secant on the step length.
                    let (mut a, mut b) = (0.0, h);
                    let (mut ga, mut gb) = (gf(y), gf(full));
                    for _ in 0..100 {
                        let c = b - gb * (b - a) / (gb - ga);
                        let gc = gf(self.rk4_time(y, c, load));
                        (a, ga, b, gb) = (b, gb, c, gc);
                        if gc.abs() < 1e-15 || (b - a).abs() < 1e-17 {
                            break;
                        }
                    }
                    // On a tie the stop (listed last) wins.
                    if hit.is_none_or(|(hh, _)| b <= hh) {
                        hit = Some((b, *which));
                    }
                }
            }
            match hit {
                Some((hh, which)) => {
                    y = self.rk4_time(y, hh, load);
                    t += hh;
                    if which {
                        return (t, y);
                    }
                    y[0] = switch;
                }
                None => {
                    y = full;
                    t += h;
                }
            }
        }
    }

    /// One turn of the energy form from φ = 0 with speed `omega0`, `n` steps (the load
    /// switches FROM and TO are step ends): (the end speed, the period, ω_min, ω_max).
    fn turn(&self, omega0: f64, n: usize) -> (f64, f64, f64, f64) {
        // y = (E, t); dE/dφ = M, dt/dφ = 1/φ̇, φ̇ = √(2E/J).
        let f = |phi: f64, y: [f64; 2], load: bool| {
            let w = (2.0 * y[0] / self.j(phi)).sqrt();
            [self.torque(phi, w, load), 1.0 / w]
        };
        let mut y = [0.5 * self.j(0.0) * omega0 * omega0, 0.0];
        let (mut lo, mut hi) = (omega0, omega0);
        let stretches = [(0.0, FROM, false), (FROM, TO, true), (TO, TAU, false)];
        for (a, b, load) in stretches {
            let steps = ((b - a) / TAU * n as f64).ceil() as usize;
            let h = (b - a) / steps as f64;
            for i in 0..steps {
                let p = a + i as f64 * h;
                let k1 = f(p, y, load);
                let k2 = f(
                    p + 0.5 * h,
                    [y[0] + 0.5 * h * k1[0], y[1] + 0.5 * h * k1[1]],
                    load,
                );
                let k3 = f(
                    p + 0.5 * h,
                    [y[0] + 0.5 * h * k2[0], y[1] + 0.5 * h * k2[1]],
                    load,
                );
                let k4 = f(p + h, [y[0] + h * k3[0], y[1] + h * k3[1]], load);
                for c in 0..2 {
                    y[c] += h / 6.0 * (k1[c] + 2.0 * k2[c] + 2.0 * k3[c] + k4[c]);
                }
                let w = (2.0 * y[0] / self.j(p + h)).sqrt();
                lo = lo.min(w);
                hi = hi.max(w);
            }
        }
        ((2.0 * y[0] / self.j(TAU)).sqrt(), y[1], lo, hi)
    }

    /// The periodic start speed at φ = 0 by secant steps on ω₀ ↦ ω(2π) − ω₀, from `guess`.
    fn periodic(&self, guess: f64, n: usize) -> f64 {
        let gap = |w: f64| self.turn(w, n).0 - w;
        let (mut a, mut b) = (guess * 0.99, guess);
        let (mut ga, mut gb) = (gap(a), gap(b));
        for _ in 0..50 {
            if gb == 0.0 || (b - a).abs() < 1e-15 * b {
                break;
            }
            let c = b - gb * (b - a) / (gb - ga);
            (a, ga) = (b, gb);
            b = c;
            gb = gap(b);
        }
        b
    }
}

fn tight() -> Tolerances {
    Tolerances::default()
        .with_relative(1e-13)
        .with_absolute(1e-13)
}

/// Without motor, load or friction, the kinetic energy ½J(φ)φ̇² stays what it was: over 100
/// turns from 10 rad/s, at every step, to 1e-10 relative (the hand J; DOP853 at 1e-13 per
/// step, some 5000 steps of errors that partly cancel), and one turn takes
/// T = ∫₀^2π √(J(φ)/(2E)) dφ — by the trapezoidal rule on 4096 points, exact to rounding
/// for this smooth periodic integrand — to 1e-10 relative.
#[test]
fn coasting_keeps_its_energy_and_turns_in_the_closed_form_period() {
    let m = slider_crank();
    let model = Dynamics::new().compile(&m).unwrap();
    let machine = Machine::new(
        &model,
        Effects {
            inertia: true,
            ..Effects::none()
        },
    );
    let hand = Hand {
        fly: 0.0,
        motor: false,
    };
    let omega0 = 10.0;
    let e0 = 0.5 * hand.j(0.0) * omega0 * omega0;
    let start = Start {
        time: 0.0,
        phi: 0.0,
        omega: omega0,
    };
    let mut worst = 0.0f64;
    let mut steps = 0;
    let stop = Stop {
        turns: Some(100.0),
        ..Stop::default()
    };
    let run = simulate(&machine, start, &stop, &tight(), &mut |r| {
        let s = match r {
            Record::Step(s) => s,
            Record::Event(e) => e.at,
        };
        steps += 1;
        let e = 0.5 * hand.j(s.phi) * s.omega * s.omega;
        worst = worst.max((e / e0 - 1.0).abs());
    })
    .unwrap();
    println!(
        "100 turns: {} steps, {} evaluations, worst relative energy change {worst:e}",
        run.steps, run.evaluations
    );
    assert!((run.end.phi - 100.0 * TAU).abs() < 1e-12 * 100.0 * TAU);
    assert!(worst < 1e-10, "{worst:e} over {steps} records");

    let n = 4096;
    let period: f64 = (0..n)
        .map(|i| (hand.j(TAU * i as f64 / n as f64) / (2.0 * e0)).sqrt())
        .sum::<f64>()
        * TAU
        / n as f64;
    let one = Stop {
        turns: Some(1.0),
        ..Stop::default()
    };
    let (turn, _) = simulate_collect(&machine, start, &one, &tight()).unwrap();
    println!("period {} s, closed form {period} s", turn.end.time);
    assert!(
        (turn.end.time / period - 1.0).abs() < 1e-10,
        "{} vs {period}",
        turn.end.time
    );
}

/// The drive torque leaves out the rotor and depends on φ̈ through the mechanism's reduced
/// inertia only: M_drive(φ, ω, α) = M_drive(φ, ω, 0) + J_m(φ) α (kinetostatics without
/// friction are linear in the inertial loads; virtual work), the relation the equation of
/// motion is built on — to 1e-12 of the torques' scale (one LU each, rounding only).
#[test]
fn drive_torque_grows_with_the_acceleration_by_the_reduced_inertia() {
    let m = slider_crank();
    let model = dynamics(true).compile(&m).unwrap();
    let effects = Effects {
        motor: false,
        ..ALL
    };
    let mut tracker = Solver::default().track(&m).unwrap();
    for phi in [0.3, 2.0, 4.0, 5.0] {
        tracker.move_to(phi).unwrap();
        let k = tracker.kinematics::<2>().unwrap();
        let at = |alpha: f64| {
            let d = DriveState {
                omega: 30.0,
                alpha,
                jerk: 0.0,
            };
            kinetostatics::solve(&model, &effects, &k, &d)
                .unwrap()
                .drive_torque
        };
        let jm = j_mechanism(phi);
        let e = energy(&model, &k.coordinates, &DriveState::constant_speed(1.0));
        // The energy module's J includes the rotor reduced by τ².
        assert!(
            (e.reduced_inertia - ROTOR / (RATIO * RATIO) - jm).abs() < 1e-13,
            "{phi}"
        );
        let (m0, m1) = (at(0.0), at(250.0));
        assert!(
            (m1 - m0 - jm * 250.0).abs() < 1e-12 * m1.abs().max(m0.abs()),
            "{phi}: {m0} {m1}"
        );
    }
}

/// Start-up from rest under the linear motor (the load acts from 3.5 rad, beyond the
/// start-up):
/// the time to 80 rad/s and the speed at t = 0.05 s agree with the hand equation integrated
/// by RK4 (steps of 2e-5 s; the reference's own error, seen as the change from 4e-5 s, is
/// below 1e-10) to 1e-8 relative; the engine's results at relative tolerance 1e-12 and
/// 5e-13 differ by less than 1e-8 relative too.
#[test]
fn start_up_agrees_with_an_independent_integration() {
    let m = slider_crank();
    let model = dynamics(true).compile(&m).unwrap();
    let machine = Machine::new(&model, ALL).with_motor(linear_motor());
    let hand = Hand {
        fly: 0.0,
        motor: true,
    };
    let speed = 80.0;
    let reference = |h: f64| hand.time_until([0.0, 0.0], h, |y| y[1] - speed).0;
    let (t_ref, t_coarse) = (reference(2e-5), reference(4e-5));
    println!("reference time to {speed} rad/s: {t_ref} s (step 4e-5 s: {t_coarse})");
    assert!((t_ref - t_coarse).abs() < 1e-10 * t_ref);
    let tol = |r: f64| Tolerances::default().with_relative(r).with_absolute(r);
    let s = start_up(&machine, 0.0, speed, 10.0, &tol(1e-12), &mut |_| {}).unwrap();
    let half = start_up(&machine, 0.0, speed, 10.0, &tol(5e-13), &mut |_| {}).unwrap();
    println!(
        "engine: {} s ({} steps, {} evaluations, peak motor torque {} N·m); at half the tolerance {} s",
        s.time_to_speed,
        s.simulation.steps,
        s.simulation.evaluations,
        s.peak_motor_torque,
        half.time_to_speed
    );
    assert!(
        (s.time_to_speed / t_ref - 1.0).abs() < 1e-8,
        "{} vs {t_ref}",
        s.time_to_speed
    );
    assert!((s.time_to_speed / half.time_to_speed - 1.0).abs() < 1e-8);
    // The linear motor's torque is largest at standstill.
    assert_eq!(s.peak_motor_torque, STALL);

    let at = 0.05;
    let stop = Stop {
        time: Some(at),
        ..Stop::default()
    };
    let (run, _) = simulate_collect(&machine, Start::at_rest(0.0), &stop, &tol(1e-12)).unwrap();
    // The reference stops at the engine's final angle (φ increases monotonically here):
    // there it must be at time 0.05 s with the same speed.
    let (t_ref, y) = hand.time_until([0.0, 0.0], 2e-5, |y| y[0] - run.end.phi);
    assert!((t_ref / at - 1.0).abs() < 1e-8, "{t_ref}");
    assert!(
        (run.end.omega / y[1] - 1.0).abs() < 1e-8,
        "{} vs {}",
        run.end.omega,
        y[1]
    );
}

/// A load switching at a crank angle is met as an event: the dense output meets the angle
/// to 1e-10 rad at the located time, and the hand equation (switches met exactly by RK4
/// step lengths) reaches that angle at a time that differs by less than 1e-10 rad worth of
/// motion (|Δt|·φ̇ < 1e-10).
#[test]
fn a_load_switch_is_located_at_its_crank_angle() {
    let m = slider_crank();
    let model = dynamics(true).compile(&m).unwrap();
    let machine = Machine::new(&model, ALL).with_motor(linear_motor());
    let hand = Hand {
        fly: 0.0,
        motor: true,
    };
    let stop = Stop {
        turns: Some(1.0),
        ..Stop::default()
    };
    let tol = Tolerances::default()
        .with_relative(1e-13)
        .with_absolute(1e-13);
    let (_, records) = simulate_collect(&machine, Start::at_rest(0.0), &stop, &tol).unwrap();
    let events: Vec<_> = records
        .iter()
        .filter_map(|r| match r {
            Record::Event(e) if e.kind == EventKind::LoadSwitch => Some(*e),
            _ => None,
        })
        .collect();
    assert_eq!(events.len(), 2, "{events:?}");
    for (e, angle) in events.iter().zip([FROM, TO]) {
        assert_eq!(e.at.phi, angle);
        assert!(e.residual < 1e-10, "{}", e.residual);
        let (t_ref, y) = hand.time_until([0.0, 0.0], 2e-5, |y| y[0] - angle);
        println!(
            "switch at {angle} rad: t = {} s, reference {t_ref} s, residual {:e}",
            e.at.time, e.residual
        );
        assert!(
            (e.at.time - t_ref).abs() * y[1] < 1e-10,
            "{} vs {t_ref}",
            e.at.time
        );
    }
}

/// The steady periodic state (shooting in the energy form) against the hand equation's
/// own periodic solution (secant on the start speed, RK4 turns of 40000 steps; the change
/// from 20000 steps is below 1e-10): the start speed, ω_min, ω_max and the period agree to
/// 1e-8 relative (ω_min/ω_max of the reference from its step ends, 1.6e-4 rad apart: a
/// grid error below 1e-9 relative); halving the tolerances moves them by less than 1e-8.
#[test]
fn steady_state_agrees_with_an_independent_periodic_solution() {
    let m = slider_crank();
    let model = dynamics(true).compile(&m).unwrap();
    let machine = Machine::new(&model, ALL).with_motor(linear_motor());
    let settings = SteadySettings::default();
    let mut samples = 0;
    let s = steady_state(&machine, &settings, &mut |_| samples += 1).unwrap();
    let halved = SteadySettings {
        tolerances: settings
            .tolerances
            .with_relative(5e-13)
            .with_absolute(5e-13),
        ..settings
    };
    let h = steady_state(&machine, &halved, &mut |_| {}).unwrap();
    println!("{s:#?}");
    let hand = Hand {
        fly: 0.0,
        motor: true,
    };
    let w0 = hand.periodic(s.omega, 40_000);
    let w0_coarse = hand.periodic(s.omega, 20_000);
    assert!((w0 / w0_coarse - 1.0).abs() < 1e-10);
    let (end, period, lo, hi) = hand.turn(w0, 40_000);
    assert!((end / w0 - 1.0).abs() < 1e-12);
    for (what, engine, reference, half) in [
        ("start speed", s.omega, w0, h.omega),
        ("period", s.period, period, h.period),
        ("ω_min", s.min.0, lo, h.min.0),
        ("ω_max", s.max.0, hi, h.max.0),
    ] {
        assert!(
            (engine / reference - 1.0).abs() < 1e-8,
            "{what}: {engine} vs {reference}"
        );
        assert!(
            (engine / half - 1.0).abs() < 1e-8,
            "{what}: {engine} vs {half}"
        );
    }
    assert!((s.mean_time - TAU / s.period).abs() < 1e-12 * s.mean_time);
    assert!(s.gain.abs() < 1e-9 * 0.5 * hand.j(0.0) * s.omega * s.omega);
    // The two formulations side by side: the same turn in time ((φ, φ̇) over t, its end
    // located as a turn event) takes the energy form's period and comes back to its start
    // speed, each to 1e-8 relative (both at 1e-12 per-step tolerances; the agreement is the
    // integrations' error, reported by `mechdiff run`).
    assert!(s.period_agreement() < 1e-8, "{:?}", s.in_time);
    assert!(s.speed_agreement() < 1e-8, "{:?}", s.in_time);
    assert!((s.in_time.period / period - 1.0).abs() < 1e-8);
}

/// The flywheel sized for δ = 0.02 (mid-range mean) gives, simulated as a steady state,
/// δ = 0.02 to 1e-6; the hand equation with that flywheel gives the same δ to 1e-6.
#[test]
fn flywheel_for_two_percent_gives_two_percent() {
    let m = slider_crank();
    let model = dynamics(true).compile(&m).unwrap();
    let machine = Machine::new(&model, ALL).with_motor(linear_motor());
    let settings = SteadySettings::default();
    let sizing = flywheel(&machine, 0.02, MeanSpeed::MidRange, &settings).unwrap();
    println!(
        "flywheel exact {} kg·m², classic {} kg·m² (ΔE_max {} J at {} rad/s), {} steady states",
        sizing.exact, sizing.classic, sizing.energy_swing, sizing.mean_speed, sizing.iterations
    );
    let with = machine.clone().with_flywheel(sizing.exact);
    let s = steady_state(&with, &settings, &mut |_| {}).unwrap();
    assert!((s.delta_mid - 0.02).abs() < 1e-6, "{}", s.delta_mid);
    let hand = Hand {
        fly: sizing.exact,
        motor: true,
    };
    let w0 = hand.periodic(s.omega, 20_000);
    let (_, _, lo, hi) = hand.turn(w0, 20_000);
    let delta = (hi - lo) / (0.5 * (hi + lo));
    assert!((delta - 0.02).abs() < 1e-6, "{delta}");
}

/// Bad input is a typed error, never a hang or a NaN: a motor too weak to start against the
/// load at the start angle, a negative flywheel, a tolerance of 0, a run without a stop, a
/// constant torque without losses (every turn gains the same energy: no steady state within
/// the turns allowed), a mechanism without mass.
#[test]
fn bad_input_is_a_located_error() {
    let m = slider_crank();
    let model = dynamics(true).compile(&m).unwrap();
    let weak = Machine::new(&model, ALL).with_motor(Characteristic::Linear {
        stall_torque: 0.5,
        no_load_speed: NO_LOAD,
    });
    // At φ = 4 rad the load needs F·x_B′/τ-reduced ≈ 8 N·m at the crank, 2.7 N·m at the motor.
    let e = start_up(&weak, 4.0, 10.0, 1.0, &Tolerances::default(), &mut |_| {}).unwrap_err();
    assert!(
        matches!(e, MotionError::CannotStart { phi: 4.0, .. }),
        "{e}"
    );
    let machine = Machine::new(&model, ALL).with_motor(linear_motor());
    let e = steady_state(
        &machine.clone().with_flywheel(-1.0),
        &SteadySettings::default(),
        &mut |_| {},
    )
    .unwrap_err();
    assert!(
        matches!(e, MotionError::InvalidValue { value: -1.0, .. }),
        "{e}"
    );
    let zero = Tolerances::default().with_relative(0.0);
    let stop = Stop {
        time: Some(1.0),
        ..Stop::default()
    };
    let e = simulate(&machine, Start::at_rest(0.0), &stop, &zero, &mut |_| {}).unwrap_err();
    assert!(matches!(e, MotionError::InvalidValue { .. }), "{e}");
    let e = simulate(
        &machine,
        Start::at_rest(0.0),
        &Stop::default(),
        &Tolerances::default(),
        &mut |_| {},
    )
    .unwrap_err();
    assert!(matches!(e, MotionError::NoStopCondition), "{e}");
    let free = Dynamics::new().compile(&m).unwrap();
    let pushed = Machine::new(
        &free,
        Effects {
            inertia: true,
            ..Effects::none()
        },
    )
    .with_motor(Characteristic::ConstantTorque { torque: 1.0 });
    let settings = SteadySettings {
        guess: Some(50.0),
        max_turns: 30,
        ..SteadySettings::default()
    };
    let e = steady_state(&pushed, &settings, &mut |_| {}).unwrap_err();
    assert!(matches!(e, MotionError::NoSteadyState { .. }), "{e}");
    let massless = Mechanism::builder()
        .point("O", [0.0, 0.0])
        .point("A", [1.0, 0.0])
        .ground(["O"])
        .link("crank", ["O", "A"])
        .revolute("O", "ground", "crank", "O")
        .drive(Drive::angle("O"))
        .build()
        .unwrap();
    let model = Dynamics::new().compile(&massless).unwrap();
    let machine = Machine::new(&model, Effects::all()).with_motor(linear_motor());
    let stop = Stop {
        time: Some(1.0),
        ..Stop::default()
    };
    let e = simulate(
        &machine,
        Start::at_rest(0.0),
        &stop,
        &Tolerances::default(),
        &mut |_| {},
    )
    .unwrap_err();
    assert!(matches!(e, MotionError::NoInertia { .. }), "{e}");
}

/// Coasting down against the load from 60 rad/s: the machine comes to rest (a located
/// event, speed exactly 0) having turned less than the kinetic energy over the load's mean
/// resisting torque allows (F·stroke work per turn bounds it from below).
#[test]
fn coast_down_ends_at_rest() {
    let m = slider_crank();
    let model = dynamics(true).compile(&m).unwrap();
    let machine = Machine::new(&model, ALL).with_motor(linear_motor());
    let start = Start {
        time: 0.0,
        phi: 0.0,
        omega: 60.0,
    };
    let c = coast_down(
        &machine,
        start,
        None,
        100.0,
        &Tolerances::default(),
        &mut |_| {},
    )
    .unwrap();
    let hand = Hand {
        fly: 0.0,
        motor: true,
    };
    let e0 = 0.5 * hand.j(0.0) * 60.0 * 60.0;
    // Work of the load per turn: F times the slider's travel while it acts.
    let x = |phi: f64| R * phi.cos() + (L * L - R * R * phi.sin().powi(2)).sqrt();
    let per_turn = F * (x(TO) - x(FROM)).abs();
    println!(
        "coast-down: {} s, {} turns, {} steps",
        c.time, c.turns, c.simulation.steps
    );
    assert_eq!(c.simulation.end.omega, 0.0);
    assert!(
        c.turns > 0.0 && c.turns < e0 / per_turn + 1.0,
        "{} turns",
        c.turns
    );
}

/// The gearbox's efficiency, derived by hand: while power flows to the mechanism the motor's
/// torque balance `M_char = J_d φ̈/τ + (τ/η)·M_drive` with `M_drive = J_m φ̈ + ½ J_m′ φ̇²`
/// (no load, no gravity) gives `φ̈ = (η M_char/τ − ½ J_m′ φ̇²) / (η J_d/τ² + J_m)`. Integrated
/// here by RK4 (steps of 2e-5 s, the last one cut by secant steps to end on the speed), the
/// start-up to 30 rad/s takes the engine's time to 1e-8 (its Newton solve of the implicit
/// acceleration, DOP853 at 1e-12), and the hand integration checks at every evaluation that
/// the power does flow to the mechanism (`M_drive > 0`), the branch its formula assumes.
#[test]
fn start_up_through_a_lossy_gearbox_agrees_with_an_independent_integration() {
    const ETA: f64 = 0.85;
    let m = slider_crank();
    let model = Dynamics::new()
        .with_motor(Motor {
            rotor_inertia: ROTOR,
            ratio: RATIO,
            efficiency: ETA,
        })
        .compile(&m)
        .unwrap();
    let effects = Effects {
        loads: false,
        efficiency: true,
        ..ALL
    };
    let machine = Machine::new(&model, effects).with_motor(linear_motor());
    let alpha = |y: [f64; 2]| {
        let (phi, w) = (y[0], y[1]);
        let jm = j_mechanism(phi);
        let djm = j_mechanism(Dual64::from(phi).derivative()).eps;
        let m_char = STALL * (1.0 - w / RATIO / NO_LOAD);
        let a = (ETA * m_char / RATIO - 0.5 * djm * w * w) / (ETA * ROTOR / (RATIO * RATIO) + jm);
        let m_drive = jm * a + 0.5 * djm * w * w;
        assert!(m_drive > 0.0, "power flows back at φ = {phi}, φ̇ = {w}");
        a
    };
    let rk4 = |y: [f64; 2], h: f64| {
        let f = |y: [f64; 2]| [y[1], alpha(y)];
        let k1 = f(y);
        let k2 = f([y[0] + 0.5 * h * k1[0], y[1] + 0.5 * h * k1[1]]);
        let k3 = f([y[0] + 0.5 * h * k2[0], y[1] + 0.5 * h * k2[1]]);
        let k4 = f([y[0] + h * k3[0], y[1] + h * k3[1]]);
        [
            y[0] + h / 6.0 * (k1[0] + 2.0 * k2[0] + 2.0 * k3[0] + k4[0]),
            y[1] + h / 6.0 * (k1[1] + 2.0 * k2[1] + 2.0 * k3[1] + k4[1]),
        ]
    };
    let speed = 30.0;
    let reference = |h: f64| {
        let (mut t, mut y) = (0.0, [0.0, 0.0]);
        loop {
            let next = rk4(y, h);
            if next[1] < speed {
                (t, y) = (t + h, next);
                continue;
            }
            // Secant on the last step's length for φ̇ = speed.
            let (mut a, mut b) = (0.0, h);
            let (mut ga, mut gb) = (y[1] - speed, next[1] - speed);
            for _ in 0..100 {
                let c = b - gb * (b - a) / (gb - ga);
                let gc = rk4(y, c)[1] - speed;
                (a, ga, b, gb) = (b, gb, c, gc);
                if gc.abs() < 1e-14 || (b - a).abs() < 1e-17 {
                    break;
                }
            }
            return t + b;
        }
    };
    let (t_ref, t_coarse) = (reference(2e-5), reference(4e-5));
    assert!(
        (t_ref / t_coarse - 1.0).abs() < 1e-10,
        "{t_ref} vs {t_coarse}"
    );
    let tol = Tolerances::default()
        .with_relative(1e-12)
        .with_absolute(1e-12);
    let s = start_up(&machine, 0.0, speed, 10.0, &tol, &mut |_| {}).unwrap();
    assert!(
        (s.time_to_speed / t_ref - 1.0).abs() < 1e-8,
        "{} vs {t_ref}",
        s.time_to_speed
    );
    // Without the losses the same motor gets there sooner.
    let lossless = Machine::new(
        &model,
        Effects {
            efficiency: false,
            ..effects
        },
    )
    .with_motor(linear_motor());
    let faster = start_up(&lossless, 0.0, speed, 10.0, &tol, &mut |_| {}).unwrap();
    assert!(faster.time_to_speed < s.time_to_speed);
}
