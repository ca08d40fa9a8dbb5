//! Mechanism 001 (gear rack, slotted link, coupler rod, slider on an incline) defined by
//! geometry only, against rack_slotted_link_001.json (`kinematics`, `kinematics_other_branch`).

use crate::common;

use common::{Closure001, rack_slotted_link, rack_slotted_link_incline};
use mechdiff_core::DriveState;
use mechdiff_core::geometry::{Kinematics, Solver};

/// Reference values at θ3 = 63°, ρ̇4 = 0.050 m/s, ρ̈4 = 0.002 m/s², θ8 = 60°, copied from
/// rack_slotted_link_001.json. Shared by both closures: θ̇3, θ̈3, ρ̇3, ρ̈3, v_G1, a_G1.
const THETA3_DOT: f64 = -0.1195621424919031;
const THETA3_DDOT: f64 = 0.009784954836442646;
const RHO3_DOT: f64 = 0.02269952498697734;
const RHO3_DDOT: f64 = 0.006234513449790341;
const V_G1: [f64; 2] = [0.024928171867456637, -0.012701537975840218];
const A_G1: [f64; 2] = [-0.003558742405302914, -0.0019409729274261352];

/// Loop-2 values per closure: θ6 (rad), θ̇6, θ̈6, ρ8, ρ̇8, ρ̈8.
const PRIMARY: [f64; 6] = [
    0.4944536749112614,
    0.20664998809740256,
    -0.04196102165081047,
    2.0027313520345755,
    0.08510695676438099,
    -0.05795435478088719,
];
const OTHER: [f64; 6] = [
    -1.5416512261078592,
    -0.20664998809740256,
    0.04196102165081047,
    0.7720593685595446,
    -0.07177869677133333,
    0.02645672430959435,
];

/// 1e-9 relative (the criterion; the values are O(1e-3..1), so relative to the
/// magnitude of each one).
fn close(name: &str, got: f64, want: f64) {
    let err = (got - want).abs() / want.abs();
    println!("{name}: relative error {err:.1e}");
    assert!(
        err <= 1e-9,
        "{name}: got {got}, want {want}, relative error {err:e}"
    );
}

fn check(k: &Kinematics<'_, 2>, drive: &DriveState, loop2: &[f64; 6]) {
    let theta3 = k.angle("slotted link", "B", "C").unwrap().motion(drive);
    close("θ3", theta3.position, 63f64.to_radians());
    close("θ̇3", theta3.velocity, THETA3_DOT);
    close("θ̈3", theta3.acceleration, THETA3_DDOT);
    let rho3 = k.displacement("slot").unwrap().motion(drive);
    close("ρ3", rho3.position, 0.3726123108946078);
    close("ρ̇3", rho3.velocity, RHO3_DOT);
    close("ρ̈3", rho3.acceleration, RHO3_DDOT);
    let theta6 = k.angle("rod", "C", "D").unwrap().motion(drive);
    close("θ6", theta6.position, loop2[0]);
    close("θ̇6", theta6.velocity, loop2[1]);
    close("θ̈6", theta6.acceleration, loop2[2]);
    let rho8 = k.displacement("incline").unwrap().motion(drive);
    close("ρ8", rho8.position, loop2[3]);
    close("ρ̇8", rho8.velocity, loop2[4]);
    close("ρ̈8", rho8.acceleration, loop2[5]);
    let g1 = k
        .point("slotted link", "G1")
        .unwrap()
        .map(|j| j.motion(drive));
    for i in 0..2 {
        close("v_G1", g1[i].velocity, V_G1[i]);
        close("a_G1", g1[i].acceleration, A_G1[i]);
    }
}

#[test]
fn reference_instant_primary_closure_matches_to_1e_9() {
    let m = rack_slotted_link(Closure001::Primary, false).unwrap();
    let t = Solver::default().track(&m).unwrap();
    // The drive is ρ4; at the sketch it is ρ4 itself (θ3 = 63°).
    assert!((t.phi() - common::rack001::RHO4).abs() < 1e-15);
    let k = t.kinematics::<2>().unwrap();
    check(&k, &DriveState::accelerating(0.050, 0.002), &PRIMARY);
}

#[test]
fn other_closure_is_kept_when_the_sketch_draws_it() {
    let m = rack_slotted_link(Closure001::Other, false).unwrap();
    let t = Solver::default().track(&m).unwrap();
    check(
        &t.kinematics::<2>().unwrap(),
        &DriveState::accelerating(0.050, 0.002),
        &OTHER,
    );
}

