//! Cam scenes: a `[cam]` section (segments, follower, base circle, speed) read into the cams
//! room of mechdiff-core ([`mechdiff_core::cams`]).
//!
//! This module only translates the file: units applied, fields checked for presence, and
//! every error of the engine pointed at the place in the file it concerns (`file:line:col`
//! of the segment or dimension, with the cam angle in the message).

use serde::Deserialize;
use toml::Spanned;

use mechdiff_core::DriveState;
use mechdiff_core::cams::continuity::derivative_peaks;
use mechdiff_core::cams::{
    CamMechanism, CamProgram, Follower, Formula, MotionLaw, Segment, sizing,
};

use super::bindings::Bindings;
use super::source::Source;
use super::units::{Dimension, Units, UnitsSection};
use super::values::Number;
use crate::error::{Error, Result};

/// The most rows of the SVAJ table over one turn (a `step` of 0.0036° at the least): the
/// table, its CSV and the accuracy run are bounded before anything is computed.
pub const MAX_TABLE_ROWS: usize = 100_000;

/// A cam scene file as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CamFile {
    /// A one-line title.
    pub title: Option<String>,
    /// Units of every number in the file.
    #[serde(default)]
    pub units: UnitsSection,
    /// The cam.
    pub cam: Spanned<CamSection>,
}

/// `[cam]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CamSection {
    /// Base circle radius (length unit).
    pub base_radius: Spanned<Number>,
    /// Cam speed (angular velocity unit; default 0: only s, s′, s″, s‴ are printed).
    #[serde(default)]
    pub speed: Option<Spanned<Number>>,
    /// Cam acceleration (angular acceleration unit; default 0).
    #[serde(default)]
    pub acceleration: Option<Spanned<Number>>,
    /// Table step (angle unit; default 10°).
    #[serde(default)]
    pub step: Option<Spanned<Number>>,
    /// Follower displacement at cam angle 0 (default 0).
    #[serde(default)]
    pub start: Option<Spanned<Number>>,
    /// Size the base circle for this largest pressure angle (angle unit; roller and
    /// knife-edge followers).
    #[serde(default)]
    pub pressure_angle_limit: Option<Spanned<Number>>,
    /// Size the base circle for this smallest radius of curvature (length unit; flat face).
    #[serde(default)]
    pub min_radius_of_curvature: Option<Spanned<Number>>,
    /// The follower.
    pub follower: Spanned<FollowerDef>,
    /// The segments, in order from cam angle 0.
    #[serde(rename = "segment")]
    pub segments: Spanned<Vec<Spanned<SegmentDef>>>,
}

/// The follower types a scene can name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FollowerKind {
    /// Translating knife-edge.
    KnifeEdge,
    /// Translating roller.
    Roller,
    /// Translating flat face.
    FlatFaced,
    /// Oscillating arm with a roller.
    OscillatingRoller,
}

impl FollowerKind {
    /// The name in scene files.
    pub fn name(self) -> &'static str {
        match self {
            FollowerKind::KnifeEdge => "knife_edge",
            FollowerKind::Roller => "roller",
            FollowerKind::FlatFaced => "flat_faced",
            FollowerKind::OscillatingRoller => "oscillating_roller",
        }
    }
}

/// `[cam.follower]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FollowerDef {
    /// The follower type.
    #[serde(rename = "type")]
    pub kind: Spanned<FollowerKind>,
    /// Offset of a translating follower's axis (length unit; default 0).
    #[serde(default)]
    pub offset: Option<Spanned<Number>>,
    /// Roller radius (length unit).
    #[serde(default)]
    pub radius: Option<Spanned<Number>>,
    /// Oscillating: cam centre to pivot (length unit).
    #[serde(default)]
    pub pivot_distance: Option<Spanned<Number>>,
    /// Oscillating: pivot to roller centre (length unit).
    #[serde(default)]
    pub arm_length: Option<Spanned<Number>>,
}

