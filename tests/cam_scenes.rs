//! Cam scenes (`scenes/cams/`): every one runs; the reference 002 scenes reproduce the
//! reference table through the scene's units; bad input is refused with `file:line:col` and
//! the cam angle; `--csv` and `--profile-csv` write what the report shows.

use std::path::PathBuf;
use std::process::Command;

use mechdiff::report::cam;
use mechdiff::scene::cam::{self as cam_scene, CamScene};
use serde_json::Value;

fn scene_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("scenes/cams")
        .join(name)
}

fn report(scene: &CamScene) -> String {
    let mut out = Vec::new();
    cam::write_report(scene, &mut out).unwrap();
    String::from_utf8(out).unwrap()
}

#[test]
fn every_cam_scene_runs() {
    let mut count = 0;
    for entry in std::fs::read_dir(scene_path("")).unwrap() {
        let path = entry.unwrap().path();
        let scene = cam_scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
        let text = report(&scene);
        assert!(
            text.contains("maximum pressure angle"),
            "{}",
            path.display()
        );
        let bad = |w: &str| ["NaN", "inf", "-inf"].contains(&w);
        assert!(!text.split_whitespace().any(bad), "{text}");
        count += 1;
    }
    assert!(
        count >= 4,
        "the three laws of reference 002 and the RDRD cam"
    );
}

/// The SVAJ CSV of the three reference-002 scenes (mm, deg) against the reference values
/// (copied from the project's reference material into `core/tests/data`): y, y′, y″ at
/// x = kπ/8 with the one-sided values at the jumps. 1e-12 relative (1e-12 of 80 mm where the
/// reference is 0): the scene converts mm → m → mm and degrees → rad, a few roundings.
#[test]
fn reference_002_scenes_reproduce_the_reference_table() {
    let data: Value =
        serde_json::from_str(include_str!("../core/tests/data/cams_reference_002.json")).unwrap();
    for (file, key) in [
        ("reference_002_uniform_velocity.toml", "uniform_velocity"),
        (
            "reference_002_parabolic.toml",
            "uniform_acceleration_retardation",
        ),
        (
            "reference_002_simple_harmonic.toml",
            "simple_harmonic_motion",
        ),
    ] {
        let scene = cam_scene::load(&scene_path(file)).unwrap();
        let mut csv = Vec::new();
        cam::write_svaj_csv(&scene, &mut csv).unwrap();
        let csv = String::from_utf8(csv).unwrap();
        let rows: Vec<Vec<&str>> = csv
            .lines()
            .skip(1)
            .map(|l| l.split(',').collect())
            .collect();
        let table = data["cams"][key]["table"].as_array().unwrap();
        for reference in table {
            let degrees = reference["x_deg"].as_f64().unwrap();
            let one_sided = reference.get("y_p_left_mm_per_rad").is_some();
            let sides: &[(&str, &str)] = if one_sided {
                &[("left", "_left"), ("right", "_right")]
            } else {
                &[("", "")]
            };
            for &(side, suffix) in sides {
                let row = rows
                    .iter()
                    .find(|r| (r[0].parse::<f64>().unwrap() - degrees).abs() < 1e-9 && r[1] == side)
                    .unwrap_or_else(|| panic!("{file}: no row at {degrees}° {side}"));
                let want = [
                    reference["y_mm"].as_f64().unwrap(),
                    reference[format!("y_p{suffix}_mm_per_rad")]
                        .as_f64()
                        .unwrap(),
                    reference[format!("y_pp{suffix}_mm_per_rad2")]
                        .as_f64()
                        .unwrap(),
                ];
                for (k, want) in want.iter().enumerate() {
                    let got: f64 = row[2 + k].parse().unwrap();
                    let allowed = 1e-12 * if *want == 0.0 { 80.0 } else { want.abs() };
                    assert!(
                        (got - want).abs() <= allowed,
                        "{file} at {degrees}° {side}, column {k}: {got} vs {want}"
                    );
                }
            }
        }
        // The boundary report of the scene names the same jumps as the core test.
        let text = report(&scene);
        let jumps = text.lines().filter(|l| l.contains(" jumps from ")).count();
        assert_eq!(
            jumps,
            if key == "simple_harmonic_motion" {
                0
            } else {
                2
            },
            "{text}"
        );
    }
}

const GOOD: &str = r#"
[units]
length = "mm"
angle = "deg"

[cam]
base_radius = 40

[cam.follower]
type = "roller"
offset = 10
radius = 8

[[cam.segment]]
law = "cycloidal"
rise = 20
extent = 120

[[cam.segment]]
law = "dwell"
extent = 60

[[cam.segment]]
law = "polynomial_345"
return = 20
extent = 120

[[cam.segment]]
law = "dwell"
extent = 60
"#;

/// The error for `GOOD` with `from` replaced by `to`.
fn error_for(from: &str, to: &str) -> String {
    let text = GOOD.replacen(from, to, 1);
    assert_ne!(text, GOOD, "the edit applies");
    match cam_scene::parse("bad.toml", &text) {
        Ok(_) => panic!("accepted: {to}"),
        Err(e) => e.to_string(),
    }
}

