//! The linkages synthesis sizes, their design variables and their positions, written once
//! generic over the scalar.
//!
//! Each linkage is driven by the absolute angle φ of its crank O2–A (counter-clockwise from
//! the x axis) and assembled from closed-form dyads (the same formulas as the solver's RRR
//! and RRP patterns, see `geometry::closed_form`), each on a fixed branch σ = ±1:
//!
//! | linkage | variables (in order) | dyads |
//! |---|---|---|
//! | [`Linkage::FourBar`] | `o2x o2y o4x o4y crank coupler rocker px py` | RRR: A–B–O4 |
//! | [`Linkage::SliderCrank`] | `o2x o2y crank rod offset guide px py` | RRP: A–B on the guide |
//! | [`Linkage::StephensonSix`] | the four-bar's nine, then `o6x o6y link5 link6 qx qy` | RRR: A–B–O4, C–E–O6 |
//!
//! A = O2 + crank·(cos φ, sin φ). The four-bar's B closes |B − A| = coupler, |B − O4| = rocker;
//! the slider-crank's B lies on the guide line through O2 + offset·n at angle `guide`
//! (direction u = (cos guide, sin guide), n = u rotated by +90°) with |B − A| = rod. The
//! coupler point P = A + px·e + py·e⊥, e the unit vector A→B, e⊥ = e rotated by +90°. The
//! Stephenson III six-bar hangs a dyad C–E–O6 on the four-bar's coupler point C = P
//! (|E − C| = link5, |E − O6| = link6) and traces Q = C + qx·f + qy·f⊥, f the unit vector C→E.
//!
//! Every dyad also reports its margin sin²γ (γ the angle between its two links at the joint
//! it places, or between the rod and the guide's normal for the RRP dyad): 1 at its best, 0
//! at a limit position, negative where it cannot close.

use super::grashof::GrashofClass;
use crate::{Scalar, atan2};

/// A linkage kind that synthesis sizes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Linkage {
    /// Four-bar O2–A–B–O4 with a coupler point P.
    FourBar,
    /// Slider-crank O2–A–B, the slider B on a guide line, with a coupler point P on the rod.
    SliderCrank,
    /// Stephenson III six-bar: a four-bar whose coupler point C carries the dyad C–E–O6; the
    /// traced point Q is on link 5 (C–E).
    StephensonSix,
}

/// What a linkage's position reports: named points, named link angles and, for the
/// slider-crank, the slider's displacement.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkagePose<D> {
    /// Positions in the order of [`Linkage::point_names`].
    pub points: Vec<[D; 2]>,
    /// Outputs in the order of [`Linkage::output_names`]: link angles (rad, counter-clockwise
    /// from x) and displacements (m).
    pub outputs: Vec<D>,
    /// The angle of the traced link's frame (e = A→B, or f = C→E for the six-bar).
    pub traced_link_angle: D,
    /// Each dyad's margin sin²γ (f64: constraints are checked on values).
    pub margins: Vec<f64>,
}

/// Why a linkage cannot take a position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NoAssembly {
    /// Which dyad fails (0 = the first, A–B).
    pub dyad: usize,
    /// Its margin (≤ 0).
    pub margin: f64,
}

