//! The small context a scene's run errors carry: the file, the units, the drive and the
//! joints' places — so that a core error is told in the scene's words (its drive positions
//! in the scene's units, a joint at its `file:line:column`) without the whole [`Scene`].
//!
//! Drive positions are written in the scene's units here and only here
//! ([`ErrorContext::drive_text`], [`ErrorContext::joint_text`],
//! [`ErrorContext::cam_angle_text`]).

use mechdiff_core::Error as Core;

use crate::error::Error;

use super::model::{Drive, Joint, Scene};
use super::units::Units;

/// What an error of a scene's run needs to know of the scene (borrowed from it).
#[derive(Debug, Clone, Copy)]
pub struct ErrorContext<'s> {
    /// The scene file, as messages name it.
    pub file: &'s str,
    /// The scene's units.
    pub units: Units,
    /// The drive (its kind, and the cam of a cam drive).
    pub drive: &'s Drive,
    /// The joints, with their places in the file.
    pub joints: &'s [Joint],
}

impl Scene {
    /// The context of this scene's errors.
    pub fn error_context(&self) -> ErrorContext<'_> {
        ErrorContext {
            file: &self.file,
            units: self.units,
            drive: &self.drive,
            joints: &self.joints,
        }
    }
}

impl ErrorContext<'_> {
    /// A drive value (SI) printed with the scene's unit, e.g. `"67.5 deg"`.
    pub fn drive_text(&self, value: f64) -> String {
        let dimension = self.drive.kind.dimension();
        format!(
            "{} {}",
            Units::tidy(self.units.from_si(value, dimension)),
            self.units.symbol(dimension)
        )
    }

    /// A cam angle (SI) of a cam drive with the follower's position there: `"21.5 deg (the
    /// cam's follower at 425 mm, joint `guide`)"`; the drive text without a cam.
    pub fn cam_angle_text(&self, theta: f64) -> String {
        let Some(cam) = &self.drive.cam else {
            return self.drive_text(theta);
        };
        let dimension = cam.joint_kind.dimension();
        format!(
            "{} (the cam's follower at {} {}, joint `{}`)",
            self.drive_text(theta),
            Units::tidy(
                self.units
                    .from_si(self.drive.joint_position(theta), dimension)
            ),
            self.units.symbol(dimension),
            self.drive.joint
        )
    }

    /// A position (SI) of the driven joint: the drive text, or for a cam drive the
    /// follower's position in its own unit (`"the cam's follower at 425 mm (joint
    /// `guide`)"`).
    pub fn joint_text(&self, value: f64) -> String {
        let Some(cam) = &self.drive.cam else {
            return self.drive_text(value);
        };
        let dimension = cam.joint_kind.dimension();
        format!(
            "the cam's follower at {} {} (joint `{}`)",
            Units::tidy(self.units.from_si(value, dimension)),
            self.units.symbol(dimension),
            self.drive.joint
        )
    }

    /// A core error about the model as a whole, located in the file where it names a joint.
    pub fn model_error(&self, source: Core) -> Error {
        let joint = match &source {
            Core::InvalidJoint { joint, .. } | Core::SketchNotAssembled { joint, .. } => {
                Some(joint)
            }
            _ => None,
        };
        match joint.and_then(|j| self.joints.iter().find(|k| &k.name == j)) {
            Some(joint) => Error::Invalid {
                location: joint.location.clone(),
                message: source.to_string(),
            },
            None => Error::Model {
                file: self.file.to_owned(),
                source,
            },
        }
    }

    /// A core solver error, with drive positions in the scene's units (of the driven
    /// joint, for a cam drive).
    pub fn solver_error(&self, source: Core) -> Error {
        self.located(source, &|x| self.joint_text(x), &|x| self.joint_text(x))
    }

    /// The error of a move along a cam ([`mechdiff_core::cams::CamJoint::move_tracker`]),
    /// whose drive positions are cam angles: in the scene's angle unit, a limit or singular
    /// position with the follower's position there.
    pub fn cam_error(&self, source: Core) -> Error {
        self.located(source, &|theta| self.cam_angle_text(theta), &|theta| {
            self.drive_text(theta)
        })
    }

    /// The scene's error for the solver's `source`, each drive position written by `at` (a
    /// position where something happens) or `between` (the ends of a move).
    fn located(
        &self,
        source: Core,
        at: &dyn Fn(f64) -> String,
        between: &dyn Fn(f64) -> String,
    ) -> Error {
        let joined = |joints: &[String]| joints.join(", ");
        let file = self.file.to_owned();
        match source {
            Core::Unassemblable {
                phi,
                last_assembled,
                joints,
                residual,
            } => Error::Unassemblable {
                file,
                position: at(phi),
                last: between(last_assembled),
                loop_joints: joined(&joints),
                residual,
            },
            Core::Singular {
                phi,
                condition,
                joints,
            } => Error::Singular {
                file,
                position: at(phi),
                loop_joints: joined(&joints),
                condition,
            },
            Core::NonFinite { phi, quantity } => Error::NotFinite {
                file,
                quantity: quantity.to_owned(),
                value: "not finite".to_owned(),
                position: at(phi),
            },
            Core::Blocked {
                from,
                to,
                limit,
                joints,
            } => Error::Blocked {
                file,
                from: between(from).into(),
                to: between(to).into(),
                limit: at(limit).into(),
                loop_joints: joined(&joints).into(),
            },
            Core::ChangePoint { phi, joints } => Error::ChangePoint {
                file,
                position: at(phi),
                loop_joints: joined(&joints),
            },
            Core::BranchFlip { from, to, joints } => Error::BranchFlip {
                file,
                from: between(from),
                to: between(to),
                loop_joints: joined(&joints),
            },
            Core::MoveTooLong {
                from,
                to,
                steps,
                longest,
            } => Error::MoveTooLong {
                file,
                from: between(from),
                to: between(to),
                steps,
                longest: between(longest),
            },
            other => self.model_error(other),
        }
    }
}
