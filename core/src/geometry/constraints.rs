//! Constraint equations Φ(q, φ) = 0, generic over the scalar, and their Jacobian Φ_q.
//!
//! Coordinates: `q = (x_1, y_1, θ_1, x_2, …)` for the moving links (see [`super::model`]).
//! A point with link-local coordinates `p` on link `k` is at `r_k + A(θ_k)·p`, and
//! `θ_k = 0` at the sketch. With `u = A(θ_g)·u_local` a guide's unit direction, `a` a point of
//! its line and `c = cross`:
//!
//! | joint | equations |
//! |---|---|
//! | revolute | `r_a(p) − r_b(p) = 0` (2) |
//! | prismatic | `θ_s − θ_g = 0`, `c(u, r_s(p) − r_g(a)) − e₀ = 0` (2) |
//! | pin in slot | `c(u, r_pin − r_g(a)) = 0` (1) |
//! | rack and pinion | `(s − s₀) − R·(θ_b − θ_a) = 0` (1) |
//! | gear | `(θ_b2 − θ_a2) − ratio·(θ_b1 − θ_a1) = 0` (1) |
//! | rigid | `r_b − r_a(p_b) = 0`, `θ_b − θ_a = 0` (3) |
//! | drive | `θ_b − θ_a − (φ − φ₀) = 0` or `(s − s₀) − (φ − φ₀) = 0` (1) |
//!
//! where `s = u·(r_s(p) − r_g(a))` is a prismatic displacement. Rows are in joint order, the
//! drive last. Angular rows are in rad, the others in m.
//!
//! The compiled data (`p`, `u`, `a`, `e₀`, `s₀`, `R`, the ratio, `φ₀`) is in a datum scalar
//! `T` (`f64` for the solver, `Dual64` for the exact parameter sensitivities of
//! [`super::parametric`]); one generic compilation and one generic evaluation serve both
//! (see [`super::datum`]).

use super::datum::{Absorb, Data, Datum};
pub(crate) use super::frames::{Frames, with_frames};
use super::model::{DriveKind, JointKind, Mechanism};
use nalgebra::DMatrix;
use std::ops::Sub;

/// Index of a body's coordinates in `q`; `None` for the ground.
pub(crate) type Body = Option<usize>;

/// A line fixed in a body: a point of it and its unit direction, both link-local.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Line<T = f64> {
    pub body: Body,
    pub origin: [T; 2],
    pub direction: [T; 2],
}

/// A prismatic pair compiled: the guide line, the slider and its measuring point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Slide<T = f64> {
    pub line: Line<T>,
    pub slider: Body,
    pub point: [T; 2],
}

/// One joint (or the drive), compiled to link-local data in `T`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Term<T = f64> {
    Revolute {
        a: Body,
        pa: [T; 2],
        b: Body,
        pb: [T; 2],
    },
    Prismatic {
        slide: Slide<T>,
        offset: T,
    },
    PinInSlot {
        line: Line<T>,
        pin: Body,
        p: [T; 2],
    },
    RackPinion {
        a: Body,
        b: Body,
        slide: Slide<T>,
        s0: T,
        radius: T,
    },
    Gear {
        a1: Body,
        b1: Body,
        a2: Body,
        b2: Body,
        ratio: T,
    },
    Rigid {
        a: Body,
        pa: [T; 2],
        b: Body,
    },
    DriveAngle {
        a: Body,
        b: Body,
        phi0: T,
    },
    DriveSlide {
        slide: Slide<T>,
        s0: T,
        phi0: T,
    },
}

impl<T> Term<T> {
    fn rows(&self) -> usize {
        match self {
            Term::Revolute { .. } | Term::Prismatic { .. } => 2,
            Term::Rigid { .. } => 3,
            _ => 1,
        }
    }
}

/// The compiled equations of a mechanism: what the solver evaluates. The link-local data is
/// in `T`: `f64` for the solver, `Dual64` (data with its derivative with respect to a
/// parameter) inside [`super::parametric::Parametric`].
#[derive(Debug, Clone, PartialEq)]
pub struct Equations<T = f64> {
    pub(crate) terms: Vec<Term<T>>,
    /// Rows that are angles (rad) rather than lengths (m).
    pub(crate) angular: Vec<bool>,
    /// Row → index of the joint it comes from (`joints.len()` for the drive).
    pub(crate) row_joint: Vec<usize>,
    coordinates: usize,
}

