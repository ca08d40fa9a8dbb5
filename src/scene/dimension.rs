//! The dimension of a scene's formula, inferred over its parse tree (the symbolic engine's
//! graph), so that a parameter written with a unit of its own (`{ value = 0.86, unit =
//! "lb" }`) is never silently used as a number of another dimension (`"2*L"` as a length).
//!
//! A dimension is a list of exponents over mass, length, time and angle (angles are a
//! dimension of their own, as the scene's units treat them), with the SI value of one unit
//! of the formula's number (its scale: the file's units of the parameters it uses,
//! multiplied together). A literal number, a constant and a parameter without a unit of its
//! own are *free*: they take the dimension of the place they are used, as every number of
//! the file does. A pure number of scale 1 (`sin(a)`, `L/L`) is free too.

use std::collections::HashMap;

use mechdiff_core::symbolic::{Binary, Graph, Id, Node, Unary};

use super::source::Source;
use super::units::{Dimension, Units};
use crate::error::Error;

/// Exponents over (mass, length, time, angle).
type Exponents = [i32; 4];

/// The names of the base dimensions, in the order of [`Exponents`].
const BASE: [&str; 4] = ["mass", "length", "time", "angle"];

/// Two scales are one unit when they agree to this relative tolerance (a few roundings of
/// products of unit factors).
const SAME_SCALE: f64 = 1e-12;

/// Every dimension a scene writes, for naming an inferred one.
const NAMED: [Dimension; 13] = [
    Dimension::Length,
    Dimension::Angle,
    Dimension::Velocity,
    Dimension::Acceleration,
    Dimension::AngularVelocity,
    Dimension::AngularAcceleration,
    Dimension::Mass,
    Dimension::Density,
    Dimension::Force,
    Dimension::Torque,
    Dimension::MomentOfInertia,
    Dimension::Jerk,
    Dimension::AngularJerk,
];

/// A quantity that is not free: its exponents and the SI value of one unit of its number.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Quantity {
    exponents: Exponents,
    scale: f64,
}

/// The exponents of a dimension of the scene's units.
fn exponents(dimension: Dimension) -> Exponents {
    match dimension {
        Dimension::Length => [0, 1, 0, 0],
        Dimension::Angle => [0, 0, 0, 1],
        Dimension::Velocity => [0, 1, -1, 0],
        Dimension::Acceleration => [0, 1, -2, 0],
        Dimension::Jerk => [0, 1, -3, 0],
        Dimension::AngularVelocity => [0, 0, -1, 1],
        Dimension::AngularAcceleration => [0, 0, -2, 1],
        Dimension::AngularJerk => [0, 0, -3, 1],
        Dimension::Mass => [1, 0, 0, 0],
        Dimension::Density => [1, -1, 0, 0],
        Dimension::Force => [1, 1, -2, 0],
        Dimension::Torque => [1, 2, -2, 0],
        Dimension::MomentOfInertia => [1, 2, 0, 0],
    }
}

impl Quantity {
    /// A number in the file's unit of `dimension`.
    pub(crate) fn of(dimension: Dimension, units: &Units) -> Quantity {
        Quantity {
            exponents: exponents(dimension),
            scale: units.factor(dimension),
        }
    }

    /// The quantity, or free for a pure number of scale 1.
    fn tidy(self) -> Option<Quantity> {
        let pure = self.exponents == [0; 4] && same(self.scale, 1.0);
        (!pure).then_some(self)
    }

    /// The dimension in words, with its article (`"a mass"`, `"an area"`).
    pub(crate) fn words(&self) -> String {
        if let Some(d) = NAMED.iter().find(|d| exponents(**d) == self.exponents) {
            return d.words().to_owned();
        }
        match self.exponents {
            [0, 0, 0, 0] => "a pure number".to_owned(),
            [0, 2, 0, 0] => "an area (a length squared)".to_owned(),
            [0, 3, 0, 0] => "a volume (a length cubed)".to_owned(),
            e => {
                let parts: Vec<String> = (e.iter().zip(BASE))
                    .filter(|(n, _)| **n != 0)
                    .map(|(n, name)| match n {
                        1 => name.to_owned(),
                        n => format!("{name}^{n}"),
                    })
                    .collect();
                format!("a quantity of dimension {}", parts.join("·"))
            }
        }
    }

