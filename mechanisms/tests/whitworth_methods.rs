//! Every derivative method against the hand-derived formulas and the high-precision
//! reference: dual numbers exact to rounding, central differences of order 2, dead positions
//! where cos φ = λ.
//!
//! Reference: `tests/data/whitworth_000.json` (copied from the project's reference
//! `whitworth_000.json`, computed in 40-digit arithmetic).

use crate::common;

use common::{digits, number, reference};
use mechdiff_core::method::{
    CentralDifference, Differentiator, Dual2, Dual3, HandDerived, HyperDual,
};
use mechdiff_core::{Jet, PositionFunction};
use mechdiff_mechanisms::Whitworth;
use mechdiff_mechanisms::whitworth::{Parameters, Pose, hand};
use proptest::prelude::*;
use std::f64::consts::TAU;

/// The scalars of a pose in `map` order (ψ, A, C, S1, S2, S3; x before y).
fn scalars<T>(pose: Pose<T>) -> Vec<T> {
    let mut all = Vec::new();
    Whitworth::map(pose, |x| all.push(x));
    all
}

/// The crank angles of a 0.1° sweep over one revolution.
fn tenth_degree_sweep() -> impl Iterator<Item = f64> {
    (0..3600).map(|k| (k as f64 * 0.1).to_radians())
}

/// The largest error of `method` against the hand-derived pose over the 0.1° sweep, per
/// derivative order, each error divided by max(|hand value|, that quantity's largest magnitude
/// over the revolution).
fn worst_scaled_error(shaper: &Whitworth, method: &impl Differentiator<Whitworth, 2>) -> [f64; 3] {
    let hand: Vec<Vec<Jet<2>>> = tenth_degree_sweep()
        .map(|phi| scalars(hand::pose(shaper, phi)))
        .collect();
    let quantities = hand[0].len();
    let scale: Vec<[f64; 3]> = (0..quantities)
        .map(|q| {
            std::array::from_fn(|k| {
                hand.iter()
                    .map(|row| row[q].derivative(k).unwrap().abs())
                    .fold(0.0, f64::max)
            })
        })
        .collect();
    let mut worst = [0.0f64; 3];
    for (phi, want) in tenth_degree_sweep().zip(&hand) {
        let got = scalars(method.jets(shaper, phi));
        for q in 0..quantities {
            for k in 0..3 {
                let (g, w) = (
                    got[q].derivative(k).unwrap(),
                    want[q].derivative(k).unwrap(),
                );
                let denominator = w.abs().max(scale[q][k]);
                if denominator > 0.0 {
                    worst[k] = worst[k].max((g - w).abs() / denominator);
                }
            }
        }
    }
    worst
}

/// Dual2, HyperDual and Dual3 agree with the hand-derived formulas (1.35), (1.36), (1.39),
/// (1.41), (1.23), (1.24) for every pose quantity (ψ, A, C, S1, S2, S3), value, first and
/// second derivative, at every 0.1° of a revolution: to 1e-13, relative or scaled by the
/// quantity's largest magnitude over the revolution. Both sides are exact formulas evaluated
/// in f64, tens of roundings apart (measured worst: ~1e-15).
#[test]
fn dual_methods_match_the_hand_derived_formulas_over_a_tenth_degree_sweep() {
    let shaper = Whitworth::reference();
    struct Dual3AsOrder2;
    impl Differentiator<Whitworth, 2> for Dual3AsOrder2 {
        fn jets(&self, f: &Whitworth, phi: f64) -> Pose<Jet<2>> {
            Dual3.jets(f, phi).map(|x: Jet<3>| x.truncate())
        }
    }
    let errors = [
        ("Dual2", worst_scaled_error(&shaper, &Dual2)),
        ("HyperDual", worst_scaled_error(&shaper, &HyperDual)),
        ("Dual3", worst_scaled_error(&shaper, &Dual3AsOrder2)),
    ];
    for (name, worst) in errors {
        eprintln!(
            "{name} vs hand-derived, worst scaled error (x, x′, x″): {:.1e}, {:.1e}, {:.1e}",
            worst[0], worst[1], worst[2]
        );
        assert!(worst.iter().all(|&e| e <= 1e-13), "{name}: {worst:?}");
    }
}

/// The hand-derived baseline used through the `HandDerived` method gives the same jets as the
/// function it wraps (the method adds nothing): exact equality.
#[test]
fn hand_derived_method_returns_the_source_formulas() {
    let shaper = Whitworth::reference();
    let method = HandDerived(|phi| hand::pose(&shaper, phi));
    assert_eq!(method.jets(&shaper, 1.3), hand::pose(&shaper, 1.3));
}

