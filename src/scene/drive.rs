//! Checking `[drive]` and `[sweep]`.

use std::f64::consts::TAU;

use toml::Spanned;

use crate::error::{Error, Result};

use super::format::{DriveSection, SweepSection};
use mechdiff_core::cams::{CamJoint, Follower};

use super::context::{Context, GROUND, Geometry};
use super::model::{Drive, DriveCam, DriveKind, Joint, JointKind, Output, OutputKind};
use super::positions::Positions;
use super::scalar::Carried;
use super::units::Dimension;

/// The most intervals of `from`, `to`, `step`: below 2⁵³ every `from + i·step` is counted
/// with an exact `i`. A longer sweep is bounded by time and disk, not memory (it streams).
const MAX_INTERVALS: f64 = 9_007_199_254_740_992.0;

/// What the drive measures, checked: the angle of a line of the driven link (from a line of
/// the other link, or from +x), or a slider's displacement along its line.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum DriveMeasure {
    /// The angle of `line` from `reference` (or +x), counter-clockwise.
    Angle {
        line: [String; 2],
        reference: Option<[String; 2]>,
    },
    /// The displacement of `point` along `line` from its first point.
    Displacement { line: [String; 2], point: String },
}

impl DriveMeasure {
    /// Angle or displacement.
    pub(crate) fn kind(&self) -> DriveKind {
        match self {
            DriveMeasure::Angle { .. } => DriveKind::Angle,
            DriveMeasure::Displacement { .. } => DriveKind::Displacement,
        }
    }

    /// Its value with the points at `sketch(name)` (rad or m), in any [`Carried`] scalar.
    pub(crate) fn at<D: Carried>(&self, sketch: impl Fn(&str) -> [D; 2]) -> D {
        let direction = |[a, b]: &[String; 2]| {
            let (a, b) = (sketch(a), sketch(b));
            (b[1] - a[1]).atan2(b[0] - a[0])
        };
        match self {
            DriveMeasure::Angle { line, reference } => match reference {
                Some(reference) => direction(line) - direction(reference),
                None => direction(line),
            },
            DriveMeasure::Displacement { line, point } => {
                let (a, b, p) = (sketch(&line[0]), sketch(&line[1]), sketch(point));
                let (ux, uy) = (b[0] - a[0], b[1] - a[1]);
                ((p[0] - a[0]) * ux + (p[1] - a[1]) * uy) / ux.hypot(uy)
            }
        }
    }
}