impl Linkage {
    /// The names of its design variables, in the order a parameter vector holds them.
    pub fn variable_names(self) -> &'static [&'static str] {
        match self {
            Linkage::FourBar => &FOUR_BAR[..],
            Linkage::SliderCrank => &["o2x", "o2y", "crank", "rod", "offset", "guide", "px", "py"],
            Linkage::StephensonSix => &SIX_BAR[..],
        }
    }

    /// The Grashof class of the four-bar loop O2–A–B–O4 of the mechanism `x` (its variables
    /// in order; ground |O4 − O2|, crank, coupler, rocker), or `None` for the slider-crank,
    /// which has no such loop, or an `x` too short to hold the loop.
    ///
    /// ```
    /// use mechdiff_core::synthesis::{GrashofClass, Linkage};
    /// // Ground |(1.2, 0.1)| ≈ 1.204, crank 0.4, coupler 1.1, rocker 0.9: 0.4 + 1.204 < 2.
    /// let x = [0.0, 0.0, 1.2, 0.1, 0.4, 1.1, 0.9, 0.5, 0.35];
    /// assert_eq!(Linkage::FourBar.grashof_class(&x), Some(GrashofClass::CrankRocker));
    /// assert_eq!(Linkage::SliderCrank.grashof_class(&x), None);
    /// ```
    pub fn grashof_class(self, x: &[f64]) -> Option<GrashofClass> {
        match (self, x) {
            (Linkage::SliderCrank, _) => None,
            (_, [o2x, o2y, o4x, o4y, crank, coupler, rocker, ..]) => {
                let ground = (o4x - o2x).hypot(o4y - o2y);
                Some(GrashofClass::of(ground, *crank, *coupler, *rocker))
            }
            _ => None,
        }
    }

    /// The names of the points whose paths it reports (`A`, `B`, the coupler point `P`; the
    /// six-bar's `E` and traced point `Q`).
    pub fn point_names(self) -> &'static [&'static str] {
        match self {
            Linkage::FourBar | Linkage::SliderCrank => &["A", "B", "P"],
            Linkage::StephensonSix => &["A", "B", "P", "E", "Q"],
        }
    }

    /// The names of its outputs: link angles, and the slider-crank's `slider` displacement.
    pub fn output_names(self) -> &'static [&'static str] {
        match self {
            Linkage::FourBar => &["crank", "coupler", "rocker"],
            Linkage::SliderCrank => &["crank", "rod", "slider"],
            Linkage::StephensonSix => &["crank", "coupler", "rocker", "link5", "link6"],
        }
    }

    /// Whether output `index` is an angle (rad) rather than a displacement (m).
    pub fn output_is_angle(self, index: usize) -> bool {
        !(self == Linkage::SliderCrank && index == 2)
    }

    /// The link whose poses motion generation prescribes (it carries the traced point).
    pub fn traced_link(self) -> &'static str {
        match self {
            Linkage::FourBar => "coupler",
            Linkage::SliderCrank => "rod",
            Linkage::StephensonSix => "link5",
        }
    }

    /// The name of the point path generation traces by default (`P`, or the six-bar's `Q`).
    pub fn traced_point(self) -> &'static str {
        match self {
            Linkage::StephensonSix => "Q",
            _ => "P",
        }
    }

    /// The number of dyads (and so of branch signs).
    pub fn dyad_count(self) -> usize {
        match self {
            Linkage::StephensonSix => 2,
            _ => 1,
        }
    }

    /// The linkage's position at drive angle `phi` for the variables `x` (in the order of
    /// [`Linkage::variable_names`]) on the branches `branch` (σ = ±1 per dyad).
    pub fn pose<D: Scalar>(
        self,
        x: &[D],
        phi: D,
        branch: &[f64],
    ) -> Result<LinkagePose<D>, NoAssembly> {
        match self {
            Linkage::FourBar => four_bar(x, phi, branch[0]).map(|f| LinkagePose {
                points: vec![f.a, f.b, f.p],
                outputs: vec![phi, f.coupler_angle, f.rocker_angle],
                traced_link_angle: f.coupler_angle,
                margins: vec![f.margin],
            }),
            Linkage::SliderCrank => slider_crank(x, phi, branch[0]),
            Linkage::StephensonSix => {
                let f = four_bar(&x[..9], phi, branch[0])?;
                let (o6, l5, l6) = ([x[9], x[10]], x[11], x[12]);
                let (e, margin) = rrr(f.p, o6, l5, l6, branch[1])
                    .map_err(|margin| NoAssembly { dyad: 1, margin })?;
                let (q, link5) = carried(f.p, e, l5, x[13], x[14]);
                let link6 = atan2(e[1] - o6[1], e[0] - o6[0]);
                Ok(LinkagePose {
                    points: vec![f.a, f.b, f.p, e, q],
                    outputs: vec![phi, f.coupler_angle, f.rocker_angle, link5, link6],
                    traced_link_angle: link5,
                    margins: vec![f.margin, margin],
                })
            }
        }
    }
}

