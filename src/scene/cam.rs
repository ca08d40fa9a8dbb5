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

use super::format::UnitsSection;
use super::source::Source;
use super::units::{Dimension, Units};
use crate::error::{Error, Result};

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
    pub base_radius: Spanned<f64>,
    /// Cam speed (angular velocity unit; default 0: only s, s′, s″, s‴ are printed).
    pub speed: Option<Spanned<f64>>,
    /// Cam acceleration (angular acceleration unit; default 0).
    pub acceleration: Option<Spanned<f64>>,
    /// Table step (angle unit; default 10°).
    pub step: Option<Spanned<f64>>,
    /// Follower displacement at cam angle 0 (default 0).
    pub start: Option<Spanned<f64>>,
    /// Size the base circle for this largest pressure angle (angle unit; roller and
    /// knife-edge followers).
    pub pressure_angle_limit: Option<Spanned<f64>>,
    /// Size the base circle for this smallest radius of curvature (length unit; flat face).
    pub min_radius_of_curvature: Option<Spanned<f64>>,
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
    pub offset: Option<Spanned<f64>>,
    /// Roller radius (length unit).
    pub radius: Option<Spanned<f64>>,
    /// Oscillating: cam centre to pivot (length unit).
    pub pivot_distance: Option<Spanned<f64>>,
    /// Oscillating: pivot to roller centre (length unit).
    pub arm_length: Option<Spanned<f64>>,
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
    pub rise: Option<Spanned<f64>>,
    /// Return (fall) over the segment, positive.
    #[serde(rename = "return")]
    pub fall: Option<Spanned<f64>>,
    /// The cam angle the segment spans (angle unit).
    pub extent: Spanned<f64>,
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
}

impl CamScene {
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

/// Reads and checks a cam scene file.
pub fn load(path: &std::path::Path) -> Result<CamScene> {
    let text = crate::files::read_scene(path)?;
    parse(&path.display().to_string(), &text)
}

fn resolve(file: CamFile, source: &Source) -> Result<CamScene> {
    let units = super::resolve::units(&file.units);
    let cam = file.cam.get_ref();
    let at = |span: std::ops::Range<usize>| source.location(span);
    let invalid = |span: std::ops::Range<usize>, message: String| Error::Invalid {
        location: at(span),
        message,
    };
    let value = |v: &Spanned<f64>, dimension: Dimension, what: &str| -> Result<f64> {
        let si = units.to_si(*v.get_ref(), dimension);
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
        invalid(span, engine_message(&e, &units, lift_dimension))
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
            engine_message(&e, &units, lift_dimension),
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
    let step = match &cam.step {
        Some(v) => {
            let step = value(v, Dimension::Angle, "step")?;
            if !(step > 0.0 && step <= std::f64::consts::TAU) {
                return Err(invalid(
                    v.span(),
                    "step must be a positive angle of at most one turn".to_owned(),
                ));
            }
            // The table holds every row: at most MAX_IN_MEMORY cam positions in a turn.
            let positions = std::f64::consts::TAU / step;
            if positions > crate::scene::positions::MAX_IN_MEMORY as f64 {
                let smallest =
                    std::f64::consts::TAU / crate::scene::positions::MAX_IN_MEMORY as f64;
                return Err(invalid(
                    v.span(),
                    format!(
                        "step gives {positions:.3e} cam positions in a turn, over the limit of \
                         {}; the smallest step is {} {}",
                        crate::scene::positions::MAX_IN_MEMORY,
                        Units::tidy(units.from_si(smallest, Dimension::Angle)),
                        units.symbol(Dimension::Angle),
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

/// The engine's message with lengths in the file's unit where it names one.
fn engine_message(
    error: &mechdiff_core::Error,
    units: &Units,
    lift_dimension: Dimension,
) -> String {
    match error {
        mechdiff_core::Error::CamDimension {
            what,
            value,
            problem,
        } => format!(
            "{what} = {} {}: {problem}",
            Units::tidy(units.from_si(*value, Dimension::Length)),
            units.symbol(Dimension::Length)
        ),
        mechdiff_core::Error::CamJoin {
            angle_deg,
            before,
            after,
            left,
            right,
        } => {
            let unit = units.symbol(lift_dimension);
            let shown = |v: f64| Units::tidy(units.from_si(v, lift_dimension));
            format!(
                "the follower displacement does not join at cam angle {angle_deg}° between \
                 segment {before} (ends at {} {unit}) and segment {after} (starts at {} {unit})",
                shown(*left),
                shown(*right)
            )
        }
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
    let finite = |v: &Spanned<f64>, dimension: Dimension| -> Result<f64> {
        let si = units.to_si(*v.get_ref(), dimension);
        if si.is_finite() {
            Ok(si)
        } else {
            Err(invalid(
                v.span(),
                &format!("{} is not a finite number", v.get_ref()),
            ))
        }
    };
    let extent = finite(&d.extent, Dimension::Angle)?;
    if !(extent.is_finite() && extent > 0.0) {
        return Err(invalid(
            d.extent.span(),
            &format!(
                "extent must be a positive angle, found {} {}",
                d.extent.get_ref(),
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
    let finite = |v: &Spanned<f64>| -> Result<f64> {
        let si = units.to_si(*v.get_ref(), Dimension::Length);
        if si.is_finite() {
            Ok(si)
        } else {
            Err(Error::Invalid {
                location: source.location(v.span()),
                message: format!("{} is not a finite number", v.get_ref()),
            })
        }
    };
    let length = |v: &Option<Spanned<f64>>, name: &str| -> Result<f64> {
        match v {
            Some(v) => finite(v),
            None => Err(Error::Invalid {
                location: source.location(def.kind.span()),
                message: format!("a `{}` follower needs `{name} = …`", kind.name()),
            }),
        }
    };
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
    let fail = |span: std::ops::Range<usize>, e: mechdiff_core::Error| Error::Invalid {
        location: source.location(span),
        message: engine_message(&e, units, Dimension::Length),
    };
    if let Some(limit) = &cam.pressure_angle_limit {
        let radians = units.to_si(*limit.get_ref(), Dimension::Angle);
        let base = sizing::base_radius_for_pressure_angle(program, follower, radians)
            .map_err(|e| fail(limit.span(), e))?;
        let what = format!(
            "largest pressure angle {} {}",
            Units::tidy(*limit.get_ref()),
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
        let si = units.to_si(*radius.get_ref(), Dimension::Length);
        let base =
            sizing::base_radius_for_flat_face(program, si).map_err(|e| fail(radius.span(), e))?;
        let what = format!(
            "smallest radius of curvature {} {}",
            Units::tidy(*radius.get_ref()),
            units.symbol(Dimension::Length)
        );
        return Ok(Some((base, what)));
    }
    Ok(None)
}
