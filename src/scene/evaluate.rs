//! Reading an output from a solved pose: point jets from the model, angles and slider
//! displacements computed from them with exact derivatives (third-order dual numbers).

use mechdiff_core::geometry::{Kinematics, Mechanism, PointOutput, PoseJets, ScalarOutput};
use mechdiff_core::num_dual::Dual3_64;
use mechdiff_core::{DriveState, Jet, JetDual, Scalar};

use crate::error::{Error, Result};

use super::error_context::ErrorContext;
use super::format::{Quantity, Sense, TransmissionForm};
use super::model::{Link, Output, OutputKind, Point};
use super::setup::Setup;
use mechdiff_core::metrics::TransmissionAngle;

/// An output's values at one position: one for an angle, a slider or a transmission angle,
/// `[x, y]` for a point. Held inline (a sweep reads every output at every position: no
/// allocation per output and row); read as a slice.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Values<T> {
    items: [T; 2],
    len: usize,
}

impl<T: Copy> Values<T> {
    /// One value.
    fn one(x: T) -> Self {
        Values {
            items: [x, x],
            len: 1,
        }
    }

    /// A point's two coordinates.
    fn two(items: [T; 2]) -> Self {
        Values { items, len: 2 }
    }

    /// Each value mapped by `f`.
    pub fn map<U: Copy>(self, mut f: impl FnMut(T) -> U) -> Values<U> {
        let first = f(self.items[0]);
        match self.len {
            1 => Values::one(first),
            _ => Values::two([first, f(self.items[1])]),
        }
    }
}

impl<T> std::ops::Deref for Values<T> {
    type Target = [T];
    fn deref(&self) -> &[T] {
        &self.items[..self.len]
    }
}

impl<T> std::ops::DerefMut for Values<T> {
    fn deref_mut(&mut self) -> &mut [T] {
        &mut self.items[..self.len]
    }
}

impl<T> IntoIterator for Values<T> {
    type Item = T;
    type IntoIter = std::iter::Take<std::array::IntoIter<T, 2>>;
    fn into_iter(self) -> Self::IntoIter {
        self.items.into_iter().take(self.len)
    }
}

impl<'a, T> IntoIterator for &'a Values<T> {
    type Item = &'a T;
    type IntoIter = std::slice::Iter<'a, T>;
    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}

/// One quantity of a jet: its value, a coefficient, or a time derivative (a derivative
/// beyond the jet's order reads as zero; the plan asks for the order the outputs need).
pub(crate) fn quantity<const N: usize>(jet: &Jet<N>, q: Quantity, drive: &DriveState) -> f64 {
    let d = |k: usize| jet.derivative(k).unwrap_or(0.0);
    quantity_in([jet.value, d(1), d(2), d(3)], q, drive)
}

/// One quantity from a value and its drive derivatives `[x, x′, x″, x‴]` (zero beyond the
/// order computed) and the drive's state, in any scalar: `f64`, or dual numbers carrying the
/// derivative with respect to a parameter (which ω and α may depend on too). The time
/// derivatives are the chain rule of [`DriveState`] (φ⃛ zero in a scene).
pub(crate) fn quantity_in<S: Scalar>(d: [S; 4], q: Quantity, drive: &DriveState<S>) -> S {
    match q {
        Quantity::Position => d[0],
        Quantity::VelocityCoefficient => d[1],
        Quantity::AccelerationCoefficient => d[2],
        Quantity::Velocity => drive.velocity(d[1]),
        Quantity::Acceleration => drive.acceleration(d[1], d[2]),
        Quantity::JerkCoefficient => d[3],
        Quantity::Jerk => drive.jerk(d[1], d[2], d[3]),
    }
}

/// An output with its points resolved in the model once, before the sweep, so that reading
/// it at a drive position costs no name lookups.
#[derive(Debug, Clone)]
pub(crate) struct Resolved<'s> {
    /// The output.
    pub output: &'s Output,
    /// Its points, in the order of [`point_names`].
    points: Vec<PointOutput>,
    /// An angle's line and reference line read as the rotation of a link that carries both
    /// points, a slider's displacement along a line one link carries, where there is one
    /// (see [`on_links`]): read from the pose's coordinates, not from the points.
    shortcuts: [Option<ScalarOutput>; 2],
    /// An angle output's value at the sketch pose, where a sweep's angle continuity starts
    /// (0 for the others).
    sketch: f64,
}

