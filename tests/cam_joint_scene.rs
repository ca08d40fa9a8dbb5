//! `scenes/cam_driven_rocker.toml`: a cam (rise–dwell–return–dwell, scenes/cams/) drives the
//! slider of a rocker linkage through `[drive] cam`. The rocker angle and its cam-angle
//! derivatives against a closed form written here, the cam-shaft torque against the power
//! balance, and bad cam drives as errors with `file:line:column`.

use std::f64::consts::TAU;

use mechdiff::scene::{self, Report};
use num_dual::{Dual3_64, DualNum};

use crate::common;
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

/// A cam that lifts its follower past the linkage's reach and back between two positions
/// of the sweep: the step is walked through every displacement the follower passes, so the
/// blocked range is reported (as a linkage's: `Error::Blocked`, from and to the step's cam
/// angles) with its limit positions, each checked against the cam law's closed form and
/// the linkage's reach solved here.
mod blocked_inside_a_step {
    use super::common::{column, temp_file};
    use mechdiff::Error;
    use mechdiff::scene;
    use std::f64::consts::PI;

    /// The rocker of `scenes/cam_driven_rocker.toml` (mm): rocker R, rod L, the follower
    /// (slider B on the x axis through O) at X0 when s = 0. The triangle O–A–B closes for
    /// L − R ≤ X0 + s ≤ L + R: the follower's reach is s ∈ [−150, 50] mm.
    const R: f64 = 100.0;
    const L: f64 = 325.0;
    const X0: f64 = 375.0;

    /// One case: a law moving the follower by `lift` (mm) over `out` degrees and back over
    /// `back` degrees (then a dwell), upwards (towards the reach L + R) or, `down`, first
    /// down (towards L − R); swept from `start` by `step` degrees over a turn.
    #[derive(Debug, Clone, Copy)]
    struct Case {
        law: &'static str,
        lift: f64,
        out: f64,
        back: f64,
        step: f64,
        start: f64,
        down: bool,
    }

    /// f(u) of each law as textbooks write it (Norton, *Design of Machinery*; the modified
    /// sine's pieces from Rothbart, *Cam Design Handbook*).
    fn rise(law: &str, u: f64) -> f64 {
        match law {
            "simple_harmonic" => (1.0 - (PI * u).cos()) / 2.0,
            "cycloidal" => u - (2.0 * PI * u).sin() / (2.0 * PI),
            "polynomial_345" => u.powi(3) * (10.0 - 15.0 * u + 6.0 * u * u),
            "polynomial_4567" => u.powi(4) * (35.0 - 84.0 * u + 70.0 * u * u - 20.0 * u.powi(3)),
            "parabolic" if u <= 0.5 => 2.0 * u * u,
            "parabolic" => 1.0 - 2.0 * (1.0 - u).powi(2),
            "uniform_velocity" => u,
            "modified_sine" => {
                let k = PI + 4.0;
                if u <= 0.125 {
                    (PI * u - 0.25 * (4.0 * PI * u).sin()) / k
                } else if u <= 0.875 {
                    (PI * u - 2.25 * (PI * (4.0 * u + 1.0) / 3.0).sin() + 2.0) / k
                } else {
                    (PI * u - 0.25 * (4.0 * PI * u).sin() + 4.0) / k
                }
            }
            other => panic!("no closed form for {other}"),
        }
    }

