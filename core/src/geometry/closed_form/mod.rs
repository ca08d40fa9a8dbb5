//! Closed-form solutions of standard loops (Assur groups of one or two links, rolling and
//! gear contacts), used instead of Newton.
//!
//! The solver splits Φ(q, φ) = 0 into loops, solved in sequence (see [`super::branch`]); each
//! loop's unknowns depend only on the loops before it. Many loops are one link, or two
//! links joined by a revolute (a dyad), attached to links already placed by standard pairs,
//! and have a closed-form solution. At [`super::Solver::track`] every loop is matched
//! against the patterns below, from the joints of the model (whatever the mechanism is
//! called; see `matching`); a loop that matches is solved by its formula, written once
//! generic over the scalar: evaluated with `Dual2_64` or `Dual3_64` in φ it gives q, q′, q″
//! (q‴) exactly, the derivatives following through the formula from the earlier loops' dual
//! coordinates, with no Newton iteration and no LU.
//!
//! With `K` the hinge (the point of the link already placed that the unknown link turns
//! about), `A(θ)` the link's rotation and `p_h` the hinge's link-local coordinates, a hinged
//! link is at `r = K − A(θ) p_h` once θ is known:
//!
//! | pattern | joints of the loop | θ (and r) |
//! |---|---|---|
//! | driven crank | revolute + angle drive | `θ = θ_other ± (φ − φ₀)` |
//! | slotted rocker | revolute + its slot (direction `d`) through a known pin `P` | `cross(A d, w) = c`, `w = P − K`, `c = cross(d, o − p_h)`: `θ + δ = arg w − ψ` |
//! | pin in a known slot | revolute + its pin (`p − p_h = r`) on a known line (`a`, `u`) | `cross(u, A r) = cross(u, a − K)`: `θ + arg r = arg u + ψ` |
//! | translating slide | prismatic on a known guide + a slot through a known pin, a pin in a known slot, or a displacement drive | `θ = θ_guide`, displacement `s` from one linear equation |
//! | RRR dyad | two links hinged at known `K₁`, `K₂`, joined at `J` (`|J − K₁| = l₁`, `|J − K₂| = l₂`) | `J = K₁ + (g d + σ √(l₁² d² − g²) d⊥) / d²`, `d = K₂ − K₁`, `g = (l₁² − l₂² + d²)/2` |
//! | RRP dyad | first link hinged at `K`, the second sliding on a known guide (`u`), joined at `J = J₀ + s u` | `s = −u·w + σ √((u·w)² − |w|² + l₁²)`, `w = J₀ − K` |
//! | RPR dyad | two links hinged at known `K_L`, `K_S`, joined by a prismatic pair (line on L) | L as a slotted rocker through `K_S`: `cross(A d, K_S − K_L) = e − cross(d, p − h_S − o + h_L)`; S turns with L, hinged at `K_S` |
//! | rolling pinion | revolute + rack-and-pinion with a known rack | `θ = θ_other ± (s − s₀)/R` |
//! | rolling rack | prismatic + rack-and-pinion with a known pinion | `s = s₀ + R (θ_b − θ_a)` |
//! | gear | revolute + gear contact with known wheels | `θ = Σ kᵢ θᵢ` (the mesh's linear relation solved for θ) |
//!
//! For the square-root patterns, with ρ the radius (`|w|`, resp. `|r|`) and c the
//! right-hand side, `ρ sin ψ = c` and `ρ cos ψ = k = σ √(ρ² − c²)`: `ψ = arg(k + i c)`, and
//! one `atan2` of a product of complex numbers gives θ (its sine and cosine follow by a
//! division, without `sin_cos`); a dyad's link angles follow from J the same way.
//! **Branch**: σ = ±1 selects one of the loop's two assembly closures (the sign of
//! `dot(A d, w)`, resp. `dot(u, A r)`; the side of `K₁K₂` that J is on; which of the line's
//! two intersections with the circle). It is chosen once, at `track`, as the sign that
//! reproduces the sketch pose (each pattern is checked against the sketch; a loop whose
//! formula does not reproduce it is left to Newton), and never changes: the loop stays on
//! the sketch's branch, as the Newton path's certificates enforce. A negative discriminant
//! is a loop that cannot assemble ([`Error::Unassemblable`](crate::Error), residual: by how
//! much it misses, m); a root near zero is a toggle (`Error::Singular`), the condition
//! estimated in the loop's own length scale as `√(size / |disc|)` with `size` what `disc`
//! is at most for the loop's lengths now (`l₁² l₂²` for an RRR dyad: the condition is
//! `1 / |sin γ|`, γ the angle between its links; `l₁²` for an RRP dyad; `ρ²` for a slot
//! through a pin), and `1 / |cross(v, u)|` for a slide whose slot is parallel to its
//! guide, compared with the solver's singular threshold. No sketch size enters, so points
//! elsewhere in the mechanism (or its scale) change no verdict.
//!
//! **Margins.** Each loop also reports its *margin*: `disc` (or the slope) divided by its
//! value's size in the sketch, so it is 1 in the sketch's shape, positive wherever the loop
//! closes on its branch, and vanishes at a limit position (a simple root: beyond it the
//! loop cannot close), at a change point (a double root: two branches meet) or at a toggle
//! of a slide. The solver checks the margins between drive positions (see
//! `solver::interval`); `1/√margin` is how much the loop amplifies rounding.
//! Angles are unwrapped to the nearest turn of the previous pose, so rotations stay
//! continuous.

