//! Linkage metrics against closed forms written here: Grashof's inequality, the input's
//! range and the transmission angle by the law of cosines, the time ratio from the dead
//! positions of a crank-rocker and of offset slider-cranks, and a four-bar inside a six-bar.
//!
//! **Tolerance 1e-12** throughout: every quantity compared is an angle (rad) or a length
//! of order 0.1–1 m computed by a few dozen floating-point operations from the sketch, so
//! its rounding is ~100 ε ≈ 2e-14 where the formula is well conditioned (the comparisons
//! of μ stay where sin μ > 0.05, so acos amplifies rounding at most twentyfold; dead
//! positions are refined by Newton to full precision). 1e-12 leaves a factor of ~50 above
//! that, while a wrong formula, branch, convention or link (degrees for radians, crank for
//! rocker, the other assembly) is off by 1e-3 or more.

use crate::common::whitworth;
use mechdiff_core::geometry::{Drive, LimitKind, Mechanism, MechanismBuilder, Solver};
use mechdiff_core::metrics::{
    FourBarLoop, GrashofClass, InputRange, LinkageMetrics, Loops, MetricsError, QuickReturn,
    SliderCrankClass, Toggle,
};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

const TOL: f64 = 1e-12;

fn close(what: &str, got: f64, want: f64) {
    assert!(
        (got - want).abs() <= TOL,
        "{what}: got {got}, closed form {want} (difference {:e})",
        got - want
    );
}

/// The point at distance `r1` from `p` and `r2` from `q`, on the left of p → q when `side`
/// is +1, on the right when −1.
fn circles(p: [f64; 2], r1: f64, q: [f64; 2], r2: f64, side: f64) -> [f64; 2] {
    let e = [q[0] - p[0], q[1] - p[1]];
    let d = e[0].hypot(e[1]);
    let (u, n) = ([e[0] / d, e[1] / d], [-e[1] / d, e[0] / d]);
    let g = (r1 * r1 - r2 * r2 + d * d) / (2.0 * d);
    let h = (r1 * r1 - g * g).sqrt();
    assert!(h.is_finite(), "the sketch does not assemble");
    [
        p[0] + g * u[0] + side * h * n[0],
        p[1] + g * u[1] + side * h * n[1],
    ]
}

/// The four-bar's points and links: O2 at the origin, O4 = (d, 0), crank pin A at input
/// angle θ, B on the `side` of A → O4; φ = θ.
fn four_bar_parts(abcd: [f64; 4], theta: f64, side: f64) -> MechanismBuilder {
    four_bar_driven(abcd, theta, side, ["ground", "crank"], theta)
}

/// [`four_bar_parts`] with the crank's pivot joining `pivot` (link a, link b: φ is b's
/// rotation relative to a) and φ = `phi` at the sketch.
fn four_bar_driven(
    [a, b, c, d]: [f64; 4],
    theta: f64,
    side: f64,
    pivot: [&str; 2],
    phi: f64,
) -> MechanismBuilder {
    let pin = [a * theta.cos(), a * theta.sin()];
    Mechanism::builder()
        .point("O2", [0.0, 0.0])
        .point("O4", [d, 0.0])
        .point("A", pin)
        .point("B", circles(pin, b, [d, 0.0], c, side))
        .link("crank", ["O2", "A"])
        .link("rocker", ["O4", "B"])
        .revolute("O2", pivot[0], pivot[1], "O2")
        .revolute("A", "crank", "coupler", "A")
        .revolute("B", "coupler", "rocker", "B")
        .revolute("O4", "ground", "rocker", "O4")
        .drive(Drive::angle("O2").at_sketch(phi))
}

fn four_bar(abcd: [f64; 4], theta: f64, side: f64) -> Mechanism {
    four_bar_parts(abcd, theta, side)
        .ground(["O2", "O4"])
        .link("coupler", ["A", "B"])
        .build()
        .unwrap()
}

/// An offset slider-crank: crank pivot O at the origin, crank pin A at θ, slider pin B on
/// the path y = e ahead of A (+x); φ = θ.
fn slider_crank([r, l, e]: [f64; 3], theta: f64) -> Mechanism {
    let pin = [r * theta.cos(), r * theta.sin()];
    let ahead = (l * l - (e - pin[1]) * (e - pin[1])).sqrt();
    Mechanism::builder()
        .point("O", [0.0, 0.0])
        .point("A", pin)
        .point("B", [pin[0] + ahead, e])
        .point("G0", [0.0, e])
        .point("G1", [1.0, e])
        .ground(["O", "G0", "G1"])
        .link("crank", ["O", "A"])
        .link("rod", ["A", "B"])
        .link("slider", ["B"])
        .revolute("O", "ground", "crank", "O")
        .revolute("A", "crank", "rod", "A")
        .revolute("B", "rod", "slider", "B")
        .prismatic("guide", "ground", ["G0", "G1"], "slider", "B")
        .drive(Drive::angle("O").at_sketch(theta))
        .build()
        .unwrap()
}

/// μ by the law of cosines: cos μ = (b² + c² − a² − d² + 2ad cos θ)/(2bc).
fn law_of_cosines([a, b, c, d]: [f64; 4], theta: f64) -> f64 {
    ((b * b + c * c - a * a - d * d + 2.0 * a * d * theta.cos()) / (2.0 * b * c)).acos()
}