/// ψ, x_C and their first three derivatives by Dual3, and the hand-derived ψ′, ψ″, x_C′, x_C″,
/// against the 30-digit reference every 10° and at both dead positions: to 1e-14 of the
/// derivative's largest magnitude over the revolution (a few ulp of f64 rounding).
#[test]
fn dual3_and_hand_formulas_match_the_30_digit_reference() {
    let data = reference();
    let shaper = Whitworth::reference();
    let rows = data["sweep_30digits"]["rows"].as_array().unwrap();
    let keys = [
        ["psi_rad", "psi_p", "psi_pp", "psi_ppp"],
        ["x_C_m", "x_C_p_m", "x_C_pp_m", "x_C_ppp_m"],
    ];
    let scale = keys.map(|row_keys| {
        row_keys.map(|key| {
            rows.iter()
                .map(|r| digits(&r[key]).abs())
                .fold(0.0, f64::max)
        })
    });
    let mut worst = [0.0f64; 2];
    for row in rows {
        let phi = digits(&row["phi_rad"]);
        let dual = Dual3.jets(&shaper, phi);
        let by_hand = hand::pose(&shaper, phi);
        for (q, (got, hand_jet)) in [(dual.psi, by_hand.psi), (dual.c.x, by_hand.c.x)]
            .into_iter()
            .enumerate()
        {
            for k in 0..4 {
                let want = digits(&row[keys[q][k]]);
                let error = (got.derivative(k).unwrap() - want).abs() / scale[q][k];
                worst[0] = worst[0].max(error);
                assert!(error <= 1e-14, "{} at φ = {phi}: {error:e}", keys[q][k]);
                if let Some(h) = hand_jet.derivative(k) {
                    let error = (h - want).abs() / scale[q][k];
                    worst[1] = worst[1].max(error);
                    assert!(
                        error <= 1e-14,
                        "hand {} at φ = {phi}: {error:e}",
                        keys[q][k]
                    );
                }
            }
        }
    }
    eprintln!(
        "worst scaled error vs 30 digits: Dual3 {:.1e}, hand {:.1e}",
        worst[0], worst[1]
    );
}

/// Positions, velocities, accelerations and inertial forces against the reference sweep
/// (every 10° and at both dead positions), to 1e-13 of each quantity's largest magnitude over
/// the sweep (f64 evaluations of exact formulas, a few dozen roundings).
#[test]
fn accelerations_and_forces_match_the_reference_sweep() {
    let data = reference();
    let shaper = Whitworth::reference();
    let drive = shaper.drive();
    let sweep = data["sweep"].as_array().unwrap();
    let keys = [
        "xdd_S1_m_s2",
        "ydd_S1_m_s2",
        "xdd_S2_m_s2",
        "ydd_S2_m_s2",
        "xdd_S3_m_s2",
        "F_x1_N",
        "F_y1_N",
        "F_x2_N",
        "F_y2_N",
        "F_x3_N",
        "F_y3_N",
        "SumF_x_N",
        "SumF_y_N",
        "xd_S3_m_s",
        "psi_ddot_rad_s2",
        "psi_rad",
        "x_A_m",
        "y_A_m",
        "x_S1_m",
        "y_S1_m",
        "x_S2_m",
        "y_S2_m",
        "x_C_m",
        "xd_S1_m_s",
        "yd_S1_m_s",
        "xd_S2_m_s",
        "yd_S2_m_s",
        "psi_dot_rad_s",
    ];
    let scale = keys.map(|k| {
        sweep
            .iter()
            .map(|r| number(&r[k]).abs())
            .fold(0.0, f64::max)
    });
    for row in sweep {
        let phi = number(&row["phi_rad"]);
        let a = shaper.centre_accelerations(phi, &drive).unwrap();
        let f = shaper.inertial_forces(phi, &drive).unwrap();
        let pose = Dual2.jets(&shaper, phi);
        let got = [
            a.s1.x,
            a.s1.y,
            a.s2.x,
            a.s2.y,
            a.s3.x,
            f.f1.x,
            f.f1.y,
            f.f2.x,
            f.f2.y,
            f.f3.x,
            f.f3.y,
            f.sum.x,
            f.sum.y,
            pose.s3.x.velocity(&drive),
            pose.psi.motion(&drive).acceleration,
            pose.psi.value,
            pose.a.x.value,
            pose.a.y.value,
            pose.s1.x.value,
            pose.s1.y.value,
            pose.s2.x.value,
            pose.s2.y.value,
            pose.c.x.value,
            pose.s1.x.velocity(&drive),
            pose.s1.y.velocity(&drive),
            pose.s2.x.velocity(&drive),
            pose.s2.y.velocity(&drive),
            pose.psi.velocity(&drive),
        ];
        for (q, key) in keys.iter().enumerate() {
            let want = number(&row[key]);
            assert!(
                (got[q] - want).abs() <= 1e-13 * scale[q].max(f64::MIN_POSITIVE),
                "{key} at φ = {phi}: {} vs {want}",
                got[q]
            );
        }
    }
}

