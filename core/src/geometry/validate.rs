//! Validation of a declared model: names, references, lengths, sketch consistency.

use super::builder::{MechanismBuilder, PendingJoint};
use super::constraints;
use super::model::{Drive, DriveKind, GROUND, Joint, JointKind, Link, Mechanism};
use crate::Error;
use std::collections::HashMap;

/// Tolerance (m, relative to the sketch size) for the sketch to satisfy each joint.
const SKETCH_TOLERANCE: f64 = 1e-9;

struct Names<'a> {
    points: HashMap<&'a str, usize>,
    links: HashMap<&'a str, usize>,
}

impl Names<'_> {
    fn point(&self, name: &str, context: &str) -> Result<usize, Error> {
        self.points
            .get(name)
            .copied()
            .ok_or_else(|| unknown("point", name, context))
    }

    fn link(&self, name: &str, context: &str) -> Result<usize, Error> {
        self.links
            .get(name)
            .copied()
            .ok_or_else(|| unknown("link", name, context))
    }
}

fn unknown(what: &'static str, name: &str, context: &str) -> Error {
    Error::UnknownName {
        what,
        name: name.to_owned(),
        context: context.to_owned(),
    }
}

fn unique<'a>(
    what: &'static str,
    names: impl Iterator<Item = &'a str>,
) -> Result<HashMap<&'a str, usize>, Error> {
    let mut map = HashMap::new();
    for (i, n) in names.enumerate() {
        if map.insert(n, i).is_some() {
            return Err(Error::DuplicateName {
                what,
                name: n.to_owned(),
            });
        }
    }
    Ok(map)
}

fn finite(what: impl FnOnce() -> String, value: f64) -> Result<(), Error> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(Error::InvalidValue {
            what: what(),
            value,
        })
    }
}

/// Builds and validates a [`Mechanism`] from a builder.
pub(super) fn build(b: MechanismBuilder) -> Result<Mechanism, Error> {
    for p in &b.points {
        finite(|| format!("x of point `{}`", p.name), p.sketch[0])?;
        finite(|| format!("y of point `{}`", p.name), p.sketch[1])?;
    }
    let link_names = std::iter::once(GROUND).chain(b.links.iter().map(|(n, _)| n.as_str()));
    let names = Names {
        points: unique("point", b.points.iter().map(|p| p.name.as_str()))?,
        links: unique("link", link_names)?,
    };
    unique("joint", b.joints.iter().map(|(n, _)| n.as_str()))?;

    let mut links = vec![Link {
        name: GROUND.to_owned(),
        points: Vec::new(),
        inertia: None,
    }];
    for (name, _) in &b.links {
        links.push(Link {
            name: name.clone(),
            points: Vec::new(),
            inertia: None,
        });
    }
    let carried = std::iter::once(&b.ground).chain(b.links.iter().map(|(_, p)| p));
    // The link that last took each point: a point listed twice on one link is found in
    // constant time (a link may carry 10⁵ points).
    let mut taken_by = vec![usize::MAX; b.points.len()];
    for (k, points) in carried.enumerate() {
        let context = format!("link `{}`", links[k].name);
        for p in points {
            let i = names.point(p, &context)?;
            if std::mem::replace(&mut taken_by[i], k) == k {
                return Err(Error::DuplicateName {
                    what: "point on a link",
                    name: format!("{p} (link `{}`)", links[k].name),
                });
            }
            links[k].points.push(i);
        }
        if k > 0 && links[k].points.is_empty() {
            return Err(Error::InvalidJoint {
                joint: links[k].name.clone(),
                problem: "a moving link must carry at least one point".to_owned(),
            });
        }
    }
    for (name, inertia) in &b.inertias {
        let k = names.link(name, "inertia")?;
        finite(|| format!("mass of link `{name}`"), inertia.mass)?;
        finite(
            || format!("moment of inertia of link `{name}`"),
            inertia.moment,
        )?;
        finite(
            || format!("centre of gravity of link `{name}`"),
            inertia.center[0],
        )?;
        finite(
            || format!("centre of gravity of link `{name}`"),
            inertia.center[1],
        )?;
        if inertia.mass < 0.0 || inertia.moment < 0.0 {
            return Err(Error::InvalidValue {
                what: format!("mass or moment of inertia of link `{name}` (must be ≥ 0)"),
                value: inertia.mass.min(inertia.moment),
            });
        }
        links[k].inertia = Some(*inertia);
    }

    let mut joints: Vec<Joint> = Vec::with_capacity(b.joints.len());
    for (name, pending) in &b.joints {
        let kind = resolve_joint(&names, &links, &b.points, &joints, name, pending)?;
        joints.push(Joint {
            name: name.clone(),
            kind,
        });
    }

    let drive = b.drive.ok_or(Error::MissingDrive)?;
    let (drive_joint, drive_kind, drive_at_sketch) = resolve_drive(&joints, &drive)?;
    let mut m = Mechanism {
        points: b.points,
        links,
        joints,
        drive_joint,
        drive_kind,
        drive_at_sketch: 0.0,
    };
    m.drive_at_sketch = match drive_at_sketch {
        Some(v) => v,
        None => constraints::sketch_drive_value(&super::datum::Data::of(&m)),
    };
    check_sketch(&m)?;
    Ok(m)
}

