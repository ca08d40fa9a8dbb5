//! Issue 14 item 6, conventions: sweeps in either direction, negative drive speeds, static
//! analysis (speed 0), the signs of the drive torque, joint reactions and slider normal
//! forces as docs/scene-format.md ("Conventions") states them, and dynamics columns
//! printed in the file's force and torque units; and the code's own conventions: no import
//! circle of more than two modules in any crate (issue 23).

use crate::common;
mod import_graph;
mod scene_parameters;

use mechdiff::scene::{self, Report};

/// Norton's four-bar from its lengths (the scene shipped in `scenes/`), with masses from a
/// density, gravity, and the drive torque and reactions asked for.
fn norton(sweep: &str, speed: &str) -> String {
    include_str!("../scenes/norton_four_bar.toml")
        .replace(
            "speed = 10 ",
            &format!("speed = {speed}\nacceleration = 5 "),
        )
        .replace("from = 0\nto = 100\nstep = 10", sweep)
        .replace(
            "\"velocity\"]",
            "\"velocity\", \"acceleration_coefficient\", \"acceleration\"]\ndead_positions = true",
        )
        + r#"
[gravity]
g = 9.81

[masses]
crank = { density = 2 }
coupler = { density = 2 }
rocker = { density = 2 }

[[dynamics]]
output = "drive_torque"

[[dynamics]]
output = "reactions"
"#
}

fn run(text: &str) -> Report {
    common::run_text("conventions.toml", text)
}

/// `a` and `b` agree to `tol` relative to each value's magnitude (absolute below 1).
fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * b.abs().max(1.0)
}

#[test]
fn a_sweep_downwards_gives_the_rows_of_the_sweep_upwards_in_reverse() {
    let up = run(&norton("from = 0\nto = 100\nstep = 10", "10"));
    for down in [
        "from = 100\nto = 0\nstep = 10",
        "from = 100\nto = 0\nstep = -10",
    ] {
        let down = run(&norton(down, "10"));
        assert_eq!(down.rows.len(), 11);
        for (d, u) in down.rows.iter().zip(up.rows.iter().rev()) {
            for (k, (x, y)) in d.iter().zip(u).enumerate() {
                // 1e-12: each loop is solved in closed form from the same drive position
                // (exact multiples of 10° either way); only the previous pose used to pick
                // the turn differs (measured: equal to the last bit or nearly).
                assert!(close(*x, *y, 1e-12), "{}: {x} vs {y}", down.columns[k].name);
            }
        }
        // The same dead position (ψ' = 0 near φ = 15°) is found either way, 1e-12 rad.
        let (d, u) = (&down.dead_positions[0], &up.dead_positions[0]);
        assert_eq!(d.positions.len(), u.positions.len());
        assert!(
            !u.positions.is_empty(),
            "the rocker turns back within 0°…100°"
        );
        for (a, b) in d.positions.iter().zip(&u.positions) {
            assert!((a.phi - b.phi).abs() < 1e-12, "{} vs {}", a.phi, b.phi);
        }
    }
    let e = scene::parse("c.toml", &norton("from = 0\nto = 100\nstep = -10", "10")).unwrap_err();
    assert!(
        e.to_string().contains("negative but `to` is above `from`"),
        "{e}"
    );
}

#[test]
fn a_negative_speed_reverses_velocities_and_keeps_accelerations_and_the_drive_torque() {
    let forward = run(&norton("from = 0\nto = 100\nstep = 10", "10"));
    let backward = run(&norton("from = 0\nto = 100\nstep = 10", "-10"));
    // With ω → −ω: velocities ω·q′ change sign; accelerations α·q′ + ω²·q″ and so every
    // inertial force, reaction and the drive torque (no friction) are unchanged. Both runs
    // solve the same poses: equal to rounding, 1e-12 relative.
    for (k, column) in forward.columns.iter().enumerate() {
        let sign = if column.name == "psi_dot" { -1.0 } else { 1.0 };
        for (f, b) in forward.rows.iter().zip(&backward.rows) {
            assert!(
                close(b[k], sign * f[k], 1e-12),
                "{}: {} vs {}",
                column.name,
                b[k],
                f[k]
            );
        }
    }
    assert!(
        forward
            .column("psi_dot")
            .unwrap()
            .iter()
            .any(|v| v.abs() > 1.0)
    );
}