/// One `[[cam.segment]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SegmentDef {
    /// A standard law (`"cycloidal"`, …); exactly one of `law` and `formula`.
    pub law: Option<Spanned<String>>,
    /// A displacement formula of `x` (cam angle, rad) or `u` (0 to 1 over the segment).
    pub formula: Option<Spanned<String>>,
    /// Rise over the segment (length unit; angle unit for an oscillating follower).
    #[serde(default)]
    pub rise: Option<Spanned<Number>>,
    /// Return (fall) over the segment, positive.
    #[serde(rename = "return")]
    #[serde(default)]
    pub fall: Option<Spanned<Number>>,
    /// The cam angle the segment spans (angle unit).
    pub extent: Spanned<Number>,
}

/// A checked cam scene.
#[derive(Debug, Clone)]
pub struct CamScene {
    /// The file's name.
    pub file: String,
    /// The title.
    pub title: Option<String>,
    /// Units of the file and of the printed results.
    pub units: Units,
    /// The cam with its follower (SI).
    pub mechanism: CamMechanism,
    /// The cam's motion (SI).
    pub drive: DriveState,
    /// Table step (rad).
    pub step: f64,
    /// Base-circle sizing asked for: the smallest base radius (SI) and what it is for.
    pub sizing: Option<(f64, String)>,
    /// Where the follower's roller radius is written (for the undercut warning).
    pub roller_at: Option<crate::error::Location>,
    /// Table step in the file's angle unit, as written (the printed cam angles are its
    /// whole multiples).
    pub table_step: f64,
    /// The stated largest pressure angle (rad) and where it is written.
    pub pressure_angle_limit: Option<(f64, crate::error::Location)>,
}

impl CamScene {
    /// The cam angles of the SVAJ table, from 0 to one turn every `step`, each as (angle in
    /// rad, angle as printed in the file's unit). The printed angle is k·step in the file's
    /// unit, so a whole-numbered step prints whole numbers (300, never 299.99999999999994);
    /// a row within 1e-9 rad of a segment boundary is evaluated exactly at the boundary.
    pub fn table_angles(&self) -> Vec<(f64, f64)> {
        let program = &self.mechanism.program;
        let boundaries: Vec<f64> = (0..program.len())
            .map(|i| program.start(i))
            .chain([std::f64::consts::TAU])
            .collect();
        let turn = self.units.from_si(std::f64::consts::TAU, Dimension::Angle);
        let count = (std::f64::consts::TAU / self.step + 1e-9).floor() as usize;
        (0..=count)
            .map(|k| {
                let shown = (k as f64 * self.table_step).min(turn);
                let theta = self.units.to_si(shown, Dimension::Angle);
                match boundaries.iter().find(|b| (theta - **b).abs() <= 1e-9) {
                    Some(&b) => (b, shown),
                    None => (theta.min(std::f64::consts::TAU), shown),
                }
            })
            .collect()
    }

    /// The warnings of the analysis that the file asked to be kept: a pressure angle above
    /// `pressure_angle_limit`, with the angle and the cam angle where it is largest (in the
    /// file's angle unit).
    pub fn warnings(&self, analysis: &mechdiff_core::cams::CamAnalysis) -> Vec<String> {
        let mut warnings = Vec::new();
        let p = analysis.max_pressure_angle;
        if let Some((limit, at)) = &self.pressure_angle_limit
            && p.value > *limit
        {
            // As the report prints the maximum pressure angle (4 decimals) and its cam angle.
            let angle = |v: f64| format!("{:.4}", self.units.from_si(v, Dimension::Angle));
            let unit = self.units.symbol(Dimension::Angle);
            let base = self
                .sizing
                .as_ref()
                .map(|(base, _)| {
                    format!(
                        "; a base circle radius of at least {:.4} {} keeps it",
                        self.units.from_si(*base, Dimension::Length),
                        self.units.symbol(Dimension::Length)
                    )
                })
                .unwrap_or_default();
            warnings.push(format!(
                "the pressure angle reaches {} {unit} at cam angle θ = {} {unit}, above the \
                 stated limit of {} {unit} (`pressure_angle_limit` at {at}){base}",
                angle(p.value),
                angle(p.angle),
                angle(*limit)
            ));
        }
        warnings
    }