pub(crate) fn body(link: usize) -> Body {
    link.checked_sub(1)
}

fn sub<T: Copy + Sub<Output = T>>(a: [T; 2], b: [T; 2]) -> [T; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

/// The line through two points of `link` (sketch positions), in the link's frame, with a unit
/// direction from the first point to the second.
fn compile_line<T: Datum>(data: &Data<'_, T>, link: usize, line: [usize; 2]) -> Line<T> {
    let (a, b) = (data.point(line[0]), data.point(line[1]));
    let d = sub(b, a);
    let len = T::length(d[0], d[1]);
    Line {
        body: body(link),
        origin: data.local(link, a),
        direction: [d[0] / len, d[1] / len],
    }
}

pub(crate) fn compile_slide<T: Datum>(
    data: &Data<'_, T>,
    guide: usize,
    line: [usize; 2],
    slider: usize,
    point: usize,
) -> Slide<T> {
    Slide {
        line: compile_line(data, guide, line),
        slider: body(slider),
        point: data.local(slider, data.point(point)),
    }
}

impl Equations {
    /// Compiles the equations of `m`.
    pub fn new(m: &Mechanism) -> Self {
        compile(&Data::of(m))
    }

    /// Evaluates Φ(q, φ) into `out` (length [`Equations::rows`]), for any scalar type.
    pub fn evaluate<D: crate::Scalar>(&self, q: &[D], phi: D, out: &mut [D]) {
        with_frames(q, |f| self.evaluate_with(f, phi, out));
    }
}

/// Compiles the equations of `data.m` from `data`'s numbers (in `T`).
pub(crate) fn compile<T: Datum>(data: &Data<'_, T>) -> Equations<T> {
    let m = data.m;
    let mut terms = Vec::with_capacity(m.joints.len() + 1);
    let mut row_joint = Vec::new();
    let slide_of = |j: usize| match m.joints[j].kind {
        JointKind::Prismatic {
            guide,
            line,
            slider,
            point,
        } => compile_slide(data, guide, line, slider, point),
        _ => unreachable!("validated: a prismatic joint"),
    };
    let bodies_of = |j: usize| match m.joints[j].kind {
        JointKind::Revolute { link_a, link_b, .. } => (body(link_a), body(link_b)),
        _ => unreachable!("validated: a revolute joint"),
    };
    for (ji, j) in m.joints.iter().enumerate() {
        let term = match j.kind {
            JointKind::Revolute {
                link_a,
                link_b,
                point,
            } => {
                let at = data.point(point);
                Term::Revolute {
                    a: body(link_a),
                    pa: data.local(link_a, at),
                    b: body(link_b),
                    pb: data.local(link_b, at),
                }
            }
            JointKind::Prismatic { .. } => {
                let slide = slide_of(ji);
                // The (constant) signed distance of the measuring point from the line.
                let offset = match j.kind {
                    JointKind::Prismatic { line, point, .. } => cross(
                        slide.line.direction,
                        sub(data.point(point), data.point(line[0])),
                    ),
                    _ => unreachable!(),
                };
                Term::Prismatic { slide, offset }
            }
            JointKind::PinInSlot {
                slot_link,
                line,
                pin_link,
                pin,
            } => Term::PinInSlot {
                line: compile_line(data, slot_link, line),
                pin: body(pin_link),
                p: data.local(pin_link, data.point(pin)),
            },
            JointKind::RackPinion { pinion, rack, .. } => {
                let (a, b) = bodies_of(pinion);
                let slide = slide_of(rack);
                Term::RackPinion {
                    a,
                    b,
                    slide,
                    s0: sketch_displacement(data, rack),
                    radius: data.numbers[ji],
                }
            }
            JointKind::Gear {
                joint_a, joint_b, ..
            } => {
                let (a1, b1) = bodies_of(joint_a);
                let (a2, b2) = bodies_of(joint_b);
                Term::Gear {
                    a1,
                    b1,
                    a2,
                    b2,
                    ratio: data.numbers[ji],
                }
            }
            JointKind::Rigid { link_a, link_b } => Term::Rigid {
                a: body(link_a),
                pa: data.local(link_a, data.reference(link_b)),
                b: body(link_b),
            },
        };
        row_joint.extend(std::iter::repeat_n(ji, term.rows()));
        terms.push(term);
    }
    let phi0 = data.drive_at_sketch;
    terms.push(match m.drive_kind {
        DriveKind::Angle => {
            let (a, b) = bodies_of(m.drive_joint);
            Term::DriveAngle { a, b, phi0 }
        }
        DriveKind::Displacement => Term::DriveSlide {
            slide: slide_of(m.drive_joint),
            s0: sketch_displacement(data, m.drive_joint),
            phi0,
        },
    });
    row_joint.push(m.joints.len());
    let mut eq = Equations {
        terms,
        angular: Vec::new(),
        row_joint,
        coordinates: m.coordinate_count(),
    };
    eq.angular = eq.angular_rows();
    eq
}

impl<T: Copy> Equations<T> {
    /// Number of equations (rows of Φ).
    pub fn rows(&self) -> usize {
        self.row_joint.len()
    }

    /// Number of coordinates (columns of Φ_q).
    pub fn coordinates(&self) -> usize {
        self.coordinates
    }

    /// Evaluates Φ at the pose of `f` (its sines and cosines already known) into `out`, in
    /// any evaluation scalar `D` that takes in the data's `T`.
    pub(crate) fn evaluate_with<D: Absorb<T>>(&self, f: &Frames<'_, D>, phi: D, out: &mut [D]) {
        let mut row = 0;
        for t in &self.terms {
            match *t {
                Term::Revolute { a, pa, b, pb } => {
                    let (ra, rb) = (f.point(a, pa), f.point(b, pb));
                    out[row] = ra[0] - rb[0];
                    out[row + 1] = ra[1] - rb[1];
                }
                Term::Prismatic { slide, offset } => {
                    out[row] = f.angle(slide.slider) - f.angle(slide.line.body);
                    let (u, d) = f.along(&slide.line, f.point(slide.slider, slide.point));
                    out[row + 1] = (u[0] * d[1] - u[1] * d[0]).minus(offset);
                }
                Term::PinInSlot { line, pin, p } => {
                    let (u, d) = f.along(&line, f.point(pin, p));
                    out[row] = u[0] * d[1] - u[1] * d[0];
                }
                Term::RackPinion {
                    a,
                    b,
                    slide,
                    s0,
                    radius,
                } => {
                    let s = f.displacement(&slide);
                    out[row] = s.minus(s0) - (f.angle(b) - f.angle(a)).times(radius);
                }
                Term::Gear {
                    a1,
                    b1,
                    a2,
                    b2,
                    ratio,
                } => {
                    out[row] = f.angle(b2) - f.angle(a2) - (f.angle(b1) - f.angle(a1)).times(ratio);
                }
                Term::Rigid { a, pa, b } => {
                    let ra = f.point(a, pa);
                    let rb = f.point::<f64>(b, [0.0, 0.0]);
                    out[row] = rb[0] - ra[0];
                    out[row + 1] = rb[1] - ra[1];
                    out[row + 2] = f.angle(b) - f.angle(a);
                }
                Term::DriveAngle { a, b, phi0 } => {
                    out[row] = f.angle(b) - f.angle(a) - phi.minus(phi0);
                }
                Term::DriveSlide { slide, s0, phi0 } => {
                    out[row] = f.displacement(&slide).minus(s0) - phi.minus(phi0);
                }
            }
            row += t.rows();
        }
    }

    /// For each row, the moving bodies (indices into `q / 3`) it depends on.
    pub(crate) fn row_bodies(&self) -> Vec<Vec<usize>> {
        let mut out = Vec::with_capacity(self.rows());
        for t in &self.terms {
            let bodies: Vec<Body> = match *t {
                Term::Revolute { a, b, .. } | Term::Rigid { a, b, .. } => vec![a, b],
                Term::DriveAngle { a, b, .. } => vec![a, b],
                Term::Prismatic { slide, .. } | Term::DriveSlide { slide, .. } => {
                    vec![slide.line.body, slide.slider]
                }
                Term::PinInSlot { line, pin, .. } => vec![line.body, pin],
                Term::RackPinion { a, b, slide, .. } => vec![a, b, slide.line.body, slide.slider],
                Term::Gear { a1, b1, a2, b2, .. } => vec![a1, b1, a2, b2],
            };
            let mut bodies: Vec<usize> = bodies.into_iter().flatten().collect();
            bodies.sort_unstable();
            bodies.dedup();
            out.extend(std::iter::repeat_n(bodies, t.rows()));
        }
        out
    }

    /// Rows of Φ_q that are angular (rad) rather than lengths (m): used to scale the
    /// Jacobian for rank and condition estimates.
    fn angular_rows(&self) -> Vec<bool> {
        let mut out = Vec::with_capacity(self.rows());
        for t in &self.terms {
            match t {
                Term::Revolute { .. } => out.extend([false, false]),
                Term::Prismatic { .. } => out.extend([true, false]),
                Term::Rigid { .. } => out.extend([false, false, true]),
                Term::Gear { .. } | Term::DriveAngle { .. } => out.push(true),
                _ => out.push(false),
            }
        }
        out
    }
}

impl Equations {
    /// Evaluates the Jacobian Φ_q at `q` (f64) into `jac` (rows × coordinates), analytically.
    pub fn jacobian(&self, q: &[f64], jac: &mut DMatrix<f64>) {
        with_frames(q, |f| self.jacobian_with(f, jac));
    }

    /// Evaluates Φ_q at the pose of `f` (its sines and cosines already known) into `jac`.
    pub(crate) fn jacobian_with(&self, f: &Frames<'_, f64>, jac: &mut DMatrix<f64>) {
        // (A slice fill is a memset; nalgebra's `fill` goes entry by entry.)
        let n = jac.nrows();
        let jac = jac.as_mut_slice();
        jac.fill(0.0);
        let mut g = Gradient { f, jac, n };
        let mut row = 0;
        for t in &self.terms {
            match *t {
                Term::Revolute { a, pa, b, pb } => {
                    g.point(row, a, pa, [1.0, 0.0]);
                    g.point(row + 1, a, pa, [0.0, 1.0]);
                    g.point(row, b, pb, [-1.0, 0.0]);
                    g.point(row + 1, b, pb, [0.0, -1.0]);
                }
                Term::Prismatic { slide, .. } => {
                    g.angle(row, slide.slider, 1.0);
                    g.angle(row, slide.line.body, -1.0);
                    g.line(row + 1, &slide.line, slide.slider, slide.point, false);
                }
                Term::PinInSlot { line, pin, p } => g.line(row, &line, pin, p, false),
                Term::RackPinion {
                    a,
                    b,
                    slide,
                    radius,
                    ..
                } => {
                    g.line(row, &slide.line, slide.slider, slide.point, true);
                    g.angle(row, b, -radius);
                    g.angle(row, a, radius);
                }
                Term::Gear {
                    a1,
                    b1,
                    a2,
                    b2,
                    ratio,
                } => {
                    g.angle(row, b2, 1.0);
                    g.angle(row, a2, -1.0);
                    g.angle(row, b1, -ratio);
                    g.angle(row, a1, ratio);
                }
                Term::Rigid { a, pa, b } => {
                    g.point(row, b, [0.0, 0.0], [1.0, 0.0]);
                    g.point(row + 1, b, [0.0, 0.0], [0.0, 1.0]);
                    g.point(row, a, pa, [-1.0, 0.0]);
                    g.point(row + 1, a, pa, [0.0, -1.0]);
                    g.angle(row + 2, b, 1.0);
                    g.angle(row + 2, a, -1.0);
                }
                Term::DriveAngle { a, b, .. } => {
                    g.angle(row, b, 1.0);
                    g.angle(row, a, -1.0);
                }
                Term::DriveSlide { slide, .. } => {
                    g.line(row, &slide.line, slide.slider, slide.point, true);
                }
            }
            row += t.rows();
        }
    }
}

/// Accumulates rows of Φ_q from the pieces every equation is made of.
struct Gradient<'a, 'f, 'q> {
    f: &'f Frames<'q, f64>,
    /// Φ_q column-major, `n` rows.
    jac: &'a mut [f64],
    n: usize,
}