const FOUR_BAR: [&str; 9] = [
    "o2x", "o2y", "o4x", "o4y", "crank", "coupler", "rocker", "px", "py",
];
const SIX_BAR: [&str; 15] = [
    "o2x", "o2y", "o4x", "o4y", "crank", "coupler", "rocker", "px", "py", "o6x", "o6y", "link5",
    "link6", "qx", "qy",
];

/// A four-bar's position: A, B, the coupler point P, the coupler's and rocker's angles and
/// the dyad's margin.
struct FourBarPose<D> {
    a: [D; 2],
    b: [D; 2],
    p: [D; 2],
    coupler_angle: D,
    rocker_angle: D,
    margin: f64,
}

fn four_bar<D: Scalar>(x: &[D], phi: D, branch: f64) -> Result<FourBarPose<D>, NoAssembly> {
    let (o2, o4) = ([x[0], x[1]], [x[2], x[3]]);
    let (crank, coupler, rocker) = (x[4], x[5], x[6]);
    let a = [o2[0] + crank * phi.cos(), o2[1] + crank * phi.sin()];
    let (b, margin) =
        rrr(a, o4, coupler, rocker, branch).map_err(|margin| NoAssembly { dyad: 0, margin })?;
    let (p, coupler_angle) = carried(a, b, coupler, x[7], x[8]);
    Ok(FourBarPose {
        a,
        b,
        p,
        coupler_angle,
        rocker_angle: atan2(b[1] - o4[1], b[0] - o4[0]),
        margin,
    })
}

fn slider_crank<D: Scalar>(x: &[D], phi: D, branch: f64) -> Result<LinkagePose<D>, NoAssembly> {
    let o2 = [x[0], x[1]];
    let (crank, rod, offset, guide) = (x[2], x[3], x[4], x[5]);
    let a = [o2[0] + crank * phi.cos(), o2[1] + crank * phi.sin()];
    let u = [guide.cos(), guide.sin()];
    let n = [-u[1], u[0]];
    let origin = [o2[0] + n[0] * offset, o2[1] + n[1] * offset];
    // B = origin + s·u with |B − A| = rod: w = origin − A, s = −u·w + σ√(rod² − (n·w)²).
    let w = [origin[0] - a[0], origin[1] - a[1]];
    let normal = n[0] * w[0] + n[1] * w[1];
    let disc = rod * rod - normal * normal;
    let margin = (disc / (rod * rod)).re();
    if margin.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return Err(NoAssembly { dyad: 0, margin });
    }
    let s = -(u[0] * w[0] + u[1] * w[1]) + disc.sqrt() * branch;
    let b = [origin[0] + u[0] * s, origin[1] + u[1] * s];
    let (p, rod_angle) = carried(a, b, rod, x[6], x[7]);
    Ok(LinkagePose {
        points: vec![a, b, p],
        outputs: vec![phi, rod_angle, s],
        traced_link_angle: rod_angle,
        margins: vec![margin],
    })
}

