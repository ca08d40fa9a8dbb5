//! Cam and follower geometry, checked independently of the code that computes it: the
//! roller profile by the envelope conditions, the pressure angle by its closed form, the
//! base-circle sizing by a search of its own, the flat face by R_b + s + s″.

use std::f64::consts::PI;

use mechdiff_core::Error;
use mechdiff_core::cams::{CamMechanism, CamProgram, Follower, MotionLaw, Segment, Side, sizing};
use num_dual::Dual64;

/// Rise 20 (cycloidal) over 120°, dwell 60°, return 20 (3-4-5) over 120°, dwell 60° (mm).
fn rise_dwell_return_dwell() -> CamProgram {
    let deg = PI / 180.0;
    CamProgram::new(
        vec![
            Segment::law(MotionLaw::Cycloidal, 20.0, 120.0 * deg),
            Segment::law(MotionLaw::Dwell, 0.0, 60.0 * deg),
            Segment::law(MotionLaw::Polynomial345, -20.0, 120.0 * deg),
            Segment::law(MotionLaw::Dwell, 0.0, 60.0 * deg),
        ],
        0.0,
    )
    .unwrap()
}

fn angles() -> impl Iterator<Item = f64> {
    // 720 angles, offset from the segment boundaries.
    (0..720).map(|k| (k as f64 + 0.37) * PI / 360.0)
}

/// At every sampled angle the profile point is at the roller radius from the roller centre
/// and the profile's tangent (the derivative of the profile point itself, by a dual number)
/// is perpendicular to the line to the roller centre: the normal passes through the centre.
/// Translating offset roller and oscillating roller. 1e-12 relative to the roller radius
/// (and to |C′| r for the tangency): exact derivatives, a few roundings of numbers of size 50.
#[test]
fn roller_profile_is_the_envelope_of_the_roller() {
    let translating = Follower::Roller {
        offset: 10.0,
        radius: 8.0,
    };
    let oscillating = Follower::OscillatingRoller {
        pivot_distance: 90.0,
        arm_length: 70.0,
        radius: 8.0,
    };
    // The oscillating follower swings its arm by 20° (the program in radians).
    let deg = PI / 180.0;
    let swing = CamProgram::new(
        vec![
            Segment::law(MotionLaw::Cycloidal, 20.0 * deg, 120.0 * deg),
            Segment::law(MotionLaw::Dwell, 0.0, 60.0 * deg),
            Segment::law(MotionLaw::Polynomial345, -20.0 * deg, 120.0 * deg),
            Segment::law(MotionLaw::Dwell, 0.0, 60.0 * deg),
        ],
        0.0,
    )
    .unwrap();
    for (follower, program) in [
        (translating, rise_dwell_return_dwell()),
        (oscillating, swing),
    ] {
        let cam = CamMechanism::new(program, 40.0, follower).unwrap();
        let r = follower.roller_radius();
        for theta in angles() {
            let c = cam.contact(Dual64::from(theta).derivative(), Side::Right);
            let (p, x) = (
                [c.pitch[0].re, c.pitch[1].re],
                [c.profile[0].re, c.profile[1].re],
            );
            let tangent = [c.profile[0].eps, c.profile[1].eps];
            let gap = [p[0] - x[0], p[1] - x[1]];
            let distance = gap[0].hypot(gap[1]);
            assert!((distance - r).abs() <= 1e-12 * r, "{theta}: {distance}");
            let along = tangent[0] * gap[0] + tangent[1] * gap[1];
            let size = tangent[0].hypot(tangent[1]) * r;
            assert!(along.abs() <= 1e-12 * size, "{theta}: {along:e} of {size}");
        }
    }
}

/// The pressure angle of a translating offset roller equals tan⁻¹((s′ − e)/(√(R_p² − e²) + s))
/// (Norton, Design of Machinery, the pressure angle of an offset roller follower; R_p the
/// prime circle radius), with s and s′ of the program: 1e-12 rad.
#[test]
fn pressure_angle_matches_the_closed_form() {
    let (e, r, base) = (10.0, 8.0, 40.0);
    let program = rise_dwell_return_dwell();
    let cam = CamMechanism::new(
        program.clone(),
        base,
        Follower::Roller {
            offset: e,
            radius: r,
        },
    )
    .unwrap();
    let prime: f64 = base + r;
    for theta in angles() {
        let svaj = program.svaj(theta, Side::Right);
        let want = ((svaj.d1() - e) / ((prime * prime - e * e).sqrt() + svaj.value)).atan();
        let got = cam.pressure_angle(theta, Side::Right);
        assert!((got - want).abs() <= 1e-12, "{theta}: {got} vs {want}");
    }
}

