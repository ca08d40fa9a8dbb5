//! From a checked [`Scene`] to the geometry model of mechdiff-core.

use mechdiff_core::geometry::{Drive, Mechanism};

use crate::error::{Error, Result};

use super::context::GROUND;
use super::model::{DriveKind, JointKind, Scene};

/// Builds the core [`Mechanism`] of a scene (the sketch, its links and joints, the drive with
/// its value at the sketch pose).
///
/// Mobility is checked when the solver starts ([`mechdiff_core::geometry::Solver::track`]).
pub fn mechanism(scene: &Scene) -> Result<Mechanism> {
    let mut b = Mechanism::builder();
    for p in &scene.points {
        b = b.point(p.name.as_str(), p.sketch);
    }
    for link in &scene.links {
        b = if link.name == GROUND {
            b.ground(link.points.iter().map(String::as_str))
        } else {
            b.link(link.name.as_str(), link.points.iter().map(String::as_str))
        };
    }
    for (link, inertia) in scene.dynamics.iter().flat_map(|d| &d.masses) {
        b = b.inertia(link.as_str(), *inertia);
    }
    for joint in &scene.joints {
        let name = joint.name.as_str();
        b = match &joint.kind {
            JointKind::Revolute { links: [a, c], at } => b.revolute(name, a, c, at),
            JointKind::Prismatic {
                links: [guide, slider],
                line: [p, q],
                point,
            } => b.prismatic(name, guide, [p, q], slider, point),
            JointKind::PinInSlot {
                links: [slot, pin_link],
                slot: [p, q],
                pin,
            } => b.pin_in_slot(name, slot, [p, q], pin_link, pin),
            JointKind::RackPinion {
                pinion,
                rack,
                radius,
            } => b.rack_pinion(name, pinion, rack, *radius),
            JointKind::Gear {
                joints: [a, c],
                ratio,
            } => b.gear(name, a, c, *ratio),
            JointKind::Weld { links: [a, c] } => b.rigid(name, a, c),
        };
    }
    let drive = match scene.drive.joint_kind() {
        DriveKind::Angle => Drive::angle(scene.drive.joint.as_str()),
        DriveKind::Displacement => Drive::displacement(scene.drive.joint.as_str()),
    };
    b.drive(drive.at_sketch(scene.drive.at_sketch))
        .build()
        .map_err(|source| model_error(scene, source))
}

/// A core error about the model as a whole, located in the file where it names a joint
/// (see [`super::error_context::ErrorContext::model_error`]).
pub(crate) fn model_error(scene: &Scene, source: mechdiff_core::Error) -> Error {
    scene.error_context().model_error(source)
}