fn resolve_drive(
    joints: &[Joint],
    drive: &Drive,
) -> Result<(usize, DriveKind, Option<f64>), Error> {
    let j = joints
        .iter()
        .position(|j| j.name == drive.joint)
        .ok_or_else(|| unknown("joint", &drive.joint, "drive"))?;
    let ok = matches!(
        (&drive.kind, &joints[j].kind),
        (DriveKind::Angle, JointKind::Revolute { .. })
            | (DriveKind::Displacement, JointKind::Prismatic { .. })
    );
    if !ok {
        return Err(Error::InvalidJoint {
            joint: drive.joint.clone(),
            problem: format!(
                "a {} joint cannot carry a drive {}",
                joints[j].kind.kind_name(),
                if drive.kind == DriveKind::Angle {
                    "angle"
                } else {
                    "displacement"
                }
            ),
        });
    }
    if let Some(v) = drive.at_sketch {
        finite(|| "drive value at the sketch".to_owned(), v)?;
    }
    Ok((j, drive.kind.clone(), drive.at_sketch))
}

fn resolve_joint(
    names: &Names<'_>,
    links: &[Link],
    points: &[super::model::Point],
    previous: &[Joint],
    name: &str,
    pending: &PendingJoint,
) -> Result<JointKind, Error> {
    let context = format!("joint `{name}`");
    let on = |link: usize, point: usize| -> Result<(), Error> {
        if links[link].points.contains(&point) {
            Ok(())
        } else {
            Err(Error::PointNotOnLink {
                point: points[point].name.clone(),
                link: links[link].name.clone(),
                context: context.clone(),
            })
        }
    };
    let distinct = |a: usize, b: usize| -> Result<(), Error> {
        if a == b {
            Err(Error::InvalidJoint {
                joint: name.to_owned(),
                problem: format!("joins link `{}` to itself", links[a].name),
            })
        } else {
            Ok(())
        }
    };
    let line = |link: usize, l: &[String; 2]| -> Result<[usize; 2], Error> {
        let p = [names.point(&l[0], &context)?, names.point(&l[1], &context)?];
        on(link, p[0])?;
        on(link, p[1])?;
        let (a, c) = (points[p[0]].sketch, points[p[1]].sketch);
        let length = (c[0] - a[0]).hypot(c[1] - a[1]);
        if length.is_nan() || length <= 0.0 {
            return Err(Error::NonPositiveLength {
                what: format!("line `{}`–`{}` of joint `{name}`", l[0], l[1]),
                length,
            });
        }
        Ok(p)
    };
    let joint_of = |jname: &str, want: &str| -> Result<usize, Error> {
        let j = previous
            .iter()
            .position(|j| j.name == jname)
            .ok_or_else(|| unknown("joint", jname, &format!("{context} (declare it before)")))?;
        if previous[j].kind.kind_name() != want {
            return Err(Error::InvalidJoint {
                joint: name.to_owned(),
                problem: format!(
                    "`{jname}` is a {} joint, not {want}",
                    previous[j].kind.kind_name()
                ),
            });
        }
        Ok(j)
    };
    Ok(match pending {
        PendingJoint::Revolute { a, b, point } => {
            let (link_a, link_b) = (names.link(a, &context)?, names.link(b, &context)?);
            distinct(link_a, link_b)?;
            let point = names.point(point, &context)?;
            on(link_a, point)?;
            on(link_b, point)?;
            JointKind::Revolute {
                link_a,
                link_b,
                point,
            }
        }
        PendingJoint::Prismatic {
            guide,
            line: l,
            slider,
            point,
        } => {
            let (guide, slider) = (names.link(guide, &context)?, names.link(slider, &context)?);
            distinct(guide, slider)?;
            let line = line(guide, l)?;
            let point = names.point(point, &context)?;
            on(slider, point)?;
            JointKind::Prismatic {
                guide,
                line,
                slider,
                point,
            }
        }
        PendingJoint::PinInSlot {
            slot,
            line: l,
            pin_link,
            pin,
        } => {
            let (slot_link, pin_link) =
                (names.link(slot, &context)?, names.link(pin_link, &context)?);
            distinct(slot_link, pin_link)?;
            let line = line(slot_link, l)?;
            let pin = names.point(pin, &context)?;
            on(pin_link, pin)?;
            JointKind::PinInSlot {
                slot_link,
                line,
                pin_link,
                pin,
            }
        }
        PendingJoint::RackPinion {
            pinion,
            rack,
            radius,
        } => {
            finite(|| format!("radius of joint `{name}`"), *radius)?;
            if *radius == 0.0 {
                return Err(Error::NonPositiveLength {
                    what: format!("pitch radius of joint `{name}`"),
                    length: 0.0,
                });
            }
            let pinion = joint_of(pinion, "revolute")?;
            let rack = joint_of(rack, "prismatic")?;
            JointKind::RackPinion {
                pinion,
                rack,
                radius: *radius,
            }
        }
        PendingJoint::Gear { a, b, ratio } => {
            finite(|| format!("ratio of joint `{name}`"), *ratio)?;
            if *ratio == 0.0 {
                return Err(Error::InvalidValue {
                    what: format!("ratio of joint `{name}` (must be non-zero)"),
                    value: 0.0,
                });
            }
            let joint_a = joint_of(a, "revolute")?;
            let joint_b = joint_of(b, "revolute")?;
            JointKind::Gear {
                joint_a,
                joint_b,
                ratio: *ratio,
            }
        }
        PendingJoint::Rigid { a, b } => {
            let (link_a, link_b) = (names.link(a, &context)?, names.link(b, &context)?);
            distinct(link_a, link_b)?;
            JointKind::Rigid { link_a, link_b }
        }
    })
}

/// Every joint must hold at the sketch pose (it is the assembly the designer drew).
fn check_sketch(m: &Mechanism) -> Result<(), Error> {
    let q = m.sketch_coordinates();
    let phi = m.drive_at_sketch;
    let mut row = 0;
    let residual = constraints::residual(m, &q, phi);
    for (index, j) in m.joints.iter().enumerate() {
        let n = j.kind.equation_count();
        // in the joint's own length scale: a point elsewhere changes no verdict
        let scale = super::length::joint_length(m, index).max(f64::MIN_POSITIVE);
        let r = residual[row..row + n]
            .iter()
            .fold(0.0f64, |a, &x| a.max(x.abs()));
        if r.is_nan() || r > SKETCH_TOLERANCE * scale {
            return Err(Error::SketchNotAssembled {
                joint: j.name.clone(),
                residual: r,
            });
        }
        row += n;
    }
    Ok(())
}