/// The only four-bar loop of `m`.
fn the_four_bar(m: &Mechanism) -> FourBarLoop {
    let loops = Loops::find(m).unwrap();
    assert_eq!(loops.four_bars.len(), 1, "{loops:#?}");
    loops.four_bars[0].clone()
}

/// A textbook four-bar of each class: lengths [a, b, c, d] (m), a sketch angle inside the
/// input's range, the class, and the shortest and longest links.
struct Case {
    abcd: [f64; 4],
    theta: f64,
    class: GrashofClass,
    shortest: &'static str,
    longest: &'static str,
}

fn cases() -> Vec<Case> {
    let case = |abcd, degrees: f64, class, shortest, longest| Case {
        abcd,
        theta: degrees.to_radians(),
        class,
        shortest,
        longest,
    };
    vec![
        // scenes/four_bar.toml: s + l = 0.1 + √0.2 = 0.547 < 0.7, the crank shortest.
        case(
            [0.1, 0.2f64.sqrt(), 0.3, 0.4],
            90.0,
            GrashofClass::CrankRocker,
            "crank",
            "coupler",
        ),
        // 0.1 + 0.45 < 0.3 + 0.4, the rocker (output) shortest: the input rocks within
        // [acos(0.53125), acos(−0.21875)] = [57.9°, 102.6°].
        case(
            [0.3, 0.45, 0.1, 0.4],
            80.0,
            GrashofClass::RockerCrank,
            "rocker",
            "coupler",
        ),
        // The frame shortest: a drag link.
        case(
            [0.3, 0.45, 0.4, 0.1],
            90.0,
            GrashofClass::DoubleCrank,
            "ground",
            "coupler",
        ),
        // The coupler shortest: input in [41.4°, 80.9°].
        case(
            [0.3, 0.1, 0.4, 0.45],
            60.0,
            GrashofClass::DoubleRocker,
            "coupler",
            "ground",
        ),
        // a + b = c + d (0.1 + 0.3 = 0.2 + 0.2): |a − d| = |b − c|, it folds flat at θ = 0.
        case(
            [0.1, 0.3, 0.2, 0.2],
            90.0,
            GrashofClass::ChangePoint,
            "crank",
            "coupler",
        ),
        // Norton's non-Grashof linkage (scenes/norton_four_bar.toml): 0.86 + 2.22 > 0.86 +
        // 1.85; the input rocks through θ = 0 within ±116°.
        case(
            [0.86, 1.85, 0.86, 2.22],
            30.0,
            GrashofClass::TripleRocker,
            "crank",
            "ground",
        ),
        // Non-Grashof rocking through θ = 180°: 0.05 + 0.2 > 0.1 + 0.12.
        case(
            [0.1, 0.2, 0.05, 0.12],
            150.0,
            GrashofClass::TripleRocker,
            "rocker",
            "coupler",
        ),
    ]
}

/// Grashof's class of each textbook four-bar, with s + l and p + q equal to the sums of its
/// lengths; the class does not change when the linkage is drawn a thousand times smaller or
/// larger (the change point's tolerance scales with the lengths).
#[test]
fn grashof_classes_of_textbook_four_bars_follow_the_inequality() {
    for scale in [1e-3, 1e3] {
        for case in cases() {
            let m = four_bar(case.abcd.map(|x| x * scale), case.theta, 1.0);
            let g = the_four_bar(&m).grashof();
            assert_eq!(g.class, case.class, "scaled by {scale}: {g}");
        }
    }
    for case in cases() {
        let m = four_bar(case.abcd, case.theta, 1.0);
        let linkage = the_four_bar(&m);
        let g = linkage.grashof();
        assert_eq!(g.class, case.class, "{g}");
        assert_eq!(
            (g.shortest.link.as_str(), g.longest.link.as_str()),
            (case.shortest, case.longest),
            "{g}"
        );
        let mut sorted = case.abcd;
        sorted.sort_by(f64::total_cmp);
        close("s + l", g.s_plus_l, sorted[0] + sorted[3]);
        close("p + q", g.p_plus_q, sorted[1] + sorted[2]);
        assert!(linkage.driven);
        // A time ratio needs a crank input and a rocking output: the crank-rocker only.
        let metrics = LinkageMetrics::of(&m, &Solver::default()).unwrap();
        let quick_return = &metrics.four_bars[0].quick_return;
        match case.class {
            GrashofClass::CrankRocker => assert!(quick_return.is_ok()),
            GrashofClass::DoubleCrank => {
                assert_eq!(quick_return, &Err(MetricsError::DeadPositions { found: 0 }))
            }
            _ => assert!(
                matches!(quick_return, Err(MetricsError::CrankDoesNotTurn { .. })),
                "{}: {quick_return:?}",
                case.class.name()
            ),
        }
    }
}