impl Gradient<'_, '_, '_> {
    /// Φ_q[row, column].
    #[inline]
    fn entry(&mut self, row: usize, column: usize) -> &mut f64 {
        &mut self.jac[column * self.n + row]
    }

    /// Adds `w·∂r/∂q` for the point of `b` at local `p` to `row`.
    #[inline]
    fn point(&mut self, row: usize, b: Body, p: [f64; 2], w: [f64; 2]) {
        if let Some(k) = b {
            let r = self.f.rotate(b, p);
            *self.entry(row, 3 * k) += w[0];
            *self.entry(row, 3 * k + 1) += w[1];
            *self.entry(row, 3 * k + 2) += w[1] * r[0] - w[0] * r[1];
        }
    }

    /// Adds `w·∂θ_b/∂q` to `row`.
    #[inline]
    fn angle(&mut self, row: usize, b: Body, w: f64) {
        if let Some(k) = b {
            *self.entry(row, 3 * k + 2) += w;
        }
    }

    /// Adds the gradient of `u·(r − r_g(a))` (`along`) or `c(u, r − r_g(a))` to `row`, where
    /// `r` is the point of `pin` at local `p` and `u`, `a` belong to `line`.
    #[inline]
    fn line(&mut self, row: usize, line: &Line, pin: Body, p: [f64; 2], along: bool) {
        let u = self.f.rotate(line.body, line.direction);
        let w = if along { u } else { [-u[1], u[0]] };
        self.point(row, pin, p, w);
        if let Some(k) = line.body {
            let rel = sub(self.f.point(pin, p), self.f.point(line.body, [0.0, 0.0]));
            *self.entry(row, 3 * k) -= w[0];
            *self.entry(row, 3 * k + 1) -= w[1];
            // The guide's rotation turns u and moves a: ∂/∂θ_g of c(u, r − r_g(a)) is
            // −u·(r − r_g), of u·(r − r_g(a)) it is c(u, r − r_g), r_g the guide's origin.
            *self.entry(row, 3 * k + 2) += if along {
                cross(u, rel)
            } else {
                -(u[0] * rel[0] + u[1] * rel[1])
            };
        }
    }
}