    /// The dimension of the follower's displacement: a length, or an angle (oscillating).
    pub fn displacement_dimension(&self) -> Dimension {
        match self.mechanism.dimensions.follower {
            Follower::OscillatingRoller { .. } => Dimension::Angle,
            _ => Dimension::Length,
        }
    }
}

/// Parses and checks a cam scene given as text; `file` names it in messages.
pub fn parse(file: &str, text: &str) -> Result<CamScene> {
    let source = Source::new(file, text);
    let raw: CamFile = toml::from_str(text).map_err(|e| source.syntax_error(&e))?;
    resolve(raw, &source)
}

/// Parses and checks a cam scene that another scene names (`[drive] cam`): the file was not
/// named by the user, so an error never quotes its content unless it is a cam scene (a TOML
/// document with a `[cam]` table). A file that is not TOML gets the place where the TOML
/// parser stopped and a fixed reason, one without a `[cam]` table just that.
pub(crate) fn parse_named(file: &str, text: &str) -> Result<CamScene> {
    let source = Source::new(file, text);
    let not_a_cam = |span: std::ops::Range<usize>, what: &str| Error::Syntax {
        location: source.location(span),
        message: format!(
            "{what}; a cam scene is a TOML file with a `[cam]` table (see docs/scene-format.md); \
             the file's text is not shown"
        ),
    };
    match text.parse::<toml::Table>() {
        Err(e) => Err(not_a_cam(
            e.span().unwrap_or(0..0),
            "not a TOML file: the TOML parser stopped here",
        )),
        Ok(table) if !table.get("cam").is_some_and(toml::Value::is_table) => Err(not_a_cam(
            0..0,
            "not a cam scene: the file has no `[cam]` table",
        )),
        Ok(_) => parse(file, text),
    }
}

/// Reads and checks a cam scene file.
pub fn load(path: &std::path::Path) -> Result<CamScene> {
    let text = crate::files::read_scene(path)?;
    parse(&path.display().to_string(), &text)
}

/// The value of a number of a cam scene as written: a literal, or a constant formula (a cam
/// scene has no `[parameters]`), its error at its place.
fn constant(v: &Spanned<Number>, source: &Source) -> Result<f64> {
    (v.get_ref().value_in(&Bindings::default()))
        .map_err(|message| source.formula_error(v.span(), &message))
}