mod margin;
mod matching;
mod pattern;

use super::branch::Loop;
use super::constraints::{Body, Equations, Frames};
use super::frames::rotate;
use crate::{Scalar, atan2};
pub(crate) use margin::{Margin, amplification};
use matching::pattern;
use pattern::{Angle, End, Pattern, Shift, sub};
use std::f64::consts::{PI, TAU};

/// One loop's closed form: the link it places, the pattern and its branch sign.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Step {
    body: usize,
    pattern: Pattern,
    branch: f64,
    /// The margin's factor: sign / size of the loop's raw margin at the sketch (see
    /// [`Margin`]), so that the loop's margin is 1 in the sketch's shape and positive
    /// wherever the loop closes regularly.
    inv_scale: f64,
}

/// Why a loop's closed form has no solution at a drive position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Failure {
    /// The loop cannot close: `residual` (m) is by how much.
    Unassemblable { residual: f64 },
    /// The loop is at (or too near) a toggle: its estimated condition number.
    Singular { condition: f64 },
}

/// Places loop `l`'s links (in `q` and its frames) by other means than a closed form (see
/// [`ClosedForm::solve_each_or`]), or fails naming a loop.
pub(crate) type PlaceByNewton<'a, D> =
    dyn FnMut(usize, &mut [D], &mut [(D, D)]) -> Result<(), (usize, Failure)> + 'a;

/// The closed forms of a mechanism's loops (`None`: that loop is solved by Newton).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ClosedForm {
    steps: Vec<Option<Step>>,
    /// The singular threshold (see [`super::Solver::singular_threshold`]).
    limit: f64,
    /// Per loop: `Some(true)` a discriminant margin, `Some(false)` a slope, `None` none.
    kinds: Vec<Option<bool>>,
}

/// The point fixed at `p` in body `b`.
#[inline]
fn place<D: Scalar>(q: &[D], frames: &[(D, D)], b: Body, p: [f64; 2]) -> [D; 2] {
    let r = rotate(frames, b, p);
    match b {
        None => r,
        Some(k) => [q[3 * k] + r[0], q[3 * k + 1] + r[1]],
    }
}

/// The reference point `K − A p` of a link turned by `(sin θ, cos θ)` about the hinge at
/// `K`, at `p` in the link (nothing to turn when the hinge is the link's own origin).
#[inline]
fn hinged_at<D: Scalar>(pivot: [D; 2], (s, c): (D, D), p: [f64; 2]) -> [D; 2] {
    if p == [0.0, 0.0] {
        return pivot;
    }
    [
        pivot[0] - (c * p[0] - s * p[1]),
        pivot[1] - (s * p[0] + c * p[1]),
    ]
}

/// The angle θ of a link (and its sine and cosine) whose local vector `r` (|r|² = `r2`)
/// points along `v` (|v|² = `r2` too): e^{iθ} = v·conj(r) / |r|².
#[inline]
fn turn_to<D: Scalar>(v: [D; 2], r: [f64; 2], r2: f64) -> (D, (D, D)) {
    let x = v[0] * r[0] + v[1] * r[1];
    let y = v[1] * r[0] - v[0] * r[1];
    (atan2(y, x), (y / r2, x / r2))
}