impl<'s> Resolved<'s> {
    /// Resolves `output`'s points in the model of `setup`.
    pub fn new(setup: &Setup<'_>, output: &'s Output) -> Result<Self> {
        let (cx, model) = (&setup.context, &setup.mechanism);
        Self::in_model(cx, setup.links, setup.points, model, output)
    }

    /// Resolves `output`'s points in `mechanism`, built from the scene whose `links` carry
    /// them and whose `points` give their sketch positions.
    pub fn in_model(
        cx: &ErrorContext<'_>,
        links: &[Link],
        points: &[Point],
        mechanism: &Mechanism,
        output: &'s Output,
    ) -> Result<Self> {
        let resolved = points_on_links(links, output)?
            .into_iter()
            .map(|(link, name)| {
                (mechanism.point_output(link, name)).map_err(|e| cx.solver_error(e))
            })
            .collect::<Result<_>>()?;
        let shortcuts = on_links(links, output).map(|on| {
            on.and_then(|on| match on {
                OnLinks::Line(link, [a, b]) => mechanism.angle_output(link, a, b).ok(),
                OnLinks::Slide(guide, line, slider, point) => {
                    mechanism.slide_output(guide, line, slider, point).ok()
                }
            })
        });
        Ok(Resolved {
            output,
            points: resolved,
            shortcuts,
            sketch: sketch_angle(points, output),
        })
    }

    /// The output's points resolved in the model, in the order [`values`] reads them.
    pub fn points(&self) -> &[PointOutput] {
        &self.points
    }

    /// An angle output's value at the sketch pose, where a sweep's angle continuity starts
    /// (0 for the others).
    pub fn sketch(&self) -> f64 {
        self.sketch
    }
}

/// The points an output is computed from, each with a link that carries it: `(link,
/// point)`, in the order [`values`] reads them.
pub(crate) fn points_on_links<'a>(
    links: &'a [Link],
    output: &'a Output,
) -> Result<Vec<(&'a str, &'a str)>> {
    point_names(output)
        .into_iter()
        .map(|name| {
            let link = (links.iter())
                .find(|l| l.points.iter().any(|p| p == name))
                .ok_or_else(|| Error::Invalid {
                    location: output.location.clone(),
                    message: format!("output `{}`: point `{name}` is on no link", output.name),
                })?;
            Ok((link.name.as_str(), name))
        })
        .collect()
}

/// A line of an output that one link carries (see [`on_links`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum OnLinks<'a> {
    /// An angle's line `[from, to]` on a link: it turns with the link, its direction the
    /// link's angle plus the line's direction in the sketch.
    Line(&'a str, [&'a str; 2]),
    /// A slider's line `[from, to]` on a link, and its point on a link: `(line's link, line,
    /// point's link, point)`; the line's unit direction turns with its link.
    Slide(&'a str, [&'a str; 2], &'a str, &'a str),
}

/// An angle output's line and reference line, a slider's line (then `None`), each where one
/// link carries both its points (`None` otherwise, and for the other outputs): what a
/// solved pose gives without trigonometry (an angle) or a square root and a division (a
/// slider's unit direction).
pub(crate) fn on_links<'a>(links: &'a [Link], output: &'a Output) -> [Option<OnLinks<'a>>; 2] {
    let carries = |l: &Link, name: &str| l.points.iter().any(|p| p == name);
    let on_one_link = |[a, b]: &'a [String; 2]| {
        (links.iter())
            .find(|l| carries(l, a) && carries(l, b))
            .map(|l| (l.name.as_str(), [a.as_str(), b.as_str()]))
    };
    match &output.kind {
        OutputKind::Angle {
            line, reference, ..
        } => [
            on_one_link(line).map(|(l, ab)| OnLinks::Line(l, ab)),
            (reference.as_ref().and_then(on_one_link)).map(|(l, ab)| OnLinks::Line(l, ab)),
        ],
        OutputKind::Slider { point, line, .. } => {
            let slider = links.iter().find(|l| carries(l, point));
            let slide = on_one_link(line).zip(slider);
            [
                slide.map(|((guide, ab), s)| OnLinks::Slide(guide, ab, &s.name, point)),
                None,
            ]
        }
        _ => [None, None],
    }
}

