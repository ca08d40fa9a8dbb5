//! Property tests of sweeps: over random slider-cranks and four-bars and random step sizes
//! (many straddling a blocked range), a sweep never returns a pose the mechanism cannot
//! reach on its sketch's branch, never jumps a blocked range, and its verdicts do not
//! depend on an unrelated far point or on the scale. The assembly conditions are computed
//! here from the closed forms, independently of the solver.

use crate::common;

use common::{four_bar, four_bar_rocker_pin};
use mechdiff_core::Error;
use mechdiff_core::geometry::{Drive, Mechanism, Solver};
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

/// Extremes of `f` (sin or cos) over [a, b] (either order): at the ends and at every
/// extremum `offset + kπ` inside.
fn range_of(f: fn(f64) -> f64, offset: f64, a: f64, b: f64) -> (f64, f64) {
    let (lo, hi) = (a.min(b), a.max(b));
    let mut values = vec![f(lo), f(hi)];
    let mut k = ((lo - offset) / PI).ceil();
    while offset + k * PI <= hi {
        values.push(f(offset + k * PI));
        k += 1.0;
    }
    let min = values.iter().copied().fold(f64::INFINITY, f64::min);
    let max = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (min, max)
}

/// Offset slider-crank (crank r about O, rod l, slider on y = e), sketched at φ0 with the
/// slider right of the crank pin, all lengths times `scale`, an extra ground point at
/// `far` (m) if given.
fn slider_crank(r: f64, l: f64, e: f64, phi0: f64, scale: f64, far: Option<f64>) -> Mechanism {
    let a = [r * phi0.cos(), r * phi0.sin()];
    let b = a[0] + (l * l - (e - a[1]).powi(2)).sqrt();
    let mut builder = Mechanism::builder()
        .point("O", [0.0, 0.0])
        .point("A", [a[0] * scale, a[1] * scale])
        .point("B", [b * scale, e * scale])
        .point("G0", [0.0, e * scale])
        .point("G1", [scale, e * scale]);
    let mut ground = vec!["O", "G0", "G1"];
    if let Some(x) = far {
        builder = builder.point("FAR", [x, -x]);
        ground.push("FAR");
    }
    builder
        .ground(ground)
        .link("crank", ["O", "A"])
        .link("rod", ["A", "B"])
        .link("slider", ["B"])
        .revolute("O", "ground", "crank", "O")
        .revolute("A", "crank", "rod", "A")
        .revolute("B", "rod", "slider", "B")
        .prismatic("guide", "ground", ["G0", "G1"], "slider", "B")
        .drive(Drive::angle("O").at_sketch(phi0))
        .build()
        .unwrap()
}

/// The drive positions φ0 + k h up to φ0 + 2π (h may be negative).
fn positions(phi0: f64, h: f64) -> Vec<f64> {
    let n = (2.0 * PI / h.abs()).ceil() as usize;
    (0..=n).map(|k| phi0 + k as f64 * h).collect()
}

/// Whether the slider-crank cannot assemble somewhere in [a, b]: |r sin φ − e| > l there,
/// i.e. sin φ leaves [(e − l)/r, (e + l)/r].
fn slider_crank_blocked(r: f64, l: f64, e: f64, a: f64, b: f64) -> bool {
    let (min, max) = range_of(f64::sin, FRAC_PI_2, a, b);
    r * max - e > l || e - r * min > l
}

/// Whether the four-bar cannot assemble somewhere in [a, b]: |A − B0|² = ca + cb cos φ
/// leaves [(b − c)², (b + c)²].
fn four_bar_blocked(lengths: [f64; 4], from: f64, to: f64) -> bool {
    let [a, b, c, d] = lengths;
    let (min, max) = range_of(f64::cos, 0.0, from, to);
    let reach = |cos: f64| a * a + d * d - 2.0 * a * d * cos;
    // cos min gives the largest distance, cos max the smallest.
    reach(min) > (b + c).powi(2) || reach(max) < (b - c).powi(2)
}

