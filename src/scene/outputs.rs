//! Checking `[[output]]` entries, and naming their columns.

use toml::Spanned;

use crate::error::{Error, Result};

use super::context::{Context, Geometry};
use super::format::{OutputDef, Quantity, Sense, TransmissionForm};
use super::model::{Drive, Joint, JointKind, Output, OutputKind};
use super::units::{Dimension, Units};

/// What an output reports when `quantities` is not given.
pub const DEFAULT_QUANTITIES: [Quantity; 3] = [
    Quantity::Position,
    Quantity::Velocity,
    Quantity::Acceleration,
];

pub(crate) fn resolve(
    cx: &Context,
    defs: &[Spanned<OutputDef>],
    geometry: &Geometry,
    joints: &[Joint],
    drive: &Drive,
) -> Result<Vec<Output>> {
    let mut outputs: Vec<Output> = Vec::with_capacity(defs.len());
    let mut names = std::collections::HashSet::with_capacity(defs.len());
    for def in defs {
        let output = resolve_one(cx, def, geometry, joints, drive)?;
        if !names.insert(output.name.clone()) {
            let at = def
                .get_ref()
                .name
                .as_ref()
                .map_or_else(|| cx.at(def), |n| cx.at(n));
            return Err(Error::Invalid {
                location: at,
                message: format!(
                    "a second output is named `{}`; give it another `name`",
                    output.name
                ),
            });
        }
        outputs.push(output);
    }
    Ok(outputs)
}