/// The source's constant-speed time formulas (1.39), (1.41), (1.23), (1.24) equal the
/// automatic velocities and accelerations at α = 0 over the 0.1° sweep, to 1e-13 of each
/// quantity's largest magnitude over the revolution (exact formulas, rounding apart).
#[test]
fn source_time_formulas_match_automatic_motion_at_constant_speed() {
    let shaper = Whitworth::reference();
    let drive = shaper.drive();
    let omega = drive.omega;
    let source: Vec<[f64; 4]> = tenth_degree_sweep()
        .map(|phi| {
            let s2 = hand::rocker_centre_acceleration(&shaper, phi, omega);
            [
                hand::ram_velocity(&shaper, phi, omega),
                hand::ram_acceleration(&shaper, phi, omega),
                s2.x,
                s2.y,
            ]
        })
        .collect();
    let scale: [f64; 4] =
        std::array::from_fn(|q| source.iter().map(|v| v[q].abs()).fold(0.0, f64::max));
    for (phi, want) in tenth_degree_sweep().zip(&source) {
        let a = shaper.centre_accelerations(phi, &drive).unwrap();
        let got = [
            Dual2.jets(&shaper, phi).s3.x.velocity(&drive),
            a.s3.x,
            a.s2.x,
            a.s2.y,
        ];
        for q in 0..4 {
            assert!(
                (got[q] - want[q]).abs() <= 1e-13 * scale[q],
                "quantity {q} at φ = {phi}: {} vs {}",
                got[q],
                want[q]
            );
        }
    }
}

/// The drive's acceleration is never assumed zero: with φ(t) = φ₀ + ω₀t + α t²/2, the
/// accelerations of S1, S2, S3 at t = 0 for the drive state (ω₀, α) equal the second time
/// difference of the positions, (x(t₁) − 2x(t₀) + x(t₋₁))/Δt² with Δt = 1e-4 s: to 1e-6 of
/// their size (truncation ~Δt²·x⁗ ~ 1e-6, rounding ~ε·x/Δt² ~ 1e-8 here).
#[test]
fn accelerations_with_a_drive_acceleration_match_time_differences() {
    let shaper = Whitworth::reference();
    let (omega, alpha, dt) = (8.0, -30.0, 1e-4);
    for phi0 in [0.3, 1.186, 2.5, 4.0, 5.5] {
        let at = |t: f64| shaper.evaluate(phi0 + omega * t + 0.5 * alpha * t * t);
        let drive = mechdiff_core::DriveState::accelerating(omega, alpha);
        let a = shaper.centre_accelerations(phi0, &drive).unwrap();
        let (before, now, after) = (at(-dt), at(0.0), at(dt));
        let second_difference =
            |f: fn(&Pose<f64>) -> f64| (f(&after) - 2.0 * f(&now) + f(&before)) / (dt * dt);
        let pairs = [
            (a.s1.x, second_difference(|p| p.s1.x)),
            (a.s1.y, second_difference(|p| p.s1.y)),
            (a.s2.x, second_difference(|p| p.s2.x)),
            (a.s2.y, second_difference(|p| p.s2.y)),
            (a.s3.x, second_difference(|p| p.s3.x)),
        ];
        let size = pairs
            .iter()
            .map(|(exact, _)| exact.abs())
            .fold(1.0, f64::max);
        for (exact, difference) in pairs {
            assert!(
                (exact - difference).abs() <= 1e-6 * size,
                "φ₀ = {phi0}: {exact} vs {difference}"
            );
        }
    }
}