/// The points an output is computed from: the point; the line, then the reference line;
/// the sliding point, then the line.
fn point_names(output: &Output) -> Vec<&str> {
    match &output.kind {
        OutputKind::Point(name) => vec![name],
        OutputKind::Angle {
            line, reference, ..
        } => line
            .iter()
            .chain(reference.iter().flatten())
            .map(String::as_str)
            .collect(),
        OutputKind::Slider { point, line, .. } => std::iter::once(point)
            .chain(line)
            .map(String::as_str)
            .collect(),
        OutputKind::Transmission { points, .. } => points.iter().map(String::as_str).collect(),
    }
}

/// The output's jets at the current pose: `[x, y]` for a point, one jet otherwise. Angles are
/// kept continuous along the sweep through `previous`.
pub(crate) fn evaluate<const N: usize>(
    k: &Kinematics<'_, N>,
    resolved: &Resolved<'_>,
    previous: &mut Option<f64>,
) -> Values<Jet<N>> {
    let position = |p: &PointOutput| k.position(p).map(|x| dual(&x));
    let rotation = |r: &ScalarOutput| dual(&k.value(r));
    evaluate_with::<Dual3_64, N>(position, rotation, resolved, previous)
}

/// The output's jets at the pose `pose` as the tracker's move solved it (see
/// [`PoseJets`]), evaluated in `D` (its order at least `N`): every quantity once, at the
/// order the plan needs, nothing allocated. Angles are kept continuous along the sweep
/// through `previous`.
pub(crate) fn evaluate_pose<D: JetDual, const N: usize>(
    pose: &PoseJets<'_>,
    resolved: &Resolved<'_>,
    previous: &mut Option<f64>,
) -> Values<Jet<N>> {
    let position = |p: &PointOutput| pose.position::<D>(p);
    let rotation = |r: &ScalarOutput| pose.value::<D>(r);
    evaluate_with::<D, N>(position, rotation, resolved, previous)
}

/// The output's jets from its points' positions `position(point)` and its lines' rotations
/// `rotation(line)` in `D`, an angle kept continuous through `previous`.
#[inline]
fn evaluate_with<D: JetDual, const N: usize>(
    position: impl Fn(&PointOutput) -> [D; 2],
    rotation: impl Fn(&ScalarOutput) -> D,
    resolved: &Resolved<'_>,
    previous: &mut Option<f64>,
) -> Values<Jet<N>> {
    let point = |i: usize| position(&resolved.points[i]);
    let line = |i: usize| resolved.shortcuts[i].as_ref().map(&rotation);
    let output = resolved.output;
    let mut values = values_read(output, point, line);
    if let OutputKind::Angle { .. } = &output.kind {
        let target = previous.unwrap_or(resolved.sketch);
        to_turn(&mut values[0], target);
        *previous = Some(values[0].re());
    }
    values.map(|v| v.jet::<N>())
}

/// The output's values as [`values`] gives them, with an angle moved by whole turns to the
/// one nearest its angle in the sketch (where a sweep's angle continuity starts).
pub(crate) fn values_on_sketch_turn<D: Scalar>(
    resolved: &Resolved<'_>,
    point: impl Fn(usize) -> [D; 2],
) -> Values<D> {
    let mut values = values(resolved.output, point);
    if let OutputKind::Angle { .. } = &resolved.output.kind {
        to_turn(&mut values[0], resolved.sketch);
    }
    values
}

/// Moves `angle` by whole turns to the one nearest `target` (unchanged when it is there).
pub(crate) fn to_turn<D: Scalar>(angle: &mut D, target: f64) {
    // Cheap check first: within 3 rad of the target, the nearest turn is this one.
    if (target - angle.re()).abs() < 3.0 {
        return;
    }
    let turns = ((target - angle.re()) / std::f64::consts::TAU).round();
    if turns != 0.0 {
        *angle += turns * std::f64::consts::TAU;
    }
}