fn resolve_one(
    cx: &Context,
    def: &Spanned<OutputDef>,
    geometry: &Geometry,
    joints: &[Joint],
    drive: &Drive,
) -> Result<Output> {
    let d = def.get_ref();
    let expected = "expected exactly one of `point = \"P\"`, `angle = [\"P\", \"Q\"]`, \
                    `slider = \"joint\"`, `transmission_angle = \"follower link\"`";
    let (kind, default_name) = match (&d.point, &d.angle, &d.slider, &d.transmission_angle) {
        (None, None, None, Some(link)) => {
            if !geometry.links.iter().any(|l| l.name == *link.get_ref()) {
                let known: Vec<&str> = geometry.links.iter().map(|l| l.name.as_str()).collect();
                return Err(Error::UnknownName {
                    location: cx.at(link),
                    what: "link",
                    name: link.get_ref().clone(),
                    context: "`[[output]] transmission_angle`".to_owned(),
                    known: known.join(", "),
                });
            }
            let form = d
                .form
                .as_ref()
                .map_or(TransmissionForm::Unsigned, |f| *f.get_ref());
            (
                OutputKind::Transmission {
                    follower: link.get_ref().clone(),
                    form,
                    points: Vec::new(),
                },
                Some(format!("mu_{}", link.get_ref())),
            )
        }
        (Some(point), None, None, None) => {
            let name = cx.point(point, geometry.names, "`[[output]] point`")?;
            if !geometry.on_a_link(name) {
                return Err(cx.invalid(
                    point,
                    format!(
                        "point `{name}` is on no link, so it does \
                    not move with the mechanism; add it to a link in `[links]`"
                    ),
                ));
            }
            (OutputKind::Point(name.to_owned()), Some(name.to_owned()))
        }
        (None, Some(angle), None, None) => {
            let line = line(cx, angle, geometry, "`[[output]] angle`")?;
            let reference = d
                .reference
                .as_ref()
                .map(|r| self::line(cx, r, geometry, "`[[output]] reference`"))
                .transpose()?;
            let sense = d.sense.as_ref().map_or(Sense::Ccw, |s| *s.get_ref());
            (
                OutputKind::Angle {
                    line,
                    reference,
                    sense,
                },
                None,
            )
        }
        (None, None, Some(slider), None) => {
            let Some(joint) = joints.iter().find(|j| &j.name == slider.get_ref()) else {
                let known: Vec<&str> = joints.iter().map(|j| j.name.as_str()).collect();
                return Err(Error::UnknownName {
                    location: cx.at(slider),
                    what: "joint",
                    name: slider.get_ref().clone(),
                    context: "`[[output]] slider`".to_owned(),
                    known: known.join(", "),
                });
            };
            let kind = match &joint.kind {
                JointKind::Prismatic { line, point, .. } => OutputKind::Slider {
                    joint: joint.name.clone(),
                    point: point.clone(),
                    line: line.clone(),
                },
                JointKind::PinInSlot { slot, pin, .. } => OutputKind::Slider {
                    joint: joint.name.clone(),
                    point: pin.clone(),
                    line: slot.clone(),
                },
                other => {
                    return Err(cx.invalid(
                        slider,
                        format!(
                            "joint `{}` is {}; a slider output needs a prismatic or pin_in_slot \
                            joint",
                            joint.name,
                            other.type_name()
                        ),
                    ));
                }
            };
            (kind, Some(joint.name.clone()))
        }
        _ => return Err(cx.invalid(def, format!("`[[output]]`: {expected}"))),
    };
    let angle_only = d
        .reference
        .as_ref()
        .map(|r| r.span())
        .or(d.sense.as_ref().map(|s| s.span()));
    if !matches!(kind, OutputKind::Angle { .. })
        && let Some(span) = angle_only
    {
        return Err(Error::Invalid {
            location: cx.source.location(span),
            message: "`reference` and `sense` apply to an `angle` output only".to_owned(),
        });
    }
    let name = match (&d.name, default_name) {
        (Some(name), _) => {
            if !valid_name(name.get_ref()) {
                return Err(cx.invalid(
                    name,
                    "an output name must be non-empty and contain no spaces, commas or quotes",
                ));
            }
            name.get_ref().clone()
        }
        (None, Some(name)) => name,
        (None, None) => {
            return Err(cx.invalid(
                def,
                "an `angle` output needs a `name`, e.g. `name = \"psi\"`",
            ));
        }
    };
    let quantities = match &d.quantities {
        None => DEFAULT_QUANTITIES.to_vec(),
        Some(list) => {
            if list.get_ref().is_empty() {
                return Err(cx.invalid(
                    list,
                    "`quantities` is empty; expected some of: position, \
                    velocity_coefficient, acceleration_coefficient, jerk_coefficient, velocity, \
                    acceleration, jerk",
                ));
            }
            let mut seen: Vec<Quantity> = Vec::new();
            for q in list.get_ref() {
                if seen.contains(q.get_ref()) {
                    return Err(cx.invalid(q, "this quantity is listed twice"));
                }
                seen.push(*q.get_ref());
            }
            seen
        }
    };
    if drive.speed.is_none()
        && let Some(q) = quantities.iter().find(|q| q.is_time_derivative())
    {
        let at = d
            .quantities
            .as_ref()
            .map_or_else(|| cx.at(def), |l| cx.at(l));
        return Err(Error::Invalid {
            location: at,
            message: format!(
                "output `{name}` asks for the {} but `[drive]` has no `speed`; give `speed` \
                    (and `acceleration`) or ask only for position and coefficients",
                q.words()
            ),
        });
    }
    if let (Some(form), false) = (&d.form, matches!(kind, OutputKind::Transmission { .. })) {
        return Err(Error::Invalid {
            location: cx.source.location(form.span()),
            message: "`form` applies to a `transmission_angle` output only".to_owned(),
        });
    }
    if d.dead_positions && matches!(kind, OutputKind::Transmission { .. }) {
        return Err(cx.invalid(
            def,
            format!(
                "output `{name}`: `dead_positions` applies to an angle or slider output; the \
                 transmission angle's extremes are printed with the linkage metrics"
            ),
        ));
    }
    if d.dead_positions && matches!(kind, OutputKind::Point(_)) {
        return Err(cx.invalid(
            def,
            format!(
                "output `{name}`: `dead_positions` applies to an angle or slider output; \
                measure the point along a line with a slider or an angle"
            ),
        ));
    }
    Ok(Output {
        name,
        kind,
        quantities,
        dead_positions: d.dead_positions,
        location: cx.at(def),
    })
}