/// Which link is the frame decides the class: the four inversions of one Grashof chain
/// (lengths 0.1, 0.3, 0.4, 0.45 around the loop) are a crank-rocker, a double-crank, a
/// rocker-crank and a double-rocker.
#[test]
fn grashof_inversions_of_one_chain_differ_by_their_frame() {
    // Around the loop: s = 0.1, then 0.45, 0.4, 0.3. Each inversion fixes a different link.
    let chain = [0.1, 0.45, 0.4, 0.3];
    let expected = [
        (GrashofClass::CrankRocker, 90.0), // frame 0.3: the shortest is the input
        (GrashofClass::DoubleRocker, 80.0), // frame 0.4: the shortest is the coupler
        (GrashofClass::RockerCrank, 40.0), // frame 0.45: the shortest is the output
        (GrashofClass::DoubleCrank, 90.0), // frame 0.1
    ];
    for (k, (class, degrees)) in expected.into_iter().enumerate() {
        // Rotate the chain so that link 3 − k is the frame: [a, b, c, d] around the loop.
        let abcd: [f64; 4] = std::array::from_fn(|i| chain[(i + 4 - k) % 4]);
        let g = the_four_bar(&four_bar(abcd, f64::to_radians(degrees), 1.0)).grashof();
        assert_eq!(g.class, class, "frame {}: {g}", abcd[3]);
    }
}

/// The input's range of each textbook four-bar by the law of cosines: the loop closes iff
/// (b − c)² ≤ a² + d² − 2ad cos θ ≤ (b + c)², i.e. k_out ≤ cos θ ≤ k_in; its ends are
/// toggles (μ = 0 where cos θ = k_in, μ = 180° where cos θ = k_out), and the solver's own
/// walk of the drive stops there too. μ's extremes: at θ = 0 and 180° where the input
/// passes them, else 0 or 180° at an end.
#[test]
fn input_ranges_and_transmission_extremes_follow_the_law_of_cosines() {
    for case in cases() {
        let [a, b, c, d] = case.abcd;
        let k_in = (a * a + d * d - (b - c) * (b - c)) / (2.0 * a * d);
        let k_out = (a * a + d * d - (b + c) * (b + c)) / (2.0 * a * d);
        let m = four_bar(case.abcd, case.theta, 1.0);
        let linkage = the_four_bar(&m);
        let range = linkage.input_range();
        let mu = linkage.transmission_extremes();
        let drive = LinkageMetrics::of(&m, &Solver::default()).unwrap().drive;
        let name = case.class.name();
        // (lower, upper, toggles) of a rocking input; μ's extremes (θ, μ).
        let (ends, min, max) = match case.class {
            GrashofClass::CrankRocker | GrashofClass::DoubleCrank => (
                None,
                (0.0, law_of_cosines(case.abcd, 0.0)),
                (PI, law_of_cosines(case.abcd, PI)),
            ),
            GrashofClass::ChangePoint => {
                let InputRange::Full { change_points } = &range else {
                    panic!("{name}: {range:?}");
                };
                assert_eq!(change_points.len(), 1);
                close("change point", change_points[0].angle, 0.0);
                // The solver walks up to the change point, a turn on from the sketch's
                // side: θ = 2π (and θ = 0 below).
                let limit = drive.range.upper.as_ref().expect("a change point");
                assert_eq!(limit.kind, LimitKind::ChangePoint, "{drive}");
                close("solver's change point above", limit.phi, TAU);
                let below = drive.range.lower.as_ref().expect("a change point");
                assert_eq!(below.kind, LimitKind::ChangePoint, "{drive}");
                close("solver's change point below", below.phi, 0.0);
                (
                    None,
                    (0.0, law_of_cosines(case.abcd, 0.0)),
                    (PI, law_of_cosines(case.abcd, PI)),
                )
            }
            GrashofClass::RockerCrank | GrashofClass::DoubleRocker => {
                let (lo, hi) = (k_in.acos(), k_out.acos());
                let ends = (lo, hi, [Toggle::Folded, Toggle::Extended]);
                (Some(ends), (lo, 0.0), (hi, PI))
            }
            GrashofClass::TripleRocker if k_in >= 1.0 => {
                let hi = k_out.acos();
                let ends = (-hi, hi, [Toggle::Extended; 2]);
                (Some(ends), (0.0, law_of_cosines(case.abcd, 0.0)), (hi, PI))
            }
            GrashofClass::TripleRocker => {
                let lo = k_in.acos();
                let ends = (lo, TAU - lo, [Toggle::Folded; 2]);
                (Some(ends), (lo, 0.0), (PI, law_of_cosines(case.abcd, PI)))
            }
        };
        match (ends, &range) {
            (None, InputRange::Full { .. }) => {
                if case.class != GrashofClass::ChangePoint {
                    assert!(drive.turns_fully(), "{name}: {drive}");
                }
            }
            (Some((lo, hi, toggles)), InputRange::Rocks { lower, upper, .. }) => {
                close(&format!("{name}: lower end"), lower.at.angle, lo);
                close(&format!("{name}: upper end"), upper.at.angle, hi);
                assert_eq!([lower.toggle, upper.toggle], toggles, "{name}");
                // φ = θ: the drive positions equal the angles, and the solver stops there.
                close(&format!("{name}: lower φ"), lower.at.drive.unwrap(), lo);
                let (below, above) = (drive.range.lower.unwrap(), drive.range.upper.unwrap());
                assert_eq!(
                    (below.kind, above.kind),
                    (LimitKind::Limit, LimitKind::Limit)
                );
                close(&format!("{name}: solver's lower limit"), below.phi, lo);
                close(&format!("{name}: solver's upper limit"), above.phi, hi);
            }
            (ends, range) => panic!("{name}: expected ends {ends:?}, got {range:?}"),
        }
        // Where μ is extreme: the angle up to the sign where the ends are symmetric.
        close(&format!("{name}: min μ"), mu.min.angle, min.1);
        close(&format!("{name}: max μ"), mu.max.angle, max.1);
        close(
            &format!("{name}: where min μ"),
            mu.min.at.angle.abs(),
            min.0,
        );
        close(
            &format!("{name}: where max μ"),
            mu.max.at.angle.abs(),
            max.0,
        );
        let worst = min.1.min(PI - max.1);
        close(&format!("{name}: worst effective μ"), mu.worst.angle, worst);
    }
}