/// The planar cross product `a_x b_y − a_y b_x`.
pub(crate) fn cross<T: crate::Scalar>(a: [T; 2], b: [T; 2]) -> T {
    a[0] * b[1] - a[1] * b[0]
}

/// Displacement `u·(r_point − r_line0)` of prismatic joint `joint` at the sketch (m).
pub(crate) fn sketch_displacement<T: Datum>(data: &Data<'_, T>, joint: usize) -> T {
    match data.m.joints[joint].kind {
        JointKind::Prismatic { line, point, .. } => {
            let (a, b) = (data.point(line[0]), data.point(line[1]));
            let d = sub(b, a);
            let len = T::length(d[0], d[1]);
            let r = sub(data.point(point), a);
            (r[0] * d[0] + r[1] * d[1]) / len
        }
        _ => T::from(0.0),
    }
}

/// The drive value implied by the sketch when the model does not give one.
pub(crate) fn sketch_drive_value<T: Datum>(data: &Data<'_, T>) -> T {
    match data.m.drive_kind {
        DriveKind::Angle => T::from(0.0),
        DriveKind::Displacement => sketch_displacement(data, data.m.drive_joint),
    }
}

/// Φ(q, φ) in f64 (allocating; for checks, not for the solver's inner loop).
pub(crate) fn residual(m: &Mechanism, q: &[f64], phi: f64) -> Vec<f64> {
    let eq = Equations::new(m);
    let mut out = vec![0.0; eq.rows()];
    eq.evaluate(q, phi, &mut out);
    out
}