fn line(
    cx: &Context,
    line: &Spanned<[super::format::Name; 2]>,
    geometry: &Geometry,
    context: &str,
) -> Result<[String; 2]> {
    let [a, b] = line.get_ref();
    let a = cx.point(a, geometry.names, context)?;
    let b = cx.point(b, geometry.names, context)?;
    let (pa, pb) = (geometry.sketch(a), geometry.sketch(b));
    let length = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
    if super::context::coincident(pa, pb) {
        return Err(Error::NonPositiveLength {
            location: cx.at(line),
            what: format!("the line `{a}`–`{b}` of {context} (distance between its points)"),
            value: cx.units.from_si(length, Dimension::Length),
        });
    }
    for p in [a, b] {
        if !geometry.on_a_link(p) {
            return Err(cx.invalid(
                line,
                format!("point `{p}` in {context} is on no link; add it to a link in `[links]`"),
            ));
        }
    }
    Ok([a.to_owned(), b.to_owned()])
}

fn valid_name(name: &str) -> bool {
    !name.is_empty()
        && !name
            .chars()
            .any(|c| c.is_whitespace() || matches!(c, ',' | '"' | '\''))
}

/// One printed column: its header and how to convert its SI values for printing.
#[derive(Debug, Clone, PartialEq)]
pub struct Column {
    /// Header name, e.g. `psi'` or `vx_C`.
    pub name: String,
    /// Unit symbol, e.g. `rad/s`.
    pub unit: String,
    /// SI value per printed unit.
    pub factor: f64,
}

impl Column {
    /// `name [unit]`, as in the CSV header.
    pub fn header(&self) -> String {
        format!("{} [{}]", self.name, self.unit)
    }
}

/// The columns of one output, in the order its values are produced by the evaluation: for
/// each quantity, one column (angle, slider) or two (x and y of a point).
pub fn columns(output: &Output, units: &Units, drive: Dimension) -> Vec<Column> {
    let units = &units.for_outputs();
    let value = output.kind.dimension();
    let point = matches!(output.kind, OutputKind::Point(_));
    let (rate, rate2, rate3) = match value {
        Dimension::Angle => (
            Dimension::AngularVelocity,
            Dimension::AngularAcceleration,
            Dimension::AngularJerk,
        ),
        _ => (
            Dimension::Velocity,
            Dimension::Acceleration,
            Dimension::Jerk,
        ),
    };
    let n = &output.name;
    let mut columns = Vec::new();
    for q in &output.quantities {
        let (unit, factor) = match q {
            Quantity::Position => (units.symbol(value).to_owned(), units.factor(value)),
            Quantity::VelocityCoefficient
            | Quantity::AccelerationCoefficient
            | Quantity::JerkCoefficient => {
                let order = q.order() as u32;
                (
                    units.coefficient_symbol(value, drive, order),
                    units.coefficient_factor(value, drive, order),
                )
            }
            Quantity::Velocity => (units.symbol(rate).to_owned(), units.factor(rate)),
            Quantity::Acceleration => (units.symbol(rate2).to_owned(), units.factor(rate2)),
            Quantity::Jerk => (units.symbol(rate3).to_owned(), units.factor(rate3)),
        };
        let names: Vec<String> = match (q, point) {
            (Quantity::Position, true) => vec![format!("x_{n}"), format!("y_{n}")],
            (Quantity::VelocityCoefficient, true) => vec![format!("x_{n}'"), format!("y_{n}'")],
            (Quantity::AccelerationCoefficient, true) => {
                vec![format!("x_{n}''"), format!("y_{n}''")]
            }
            (Quantity::Velocity, true) => vec![format!("vx_{n}"), format!("vy_{n}")],
            (Quantity::Acceleration, true) => vec![format!("ax_{n}"), format!("ay_{n}")],
            (Quantity::JerkCoefficient, true) => vec![format!("x_{n}'''"), format!("y_{n}'''")],
            (Quantity::Jerk, true) => vec![format!("jx_{n}"), format!("jy_{n}")],
            (Quantity::Position, false) => vec![n.clone()],
            (Quantity::VelocityCoefficient, false) => vec![format!("{n}'")],
            (Quantity::AccelerationCoefficient, false) => vec![format!("{n}''")],
            (Quantity::Velocity, false) => vec![format!("{n}_dot")],
            (Quantity::Acceleration, false) => vec![format!("{n}_ddot")],
            (Quantity::JerkCoefficient, false) => vec![format!("{n}'''")],
            (Quantity::Jerk, false) => vec![format!("{n}_dddot")],
        };
        columns.extend(names.into_iter().map(|name| Column {
            name,
            unit: unit.clone(),
            factor,
        }));
    }
    columns
}

