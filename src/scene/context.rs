//! What every section's resolver shares: the explicit context of resolution ([`Context`]:
//! the source, units and parameters, turning numbers as written into checked values in SI
//! and spans into places), the resolved points and links ([`Geometry`]), and the checks of
//! names, lines and lengths that several sections make.
//!
//! The resolvers of the sections (`joints`, `drive`, `outputs`, `plot`, `solver`, dynamics,
//! balancing) build on this module; `resolve` orchestrates them.

use std::cell::RefCell;
use std::collections::{HashMap, HashSet};
use std::ops::Range;

use mechdiff_core::num_dual::Dual64;

use toml::Spanned;

use crate::error::{Error, Location, Result};

use super::bindings::Bindings;
use super::limits;
use super::model::{Link, Point};
use super::scalar::Carried;
use super::source::Source;
use super::units::{Dimension, Units};
use super::values::{Name, Number};

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
    pub(crate) parameters: &'a Bindings,
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