/// The profile's radius of curvature (from the profile's own derivatives) is the pitch
/// curve's minus the roller radius (parallel curves), where the pitch curve is convex and
/// not flat: 1e-9 relative (the radii are 1/κ with κ from second derivatives).
#[test]
fn profile_curvature_is_the_parallel_curve_of_the_pitch_curve() {
    let r = 8.0;
    let cam = CamMechanism::new(
        rise_dwell_return_dwell(),
        40.0,
        Follower::Roller {
            offset: 10.0,
            radius: r,
        },
    )
    .unwrap();
    for theta in angles() {
        let pitch = 1.0 / cam.pitch_curvature(theta, Side::Right);
        if !(pitch > r && pitch < 1e4) {
            continue;
        }
        let profile = 1.0 / cam.profile_curvature(theta, Side::Right);
        assert!(
            (profile - (pitch - r)).abs() <= 1e-9 * pitch,
            "{theta}: {profile} vs {pitch} − {r}"
        );
    }
}

/// The test's own search for max |φ| over the turn, from the closed form: 3000 samples per
/// segment, then golden section around the best (independent of the library's search).
fn max_pressure_angle(program: &CamProgram, e: f64, prime: f64) -> f64 {
    let phi = |t: f64, side| {
        let j = program.svaj(t, side);
        ((j.d1() - e) / ((prime * prime - e * e).sqrt() + j.value))
            .atan()
            .abs()
    };
    let mut best: f64 = 0.0;
    for index in 0..program.len() {
        let (a, b) = (program.start(index), program.end(index));
        let n = 3000;
        let at = |t: f64| {
            phi(
                t,
                if t < 0.5 * (a + b) {
                    Side::Right
                } else {
                    Side::Left
                },
            )
        };
        let k = (0..=n)
            .max_by(|&i, &j| {
                let (x, y) = (
                    a + (b - a) * i as f64 / n as f64,
                    a + (b - a) * j as f64 / n as f64,
                );
                at(x).total_cmp(&at(y))
            })
            .unwrap();
        let h = (b - a) / n as f64;
        let (mut lo, mut hi) = (
            (a + h * (k as f64 - 1.0)).max(a),
            (a + h * (k as f64 + 1.0)).min(b),
        );
        for _ in 0..100 {
            let (m1, m2) = (lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0);
            if at(m1) < at(m2) {
                lo = m1;
            } else {
                hi = m2;
            }
        }
        best = best.max(at(0.5 * (lo + hi))).max(at(a)).max(at(b));
    }
    best
}

/// The sizing returns a base radius at which the largest pressure angle, found by the
/// test's own search on the closed form, equals the limit: 1e-10 rad.
#[test]
fn base_circle_sizing_reaches_the_pressure_angle_limit() {
    let program = rise_dwell_return_dwell();
    for (e, r, limit_deg) in [(10.0, 8.0, 30.0), (0.0, 5.0, 25.0), (-6.0, 0.0, 35.0)] {
        let follower = if r > 0.0 {
            Follower::Roller {
                offset: e,
                radius: r,
            }
        } else {
            Follower::KnifeEdge { offset: e }
        };
        let limit = f64::to_radians(limit_deg);
        let base = sizing::base_radius_for_pressure_angle(&program, follower, limit).unwrap();
        let found = max_pressure_angle(&program, e, base + r);
        assert!(
            (found - limit).abs() <= 1e-10,
            "e = {e}: {found} vs {limit}"
        );
        let analysed = CamMechanism::new(program.clone(), base, follower)
            .unwrap()
            .analyse()
            .max_pressure_angle
            .value;
        assert!((analysed - limit).abs() <= 1e-10);
    }
}

