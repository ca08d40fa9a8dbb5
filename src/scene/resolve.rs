//! From the file as written ([`super::format`]) to a checked [`Scene`]: units applied,
//! names resolved, required fields present for each joint type, the sketch consistent.
//!
//! Every error names `file:line:column` and what was expected there.

use std::cell::RefCell;
use std::collections::{BTreeMap, HashMap, HashSet};
use std::ops::Range;

use mechdiff_core::num_dual::Dual64;

use toml::Spanned;

use crate::error::{Error, Location, Result};

use super::bindings::Bindings;
use super::drive::nearest_turn;
use super::format::{self, JointDef, Name, SceneFile};
use super::limits;
use super::model::{DriveKind, Joint, JointKind, Link, Point, Scene};
use super::outputs;
use super::scalar::Carried;
use super::source::Source;
use super::units::{Dimension, Units};
use super::values::Number;

/// The name of the frame link, which every scene has.
pub const GROUND: &str = "ground";

/// Relative tolerance (of the joint's own size: its line's points and the point) for "this
/// point lies on that line".
const ON_LINE_TOLERANCE: f64 = 1e-9;

/// Whether two sketch points are the same to the rounding of their own coordinates (not
/// of the sketch's extent: a point far away elsewhere must not make a 1 m line "not
/// positive").
pub(crate) fn coincident(pa: [f64; 2], pb: [f64; 2]) -> bool {
    let apart =
        |i: usize| (pb[i] - pa[i]).abs() > 64.0 * f64::EPSILON * pa[i].abs().max(pb[i].abs());
    !(apart(0) || apart(1))
}

/// Checks a parsed file and resolves it into a [`Scene`], its formulas evaluated with the
/// scene's `parameters` ([`super::parameters::bindings`]).
///
/// # Errors
/// The first thing wrong in the file, at `file:line:column`.
pub fn resolve(file: &SceneFile, source: &Source, parameters: &Bindings) -> Result<Scene> {
    scene(file, &Context::new(source, units(&file.units), parameters))
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
    Ok(Scene {
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
        plot,
        solver,
        parameters: cx.parameters.ordered().to_vec(),
    })
}

/// The units a `[units]` section declares (SI where it is silent).
pub(crate) fn units(section: &format::UnitsSection) -> Units {
    fn or_default<T: Copy + Default>(unit: &Option<Spanned<T>>) -> T {
        unit.as_ref().map(|u| *u.get_ref()).unwrap_or_default()
    }
    Units {
        length: or_default(&section.length),
        angle: or_default(&section.angle),
        angular_velocity: or_default(&section.angular_velocity),
        angular_acceleration: or_default(&section.angular_acceleration),
        mass: or_default(&section.mass),
        force: or_default(&section.force),
        torque: or_default(&section.torque),
        inertia: or_default(&section.inertia),
    }
}

/// The most names an error lists (`the points are: …`): a scene may have 10⁵.
const LISTED_NAMES: usize = 40;

/// `names` joined for an error message: all of them up to [`LISTED_NAMES`], else the first
/// ones and how many there are in all.
pub(crate) fn listed(names: &[&str]) -> String {
    if names.len() <= LISTED_NAMES {
        return names.join(", ");
    }
    format!(
        "{}, … ({} in all)",
        names[..LISTED_NAMES].join(", "),
        names.len()
    )
}

/// The resolved points and links, for the checks of joints, drive and outputs.
pub(crate) struct Geometry<'a> {
    pub(crate) points: &'a [Point],
    pub(crate) names: &'a HashMap<&'a str, usize>,
    pub(crate) links: &'a [Link],
    /// Each link's index by name.
    link_index: HashMap<&'a str, usize>,
    /// Every (link, point) that a link carries, so that membership is found in constant
    /// time (a scene may hold 10⁵ points).
    carried: HashSet<(&'a str, &'a str)>,
    /// Every point carried by some link.
    moving_or_ground: HashSet<&'a str>,
}