/// Checks one sweep against the independent assembly condition `blocked` over each step,
/// and each pose (point B of `link`) with `check_pose`; returns the limit position met.
fn check_sweep(
    m: &Mechanism,
    link: &str,
    phis: &[f64],
    blocked: impl Fn(f64, f64) -> bool,
    at_limit: impl Fn(f64) -> f64,
    check_pose: impl Fn(f64, [f64; 2]) -> Result<(), TestCaseError>,
) -> Result<Option<f64>, TestCaseError> {
    let mut t = Solver::default().track(m).unwrap();
    let mut last = phis[0];
    for &phi in phis {
        match t.move_to(phi) {
            Ok(_) => {
                // Never past a blocked range.
                prop_assert!(
                    !blocked(last, phi),
                    "jumped a blocked range in [{last}, {phi}]"
                );
                let k = t.kinematics::<1>().unwrap();
                let p = k.point(link, "B").unwrap();
                check_pose(phi, [p[0].value, p[1].value])?;
                last = phi;
            }
            Err(Error::Blocked {
                from, to, limit, ..
            }) => {
                prop_assert_eq!((from, to), (last, phi));
                // A real blocked range lies in the step, and the limit is on its edge: the
                // assembly condition's residual vanishes there (1e-9 relative: the limit is
                // refined to rounding; the condition's slope is O(1)).
                prop_assert!(blocked(from, to), "no blocked range in [{from}, {to}]");
                prop_assert!(
                    at_limit(limit).abs() < 1e-9,
                    "limit {limit}: {}",
                    at_limit(limit)
                );
                prop_assert!((limit - from) * (to - limit) >= 0.0);
                return Ok(Some(limit));
            }
            Err(e) => return Err(TestCaseError::fail(format!("{e}"))),
        }
    }
    Ok(None)
}