    fn times(self, other: Quantity, sign: i32) -> Option<Quantity> {
        let mut exponents = self.exponents;
        for (e, o) in exponents.iter_mut().zip(other.exponents) {
            *e += sign * o;
        }
        Quantity {
            exponents,
            scale: self.scale * other.scale.powi(sign),
        }
        .tidy()
    }

    /// The quantity to the rational power `numerator / denominator`, if its exponents stay
    /// whole.
    fn power(self, numerator: i32, denominator: i32) -> Option<Quantity> {
        let mut exponents = self.exponents;
        for e in &mut exponents {
            let n = *e * numerator;
            if n % denominator != 0 {
                return None;
            }
            *e = n / denominator;
        }
        Some(Quantity {
            exponents,
            scale: self
                .scale
                .powf(f64::from(numerator) / f64::from(denominator)),
        })
    }

    fn is_angle(&self) -> bool {
        self.exponents == exponents(Dimension::Angle)
    }
}

fn same(a: f64, b: f64) -> bool {
    (a - b).abs() <= SAME_SCALE * a.abs().max(b.abs())
}

/// What a scene's parameters are: those with a unit of their own, and those defined by a
/// formula of such parameters; every other parameter is free.
#[derive(Debug, Clone, Default)]
pub(crate) struct ParameterDimensions {
    /// name → (its quantity, why, in words: "unit `lb` of parameter `L` is a mass").
    by_name: HashMap<String, (Quantity, String)>,
    /// name → its unit, for the parameters with a unit of their own.
    units: HashMap<String, String>,
}

impl ParameterDimensions {
    /// Records a parameter with a unit of its own.
    pub(crate) fn with_unit(&mut self, name: &str, unit: &str, quantity: Quantity) {
        let why = format!(
            "unit `{unit}` of parameter `{name}` is {}",
            quantity.words()
        );
        self.by_name.insert(name.to_owned(), (quantity, why));
        self.units.insert(name.to_owned(), unit.to_owned());
    }

    /// Records a parameter defined by `formula`, of the inferred `quantity` (free: nothing
    /// to record).
    pub(crate) fn with_formula(&mut self, name: &str, formula: &str, quantity: Option<Quantity>) {
        if let Some(q) = quantity {
            let why = format!("parameter `{name}` = \"{formula}\" is {}", q.words());
            self.by_name.insert(name.to_owned(), (q, why));
        }
    }

    /// Whether every parameter is free (nothing to check).
    pub(crate) fn is_empty(&self) -> bool {
        self.by_name.is_empty()
    }

    /// Why the parameters of `graph` that are not free are what they are, joined by `; `.
    fn why(&self, graph: &Graph, root: Id) -> String {
        let whys: Vec<&str> = (graph.symbols(&[root]).iter())
            .filter_map(|s| self.by_name.get(*s).map(|(_, why)| why.as_str()))
            .collect();
        whys.join("; ")
    }
}

