//! A cam program is a position function of the cam angle: every derivative method applies,
//! and the follower's time derivatives follow from the chain rule.

use std::f64::consts::PI;

use mechdiff_core::cams::{CamProgram, MotionLaw, Segment, Side};
use mechdiff_core::method::{CentralDifference, Differentiator, Dual2, HyperDual};
use mechdiff_core::{DriveState, Jet};

fn program() -> CamProgram {
    let deg = PI / 180.0;
    CamProgram::new(
        vec![
            Segment::law(MotionLaw::ModifiedSine, 0.025, 100.0 * deg),
            Segment::law(MotionLaw::Dwell, 0.0, 80.0 * deg),
            Segment::law(MotionLaw::ModifiedTrapezoidal, -0.025, 100.0 * deg),
            Segment::law(MotionLaw::Dwell, 0.0, 80.0 * deg),
        ],
        0.0,
    )
    .unwrap()
}

/// Dual2 and HyperDual give the same s′, s″ as the program's own Dual3 (1e-15 relative of
/// the peak: the same exact arithmetic in another order), and central differences of step
/// 1e-4 agree to 1e-6 of the peak (their O(h²) truncation error).
#[test]
fn every_derivative_method_agrees_on_the_program() {
    let program = program();
    let peaks = mechdiff_core::cams::continuity::derivative_peaks(&program);
    for k in 0..90 {
        let theta = (k as f64 + 0.3) * 4.0 * PI / 180.0;
        let exact = program.svaj(theta, Side::Right);
        let dual: Jet<2> = Dual2.jets(&program, theta);
        let hyper: Jet<2> = HyperDual.jets(&program, theta);
        let fd: Jet<2> = CentralDifference::new(1e-4).jets(&program, theta);
        for (order, peak) in [(1, peaks[1]), (2, peaks[2])] {
            let want = exact.derivatives[order - 1];
            assert!((dual.derivatives[order - 1] - want).abs() <= 1e-15 * peak);
            assert!((hyper.derivatives[order - 1] - want).abs() <= 1e-15 * peak);
            // Pieces of the modified laws meet with a jump in s‴ (not in s″): the central
            // difference straddling a break is still O(h²) in s′ but only O(h) in s″.
            let tol = if order == 1 { 1e-6 } else { 1e-3 };
            assert!(
                (fd.derivatives[order - 1] - want).abs() <= tol * peak,
                "order {order} at {theta}"
            );
        }
    }
}

/// Follower velocity ω s′, acceleration α s′ + ω² s″, jerk 3ωα s″ + ω³ s‴ (φ⃛ = 0) at a
/// cam speed of 300 rpm accelerating at 50 rad/s²: the chain rule term by term, 1e-13
/// relative.
#[test]
fn follower_motion_follows_the_cam_speed_and_acceleration() {
    let program = program();
    let (omega, alpha) = (300.0 * PI / 30.0, 50.0);
    let drive = DriveState::accelerating(omega, alpha);
    let theta = 0.6;
    let j = program.svaj(theta, Side::Right);
    let m = program.follower_motion(theta, Side::Right, &drive);
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-13 * b.abs();
    assert!(close(m.velocity, omega * j.d1()));
    assert!(close(
        m.acceleration,
        alpha * j.d1() + omega * omega * j.d2()
    ));
    let jerk = 3.0 * omega * alpha * j.d2() + omega.powi(3) * j.d3();
    assert!(close(m.jerk.unwrap(), jerk));
}
