//! `scenes/cam_driven_rocker.toml`: a cam (rise–dwell–return–dwell, scenes/cams/) drives the
//! slider of a rocker linkage through `[drive] cam`. The rocker angle and its cam-angle
//! derivatives against a closed form written here, the cam-shaft torque against the power
//! balance, and bad cam drives as errors with `file:line:column`.

use std::f64::consts::TAU;

use mechdiff::scene::{self, Report};
use num_dual::{Dual3_64, DualNum};

mod common;
use common::{column, scene_path};

fn run() -> Report {
    let s = scene::load(scene_path("cam_driven_rocker.toml")).unwrap_or_else(|e| panic!("{e}"));
    scene::run(&s).unwrap_or_else(|e| panic!("{e}"))
}

/// The scene's data (m): rocker, rod, follower at s = 0; the cam's lift and extents (rad).
const R: f64 = 0.1;
const L: f64 = 0.325;
const X0: f64 = 0.375;
const LIFT: f64 = 0.02;
const RISE: f64 = TAU / 3.0;
const DWELL: f64 = TAU / 6.0;

/// The follower's travel from the laws as textbooks write them (Norton, *Design of
/// Machinery*: cycloidal rise, 3-4-5 polynomial return), with θ-derivatives.
fn travel(theta: f64) -> Dual3_64 {
    let t = Dual3_64::from(theta).derivative();
    let return_start = RISE + DWELL;
    if theta < RISE {
        let u = t / RISE;
        (u - (u * TAU).sin() / TAU) * LIFT
    } else if theta < return_start {
        t * 0.0 + LIFT
    } else if theta < return_start + RISE {
        let u = (t - return_start) / RISE;
        (-(u.powi(3) * 10.0 - u.powi(4) * 15.0 + u.powi(5) * 6.0) + 1.0) * LIFT
    } else {
        t * 0.0
    }
}

/// The rocker angle ψ = ∠(O→A) from the triangle O–A–B (A above the guide).
fn rocker(theta: f64) -> Dual3_64 {
    let x = travel(theta) + X0;
    ((x * x + R * R - L * L) / (x * (2.0 * R))).acos()
}

#[test]
fn rocker_angle_and_its_cam_angle_derivatives_equal_the_closed_form() {
    let r = run();
    let theta = column(&r, "theta");
    assert_eq!(theta.len(), 25, "0° to 360° by 15°");
    let columns = [
        column(&r, "psi"),
        column(&r, "psi'"),
        column(&r, "psi''"),
        column(&r, "psi_dot"),
    ];
    let omega = 300.0 * TAU / 60.0;
    for (i, &t) in theta.iter().enumerate() {
        let want = rocker(t);
        let expected = [want.re, want.v1, want.v2, want.v1 * omega];
        let scale = [1.0, 0.2, 1.0, 0.2 * omega];
        for ((c, w), s) in columns.iter().zip(expected).zip(scale) {
            // 1e-12 of the quantity's size over the turn: the geometry solver is exact to
            // rounding and the closed form is a few dozen operations in f64.
            assert!(
                (c[i] - w).abs() <= 1e-12 * s,
                "θ = {t}: {} vs closed form {w}",
                c[i]
            );
        }
    }
}

#[test]
fn cam_torque_is_the_follower_force_times_s_prime_and_closes_the_power_balance() {
    let r = run();
    let theta = column(&r, "theta");
    let (force, cam, balance, dm) = (
        column(&r, "F_drive"),
        column(&r, "M_cam"),
        column(&r, "M_balance"),
        column(&r, "dM"),
    );
    let scale = cam.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    assert!(scale > 1.0, "the cam works against the 5 N·m load: {scale}");
    for i in 0..theta.len() {
        let s1 = travel(theta[i]).v1;
        // 1e-12 relative: F_s s′ is one product, s′ exact from both sides.
        assert!(
            (cam[i] - force[i] * s1).abs() <= 1e-12 * scale,
            "θ = {}",
            theta[i]
        );
        // The balance (dT/dt − P_gravity − P_loads)/ω and F_s s′ agree to rounding of the
        // power terms (1e-12 of the largest torque).
        assert!(
            (cam[i] - balance[i]).abs() <= 1e-12 * scale,
            "θ = {}",
            theta[i]
        );
        assert!(dm[i].abs() <= 1e-12 * scale, "θ = {}", theta[i]);
    }
}

/// The shipped scene with `from` replaced by `to` (which must occur), parsed as if it were
/// in scenes/ (so that its relative cam path resolves).
fn variant(from: &str, to: &str) -> mechdiff::Error {
    let text = std::fs::read_to_string(scene_path("cam_driven_rocker.toml")).unwrap();
    assert!(text.contains(from), "{from}");
    let text = text.replace(from, to);
    let file = scene_path("variant.toml").display().to_string();
    match scene::parse(&file, &text) {
        Ok(s) => scene::run(&s).map(|_| ()).unwrap_err(),
        Err(e) => e,
    }
}

#[test]
fn bad_cam_drives_are_errors_naming_the_place() {
    let missing = variant("cams/rise_dwell_return_dwell.toml", "cams/none.toml").to_string();
    assert!(
        missing.contains("variant.toml:") && missing.contains("`[drive] cam`"),
        "{missing}"
    );
    // A translating follower on a revolute joint.
    let wrong = variant("joint = \"guide\"", "joint = \"O\"\nline = [\"O\", \"A\"]").to_string();
    assert!(
        wrong.contains("translating") && wrong.contains("prismatic"),
        "{wrong}"
    );
    let dead = variant(
        "\"velocity\", \"acceleration\"]",
        "\"velocity\", \"acceleration\"]\ndead_positions = true",
    )
    .to_string();
    assert!(
        dead.contains("`dead_positions` is not supported with a cam drive"),
        "{dead}"
    );
}
