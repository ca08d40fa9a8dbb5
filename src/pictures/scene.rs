//! Drawings of a scene's mechanism: every point's position at chosen drive positions
//! ([`Poses`]), and how the links, joints, ground, guides, sliders and gears are drawn from
//! them ([`Rig`]).

use mechdiff_core::geometry::{Mechanism, PointOutput};
use mechdiff_core::{DriveState, Jet};

use super::drawing::{Drawing, Style};
use crate::error::{Error, Result};
use crate::scene::context::GROUND;
use crate::scene::model::{JointKind, Scene};
use crate::scene::units::Dimension;

/// Every scene point's position at a list of drive positions.
#[derive(Debug, Clone, PartialEq)]
pub struct Poses {
    /// The drive positions (SI).
    pub phi: Vec<f64>,
    /// Per drive position, the position of every point of the scene (in the order of
    /// [`Scene::points`], m).
    pub xy: Vec<Vec<[f64; 2]>>,
}

impl Poses {
    /// The path of point `k` over the poses.
    pub fn path(&self, k: usize) -> Vec<[f64; 2]> {
        self.xy.iter().map(|pose| pose[k]).collect()
    }
}

/// Where each point is read from: a moving link's point output, or fixed at its sketch place.
enum Source {
    Moving(PointOutput),
    Fixed([f64; 2]),
}

/// Solves the scene at the drive positions `phi`, in order, from the sketch (keeping the
/// sketch's assembly branches, as a run does), and reads every point.
pub fn poses(scene: &Scene, mechanism: &Mechanism, phi: &[f64]) -> Result<Poses> {
    let xy = jets(scene, mechanism, phi)?
        .into_iter()
        .map(|pose| pose.iter().map(|p| p.map(|j| j.value)).collect())
        .collect();
    Ok(Poses {
        phi: phi.to_vec(),
        xy,
    })
}

/// The velocity and acceleration `[v, a]` (m/s, m/s²) of every scene point at each of the
/// drive positions `phi` (solved as [`poses`] solves them), for the drive speed `omega` and
/// acceleration `alpha` (a cam drive's: its follower's motion is taken through s(θ)).
pub fn point_motions(
    scene: &Scene,
    mechanism: &Mechanism,
    phi: &[f64],
    omega: f64,
    alpha: f64,
) -> Result<Vec<Vec<[[f64; 2]; 2]>>> {
    let drive = DriveState::accelerating(omega, alpha);
    let jets = jets(scene, mechanism, phi)?;
    Ok(phi
        .iter()
        .zip(jets)
        .map(|(&p, pose)| {
            // The driven joint's speed and acceleration: the drive's, or a cam follower's.
            let joint = match &scene.drive.cam {
                Some(c) => c.joint.drive_at(p, &drive).1,
                None => drive,
            };
            pose.iter()
                .map(|[x, y]| {
                    let (mx, my) = (x.motion(&joint), y.motion(&joint));
                    [
                        [mx.velocity, my.velocity],
                        [mx.acceleration, my.acceleration],
                    ]
                })
                .collect()
        })
        .collect())
}

/// Every point's position with its first two derivatives with respect to the driven joint,
/// at the drive positions `phi`, solved in order from the sketch.
fn jets(scene: &Scene, mechanism: &Mechanism, phi: &[f64]) -> Result<Vec<Vec<[Jet<2>; 2]>>> {
    let sources = scene
        .points
        .iter()
        .map(|p| {
            let link = scene
                .links
                .iter()
                .find(|l| l.name != GROUND && l.points.contains(&p.name));
            match link {
                Some(l) => mechanism
                    .point_output(&l.name, &p.name)
                    .map(Source::Moving)
                    .map_err(|e| scene.error_context().solver_error(e)),
                None => Ok(Source::Fixed(p.sketch)),
            }
        })
        .collect::<Result<Vec<_>>>()?;
    let mut tracker = scene
        .solver
        .track(mechanism)
        .map_err(|e| scene.error_context().solver_error(e))?;
    let mut out = Vec::with_capacity(phi.len());
    for &p in phi {
        let p = scene.drive.joint_position(p);
        tracker
            .move_to(p)
            .map_err(|e| scene.error_context().solver_error(e))?;
        out.push(
            sources
                .iter()
                .map(|s| match s {
                    Source::Moving(point) => tracker.position(point),
                    Source::Fixed(at) => at.map(Jet::from),
                })
                .collect(),
        );
    }
    Ok(out)
}