impl<'a> Geometry<'a> {
    /// The geometry of the resolved `points` (with their indices by name) and `links`.
    pub(crate) fn new(
        points: &'a [Point],
        names: &'a HashMap<&'a str, usize>,
        links: &'a [Link],
    ) -> Self {
        let carried: HashSet<(&str, &str)> = links
            .iter()
            .flat_map(|l| l.points.iter().map(|p| (l.name.as_str(), p.as_str())))
            .collect();
        Geometry {
            points,
            names,
            links,
            link_index: links
                .iter()
                .enumerate()
                .map(|(k, l)| (l.name.as_str(), k))
                .collect(),
            moving_or_ground: carried.iter().map(|&(_, p)| p).collect(),
            carried,
        }
    }

    /// Sketch coordinates of a point known to exist.
    pub(crate) fn sketch(&self, name: &str) -> [f64; 2] {
        self.points[self.names[name]].sketch
    }

    pub(crate) fn link(&self, name: &str) -> Option<&Link> {
        self.link_index.get(name).map(|&k| &self.links[k])
    }

    /// Whether `link` carries `point`.
    pub(crate) fn carries(&self, link: &str, point: &str) -> bool {
        self.carried.contains(&(link, point))
    }

    /// Whether some link (the ground included) carries `point`.
    pub(crate) fn on_a_link(&self, point: &str) -> bool {
        self.moving_or_ground.contains(point)
    }

    /// Distance of `p` from the line through `a`, `b` in the sketch.
    pub(crate) fn off_line(&self, p: &str, [a, b]: [&str; 2]) -> f64 {
        let (p, a, b) = (self.sketch(p), self.sketch(a), self.sketch(b));
        let (ux, uy) = (b[0] - a[0], b[1] - a[1]);
        ((p[0] - a[0]) * uy - (p[1] - a[1]) * ux).abs() / ux.hypot(uy)
    }
}

/// The source, units and parameters, for turning spans into locations and numbers as
/// written into values in SI: the explicit context of resolution. With a seeded parameter
/// ([`Bindings::seed`]), the numbers read in [`Dual64`] carry their derivative with respect
/// to it, and the context keeps which formulas move with it and which of those were read
/// with their derivative ([`Context::not_carried`]).
pub(crate) struct Context<'a> {
    pub(crate) source: &'a Source,
    pub(crate) units: Units,
    parameters: &'a Bindings,
    /// In a context with a seeded parameter: the formulas that move with it.
    moving: Option<RefCell<Moving>>,
}

/// The formulas of a scene that move with the seeded parameter, by place.
#[derive(Debug, Default)]
struct Moving {
    /// Every formula read whose derivative is not zero.
    moving: HashSet<Range<usize>>,
    /// Those read in a scalar that carries the derivative.
    carried: HashSet<Range<usize>>,
}

impl<'a> Context<'a> {
    pub(crate) fn new(source: &'a Source, units: Units, parameters: &'a Bindings) -> Self {
        Context {
            source,
            units,
            parameters,
            moving: parameters.seed().map(|_| RefCell::default()),
        }
    }

    /// The value of the number `value` as written (in the file's unit), in the scalar `D`:
    /// a literal, or its formula evaluated with the scene's parameters.
    ///
    /// # Errors
    /// A formula that cannot be read or evaluated, at its place (the column inside the
    /// formula where the message names one).
    pub(crate) fn value<D: Carried>(&self, value: &Spanned<Number>) -> Result<D> {
        let v: D = (value.get_ref().value_in(self.parameters))
            .map_err(|message| self.source.formula_error(value.span(), &message))?;
        if let (Some(moving), Number::Formula(_)) = (&self.moving, value.get_ref()) {
            let moves = if D::CARRIES {
                v.tangent() != 0.0
            } else {
                (value.get_ref().value_in::<Dual64>(self.parameters)).is_ok_and(|d| d.eps != 0.0)
            };
            if moves {
                let mut moving = moving.borrow_mut();
                moving.moving.insert(value.span());
                if D::CARRIES {
                    moving.carried.insert(value.span());
                }
            }
        }
        Ok(v)
    }

    /// The formulas read so far that move with the seeded parameter and were not read with
    /// their derivative, in the file's order (none without a seeded parameter).
    pub(crate) fn not_carried(&self) -> Vec<Range<usize>> {
        let Some(moving) = &self.moving else {
            return Vec::new();
        };
        let moving = moving.borrow();
        let mut left: Vec<Range<usize>> = (moving.moving.iter())
            .filter(|span| !moving.carried.contains(*span))
            .cloned()
            .collect();
        left.sort_by_key(|span| span.start);
        left
    }