    /// The u in [0, 1] where the (increasing) law reaches `y`: bisection to adjacent
    /// numbers.
    fn rise_inverse(law: &str, y: f64) -> f64 {
        let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
        while hi - lo > f64::EPSILON {
            let mid = 0.5 * (lo + hi);
            if rise(law, mid) < y {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    impl Case {
        /// The follower's displacement magnitude (mm) at cam angle `t` (deg, in one turn).
        fn travel(&self, t: f64) -> f64 {
            if t <= self.out {
                self.lift * rise(self.law, t / self.out)
            } else if t <= self.out + self.back {
                self.lift * (1.0 - rise(self.law, (t - self.out) / self.back))
            } else {
                0.0
            }
        }

        /// How far the follower may move from s = 0 in its direction (mm).
        fn reach(&self) -> f64 {
            if self.down { X0 - (L - R) } else { L + R - X0 }
        }

        /// The blocked range's ends (deg): where the follower reaches the linkage's reach
        /// going out, and where it comes back to it.
        fn blocked(&self) -> (f64, f64) {
            let u = rise_inverse(self.law, self.reach() / self.lift);
            (self.out * u, self.out + self.back * (1.0 - u))
        }

        /// The sweep positions before and after the follower's turn.
        fn step_around_the_turn(&self) -> (f64, f64) {
            let k = ((self.out - self.start) / self.step).floor();
            let a = self.start + k * self.step;
            (a, a + self.step)
        }

        /// Writes the cam and the scene into a folder of their own; the scene's path.
        fn write(&self, name: &str, from: f64, to: f64, step: f64) -> std::path::PathBuf {
            let dir = temp_file(name);
            std::fs::create_dir_all(&dir).unwrap();
            let (go, come) = if self.down {
                ("return", "rise")
            } else {
                ("rise", "return")
            };
            let rest = 360.0 - self.out - self.back;
            let dwell = if rest > 0.0 {
                format!("[[cam.segment]]\nlaw = \"dwell\"\nextent = {rest}\n")
            } else {
                String::new()
            };
            let cam = format!(
                "[units]\nlength = \"mm\"\nangle = \"deg\"\n[cam]\nbase_radius = 400\n\
                 [cam.follower]\ntype = \"roller\"\nradius = 8\n\
                 [[cam.segment]]\nlaw = \"{law}\"\n{go} = {lift}\nextent = {out}\n\
                 [[cam.segment]]\nlaw = \"{law}\"\n{come} = {lift}\nextent = {back}\n{dwell}",
                law = self.law,
                lift = self.lift,
                out = self.out,
                back = self.back,
            );
            std::fs::write(dir.join("cam.toml"), cam).unwrap();
            let scene = format!(
                r#"[units]
length = "mm"
angle = "deg"
[points]
O = [0, 0]
A = [60, 80]
B = [375, 0]
X = [1000, 0]
[links]
ground = ["O", "X"]
rocker = ["O", "A"]
rod = ["A", "B"]
follower = ["B"]
[joints]
O = {{ type = "revolute", at = "O", links = ["ground", "rocker"] }}
A = {{ type = "revolute", at = "A", links = ["rocker", "rod"] }}
B = {{ type = "revolute", at = "B", links = ["rod", "follower"] }}
guide = {{ type = "prismatic", line = ["O", "X"], point = "B", links = ["ground", "follower"] }}
[drive]
joint = "guide"
cam = "cam.toml"
[sweep]
from = {from}
to = {to}
step = {step}
[[output]]
name = "psi"
angle = ["O", "A"]
quantities = ["position", "velocity_coefficient"]
"#
            );
            let path = dir.join("scene.toml");
            std::fs::write(&path, scene).unwrap();
            path
        }

        /// Runs the case swept from `from` to `to` by `step` (deg): its blocked range's
        /// report (from, to, limit in deg), or the rows' cam angles if it ran.
        fn run(
            &self,
            name: &str,
            from: f64,
            to: f64,
            step: f64,
        ) -> Result<(f64, f64, f64), Vec<f64>> {
            let path = self.write(name, from, to, step);
            let s = scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
            let result = scene::run(&s);
            let _ = std::fs::remove_dir_all(path.parent().unwrap());
            match result {
                Err(Error::Blocked {
                    from, to, limit, ..
                }) => {
                    let degrees = |text: &str| -> f64 {
                        let number = text.split(' ').next().unwrap();
                        assert!(text.starts_with(&format!("{number} deg")), "{text}");
                        number.parse().unwrap()
                    };
                    Ok((degrees(&from), degrees(&to), degrees(&limit)))
                }
                Err(other) => panic!("{self:?}: expected a blocked range, got: {other}"),
                Ok(report) => Err(column(&report, "theta")),
            }
        }
    }

    const CASES: [Case; 9] = [
        Case {
            law: "simple_harmonic",
            lift: 50.01,
            out: 172.5,
            back: 172.5,
            step: 15.0,
            start: 0.0,
            down: false,
        },
        Case {
            law: "cycloidal",
            lift: 50.001,
            out: 97.5,
            back: 97.5,
            step: 15.0,
            start: 0.0,
            down: false,
        },
        Case {
            law: "polynomial_345",
            lift: 50.0005,
            out: 110.0,
            back: 140.0,
            step: 20.0,
            start: 0.0,
            down: false,
        },
        Case {
            law: "polynomial_4567",
            lift: 50.0005,
            out: 128.0,
            back: 124.0,
            step: 10.0,
            start: 3.0,
            down: false,
        },
        Case {
            law: "parabolic",
            lift: 50.01,
            out: 200.0,
            back: 120.0,
            step: 15.0,
            start: 7.0,
            down: false,
        },
        Case {
            law: "uniform_velocity",
            lift: 50.3,
            out: 95.0,
            back: 130.0,
            step: 15.0,
            start: 0.0,
            down: false,
        },
        Case {
            law: "modified_sine",
            lift: 50.0005,
            out: 157.5,
            back: 150.0,
            step: 15.0,
            start: 0.0,
            down: false,
        },
        Case {
            law: "simple_harmonic",
            lift: 150.02,
            out: 100.0,
            back: 100.0,
            step: 15.0,
            start: 0.0,
            down: true,
        },
        Case {
            law: "cycloidal",
            lift: 150.01,
            out: 56.25,
            back: 52.5,
            step: 7.5,
            start: 0.0,
            down: true,
        },
    ];

    /// 1e-9 rad: the limit is the root of the linkage's margin in the follower's
    /// displacement (full precision), taken to the cam angle by bisection to adjacent
    /// numbers; s′ there is at least ~4e-5 m/rad in these cases, so rounding of s (1e-17 m)
    /// moves it by < 1e-12 rad, and the printed angle has 15 significant digits (1e-13 deg).
    const TOLERANCE: f64 = 1e-9;

    fn close(got_deg: f64, want_deg: f64) -> bool {
        (got_deg - want_deg).to_radians().abs() <= TOLERANCE
    }

    /// Every case is a jump (the sweep positions either side of the follower's turn are
    /// within reach, the blocked range lies between them); the run reports it going out,
    /// at the cam angle where the follower reaches the linkage's reach, and swept
    /// backwards, at the cam angle where it comes back.
    #[test]
    fn a_blocked_range_inside_a_step_is_reported_with_its_limit_positions() {
        for (k, case) in CASES.iter().enumerate() {
            let (a, b) = case.step_around_the_turn();
            let (enter, leave) = case.blocked();
            let reach = case.reach();
            assert!(
                case.travel(a) < reach && case.travel(b) < reach && a < enter && leave < b,
                "{case:?} is not a jump: s({a}) = {}, s({b}) = {}, blocked {enter}..{leave}",
                case.travel(a),
                case.travel(b)
            );
            let end = case.start + 360.0;
            let (from, to, limit) = case
                .run(&format!("jump-{k}"), case.start, end, case.step)
                .unwrap_or_else(|rows| panic!("{case:?}: jumped, ran {} rows", rows.len()));
            assert!(
                close(from, a) && close(to, b),
                "{case:?}: between {from} and {to}"
            );
            assert!(
                close(limit, enter),
                "{case:?}: limit {limit} deg, closed form {enter} deg"
            );
            // Backwards the follower meets the reach on its way back.
            let (from, to, limit) = case
                .run(&format!("back-{k}"), end, case.start, case.step)
                .unwrap_or_else(|rows| {
                    panic!("{case:?} backwards: jumped, ran {} rows", rows.len())
                });
            assert!(
                close(from, b) && close(to, a),
                "{case:?}: between {from} and {to}"
            );
            assert!(
                close(limit, leave),
                "{case:?}: limit {limit} deg, closed form {leave} deg"
            );
        }
    }

    /// A 1° sweep and the coarse sweep give the same verdict: the same blocked range, the
    /// same limit position (to 1e-9 rad).
    #[test]
    fn a_fine_and_a_coarse_step_give_the_same_verdict() {
        for (k, case) in CASES.iter().enumerate().step_by(2) {
            let end = case.start + 360.0;
            let coarse = case.run(&format!("coarse-{k}"), case.start, end, case.step);
            let fine = case.run(&format!("fine-{k}"), case.start, end, 1.0);
            let (Ok((_, _, coarse)), Ok((from, to, fine))) = (coarse, fine) else {
                panic!("{case:?}: a sweep ran through the blocked range");
            };
            assert!(close(coarse, fine), "{case:?}: {coarse} vs {fine} deg");
            assert!(
                from < fine && fine < to && to - from <= 1.0 + 1e-9,
                "{from}..{to}"
            );
        }
    }

    /// On the command line, `run` and `accuracy` (which walks the sweep's positions too)
    /// exit with the blocked range's message, never with a table that jumps it.
    #[test]
    fn the_commands_exit_with_the_blocked_range() {
        let case = CASES[0];
        let path = case.write("cli", 0.0, 360.0, 15.0);
        for command in ["run", "accuracy"] {
            let out = super::common::mechdiff(&[command, path.to_str().unwrap()]);
            let message = super::common::stderr(&out);
            assert!(!out.status.success(), "{command}: exit 0");
            assert!(
                message.contains("cannot assemble between drive positions 165 deg and 180 deg")
                    && message.contains("first fails at 170.94705787858"),
                "{command}: {message}"
            );
        }
        let _ = std::fs::remove_dir_all(path.parent().unwrap());
    }

    /// The same cams with a lift 1 mm short of the reach run through every position.
    #[test]
    fn a_follower_within_reach_runs_the_whole_sweep() {
        for (k, case) in CASES.iter().enumerate().step_by(3) {
            let short = Case {
                lift: case.reach() - 1.0,
                ..*case
            };
            let end = case.start + 360.0;
            let rows = short
                .run(&format!("short-{k}"), case.start, end, case.step)
                .expect_err("the follower stays within reach");
            assert_eq!(rows.len(), (360.0 / case.step) as usize + 1, "{case:?}");
        }
    }
}

/// A sweep with no blocked range writes the same table as before the follower's travel was
/// walked between positions: the shipped scene, and a cam whose follower turns back inside a
/// step (walked through its reversal). The CSV files in tests/data/ were written by the
/// program before that change (commit d236df9); every loop here is in closed form, so a
/// position's results do not depend on the route to it.
///
/// The same header and drive positions, byte for byte, and every other value within 1e-13
/// of its column's largest magnitude: since then the outputs are read from the pose as the
/// solver's move computed it (a link's angle instead of the `atan2` of two of its points,
/// the loops' own sines and cosines), which changes last bits — a few ulps of each
/// quantity's scale in these well-conditioned poses (the tracker's amplification is ~1 here;
/// its ill-conditioned warning starts at 1e4). A column's scale, not each value's, because a
/// value that is zero up to rounding (ψ′ = 1.2e-17 at a dwell) has no relative digits to
/// keep; a change of the feature's meaning (a step walked another way, a position missed or
/// added) moves values by far more than 1e-13 of their scale.
#[test]
fn a_sweep_without_a_blocked_range_writes_the_same_table_as_before() {
    let data = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let scenes = [
        (
            scene_path("cam_driven_rocker.toml"),
            "cam_driven_rocker.csv",
        ),
        (data.join("cam_peak_in_step.toml"), "cam_peak_in_step.csv"),
    ];
    let table = |text: &str| -> (String, Vec<Vec<String>>) {
        let mut lines = text.lines();
        let header = lines.next().expect("a header").to_owned();
        let rows = lines
            .map(|l| l.split(',').map(str::to_owned).collect())
            .collect();
        (header, rows)
    };
    for (scene, before) in scenes {
        let csv = common::temp_file(before);
        let out = common::mechdiff(&[
            "run",
            scene.to_str().unwrap(),
            "--csv",
            csv.to_str().unwrap(),
        ]);
        assert!(out.status.success(), "{}", common::stderr(&out));
        let written = std::fs::read_to_string(&csv).unwrap();
        let _ = std::fs::remove_file(&csv);
        let (header, rows) = table(&written);
        let (header_before, rows_before) =
            table(&std::fs::read_to_string(data.join(before)).unwrap());
        assert_eq!(header, header_before, "{before}: the columns changed");
        assert_eq!(rows.len(), rows_before.len(), "{before}: the rows changed");
        let number = |t: &str| t.parse::<f64>().expect("a number");
        let columns = header.split(',').count();
        for c in 0..columns {
            let scale = (rows_before.iter())
                .map(|r| number(&r[c]).abs())
                .fold(0.0, f64::max);
            for (k, (row, row_before)) in rows.iter().zip(&rows_before).enumerate() {
                assert_eq!(row.len(), columns, "{before}: row {k}");
                if c == 0 {
                    assert_eq!(
                        row[0], row_before[0],
                        "{before}: the drive position of row {k}"
                    );
                    continue;
                }
                let (new, old) = (number(&row[c]), number(&row_before[c]));
                assert!(
                    (new - old).abs() <= 1e-13 * scale,
                    "{before}: row {k}, column {c}: {new:e} against {old:e} (scale {scale:e})"
                );
            }
        }
    }
}

/// An oscillating follower turns the crank of a parallelogram four-bar (crank 100 mm,
/// sketched at 20°) back by 20.01° and forth, turning back at 172.5°, between two positions
/// of the 15° sweep: the crank passes the parallelogram's change point (φ = 0, coupler and
/// rocker folded onto the ground line) inside the step, and the run reports it at the cam
/// angle where the harmonic return reaches −20°: θ = 172.5° · acos(1 − 2·20/20.01)/π.
#[test]
fn a_change_point_inside_a_step_is_reported_at_its_cam_angle() {
    let dir = common::temp_file("cam-change-point");
    std::fs::create_dir_all(&dir).unwrap();
    let cam = r#"
[units]
length = "mm"
angle = "deg"
[cam]
base_radius = 40
[cam.follower]
type = "oscillating_roller"
pivot_distance = 120
arm_length = 100
radius = 10
[[cam.segment]]
law = "simple_harmonic"
return = 20.01
extent = 172.5
[[cam.segment]]
law = "simple_harmonic"
rise = 20.01
extent = 187.5
"#;
    std::fs::write(dir.join("cam.toml"), cam).unwrap();
    // The parallelogram of `common` driven by the cam (its crank angle is the follower's
    // displacement), over a turn of the cam at 15°.
    let drive = "line = [\"A0\", \"A\"]\n";
    assert!(common::PARALLELOGRAM.contains(drive));
    let scene_text = common::PARALLELOGRAM.replace(drive, &format!("{drive}cam = \"cam.toml\"\n"))
        + "[sweep]\nfrom = 0\nto = 360\nstep = 15\n";
    let path = dir.join("scene.toml");
    std::fs::write(&path, scene_text).unwrap();
    let result = scene::load(&path).and_then(|s| scene::run(&s));
    let _ = std::fs::remove_dir_all(&dir);
    let want = 172.5 * (1.0 - 2.0 * 20.0 / 20.01_f64).acos() / std::f64::consts::PI;
    match result {
        Err(mechdiff::Error::ChangePoint { position, .. }) => {
            let got: f64 = position.split(' ').next().unwrap().parse().unwrap();
            // 1e-9 rad: the change point in the crank angle to rounding, s′ ≈ 0.1 rad/rad
            // there.
            assert!(
                (got - want).to_radians().abs() < 1e-9,
                "{position} vs {want} deg"
            );
        }
        Err(e) => panic!("expected a change point, got: {e}"),
        Ok(_) => panic!("the change point inside the step was jumped"),
    }
}