/// The line of the first occurrence of `needle` in `GOOD` after editing (1-based).
fn line_of(needle: &str) -> usize {
    GOOD.lines().position(|l| l.contains(needle)).unwrap() + 1
}

#[test]
fn bad_cam_input_is_refused_with_file_line_and_cam_angle() {
    assert!(cam_scene::parse("good.toml", GOOD).is_ok());
    // Segments that do not cover a turn.
    let e = error_for(
        "extent = 60\n\n[[cam.segment]]\nlaw = \"polynomial_345\"",
        "extent = 50\n\n[[cam.segment]]\nlaw = \"polynomial_345\"",
    );
    assert!(e.starts_with("bad.toml:") && e.contains("350°"), "{e}");
    // An extent that is not positive: the line of the extent, in the file's unit.
    let e = error_for("extent = 60", "extent = -60");
    let line = line_of("extent = 60");
    assert!(
        e.starts_with(&format!("bad.toml:{line}:")) && e.contains("-60 deg"),
        "{e}"
    );
    // Displacements that do not join (a formula that starts at 5 mm after a dwell at 20).
    let e = error_for(
        "law = \"dwell\"\nextent = 60",
        "formula = \"5\"\nextent = 60",
    );
    let line = line_of("law = \"dwell\"") - 1;
    assert!(e.starts_with(&format!("bad.toml:{line}:")), "{e}");
    assert!(e.contains("cam angle 120°"), "{e}");
    assert!(
        e.contains("ends at 20 mm") && e.contains("starts at 5 mm"),
        "{e}"
    );
    // An offset not smaller than the prime circle.
    let e = error_for("offset = 10", "offset = 60");
    assert!(
        e.starts_with(&format!("bad.toml:{}:", line_of("offset = 10"))),
        "{e}"
    );
    assert!(e.contains("offset = 60 mm"), "{e}");
    // Other mistakes: unknown law, missing rise, a formula that does not parse.
    let e = error_for("\"cycloidal\"", "\"cubic\"");
    assert!(
        e.contains("unknown law `cubic`") && e.contains("modified_sine"),
        "{e}"
    );
    let e = error_for("rise = 20\n", "");
    assert!(e.contains("needs `rise = …` or `return = …`"), "{e}");
    let e = error_for("law = \"dwell\"", "formula = \"20 +* x\"");
    assert!(e.contains("in the formula"), "{e}");
    let e = error_for("extent = 120", "extent = nan");
    assert!(e.starts_with("bad.toml:"), "{e}");
    // Numbers whose results overflow: the place of the number, never an inf in the table.
    let e = error_for("base_radius = 40", "base_radius = 40\nspeed = 1e300");
    assert!(
        e.starts_with(&format!("bad.toml:{}:", line_of("base_radius") + 1)),
        "{e}"
    );
    assert!(e.contains("overflows"), "{e}");
    let e = error_for("rise = 20", "rise = 1e308");
    assert!(e.starts_with("bad.toml:"), "{e}");
    let e = error_for("radius = 8", "radius = inf");
    assert!(
        e.starts_with(&format!("bad.toml:{}:", line_of("radius = 8"))),
        "{e}"
    );
}

/// A roller larger than the smallest radius of curvature of the pitch curve: a warning with
/// the cam angles and the place of the roller radius in the file (not an error: the report
/// is what the designer needs to fix it).
#[test]
fn a_roller_too_large_is_reported_with_cam_angles() {
    let text = GOOD
        .replace("rise = 20\nextent = 120", "rise = 30\nextent = 45")
        .replace("return = 20\nextent = 120", "return = 30\nextent = 45")
        .replace(
            "law = \"dwell\"\nextent = 60\n\n[[cam.segment]]\nlaw = \"polynomial_345\"",
            "law = \"polynomial_345\"",
        )
        .replace("extent = 60\n", "extent = 270\n")
        .replace("radius = 8", "radius = 15")
        .replace("base_radius = 40", "base_radius = 10")
        .replace("offset = 10", "offset = 0");
    let scene = cam_scene::parse("big_roller.toml", &text).unwrap();
    let out = report(&scene);
    let warning = out
        .lines()
        .find(|l| l.starts_with("WARNING: undercutting"))
        .unwrap_or_else(|| panic!("{out}"));
    assert!(warning.contains("big_roller.toml:"), "{warning}");
    assert!(warning.contains(" deg"), "{warning}");
}

