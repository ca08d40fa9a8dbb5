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
    // In the file's angle unit (issue 22: every number of an error in the scene's units).
    assert!(e.contains("cam angle 120 deg"), "{e}");
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

/// Issue 22, cam messages and answers: each class of defect, reproduced on `GOOD` and its
/// variants, with the new behaviour.
mod messages_and_answers {
    use super::*;

    /// `GOOD` as a flat-faced follower (no offset or radius) with `base_radius`.
    fn flat(base_radius: &str) -> String {
        GOOD.replace("type = \"roller\"", "type = \"flat_faced\"")
            .replace("offset = 10\n", "")
            .replace("radius = 8\n", "")
            .replace("base_radius = 40", &format!("base_radius = {base_radius}"))
    }

    fn parse(text: &str) -> CamScene {
        cam_scene::parse("cam.toml", text).unwrap_or_else(|e| panic!("{e}"))
    }

    fn csv(scene: &CamScene) -> (Vec<String>, Vec<Vec<String>>) {
        let mut out = Vec::new();
        cam::write_svaj_csv(scene, &mut out).unwrap();
        let text = String::from_utf8(out).unwrap();
        let mut lines = text.lines();
        let header = lines
            .next()
            .unwrap()
            .split(',')
            .map(str::to_owned)
            .collect();
        let rows = lines
            .map(|l| l.split(',').map(str::to_owned).collect())
            .collect();
        (header, rows)
    }

    fn column(header: &[String], rows: &[Vec<String>], name: &str) -> Vec<f64> {
        let k = header.iter().position(|h| h.starts_with(name)).unwrap();
        rows.iter().map(|r| r[k].parse().unwrap()).collect()
    }

    /// A flat face with a 5 mm base circle has cusps: the CSV's ρ is signed, each row equals
    /// the closed form R_b + s + s″ of the same row (1e-9 mm: rounding of a sum of terms of
    /// at most ~100 mm), its negative values are in the summary's undercut ranges, and the
    /// summary's minimum (refined by golden section) is at most the CSV's smallest value
    /// and within 0.5 mm of it (rows every 10°; ρ changes by less than that between them
    /// near its minimum).
    #[test]
    fn flat_face_radius_of_curvature_is_signed_in_table_csv_and_summary() {
        let scene = parse(&flat("5"));
        let (header, rows) = csv(&scene);
        let s = column(&header, &rows, "s [");
        let s2 = column(&header, &rows, "s″");
        let rho = column(&header, &rows, "ρ profile");
        for ((s, s2), rho) in s.iter().zip(&s2).zip(&rho) {
            assert!(
                (rho - (5.0 + s + s2)).abs() <= 1e-9,
                "{rho} vs {}",
                5.0 + s + s2
            );
        }
        let least = rho.iter().copied().fold(f64::INFINITY, f64::min);
        assert!(least < 0.0, "the cusps are in the CSV: {rho:?}");
        let analysis = scene.mechanism.analyse();
        let summary = analysis.min_profile_radius.value * 1e3;
        assert!(
            summary <= least + 1e-9 && least - summary < 0.5,
            "{summary} vs {least}"
        );
        let text = report(&scene);
        assert!(text.contains(&format!("{:.4} mm", summary)), "{text}");
        // The table prints the same signed numbers (its last column, about 8 digits).
        let table = &text[text.find("SVAJ (").unwrap()..text.find("boundaries:").unwrap()];
        let printed: Vec<f64> = (table.lines().skip(2))
            .filter_map(|l| l.split_whitespace().last()?.parse().ok())
            .collect();
        assert_eq!(printed.len(), rho.len());
        for (p, r) in printed.iter().zip(&rho) {
            assert!((p - r).abs() <= 1e-6, "table {p} vs CSV {r}");
        }
        // A flat face is never told to use a smaller roller.
        assert!(!text.contains("roller"), "{text}");
        assert!(text.contains("enlarge the base circle"), "{text}");
    }