impl Context<'_> {
    pub(crate) fn drive(
        &self,
        section: &Spanned<DriveSection>,
        geometry: &Geometry,
        joints: &[Joint],
    ) -> Result<Drive> {
        let d = section.get_ref();
        let (joint, measure) = self.drive_measure(section, geometry, joints)?;
        let (kind, at_sketch) = (measure.kind(), measure.at(|n| geometry.sketch(n)));
        let cam = match &d.cam {
            Some(path) => Some(self.drive_cam(path, &joint.name, kind)?),
            None => None,
        };
        // With a cam the drive position, speed and acceleration are the cam's angle and
        // motion; the joint's own kind is kept in the cam drive.
        let kind = if cam.is_some() {
            DriveKind::Angle
        } else {
            kind
        };
        let speed = d
            .speed
            .as_ref()
            .map(|v| self.number(v, "`[drive] speed`", kind.speed_dimension()))
            .transpose()?;
        let acceleration = d
            .acceleration
            .as_ref()
            .map(|v| self.number(v, "`[drive] acceleration`", kind.acceleration_dimension()))
            .transpose()?
            .unwrap_or(0.0);
        Ok(Drive {
            joint: joint.name.clone(),
            kind,
            at_sketch,
            speed,
            acceleration,
            location: self.at(section),
            cam,
        })
    }

    /// The drive's joint and what it measures, checked (see [`Context::drive`]).
    pub(crate) fn drive_measure<'j>(
        &self,
        section: &Spanned<DriveSection>,
        geometry: &Geometry,
        joints: &'j [Joint],
    ) -> Result<(&'j Joint, DriveMeasure)> {
        let d = section.get_ref();
        let Some(joint) = joints.iter().find(|j| &j.name == d.joint.get_ref()) else {
            let known: Vec<&str> = joints.iter().map(|j| j.name.as_str()).collect();
            return Err(Error::UnknownName {
                location: self.at(&d.joint),
                what: "joint",
                name: d.joint.get_ref().clone(),
                context: "`[drive]`".to_owned(),
                known: known.join(", "),
            });
        };
        let measure = match &joint.kind {
            JointKind::Revolute { links, .. } => {
                let Some(line) = &d.line else {
                    return Err(self.invalid(
                        section,
                        format!(
                            "`[drive]` of revolute joint `{}` needs `line = [\"P\", \"Q\"]`: two \
                            points of link `{}` whose angle is the drive",
                            joint.name, links[1]
                        ),
                    ));
                };
                let context = format!("`[drive] line` (of the driven link `{}`)", links[1]);
                let line = self.line(line, &links[1], geometry, &context)?;
                let reference = match &d.reference {
                    Some(reference) => {
                        let context = format!("`[drive] reference` (of link `{}`)", links[0]);
                        Some(self.line(reference, &links[0], geometry, &context)?)
                    }
                    None if links[0] != GROUND => {
                        return Err(self.invalid(
                            section,
                            format!(
                                "`[drive]`: joint `{}` turns relative to link `{}`, not the \
                                ground; give `reference = [\"P\", \"Q\"]`, two points of `{}`",
                                joint.name, links[0], links[0]
                            ),
                        ));
                    }
                    None => None,
                };
                DriveMeasure::Angle { line, reference }
            }
            JointKind::Prismatic { line, point, .. } => {
                if let Some(extra) = d
                    .line
                    .as_ref()
                    .map(|l| l.span())
                    .or(d.reference.as_ref().map(|r| r.span()))
                {
                    return Err(Error::Invalid {
                        location: self.source.location(extra),
                        message: format!(
                            "`[drive]`: joint `{}` is prismatic, its displacement is measured \
                            along its own line; `line` and `reference` apply to a revolute drive \
                            only",
                            joint.name
                        ),
                    });
                }
                DriveMeasure::Displacement {
                    line: line.clone(),
                    point: point.clone(),
                }
            }
            other => {
                return Err(self.invalid(
                    &d.joint,
                    format!(
                        "`[drive]`: joint `{}` is {}; expected a revolute or prismatic joint",
                        joint.name,
                        other.type_name()
                    ),
                ));
            }
        };
        Ok((joint, measure))
    }

    /// Loads the cam scene `path` (relative to this file, and under its folder unless the
    /// user allowed more: [`crate::files::read_referenced`]) for `[drive] cam` of joint
    /// `joint` and checks that its follower moves a joint of kind `kind`.
    fn drive_cam(&self, path: &Spanned<String>, joint: &str, kind: DriveKind) -> Result<DriveCam> {
        let scene = std::path::Path::new(&self.source.file);
        let (file, text) = crate::files::read_referenced(path.get_ref(), scene, "the cam file")
            .map_err(|e| self.invalid(path, format!("`[drive] cam`: {e}")))?;
        let cam = super::cam::parse_named(&file.display().to_string(), &text).map_err(|e| {
            self.invalid(
                path,
                format!("`[drive] cam`: the cam scene does not load: {e}"),
            )
        })?;
        let translating = !matches!(
            cam.mechanism.dimensions.follower,
            Follower::OscillatingRoller { .. }
        );
        let expected = if translating {
            DriveKind::Displacement
        } else {
            DriveKind::Angle
        };
        if kind != expected {
            let (follower, wanted) = if translating {
                ("translating", "prismatic")
            } else {
                ("oscillating", "revolute")
            };
            return Err(self.invalid(
                path,
                format!(
                    "`[drive] cam`: the cam's follower is {follower} ({}), so it moves a \
                     {wanted} joint; joint `{joint}` is not one",
                    cam.mechanism.dimensions.follower.describe()
                ),
            ));
        }
        Ok(DriveCam {
            file: file.display().to_string(),
            joint: CamJoint::new(cam.mechanism.program),
            joint_kind: kind,
        })
    }

    /// The output named by `[sweep] of`, if any: an angle or slider output.
    pub(crate) fn sweep_of(
        &self,
        section: &Spanned<SweepSection>,
        outputs: &[Output],
    ) -> Result<Option<usize>> {
        let Some(name) = &section.get_ref().of else {
            return Ok(None);
        };
        let Some(k) = outputs.iter().position(|o| &o.name == name.get_ref()) else {
            let known: Vec<&str> = outputs.iter().map(|o| o.name.as_str()).collect();
            return Err(self.invalid(
                name,
                format!(
                    "`[sweep] of`: no output is named `{}`; expected the name of an angle or \
                     slider output: {}",
                    name.get_ref(),
                    known.join(", ")
                ),
            ));
        };
        if matches!(outputs[k].kind, OutputKind::Point(_)) {
            return Err(self.invalid(
                name,
                format!(
                    "`[sweep] of`: output `{}` is a point (two values); expected an angle or \
                     slider output",
                    outputs[k].name
                ),
            ));
        }
        Ok(Some(k))
    }

    /// The positions (SI) of `[sweep]`: drive positions, or values of the `of` output.
    pub(crate) fn sweep(
        &self,
        section: &Spanned<SweepSection>,
        dimension: Dimension,
    ) -> Result<Positions> {
        let s = section.get_ref();
        let expected = "expected either `from`, `to` and `step`, or `positions = [...]`";
        match (&s.positions, &s.from, &s.to, &s.step) {
            (Some(list), None, None, None) => {
                if list.get_ref().is_empty() {
                    return Err(self.invalid(
                        list,
                        "`positions` is empty; expected at least one drive position",
                    ));
                }
                (list.get_ref().iter().enumerate())
                    .map(|(k, v)| {
                        let what = format!("`positions` entry {}", k + 1);
                        self.number(v, &what, dimension)
                    })
                    .collect::<Result<_>>()
                    .map(Positions::List)
            }
            (None, Some(from), Some(to), Some(step)) => {
                let (from_si, to_si, step_si) = (
                    self.number(from, "`[sweep] from`", dimension)?,
                    self.number(to, "`[sweep] to`", dimension)?,
                    self.number(step, "`[sweep] step`", dimension)?,
                );
                if step_si == 0.0 {
                    return Err(self.invalid(
                        step,
                        "`[sweep] step` is zero; expected the distance between two drive \
                         positions (positive, or negative to walk from `from` down to `to`)",
                    ));
                }
                if to_si > from_si && step_si < 0.0 {
                    return Err(self.invalid(
                        step,
                        "`[sweep] step` is negative but `to` is above `from`; a negative step \
                         walks from `from` down to `to`: swap `from` and `to`, or make the step \
                         positive",
                    ));
                }
                // Count in the file's units so that 0..360 by 0.5 has exactly 721 positions.
                // Downwards when `to` is below `from`, whatever the step's sign (its size).
                let (f, t): (f64, f64) = (self.value(from)?, self.value(to)?);
                let h = self.value::<f64>(step)?.abs().copysign(t - f);
                let intervals = if t == f {
                    0.0
                } else {
                    ((t - f) / h * (1.0 + 4.0 * f64::EPSILON)).floor()
                };
                if intervals >= MAX_INTERVALS {
                    return Err(self.invalid(
                        step,
                        format!(
                            "the sweep has {intervals:.3e} intervals; from, to and step count \
                            at most 2^53 exactly: expected a larger step"
                        ),
                    ));
                }
                Ok(Positions::Steps {
                    from: f,
                    step: h,
                    count: intervals as usize + 1,
                    factor: self.units.factor(dimension),
                    location: self.at(step),
                })
            }
            _ => Err(self.invalid(section, format!("`[sweep]`: {expected}"))),
        }
    }
}

/// Moves the sketch's drive angle by whole turns to within half a turn of `target`, so that
/// the solver goes the short way from the sketch to the first position.
pub(crate) fn nearest_turn(angle: f64, target: f64) -> f64 {
    angle + ((target - angle) / TAU).round() * TAU
}