/// Flat face: the profile's radius of curvature is R_b + s + s″ (its smallest value found by
/// the library equals the test's own minimum over samples refined by ternary search, 1e-9);
/// the face spans s′ from −1.875h/β (3-4-5 return) to 2h/β (cycloidal rise), 1e-12
/// relative; the sizing for a smallest radius of 5 gives exactly that minimum.
#[test]
fn flat_face_curvature_width_and_sizing() {
    let program = rise_dwell_return_dwell();
    let base = sizing::base_radius_for_flat_face(&program, 5.0).unwrap();
    let cam = CamMechanism::new(program.clone(), base, Follower::FlatFaced).unwrap();
    let analysis = cam.analyse();
    let radius = |t: f64| {
        let j = program.svaj(t, Side::Right);
        base + j.value + j.d2()
    };
    let mut least = f64::INFINITY;
    for k in 0..20000 {
        least = least.min(radius((k as f64 + 0.5) * 2.0 * PI / 20000.0));
    }
    assert!((analysis.min_profile_radius.value - 5.0).abs() <= 1e-9);
    assert!(least >= 5.0 - 1e-9 && least - 5.0 < 1e-3, "{least}");
    let beta = 120f64.to_radians();
    let (low, high) = analysis.face_extent.unwrap();
    assert!((high - 2.0 * 20.0 / beta).abs() <= 1e-12 * high);
    assert!((low + 1.875 * 20.0 / beta).abs() <= 1e-12 * low.abs());
    assert!(analysis.undercut.is_empty());
    // A smaller base circle gives a cusp, reported with its cam angles inside the rise or
    // the return (where s″ is most negative).
    let small = CamMechanism::new(program, base - 8.0, Follower::FlatFaced).unwrap();
    let cusp = small.analyse();
    assert!(cusp.min_profile_radius.value < 0.0);
    assert!(!cusp.undercut.is_empty());
    for (from, to) in cusp.undercut {
        assert!(from < to && to < 300f64.to_radians(), "{from}..{to}");
    }
}

/// A roller larger than the pitch curve's smallest convex radius undercuts: the analysis
/// says where (inside the sharp rise–return, 0 to 90°), there κ r > 1, and the minimum
/// profile radius is negative; with a base circle of 40 the same roller fits.
#[test]
fn undercutting_is_reported_with_cam_angles() {
    let deg = PI / 180.0;
    let sharp = CamProgram::new(
        vec![
            Segment::law(MotionLaw::Cycloidal, 30.0, 45.0 * deg),
            Segment::law(MotionLaw::Polynomial345, -30.0, 45.0 * deg),
            Segment::law(MotionLaw::Dwell, 0.0, 270.0 * deg),
        ],
        0.0,
    )
    .unwrap();
    let follower = Follower::Roller {
        offset: 0.0,
        radius: 15.0,
    };
    let cam = CamMechanism::new(sharp.clone(), 10.0, follower).unwrap();
    let analysis = cam.analyse();
    assert!(analysis.min_profile_radius.value < 0.0);
    assert!(!analysis.undercut.is_empty());
    for &(from, to) in &analysis.undercut {
        assert!(0.0 < from && from < to && to < 90.0 * deg, "{from}..{to}");
        let mid = 0.5 * (from + to);
        assert!(cam.pitch_curvature(mid, Side::Right) * 15.0 > 1.0);
        // Just outside each range the roller fits (the ends are refined by bisection).
        for outside in [from - 1e-6, to + 1e-6] {
            assert!(cam.pitch_curvature(outside, Side::Right) * 15.0 < 1.0);
        }
    }
    let fine = CamMechanism::new(sharp, 40.0, follower).unwrap();
    assert!(fine.analyse().undercut.is_empty());
}

#[test]
fn bad_dimensions_and_programs_are_typed_errors() {
    let program = rise_dwell_return_dwell();
    let offset_too_big = Follower::Roller {
        offset: 50.0,
        radius: 5.0,
    };
    assert!(matches!(
        CamMechanism::new(program.clone(), 40.0, offset_too_big),
        Err(Error::CamDimension { ref what, .. }) if what == "offset"
    ));
    let no_roller = Follower::Roller {
        offset: 0.0,
        radius: 0.0,
    };
    assert!(matches!(
        CamMechanism::new(program.clone(), 40.0, no_roller),
        Err(Error::CamDimension { .. })
    ));
    assert!(matches!(
        CamMechanism::new(program, -1.0, Follower::FlatFaced),
        Err(Error::CamDimension { .. })
    ));
    let short = CamProgram::new(vec![Segment::law(MotionLaw::Dwell, 0.0, PI)], 0.0);
    assert!(matches!(short, Err(Error::CamTurn { total_deg }) if (total_deg - 180.0).abs() < 1e-9));
    let negative = CamProgram::new(
        vec![
            Segment::law(MotionLaw::Dwell, 0.0, 3.0 * PI),
            Segment::law(MotionLaw::Dwell, 0.0, -PI),
        ],
        0.0,
    );
    assert!(matches!(
        negative,
        Err(Error::CamSegment { segment: 2, .. })
    ));
    let nan = CamProgram::new(
        vec![Segment::law(MotionLaw::Cycloidal, f64::NAN, 2.0 * PI)],
        0.0,
    );
    assert!(matches!(nan, Err(Error::CamSegment { segment: 1, .. })));
    let open = CamProgram::new(
        vec![Segment::law(MotionLaw::Cycloidal, 10.0, 2.0 * PI)],
        0.0,
    );
    assert!(matches!(
        open,
        Err(Error::CamJoin {
            before: 1,
            after: 1,
            ..
        })
    ));
}