fn resolve(file: CamFile, source: &Source) -> Result<CamScene> {
    let units = Units::declared(&file.units);
    let cam = file.cam.get_ref();
    let at = |span: std::ops::Range<usize>| source.location(span);
    let invalid = |span: std::ops::Range<usize>, message: String| Error::Invalid {
        location: at(span),
        message,
    };
    let value = |v: &Spanned<Number>, dimension: Dimension, what: &str| -> Result<f64> {
        let si = units.to_si(constant(v, source)?, dimension);
        if si.is_finite() {
            Ok(si)
        } else {
            Err(invalid(v.span(), format!("{what} must be a finite number")))
        }
    };
    let follower_def = cam.follower.get_ref();
    let oscillating = *follower_def.kind.get_ref() == FollowerKind::OscillatingRoller;
    let lift_dimension = if oscillating {
        Dimension::Angle
    } else {
        Dimension::Length
    };
    let segments = cam
        .segments
        .get_ref()
        .iter()
        .map(|def| segment(def, &units, lift_dimension, source))
        .collect::<Result<Vec<_>>>()?;
    let start = match &cam.start {
        Some(v) => value(v, lift_dimension, "start")?,
        None => 0.0,
    };
    let program = CamProgram::new(segments, start).map_err(|e| {
        let span = match &e {
            mechdiff_core::Error::CamSegment { segment, .. } => {
                cam.segments.get_ref()[segment - 1].span()
            }
            mechdiff_core::Error::CamJoin { after, .. } => cam.segments.get_ref()[after - 1].span(),
            _ => cam.segments.span(),
        };
        invalid(span, engine_message(&e, &units, lift_dimension, None))
    })?;
    let follower = follower(follower_def, &units, source)?;
    let base_radius = value(&cam.base_radius, Dimension::Length, "base_radius")?;
    let mechanism = CamMechanism::new(program, base_radius, follower).map_err(|e| {
        let span = match &e {
            mechdiff_core::Error::CamDimension { what, .. } => match what.as_str() {
                "offset" => follower_def.offset.as_ref().map(Spanned::span),
                "roller radius" => follower_def.radius.as_ref().map(Spanned::span),
                "arm length" => follower_def.arm_length.as_ref().map(Spanned::span),
                "pivot distance" => follower_def.pivot_distance.as_ref().map(Spanned::span),
                "base radius" => Some(cam.base_radius.span()),
                _ => None,
            },
            _ => None,
        };
        invalid(
            span.unwrap_or_else(|| cam.follower.span()),
            engine_message(&e, &units, lift_dimension, Some((base_radius, follower))),
        )
    })?;
    let speed = match &cam.speed {
        Some(v) => value(v, Dimension::AngularVelocity, "speed")?,
        None => 0.0,
    };
    let acceleration = match &cam.acceleration {
        Some(v) => value(v, Dimension::AngularAcceleration, "acceleration")?,
        None => 0.0,
    };
    let table_step = match &cam.step {
        Some(v) => constant(v, source)?,
        None => units.from_si(10f64.to_radians(), Dimension::Angle),
    };
    let step = match &cam.step {
        Some(v) => {
            let step = value(v, Dimension::Angle, "step")?;
            if !(step > 0.0 && step <= std::f64::consts::TAU) {
                return Err(invalid(
                    v.span(),
                    "step must be a positive angle of at most one turn".to_owned(),
                ));
            }
            // Bounded before any row is computed: at most MAX_TABLE_ROWS rows a turn (the
            // smallest step, as printed, is accepted whatever its rounding to radians).
            if std::f64::consts::TAU / step > MAX_TABLE_ROWS as f64 * (1.0 + 1e-9) {
                let smallest = units.from_si(
                    std::f64::consts::TAU / MAX_TABLE_ROWS as f64,
                    Dimension::Angle,
                );
                return Err(invalid(
                    v.span(),
                    format!(
                        "step = {} {unit} gives more than {MAX_TABLE_ROWS} rows a turn; the \
                         smallest step is {} {unit}",
                        Units::tidy(constant(v, source)?),
                        Units::tidy(smallest),
                        unit = units.symbol(Dimension::Angle),
                    ),
                ));
            }
            step
        }
        None => 10f64.to_radians(),
    };
    let drive = DriveState::accelerating(speed, acceleration);
    check_finite_results(cam, &mechanism, &drive, source)?;
    let sizing = sizing_request(cam, &mechanism, &units, source)?;
    Ok(CamScene {
        file: source.file.clone(),
        title: file.title,
        units,
        mechanism,
        drive,
        step,
        sizing,
        roller_at: follower_def.radius.as_ref().map(|r| at(r.span())),
        table_step,
        pressure_angle_limit: match &cam.pressure_angle_limit {
            Some(l) => Some((
                units.to_si(constant(l, source)?, Dimension::Angle),
                at(l.span()),
            )),
            None => None,
        },
    })
}

/// No printed result may overflow: the peaks of s′, s″, s‴, of the follower's velocity,
/// acceleration and jerk, and the cam's geometry are checked once, and an overflow is
/// reported at the number that causes it.
fn check_finite_results(
    cam: &CamSection,
    mechanism: &CamMechanism,
    drive: &DriveState,
    source: &Source,
) -> Result<()> {
    let overflow = |span: std::ops::Range<usize>, what: &str| Error::Invalid {
        location: source.location(span),
        message: format!("{what} overflows (is not a finite number); reduce this value"),
    };
    let [_, v, a, j] = derivative_peaks(&mechanism.program);
    if ![v, a, j].iter().all(|x| x.is_finite()) {
        return Err(Error::Invalid {
            location: source.location(cam.segments.span()),
            message: "the displacement or one of its derivatives is not a finite number \
                      somewhere in the turn (a formula outside its domain, or too large a \
                      lift); check the formulas and lifts of the segments"
                .to_owned(),
        });
    }
    let (w, al) = (drive.omega.abs(), drive.alpha.abs());
    let motion = [w * v, al * v + w * w * a, 3.0 * w * al * a + w * w * w * j];
    if !motion.iter().all(|x| x.is_finite()) {
        let span = cam
            .speed
            .as_ref()
            .or(cam.acceleration.as_ref())
            .map_or_else(|| cam.segments.span(), Spanned::span);
        return Err(overflow(
            span,
            "the follower's velocity, acceleration or jerk",
        ));
    }
    let analysis = mechanism.analyse();
    if !(analysis.max_pressure_angle.value.is_finite()
        && analysis.min_profile_radius.value.is_finite())
    {
        return Err(overflow(cam.base_radius.span(), "the cam's geometry"));
    }
    Ok(())
}