    /// Every number of an error in the file's units: lengths in mm (no SI 0.048), an angle
    /// in the file's angle unit (never in mm), no `NaN`.
    #[test]
    fn errors_give_numbers_in_the_files_units() {
        let e = error_for("offset = 10", "offset = 60");
        assert!(e.contains("prime circle radius 48 mm"), "{e}");
        assert!(!e.contains("0.048"), "{e}");
        let e = error_for(
            "base_radius = 40",
            "base_radius = 40\npressure_angle_limit = 95",
        );
        assert!(e.contains("95 deg") && e.contains("90 deg"), "{e}");
        assert!(!e.contains("mm") && !e.contains("5156620"), "{e}");
        let rad = GOOD.replace("angle = \"deg\"", "angle = \"rad\"").replace(
            "base_radius = 40",
            "base_radius = 40\npressure_angle_limit = 2",
        );
        let rad = rad
            .replace("extent = 120", "extent = \"2*pi/3\"")
            .replace("extent = 60", "extent = \"pi/3\"");
        let e = cam_scene::parse("rad.toml", &rad).unwrap_err().to_string();
        assert!(
            e.contains("2 rad") && e.contains("1.5707963267949 rad"),
            "{e}"
        );
        let e = cam_scene::parse("flat.toml", &flat("40\npressure_angle_limit = 30"))
            .unwrap_err()
            .to_string();
        assert!(!e.contains("NaN"), "{e}");
        assert!(e.contains("min_radius_of_curvature"), "{e}");
        assert!(
            e.starts_with(&format!("flat.toml:{}:", line_of("base_radius") + 1)),
            "{e}"
        );
    }

    /// A key the follower type has no use for is refused where it is written.
    #[test]
    fn keys_that_do_not_apply_to_the_follower_are_refused() {
        let with_offset =
            flat("40").replace("type = \"flat_faced\"", "type = \"flat_faced\"\noffset = 5");
        let e = cam_scene::parse("f.toml", &with_offset)
            .unwrap_err()
            .to_string();
        let line = with_offset.lines().position(|l| l == "offset = 5").unwrap() + 1;
        assert!(e.starts_with(&format!("f.toml:{line}:10:")), "{e}");
        assert!(
            e.contains("`offset` does not apply to a `flat_faced` follower"),
            "{e}"
        );
        let e = error_for("type = \"roller\"", "type = \"knife_edge\"");
        assert!(
            e.starts_with(&format!("bad.toml:{}:10:", line_of("radius = 8"))),
            "{e}"
        );
        assert!(
            e.contains("`radius` does not apply to a `knife_edge` follower"),
            "{e}"
        );
        let e = error_for("radius = 8", "radius = 8\narm_length = 50");
        assert!(
            e.contains("`arm_length` does not apply to a `roller`"),
            "{e}"
        );
    }

    /// A step too small for a table is refused before anything is computed (1e-300 aborted
    /// with "capacity overflow"; 1e-4° allocated gigabytes), naming the smallest step.
    #[test]
    fn a_cam_step_is_bounded() {
        for step in ["1e-300", "1e-4", "0.0035"] {
            let e = error_for(
                "base_radius = 40",
                &format!("base_radius = 40\nstep = {step}"),
            );
            assert!(e.contains("100000 rows") && e.contains("0.0036 deg"), "{e}");
        }
        assert!(
            cam_scene::parse(
                "ok.toml",
                &GOOD.replace("base_radius = 40", "base_radius = 40\nstep = 0.0036")
            )
            .is_ok()
        );
    }

    /// Quoted formulas wherever a number is: the same cam as with the numbers written out
    /// (bit for bit: the formulas evaluate to the same f64).
    #[test]
    fn formulas_are_accepted_in_cam() {
        let formulas = GOOD
            .replace("base_radius = 40", "base_radius = \"30 + 10\"")
            .replace("radius = 8", "radius = \"2*4\"")
            .replace("rise = 20", "rise = \"40/2\"")
            .replace("extent = 120", "extent = \"360/3\"");
        let (a, b) = (parse(GOOD), parse(&formulas));
        assert_eq!(a.mechanism.dimensions, b.mechanism.dimensions);
        assert_eq!(report(&a), report(&b));
    }