proptest! {
    // 48 cases each: a sweep is ≤ 360 closed-form positions, milliseconds in debug.
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Random offset slider-cranks and step sizes: every pose returned is the sketch
    /// branch's closed form x_B = r cos φ + √(l² − (e − r sin φ)²), and a step across a
    /// blocked range ends in `Blocked` at a limit where |r sin φ − e| = l.
    #[test]
    fn slider_crank_sweeps_never_jump_or_change_branch(
        r in 0.2f64..2.0,
        rod in 0.3f64..3.0,
        offset in -1.0f64..1.0,
        phi0 in -PI..PI,
        step_degrees in prop::sample::select(vec![-45.0f64, -20.0, -7.0, 3.0, 10.0, 20.0, 33.0, 60.0]),
    ) {
        let (l, e) = (rod, offset);
        // Only sketches that assemble with room (|r sin φ0 − e| ≤ 0.99 l).
        prop_assume!((r * phi0.sin() - e).abs() <= 0.99 * l);
        let m = slider_crank(r, l, e, phi0, 1.0, None);
        let phis = positions(phi0, step_degrees.to_radians());
        let verdict = check_sweep(
            &m,
            "rod",
            &phis,
            |a, b| slider_crank_blocked(r, l, e, a, b),
            |phi| ((r * phi.sin() - e).abs() - l) / l,
            |phi, p| {
                let exact = r * phi.cos() + (l * l - (e - r * phi.sin()).powi(2)).sqrt();
                // 1e-9 relative to the mechanism: the closed form and the solver agree to
                // rounding except right at a limit, where √ amplifies it (≤ 1e-4 rad away
                // the margin is ≥ 1e-8: error ≤ ε/√1e-8 ≈ 2e-12).
                prop_assert!((p[0] - exact).abs() < 1e-9 * (r + l), "φ = {phi}: {} vs {exact}", p[0]);
                prop_assert!((p[1] - e).abs() < 1e-12 * (r + l));
                Ok(())
            },
        )?;
        if verdict.is_none() {
            prop_assert!(!slider_crank_blocked(r, l, e, phis[0], *phis.last().unwrap()));
        }
    }

    /// Narrow blocked ranges (width 1e-3 to 0.3 rad, often inside one 1/8 rad sub-step):
    /// the rod is just too short to reach the guide around φ = −π/2 (e ≥ 0, l = e +
    /// r cos(w/2): blocked where sin φ < −cos(w/2)).
    #[test]
    fn narrow_blocked_ranges_are_never_jumped(
        r in 0.2f64..2.0,
        offset in 0.0f64..1.0,
        width in 1e-3f64..0.3,
        phi0 in -1.0f64..1.0,
        step_degrees in prop::sample::select(vec![-45.0f64, -20.0, -7.0, 3.0, 10.0, 20.0, 33.0]),
    ) {
        let e = offset;
        let l = e + r * (0.5 * width).cos();
        let m = slider_crank(r, l, e, phi0, 1.0, None);
        let phis = positions(phi0, step_degrees.to_radians());
        let verdict = check_sweep(
            &m,
            "rod",
            &phis,
            |a, b| slider_crank_blocked(r, l, e, a, b),
            |phi| ((r * phi.sin() - e).abs() - l) / l,
            |_, _| Ok(()),
        )?;
        // Every sweep of a full turn meets the range.
        prop_assert!(verdict.is_some());
    }

    /// Random four-bars (any Grashof class) and step sizes: every pose is the sketch
    /// closure's rocker pin, and blocked ranges end the sweep at a limit position where
    /// |A − B0| = b ± c.
    #[test]
    fn four_bar_sweeps_never_jump_or_change_branch(
        lengths in prop::array::uniform4(0.1f64..1.0),
        phi0 in -PI..PI,
        up in any::<bool>(),
        step_degrees in prop::sample::select(vec![-40.0f64, -15.0, 5.0, 12.0, 25.0, 50.0]),
    ) {
        let [a, b, c, d] = lengths;
        let pa = [a * phi0.cos(), a * phi0.sin()];
        let reach = (d - pa[0]).hypot(pa[1]);
        // Only sketches that assemble with room.
        prop_assume!(reach < 0.99 * (b + c) && reach > 1.01 * (b - c).abs());
        prop_assume!(four_bar_rocker_pin(pa, b, c, d, up).is_some());
        let m = four_bar(a, b, c, d, phi0, up).unwrap();
        let phis = positions(phi0, step_degrees.to_radians());
        let verdict = check_sweep(
            &m,
            "rocker",
            &phis,
            |x, y| four_bar_blocked(lengths, x, y),
            |phi| {
                let dist = (a * a + d * d - 2.0 * a * d * phi.cos()).sqrt();
                ((dist - (b + c)).abs()).min((dist - (b - c).abs()).abs()) / (b + c)
            },
            |phi, p| {
                let exact = four_bar_rocker_pin([a * phi.cos(), a * phi.sin()], b, c, d, up)
                    .unwrap_or([f64::NAN; 2]);
                // 1e-9 of the mechanism's size, as for the slider-crank.
                let size = a + b + c + d;
                prop_assert!((p[0] - exact[0]).hypot(p[1] - exact[1]) < 1e-9 * size,
                    "φ = {phi}: {p:?} vs {exact:?}");
                Ok(())
            },
        )?;
        if verdict.is_none() {
            prop_assert!(!four_bar_blocked(lengths, phis[0], *phis.last().unwrap()));
        }
    }

    /// An unrelated ground point 1e6 m away, or the whole mechanism scaled by 1e-3 or 1e3:
    /// the same verdict, the same limit position, the same poses (scaled) to rounding.
    #[test]
    fn far_points_and_scale_change_no_verdict(
        r in 0.2f64..2.0,
        rod in 0.3f64..3.0,
        offset in -1.0f64..1.0,
        phi0 in -PI..PI,
        scale in prop::sample::select(vec![1e-3, 1.0, 1e3]),
        far in prop::sample::select(vec![None, Some(3e4), Some(1e6)]),
    ) {
        let (l, e) = (rod, offset);
        prop_assume!((r * phi0.sin() - e).abs() <= 0.99 * l);
        let phis = positions(phi0, 0.3);
        let (m1, m2) = (slider_crank(r, l, e, phi0, 1.0, None), slider_crank(r, l, e, phi0, scale, far));
        let reference = Solver::default().sweep::<1>(&m1, &phis);
        let got = Solver::default().sweep::<1>(&m2, &phis);
        match (reference, got) {
            (Ok(x), Ok(y)) => {
                for (x, y) in x.iter().zip(&y) {
                    let (px, py) = (x.point("rod", "B").unwrap(), y.point("rod", "B").unwrap());
                    // 1e-12 relative to the mechanism: the same formulas on scaled inputs.
                    prop_assert!((py[0].value / scale - px[0].value).abs() < 1e-12 * (r + l));
                    prop_assert!((py[0].d1() / scale - px[0].d1()).abs() < 1e-9 * (r + l));
                }
            }
            (Err(Error::Blocked { limit: a, .. }), Err(Error::Blocked { limit: b, .. })) => {
                // 1e-12: both refined to rounding.
                prop_assert!((a - b).abs() < 1e-12, "{a} vs {b}");
            }
            (x, y) => prop_assert!(false, "different verdicts: {x:?} vs {y:?}"),
        }
    }
}