/// The sketch pose: every point where the file puts it.
pub fn sketch_pose(scene: &Scene) -> Vec<[f64; 2]> {
    scene.points.iter().map(|p| p.sketch).collect()
}

/// How a scene is drawn, by point index (into [`Scene::points`]): the same rig draws every
/// pose, and the HTML report moves its elements from frame to frame by these indices.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Rig {
    /// Links drawn as bars (two points) or outlines (their convex hull, three or more).
    pub links: Vec<Vec<usize>>,
    /// Fixed pivots (ground symbols).
    pub grounds: Vec<usize>,
    /// Guides fixed to the ground, by their two line points.
    pub guides: Vec<[usize; 2]>,
    /// Slider blocks: the block's point and the two points of its line.
    pub blocks: Vec<(usize, [usize; 2])>,
    /// Pitch circles: centre point and radius (m).
    pub circles: Vec<(usize, f64)>,
    /// Points drawn as joints with their names.
    pub joints: Vec<usize>,
}

impl Rig {
    /// The rig of a scene.
    pub fn of(scene: &Scene) -> Rig {
        let index = |name: &str| scene.points.iter().position(|p| p.name == name);
        let mut rig = Rig::default();
        for link in scene.links.iter().filter(|l| l.name != GROUND) {
            let points: Vec<usize> = link.points.iter().filter_map(|p| index(p)).collect();
            let hull = hull(&points, &sketch_pose(scene));
            if hull.len() >= 2 {
                rig.links.push(hull);
            }
        }
        let on_ground = |links: &[String; 2]| links[0] == GROUND;
        let revolute = |joint: &str| {
            scene.joints.iter().find_map(|j| match &j.kind {
                JointKind::Revolute { at, .. } if j.name == joint => index(at),
                _ => None,
            })
        };
        for joint in &scene.joints {
            match &joint.kind {
                JointKind::Revolute { links, at } => {
                    if links.contains(&GROUND.to_owned())
                        && let Some(k) = index(at)
                    {
                        rig.grounds.push(k);
                    }
                }
                JointKind::Prismatic { links, line, point } => {
                    if let (Some(p), Some(a), Some(b)) =
                        (index(point), index(&line[0]), index(&line[1]))
                    {
                        rig.blocks.push((p, [a, b]));
                        if on_ground(links) {
                            rig.guides.push([a, b]);
                        }
                    }
                }
                JointKind::PinInSlot { links, slot, pin } => {
                    if let (Some(p), Some(a), Some(b)) =
                        (index(pin), index(&slot[0]), index(&slot[1]))
                    {
                        rig.blocks.push((p, [a, b]));
                        if on_ground(links) {
                            rig.guides.push([a, b]);
                        }
                    }
                }
                JointKind::RackPinion { pinion, radius, .. } => {
                    if let Some(k) = revolute(pinion) {
                        rig.circles.push((k, radius.abs()));
                    }
                }
                JointKind::Gear { joints, ratio } => {
                    if let (Some(a), Some(b)) = (revolute(&joints[0]), revolute(&joints[1])) {
                        let [pa, pb] = [scene.points[a].sketch, scene.points[b].sketch];
                        let d = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
                        // External mesh (ratio < 0): r_a + r_b = d; internal: |r_b − r_a| = d;
                        // and r_b = |ratio| r_a.
                        let q = ratio.abs();
                        let ra = if *ratio < 0.0 {
                            d / (1.0 + q)
                        } else {
                            d / (q - 1.0).abs()
                        };
                        if ra.is_finite() && ra > 0.0 {
                            rig.circles.push((a, ra));
                            rig.circles.push((b, q * ra));
                        }
                    }
                }
                JointKind::Weld { .. } => {}
            }
        }
        rig.grounds.sort_unstable();
        rig.grounds.dedup();
        rig.joints = (0..scene.points.len()).collect();
        rig
    }