/// Finds, for every `transmission_angle` output of `scene`, the four-bar or slider-crank
/// loop whose follower it names ([`mechdiff_core::metrics::Loops::find`]) and records the
/// points its μ is read from.
///
/// # Errors
/// The model's errors; a link that is no recognised loop's follower, at the output, with
/// the followers there are (or why the scene has none).
pub(crate) fn locate_transmissions(scene: &mut super::model::Scene) -> Result<()> {
    use super::model::JointKind as J;
    if !(scene.outputs.iter()).any(|o| matches!(o.kind, OutputKind::Transmission { .. })) {
        return Ok(());
    }
    let m = super::build::mechanism(scene)?;
    let found = mechdiff_core::metrics::Loops::find(&m);
    let joint = |name: &str| {
        scene
            .joints
            .iter()
            .find(|j| j.name == name)
            .map(|j| &j.kind)
    };
    let pin = |name: &str| match joint(name) {
        Some(J::Revolute { at, .. }) => Some(at.clone()),
        Some(J::PinInSlot { pin, .. }) => Some(pin.clone()),
        _ => None,
    };
    let line = |name: &str| match joint(name) {
        Some(J::Prismatic { line, .. }) => Some(line.to_vec()),
        Some(J::PinInSlot { slot, .. }) => Some(slot.to_vec()),
        _ => None,
    };
    // (follower, points, the loop in words)
    let mut followers: Vec<(String, Option<Vec<String>>, String)> = Vec::new();
    if let Ok(loops) = &found {
        for l in &loops.four_bars {
            let [_, a, b, o] = l.joints.each_ref().map(|j| pin(j));
            let points = (b.zip(a).zip(o)).map(|((b, a), o)| vec![b, a, o]);
            let words = format!("four-bar {}", l.links.join("–"));
            followers.push((l.links[3].clone(), points, words));
        }
        for l in &loops.slider_cranks {
            let follower = l.slider.clone().unwrap_or_else(|| l.rod.clone());
            let (a, b) = (pin(&l.joints[1]), pin(&l.joints[2]));
            let path = line(l.joints.last().map_or("", String::as_str));
            let points = (b.zip(a).zip(path)).map(|((b, a), path)| {
                let mut points = vec![b, a];
                points.extend(path);
                points
            });
            let words = format!("slider-crank {}–{}–{}", l.frame, l.crank, l.rod);
            followers.push((follower, points, words));
        }
    }
    for output in &mut scene.outputs {
        let OutputKind::Transmission {
            follower, points, ..
        } = &mut output.kind
        else {
            continue;
        };
        match followers.iter().find(|(f, ..)| f == follower) {
            Some((_, Some(found), _)) => *points = found.clone(),
            _ => {
                let known: Vec<String> = (followers.iter())
                    .map(|(f, _, words)| format!("`{f}` ({words})"))
                    .collect();
                let why = match (&found, known.is_empty()) {
                    (Err(e), _) => format!("the model's loops could not be found: {e}"),
                    (Ok(_), true) => "the scene has no four-bar or slider-crank loop driven \
                                      through its input (see `mechdiff check`)"
                        .to_owned(),
                    (Ok(_), false) => format!("the followers there are: {}", known.join(", ")),
                };
                return Err(Error::Invalid {
                    location: output.location.clone(),
                    message: format!(
                        "output `{}`: link `{follower}` is the follower of no four-bar or \
                         slider-crank loop; {why}",
                        output.name
                    ),
                });
            }
        }
    }
    Ok(())
}