/// At 360 crank angles of a crank-rocker and a drag link (both branches), and across the
/// range of Norton's triple-rocker, μ read from the solved pose equals the law of cosines;
/// the signed form carries the branch, the effective form is min(μ, 180° − μ), and μ′
/// equals the law of cosines differentiated: μ′ = ad sin θ / (bc sin μ).
#[test]
fn transmission_angle_at_each_pose_is_the_law_of_cosines() {
    let crank_rocker = [0.1, 0.2f64.sqrt(), 0.3, 0.4];
    let drag_link = [0.3, 0.45, 0.4, 0.1];
    let norton = [0.86, 1.85, 0.86, 2.22];
    let limit = f64::acos((0.86f64 * 0.86 + 2.22 * 2.22 - 2.71 * 2.71) / (2.0 * 0.86 * 2.22));
    let turn: Vec<f64> = (0..360).map(|k| f64::to_radians(k as f64)).collect();
    // Norton's input within its limits, 3° short of them (sin μ > 0.05 there).
    let rocking: Vec<f64> = (0..200)
        .map(|k| -limit + 0.05 + (2.0 * limit - 0.1) * k as f64 / 199.0)
        .collect();
    for (abcd, side, thetas) in [
        (crank_rocker, 1.0, &turn),
        (crank_rocker, -1.0, &turn),
        (drag_link, 1.0, &turn),
        (norton, -1.0, &rocking),
    ] {
        let m = four_bar(abcd, FRAC_PI_2.min(thetas[0] + 0.5), side);
        let linkage = the_four_bar(&m);
        assert_eq!(linkage.branch, side);
        let mut tracker = Solver::default().track(&m).unwrap();
        for &theta in thetas {
            tracker.move_to(theta).unwrap();
            let mu = linkage.transmission_at(&tracker.kinematics::<2>().unwrap());
            let want = law_of_cosines(abcd, theta);
            assert!(want.sin() > 0.05);
            let at = format!("{abcd:?} at θ = {theta}");
            close(&format!("μ, {at}"), mu.unsigned.value, want);
            close(&format!("signed μ, {at}"), mu.signed.value, side * want);
            close(
                &format!("effective μ, {at}"),
                mu.effective.value,
                want.min(PI - want),
            );
            close(
                &format!("deviation, {at}"),
                mu.deviation.value,
                FRAC_PI_2 - want.min(PI - want),
            );
            let [a, b, c, d] = abcd;
            let slope = a * d * theta.sin() / (b * c * want.sin());
            close(&format!("μ′, {at}"), mu.unsigned.d1(), slope);
            close(
                &format!("closed form, {at}"),
                linkage.transmission_angle(theta),
                want,
            );
        }
    }
}

/// The crank-rocker of scenes/four_bar.toml (a = 0.1, b = √0.2, c = 0.3, d = 0.4 m).
const CRANK_ROCKER: [f64; 4] = [0.1, 0.4472135954999579, 0.3, 0.4]; // b = √0.2

/// The closed form of a crank-rocker's quick return on branch `side`: the rocker's dead
/// positions are where crank and coupler are in line, |O₂B| = b + a (extended) and b − a
/// (folded); in triangle O₂ O₄ B the crank's angle from the frame is
/// α₁ = acos((d² + (a + b)² − c²)/(2d(a + b))) extended, and the crank points away from B at
/// π + α₂, α₂ = acos((d² + (b − a)² − c²)/(2d(b − a))) folded (B above the frame on branch
/// +1, mirrored on −1). Returns (extended φ, folded φ, δ = α₂ − α₁, swing).
fn crank_rocker_dead_positions([a, b, c, d]: [f64; 4], side: f64) -> (f64, f64, f64, f64) {
    let alpha1 = ((d * d + (a + b) * (a + b) - c * c) / (2.0 * d * (a + b))).acos();
    let alpha2 = ((d * d + (b - a) * (b - a) - c * c) / (2.0 * d * (b - a))).acos();
    // The rocker's angle at O₄ in the same triangles.
    let gamma1 = ((d * d + c * c - (a + b) * (a + b)) / (2.0 * d * c)).acos();
    let gamma2 = ((d * d + c * c - (b - a) * (b - a)) / (2.0 * d * c)).acos();
    (
        side * alpha1,
        PI + side * alpha2,
        alpha2 - alpha1,
        gamma1 - gamma2,
    )
}

/// `phi` equals `want` up to whole turns.
fn same_angle(what: &str, phi: f64, want: f64) {
    let turns = ((phi - want) / TAU).round();
    close(what, phi - turns * TAU, want);
}