/// `theta` moved by whole turns to the one nearest to `previous`.
#[inline]
fn unwrap<D: Scalar>(theta: D, previous: f64) -> D {
    let gap = previous - theta.re();
    if gap.abs() > PI {
        theta + (gap / TAU).round() * TAU
    } else {
        theta
    }
}

#[inline]
fn cross_d<D: Scalar>(a: [D; 2], b: [D; 2]) -> D {
    a[0] * b[1] - a[1] * b[0]
}

impl ClosedForm {
    /// Matches every loop of `eq` and chooses each branch so that the formula reproduces
    /// the sketch pose `sketch` at drive position `phi0` to 1e-9 of the loop's length
    /// (`lengths`, per loop; loops it does not reproduce are left to Newton).
    pub fn new(
        eq: &Equations,
        loops: &[Loop],
        sketch: &[f64],
        phi0: f64,
        lengths: &[f64],
        limit: f64,
    ) -> Self {
        let mut cf = ClosedForm {
            steps: Vec::with_capacity(loops.len()),
            limit,
            kinds: Vec::with_capacity(loops.len()),
        };
        let frames: Vec<(f64, f64)> = sketch.chunks_exact(3).map(|p| p[2].sin_cos()).collect();
        for (l, length) in loops.iter().zip(lengths) {
            let tolerance = 1e-9 * length.max(f64::MIN_POSITIVE);
            let found = pattern(eq, l).and_then(|(body, pattern)| {
                [1.0, -1.0].into_iter().find_map(|branch| {
                    let mut step = Step {
                        body,
                        pattern,
                        branch,
                        inv_scale: 1.0,
                    };
                    let (mut q, mut f) = (sketch.to_vec(), frames.clone());
                    let mut margin = Margin::none();
                    cf.solve(&step, phi0, sketch, &mut q, &mut f, &mut margin)
                        .ok()?;
                    let sign = if margin.value < 0.0 { -1.0 } else { 1.0 };
                    step.inv_scale = sign / margin.size;
                    let second = match pattern {
                        Pattern::Dyad { second, .. }
                        | Pattern::Hinged {
                            rider: Some((second, _)),
                            ..
                        } => second,
                        _ => body,
                    };
                    let close = [body, second].iter().all(|&b| {
                        (0..3).all(|i| {
                            let scale = if i == 2 { 1e-9 } else { tolerance };
                            (q[3 * b + i] - sketch[3 * b + i]).abs() <= scale
                        })
                    });
                    close.then_some((step, margin.root))
                })
            });
            cf.kinds.push(found.and_then(|(_, kind)| kind));
            cf.steps.push(found.map(|(step, _)| step));
        }
        cf
    }

    /// Whether every loop has a closed form (then Newton is not needed at all).
    pub fn complete(&self) -> bool {
        self.steps.iter().all(Option::is_some)
    }