/// The output's values from the positions `point(i)` of its points (in the order of
/// [`Resolved::points`]), in any scalar: `[x, y]` for a point, one value otherwise (an
/// angle in (−π, π] before any reference line is subtracted, on no particular turn).
pub(crate) fn values<D: Scalar>(output: &Output, point: impl Fn(usize) -> [D; 2]) -> Values<D> {
    values_read(output, point, |_| None)
}

/// [`values`], with an angle's line (`shortcut(0)`) and reference line (`shortcut(1)`), a
/// slider's displacement (`shortcut(0)`), read from the pose where `shortcut` gives them
/// (see [`on_links`]): the same values, an angle on a continuous turn.
#[inline]
pub(crate) fn values_read<D: Scalar>(
    output: &Output,
    point: impl Fn(usize) -> [D; 2],
    shortcut: impl Fn(usize) -> Option<D>,
) -> Values<D> {
    match &output.kind {
        OutputKind::Point(_) => Values::two(point(0)),
        OutputKind::Angle {
            reference, sense, ..
        } => {
            let mut angle = shortcut(0).unwrap_or_else(|| direction(point(0), point(1)));
            if reference.is_some() {
                angle -= shortcut(1).unwrap_or_else(|| direction(point(2), point(3)));
            }
            if *sense == Sense::Cw {
                angle = -angle;
            }
            Values::one(angle)
        }
        OutputKind::Slider { .. } => Values::one(shortcut(0).unwrap_or_else(|| {
            // s = (p − a)·u with u the unit direction a → b of the guide or slot (both points
            // on one link, so |b − a| is constant; it is differentiated anyway, exactly).
            let (p, a, b) = (point(0), point(1), point(2));
            let u = [b[0] - a[0], b[1] - a[1]];
            let norm = (u[0] * u[0] + u[1] * u[1]).sqrt();
            ((p[0] - a[0]) * u[0] + (p[1] - a[1]) * u[1]) / norm
        })),
        OutputKind::Transmission { form, points, .. } => {
            // μ between the coupler B → A and the follower B → O_out, or the normal of the
            // slider's path (its direction g0 → g1 turned +90°), as core defines it.
            let (b, a) = (point(0), point(1));
            let follower = match points.len() {
                3 => {
                    let o = point(2);
                    [o[0] - b[0], o[1] - b[1]]
                }
                _ => {
                    let (g0, g1) = (point(2), point(3));
                    [g0[1] - g1[1], g1[0] - g0[0]]
                }
            };
            let mu = TransmissionAngle::between([a[0] - b[0], a[1] - b[1]], follower);
            Values::one(match form {
                TransmissionForm::Signed => mu.signed,
                TransmissionForm::Unsigned => mu.unsigned,
                TransmissionForm::Effective => mu.effective,
                TransmissionForm::Deviation => mu.deviation,
            })
        }
    }
}

/// The output angle at the sketch pose, where the sweep's angle continuity starts.
fn sketch_angle(points: &[Point], output: &Output) -> f64 {
    let sketch = |name: &str| {
        points
            .iter()
            .find(|p| p.name == name)
            .map_or([0.0, 0.0], |p| p.sketch)
    };
    let dir = |[a, b]: &[String; 2]| {
        let (a, b) = (sketch(a), sketch(b));
        (b[1] - a[1]).atan2(b[0] - a[0])
    };
    match &output.kind {
        OutputKind::Angle {
            line,
            reference,
            sense,
        } => {
            let angle = dir(line) - reference.as_ref().map_or(0.0, dir);
            if *sense == Sense::Cw { -angle } else { angle }
        }
        _ => 0.0,
    }
}

/// Direction angle of `a → b`, with derivatives.
fn direction<D: Scalar>(a: [D; 2], b: [D; 2]) -> D {
    mechdiff_core::atan2(b[1] - a[1], b[0] - a[0])
}

fn dual<const N: usize>(j: &Jet<N>) -> Dual3_64 {
    let d = |k: usize| j.derivatives.get(k).copied().unwrap_or(0.0);
    Dual3_64::new(j.value, d(0), d(1), d(2))
}
