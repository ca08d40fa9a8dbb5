//! `[points]`: every sketch point placed from its definition — coordinates, a polar offset,
//! or a construction from lengths ([`super::construct`]) — after the points it is built
//! from, with a message naming the construction and its lengths when it has no solution.

use std::collections::{BTreeMap, HashMap, HashSet};

use toml::Spanned;

use crate::error::{Error, Result};

use super::construct::{self, NoSolution};
use super::context::Context;
use super::format::{Name, PointDef};
use super::model::Point;
use super::scalar::Carried;
use super::units::{Dimension, Units};
use super::values::Number;

/// The definitions of the points by name, for placing them in order.
type Defs<'a> = HashMap<&'a str, &'a Spanned<PointDef>>;

impl Context<'_> {
    /// The points of `[points]` in the order written, each at its sketch position (SI).
    pub(crate) fn points(
        &self,
        table: &Spanned<BTreeMap<Name, Spanned<PointDef>>>,
    ) -> Result<Vec<Point>> {
        Ok(self.points_in::<f64>(table)?.1)
    }

    /// As [`Context::points`], each point's coordinates also in the scalar `D` (with their
    /// derivatives, when the context carries a tangent), in the same order.
    pub(crate) fn points_in<D: Carried>(
        &self,
        table: &Spanned<BTreeMap<Name, Spanned<PointDef>>>,
    ) -> Result<(Vec<[D; 2]>, Vec<Point>)> {
        let mut entries: Vec<(&Name, &Spanned<PointDef>)> = table.get_ref().iter().collect();
        entries.sort_by_key(|(name, _)| name.span().start);
        if entries.is_empty() {
            return Err(self.invalid(table, "`[points]` is empty; expected `NAME = [x, y]` lines"));
        }
        let defs: Defs = entries
            .iter()
            .map(|(n, d)| (n.get_ref().as_str(), *d))
            .collect();
        let mut placed: HashMap<&str, [D; 2]> = HashMap::with_capacity(entries.len());
        for (name, _) in &entries {
            self.place(name.get_ref(), &defs, &mut placed)?;
        }
        let carried: Vec<[D; 2]> = (entries.iter())
            .map(|(name, _)| placed[name.get_ref().as_str()])
            .collect();
        let points = (entries.iter().zip(&carried))
            .map(|((name, _), xy)| Point {
                name: name.get_ref().clone(),
                sketch: [xy[0].re(), xy[1].re()],
                location: self.at(name),
            })
            .collect();
        Ok((carried, points))
    }

    /// Places `name` after the points it is built from, depth first with a stack of its
    /// own (so a chain of any length is placed without recursion).
    fn place<'d, D: Carried>(
        &self,
        name: &'d str,
        defs: &Defs<'d>,
        placed: &mut HashMap<&'d str, [D; 2]>,
    ) -> Result<()> {
        let mut path: Vec<&'d str> = vec![name];
        let mut on_path: HashSet<&'d str> = HashSet::from([name]);
        while let Some(&top) = path.last() {
            if placed.contains_key(top) {
                path.pop();
                on_path.remove(top);
                continue;
            }
            let def = defs[top];
            let mut next = None;
            for (used, what) in sources(def.get_ref()) {
                let context = format!("the {what} of point `{top}`");
                let origin = self.point_of(used, defs, &context)?;
                if on_path.contains(origin) {
                    return Err(self.invalid(
                        used,
                        format!(
                            "point `{top}` is built from `{origin}`, which is built from \
                             `{top}` (a cycle); place one of them by `[x, y]`"
                        ),
                    ));
                }
                if !placed.contains_key(origin) {
                    next = Some(origin);
                    break;
                }
            }
            match next {
                Some(origin) => {
                    path.push(origin);
                    on_path.insert(origin);
                }
                None => {
                    let xy = self.construct(top, def, placed)?;
                    placed.insert(top, xy);
                }
            }
        }
        Ok(())
    }

    /// A point name that must be defined in `[points]`.
    fn point_of<'d>(&self, used: &'d Name, defs: &Defs<'d>, context: &str) -> Result<&'d str> {
        if defs.contains_key(used.get_ref().as_str()) {
            return Ok(used.get_ref());
        }
        let mut known: Vec<&str> = defs.keys().copied().collect();
        known.sort_unstable();
        Err(Error::UnknownPoint {
            location: self.at(used),
            name: used.get_ref().clone(),
            context: context.to_owned(),
            known: super::context::listed(&known),
        })
    }

    /// Sketch coordinates of a point whose sources are placed.
    fn construct<D: Carried>(
        &self,
        name: &str,
        def: &Spanned<PointDef>,
        placed: &HashMap<&str, [D; 2]>,
    ) -> Result<[D; 2]> {
        let at = |p: &Name| placed[p.get_ref().as_str()];
        let length = |v: &Spanned<Number>, what: &str| {
            self.positive_in::<D>(v, &format!("{what} of point `{name}`"), Dimension::Length)
        };
        Ok(match def.get_ref() {
            PointDef::Xy([x, y]) => {
                let coordinate = |v: &Spanned<Number>, axis: &str| {
                    let what = format!("the {axis} coordinate of point `{name}`");
                    self.number_in::<D>(v, &what, Dimension::Length)
                };
                [coordinate(x, "x")?, coordinate(y, "y")?]
            }
            PointDef::Polar {
                from,
                length: l,
                angle,
            } => {
                let l = length(l, "`length`")?;
                let angle = self.number_in::<D>(
                    angle,
                    &format!("`angle` of point `{name}`"),
                    Dimension::Angle,
                )?;
                construct::polar(at(from), l, angle)
            }
            PointDef::Circles {
                circles,
                radii,
                side,
            } => {
                let [a, b] = circles.get_ref();
                let r1 = length(&radii[0], "the first radius")?;
                let r2 = length(&radii[1], "the second radius")?;
                construct::circles(at(a), r1, at(b), r2, *side.get_ref()).map_err(|why| {
                    let what = format!(
                        "point `{name}`: the circle about `{}` of radius {} and the circle \
                         about `{}` of radius {}",
                        a.get_ref(),
                        self.length_text(r1.re()),
                        b.get_ref(),
                        self.length_text(r2.re())
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
                construct::circle_line(at(circle), r, [at(p), at(q)], *along.get_ref()).map_err(
                    |why| {
                        let what = format!(
                            "point `{name}`: the circle about `{}` of radius {} and the line \
                             `{}`–`{}`",
                            circle.get_ref(),
                            self.length_text(r.re()),
                            p.get_ref(),
                            q.get_ref()
                        );
                        self.no_solution(def, &what, why)
                    },
                )?
            }
        })
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

/// The points a definition is built from, each with what it is for (for messages).
fn sources(def: &PointDef) -> Vec<(&Name, &'static str)> {
    match def {
        PointDef::Xy(_) => Vec::new(),
        PointDef::Polar { from, .. } => vec![(from, "polar definition")],
        PointDef::Circles { circles, .. } => {
            let [a, b] = circles.get_ref();
            vec![(a, "circles"), (b, "circles")]
        }
        PointDef::CircleLine { circle, line, .. } => {
            let [p, q] = line.get_ref();
            vec![(circle, "circle"), (p, "line"), (q, "line")]
        }
    }
}