/// A crank alone, its mass on its tip: `M_drive = m·g·a·cos φ` (the torque that holds the
/// crank against its weight, counter-clockwise positive); the ground holds it up at O.
#[test]
fn a_static_crank_needs_the_torque_of_its_weight_counter_clockwise_positive() {
    let text = r#"
[units]
angle = "deg"
[points]
O = [0, 0]
A = [0.5, 0]
[links]
ground = ["O"]
crank = ["O", "A"]
[joints]
O = { type = "revolute", at = "O", links = ["ground", "crank"] }
[drive]
joint = "O"
line = ["O", "A"]
speed = 0
[sweep]
from = 0
to = 330
step = 30
[gravity]
g = 9.81
[masses]
crank = { mass = 2, center = "A" }
[[dynamics]]
output = "drive_torque"
[[dynamics]]
output = "reactions"
"#;
    let report = run(text);
    let (phi, torque) = (
        report.column("phi").unwrap(),
        report.column("M_drive").unwrap(),
    );
    let (fx, fy) = (
        report.column("Fx_O").unwrap(),
        report.column("Fy_O").unwrap(),
    );
    for k in 0..phi.len() {
        // m·g·a = 9.81 N·m; 1e-12 relative to it: a 2×2 equilibrium solved in f64.
        let want = 2.0 * 9.81 * 0.5 * phi[k].cos();
        assert!(
            (torque[k] - want).abs() < 9.81e-12,
            "phi {}: {}",
            phi[k],
            torque[k]
        );
        // The ground (first link) on the crank (second): up, m·g = 19.62 N.
        assert!(
            fx[k].abs() < 1e-12 && (fy[k] - 19.62).abs() < 19.62e-12,
            "{} {}",
            fx[k],
            fy[k]
        );
    }
}

