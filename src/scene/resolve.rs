//! From the file as written ([`super::format`]) to a checked [`Scene`]: units applied,
//! names resolved, required fields present for each joint type, the sketch consistent.
//!
//! Every error names `file:line:column` and what was expected there.

use std::collections::{BTreeMap, HashMap, HashSet};

use toml::Spanned;

use crate::error::{Error, Result};

use super::bindings::Bindings;
use super::context::{Context, GROUND, Geometry};
use super::drive::nearest_turn;
use super::format::{JointDef, SceneFile};
use super::model::{DriveKind, Joint, JointKind, Link, Scene};
use super::outputs;
use super::source::Source;
use super::units::Units;
use super::values::Name;

/// Checks a parsed file and resolves it into a [`Scene`], its formulas evaluated with the
/// scene's `parameters` ([`super::parameters::bindings`]).
///
/// # Errors
/// The first thing wrong in the file, at `file:line:column`.
pub fn resolve(file: &SceneFile, source: &Source, parameters: &Bindings) -> Result<Scene> {
    scene(
        file,
        &Context::new(source, Units::declared(&file.units), parameters),
    )
}

/// [`resolve`] in the context `cx`.
pub(crate) fn scene(file: &SceneFile, cx: &Context<'_>) -> Result<Scene> {
    let points = cx.points(&file.points)?;
    let names: HashMap<&str, usize> = points
        .iter()
        .enumerate()
        .map(|(i, p)| (p.name.as_str(), i))
        .collect();
    let links = cx.links(&file.links, &names)?;
    let geometry = Geometry::new(&points, &names, &links);
    let joints = cx.joints(&file.joints, &geometry)?;
    let mut drive = cx.drive(&file.drive, &geometry, &joints)?;
    let outputs = outputs::resolve(cx, &file.outputs, &geometry, &joints, &drive)?;
    let sections = super::dynamics::DynamicsSections::of(file);
    let dynamics = super::dynamics::resolve(cx, &sections, &geometry, &joints, drive.kind)?;
    let motion =
        super::motion::resolve(cx, file.motor.as_ref(), file.simulate.as_ref(), drive.kind)?;
    if let Some(simulate) = &file.simulate {
        if file.balancing.is_some() || file.rotor.is_some() {
            return Err(cx.invalid(
                simulate,
                "`[simulate]` runs the machine under its motor; balancing is sized at a \
                 prescribed speed: run it from a scene without `[simulate]`",
            ));
        }
        let power = (dynamics.iter().flat_map(|d| &d.outputs))
            .find(|o| o.quantity == super::dynamics::DynamicQuantity::PowerBalance);
        if let Some(o) = power {
            return Err(Error::Invalid {
                location: o.location.clone(),
                message: "the power balance divides by the drive speed, which is 0 where a \
                          simulated machine starts from rest: ask for `drive_torque` instead"
                    .to_owned(),
            });
        }
    }
    let balancing =
        super::balancing::resolve(cx, file.rotor.as_ref(), file.balancing.as_ref(), &geometry)?;
    let plot = super::plot::resolve(cx, file.plot.as_ref(), &geometry, drive.kind)?;
    let solver = super::solver::resolve(cx, file.solver.as_ref())?;
    let sweep_of = cx.sweep_of(&file.sweep, &outputs)?;
    let dimension = match sweep_of {
        Some(k) => outputs[k].kind.dimension(),
        None => drive.kind.dimension(),
    };
    let positions = cx.sweep(&file.sweep, dimension)?;
    if drive.kind == DriveKind::Angle && sweep_of.is_none() && drive.cam.is_none() {
        drive.at_sketch = nearest_turn(drive.at_sketch, positions.get(0));
    }
    if let Some(cam) = &file.drive.get_ref().cam {
        let unsupported = [
            (sweep_of.is_some(), "`[sweep] of`"),
            (outputs.iter().any(|o| o.dead_positions), "`dead_positions`"),
            (
                file.balancing.is_some() || file.rotor.is_some(),
                "balancing",
            ),
            (
                file.motor.is_some(),
                "a `[motor]` (the motor turns the cam, not the joint)",
            ),
        ];
        if let Some((_, what)) = unsupported.iter().find(|u| u.0) {
            return Err(cx.invalid(
                cam,
                format!("`[drive] cam`: {what} is not supported with a cam drive; remove it"),
            ));
        }
    }
    if let Some(output) = outputs.iter().find(|o| o.dead_positions) {
        let (lo, hi) = positions.range();
        if hi <= lo {
            return Err(Error::Invalid {
                location: output.location.clone(),
                message: format!(
                    "output `{}`: `dead_positions` needs a range of drive positions to search; \
                    `[sweep]` has one position",
                    output.name
                ),
            });
        }
    }
    let mut scene = Scene {
        file: cx.source.file.clone(),
        title: file.title.clone(),
        units: cx.units,
        points,
        links,
        joints,
        drive,
        positions,
        sweep_of,
        outputs,
        dynamics,
        balancing,
        motion,
        plot,
        solver,
        parameters: cx.parameters.ordered().to_vec(),
    };
    outputs::locate_transmissions(&mut scene)?;
    Ok(scene)
}