#[test]
fn loop_2_certificates_differ_between_closures_and_survive_a_sweep() {
    let signs = |closure| {
        let m = rack_slotted_link(closure, false).unwrap();
        let mut t = Solver::default().track(&m).unwrap();
        let start = t.loops();
        // Three loops: {rack guide, drive}, {A, slot, B}, {C, D, incline}.
        assert_eq!(start.len(), 3, "{start:?}");
        assert!(start[2].0.contains(&"incline".to_owned()));
        // Move the rack ±5 cm and back: the closure must not change.
        for rho4 in [0.40, 0.37, 0.45, common::rack001::RHO4] {
            t.move_to(rho4).unwrap();
        }
        let k = t.kinematics::<2>().unwrap();
        let rho8 = k.displacement("incline").unwrap().value;
        (start[2].1, rho8)
    };
    let (primary, rho8_primary) = signs(Closure001::Primary);
    let (other, rho8_other) = signs(Closure001::Other);
    assert_ne!(
        primary, other,
        "the two closures must have opposite certificates"
    );
    // Back at θ3 = 63° each sweep returns to its own closure (1e-12 m: solver rounding).
    assert!((rho8_primary - PRIMARY[3]).abs() < 1e-12);
    assert!((rho8_other - OTHER[3]).abs() < 1e-12);
}

#[test]
fn pinion_drive_through_rack_and_pinion_gives_the_same_motion() {
    // ω1 = v_A / R = 1.25 rad/s, ω̇1 = a_A / R = 0.05 rad/s² (the reference's `gear` values).
    let m = rack_slotted_link(Closure001::Primary, true).unwrap();
    let t = Solver::default().track(&m).unwrap();
    let k = t.kinematics::<2>().unwrap();
    check(&k, &DriveState::accelerating(1.25, 0.05), &PRIMARY);
    let rack = k.displacement("rack guide").unwrap();
    // ρ4′ = R exactly (rolling), ρ4″ = 0; 1e-15: rounding of a linear relation.
    assert!((rack.d1() - 0.04).abs() < 1e-15 && rack.d2().abs() < 1e-15);
}

#[test]
fn other_incline_angles_match_the_reference_variants() {
    // `kinematics_theta8_variants_primary_branch` of rack_slotted_link_001.json:
    // θ8 (°) → θ6 (°), ρ8, θ̇6, θ̈6, ρ̇8, ρ̈8.
    let variants: [(f64, [f64; 6]); 5] = [
        (
            50.0,
            [
                -8.240942702425937,
                1.6809519770052201,
                0.32602858124277,
                -0.18939230174011784,
                0.22906812611242588,
                -0.17405658532661164,
            ],
        ),
        (
            70.0,
            [
                59.40722933544724,
                2.1429123205289846,
                0.17783633676468924,
                -0.02307928604969454,
                0.00811764976373331,
                -0.039383979380916666,
            ],
        ),
        (
            80.0,
            [
                89.37847581987023,
                2.146889514681985,
                0.1707047006421322,
                -0.015397500129103892,
                -0.05734063038923242,
                -0.03048485555834719,
            ],
        ),
        (
            90.0,
            [
                120.31719180646512,
                2.015441480087347,
                0.18178257510076362,
                -0.006628069075225189,
                -0.12415178849769577,
                -0.027039097846706224,
            ],
        ),
        (
            100.0,
            [
                156.23048305177437,
                1.7086860186876953,
                0.25304241691809015,
                0.0522505208580549,
                -0.22871378024322958,
                -0.06302323125321062,
            ],
        ),
    ];
    let drive = DriveState::accelerating(0.050, 0.002);
    for (theta8, r) in variants {
        let m = rack_slotted_link_incline(Closure001::Primary, false, theta8.to_radians()).unwrap();
        let k = Solver::default()
            .track(&m)
            .unwrap()
            .kinematics::<2>()
            .unwrap();
        let theta6 = k.angle("rod", "C", "D").unwrap().motion(&drive);
        let rho8 = k.displacement("incline").unwrap().motion(&drive);
        let theta6_deg = theta6.position.to_degrees();
        // Angles compared modulo a turn (the sketch's atan2 branch).
        let wrapped = theta6_deg - 360.0 * ((theta6_deg - r[0]) / 360.0).round();
        close("θ6", wrapped, r[0]);
        close("ρ8", rho8.position, r[1]);
        close("θ̇6", theta6.velocity, r[2]);
        close("θ̈6", theta6.acceleration, r[3]);
        close("ρ̇8", rho8.velocity, r[4]);
        close("ρ̈8", rho8.acceleration, r[5]);
    }
}