/// A slider-crank at rest with weight on the slider only: the guide carries it. Its normal
/// force is along the guide's normal `n` (the guide line's direction turned +90°): +m·g
/// for a guide drawn O → B (u = +x, n = +y), −m·g for one drawn B → O.
#[test]
fn a_slider_normal_force_is_along_the_guide_direction_turned_counter_clockwise() {
    let text = |line: &str| {
        format!(
            r#"
[units]
angle = "deg"
[points]
O = [0, 0]
A = [0, 0.1]
B = [0.3, 0]
[links]
ground = ["O", "B"]
crank = ["O", "A"]
rod = ["A", "B"]
slider = ["B"]
[joints]
O = {{ type = "revolute", at = "O", links = ["ground", "crank"] }}
A = {{ type = "revolute", at = "A", links = ["crank", "rod"] }}
B = {{ type = "revolute", at = "B", links = ["rod", "slider"] }}
G = {{ type = "prismatic", links = ["ground", "slider"], line = {line}, point = "B" }}
[drive]
joint = "O"
line = ["O", "A"]
speed = 0
[sweep]
from = 0
to = 330
step = 30
[gravity]
g = 9.81
[masses]
slider = {{ mass = 3, center = "B" }}
[[dynamics]]
output = "drive_torque"
[[dynamics]]
output = "reactions"
"#
        )
    };
    let mg = 3.0 * 9.81;
    for (line, sign) in [(r#"["O", "B"]"#, 1.0), (r#"["B", "O"]"#, -1.0)] {
        let report = run(&text(line));
        // The rod is never vertical (crank 0.1 < rod 0.316 m), so it carries no force: the
        // drive torque is 0 and the guide takes the weight (1e-12 of m·g: a small linear
        // system in f64).
        for (n, m) in report
            .column("N_G")
            .unwrap()
            .iter()
            .zip(report.column("M_drive").unwrap())
        {
            assert!((n - sign * mg).abs() < 1e-12 * mg, "{line}: N_G = {n}");
            assert!(m.abs() < 1e-12 * mg, "{line}: M_drive = {m}");
        }
    }
}

#[test]
fn dynamics_columns_are_printed_in_the_files_force_and_torque_units() {
    let lbf = 0.45359237 * 9.80665;
    let metric = norton("from = 0\nto = 100\nstep = 10", "10");
    let inch = metric.replace(
        "angle = \"deg\"",
        "angle = \"deg\"\nforce = \"lbf\"\ntorque = \"lbf*in\"",
    );
    let (m, i) = (run(&metric), run(&inch));
    let unit = |r: &Report, name: &str| {
        let c = r.columns.iter().find(|c| c.name == name).unwrap();
        (c.unit.clone(), c.factor)
    };
    assert_eq!(unit(&m, "M_drive"), ("N m".to_owned(), 1.0));
    assert_eq!(unit(&i, "M_drive"), ("lbf*in".to_owned(), lbf * 0.0254));
    assert_eq!(unit(&i, "Fx_O2"), ("lbf".to_owned(), lbf));
    // The values stay SI (the factor only changes the printing): the same numbers, since
    // `force` and `torque` units apply to loads only and this scene has none.
    assert_eq!(m.column("M_drive"), i.column("M_drive"));
    let mut csv = Vec::new();
    scene::table::write_csv(&i, &mut csv).unwrap();
    let csv = String::from_utf8(csv).unwrap();
    assert!(
        csv.lines().next().unwrap().contains("M_drive [lbf*in]"),
        "{csv}"
    );
}

/// Issue 22 item 6: verdicts are scale-free. The shipped linkage scenes scaled by 10^k
/// (k = −6…6: every length of the model — points, pitch radii, a displacement drive's
/// positions, speed and acceleration), or with a point 1 m to 1e8 m away added to a moving
/// link of a loop (it takes part in no loop's closure): the check's mobility and motion
/// range, the run's rows, dead positions, limits and warnings are those of the scene as
/// shipped — the same verdicts, and the same numbers scaled by the factor's power of their
/// dimension.
mod scale_free_verdicts {
    use super::common;
    use mechdiff::scene::model::{DriveKind, JointKind, Link, Point};
    use mechdiff::scene::units::Dimension;
    use mechdiff::scene::{self, Positions, Report, Scene};
    use proptest::prelude::*;
    use proptest::test_runner::{Config, FileFailurePersistence};
    use std::sync::OnceLock;

    /// The scenes, each with a moving link of a loop that can carry a far point.
    const SCENES: [(&str, &str); 6] = [
        ("four_bar", "coupler"),
        ("slider_crank", "rod"),
        ("whitworth", "rocker"),
        ("shaper", "lever"),
        ("rack_slotted_link", "rod"),
        ("norton_four_bar", "coupler"),
    ];

    /// Agreement asked of every number, relative to its column's largest magnitude (scaled):
    /// the scaled mechanism is the same computation on numbers that differ by a power of
    /// ten, so each result differs by its rounding (a few ulp times the position's
    /// condition, ≤ 1e4 where the run would warn): 1e-12 leaves a factor ~10 above
    /// 1e4 × 2e-16 × a few. A changed verdict — a missing row, a toggle, another branch —
    /// errs at O(1).
    const AGREEMENT: f64 = 1e-12;

    fn load(name: &str) -> Scene {
        scene::load(common::scene_path(&format!("{name}.toml")))
            .unwrap_or_else(|e| panic!("{name}: {e}"))
    }

    /// `scene` with every length multiplied by `factor`, and a point `far` m away (in x and
    /// y) carried by `link` if `far` is given.
    fn transformed(scene: &Scene, factor: f64, far: Option<(&str, f64)>) -> Scene {
        let mut s = scene.clone();
        for p in &mut s.points {
            p.sketch = p.sketch.map(|x| x * factor);
        }
        for j in &mut s.joints {
            if let JointKind::RackPinion { radius, .. } = &mut j.kind {
                *radius *= factor;
            }
        }
        let displacement = s.drive.kind == DriveKind::Displacement;
        if displacement {
            s.drive.at_sketch *= factor;
            s.drive.speed = s.drive.speed.map(|v| v * factor);
            s.drive.acceleration *= factor;
        }
        let lengths = match s.sweep_of {
            Some(k) => s.outputs[k].kind.dimension() == Dimension::Length,
            None => displacement,
        };
        if lengths {
            s.positions = match &s.positions {
                Positions::List(list) => Positions::List(list.iter().map(|x| x * factor).collect()),
                Positions::Steps {
                    from,
                    step,
                    count,
                    factor: unit,
                    location,
                } => Positions::Steps {
                    from: *from,
                    step: *step,
                    count: *count,
                    factor: unit * factor,
                    location: location.clone(),
                },
            };
        }
        if let Some((link, distance)) = far {
            let location = s.points[0].location.clone();
            s.points.push(Point {
                name: "far".into(),
                sketch: [distance, 0.6 * distance],
                location,
            });
            let carrier: &mut Link = s.links.iter_mut().find(|l| l.name == link).unwrap();
            carrier.points.push("far".into());
        }
        s
    }

    /// The power of `factor` that a value of `dimension` scales with.
    fn power(dimension: Dimension) -> i32 {
        match dimension {
            Dimension::Length => 1,
            _ => 0,
        }
    }

    /// `got` is `base` × `scale` to [`AGREEMENT`] of `magnitude × scale`.
    fn agrees(got: f64, base: f64, scale: f64, magnitude: f64) -> bool {
        (got - base * scale).abs() <= AGREEMENT * magnitude * scale
    }

    /// What differs between the shipped scene's `base` results and those of the scene
    /// transformed by `factor`, or `Ok`.
    fn compare(base: &Report, got: &Report, factor: f64, drive: f64) -> Result<(), String> {
        let names = |r: &Report| r.columns.iter().map(|c| c.name.clone()).collect::<Vec<_>>();
        if names(base) != names(got) || base.rows.len() != got.rows.len() {
            return Err(format!(
                "table {:?} × {} rows, was {:?} × {}",
                names(got),
                got.rows.len(),
                names(base),
                base.rows.len()
            ));
        }
        for (c, column) in base.columns.iter().enumerate() {
            let magnitude = base.rows.iter().map(|r| r[c].abs()).fold(0.0, f64::max);
            // the power of the factor: that of the largest value (an integer power of 10^k
            // is unmistakable), then every value must follow it
            let at = base
                .rows
                .iter()
                .position(|r| r[c].abs() == magnitude)
                .unwrap();
            let e = if factor == 1.0 || magnitude == 0.0 {
                0
            } else {
                ((got.rows[at][c] / base.rows[at][c]).abs().log10() / factor.log10()).round() as i32
            };
            let scale = factor.powi(e);
            for (g, b) in got.rows.iter().zip(&base.rows) {
                if !agrees(g[c], b[c], scale, magnitude) {
                    return Err(format!(
                        "{} at φ = {}: {:e}, was {:e} × {scale:e}",
                        column.name, b[0], g[c], b[c]
                    ));
                }
            }
        }
        let dead = |r: &Report| {
            (r.dead_positions.iter())
                .map(|d| (d.output.clone(), d.positions.len()))
                .collect::<Vec<_>>()
        };
        if dead(base) != dead(got) {
            return Err(format!(
                "dead positions {:?}, were {:?}",
                dead(got),
                dead(base)
            ));
        }
        for (d, b) in got.dead_positions.iter().zip(&base.dead_positions) {
            let scale = factor.powi(power(d.dimension));
            for (x, y) in d.positions.iter().zip(&b.positions) {
                // roots of x′ refined to full precision: the drive position to 1e-12 of a
                // turn (or of the stroke), the value to 1e-12 of itself
                let turn = if drive == 1.0 {
                    2.0 * std::f64::consts::PI
                } else {
                    y.phi.abs()
                };
                if !agrees(x.phi, y.phi, drive, turn)
                    || !agrees(x.value, y.value, scale, y.value.abs())
                {
                    return Err(format!("dead position of {}: {x:?}, was {y:?}", d.output));
                }
            }
        }
        let limits = |r: &Report| {
            (r.limits.iter())
                .map(|l| (l.limit.kind, l.limit.joints.clone()))
                .collect::<Vec<_>>()
        };
        if limits(base) != limits(got) {
            return Err(format!("limits {:?}, were {:?}", limits(got), limits(base)));
        }
        for (l, b) in got.limits.iter().zip(&base.limits) {
            if !agrees(l.limit.phi, b.limit.phi, drive, b.limit.phi.abs().max(1.0)) {
                return Err(format!("limit at {}, was {}", l.limit.phi, b.limit.phi));
            }
        }
        if base.warnings.len() != got.warnings.len() {
            return Err(format!(
                "warnings {:?}, were {:?}",
                got.warnings, base.warnings
            ));
        }
        Ok(())
    }

    /// The verdicts of `check`: mobility, and the motion range's ends (kind, loop, position
    /// scaled by `drive`).
    fn check_verdicts(scene: &Scene, drive: f64) -> Result<String, String> {
        let checked = scene::check(scene).map_err(|e| format!("check: {e}"))?;
        let range = checked
            .motion_range
            .map_err(|e| format!("motion range: {e}"))?;
        let end = |l: &Option<mechdiff_core::geometry::DriveLimit>| {
            l.as_ref()
                .map(|l| format!("{:?} {:?} {:.9e}", l.kind, l.joints, l.phi / drive))
        };
        Ok(format!(
            "{:?} {:?} {:?} {:?}",
            checked.mobility,
            checked.loops,
            end(&range.lower),
            end(&range.upper)
        ))
    }

    /// A shipped scene, its check's verdicts and its run.
    type Base = (Scene, Result<String, String>, Report);

    /// The shipped scenes' check verdicts and runs, computed once.
    fn bases() -> &'static Vec<Base> {
        static BASES: OnceLock<Vec<Base>> = OnceLock::new();
        BASES.get_or_init(|| {
            SCENES
                .iter()
                .map(|(name, _)| {
                    let scene = load(name);
                    let check = check_verdicts(&scene, 1.0);
                    let report = scene::run(&scene).unwrap_or_else(|e| panic!("{name}: {e}"));
                    (scene, check, report)
                })
                .collect()
        })
    }

    fn verdicts_hold(index: usize, exponent: i32, far: Option<f64>) -> Result<(), String> {
        let (scene, base_check, base) = &bases()[index];
        let factor = 10f64.powi(exponent);
        let drive = if scene.drive.kind == DriveKind::Displacement {
            factor
        } else {
            1.0
        };
        let changed = transformed(scene, factor, far.map(|d| (SCENES[index].1, d)));
        let check = check_verdicts(&changed, drive);
        // the check's positions to 10 digits: equal verdicts print equally
        if &check != base_check {
            return Err(format!("check: {check:?}, was {base_check:?}"));
        }
        let report = scene::run(&changed).map_err(|e| format!("run: {e}"))?;
        compare(base, &report, factor, drive)
    }

    /// The examples of issue 22: the four-bar scaled by 1e-6 and 1e6, and its coupler
    /// carrying a point 3e4 m and 1e6 m away, gave a false toggle at the sketch.
    #[test]
    fn the_four_bar_scaled_or_with_a_far_coupler_point_keeps_its_verdicts() {
        for (exponent, far) in [
            (-6, None),
            (6, None),
            (-4, None),
            (5, None),
            (0, Some(3e4)),
            (0, Some(1e6)),
        ] {
            verdicts_hold(0, exponent, far)
                .unwrap_or_else(|e| panic!("four-bar ×1e{exponent}, far {far:?}: {e}"));
        }
    }

    proptest! {
        #![proptest_config(Config {
            cases: 48,
            failure_persistence: Some(Box::new(FileFailurePersistence::Direct(
                "proptest-regressions/scale_free_verdicts.txt",
            ))),
            ..Config::default()
        })]

        #[test]
        fn scaling_and_far_points_change_no_verdict(
            index in 0..SCENES.len(),
            exponent in -6i32..=6,
            far in prop::option::of(0.0f64..8.0),
            both in any::<bool>(),
        ) {
            // a far point alone (factor 1), or with the scaling
            let exponent = if far.is_some() && !both { 0 } else { exponent };
            let far = far.map(|log| 10f64.powf(log));
            let verdict = verdicts_hold(index, exponent, far);
            prop_assert!(
                verdict.is_ok(),
                "{} ×1e{exponent}, far {far:?}: {}",
                SCENES[index].0,
                verdict.unwrap_err()
            );
        }
    }
}