impl Context<'_> {
    pub(crate) fn links(
        &self,
        table: &Spanned<BTreeMap<Name, Spanned<Vec<Name>>>>,
        names: &HashMap<&str, usize>,
    ) -> Result<Vec<Link>> {
        let mut entries: Vec<(&Name, &Spanned<Vec<Name>>)> = table.get_ref().iter().collect();
        entries.sort_by_key(|(name, _)| name.span().start);
        let Some(ground) = entries.iter().position(|(n, _)| n.get_ref() == GROUND) else {
            return Err(self.invalid(
                table,
                format!(
                    "`[links]` has no `{GROUND}`; expected `{GROUND} = [\"O\", ...]` listing \
                    the fixed points"
                ),
            ));
        };
        let ground = entries.remove(ground);
        entries.insert(0, ground);
        let mut links = Vec::with_capacity(entries.len());
        for (name, list) in entries {
            let context = format!("link `{}`", name.get_ref());
            if list.get_ref().is_empty() {
                return Err(self.invalid(
                    list,
                    format!("{context} has no points; expected a list of point names"),
                ));
            }
            let mut points: Vec<String> = Vec::new();
            let mut seen = HashSet::new();
            for point in list.get_ref() {
                let point = self.point(point, names, &context)?;
                if !seen.insert(point) {
                    let spanned = list
                        .get_ref()
                        .iter()
                        .filter(|p| p.get_ref() == point)
                        .nth(1);
                    return Err(Error::DuplicatePoint {
                        location: self.at(spanned.unwrap_or(&list.get_ref()[0])),
                        name: point.to_owned(),
                        context,
                    });
                }
                points.push(point.to_owned());
            }
            links.push(Link {
                name: name.get_ref().clone(),
                points,
                location: self.at(name),
            });
        }
        Ok(links)
    }

    pub(crate) fn joints(
        &self,
        table: &Spanned<BTreeMap<Name, Spanned<JointDef>>>,
        geometry: &Geometry,
    ) -> Result<Vec<Joint>> {
        let mut entries: Vec<(&Name, &Spanned<JointDef>)> = table.get_ref().iter().collect();
        entries.sort_by_key(|(name, _)| name.span().start);
        let mut joints: Vec<Joint> = Vec::with_capacity(entries.len());
        for (name, def) in &entries {
            for (joint, kind) in
                super::joints::resolve(self, name.get_ref(), def, geometry, &joints)?
            {
                if let Some((clash, _)) = entries
                    .iter()
                    .find(|(n, _)| n.get_ref() != name.get_ref() && *n.get_ref() == joint)
                {
                    return Err(self.invalid(
                        clash,
                        format!(
                            "joint `{joint}` is also the name of the joint that `{}`'s links \
                             stand for (its first link with a further one); rename one of them",
                            name.get_ref()
                        ),
                    ));
                }
                joints.push(Joint {
                    name: joint,
                    kind,
                    location: self.at(name),
                });
            }
        }
        Ok(joints)
    }
}

impl JointKind {
    /// The type name as written in the file.
    pub fn type_name(&self) -> &'static str {
        match self {
            JointKind::Revolute { .. } => "revolute",
            JointKind::Prismatic { .. } => "prismatic",
            JointKind::PinInSlot { .. } => "pin_in_slot",
            JointKind::RackPinion { .. } => "rack_pinion",
            JointKind::Gear { .. } => "gear",
            JointKind::Weld { .. } => "weld",
        }
    }
}