/// The time ratio of a crank-rocker from its dead positions: Q = (180° + δ)/(180° − δ)
/// with δ = α₂ − α₁, the forward stroke from the extended to the folded dead position
/// (branch +1) or from the folded to the extended (−1), and the swing γ₁ − γ₂.
fn check_crank_rocker_quick_return(q: &QuickReturn, abcd: [f64; 4], side: f64) {
    let (extended, folded, delta, swing) = crank_rocker_dead_positions(abcd, side);
    close("forward crank angle", q.forward.crank_angle, PI + delta);
    close("return crank angle", q.back.crank_angle, PI - delta);
    close("time ratio", q.time_ratio, (PI + delta) / (PI - delta));
    close("swing", q.travel, swing);
    let (start, end) = if side > 0.0 {
        (extended, folded)
    } else {
        (folded, extended)
    };
    same_angle("forward stroke's start", q.forward.from, start);
    same_angle("forward stroke's end", q.forward.to, end);
    same_angle("return stroke's start", q.back.from, end);
}

#[test]
fn time_ratio_of_a_crank_rocker_is_the_closed_form_from_its_dead_positions() {
    for side in [1.0, -1.0] {
        let m = four_bar(CRANK_ROCKER, FRAC_PI_2, side);
        let metrics = LinkageMetrics::of(&m, &Solver::default()).unwrap();
        let q = metrics.four_bars[0].quick_return.as_ref().unwrap();
        check_crank_rocker_quick_return(q, CRANK_ROCKER, side);
        assert!(
            q.time_ratio > 1.17 && q.time_ratio < 1.18,
            "{}",
            q.time_ratio
        );
    }
}

/// An offset slider-crank's dead positions: crank and rod stretched in line at
/// θ₁ = asin(e/(l + r)), folded at θ₂ = π + asin(e/(l − r)); the stroke
/// √((l + r)² − e²) − √((l − r)² − e²), and Q = (180° + |δ|)/(180° − |δ|) with
/// δ = asin(e/(l − r)) − asin(e/(l + r)).
#[test]
fn time_ratio_and_stroke_of_offset_slider_cranks_are_the_closed_forms() {
    // scenes/slider_crank.toml (r = 100, l = 400, e = −12 mm), and a strongly offset one.
    for rle in [[0.1, 0.4, -0.012], [0.1, 0.3, 0.1]] {
        let [r, l, e] = rle;
        let m = slider_crank(rle, FRAC_PI_2);
        let metrics = LinkageMetrics::of(&m, &Solver::default()).unwrap();
        assert!(metrics.four_bars.is_empty() && metrics.not_applicable.is_empty());
        let sc = &metrics.slider_cranks[0];
        assert_eq!(sc.linkage.slider.as_deref(), Some("slider"));
        close("crank", sc.linkage.lengths.crank, r);
        close("rod", sc.linkage.lengths.rod, l);
        close("offset", sc.linkage.lengths.offset, e);
        assert_eq!(
            sc.criterion.class,
            SliderCrankClass::Crank,
            "{}",
            sc.criterion
        );
        close("r + |e|", sc.criterion.crank_plus_offset, r + e.abs());
        let q = sc.quick_return.as_ref().unwrap();
        let (theta1, theta2) = ((e / (l + r)).asin(), PI + (e / (l - r)).asin());
        let delta = ((e / (l - r)).asin() - (e / (l + r)).asin()).abs();
        let stroke = ((l + r) * (l + r) - e * e).sqrt() - ((l - r) * (l - r) - e * e).sqrt();
        close("stroke", q.travel, stroke);
        close("time ratio", q.time_ratio, (PI + delta) / (PI - delta));
        close("forward crank angle", q.forward.crank_angle, PI + delta);
        // Which dead position comes first depends on where the turn starts (the sketch).
        for (what, want) in [("stretched", theta1), ("folded", theta2)] {
            let apart = |phi: f64| (phi - want - ((phi - want) / TAU).round() * TAU).abs();
            let found =
                (q.dead_positions.iter()).min_by(|x, y| apart(x.phi).total_cmp(&apart(y.phi)));
            same_angle(&format!("{what} dead position"), found.unwrap().phi, want);
        }
        // μ: least at θ = 90° (acos((r − e)/l)), greatest at −90° (acos((−r − e)/l)).
        let mu = &sc.transmission;
        close("min μ", mu.min.angle, ((r - e) / l).acos());
        close("max μ", mu.max.angle, ((-r - e) / l).acos());
        close("where min μ", mu.min.at.angle, FRAC_PI_2);
        same_angle("where max μ", mu.max.at.angle, -FRAC_PI_2);
        close(
            "worst effective μ",
            mu.worst.angle,
            ((r + e.abs()) / l).acos(),
        );
    }
}

/// μ of a slider-crank at each of 360 solved poses equals acos((r sin θ − e)/l), the
/// signed form carrying the branch (B ahead of the crank along +x: −1).
#[test]
fn slider_crank_transmission_angle_at_each_pose_is_the_closed_form() {
    let rle = [0.1, 0.3, 0.1];
    let [r, l, e] = rle;
    let m = slider_crank(rle, FRAC_PI_2);
    let linkage = Loops::find(&m).unwrap().slider_cranks.remove(0);
    assert_eq!(linkage.branch, -1.0);
    let mut tracker = Solver::default().track(&m).unwrap();
    for k in 0..360 {
        let theta = f64::to_radians(k as f64);
        tracker.move_to(theta).unwrap();
        let mu = linkage.transmission_at(&tracker.kinematics::<1>().unwrap());
        let want = ((r * theta.sin() - e) / l).acos();
        close(&format!("μ at θ = {theta}"), mu.unsigned.value, want);
        close(&format!("signed μ at θ = {theta}"), mu.signed.value, -want);
        // μ′ = −r cos θ / (l sin μ).
        let slope = -r * theta.cos() / (l * want.sin());
        close(&format!("μ′ at θ = {theta}"), mu.unsigned.d1(), slope);
    }
}