/// The workspace's crates: every `src/lib.rs` and `src/main.rs` of the root package and of
/// each member directory, as (crate root file, relative name).
fn crate_roots() -> Vec<(std::path::PathBuf, String)> {
    let workspace = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut packages = vec![workspace.to_path_buf()];
    let mut members: Vec<_> = std::fs::read_dir(workspace)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|dir| dir.join("Cargo.toml").is_file() && dir.join("src").is_dir())
        .collect();
    members.sort();
    packages.extend(members);
    let mut roots = Vec::new();
    for package in packages {
        for file in ["src/lib.rs", "src/main.rs"] {
            let root = package.join(file);
            if root.is_file() {
                let name = root.strip_prefix(workspace).unwrap().display().to_string();
                roots.push((root, name));
            }
        }
    }
    roots
}

/// Issue 23: no import circle of more than two modules in any crate (see
/// `import_graph` for what counts as an edge). The facade library had one of 18 when the
/// checker was written (its scene reading and run side); every crate is held to 2 now.
#[test]
fn no_crate_has_an_import_circle_of_more_than_two_modules() {
    let mut failures = Vec::new();
    let roots = crate_roots();
    assert!(roots.len() >= 5, "crates found: {roots:?}");
    for (root, name) in roots {
        let graph = import_graph::ImportGraph::from_disk(&root).unwrap();
        let circles = graph.circles();
        let largest = circles.first().map_or(0, Vec::len);
        let allowed = 2;
        println!("{name}: largest import circle {largest} modules (allowed {allowed})");
        for circle in &circles {
            println!("  {}: {}", circle.len(), circle.join(", "));
        }
        if largest > allowed {
            let big: Vec<String> = (circles.iter())
                .filter(|c| c.len() > allowed)
                .map(|c| c.join(" → "))
                .collect();
            failures.push(format!(
                "{name}: circles of more than {allowed} modules: {}",
                big.join("; ")
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The checker itself, on a crate written here: `a → b → c → a` is a circle of three; a
/// parent that declares and re-exports its child, named back by the child, is none; a path
/// through a re-export is an edge to the module that defines the item.
#[test]
fn the_import_checker_finds_a_three_circle_and_no_parent_child_circle() {
    let files: std::collections::HashMap<&str, &str> = [
        ("src/lib.rs", "mod a;\nmod b;\nmod c;\nmod d;\npub mod p;\n"),
        ("src/a.rs", "use crate::b::B;\npub struct A(B);\n"),
        ("src/b.rs", "pub struct B(pub crate::c::C);\n"),
        (
            "src/c.rs",
            "pub struct C;\nfn f() -> usize { std::mem::size_of::<crate::a::A>() }\n",
        ),
        (
            "src/d.rs",
            "use crate::p::Thing;\nfn g(t: Thing) -> Thing { t }\n",
        ),
        (
            "src/p.rs",
            "mod child;\npub use child::Thing;\npub const P: u8 = 1;\n\
             #[cfg(test)]\nmod tests {\n    use super::*;\n    fn h() -> u8 { P }\n}\n",
        ),
        (
            "src/p/child.rs",
            "pub struct Thing(u8);\nfn f() -> u8 { super::P }\n",
        ),
    ]
    .into_iter()
    .collect();
    let read = |path: &std::path::Path| files.get(path.to_str()?).map(|s| s.to_string());
    let graph = import_graph::ImportGraph::load("src/lib.rs".as_ref(), &read).unwrap();
    assert_eq!(graph.circles(), [["a", "b", "c"]]);
    let edges = graph.named_edges();
    for edge in [
        ("a", "b"),
        ("b", "c"),
        ("c", "a"),
        ("d", "p::child"),
        ("p::child", "p"),
    ] {
        let edge = (edge.0.to_owned(), edge.1.to_owned());
        assert!(edges.contains(&edge), "{edge:?} missing from {edges:?}");
    }
    // the parent's `pub use` is not an edge, nor is the re-export d reaches p's child by
    assert!(
        !edges
            .iter()
            .any(|(a, b)| (a, b) == (&"p".to_owned(), &"p::child".to_owned()))
    );
    assert!(!edges.iter().any(|(a, b)| a == "d" && b == "p"));
    // a module that uses its child's item while the child names the parent: a circle of two
    let with_use = [
        ("src/lib.rs", "mod p;\n"),
        (
            "src/p.rs",
            "mod child;\nfn g() -> child::Thing { child::Thing(super_p()) }\nfn super_p() -> u8 { 1 }\n",
        ),
        (
            "src/p/child.rs",
            "pub struct Thing(pub u8);\nfn f() -> u8 { super::super_p() }\n",
        ),
    ];
    let files: std::collections::HashMap<&str, &str> = with_use.into_iter().collect();
    let read = |path: &std::path::Path| files.get(path.to_str()?).map(|s| s.to_string());
    let graph = import_graph::ImportGraph::load("src/lib.rs".as_ref(), &read).unwrap();
    assert_eq!(graph.circles(), [["p", "p::child"]]);
}

/// The runner and the effects (issue 23): they take a resolved `Setup` (or the parts of it
/// they need, e.g. the scene's words `ErrorContext`), never the whole `Scene`. Relative to
/// the workspace; a folder stands for every `.rs` file under it.
const RUN_SIDE: [&str; 13] = [
    "src/scene/run.rs",
    "src/scene/sweep.rs",
    "src/scene/sweep_limits.rs",
    "src/scene/evaluate.rs",
    "src/scene/plan.rs",
    "src/scene/preflight.rs",
    "src/stream",
    "src/scene/dynamics/run.rs",
    "src/scene/dynamics/tangent.rs",
    "src/scene/balancing/run.rs",
    "src/evaluator/program.rs",
    "src/evaluator/code.rs",
    "src/scene/setup.rs",
];

/// Every `.rs` file at `path` (a file, or a folder searched recursively), sorted.
fn rust_files(path: &std::path::Path) -> Vec<std::path::PathBuf> {
    if path.is_file() {
        return vec![path.to_path_buf()];
    }
    let mut files: Vec<_> = (std::fs::read_dir(path).unwrap())
        .map(|entry| entry.unwrap().path())
        .flat_map(|p| match p.is_dir() {
            true => rust_files(&p),
            false => (p.extension().is_some_and(|e| e == "rs"))
                .then_some(p)
                .into_iter()
                .collect(),
        })
        .collect();
    files.sort();
    files
}

/// Issue 23: "`&Scene` appears in no function of the runner or the effects" — no function
/// of the run side takes the scene and no type of it holds the scene (see
/// `scene_parameters`), except `Setup::of`, the one place the scene is resolved for a run.
#[test]
fn no_function_of_the_runner_or_the_effects_takes_the_scene() {
    let workspace = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut failures = Vec::new();
    let mut files = 0;
    for path in RUN_SIDE {
        let path = workspace.join(path);
        assert!(path.exists(), "{} is gone: update RUN_SIDE", path.display());
        for file in rust_files(&path) {
            files += 1;
            let text = std::fs::read_to_string(&file).unwrap();
            let found = scene_parameters::taking_the_scene(&text).unwrap();
            let name = file.strip_prefix(workspace).unwrap().display().to_string();
            for what in found {
                // The edge: the scene resolved once for a run.
                if !(name == "src/scene/setup.rs" && what == "fn of takes the scene") {
                    failures.push(format!("{name}: {what}"));
                }
            }
        }
    }
    assert!(files >= RUN_SIDE.len() + 3, "files read: {files}");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The scene checker itself, on planted code: each way of taking or holding the scene is
/// found, named with its module and enclosing function; the resolved setup, a type whose
/// name only starts with `Scene`, a returned scene and a path through `Scene::` are not.
#[test]
fn the_scene_checker_finds_each_planted_scene_parameter() {
    let planted = r#"
        use crate::scene::Scene;
        pub fn run(scene: &Scene) {}
        fn lifetime<'s>(x: u8, scene: &'s crate::scene::model::Scene) {}
        fn wrapped(scene: Option<&Scene>) {}
        fn by_value(scene: Scene) {}
        pub struct Sweeper<'s> { scene: &'s Scene, n: usize }
        enum Walk<'s> { First(&'s Scene), Second }
        impl Scene { fn describe(&self) -> String { String::new() } fn new() -> Self { todo!() } }
        impl Sweeper<'_> { fn row(&mut self, scene: &Scene) {} }
        trait Words { fn head(&self, scene: &Scene) -> String; }
        fn outer() { fn inner(s: &Scene) {} }
        mod tests { fn helper(s: &super::Scene) {} }
        // none of these takes the scene
        fn setup(setup: &Setup<'_>, d: &SceneDynamics, code: &SceneCode) {}
        fn read(text: &str) -> Scene { todo!() }
        fn path() { let s = Scene::default(); }
        fn closure() { let f = |s: &Scene| (); }
        struct Fine { d: SceneDynamics }
    "#;
    let found = scene_parameters::taking_the_scene(planted).unwrap();
    assert_eq!(
        found,
        [
            "fn run takes the scene",
            "fn lifetime takes the scene",
            "fn wrapped takes the scene",
            "fn by_value takes the scene",
            "struct Sweeper holds the scene",
            "enum Walk holds the scene",
            "fn describe takes the scene",
            "fn row takes the scene",
            "fn head takes the scene",
            "fn outer::inner takes the scene",
            "fn tests::helper takes the scene",
        ]
    );
}

/// A module that re-exports another crate's module (`pub use other::units;`, as the facade
/// re-exports `mechdiff-scene`'s) is not where its children's paths through it lead: a child
/// naming `super::units::Dimension` names the other crate, so the parent, whose own code
/// names that child, is in no circle with it.
#[test]
fn the_import_checker_takes_a_path_through_another_crates_module_as_external() {
    let files: std::collections::HashMap<&str, &str> = [
        ("src/lib.rs", "mod scene;\n"),
        (
            "src/scene.rs",
            "mod drive;\npub use other::units;\nfn f() -> drive::Drive { drive::Drive }\n",
        ),
        (
            "src/scene/drive.rs",
            "pub struct Drive;\nfn g() -> super::units::Dimension { todo!() }\n",
        ),
    ]
    .into_iter()
    .collect();
    let read = |path: &std::path::Path| files.get(path.to_str()?).map(|s| s.to_string());
    let graph = import_graph::ImportGraph::load("src/lib.rs".as_ref(), &read).unwrap();
    let edges = graph.named_edges();
    assert_eq!(edges, [("scene".to_owned(), "scene::drive".to_owned())]);
    assert!(graph.circles().is_empty(), "{:?}", graph.circles());
}