/// The RRR dyad's joint J with |J − k1| = l1, |J − k2| = l2 on branch σ (the side of k1→k2
/// J is on: + left), and its margin sin²γ; `Err(margin)` when it cannot close.
fn rrr<D: Scalar>(k1: [D; 2], k2: [D; 2], l1: D, l2: D, branch: f64) -> Result<([D; 2], f64), f64> {
    let d = [k2[0] - k1[0], k2[1] - k1[1]];
    let d2 = d[0] * d[0] + d[1] * d[1];
    let g = (l1 * l1 - l2 * l2 + d2) * 0.5;
    let disc = l1 * l1 * d2 - g * g;
    let margin = (disc / (l1 * l1 * l2 * l2)).re();
    // Not `margin <= 0.0`: a NaN margin (zero lengths) is no assembly either.
    if margin.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return Err(margin);
    }
    let root = disc.sqrt() * branch;
    Ok((
        [
            k1[0] + (g * d[0] - root * d[1]) / d2,
            k1[1] + (g * d[1] + root * d[0]) / d2,
        ],
        margin,
    ))
}

/// The point at (along, across) in the frame of the link from `from` to `to` (|to − from| =
/// `length`), and the link's angle.
fn carried<D: Scalar>(from: [D; 2], to: [D; 2], length: D, along: D, across: D) -> ([D; 2], D) {
    let e = [(to[0] - from[0]) / length, (to[1] - from[1]) / length];
    (
        [
            from[0] + e[0] * along - e[1] * across,
            from[1] + e[1] * along + e[0] * across,
        ],
        atan2(e[1], e[0]),
    )
}

impl Linkage {
    /// The variables of the same linkage moved as a rigid body and scaled: every point p
    /// taken to `scale`·R(`rotation`)·p + `shift`, lengths and coupler-point coordinates
    /// times `scale`, the slider's guide turned by `rotation` (its positions are then met
    /// at drive angles `rotation` greater). `scale` > 0 keeps every branch.
    pub(crate) fn similar(self, x: &[f64], scale: f64, rotation: f64, shift: [f64; 2]) -> Vec<f64> {
        let (sin, cos) = rotation.sin_cos();
        let mut y = x.to_vec();
        let mut point = |i: usize| {
            let (px, py) = (x[i], x[i + 1]);
            y[i] = scale * (cos * px - sin * py) + shift[0];
            y[i + 1] = scale * (sin * px + cos * py) + shift[1];
        };
        let (points, lengths): (&[usize], &[usize]) = match self {
            Linkage::FourBar => (&[0, 2], &[4, 5, 6, 7, 8]),
            Linkage::SliderCrank => (&[0], &[2, 3, 4, 6, 7]),
            Linkage::StephensonSix => (&[0, 2, 9], &[4, 5, 6, 7, 8, 11, 12, 13, 14]),
        };
        for &i in points {
            point(i);
        }
        for &i in lengths {
            y[i] = scale * x[i];
        }
        if self == Linkage::SliderCrank {
            y[5] = x[5] + rotation;
        }
        y
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn four_bar_closes_its_loop_on_both_branches() {
        let x: [f64; 9] = [0.0, 0.0, 1.0, 0.0, 0.4, 1.2, 0.9, 0.5, 0.3];
        for branch in [1.0, -1.0] {
            let pose = Linkage::FourBar.pose(&x, 0.7, &[branch]).unwrap();
            let [a, b] = [pose.points[0], pose.points[1]];
            // Lengths of order 1 formed from O(1) numbers: rounding ~1e-15.
            assert!(((b[0] - a[0]).hypot(b[1] - a[1]) - 1.2).abs() < 1e-14);
            assert!(((b[0] - 1.0).hypot(b[1]) - 0.9).abs() < 1e-14);
            // σ = +1 puts B left of A→O4.
            let side = (1.0 - a[0]) * (b[1] - a[1]) - (-a[1]) * (b[0] - a[0]);
            assert_eq!(side > 0.0, branch > 0.0);
        }
    }

    #[test]
    fn a_dyad_too_short_to_close_is_no_assembly() {
        let x: [f64; 9] = [0.0, 0.0, 3.0, 0.0, 0.4, 1.0, 1.0, 0.5, 0.3];
        let err = Linkage::FourBar.pose(&x, 0.0, &[1.0]).unwrap_err();
        assert_eq!(err.dyad, 0);
        assert!(err.margin < 0.0);
    }
}
