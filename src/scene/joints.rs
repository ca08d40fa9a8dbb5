//! Checking one `[joints.<name>]` entry against the fields its type needs.

use toml::Spanned;

use crate::error::{Error, Result};

use super::format::{JointDef, JointKind as Kind, Name};
use super::model::{Joint, JointKind};
use super::resolve::{Context, GROUND, Geometry};
use super::units::Dimension;

/// The fields each joint type takes, besides `type` (in the order they are documented).
fn fields(kind: Kind) -> &'static [&'static str] {
    match kind {
        Kind::Revolute => &["links", "at"],
        Kind::Prismatic => &["links", "line", "point"],
        Kind::PinInSlot => &["links", "slot", "pin"],
        Kind::RackPinion => &["pinion", "rack", "radius"],
        Kind::Gear => &["gears", "ratio"],
        Kind::Weld => &["links"],
    }
}

fn type_name(kind: Kind) -> &'static str {
    match kind {
        Kind::Revolute => "revolute",
        Kind::Prismatic => "prismatic",
        Kind::PinInSlot => "pin_in_slot",
        Kind::RackPinion => "rack_pinion",
        Kind::Gear => "gear",
        Kind::Weld => "weld",
    }
}

/// Resolves joint `name`; `earlier` are the joints defined before it (a rack-and-pinion
/// refers to them).
pub(crate) fn resolve(
    cx: &Context,
    name: &str,
    def: &Spanned<JointDef>,
    geometry: &Geometry,
    earlier: &[Joint],
) -> Result<JointKind> {
    let d = def.get_ref();
    let kind = *d.kind.get_ref();
    let context = format!("joint `{name}`");
    let allowed = fields(kind);
    let given: [(&str, Option<std::ops::Range<usize>>); 11] = [
        ("links", d.links.as_ref().map(|v| v.span())),
        ("at", d.at.as_ref().map(|v| v.span())),
        ("line", d.line.as_ref().map(|v| v.span())),
        ("point", d.point.as_ref().map(|v| v.span())),
        ("pin", d.pin.as_ref().map(|v| v.span())),
        ("slot", d.slot.as_ref().map(|v| v.span())),
        ("pinion", d.pinion.as_ref().map(|v| v.span())),
        ("rack", d.rack.as_ref().map(|v| v.span())),
        ("radius", d.radius.as_ref().map(|v| v.span())),
        ("gears", d.gears.as_ref().map(|v| v.span())),
        ("ratio", d.ratio.as_ref().map(|v| v.span())),
    ];
    let expected = format!(
        "a `{}` joint takes `type`, {}",
        type_name(kind),
        allowed
            .iter()
            .map(|f| format!("`{f}`"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    for (field, span) in &given {
        match span {
            Some(span) if !allowed.contains(field) => {
                return Err(Error::Invalid {
                    location: cx.source.location(span.clone()),
                    message: format!("{context}: `{field}` does not apply; {expected}"),
                });
            }
            _ => {}
        }
    }
    // A field the type takes (every other one was refused above), or which one is missing.
    let missing =
        |field: &str| cx.invalid(def, format!("{context}: `{field}` is missing; {expected}"));
    let links = |cx: &Context| -> Result<[String; 2]> {
        let links = d.links.as_ref().ok_or_else(|| missing("links"))?;
        let [a, b] = links.get_ref();
        let a = cx.link(a, geometry.links, &context)?;
        let b = cx.link(b, geometry.links, &context)?;
        if a == b {
            return Err(cx.invalid(
                links,
                format!("{context} joins link `{a}` to itself; expected two different links"),
            ));
        }
        Ok([a.to_owned(), b.to_owned()])
    };
    Ok(match kind {
        Kind::Revolute => {
            let links = links(cx)?;
            let at = d.at.as_ref().ok_or_else(|| missing("at"))?;
            cx.point_on(at, &links[0], geometry, &context)?;
            let at = cx.point_on(at, &links[1], geometry, &context)?;
            JointKind::Revolute {
                links,
                at: at.to_owned(),
            }
        }
        Kind::Prismatic => {
            let links = links(cx)?;
            let line = cx.line(
                d.line.as_ref().ok_or_else(|| missing("line"))?,
                &links[0],
                geometry,
                &context,
            )?;
            let point_name = d.point.as_ref().ok_or_else(|| missing("point"))?;
            let point = cx
                .point_on(point_name, &links[1], geometry, &context)?
                .to_owned();
            cx.on_line(point_name, geometry, &point, &line, &context)?;
            JointKind::Prismatic { links, line, point }
        }
        Kind::PinInSlot => {
            let links = links(cx)?;
            let slot = cx.line(
                d.slot.as_ref().ok_or_else(|| missing("slot"))?,
                &links[0],
                geometry,
                &context,
            )?;
            let pin_name = d.pin.as_ref().ok_or_else(|| missing("pin"))?;
            let pin = cx
                .point_on(pin_name, &links[1], geometry, &context)?
                .to_owned();
            cx.on_line(pin_name, geometry, &pin, &slot, &context)?;
            JointKind::PinInSlot { links, slot, pin }
        }
        Kind::RackPinion => {
            let pinion = joint_of(
                cx,
                d.pinion.as_ref().ok_or_else(|| missing("pinion"))?,
                earlier,
                "revolute",
                &context,
            )?;
            let rack = joint_of(
                cx,
                d.rack.as_ref().ok_or_else(|| missing("rack"))?,
                earlier,
                "prismatic",
                &context,
            )?;
            let radius = cx.positive(
                d.radius.as_ref().ok_or_else(|| missing("radius"))?,
                &format!("`radius` of {context}"),
                Dimension::Length,
            )?;
            let sign = rolling_sense(geometry, pinion, rack);
            JointKind::RackPinion {
                pinion: pinion.name.clone(),
                rack: rack.name.clone(),
                radius: sign * radius,
            }
        }
        Kind::Gear => {
            let [a, b] = d.gears.as_ref().ok_or_else(|| missing("gears"))?.get_ref();
            let a = joint_of(cx, a, earlier, "revolute", &context)?;
            let b = joint_of(cx, b, earlier, "revolute", &context)?;
            let ratio = d.ratio.as_ref().ok_or_else(|| missing("ratio"))?;
            let value = *ratio.get_ref();
            if !value.is_finite() || value == 0.0 {
                return Err(cx.invalid(
                    ratio,
                    format!("{context}: `ratio` must be a finite, non-zero number, found {value}"),
                ));
            }
            JointKind::Gear {
                joints: [a.name.clone(), b.name.clone()],
                ratio: value,
            }
        }
        Kind::Weld => {
            let links = links(cx)?;
            if links[1] == GROUND {
                return Err(cx.invalid(
                    def,
                    format!(
                        "{context}: weld the other link to `{GROUND}` \
                    with `links = [\"{GROUND}\", \"{}\"]`",
                        links[0]
                    ),
                ));
            }
            JointKind::Weld { links }
        }
    })
}

/// A joint named by a rack-and-pinion, which must be defined before it and of `kind`.
fn joint_of<'j>(
    cx: &Context,
    name: &Name,
    earlier: &'j [Joint],
    kind: &str,
    context: &str,
) -> Result<&'j Joint> {
    let Some(joint) = earlier.iter().find(|j| &j.name == name.get_ref()) else {
        let known: Vec<&str> = earlier.iter().map(|j| j.name.as_str()).collect();
        return Err(Error::UnknownName {
            location: cx.at(name),
            what: "joint",
            name: name.get_ref().clone(),
            context: format!("{context} (it must be defined above it)"),
            known: known.join(", "),
        });
    };
    if joint.kind.type_name() != kind {
        return Err(cx.invalid(
            name,
            format!(
                "{context}: joint `{}` is {}; expected a {kind} joint",
                joint.name,
                joint.kind.type_name()
            ),
        ));
    }
    Ok(joint)
}

/// +1 when the pinion's centre is to the left of the rack's line (then a counter-clockwise
/// turn of the pinion pushes the rack forwards along the line), −1 otherwise.
fn rolling_sense(geometry: &Geometry, pinion: &Joint, rack: &Joint) -> f64 {
    let (JointKind::Revolute { at, .. }, JointKind::Prismatic { line, .. }) =
        (&pinion.kind, &rack.kind)
    else {
        return 1.0;
    };
    let (c, a, b) = (
        geometry.sketch(at),
        geometry.sketch(&line[0]),
        geometry.sketch(&line[1]),
    );
    let cross = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    if cross >= 0.0 { 1.0 } else { -1.0 }
}