/// A slider-crank whose crank cannot turn (r + |e| = 0.2 > l = 0.15): it rocks between the
/// positions where the rod stands perpendicular to the path, sin θ = (e − l)/r = −1/2
/// (θ = −30° and 210°), as the solver finds too; it has no time ratio.
#[test]
fn a_slider_crank_with_too_short_a_rod_rocks_between_its_toggles() {
    let m = slider_crank([0.1, 0.15, 0.1], FRAC_PI_2);
    let metrics = LinkageMetrics::of(&m, &Solver::default()).unwrap();
    let sc = &metrics.slider_cranks[0];
    assert_eq!(
        sc.criterion.class,
        SliderCrankClass::Rocker,
        "{}",
        sc.criterion
    );
    let InputRange::Rocks { lower, upper, .. } = &sc.input_range else {
        panic!("{:?}", sc.input_range);
    };
    let (lo, hi) = (-PI / 6.0, 7.0 * PI / 6.0);
    close("lower end", lower.at.angle, lo);
    close("upper end", upper.at.angle, hi);
    assert_eq!([lower.toggle, upper.toggle], [Toggle::Extended; 2]);
    close(
        "solver's lower limit",
        metrics.drive.range.lower.as_ref().unwrap().phi,
        lo,
    );
    close(
        "solver's upper limit",
        metrics.drive.range.upper.as_ref().unwrap().phi,
        hi,
    );
    assert!(
        metrics.drive.to_string().starts_with("rocks from -30"),
        "{}",
        metrics.drive
    );
    assert!(
        matches!(sc.quick_return, Err(MetricsError::CrankDoesNotTurn { .. })),
        "{:?}",
        sc.quick_return
    );
    // μ: 90° at θ = 90° (r sin θ = e), 180° at the ends.
    close("min μ", sc.transmission.min.angle, FRAC_PI_2);
    close("max μ", sc.transmission.max.angle, PI);
}

/// The same slider-crank with the rod's pin running in a slot of the ground (no slider
/// link) is recognised too, with the same stroke and time ratio.
#[test]
fn a_pin_in_a_slot_of_the_ground_is_a_slider_crank_too() {
    let [r, l, e]: [f64; 3] = [0.1, 0.3, 0.1];
    let ahead = (l * l - (e - r) * (e - r)).sqrt();
    let m = Mechanism::builder()
        .point("O", [0.0, 0.0])
        .point("A", [0.0, r])
        .point("B", [ahead, e])
        .point("G0", [0.0, e])
        .point("G1", [1.0, e])
        .ground(["O", "G0", "G1"])
        .link("crank", ["O", "A"])
        .link("rod", ["A", "B"])
        .revolute("O", "ground", "crank", "O")
        .revolute("A", "crank", "rod", "A")
        .pin_in_slot("slot", "ground", ["G0", "G1"], "rod", "B")
        .drive(Drive::angle("O").at_sketch(FRAC_PI_2))
        .build()
        .unwrap();
    let metrics = LinkageMetrics::of(&m, &Solver::default()).unwrap();
    let sc = &metrics.slider_cranks[0];
    assert_eq!(sc.linkage.slider, None);
    let q = sc.quick_return.as_ref().unwrap();
    let delta = (e / (l - r)).asin() - (e / (l + r)).asin();
    let stroke = ((l + r) * (l + r) - e * e).sqrt() - ((l - r) * (l - r) - e * e).sqrt();
    close("stroke", q.travel, stroke);
    close("time ratio", q.time_ratio, (PI + delta) / (PI - delta));
}

/// Stephenson's six-bar: the crank-rocker with a dyad (links 5 and 6) from its coupler
/// point C to a ground pivot O6. Its four-bar loop is found and its metrics are those of
/// the isolated four-bar (and of the closed forms); the dyad has none.
#[test]
fn a_four_bar_inside_a_stephenson_six_bar_has_the_isolated_four_bars_metrics() {
    let (c, o6) = ([0.3, 0.45], [0.9, 0.9]);
    let d_point = circles(c, 0.6, o6, 0.5, 1.0);
    let m = four_bar_parts(CRANK_ROCKER, FRAC_PI_2, 1.0)
        .point("C", c)
        .point("D", d_point)
        .point("O6", o6)
        .ground(["O2", "O4", "O6"])
        .link("coupler", ["A", "B", "C"])
        .link("link5", ["C", "D"])
        .link("link6", ["D", "O6"])
        .revolute("C", "coupler", "link5", "C")
        .revolute("D", "link5", "link6", "D")
        .revolute("O6", "ground", "link6", "O6")
        .build()
        .unwrap();
    let solver = Solver::default();
    let six = LinkageMetrics::of(&m, &solver).unwrap();
    let four = LinkageMetrics::of(&four_bar(CRANK_ROCKER, FRAC_PI_2, 1.0), &solver).unwrap();
    assert_eq!(six.four_bars.len(), 1);
    let (inner, alone) = (&six.four_bars[0], &four.four_bars[0]);
    assert_eq!(inner.grashof, alone.grashof);
    assert_eq!(inner.input_range, alone.input_range);
    assert_eq!(inner.transmission, alone.transmission);
    let (q6, q4) = (
        inner.quick_return.as_ref().unwrap(),
        alone.quick_return.as_ref().unwrap(),
    );
    check_crank_rocker_quick_return(q6, CRANK_ROCKER, 1.0);
    close(
        "six-bar's time ratio vs the four-bar's",
        q6.time_ratio,
        q4.time_ratio,
    );
    assert_eq!(six.not_applicable.len(), 1, "{:#?}", six.not_applicable);
    let dyad = &six.not_applicable[0];
    assert_eq!(dyad.links, ["link5", "link6"]);
    assert!(dyad.reason.contains("no four-bar"), "{}", dyad.reason);
}