/// The engine's message with every number in the file's units: lengths in its length unit,
/// angles (cam angles, the pressure angle limit) in its angle unit, the displacement in the
/// follower's unit (length, or angle for an oscillating arm); with the dimensions the rule
/// compares, when the follower is known (`dimensions`: base radius and follower, SI).
fn engine_message(
    error: &mechdiff_core::Error,
    units: &Units,
    lift_dimension: Dimension,
    dimensions: Option<(f64, Follower)>,
) -> String {
    let shown = |v: f64, dimension: Dimension| {
        format!(
            "{} {}",
            Units::tidy(units.from_si(v, dimension)),
            units.symbol(dimension)
        )
    };
    let cam_angle = |deg: f64| shown(deg.to_radians(), Dimension::Angle);
    match error {
        mechdiff_core::Error::CamDimension {
            what,
            value,
            problem,
        } => {
            let value = match what.as_str() {
                // Not a number: the follower type is what is wrong.
                "follower" => return problem.clone(),
                "pressure angle limit" => {
                    return format!(
                        "{what} = {}: must be between 0 and {} (90°)",
                        cam_angle(*value),
                        cam_angle(90.0)
                    );
                }
                "smallest displacement" => shown(*value, lift_dimension),
                _ => shown(*value, Dimension::Length),
            };
            let compared = dimensions.and_then(|(base, follower)| {
                let prime = base + follower.roller_radius();
                let length = |v: f64| shown(v, Dimension::Length);
                match (what.as_str(), follower) {
                    ("offset", _) => Some(format!(
                        "prime circle radius {} = base {} + roller {}",
                        length(prime),
                        length(base),
                        length(follower.roller_radius())
                    )),
                    ("arm length", Follower::OscillatingRoller { pivot_distance, .. }) => Some(
                        format!("R_p = {}, a = {}", length(prime), length(pivot_distance)),
                    ),
                    (
                        "smallest displacement",
                        Follower::KnifeEdge { offset } | Follower::Roller { offset, .. },
                    ) => Some(format!(
                        "the follower's height at s = 0 is {}",
                        length((prime * prime - offset * offset).sqrt())
                    )),
                    _ => None,
                }
            });
            match compared {
                Some(c) => format!("{what} = {value}: {problem} ({c})"),
                None => format!("{what} = {value}: {problem}"),
            }
        }
        mechdiff_core::Error::CamJoin {
            angle_deg,
            before,
            after,
            left,
            right,
        } => format!(
            "the follower displacement does not join at cam angle {} between segment {before} \
             (ends at {}) and segment {after} (starts at {})",
            cam_angle(*angle_deg),
            shown(*left, lift_dimension),
            shown(*right, lift_dimension)
        ),
        mechdiff_core::Error::CamSegment {
            segment,
            start_deg,
            problem,
        } => format!(
            "cam segment {segment} (starting at cam angle {}): {problem}",
            cam_angle(*start_deg)
        ),
        other => other.to_string(),
    }
}