/// Central differences converge at order 2: halving the step from 1e-2 to 5e-3 rad divides
/// the error of ψ′ and ψ″ (against the 30-digit reference) by 4, checked within [3.8, 4.2]
/// (order 1 would give 2, order 3 give 8; the O(h⁴) remainder and rounding, ~1e-12 here,
/// move the ratio by less than 1%).
#[test]
fn central_differences_converge_at_order_two() {
    let data = reference();
    let rocker = Whitworth::reference().rocker();
    for row in data["sweep_30digits"]["rows"].as_array().unwrap() {
        let phi = digits(&row["phi_rad"]);
        let want = [digits(&row["psi_p"]), digits(&row["psi_pp"])];
        let error = |h: f64| {
            let psi: Jet<2> = CentralDifference::new(h).jets(&rocker, phi);
            [(psi.d1() - want[0]).abs(), (psi.d2() - want[1]).abs()]
        };
        let (coarse, fine) = (error(1e-2), error(5e-3));
        for k in 0..2 {
            // Where the leading error term (ψ‴ for ψ′, ψ'''' for ψ″) nearly vanishes the
            // ratio is not defined: skip errors below 1e-9 (the leading term is ~1e-5 elsewhere).
            if coarse[k] < 1e-9 {
                continue;
            }
            let ratio = coarse[k] / fine[k];
            assert!(
                (3.8..=4.2).contains(&ratio),
                "φ = {phi}, order {}: ratio {ratio}",
                k + 1
            );
        }
    }
}

/// The dead positions found numerically (sign changes of ψ′, refined by Newton) are
/// φ = acos λ and 2π − acos λ to 1e-13 rad (measured: within 1 ulp), with |ψ′| ≤ 1e-15 there,
/// ψ = ±asin λ and ψ″ = ∓λ/√(1 − λ²) (1e-15, a few ulp), and the ram's stroke
/// 2hλ/√(1 − λ²) = 0.5258758927213288 m (1e-15 m).
#[test]
fn dead_positions_match_cos_phi_equals_lambda() {
    let data = reference();
    let shaper = Whitworth::reference();
    let lambda = shaper.lambda();
    let [first, second] = shaper.dead_positions().unwrap();
    let phi1 = digits(&data["dead_positions"]["phi1_rad_30digits"]);
    let phi2 = digits(&data["dead_positions"]["phi2_rad_30digits"]);
    assert!((first.phi - lambda.acos()).abs() <= 1e-13);
    assert!((second.phi - (TAU - lambda.acos())).abs() <= 1e-13);
    assert!((first.phi - phi1).abs() <= 1e-13 && (second.phi - phi2).abs() <= 1e-13);
    eprintln!(
        "dead positions: φ1 − acos λ = {:e}, φ2 − (2π − acos λ) = {:e}, ψ′ = {:e}, {:e}",
        first.phi - lambda.acos(),
        second.phi - (TAU - lambda.acos()),
        first.d1,
        second.d1
    );
    for (dead, sign) in [(first, 1.0), (second, -1.0)] {
        assert!(dead.d1.abs() <= 1e-15, "ψ′ = {}", dead.d1);
        assert!((dead.value - sign * lambda.asin()).abs() <= 1e-15);
        assert!((dead.d2 + sign * lambda / (1.0 - lambda * lambda).sqrt()).abs() <= 1e-15);
    }
    let stroke = number(&data["dead_positions"]["stroke_of_C_m"]);
    assert!((shaper.stroke().unwrap() - stroke).abs() <= 1e-15);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// Over random valid geometry (λ in (0.05, 0.95)) and crank angle, Dual2 agrees with the
    /// hand-derived ψ, ψ′, ψ″ and x_C, x_C′, x_C″. Tolerance 1e-13 scaled by the quantity's
    /// size and by 1/(1 − λ)²: the hand formulas form 1 − 2λ cos φ + λ², whose relative
    /// rounding error grows like 1/(1 − λ)² as λ → 1 (the dual evaluation's like its own).
    #[test]
    fn dual2_matches_hand_derived_for_random_geometry(
        lambda in 0.05f64..0.95,
        l0 in 0.05f64..5.0,
        h_over_l0 in 1.0f64..4.0,
        l_s1 in 0.01f64..1.0,
        l_s2 in 0.01f64..1.0,
        phi in 0.0f64..TAU,
    ) {
        let shaper = Whitworth::new(Parameters {
            l0, l1: lambda * l0, l_s1, l_s2, h: h_over_l0 * l0, ..Parameters::reference()
        }).unwrap();
        let conditioning = 1e-13 / (1.0 - lambda).powi(2);
        let dual = Dual2.jets(&shaper, phi);
        let by_hand = hand::pose(&shaper, phi);
        for (got, want, size) in [
            (dual.psi, by_hand.psi, 1.0),
            (dual.c.x, by_hand.c.x, shaper.parameters().h),
            (dual.s2.y, by_hand.s2.y, l_s2),
        ] {
            for k in 0..3 {
                let (g, w) = (got.derivative(k).unwrap(), want.derivative(k).unwrap());
                let scale = w.abs().max(size / (1.0 - lambda).powi(k as i32));
                prop_assert!((g - w).abs() <= conditioning * scale,
                    "order {k}: {g} vs {w} (λ = {lambda}, φ = {phi})");
            }
        }
    }
}