    /// The derivative (SI, per unit of the seeded parameter) of the number `value` of the
    /// file, of `dimension`; 0 without a seeded parameter or for a number that does not move.
    ///
    /// # Errors
    /// As [`Context::value`].
    pub(crate) fn tangent(&self, value: &Spanned<Number>, dimension: Dimension) -> Result<f64> {
        Ok(self.units.to_si(self.tangent_plain(value)?, dimension))
    }

    /// As [`Context::tangent`], for a number the file writes in SI (a ratio).
    ///
    /// # Errors
    /// As [`Context::value`].
    pub(crate) fn tangent_plain(&self, value: &Spanned<Number>) -> Result<f64> {
        Ok(self.value::<Dual64>(value)?.eps)
    }

    /// As [`Context::number`], in the scalar `D`: with its derivative.
    pub(crate) fn number_in<D: Carried>(
        &self,
        value: &Spanned<Number>,
        what: &str,
        dimension: Dimension,
    ) -> Result<D> {
        let si = self.number(value, what, dimension)?;
        self.carry(si, value, dimension)
    }

    /// As [`Context::positive`], in the scalar `D`: with its derivative.
    pub(crate) fn positive_in<D: Carried>(
        &self,
        value: &Spanned<Number>,
        what: &str,
        dimension: Dimension,
    ) -> Result<D> {
        let si = self.positive(value, what, dimension)?;
        self.carry(si, value, dimension)
    }

    /// The checked value `si` of `value` in `D`: with the derivative of `value` read in `D`
    /// (its real part is `si` itself, the `f64` resolution's, bit for bit).
    fn carry<D: Carried>(
        &self,
        si: f64,
        value: &Spanned<Number>,
        dimension: Dimension,
    ) -> Result<D> {
        let plain: D = self.carry_plain(si, value)?;
        Ok(D::with_tangent(
            si,
            self.units.to_si(plain.tangent(), dimension),
        ))
    }

    /// As [`Context::carry`], for a number the file writes in SI (a ratio): the checked
    /// value `x` of `value`, with the derivative of `value` read in `D`.
    ///
    /// # Errors
    /// As [`Context::value`].
    pub(crate) fn carry_plain<D: Carried>(&self, x: f64, value: &Spanned<Number>) -> Result<D> {
        if !D::CARRIES {
            return Ok(D::constant(x));
        }
        let carried: D = self.value(value)?;
        Ok(D::with_tangent(x, carried.tangent()))
    }

    pub(crate) fn at<T>(&self, spanned: &Spanned<T>) -> Location {
        self.source.location(spanned.span())
    }

    pub(crate) fn invalid<T>(&self, at: &Spanned<T>, message: impl Into<String>) -> Error {
        Error::Invalid {
            location: self.at(at),
            message: message.into(),
        }
    }

    /// A finite number in the file, converted to SI.
    pub(crate) fn number(
        &self,
        value: &Spanned<Number>,
        what: &str,
        dimension: Dimension,
    ) -> Result<f64> {
        let v: f64 = self.value(value)?;
        if !v.is_finite() {
            return Err(self.invalid(value, format!("{what} must be a finite number, found {v}")));
        }
        if let Some(e) =
            super::dimension::check(self.source, value.span(), what, dimension, &self.units)
        {
            return Err(e);
        }
        let si = self.units.to_si(v, dimension);
        let largest = limits::largest(dimension);
        if si.abs() > largest {
            let unit = self.units.symbol(dimension);
            return Err(Error::OutOfRange {
                location: self.at(value),
                what: what.to_owned(),
                value: format!("{} {unit}", Units::tidy(v)),
                expected: format!(
                    "a magnitude of at most {} {unit}",
                    Units::tidy(self.units.from_si(largest, dimension))
                ),
            });
        }
        Ok(si)
    }

    /// A number of a quantity the file writes in SI (kg, N, a ratio), within `range`.
    pub(crate) fn in_range(
        &self,
        value: &Spanned<Number>,
        what: &str,
        range: std::ops::RangeInclusive<f64>,
        unit: &str,
    ) -> Result<f64> {
        let v: f64 = self.value(value)?;
        if range.contains(&v) {
            return Ok(v);
        }
        let unit = if unit.is_empty() {
            String::new()
        } else {
            format!(" {unit}")
        };
        Err(Error::OutOfRange {
            location: self.at(value),
            what: what.to_owned(),
            value: format!("{}{unit}", Units::tidy(v)),
            expected: format!(
                "a number ≥ {}{unit} and ≤ {}{unit}",
                Units::tidy(*range.start()),
                Units::tidy(*range.end())
            ),
        })
    }