/// The dimension of the formula `text` (parsed as `graph`, `root`): `Ok(None)` when free.
///
/// # Errors
/// A message naming the formula, what it combines that cannot be combined (a length plus a
/// time, the sine of a length, the square root of a length), the parameters involved and
/// the fix.
pub(crate) fn infer(
    text: &str,
    graph: &Graph,
    root: Id,
    parameters: &ParameterDimensions,
) -> Result<Option<Quantity>, String> {
    let reachable = graph.reachable(&[root]);
    let mut found: Vec<Option<Quantity>> = vec![None; root.index() + 1];
    let fail = |what: String, fix: &str| {
        let why = parameters.why(graph, root);
        Err(format!("the formula \"{text}\" {what}, since {why}; {fix}"))
    };
    for (i, node) in graph.nodes().iter().enumerate().take(root.index() + 1) {
        if !reachable[i] {
            continue;
        }
        let of = |id: Id| found[id.index()];
        let quantity = match node {
            Node::Num(_) => None,
            Node::Sym(name) => parameters.by_name.get(&**name).map(|(q, _)| *q),
            Node::Unary(op, a) => match (op, of(*a)) {
                (_, None) => None,
                (Unary::Neg | Unary::Abs, q) => q,
                (Unary::Sqrt | Unary::Cbrt, Some(q)) => {
                    let (root_of, n) = match op {
                        Unary::Sqrt => ("square root", 2),
                        _ => ("cube root", 3),
                    };
                    match q.power(1, n) {
                        Some(q) => q.tidy(),
                        None => {
                            return fail(
                                format!("takes the {root_of} of {}", q.words()),
                                "that has no dimension: use parameters whose root is a \
                                 length, a mass, …",
                            );
                        }
                    }
                }
                (Unary::Sin | Unary::Cos | Unary::Tan, Some(q)) if q.is_angle() => {
                    if !same(q.scale, 1.0) {
                        return fail(
                            format!(
                                "takes the {op} of an angle in the file's angle unit ({} rad), \
                                 and {op} takes radians",
                                Units::tidy(q.scale)
                            ),
                            &format!(
                                "multiply the angle by {} inside {op}, or set `[units] angle \
                                 = \"rad\"`",
                                Units::tidy(q.scale)
                            ),
                        );
                    }
                    None
                }
                (_, Some(q)) => {
                    let takes = if matches!(op, Unary::Sin | Unary::Cos | Unary::Tan) {
                        "a pure number or an angle"
                    } else {
                        "a pure number"
                    };
                    return fail(
                        format!("takes the {op} of {}, and {op} takes {takes}", q.words()),
                        "divide by a parameter of the same dimension first",
                    );
                }
            },
            Node::Powi(a, n) => of(*a).and_then(|q| q.power(*n, 1).and_then(Quantity::tidy)),
            Node::Binary(op, a, b) => match (op, of(*a), of(*b)) {
                (Binary::Mul, Some(x), Some(y)) => x.times(y, 1),
                (Binary::Div, Some(x), Some(y)) => x.times(y, -1),
                (Binary::Div, None, Some(y)) => Quantity {
                    exponents: [0; 4],
                    scale: 1.0,
                }
                .times(y, -1),
                (Binary::Mul | Binary::Div, x, y) => x.or(y),
                (Binary::Add | Binary::Sub | Binary::Hypot, x, y) => match sum(x, y) {
                    Ok(q) => q,
                    Err((x, y)) => {
                        let verb = match op {
                            Binary::Hypot => "takes the hypot of",
                            _ => "adds",
                        };
                        let (a, b) = (x.words(), y.words());
                        let what = if x.exponents == y.exponents {
                            format!("{verb} {a} and {b} in different units ({a} plus {b})")
                        } else {
                            format!("{verb} {a} and {b} ({a} plus {b})")
                        };
                        return fail(
                            what,
                            &format!("make every term {a}, in the file's unit of it"),
                        );
                    }
                },
                (Binary::Atan2, x, y) => match sum(x, y) {
                    Ok(None) => None,
                    Ok(Some(_)) => Some(Quantity {
                        exponents: exponents(Dimension::Angle),
                        scale: 1.0,
                    }),
                    Err((x, y)) => {
                        return fail(
                            format!("takes atan2 of {} and {}", x.words(), y.words()),
                            "atan2(y, x) takes two numbers of one dimension in one unit",
                        );
                    }
                },
                (Binary::Powf, x, y) => {
                    if let Some(y) = y {
                        return fail(
                            format!("raises to a power that is {}", y.words()),
                            "an exponent is a pure number",
                        );
                    }
                    match (x, graph.as_number(*b)) {
                        (None, _) => None,
                        (Some(x), Some(p)) => match rational(p).and_then(|(n, d)| x.power(n, d)) {
                            Some(q) => q.tidy(),
                            None => {
                                return fail(
                                    format!("raises {} to the power {p}", x.words()),
                                    "that has no dimension: use a whole power, or a half \
                                     of an even one",
                                );
                            }
                        },
                        (Some(x), None) => {
                            return fail(
                                format!("raises {} to a power that is not a constant", x.words()),
                                "only a pure number can be raised to a variable power",
                            );
                        }
                    }
                }
            },
            Node::Select(_, [a, b, then, otherwise]) => {
                if sum(of(*a), of(*b)).is_err() {
                    return fail(
                        "compares numbers of different dimensions".to_owned(),
                        "compare numbers of one dimension",
                    );
                }
                match sum(of(*then), of(*otherwise)) {
                    Ok(q) => q,
                    Err(_) => {
                        return fail(
                            "chooses between numbers of different dimensions".to_owned(),
                            "make both branches of one dimension",
                        );
                    }
                }
            }
        };
        found[i] = quantity;
    }
    Ok(found[root.index()])
}