/// Watt's six-bar II: a second four-bar (ground – rocker – link5 – link6) driven by the
/// first's rocker. Both loops are found; the second's input is not the drive, so it has a
/// Grashof class and a range of its own but no time ratio.
#[test]
fn both_four_bars_of_a_watt_six_bar_are_found() {
    let (e, o6) = ([0.55, -0.1], [0.9, -0.3]);
    let f = circles(e, 0.5, o6, 0.3, 1.0);
    let m = four_bar_parts_ternary_rocker(e)
        .point("F", f)
        .point("O6", o6)
        .ground(["O2", "O4", "O6"])
        .link("coupler", ["A", "B"])
        .link("link5", ["E", "F"])
        .link("link6", ["F", "O6"])
        .revolute("E", "rocker", "link5", "E")
        .revolute("F", "link5", "link6", "F")
        .revolute("O6", "ground", "link6", "O6")
        .build()
        .unwrap();
    let metrics = LinkageMetrics::of(&m, &Solver::default()).unwrap();
    assert_eq!(metrics.four_bars.len(), 2, "{:#?}", metrics.not_applicable);
    assert!(metrics.not_applicable.is_empty());
    let first = &metrics.four_bars[0];
    check_crank_rocker_quick_return(first.quick_return.as_ref().unwrap(), CRANK_ROCKER, 1.0);
    let second = &metrics.four_bars[1];
    assert_eq!(second.linkage.links, ["ground", "rocker", "link5", "link6"]);
    assert!(!second.linkage.driven);
    let frame = (o6[0] - 0.4f64).hypot(o6[1]);
    let input = (e[0] - 0.4f64).hypot(e[1]);
    close("second frame", second.linkage.lengths.frame, frame);
    close("second input", second.linkage.lengths.input, input);
    close("second coupler", second.linkage.lengths.coupler, 0.5);
    close("second output", second.linkage.lengths.output, 0.3);
    // input + frame = 0.18 + 0.58 < 0.5 + 0.3, the input shortest.
    assert_eq!(
        second.grashof.class,
        GrashofClass::CrankRocker,
        "{}",
        second.grashof
    );
    assert!(
        matches!(&second.quick_return, Err(MetricsError::InputNotDriven { input }) if input == "rocker")
    );
    assert_eq!(second.transmission.min.at.drive, None);
}

/// The crank-rocker's parts with a ternary rocker O4–B–E.
fn four_bar_parts_ternary_rocker(e: [f64; 2]) -> MechanismBuilder {
    let [a, b, c, d] = CRANK_ROCKER;
    let pin = [0.0, a];
    Mechanism::builder()
        .point("O2", [0.0, 0.0])
        .point("O4", [d, 0.0])
        .point("A", pin)
        .point("B", circles(pin, b, [d, 0.0], c, 1.0))
        .point("E", e)
        .link("crank", ["O2", "A"])
        .link("rocker", ["O4", "B", "E"])
        .revolute("O2", "ground", "crank", "O2")
        .revolute("A", "crank", "coupler", "A")
        .revolute("B", "coupler", "rocker", "B")
        .revolute("O4", "ground", "rocker", "O4")
        .drive(Drive::angle("O2").at_sketch(FRAC_PI_2))
}

/// The Whitworth has no four-bar or slider-crank loop (its pins run in a slotted lever):
/// each of its loops is listed as not applicable, with its joints.
#[test]
fn a_whitworth_has_no_linkage_loops_and_says_why() {
    let m = whitworth().unwrap();
    let loops = Loops::find(&m).unwrap();
    assert!(loops.four_bars.is_empty() && loops.slider_cranks.is_empty());
    let links: Vec<&str> = (loops.not_applicable.iter())
        .flat_map(|n| n.links.iter().map(String::as_str))
        .collect();
    assert_eq!(links, ["crank", "rocker", "ram"]);
    assert!(
        loops.not_applicable[1].reason.contains("pin-in-slot"),
        "{}",
        loops.not_applicable[1].reason
    );
}