fn segment(
    def: &Spanned<SegmentDef>,
    units: &Units,
    lift_dimension: Dimension,
    source: &Source,
) -> Result<Segment> {
    let d = def.get_ref();
    let invalid = |span: std::ops::Range<usize>, message: &str| Error::Invalid {
        location: source.location(span),
        message: message.to_owned(),
    };
    let finite = |v: &Spanned<Number>, dimension: Dimension| -> Result<f64> {
        let x = constant(v, source)?;
        let si = units.to_si(x, dimension);
        if si.is_finite() {
            Ok(si)
        } else {
            Err(invalid(v.span(), &format!("{x} is not a finite number")))
        }
    };
    let extent = finite(&d.extent, Dimension::Angle)?;
    if !(extent.is_finite() && extent > 0.0) {
        return Err(invalid(
            d.extent.span(),
            &format!(
                "extent must be a positive angle, found {} {}",
                constant(&d.extent, source)?,
                units.symbol(Dimension::Angle)
            ),
        ));
    }
    let lift = match (&d.rise, &d.fall) {
        (Some(_), Some(f)) => {
            return Err(invalid(
                f.span(),
                "a segment has a `rise` or a `return`, not both",
            ));
        }
        (Some(r), None) => finite(r, lift_dimension)?,
        (None, Some(f)) => -finite(f, lift_dimension)?,
        (None, None) => 0.0,
    };
    match (&d.law, &d.formula) {
        (Some(law), None) => {
            let Some(parsed) = MotionLaw::from_name(law.get_ref()) else {
                let known: Vec<&str> = MotionLaw::ALL.iter().map(|l| l.name()).collect();
                return Err(invalid(
                    law.span(),
                    &format!(
                        "unknown law `{}`; expected one of: {}",
                        law.get_ref(),
                        known.join(", ")
                    ),
                ));
            };
            if parsed != MotionLaw::Dwell && d.rise.is_none() && d.fall.is_none() {
                return Err(invalid(
                    def.span(),
                    &format!("a `{parsed}` segment needs `rise = …` or `return = …`"),
                ));
            }
            if parsed == MotionLaw::Dwell
                && let Some(given) = d.rise.as_ref().or(d.fall.as_ref())
            {
                return Err(invalid(
                    given.span(),
                    "a dwell has no lift; remove `rise`/`return`, or use a rise or return law",
                ));
            }
            Ok(Segment::law(parsed, lift, extent))
        }
        (None, Some(text)) => {
            if d.rise.is_some() || d.fall.is_some() {
                return Err(invalid(
                    def.span(),
                    "a formula gives the displacement itself; remove `rise`/`return`",
                ));
            }
            // The formula is written in the file's unit of displacement.
            let formula = Formula::parse(text.get_ref())
                .map_err(|e| invalid(text.span(), &format!("in the formula: {e}")))?
                .scaled(units.factor(lift_dimension));
            Ok(Segment::formula(formula, extent))
        }
        _ => Err(invalid(
            def.span(),
            "a segment needs exactly one of `law = \"…\"` and `formula = \"…\"`",
        )),
    }
}