    /// Per loop, whether it has a closed form.
    pub fn matched(&self) -> impl Iterator<Item = bool> + '_ {
        self.steps.iter().map(Option::is_some)
    }

    /// Number of loops solved in closed form.
    pub fn count(&self) -> usize {
        self.steps.iter().filter(|s| s.is_some()).count()
    }

    /// Solves every loop in closed form at drive position `phi` (a dual number: its
    /// derivative parts are those of φ itself), writing the pose and its bodies' `(sin, cos)`
    /// into `q`, `frames`. `previous` (the last pose, f64) picks the turn of each angle.
    /// All loops must have a closed form ([`ClosedForm::complete`]).
    /// `margins` receives every loop's margin (see [`ClosedForm::amplification`]) up to
    /// the failing loop included.
    pub fn solve_all<D: Scalar>(
        &self,
        phi: D,
        previous: &[f64],
        q: &mut [D],
        frames: &mut [(D, D)],
        margins: &mut [D],
    ) -> Result<(), (usize, Failure)> {
        self.solve_each(phi, previous, q, frames, |i, margin, inv_scale| {
            margins[i] = margin.value * inv_scale;
        })
    }

    /// [`ClosedForm::solve_all`], handing each loop's margin and its factor (sign / size
    /// at the sketch) to `margin_of`, up to the failing loop included.
    pub(crate) fn solve_each<D: Scalar>(
        &self,
        phi: D,
        previous: &[f64],
        q: &mut [D],
        frames: &mut [(D, D)],
        margin_of: impl FnMut(usize, &Margin<D>, f64),
    ) -> Result<(), (usize, Failure)> {
        let mut no_newton = |i: usize, _: &mut [D], _: &mut [(D, D)]| {
            Err((
                i,
                Failure::Singular {
                    condition: f64::NAN,
                },
            ))
        };
        let all = vec![true; self.steps.len()];
        self.solve_each_or(phi, previous, q, frames, &all, margin_of, &mut no_newton)
    }

    /// [`ClosedForm::solve_each`], placing each loop without a closed form (or whose
    /// closed form is not in use: `in_use` false there) by `newton` instead, which may fail
    /// with its own loop index and failure.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn solve_each_or<D: Scalar>(
        &self,
        phi: D,
        previous: &[f64],
        q: &mut [D],
        frames: &mut [(D, D)],
        in_use: &[bool],
        mut margin_of: impl FnMut(usize, &Margin<D>, f64),
        newton: &mut PlaceByNewton<'_, D>,
    ) -> Result<(), (usize, Failure)> {
        for (i, step) in self.steps.iter().enumerate() {
            let Some(step) = step.as_ref().filter(|_| in_use[i]) else {
                newton(i, q, frames)?;
                continue;
            };
            let mut margin = Margin::none();
            let solved = self.solve(step, phi, previous, q, frames, &mut margin);
            margin_of(i, &margin, step.inv_scale);
            solved.map_err(|f| (i, f))?;
        }
        Ok(())
    }

    /// Places the links of the loops that have a closed form, in f64, leaving the others
    /// (and any loop whose formula fails) as they are: a predictor for Newton.
    pub fn seed(&self, phi: f64, previous: &[f64], q: &mut [f64], frames: &mut [(f64, f64)]) {
        for step in self.steps.iter().flatten() {
            let _ = self.solve(step, phi, previous, q, frames, &mut Margin::none());
        }
    }

    /// Solves one loop: sets its body's coordinates and `(sin θ, cos θ)`, and its margin.
    #[inline(always)]
    fn solve<D: Scalar>(
        &self,
        step: &Step,
        phi: D,
        previous: &[f64],
        q: &mut [D],
        frames: &mut [(D, D)],
        margin: &mut Margin<D>,
    ) -> Result<(), Failure> {
        let k = step.body;
        let (theta, sin_cos, r) = match step.pattern {
            Pattern::Dyad {
                hinge,
                joint,
                second,
                end,
            } => {
                let pivot = place(q, frames, hinge.known, hinge.at_known);
                let r1 = sub(joint[0], hinge.at_body);
                let l1 = r1[0] * r1[0] + r1[1] * r1[1];
                // The joint J, then the second link's coordinates.
                let (j, theta2, sin_cos2, ref2) = match end {
                    End::Hinge(h2) => {
                        let pivot2 = place(q, frames, h2.known, h2.at_known);
                        let r2 = sub(joint[1], h2.at_body);
                        let l2 = r2[0] * r2[0] + r2[1] * r2[1];
                        let d = [pivot2[0] - pivot[0], pivot2[1] - pivot[1]];
                        let d2 = d[0] * d[0] + d[1] * d[1];
                        // J = K₁ + (g d + σ √(l₁² d² − g²) d⊥) / d², g = (l₁² − l₂² + d²)/2.
                        let g = (d2 + (l1 - l2)) * 0.5;
                        let disc = d2 * l1 - g * g;
                        let dist = d2.re().sqrt();
                        let (a, b) = (l1.sqrt(), l2.sqrt());
                        let gap = (dist - (a + b)).max((a - b).abs() - dist);
                        // √disc = l₁ l₂ |sin γ|, γ the angle between the links at J.
                        let h = self.root(disc, D::from(l1 * l2), gap, step.branch, margin)?;
                        let inv = d2.recip();
                        let j = [
                            pivot[0] + (d[0] * g - d[1] * h) * inv,
                            pivot[1] + (d[1] * g + d[0] * h) * inv,
                        ];
                        let v = [j[0] - pivot2[0], j[1] - pivot2[1]];
                        let (t2, sc2) = turn_to(v, r2, l2);
                        let t2 = unwrap(t2, previous[3 * second + 2]);
                        let ref2 = hinged_at(pivot2, sc2, h2.at_body);
                        (j, t2, sc2, ref2)
                    }
                    End::Slide { slide, offset } => {
                        let g = slide.line.body;
                        let t2 = g.map_or(D::from(0.0), |g| q[3 * g + 2]);
                        let sc2 = g.map_or((D::from(0.0), D::from(1.0)), |g| frames[g]);
                        let u = rotate(frames, g, slide.line.direction);
                        let a = place(q, frames, g, slide.line.origin);
                        // The second link's reference point a + e₀ n − A p at displacement
                        // 0 along u, and J there.
                        let rp = rotate(frames, g, slide.point);
                        let rj = rotate(frames, g, joint[1]);
                        let base = [a[0] - u[1] * offset - rp[0], a[1] + u[0] * offset - rp[1]];
                        let j0 = [base[0] + rj[0], base[1] + rj[1]];
                        let w = [j0[0] - pivot[0], j0[1] - pivot[1]];
                        let uw = u[0] * w[0] + u[1] * w[1];
                        let ww = w[0] * w[0] + w[1] * w[1];
                        // |w + s u| = l₁: s = −u·w ± √((u·w)² − |w|² + l₁²).
                        let disc = uw * uw - ww + l1;
                        let gap = (ww.re() - uw.re() * uw.re()).max(0.0).sqrt() - l1.sqrt();
                        // √disc = l₁ |cos| of the link's angle to the guide's normal.
                        let s = self.root(disc, D::from(l1), gap, step.branch, margin)? - uw;
                        let j = [j0[0] + u[0] * s, j0[1] + u[1] * s];
                        (j, t2, sc2, [base[0] + u[0] * s, base[1] + u[1] * s])
                    }
                };
                q[3 * second] = ref2[0];
                q[3 * second + 1] = ref2[1];
                q[3 * second + 2] = theta2;
                frames[second] = sin_cos2;
                let v = [j[0] - pivot[0], j[1] - pivot[1]];
                let (t1, (s1, c1)) = turn_to(v, r1, l1);
                let t1 = unwrap(t1, previous[3 * k + 2]);
                (t1, (s1, c1), hinged_at(pivot, (s1, c1), hinge.at_body))
            }
            Pattern::Hinged {
                hinge,
                angle,
                rider,
            } => {
                let pivot = place(q, frames, hinge.known, hinge.at_known);
                let (theta, sin_cos) = match angle {
                    Angle::Driven { other, sign, phi0 } => {
                        let base = other.map_or(D::from(0.0), |o| q[3 * o + 2]);
                        let theta = base + (phi - phi0) * sign;
                        (theta, theta.sin_cos())
                    }
                    Angle::SlotThroughPin {
                        direction: d,
                        c,
                        pin,
                        at,
                    } => {
                        let p = place(q, frames, pin, at);
                        let w = [p[0] - pivot[0], p[1] - pivot[1]];
                        let rho2 = w[0] * w[0] + w[1] * w[1];
                        let gap = c.abs() - rho2.re().sqrt();
                        // √disc = ρ |cos ψ|; its size is ρ² now (and the lever ρ itself
                        // shrinks as the pin nears the hinge: the margin is measured
                        // against ρ² in the sketch).
                        let root = self.root(rho2 - c * c, rho2, gap, step.branch, margin)?;
                        // e^{i(θ+δ)} ∝ w·(k − i c), then rotated back by δ = arg d.
                        let v = [w[0] * root + w[1] * c, w[1] * root - w[0] * c];
                        let x = v[0] * d[0] + v[1] * d[1];
                        let y = v[1] * d[0] - v[0] * d[1];
                        let inv = rho2.recip();
                        (atan2(y, x), (y * inv, x * inv))
                    }
                    Angle::PinInKnownSlot { line, r } => {
                        let u = rotate(frames, line.body, line.direction);
                        let a = place(q, frames, line.body, line.origin);
                        let c = cross_d(u, [a[0] - pivot[0], a[1] - pivot[1]]);
                        let rho2 = r[0] * r[0] + r[1] * r[1];
                        let gap = c.re().abs() - rho2.sqrt();
                        let root =
                            self.root(-c * c + rho2, D::from(rho2), gap, step.branch, margin)?;
                        // e^{i(θ+β)} ∝ u·(k + i c), then rotated back by β = arg r.
                        let v = [u[0] * root - u[1] * c, u[1] * root + u[0] * c];
                        let x = v[0] * r[0] + v[1] * r[1];
                        let y = v[1] * r[0] - v[0] * r[1];
                        (atan2(y, x), (y / rho2, x / rho2))
                    }
                    Angle::Rolling {
                        other,
                        sign,
                        slide,
                        s0,
                        radius,
                    } => {
                        let base = other.map_or(D::from(0.0), |o| q[3 * o + 2]);
                        let s = Frames { q, frames }.displacement(&slide);
                        let theta = base + (s - s0) * (sign / radius);
                        (theta, theta.sin_cos())
                    }
                    Angle::Geared { terms } => {
                        let theta = terms.iter().fold(D::from(0.0), |sum, &(b, k)| {
                            b.map_or(sum, |b| sum + q[3 * b + 2] * k)
                        });
                        (theta, theta.sin_cos())
                    }
                };
                let theta = match angle {
                    Angle::Driven { .. } | Angle::Rolling { .. } | Angle::Geared { .. } => theta,
                    _ => {
                        // The turn nearest to the previous pose's angle.
                        let gap = previous[3 * k + 2] - theta.re();
                        if gap.abs() > PI {
                            theta + (gap / TAU).round() * TAU
                        } else {
                            theta
                        }
                    }
                };
                if let Some((second, h2)) = rider {
                    let pivot2 = place(q, frames, h2.known, h2.at_known);
                    let r2 = hinged_at(pivot2, sin_cos, h2.at_body);
                    q[3 * second] = r2[0];
                    q[3 * second + 1] = r2[1];
                    q[3 * second + 2] = theta;
                    frames[second] = sin_cos;
                }
                (theta, sin_cos, hinged_at(pivot, sin_cos, hinge.at_body))
            }
            Pattern::Sliding {
                slide,
                offset,
                shift,
            } => {
                let g = slide.line.body;
                let theta = g.map_or(D::from(0.0), |g| q[3 * g + 2]);
                let sin_cos = g.map_or((D::from(0.0), D::from(1.0)), |g| frames[g]);
                let u = rotate(frames, g, slide.line.direction);
                let a = place(q, frames, g, slide.line.origin);
                // The slider's reference point at displacement 0: a + e₀ n − A p.
                let rp = rotate(frames, g, slide.point);
                let base = [a[0] - u[1] * offset - rp[0], a[1] + u[0] * offset - rp[1]];
                let s = match shift {
                    Shift::Driven { s0, phi0 } => phi - phi0 + s0,
                    Shift::SlotThroughPin { line, pin, at } => {
                        let v = rotate(frames, g, line.direction);
                        let o = rotate(frames, g, line.origin);
                        let p = place(q, frames, pin, at);
                        let d = [p[0] - base[0] - o[0], p[1] - base[1] - o[1]];
                        cross_d(v, d) / self.slope(cross_d(v, u), margin)?
                    }
                    Shift::PinInKnownSlot { line, p } => {
                        let v = rotate(frames, line.body, line.direction);
                        let o = place(q, frames, line.body, line.origin);
                        let pp = rotate(frames, g, p);
                        let d = [base[0] + pp[0] - o[0], base[1] + pp[1] - o[1]];
                        -cross_d(v, d) / self.slope(cross_d(v, u), margin)?
                    }
                    Shift::Rolling { a, b, s0, radius } => {
                        let angle = |x: Body| x.map_or(D::from(0.0), |x| q[3 * x + 2]);
                        (angle(b) - angle(a)) * radius + s0
                    }
                };
                (theta, sin_cos, [base[0] + u[0] * s, base[1] + u[1] * s])
            }
        };
        q[3 * k] = r[0];
        q[3 * k + 1] = r[1];
        q[3 * k + 2] = theta;
        frames[k] = sin_cos;
        let finite = [r[0], r[1], theta].iter().all(|x| x.re().is_finite());
        if finite {
            Ok(())
        } else {
            Err(Failure::Singular {
                condition: f64::INFINITY,
            })
        }
    }
}