/// `mechdiff run --csv --profile-csv` on the RDRD cam: the profile CSV's points are at the
/// roller radius (8 mm) from the pitch points, 1e-12 relative (values written with all
/// their digits).
#[test]
fn run_writes_the_svaj_and_profile_csv() {
    let dir = std::env::temp_dir();
    let svaj = dir.join(format!("mechdiff-cam-{}-svaj.csv", std::process::id()));
    let profile = dir.join(format!("mechdiff-cam-{}-profile.csv", std::process::id()));
    let output = Command::new(env!("CARGO_BIN_EXE_mechdiff"))
        .args(["run", "scenes/cams/rise_dwell_return_dwell.toml", "--csv"])
        .arg(&svaj)
        .arg("--profile-csv")
        .arg(&profile)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let stdout = String::from_utf8(output.stdout).unwrap();
    assert!(stdout.contains("smallest base circle radius"), "{stdout}");
    let svaj_text = std::fs::read_to_string(&svaj).unwrap();
    assert!(
        svaj_text.starts_with("θ [deg],side,s [mm],s′ [mm/rad]"),
        "{svaj_text}"
    );
    let profile_text = std::fs::read_to_string(&profile).unwrap();
    let lines: Vec<&str> = profile_text.lines().collect();
    assert_eq!(lines.len(), 1 + cam::PROFILE_POINTS);
    for line in &lines[1..] {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        let distance = (v[1] - v[3]).hypot(v[2] - v[4]);
        assert!((distance - 8.0).abs() <= 8.0 * 1e-12, "{line}");
    }
    std::fs::remove_file(svaj).ok();
    std::fs::remove_file(profile).ok();
}

/// The pictures of every cam scene: the SVAJ diagram and the profile drawing render to
/// pixels with ink in them, and the drawn contact point carries the exact model position of
/// the contact (`data-x`, `data-y`, written with all digits): equal to the library's to
/// 1e-12 of the base radius.
#[test]
fn cam_pictures_render_and_the_contact_is_drawn_where_it_is() {
    use mechdiff::pictures::{cam as cam_pictures, raster};
    use mechdiff_core::cams::Side;
    for entry in std::fs::read_dir(scene_path("")).unwrap() {
        let path = entry.unwrap().path();
        let scene = cam_scene::load(&path).unwrap();
        for svg in [
            cam_pictures::svaj_diagram(&scene).to_svg().unwrap(),
            cam_pictures::profile_drawing(&scene, 0.0).to_svg(),
        ] {
            let image = raster::render(&svg).unwrap();
            let inked = image
                .rgba
                .chunks(4)
                .filter(|p| p[0] < 128 && p[3] > 0)
                .count();
            assert!(inked > 500, "{}: {inked} dark pixels", path.display());
        }
        let svg = cam_pictures::profile_drawing(&scene, 0.0).to_svg();
        let at = svg.find("data-point=\"contact\"").unwrap();
        let attribute = |name: &str| -> f64 {
            let start = svg[at..].find(&format!("{name}=\"")).unwrap() + at + name.len() + 2;
            let end = svg[start..].find('"').unwrap() + start;
            svg[start..end].parse().unwrap()
        };
        let contact = scene.mechanism.contact(0.0, Side::Right).profile;
        let mm = 1.0
            / scene
                .units
                .factor(mechdiff::scene::units::Dimension::Length);
        let base = scene.mechanism.dimensions.base_radius * mm;
        assert!((attribute("data-x") - contact[0] * mm).abs() <= 1e-12 * base);
        assert!((attribute("data-y") - contact[1] * mm).abs() <= 1e-12 * base);
    }
}

/// A formula that is not a number inside its segment only (√ of a negative number between
/// its finite ends) is refused,
/// never printed as NaN.
#[test]
fn a_formula_that_is_nan_inside_its_segment_is_refused() {
    let text = GOOD.replacen(
        "law = \"dwell\"\nextent = 60",
        "formula = \"20 + 1e-9*sqrt((x - 2.5)^2 - 0.01)\"\nextent = 60",
        1,
    );
    match cam_scene::parse("nan.toml", &text) {
        Ok(scene) => panic!("accepted:\n{}", report(&scene)),
        Err(e) => assert!(e.to_string().starts_with("nan.toml:"), "{e}"),
    }
}

/// Formula segments are written in the file's units (mm here, x in rad): reference 002's
/// parabolic pieces as formulas give its table (80 mm at 180°, 40 mm and y′ = 160/π mm/rad
/// at 90°), 1e-12 relative.
#[test]
fn formula_segments_are_in_the_files_units() {
    let text = r#"
[units]
length = "mm"
angle = "deg"
[cam]
base_radius = 50
[cam.follower]
type = "knife_edge"
[[cam.segment]]
formula = "160*x^2/pi^2"
extent = 90
[[cam.segment]]
formula = "-160*x^2/pi^2 + 320*x/pi - 80"
extent = 180
[[cam.segment]]
formula = "160*x^2/pi^2 - 640*x/pi + 640"
extent = 90
"#;
    let scene = cam_scene::parse("formulas.toml", text).unwrap();
    let program = &scene.mechanism.program;
    let mm = 1e3;
    let pi = std::f64::consts::PI;
    let at = |x: f64| program.svaj(x, mechdiff_core::cams::Side::Right);
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
    assert!(close(at(pi).value * mm, 80.0));
    assert!(close(at(pi / 2.0).value * mm, 40.0));
    assert!(close(at(pi / 2.0).d1() * mm, 160.0 / pi));
}
