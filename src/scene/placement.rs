//! `[points]`: every sketch point placed from its definition — coordinates, a polar offset,
//! or a construction from lengths ([`super::construct`]) — after the points it is built
//! from, with a message naming the construction and its lengths when it has no solution.

use std::collections::{BTreeMap, HashMap};

use toml::Spanned;

use crate::error::{Error, Result};

use super::construct::{self, NoSolution};
use super::format::{Name, PointDef};
use super::model::Point;
use super::resolve::Context;
use super::units::{Dimension, Units};

/// The definitions of the points by name, for placing them in order.
type Defs<'a> = HashMap<&'a str, &'a Spanned<PointDef>>;

impl Context<'_> {
    /// The points of `[points]` in the order written, each at its sketch position (SI).
    pub(crate) fn points(
        &self,
        table: &Spanned<BTreeMap<Name, Spanned<PointDef>>>,
    ) -> Result<Vec<Point>> {
        let mut entries: Vec<(&Name, &Spanned<PointDef>)> = table.get_ref().iter().collect();
        entries.sort_by_key(|(name, _)| name.span().start);
        if entries.is_empty() {
            return Err(self.invalid(table, "`[points]` is empty; expected `NAME = [x, y]` lines"));
        }
        let defs: Defs = entries
            .iter()
            .map(|(n, d)| (n.get_ref().as_str(), *d))
            .collect();
        let mut placed: HashMap<String, [f64; 2]> = HashMap::new();
        let mut points = Vec::with_capacity(entries.len());
        for (name, _) in &entries {
            let sketch = self.place(name.get_ref(), &defs, &mut placed, &mut Vec::new())?;
            points.push(Point {
                name: name.get_ref().clone(),
                sketch,
                location: self.at(name),
            });
        }
        Ok(points)
    }

    /// Sketch coordinates of a point, placing the points it is built from first.
    fn place(
        &self,
        name: &str,
        defs: &Defs,
        placed: &mut HashMap<String, [f64; 2]>,
        chain: &mut Vec<String>,
    ) -> Result<[f64; 2]> {
        if let Some(&xy) = placed.get(name) {
            return Ok(xy);
        }
        let def = defs[name];
        // Places a point this one is built from, refusing a cycle.
        let mut from = |other: &Name, what: &str, placed: &mut HashMap<String, [f64; 2]>| {
            let names: HashMap<&str, usize> = defs.keys().map(|&k| (k, 0)).collect();
            let origin = self.point(other, &names, &format!("the {what} of point `{name}`"))?;
            if chain.iter().any(|c| c == origin) || origin == name {
                return Err(self.invalid(
                    other,
                    format!(
                        "point `{name}` is built from `{origin}`, which is built from `{name}` \
                        (a cycle); place one of them by `[x, y]`"
                    ),
                ));
            }
            chain.push(name.to_owned());
            let xy = self.place(origin, defs, placed, chain);
            chain.pop();
            xy
        };
        let length = |v: &Spanned<f64>, what: &str| {
            self.positive(v, &format!("{what} of point `{name}`"), Dimension::Length)
        };
        let xy = match def.get_ref() {
            PointDef::Xy(xy) => {
                let what = |axis: &str| format!("the {axis} coordinate of point `{name}`");
                let coordinate = |v: f64, axis: &str| {
                    let v = Spanned::new(def.span(), v);
                    self.number(&v, &what(axis), Dimension::Length)
                };
                [coordinate(xy[0], "x")?, coordinate(xy[1], "y")?]
            }
            PointDef::Polar {
                from: origin,
                length: l,
                angle,
            } => {
                let l = length(l, "`length`")?;
                let angle = self.number(
                    angle,
                    &format!("`angle` of point `{name}`"),
                    Dimension::Angle,
                )?;
                let o = from(origin, "polar definition", placed)?;
                construct::polar(o, l, angle)
            }
            PointDef::Circles {
                circles,
                radii,
                side,
            } => {
                let [a, b] = circles.get_ref();
                let r1 = length(&radii[0], "the first radius")?;
                let r2 = length(&radii[1], "the second radius")?;
                let ca = from(a, "circles", placed)?;
                let cb = from(b, "circles", placed)?;
                construct::circles(ca, r1, cb, r2, *side.get_ref()).map_err(|why| {
                    let what = format!(
                        "point `{name}`: the circle about `{}` of radius {} and the circle \
                         about `{}` of radius {}",
                        a.get_ref(),
                        self.length_text(r1),
                        b.get_ref(),
                        self.length_text(r2)
                    );
                    self.no_solution(def, &what, why)
                })?
            }
            PointDef::CircleLine {
                circle,
                radius,
                line,
                along,
            } => {
                let r = length(radius, "`radius`")?;
                let [p, q] = line.get_ref();
                let c = from(circle, "circle", placed)?;
                let ends = [from(p, "line", placed)?, from(q, "line", placed)?];
                construct::circle_line(c, r, ends, *along.get_ref()).map_err(|why| {
                    let what = format!(
                        "point `{name}`: the circle about `{}` of radius {} and the line \
                         `{}`–`{}`",
                        circle.get_ref(),
                        self.length_text(r),
                        p.get_ref(),
                        q.get_ref()
                    );
                    self.no_solution(def, &what, why)
                })?
            }
        };
        placed.insert(name.to_owned(), xy);
        Ok(xy)
    }

    /// An SI length in the file's unit, with the unit.
    fn length_text(&self, si: f64) -> String {
        let unit = self.units.symbol(Dimension::Length);
        format!(
            "{} {unit}",
            Units::tidy(self.units.from_si(si, Dimension::Length))
        )
    }

    /// The error for a construction without a point: which, with its lengths, and why.
    fn no_solution(&self, def: &Spanned<PointDef>, what: &str, why: NoSolution) -> Error {
        let reason = match why {
            NoSolution::Concentric => {
                "do not meet: their centres coincide; build the point from two distinct points"
                    .to_owned()
            }
            NoSolution::TooFar { distance } => format!(
                "do not meet: the centres are {} apart, more than the sum of the radii; \
                 lengthen a radius or bring the centres closer",
                self.length_text(distance)
            ),
            NoSolution::Inside { distance } => format!(
                "do not meet: the centres are {} apart, less than the difference of the radii \
                 (one circle lies inside the other); shorten the longer radius",
                self.length_text(distance)
            ),
            NoSolution::Misses { distance } => format!(
                "do not meet: the line passes {} from the centre, more than the radius; \
                 lengthen the radius or move the line",
                self.length_text(distance)
            ),
            NoSolution::NoLine => "cannot meet: the line's two points coincide".to_owned(),
        };
        Error::Unconstructible {
            location: self.at(def),
            message: format!("{what} {reason}"),
        }
    }
}