    /// A positive length in the file, converted to SI.
    pub(crate) fn positive(
        &self,
        value: &Spanned<Number>,
        what: &str,
        dimension: Dimension,
    ) -> Result<f64> {
        let v = self.number(value, what, dimension)?;
        if v <= 0.0 {
            return Err(Error::NonPositiveLength {
                location: self.at(value),
                what: what.to_owned(),
                value: self.value(value)?,
            });
        }
        Ok(v)
    }

    /// A reference to a point that must exist.
    pub(crate) fn point<'n>(
        &self,
        name: &'n Name,
        names: &HashMap<&str, usize>,
        context: &str,
    ) -> Result<&'n str> {
        if names.contains_key(name.get_ref().as_str()) {
            return Ok(name.get_ref());
        }
        let mut known: Vec<&str> = names.keys().copied().collect();
        known.sort_unstable();
        Err(Error::UnknownPoint {
            location: self.at(name),
            name: name.get_ref().clone(),
            context: context.to_owned(),
            known: listed(&known),
        })
    }

    /// A point that must also be carried by `link`.
    pub(crate) fn point_on<'n>(
        &self,
        name: &'n Name,
        link: &str,
        geometry: &Geometry,
        context: &str,
    ) -> Result<&'n str> {
        let point = self.point(name, geometry.names, context)?;
        if !geometry.carries(link, point) {
            return Err(self.invalid(
                name,
                format!(
                    "point `{point}` in {context} must be a point of link `{link}`; add it \
                    to `links.{link}`"
                ),
            ));
        }
        Ok(point)
    }

    /// A line: two distinct points of `link`.
    pub(crate) fn line(
        &self,
        line: &Spanned<[Name; 2]>,
        link: &str,
        geometry: &Geometry,
        context: &str,
    ) -> Result<[String; 2]> {
        let [a, b] = line.get_ref();
        let a = self.point_on(a, link, geometry, context)?;
        let b = self.point_on(b, link, geometry, context)?;
        let (pa, pb) = (geometry.sketch(a), geometry.sketch(b));
        let length = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
        if coincident(pa, pb) {
            return Err(Error::NonPositiveLength {
                location: self.at(line),
                what: format!("the line `{a}`–`{b}` in {context} (distance between its points)"),
                value: self.units.from_si(length, Dimension::Length),
            });
        }
        Ok([a.to_owned(), b.to_owned()])
    }

    /// A link that must exist.
    pub(crate) fn link<'n>(
        &self,
        name: &'n Name,
        geometry: &Geometry,
        context: &str,
    ) -> Result<&'n str> {
        if geometry.link(name.get_ref()).is_some() {
            return Ok(name.get_ref());
        }
        let known: Vec<&str> = geometry.links.iter().map(|l| l.name.as_str()).collect();
        Err(Error::UnknownName {
            location: self.at(name),
            what: "link",
            name: name.get_ref().clone(),
            context: context.to_owned(),
            known: listed(&known),
        })
    }

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

    /// Checks that point `p` lies on `line` in the sketch.
    pub(crate) fn on_line<T>(
        &self,
        at: &Spanned<T>,
        geometry: &Geometry,
        p: &str,
        line: &[String; 2],
        context: &str,
    ) -> Result<()> {
        let off = geometry.off_line(p, [&line[0], &line[1]]);
        // relative to the joint's own size (its line and point), so that a point elsewhere
        // in the sketch, or the sketch's overall scale, changes no verdict
        let size =
            mechdiff_core::geometry::extent([p, &line[0], &line[1]].map(|n| geometry.sketch(n)));
        if off > ON_LINE_TOLERANCE * size {
            return Err(self.invalid(
                at,
                format!(
                    "in the sketch, point `{p}` of {context} is {} {} off the line `{}`–`{}`; \
                    draw it on the line",
                    self.units.from_si(off, Dimension::Length),
                    self.units.symbol(Dimension::Length),
                    line[0],
                    line[1]
                ),
            ));
        }
        Ok(())
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