fn follower(def: &FollowerDef, units: &Units, source: &Source) -> Result<Follower> {
    let kind = *def.kind.get_ref();
    let finite = |v: &Spanned<Number>| -> Result<f64> {
        let x = constant(v, source)?;
        let si = units.to_si(x, Dimension::Length);
        if si.is_finite() {
            Ok(si)
        } else {
            Err(Error::Invalid {
                location: source.location(v.span()),
                message: format!("{x} is not a finite number"),
            })
        }
    };
    let length = |v: &Option<Spanned<Number>>, name: &str| -> Result<f64> {
        match v {
            Some(v) => finite(v),
            None => Err(Error::Invalid {
                location: source.location(def.kind.span()),
                message: format!("a `{}` follower needs `{name} = …`", kind.name()),
            }),
        }
    };
    // A key the follower type has no use for is refused, not ignored.
    let keys = [
        ("offset", &def.offset),
        ("radius", &def.radius),
        ("pivot_distance", &def.pivot_distance),
        ("arm_length", &def.arm_length),
    ];
    let applies: &[&str] = match kind {
        FollowerKind::KnifeEdge => &["offset"],
        FollowerKind::Roller => &["offset", "radius"],
        FollowerKind::FlatFaced => &[],
        FollowerKind::OscillatingRoller => &["radius", "pivot_distance", "arm_length"],
    };
    if let Some((key, Some(v))) = keys
        .iter()
        .find(|(key, v)| v.is_some() && !applies.contains(key))
    {
        let why = match (kind, *key) {
            (FollowerKind::FlatFaced, "offset") => {
                "a flat face's contact slides along the face, so an offset of its axis \
                 changes nothing"
            }
            (_, "radius") => "only a roller follower has a radius",
            (_, "offset") => "an oscillating arm is placed by `pivot_distance`",
            _ => "only an oscillating follower has a pivot and an arm",
        };
        let expected = if applies.is_empty() {
            "no dimension".to_owned()
        } else {
            applies
                .iter()
                .map(|k| format!("`{k}`"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        return Err(Error::Invalid {
            location: source.location(v.span()),
            message: format!(
                "`{key}` does not apply to a `{}` follower ({why}); it takes {expected}: \
                 remove `{key}` or change the follower's `type`",
                kind.name()
            ),
        });
    }
    let offset = match &def.offset {
        Some(v) => finite(v)?,
        None => 0.0,
    };
    Ok(match kind {
        FollowerKind::KnifeEdge => Follower::KnifeEdge { offset },
        FollowerKind::Roller => Follower::Roller {
            offset,
            radius: length(&def.radius, "radius")?,
        },
        FollowerKind::FlatFaced => Follower::FlatFaced,
        FollowerKind::OscillatingRoller => Follower::OscillatingRoller {
            pivot_distance: length(&def.pivot_distance, "pivot_distance")?,
            arm_length: length(&def.arm_length, "arm_length")?,
            radius: length(&def.radius, "radius")?,
        },
    })
}

/// The sizing the scene asks for, computed: (smallest base radius, what it keeps).
fn sizing_request(
    cam: &CamSection,
    mechanism: &CamMechanism,
    units: &Units,
    source: &Source,
) -> Result<Option<(f64, String)>> {
    let program = &mechanism.program;
    let follower = mechanism.dimensions.follower;
    let dimensions = Some((mechanism.dimensions.base_radius, follower));
    let fail = |span: std::ops::Range<usize>, e: mechdiff_core::Error| Error::Invalid {
        location: source.location(span),
        message: engine_message(&e, units, Dimension::Length, dimensions),
    };
    if let Some(limit) = &cam.pressure_angle_limit {
        if !matches!(
            follower,
            Follower::Roller { .. } | Follower::KnifeEdge { .. }
        ) {
            let instead = match follower {
                Follower::FlatFaced => {
                    "a flat face's pressure angle is 0 everywhere; size its base circle with \
                     `min_radius_of_curvature`"
                }
                _ => {
                    "give the base circle directly and read the maximum pressure angle in the report"
                }
            };
            return Err(Error::Invalid {
                location: source.location(limit.span()),
                message: format!(
                    "`pressure_angle_limit` sizes the base circle of a translating roller or \
                     knife-edge follower, not of a {} follower: {instead}",
                    follower.describe()
                ),
            });
        }
        let limit_value = constant(limit, source)?;
        let radians = units.to_si(limit_value, Dimension::Angle);
        let base = sizing::base_radius_for_pressure_angle(program, follower, radians)
            .map_err(|e| fail(limit.span(), e))?;
        let what = format!(
            "largest pressure angle {} {}",
            Units::tidy(limit_value),
            units.symbol(Dimension::Angle)
        );
        return Ok(Some((base, what)));
    }
    if let Some(radius) = &cam.min_radius_of_curvature {
        if follower != Follower::FlatFaced {
            return Err(Error::Invalid {
                location: source.location(radius.span()),
                message: "`min_radius_of_curvature` sizes a flat-faced follower's cam; for a \
                          roller use `pressure_angle_limit`"
                    .to_owned(),
            });
        }
        let radius_value = constant(radius, source)?;
        let si = units.to_si(radius_value, Dimension::Length);
        let base =
            sizing::base_radius_for_flat_face(program, si).map_err(|e| fail(radius.span(), e))?;
        let what = format!(
            "smallest radius of curvature {} {}",
            Units::tidy(radius_value),
            units.symbol(Dimension::Length)
        );
        return Ok(Some((base, what)));
    }
    Ok(None)
}