/// The drive positions given for μ's extremes are where the solved pose's μ is extreme
/// (μ′ = 0 there), also when the drive turns the other way (the pivot joint declared
/// crank → ground, φ = 1 − (θ − 90°)) and when the drive starts elsewhere.
#[test]
fn transmission_extremes_are_where_the_solved_pose_has_them() {
    for (pivot, phi_at_sketch, slope) in [
        (["ground", "crank"], 2.0, 1.0),
        (["crank", "ground"], 1.0, -1.0),
    ] {
        let m = four_bar_driven(CRANK_ROCKER, FRAC_PI_2, 1.0, pivot, phi_at_sketch)
            .ground(["O2", "O4"])
            .link("coupler", ["A", "B"])
            .build()
            .unwrap();
        let linkage = the_four_bar(&m);
        let extremes = linkage.transmission_extremes();
        let mut tracker = Solver::default().track(&m).unwrap();
        for (what, at) in [("min", extremes.min), ("max", extremes.max)] {
            let phi = at.at.drive.unwrap();
            // φ = φ_sketch + slope·(θ − 90°), on the turn nearest the sketch.
            let theta = FRAC_PI_2 + (phi - phi_at_sketch) * slope;
            same_angle(&format!("{what}: θ"), theta, at.at.angle);
            tracker.move_to(phi).unwrap();
            let mu = linkage.transmission_at(&tracker.kinematics::<1>().unwrap());
            close(&format!("{what} μ at its φ"), mu.unsigned.value, at.angle);
            close(&format!("{what}: μ′ at its φ"), mu.unsigned.d1(), 0.0);
        }
    }
}

/// Any output with two dead positions has a time ratio: the ram of the crank and
/// slotted-lever shaper of scenes/shaper.toml (reference 003: crank l1 = 0.1 m, lever pivot
/// l0 = 0.315 m below the crank's, lever l3 = 0.48 m). The lever swings to its extremes
/// where the crank stands perpendicular to it, sin φ1 = −l1/l0; the crank turns
/// 180° + 2 asin(l1/l0) forward and 180° − 2 asin(l1/l0) back, and the ram's stroke is
/// 2 l3 l1/l0 = 0.304761904761905 m.
#[test]
fn time_ratio_and_stroke_of_the_slotted_lever_shaper_are_the_closed_forms() {
    let (l0, l1, l3, l5) = (0.315, 0.1, 0.48, 0.18);
    let m = Mechanism::builder()
        .point("A", [0.0, 0.0])
        .point("C", [0.0, -l0])
        .point("B", [0.0, l1])
        .point("D", [0.0, l3 - l0])
        .point("G", [0.0, l5])
        .point("H", [1.0, l5])
        .point("F", [0.0, l5])
        .point("F1", [0.0, 0.0])
        .ground(["A", "C", "G", "H"])
        .link("crank", ["A", "B"])
        .link("lever", ["C", "D"])
        .link("ram", ["F", "F1"])
        .revolute("A", "ground", "crank", "A")
        .revolute("C", "ground", "lever", "C")
        .pin_in_slot("block2", "lever", ["C", "D"], "crank", "B")
        .prismatic("ram_guide", "ground", ["G", "H"], "ram", "F")
        .pin_in_slot("block4", "ram", ["F", "F1"], "lever", "D")
        .drive(Drive::angle("A").at_sketch(FRAC_PI_2))
        .build()
        .unwrap();
    let ram = m.displacement_output("ram_guide").unwrap();
    let q = QuickReturn::find(&m, &Solver::default(), |k| k.value(&ram)).unwrap();
    let beta = (l1 / l0).asin();
    close(
        "forward crank angle",
        q.forward.crank_angle,
        PI + 2.0 * beta,
    );
    close("return crank angle", q.back.crank_angle, PI - 2.0 * beta);
    close(
        "time ratio",
        q.time_ratio,
        (PI + 2.0 * beta) / (PI - 2.0 * beta),
    );
    close("stroke", q.travel, 2.0 * l3 * l1 / l0);
    same_angle("first dead position", q.dead_positions[0].phi, PI + beta);
    same_angle("second dead position", q.dead_positions[1].phi, TAU - beta);
    // Not a four-bar or a slider-crank: its loops have no Grashof class.
    let loops = Loops::find(&m).unwrap();
    assert!(loops.four_bars.is_empty() && loops.slider_cranks.is_empty());
}

/// A slider-crank driven at its slider (an engine) is found but its crank is not placed
/// first, so it has no slider-crank metrics, and both its loops say why.
#[test]
fn an_engine_driven_at_its_slider_is_not_applicable_and_says_why() {
    let [r, l] = [0.1, 0.4];
    let m = Mechanism::builder()
        .point("O", [0.0, 0.0])
        .point("A", [0.0, r])
        .point("B", [(l * l - r * r).sqrt(), 0.0])
        .point("G0", [0.0, 0.0])
        .point("G1", [1.0, 0.0])
        .ground(["O", "G0", "G1"])
        .link("crank", ["O", "A"])
        .link("rod", ["A", "B"])
        .link("piston", ["B"])
        .revolute("O", "ground", "crank", "O")
        .revolute("A", "crank", "rod", "A")
        .revolute("B", "rod", "piston", "B")
        .prismatic("cylinder", "ground", ["G0", "G1"], "piston", "B")
        .drive(Drive::displacement("cylinder"))
        .build()
        .unwrap();
    let loops = Loops::find(&m).unwrap();
    assert!(loops.slider_cranks.is_empty() && loops.four_bars.is_empty());
    assert_eq!(loops.not_applicable.len(), 2, "{:#?}", loops.not_applicable);
    for loop_ in &loops.not_applicable {
        assert!(
            loop_.reason.contains("crank is not placed before its rod"),
            "{}",
            loop_.reason
        );
    }
}
