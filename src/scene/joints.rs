//! Checking one `[joints.<name>]` entry against the fields its type needs.

use toml::Spanned;

use crate::error::{Error, Result};

use super::context::{Context, GROUND, Geometry};
use super::format::{JointDef, JointKind as Kind, Name};
use super::limits;
use super::model::{Joint, JointKind};
use super::units::Dimension;
use super::values::Number;

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

/// The name of the joint that a revolute or weld joint `name` listing more than two links
/// stands for between its first link and `link` (the first pair keeps `name`).
pub fn expanded_name(name: &str, link: &str) -> String {
    format!("{name}:{link}")
}

/// Resolves joint `name`; `earlier` are the joints defined before it (a rack-and-pinion
/// refers to them). A revolute or weld joint given links `[a, b, c, …]` stands for the
/// joints a–b (named `name`), a–c (named by [`expanded_name`]), …: one kind per pair.
pub(crate) fn resolve(
    cx: &Context,
    name: &str,
    def: &Spanned<JointDef>,
    geometry: &Geometry,
    earlier: &[Joint],
) -> Result<Vec<(String, JointKind)>> {
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
    // Every link named, checked to exist and to be listed once; and the list, for messages.
    let all_links = |cx: &Context| -> Result<(Vec<String>, &Spanned<Vec<Name>>)> {
        let links = d.links.as_ref().ok_or_else(|| missing("links"))?;
        let list = links.get_ref();
        if list.len() < 2 {
            return Err(cx.invalid(
                links,
                format!(
                    "{context} lists {} link(s); expected two: `links = [\"base\", \"moving\"]`",
                    list.len()
                ),
            ));
        }
        let mut names: Vec<String> = Vec::with_capacity(list.len());
        for link in list {
            let link = cx.link(link, geometry, &context)?;
            if names.iter().any(|n| n == link) {
                return Err(cx.invalid(
                    links,
                    format!("{context} lists link `{link}` twice; expected different links"),
                ));
            }
            names.push(link.to_owned());
        }
        Ok((names, links))
    };
    // Exactly two links: the joint types that cannot be expanded pairwise.
    let links = |cx: &Context| -> Result<[String; 2]> {
        let (names, list) = all_links(cx)?;
        let n = names.len();
        <[String; 2]>::try_from(names).map_err(|_| {
            cx.invalid(
                list,
                format!(
                    "{context} lists {n} links; a `{}` joint joins exactly two: `links = \
                     [\"base\", \"moving\"]` (a revolute or weld joint may list more)",
                    type_name(kind)
                ),
            )
        })
    };
    // The pairs first–k of a revolute or weld joint, named `name`, then `name:k`.
    let pairs = |names: Vec<String>| -> Vec<(String, [String; 2])> {
        names[1..]
            .iter()
            .enumerate()
            .map(|(k, link)| {
                let joint = match k {
                    0 => name.to_owned(),
                    _ => expanded_name(name, link),
                };
                (joint, [names[0].clone(), link.clone()])
            })
            .collect()
    };
    let one = |kind: JointKind| vec![(name.to_owned(), kind)];
    Ok(match kind {
        Kind::Revolute => {
            let (names, _) = all_links(cx)?;
            let at = d.at.as_ref().ok_or_else(|| missing("at"))?;
            for link in &names {
                cx.point_on(at, link, geometry, &context)?;
            }
            pairs(names)
                .into_iter()
                .map(|(joint, links)| {
                    let at = at.get_ref().clone();
                    (joint, JointKind::Revolute { links, at })
                })
                .collect()
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
            one(JointKind::Prismatic { links, line, point })
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
            one(JointKind::PinInSlot { links, slot, pin })
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
            let radius_def = d.radius.as_ref().ok_or_else(|| missing("radius"))?;
            let what = format!("`radius` of {context}");
            let radius = cx.positive(radius_def, &what, Dimension::Length)?;
            if radius < limits::SMALLEST_RADIUS {
                let si = Spanned::new(radius_def.span(), Number::Literal(radius));
                cx.in_range(&si, &what, limits::SMALLEST_RADIUS..=limits::LENGTH, "m")?;
            }
            let sign = rolling_sense(geometry, pinion, rack);
            one(JointKind::RackPinion {
                pinion: pinion.name.clone(),
                rack: rack.name.clone(),
                radius: sign * radius,
            })
        }
        Kind::Gear => {
            let [a, b] = d.gears.as_ref().ok_or_else(|| missing("gears"))?.get_ref();
            let a = joint_of(cx, a, earlier, "revolute", &context)?;
            let b = joint_of(cx, b, earlier, "revolute", &context)?;
            let ratio = d.ratio.as_ref().ok_or_else(|| missing("ratio"))?;
            let value: f64 = cx.value(ratio)?;
            cx.in_range(
                &Spanned::new(ratio.span(), Number::Literal(value.abs())),
                &format!("the magnitude of `ratio` of {context}"),
                limits::RATIO,
                "",
            )?;
            one(JointKind::Gear {
                joints: [a.name.clone(), b.name.clone()],
                ratio: value,
            })
        }
        Kind::Weld => {
            let (names, _) = all_links(cx)?;
            if names[1..].iter().any(|l| l == GROUND) {
                let others: Vec<String> = (names.iter())
                    .filter(|l| *l != GROUND)
                    .map(|l| format!("\"{l}\""))
                    .collect();
                return Err(cx.invalid(
                    def,
                    format!(
                        "{context}: weld the other link to `{GROUND}` \
                    with `links = [\"{GROUND}\", {}]`",
                        others.join(", ")
                    ),
                ));
            }
            pairs(names)
                .into_iter()
                .map(|(joint, links)| (joint, JointKind::Weld { links }))
                .collect()
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