    /// The drawing of `pose` (every point's position), framed to include `extent` as well,
    /// with the traced `paths` (point index and its path).
    pub fn drawing(
        &self,
        scene: &Scene,
        title: &str,
        pose: &[[f64; 2]],
        extent: &[[f64; 2]],
        paths: &[(usize, Vec<[f64; 2]>)],
    ) -> Drawing {
        let units = &scene.units;
        let mut d = Drawing::new(title).include(extent).unit(
            units.symbol(Dimension::Length),
            units.to_si(1.0, Dimension::Length),
        );
        for [a, b] in &self.guides {
            let (from, to) = guide_extent(pose[*a], pose[*b], extent);
            d = d.guide(from, to);
        }
        for (k, path) in paths {
            d = d.path(&scene.points[*k].name, path);
        }
        for (k, r) in &self.circles {
            d = d
                .circle(pose[*k], *r, Style::construction())
                .bind(&format!("c {k}"));
        }
        for link in &self.links {
            let points: Vec<[f64; 2]> = link.iter().map(|&k| pose[k]).collect();
            let bind = format!(
                "p {}",
                link.iter()
                    .map(|k| k.to_string())
                    .collect::<Vec<_>>()
                    .join(" ")
            );
            d = if link.len() > 2 {
                d.polygon(&points, Style::link().filled("#cfe2f3"))
            } else {
                d.polyline(&points, Style::link())
            }
            .bind(&bind);
        }
        for (p, [a, b]) in &self.blocks {
            let (pa, pb) = (pose[*a], pose[*b]);
            let direction = (pb[1] - pa[1]).atan2(pb[0] - pa[0]);
            d = d.block(pose[*p], direction).bind(&format!("b {p} {a} {b}"));
        }
        for &k in &self.grounds {
            d = d.ground(pose[k]);
        }
        for &k in &self.joints {
            let name = &scene.points[k].name;
            d = d
                .joint(name, pose[k])
                .bind(&format!("c {k}"))
                .label_toward(pose[k], name, self.clear_of_links(k, pose))
                .bind(&format!("t {k}"));
        }
        d
    }

    /// The direction from point `k` away from the links at it: minus the sum of the unit
    /// vectors along its bars (to the other corners of each link holding it); a point on no
    /// link, or where the bars cancel, gets the normal of the first bar, else up-right.
    pub fn clear_of_links(&self, k: usize, pose: &[[f64; 2]]) -> [f64; 2] {
        let at = pose[k];
        let mut sum = [0.0, 0.0];
        let mut first = None;
        for link in self.links.iter().filter(|l| l.contains(&k)) {
            for &j in link.iter().filter(|&&j| j != k) {
                let (dx, dy) = (pose[j][0] - at[0], pose[j][1] - at[1]);
                let length = dx.hypot(dy);
                if length > 0.0 && length.is_finite() {
                    sum[0] -= dx / length;
                    sum[1] -= dy / length;
                    first.get_or_insert([-dy / length, dx / length]);
                }
            }
        }
        if sum[0].hypot(sum[1]) > 1e-6 {
            sum
        } else {
            first.unwrap_or([1.0, 1.0])
        }
    }

    /// Where the centres of mass of the scene's `[masses]` are at `pose`: each moved with its
    /// link (the rigid motion that takes the link's first two points from the sketch to the
    /// pose; a link of one point only translates).
    pub fn mass_centres(scene: &Scene, pose: &[[f64; 2]]) -> Vec<[f64; 2]> {
        let Some(dynamics) = &scene.dynamics else {
            return Vec::new();
        };
        let sketch = sketch_pose(scene);
        let index = |name: &str| scene.points.iter().position(|p| p.name == name);
        dynamics
            .masses
            .iter()
            .filter_map(|(link, inertia)| {
                let c = inertia.center;
                if link == GROUND {
                    return Some(c);
                }
                let link = scene.links.iter().find(|l| &l.name == link)?;
                let points: Vec<usize> = link.points.iter().filter_map(|p| index(p)).collect();
                let a = *points.first()?;
                let (sa, pa) = (sketch[a], pose[a]);
                let turn = points.iter().find(|&&b| sketch[b] != sa).map_or(0.0, |&b| {
                    let before = (sketch[b][1] - sa[1]).atan2(sketch[b][0] - sa[0]);
                    let after = (pose[b][1] - pa[1]).atan2(pose[b][0] - pa[0]);
                    after - before
                });
                let (sin, cos) = turn.sin_cos();
                let (dx, dy) = (c[0] - sa[0], c[1] - sa[1]);
                Some([pa[0] + cos * dx - sin * dy, pa[1] + sin * dx + cos * dy])
            })
            .collect()
    }
}