    /// A pressure angle over the stated limit is warned with the angle and the cam angle
    /// where it is largest (the report's maximum, in degrees); under the limit, no warning.
    #[test]
    fn a_pressure_angle_over_the_limit_is_warned() {
        let over = parse(&GOOD.replace(
            "base_radius = 40",
            "base_radius = 40\npressure_angle_limit = 20",
        ));
        let analysis = over.mechanism.analyse();
        let warnings = over.warnings(&analysis);
        assert_eq!(warnings.len(), 1, "{warnings:?}");
        let p = analysis.max_pressure_angle;
        assert!(p.value.to_degrees() > 20.0);
        let w = &warnings[0];
        assert!(
            w.contains(&format!("{:.4} deg", p.value.to_degrees())),
            "{w}"
        );
        assert!(
            w.contains(&format!("θ = {:.4} deg", p.angle.to_degrees())),
            "{w}"
        );
        assert!(
            w.contains("limit of 20.0000 deg") && w.contains("cam.toml:"),
            "{w}"
        );
        assert!(report(&over).contains(&format!("WARNING: {w}")));
        let under = parse(&GOOD.replace(
            "base_radius = 40",
            "base_radius = 40\npressure_angle_limit = 40",
        ));
        assert!(under.warnings(&under.mechanism.analyse()).is_empty());
    }

    /// Boundary rows at the exact boundary angle: every θ of the CSV is a whole multiple of
    /// the 10° step, written exactly (120, 180, 300, not 299.99999999999994).
    #[test]
    fn table_rows_are_at_exact_multiples_of_the_step() {
        let scene = parse(&GOOD.replace("base_radius = 40", "base_radius = 40\nstep = 10"));
        let (header, rows) = csv(&scene);
        let theta = column(&header, &rows, "θ");
        for t in &theta {
            assert_eq!(*t, (t / 10.0).round() * 10.0, "{t}");
        }
        for boundary in [120.0, 180.0, 300.0, 360.0] {
            assert_eq!(
                theta.iter().filter(|t| **t == boundary).count(),
                2,
                "{boundary}"
            );
        }
    }

    /// `--json`: the summary's values, in the file's units, equal the analysis (to 15
    /// significant digits, as they are rounded).
    #[test]
    fn json_holds_the_summary_in_the_files_units() {
        let scene = parse(&flat("5"));
        let mut out = Vec::new();
        cam::write_json(&scene, &mut out).unwrap();
        let json: Value = serde_json::from_slice(&out).unwrap();
        let a = scene.mechanism.analyse();
        let close = |v: &Value, x: f64| (v.as_f64().unwrap() - x).abs() <= 1e-12 * x.abs().max(1.0);
        assert!(close(
            &json["min_profile_radius"]["value"],
            a.min_profile_radius.value * 1e3
        ));
        assert!(close(
            &json["min_profile_radius"]["cam_angle"],
            a.min_profile_radius.angle.to_degrees()
        ));
        let (low, high) = a.face_extent.unwrap();
        assert!(close(&json["face"]["min_width"], (high - low) * 1e3));
        assert_eq!(json["undercut"].as_array().unwrap().len(), a.undercut.len());
        assert!(close(
            &json["undercut"][0]["from"],
            a.undercut[0].0.to_degrees()
        ));
        assert_eq!(json["units"]["length"], "mm");
        let sized = parse(&GOOD.replace(
            "base_radius = 40",
            "base_radius = 40\npressure_angle_limit = 30",
        ));
        let mut out = Vec::new();
        cam::write_json(&sized, &mut out).unwrap();
        let json: Value = serde_json::from_slice(&out).unwrap();
        assert!(close(
            &json["sizing"]["min_base_radius"],
            sized.sizing.as_ref().unwrap().0 * 1e3
        ));
        // `mechdiff run cam.toml --json FILE` writes it.
        let path = std::env::temp_dir().join(format!("mechdiff-cam-{}.json", std::process::id()));
        let output = crate::common::mechdiff(&[
            "run",
            "scenes/cams/rise_dwell_return_dwell.toml",
            "--json",
            path.to_str().unwrap(),
        ]);
        assert!(
            output.status.success(),
            "{}",
            String::from_utf8_lossy(&output.stderr)
        );
        let json: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        assert!(json["max_pressure_angle"]["value"].as_f64().unwrap() > 0.0);
        std::fs::remove_file(path).ok();
    }
}
