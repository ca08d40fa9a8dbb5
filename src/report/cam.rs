//! The report of a cam scene: plan, segments, SVAJ table, boundary report, pressure angle,
//! curvature, undercutting, sizing; and the CSV files of the SVAJ table and of the profile.

use std::f64::consts::TAU;
use std::io::{self, Write};

use mechdiff_core::cams::{BoundaryKind, CamAnalysis, ContinuityReport, Follower, Side};

use super::{Table, fixed};
use crate::scene::cam::CamScene;
use crate::scene::units::{Dimension, Units};

/// Points of the profile written by [`write_profile_csv`] (every 0.5°).
pub const PROFILE_POINTS: usize = 720;

/// One row of the SVAJ table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SvajRow {
    /// Cam angle (rad).
    pub theta: f64,
    /// Cam angle as printed, in the file's angle unit (a whole multiple of the step).
    pub shown_theta: f64,
    /// The side of a boundary the row is on (`None` away from boundaries with a jump).
    pub side: Option<Side>,
    /// s, s′, s″, s‴ (SI, per rad).
    pub svaj: [f64; 4],
    /// Follower velocity, acceleration, jerk (SI, per s), if the cam turns.
    pub motion: Option<[f64; 3]>,
    /// Pressure angle (rad).
    pub pressure_angle: f64,
    /// Profile radius of curvature (SI; infinite where the profile is straight).
    pub profile_radius: f64,
}

/// The rows of the SVAJ table: every `step` from 0 to 360°, two rows (one-sided values) at
/// a boundary where a derivative jumps.
pub fn svaj_rows(scene: &CamScene, report: &ContinuityReport) -> Vec<SvajRow> {
    let cam = &scene.mechanism;
    let mut rows = Vec::new();
    for (theta, shown_theta) in scene.table_angles() {
        let jumps = report.boundaries.iter().any(|b| {
            let d = (theta - b.angle).rem_euclid(TAU);
            b.first_jump().is_some() && d.min(TAU - d) <= 1e-9
        });
        let sides: &[Option<Side>] = if jumps {
            &[Some(Side::Left), Some(Side::Right)]
        } else {
            &[None]
        };
        for &side in sides {
            let at = side.unwrap_or(if theta >= TAU {
                Side::Left
            } else {
                Side::Right
            });
            let jet = cam.program.svaj(theta, at);
            let svaj = [jet.value, jet.d1(), jet.d2(), jet.d3()];
            let motion = (scene.drive.omega != 0.0 || scene.drive.alpha != 0.0).then(|| {
                let m = jet.motion(&scene.drive);
                [m.velocity, m.acceleration, m.jerk.unwrap_or(0.0)]
            });
            let r = cam.dimensions.follower.roller_radius();
            // Signed for every follower, as in the summary: negative at a flat face's cusp
            // (R_b + s + s″ < 0) and where a roller's profile is concave or undercut.
            let profile_radius = match cam.dimensions.follower {
                Follower::FlatFaced => cam.flat_face_radius(theta, at),
                _ => 1.0 / cam.pitch_curvature(theta, at) - r,
            };
            rows.push(SvajRow {
                theta,
                shown_theta,
                side,
                svaj,
                motion,
                pressure_angle: cam.pressure_angle(theta, at),
                profile_radius,
            });
        }
    }
    rows
}