/// The quantity of a sum: the terms' common one (a free term takes the other's), or the two
/// that differ.
fn sum(x: Option<Quantity>, y: Option<Quantity>) -> Result<Option<Quantity>, (Quantity, Quantity)> {
    match (x, y) {
        (Some(x), Some(y)) if x.exponents != y.exponents || !same(x.scale, y.scale) => Err((x, y)),
        (x, y) => Ok(x.or(y)),
    }
}

/// `p` as a fraction with a small denominator (½, ⅓, 2), if it is one.
fn rational(p: f64) -> Option<(i32, i32)> {
    (1..=6).find_map(|d| {
        let n = p * f64::from(d);
        (n.abs() < 1e6 && (n - n.round()).abs() <= 1e-9).then(|| (n.round() as i32, d))
    })
}

/// The error for the number at `span` that is used as `dimension` ({what}), when the
/// scene's parameters with units make it of another dimension (see the module's doc); `None`
/// when it is free, of that dimension, or not a formula.
pub(crate) fn check(
    source: &Source,
    span: std::ops::Range<usize>,
    what: &str,
    dimension: Dimension,
    units: &Units,
) -> Option<Error> {
    let parameters = source.parameter_dimensions().filter(|p| !p.is_empty())?;
    let written = source.text.get(span.clone())?;
    let text = match written.as_bytes().first() {
        Some(b'"') => (written[1..].strip_suffix('"')).filter(|t| !t.contains('\\'))?,
        Some(b'\'') => written[1..].strip_suffix('\'')?,
        _ => return None,
    };
    let (graph, root) = super::values::parse_formula(text).ok()?;
    let invalid = |message: String| {
        Some(Error::Invalid {
            location: source.location(span.clone()),
            message,
        })
    };
    let found = match infer(text, &graph, root, parameters) {
        Ok(found) => found?,
        Err(message) => return invalid(message),
    };
    let expected = Quantity::of(dimension, units);
    let file_unit = units.symbol(dimension);
    let words = dimension.words();
    if found.exponents != expected.exponents {
        // One parameter with a unit of its own, its dimension unchanged (`"L"`, `"L - 0.1"`,
        // `"2*L"`): name its unit.
        let named: Vec<&str> = (graph.symbols(&[root]).into_iter())
            .filter(|s| parameters.by_name.contains_key(*s))
            .collect();
        if let [name] = named[..]
            && let Some(unit) = parameters.units.get(name)
            && parameters.by_name[name].0.exponents == found.exponents
        {
            return invalid(format!(
                "unit `{unit}` of parameter `{name}` is {}; `{name}` is used here as \
                 {words} ({what}): write {words} unit ({file_unit}, …) for `{name}`, or use \
                 another parameter",
                found.words(),
            ));
        }
        return invalid(format!(
            "`{text}` is {}, since {}; it is used here as {words} ({what}): write a formula \
             that is {words} (with parameters in units such as {file_unit}), or use other \
             parameters",
            found.words(),
            parameters.why(&graph, root),
        ));
    }
    if !same(found.scale, expected.scale) {
        return invalid(format!(
            "`{text}` is {words}, but its number is in a unit of {} SI (the file's units of \
             its parameters multiplied together, since {}), and the file's unit of {words} \
             `{file_unit}` is {} SI; multiply the formula by {}, or write it as a parameter \
             with a unit of {words}",
            Units::tidy(found.scale),
            parameters.why(&graph, root),
            Units::tidy(expected.scale),
            Units::tidy(found.scale / expected.scale)
        ));
    }
    None
}