/// A guide through `a` and `b`, long enough to cover the projections of `a`, `b` and every
/// extent point onto its line.
fn guide_extent(a: [f64; 2], b: [f64; 2], extent: &[[f64; 2]]) -> ([f64; 2], [f64; 2]) {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let length = dx.hypot(dy);
    if length.is_nan() || length <= 0.0 {
        return (a, b);
    }
    let (ux, uy) = (dx / length, dy / length);
    let along = |p: [f64; 2]| (p[0] - a[0]) * ux + (p[1] - a[1]) * uy;
    // Only points near the line count (the slider's own path), not the whole mechanism.
    let near = |p: &&[f64; 2]| {
        ((p[0] - a[0]) * uy - (p[1] - a[1]) * ux).abs() <= 0.02 * length.max(1e-9) + 1e-12
    };
    let (lo, hi) = extent
        .iter()
        .filter(near)
        .map(|&p| along(p))
        .chain([0.0, length])
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), t| {
            (lo.min(t), hi.max(t))
        });
    let pad = 0.05 * (hi - lo);
    let at = |t: f64| [a[0] + ux * t, a[1] + uy * t];
    (at(lo - pad), at(hi + pad))
}

/// The convex hull of the points (indices) in counter-clockwise order; for collinear points,
/// the two extreme ones.
fn hull(points: &[usize], pose: &[[f64; 2]]) -> Vec<usize> {
    let mut p: Vec<usize> = points.to_vec();
    p.sort_by(|&i, &j| {
        pose[i]
            .partial_cmp(&pose[j])
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    p.dedup_by(|i, j| pose[*i] == pose[*j]);
    if p.len() < 3 {
        return p;
    }
    let cross = |o: usize, a: usize, b: usize| {
        (pose[a][0] - pose[o][0]) * (pose[b][1] - pose[o][1])
            - (pose[a][1] - pose[o][1]) * (pose[b][0] - pose[o][0])
    };
    let scale = p
        .iter()
        .flat_map(|&i| pose[i])
        .fold(0.0_f64, |m, v| m.max(v.abs()))
        .max(1e-300);
    let tolerance = 1e-9 * scale * scale;
    let mut lower: Vec<usize> = Vec::new();
    for &i in &p {
        while lower.len() >= 2
            && cross(lower[lower.len() - 2], lower[lower.len() - 1], i) <= tolerance
        {
            lower.pop();
        }
        lower.push(i);
    }
    let mut upper: Vec<usize> = Vec::new();
    for &i in p.iter().rev() {
        while upper.len() >= 2
            && cross(upper[upper.len() - 2], upper[upper.len() - 1], i) <= tolerance
        {
            upper.pop();
        }
        upper.push(i);
    }
    lower.pop();
    upper.pop();
    lower.extend(upper);
    if lower.len() <= 2 {
        // Collinear: the two extremes.
        return vec![p[0], p[p.len() - 1]];
    }
    lower
}

/// The pose of `scene` at each drive position of `[plot] positions`, after checking that each
/// lies inside the run's range of drive positions `[lo, hi]`.
pub fn plot_positions(scene: &Scene, lo: f64, hi: f64) -> Result<Vec<f64>> {
    let slack = 1e-9 * (hi - lo).abs().max(lo.abs()).max(hi.abs()).max(1e-300);
    let mut out = Vec::new();
    for (phi, location) in &scene.plot.positions {
        if *phi < lo - slack || *phi > hi + slack {
            return Err(Error::Invalid {
                location: location.clone(),
                message: format!(
                    "drive position {} is outside the sweep ({} to {}); choose one inside it",
                    scene.drive_text(*phi),
                    scene.drive_text(lo),
                    scene.drive_text(hi)
                ),
            });
        }
        out.push(phi.clamp(lo, hi));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::hull;

    /// A square with a point inside: the hull is the four corners; collinear points: the ends.
    #[test]
    fn hull_of_a_square_and_of_a_line() {
        let pose = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.5]];
        let mut h = hull(&[0, 1, 2, 3, 4], &pose);
        h.sort_unstable();
        assert_eq!(h, vec![0, 1, 2, 3]);
        let line = [[0.0, 0.0], [0.0, 2.0], [0.0, 1.0]];
        let mut h = hull(&[0, 1, 2], &line);
        h.sort_unstable();
        assert_eq!(h, vec![0, 1]);
    }
}