/// Units of the displacement and its derivatives: `[s, s′, s″, s‴, v, a, j]`.
fn column_units(scene: &CamScene) -> ([&'static str; 7], Dimension) {
    let u = &scene.units;
    match scene.displacement_dimension() {
        Dimension::Angle => (
            [
                u.symbol(Dimension::Angle),
                "rad/rad",
                "rad/rad^2",
                "rad/rad^3",
                "rad/s",
                "rad/s^2",
                "rad/s^3",
            ],
            Dimension::Angle,
        ),
        _ => {
            let mm = u.length == crate::scene::units::LengthUnit::Millimetre;
            let l = if mm { "mm" } else { "m" };
            let per = |s: &'static str, t: &'static str| if mm { s } else { t };
            (
                [
                    l,
                    per("mm/rad", "m/rad"),
                    per("mm/rad^2", "m/rad^2"),
                    per("mm/rad^3", "m/rad^3"),
                    per("mm/s", "m/s"),
                    per("mm/s^2", "m/s^2"),
                    per("mm/s^3", "m/s^3"),
                ],
                Dimension::Length,
            )
        }
    }
}

/// The factor from SI to the printed unit for the displacement's derivatives (the
/// displacement itself is converted with its dimension).
fn derivative_factor(scene: &CamScene, dimension: Dimension) -> f64 {
    match dimension {
        Dimension::Angle => 1.0,
        _ => 1.0 / scene.units.factor(Dimension::Length),
    }
}

/// Header (`name [unit]`) and values of the SVAJ table, in the scene's units: per row the
/// cam angle as printed (a boundary's side marked `−` or `+`) and its numbers.
pub fn table_cells(scene: &CamScene, rows: &[SvajRow]) -> (Vec<String>, Vec<(String, Vec<f64>)>) {
    let (names, dimension) = column_units(scene);
    let u = &scene.units;
    let angle = u.symbol(Dimension::Angle);
    let length = u.symbol(Dimension::Length);
    let mut header = vec![
        format!("θ [{angle}]"),
        format!("s [{}]", names[0]),
        format!("s′ [{}]", names[1]),
        format!("s″ [{}]", names[2]),
        format!("s‴ [{}]", names[3]),
    ];
    let moving = rows.first().is_some_and(|r| r.motion.is_some());
    if moving {
        header.extend([
            format!("v [{}]", names[4]),
            format!("a [{}]", names[5]),
            format!("j [{}]", names[6]),
        ]);
    }
    header.extend([
        format!("pressure angle [{angle}]"),
        format!("ρ profile [{length}]"),
    ]);
    let k = derivative_factor(scene, dimension);
    let values = rows
        .iter()
        .map(|r| {
            let mark = match r.side {
                Some(Side::Left) => "−",
                Some(Side::Right) => "+",
                None => "",
            };
            let theta = format!("{}{mark}", Units::tidy(r.shown_theta));
            let mut cells = vec![
                u.from_si(r.svaj[0], dimension),
                r.svaj[1] * k,
                r.svaj[2] * k,
                r.svaj[3] * k,
            ];
            if let Some(m) = r.motion {
                cells.extend(m.iter().map(|v| v * k));
            }
            cells.push(u.from_si(r.pressure_angle, Dimension::Angle));
            cells.push(u.from_si(r.profile_radius, Dimension::Length));
            (theta, cells)
        })
        .collect();
    (header, values)
}

/// Decimals that give about 8 significant digits to the largest finite value of a column.
fn decimals(values: impl Iterator<Item = f64>) -> usize {
    let largest = values
        .filter(|v| v.is_finite())
        .fold(0.0f64, |m, v| m.max(v.abs()));
    if largest == 0.0 {
        return 1;
    }
    (7 - largest.log10().floor() as i64).clamp(0, 12) as usize
}

/// A number of the table; an infinite radius of curvature (κ = 0) is a straight profile.
/// (The scene refuses programs with non-finite values before anything is printed.)
fn number(value: f64, decimals: usize) -> String {
    if value.is_nan() {
        "NaN".to_owned()
    } else if value.is_finite() && value.abs() < 1e12 {
        fixed(value, decimals)
    } else {
        "straight".to_owned()
    }
}

/// Writes the whole report.
pub fn write_report(scene: &CamScene, out: &mut impl Write) -> io::Result<()> {
    let cam = &scene.mechanism;
    let u = &scene.units;
    let (angle, length) = (u.symbol(Dimension::Angle), u.symbol(Dimension::Length));
    let deg = |rad: f64| Units::tidy(u.from_si(rad, Dimension::Angle));
    let len = |m: f64| format!("{} {length}", fixed(u.from_si(m, Dimension::Length), 4));
    if let Some(title) = &scene.title {
        writeln!(out, "{title}")?;
    }
    let report = ContinuityReport::new(&cam.program);
    let analysis = cam.analyse();
    let rows = svaj_rows(scene, &report);
    writeln!(
        out,
        "plan: cam program of {} segment(s) over 360°; s, s′, s″, s‴ by dual numbers (Dual3) \
         at {} cam angles; profile normals and curvature by nested dual numbers",
        cam.program.len(),
        rows.len()
    )?;
    let follower = cam.dimensions.follower;
    let dims = match follower {
        Follower::KnifeEdge { offset } => format!("offset {}", len(offset)),
        Follower::Roller { offset, radius } => {
            format!("offset {}, roller radius {}", len(offset), len(radius))
        }
        Follower::FlatFaced => "face perpendicular to its axis".to_owned(),
        Follower::OscillatingRoller {
            pivot_distance,
            arm_length,
            radius,
        } => format!(
            "pivot at {}, arm {}, roller radius {}, arm angle at rest {} {angle}",
            len(pivot_distance),
            len(arm_length),
            len(radius),
            deg(cam.dimensions.rest)
        ),
    };
    let motion = if scene.drive.omega == 0.0 && scene.drive.alpha == 0.0 {
        "no cam speed given: s and its derivatives per radian of cam angle only".to_owned()
    } else {
        format!(
            "cam speed {} {}, acceleration {} {}",
            Units::tidy(u.from_si(scene.drive.omega, Dimension::AngularVelocity)),
            u.symbol(Dimension::AngularVelocity),
            Units::tidy(u.from_si(scene.drive.alpha, Dimension::AngularAcceleration)),
            u.symbol(Dimension::AngularAcceleration),
        )
    };
    writeln!(
        out,
        "cam: base circle radius {}; follower: {} ({dims}); {motion}",
        len(cam.dimensions.base_radius),
        follower.describe(),
    )?;
    writeln!(out, "\nsegments:")?;
    let lift_dimension = scene.displacement_dimension();
    for (i, segment) in cam.program.segments().enumerate() {
        let what = match &segment.motion {
            mechdiff_core::cams::SegmentMotion::Law { law, lift } if *lift != 0.0 => {
                let kind = if *lift > 0.0 { "rise" } else { "return" };
                format!(
                    "{law} {kind} {} {}",
                    Units::tidy(u.from_si(lift.abs(), lift_dimension)),
                    u.symbol(lift_dimension)
                )
            }
            _ => segment.describe(),
        };
        writeln!(
            out,
            "  {:>2}  {:>8} – {:<8} {angle}  {what}",
            i + 1,
            deg(cam.program.start(i)),
            deg(cam.program.end(i)),
        )?;
    }
    writeln!(out, "\nSVAJ (− and +: the one-sided values at a jump):")?;
    let (header, values) = table_cells(scene, &rows);
    let columns = header.len() - 1;
    let places: Vec<usize> = (0..columns)
        .map(|c| decimals(values.iter().map(|(_, v)| v[c])))
        .collect();
    let mut table = Table::new(0, header);
    for (theta, cells) in &values {
        let mut row = vec![theta.clone()];
        row.extend(cells.iter().zip(&places).map(|(v, &d)| number(*v, d)));
        table.row(row);
    }
    write!(out, "{}", table.render())?;
    writeln!(out, "\nboundaries:")?;
    write_boundaries(scene, &report, out)?;
    write_geometry(scene, &analysis, out)
}

fn write_boundaries(
    scene: &CamScene,
    report: &ContinuityReport,
    out: &mut impl Write,
) -> io::Result<()> {
    const NAMES: [&str; 4] = ["s", "s′", "s″", "s‴"];
    const MEANING: [&str; 4] = [
        "the displacement itself jumps",
        "infinite acceleration (an impulse: the follower is struck)",
        "infinite jerk",
        "a finite jump of jerk",
    ];
    let (names, dimension) = column_units(scene);
    let u = &scene.units;
    let k = derivative_factor(scene, dimension);
    let angle = u.symbol(Dimension::Angle);
    for b in &report.boundaries {
        let place = match b.kind {
            BoundaryKind::Segments { before, after } => {
                format!("segments {} → {}", before + 1, after + 1)
            }
            BoundaryKind::InsideSegment { segment } => format!("inside segment {}", segment + 1),
        };
        let at = Units::tidy(u.from_si(b.angle, Dimension::Angle));
        let at = if b.angle == 0.0 {
            format!("{at} (= 360)")
        } else {
            at
        };
        match b.first_jump() {
            None => writeln!(out, "  θ = {at} {angle}, {place}: s, s′, s″, s‴ continuous")?,
            Some(order) => {
                let scale = |v: f64| {
                    if order == 0 {
                        u.from_si(v, dimension)
                    } else {
                        v * k
                    }
                };
                writeln!(
                    out,
                    "  θ = {at} {angle}, {place}: {} jumps from {} to {} {}: {}",
                    NAMES[order],
                    Units::tidy(scale(b.left[order])),
                    Units::tidy(scale(b.right[order])),
                    names[order],
                    MEANING[order]
                )?;
            }
        }
    }
    if report.satisfies_fundamental_law() {
        writeln!(
            out,
            "  fundamental law of cam design: met (s, s′, s″ continuous)"
        )
    } else {
        writeln!(
            out,
            "  fundamental law of cam design: NOT met (s, s′ or s″ jumps above)"
        )
    }
}

fn write_geometry(
    scene: &CamScene,
    analysis: &CamAnalysis,
    out: &mut impl Write,
) -> io::Result<()> {
    let u = &scene.units;
    let (angle, length) = (u.symbol(Dimension::Angle), u.symbol(Dimension::Length));
    let deg = |rad: f64| fixed(u.from_si(rad, Dimension::Angle), 3);
    let len = |m: f64| format!("{} {length}", fixed(u.from_si(m, Dimension::Length), 4));
    writeln!(out)?;
    let p = analysis.max_pressure_angle;
    writeln!(
        out,
        "maximum pressure angle: {} {angle} at θ = {} {angle}",
        fixed(u.from_si(p.value, Dimension::Angle), 4),
        deg(p.angle)
    )?;
    if let Some(pitch) = analysis.min_pitch_radius {
        writeln!(
            out,
            "minimum radius of curvature of the pitch curve (convex): {} at θ = {} {angle}",
            len(pitch.value),
            deg(pitch.angle)
        )?;
    }
    for warning in scene.warnings(analysis) {
        writeln!(out, "WARNING: {warning}")?;
    }
    let profile = analysis.min_profile_radius;
    writeln!(
        out,
        "minimum radius of curvature of the profile: {} at θ = {} {angle}",
        len(profile.value),
        deg(profile.angle)
    )?;
    if analysis.undercut.is_empty() {
        writeln!(out, "undercutting: none")?;
    } else {
        let ranges: Vec<String> = analysis
            .undercut
            .iter()
            .map(|(a, b)| {
                format!(
                    "{}–{} {angle}",
                    fixed(u.from_si(*a, Dimension::Angle), 3),
                    fixed(u.from_si(*b, Dimension::Angle), 3)
                )
            })
            .collect();
        let (what, remedy) = if scene.mechanism.dimensions.follower == Follower::FlatFaced {
            (
                "the profile has a cusp (radius of curvature ≤ 0)",
                "enlarge the base circle (`min_radius_of_curvature` sizes it) or soften the \
                 program's s″ there",
            )
        } else {
            (
                "the roller is larger than the pitch curve's radius of curvature",
                "enlarge the base circle or use a smaller roller",
            )
        };
        let place = scene
            .roller_at
            .as_ref()
            .map(|l| format!(" (roller radius at {l})"))
            .unwrap_or_default();
        writeln!(
            out,
            "WARNING: undercutting at cam angles {}: {what}{place}; the follower would not \
             follow the program there: {remedy}",
            ranges.join(", ")
        )?;
    }
    if let Some((low, high)) = analysis.face_extent {
        writeln!(
            out,
            "flat face: the contact moves from {} to {} off the axis; minimum face width {}",
            len(low),
            len(high),
            len(high - low)
        )?;
    }
    if let Some((base, what)) = &scene.sizing {
        writeln!(
            out,
            "smallest base circle radius for a {what}: {}",
            len(*base)
        )?;
    }
    Ok(())
}

/// Writes the SVAJ table as CSV (header `name [unit]`, one-sided rows marked in `side`).
pub fn write_svaj_csv(scene: &CamScene, out: &mut impl Write) -> io::Result<()> {
    let report = ContinuityReport::new(&scene.mechanism.program);
    let rows = svaj_rows(scene, &report);
    let (header, values) = table_cells(scene, &rows);
    let mut header = header;
    header.insert(1, "side".to_owned());
    out.write_all(crate::stream::record::csv_record(header).as_bytes())?;
    for ((_, cells), row) in values.iter().zip(&rows) {
        let side = match row.side {
            Some(Side::Left) => "left",
            Some(Side::Right) => "right",
            None => "",
        };
        let theta = row.shown_theta;
        let numbers: Vec<String> = cells.iter().map(|v| format!("{v:e}")).collect();
        writeln!(out, "{theta:e},{side},{}", numbers.join(","))?;
    }
    Ok(())
}

/// Writes the profile as CSV for CAD/CNC: cam angle, pitch point, profile point and outward
/// normal in the cam's frame (the cam's centre at the origin), every 0.5°.
pub fn write_profile_csv(scene: &CamScene, out: &mut impl Write) -> io::Result<()> {
    let u = &scene.units;
    let (angle, length) = (u.symbol(Dimension::Angle), u.symbol(Dimension::Length));
    writeln!(
        out,
        "θ [{angle}],pitch x [{length}],pitch y [{length}],profile x [{length}],profile y \
         [{length}],normal x,normal y"
    )?;
    for k in 0..PROFILE_POINTS {
        let theta = TAU * k as f64 / PROFILE_POINTS as f64;
        let c = scene.mechanism.contact(theta, Side::Right);
        let l = |v: f64| u.from_si(v, Dimension::Length);
        writeln!(
            out,
            "{:e},{:e},{:e},{:e},{:e},{:e},{:e}",
            u.from_si(theta, Dimension::Angle),
            l(c.pitch[0]),
            l(c.pitch[1]),
            l(c.profile[0]),
            l(c.profile[1]),
            c.normal[0],
            c.normal[1]
        )?;
    }
    Ok(())
}

/// Writes the cam's summary as JSON (`--json`), every number in the file's units (named in
/// `units`): the follower and base circle, the maximum pressure angle, the smallest radii of
/// curvature (signed: negative at a cusp or undercut), the undercut ranges, a flat face's
/// contact extent and width, the base-circle sizing asked for, the boundaries' continuity
/// and the warnings.
pub fn write_json(scene: &CamScene, out: &mut impl Write) -> io::Result<()> {
    use serde_json::{Value, json};
    let cam = &scene.mechanism;
    let u = &scene.units;
    // Rounded to 15 significant digits, as printed: 120, not 119.99999999999999.
    let tidy = |v: f64| Units::tidy(v).parse::<f64>().unwrap_or(v);
    let angle = |rad: f64| tidy(u.from_si(rad, Dimension::Angle));
    let length = |m: f64| tidy(u.from_si(m, Dimension::Length));
    let report = ContinuityReport::new(&cam.program);
    let analysis = cam.analyse();
    let extreme = |e: mechdiff_core::cams::Extreme, value: &dyn Fn(f64) -> f64| json!({ "value": value(e.value), "cam_angle": angle(e.angle) });
    let boundaries: Vec<Value> = report
        .boundaries
        .iter()
        .map(|b| {
            json!({
                "cam_angle": angle(b.angle),
                "first_jump": b.first_jump().map(|order| ["s", "s'", "s''", "s'''"][order]),
            })
        })
        .collect();
    let json = json!({
        "file": scene.file,
        "title": scene.title,
        "units": {
            "length": u.symbol(Dimension::Length),
            "angle": u.symbol(Dimension::Angle),
            "displacement": u.symbol(scene.displacement_dimension()),
        },
        "follower": cam.dimensions.follower.describe(),
        "base_radius": length(cam.dimensions.base_radius),
        "segments": cam.program.len(),
        "max_pressure_angle": extreme(analysis.max_pressure_angle, &angle),
        "min_pitch_radius": analysis.min_pitch_radius.map(|e| extreme(e, &length)),
        "min_profile_radius": extreme(analysis.min_profile_radius, &length),
        "undercut": analysis
            .undercut
            .iter()
            .map(|(a, b)| json!({ "from": angle(*a), "to": angle(*b) }))
            .collect::<Vec<_>>(),
        "face": analysis.face_extent.map(|(low, high)| json!({
            "contact_from": length(low),
            "contact_to": length(high),
            "min_width": length(high - low),
        })),
        "sizing": scene.sizing.as_ref().map(|(base, what)| json!({
            "min_base_radius": length(*base),
            "for": what,
        })),
        "boundaries": boundaries,
        "fundamental_law_met": report.satisfies_fundamental_law(),
        "warnings": scene.warnings(&analysis),
    });
    serde_json::to_writer_pretty(&mut *out, &json)?;
    writeln!(out)
}
