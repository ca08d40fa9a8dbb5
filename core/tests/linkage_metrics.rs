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
fn four_bar_parts([a, b, c, d]: [f64; 4], theta: f64, side: f64) -> MechanismBuilder {
    let pin = [a * theta.cos(), a * theta.sin()];
    Mechanism::builder()
        .point("O2", [0.0, 0.0])
        .point("O4", [d, 0.0])
        .point("A", pin)
        .point("B", circles(pin, b, [d, 0.0], c, side))
        .link("crank", ["O2", "A"])
        .link("rocker", ["O4", "B"])
        .revolute("O2", "ground", "crank", "O2")
        .revolute("A", "crank", "coupler", "A")
        .revolute("B", "coupler", "rocker", "B")
        .revolute("O4", "ground", "rocker", "O4")
        .drive(Drive::angle("O2").at_sketch(theta))
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
        case([0.1, 0.2f64.sqrt(), 0.3, 0.4], 90.0, GrashofClass::CrankRocker, "crank", "coupler"),
        // 0.1 + 0.45 < 0.3 + 0.4, the rocker (output) shortest: the input rocks within
        // [acos(0.53125), acos(−0.21875)] = [57.9°, 102.6°].
        case([0.3, 0.45, 0.1, 0.4], 80.0, GrashofClass::RockerCrank, "rocker", "coupler"),
        // The frame shortest: a drag link.
        case([0.3, 0.45, 0.4, 0.1], 90.0, GrashofClass::DoubleCrank, "ground", "coupler"),
        // The coupler shortest: input in [41.4°, 80.9°].
        case([0.3, 0.1, 0.4, 0.45], 60.0, GrashofClass::DoubleRocker, "coupler", "ground"),
        // a + b = c + d (0.1 + 0.3 = 0.2 + 0.2): |a − d| = |b − c|, it folds flat at θ = 0.
        case([0.1, 0.3, 0.2, 0.2], 90.0, GrashofClass::ChangePoint, "crank", "coupler"),
        // Norton's non-Grashof linkage (scenes/norton_four_bar.toml): 0.86 + 2.22 > 0.86 +
        // 1.85; the input rocks through θ = 0 within ±116°.
        case([0.86, 1.85, 0.86, 2.22], 30.0, GrashofClass::TripleRocker, "crank", "ground"),
        // Non-Grashof rocking through θ = 180°: 0.05 + 0.2 > 0.1 + 0.12.
        case([0.1, 0.2, 0.05, 0.12], 150.0, GrashofClass::TripleRocker, "rocker", "coupler"),
    ]
}

/// Grashof's class of each textbook four-bar, with s + l and p + q equal to the sums of its
/// lengths.
#[test]
fn grashof_classes_of_textbook_four_bars_follow_the_inequality() {
    for case in cases() {
        let linkage = the_four_bar(&four_bar(case.abcd, case.theta, 1.0));
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
        (GrashofClass::CrankRocker, 90.0),  // frame 0.3: the shortest is the input
        (GrashofClass::DoubleRocker, 80.0), // frame 0.4: the shortest is the coupler
        (GrashofClass::RockerCrank, 40.0),  // frame 0.45: the shortest is the output
        (GrashofClass::DoubleCrank, 90.0),  // frame 0.1
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
            GrashofClass::CrankRocker | GrashofClass::DoubleCrank => {
                (None, (0.0, law_of_cosines(case.abcd, 0.0)), (PI, law_of_cosines(case.abcd, PI)))
            }
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
                (None, (0.0, law_of_cosines(case.abcd, 0.0)), (PI, law_of_cosines(case.abcd, PI)))
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
                assert_eq!((below.kind, above.kind), (LimitKind::Limit, LimitKind::Limit));
                close(&format!("{name}: solver's lower limit"), below.phi, lo);
                close(&format!("{name}: solver's upper limit"), above.phi, hi);
            }
            (ends, range) => panic!("{name}: expected ends {ends:?}, got {range:?}"),
        }
        // Where μ is extreme: the angle up to the sign where the ends are symmetric.
        close(&format!("{name}: min μ"), mu.min.angle, min.1);
        close(&format!("{name}: max μ"), mu.max.angle, max.1);
        close(&format!("{name}: where min μ"), mu.min.at.angle.abs(), min.0);
        close(&format!("{name}: where max μ"), mu.max.at.angle.abs(), max.0);
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
            close(&format!("effective μ, {at}"), mu.effective.value, want.min(PI - want));
            close(&format!("deviation, {at}"), mu.deviation.value, FRAC_PI_2 - want.min(PI - want));
            let [a, b, c, d] = abcd;
            let slope = a * d * theta.sin() / (b * c * want.sin());
            close(&format!("μ′, {at}"), mu.unsigned.d1(), slope);
            close(&format!("closed form, {at}"), linkage.transmission_angle(theta), want);
        }
    }
}
