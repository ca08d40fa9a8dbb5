//! Length scales: the one measure of how big a set of sketch points is ([`extent`]), and the
//! scales the solver's thresholds are measured in.
//!
//! Every threshold of the geometry solver is dimensionless: a residual is compared with a
//! tolerance times a length, a Jacobian's angular rows are multiplied by a length before its
//! condition is estimated, a rank is decided on that scaled matrix. The length is **each
//! loop's own** ([`LoopLengths`]): the extent of the points its equations involve (the
//! joints' points and the reference points of the links it places), not the whole
//! mechanism's size. So a coupler point that takes part in no loop's closure — even one
//! 1e8 m away — changes no loop's verdict, and scaling the whole mechanism by any factor
//! scales every loop's length by that factor, which the thresholds divide out.

use super::branch::Loop;
use super::constraints::Equations;
use super::model::{GROUND, JointKind, Mechanism};

/// The diagonal of the box around `points` (0 for none): the one measure of how big a set
/// of sketch points is.
///
/// ```
/// use mechdiff_core::geometry::extent;
/// assert_eq!(extent([[0.0, 0.0], [0.3, 0.4], [0.1, 0.1]]), 0.5);
/// assert_eq!(extent([[2.0, 1.0]]), 0.0);
/// ```
pub fn extent(points: impl IntoIterator<Item = [f64; 2]>) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in points {
        for i in 0..2 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    if lo[0] > hi[0] {
        0.0
    } else {
        (hi[0] - lo[0]).hypot(hi[1] - lo[1])
    }
}

/// The mechanism's own length scale (m): the [`extent`] of the points carried by moving
/// links (a point only on the ground — a guide's far direction point, a mark — does not
/// count); that of all points if the moving links' points coincide, 1 m if all points do.
pub(crate) fn sketch_size(m: &Mechanism) -> f64 {
    let moving = (m.links.iter())
        .filter(|l| l.name != GROUND)
        .flat_map(|l| l.points.iter().map(|&p| m.points[p].sketch));
    let own = extent(moving);
    if own > 0.0 {
        return own;
    }
    let all = extent(m.points.iter().map(|p| p.sketch));
    if all > 0.0 { all } else { 1.0 }
}

/// The points (indices) joint `j`'s equations involve: its own, those of the joints a
/// rolling or gear contact couples, the reference points of the moving links a weld joins.
fn joint_points(m: &Mechanism, j: usize, out: &mut Vec<usize>) {
    match m.joints[j].kind {
        JointKind::Revolute { point, .. } => out.push(point),
        JointKind::Prismatic { line, point, .. } => out.extend([line[0], line[1], point]),
        JointKind::PinInSlot { line, pin, .. } => out.extend([line[0], line[1], pin]),
        JointKind::RackPinion { pinion, rack, .. } => {
            joint_points(m, pinion, out);
            joint_points(m, rack, out);
        }
        JointKind::Gear {
            joint_a, joint_b, ..
        } => {
            joint_points(m, joint_a, out);
            joint_points(m, joint_b, out);
        }
        JointKind::Rigid { link_a, link_b } => {
            let references = [link_a, link_b].into_iter().filter(|&k| k != 0);
            out.extend(references.filter_map(|k| m.links[k].points.first().copied()));
        }
    }
}

/// The length scale of joint `j` (m): the [`extent`] of its points and of the reference
/// points of the moving links it joins (what its residual's rounding is proportional to);
/// the mechanism's [`sketch_size`] where those coincide.
pub(crate) fn joint_length(m: &Mechanism, j: usize) -> f64 {
    let mut indices = Vec::new();
    joint_points(m, j, &mut indices);
    let mut points: Vec<[f64; 2]> = indices.iter().map(|&p| m.points[p].sketch).collect();
    let links = m.joints[j].kind.joined_links().unwrap_or_default();
    points.extend((links.into_iter().filter(|&k| k != 0)).map(|k| m.reference_sketch(k)));
    let own = extent(points);
    if own > 0.0 { own } else { sketch_size(m) }
}

/// The points loop `l`'s equations involve: its joints' points and the reference points of
/// the links it places (their lever arms are the Jacobian's entries).
fn loop_points(m: &Mechanism, eq: &Equations, l: &Loop) -> Vec<[f64; 2]> {
    let links = l.columns.iter().map(|&c| c / 3 + 1);
    let mut points: Vec<[f64; 2]> = links.map(|k| m.reference_sketch(k)).collect();
    let mut indices = Vec::new();
    for &r in &l.rows {
        let j = eq.row_joint[r];
        let joint = if j == m.joints.len() {
            m.drive_joint
        } else {
            j
        };
        joint_points(m, joint, &mut indices);
    }
    points.extend(indices.iter().map(|&p| m.points[p].sketch));
    points
}

/// The linkage's length scale (m): the [`extent`] of the points carried by moving links
/// that a joint involves or that are a moving link's reference point — [`sketch_size`]'s
/// points without those that take part in no joint (a coupler point, however far); the
/// mechanism's [`sketch_size`] where those coincide.
fn linkage_length(m: &Mechanism) -> f64 {
    let mut involved = vec![false; m.points.len()];
    let mut indices = Vec::new();
    for j in 0..m.joints.len() {
        joint_points(m, j, &mut indices);
    }
    let moving = || m.links.iter().filter(|l| l.name != GROUND);
    indices.extend(moving().filter_map(|l| l.points.first().copied()));
    for p in indices {
        involved[p] = true;
    }
    let points = moving().flat_map(|l| l.points.iter().filter(|&&p| involved[p]));
    let own = extent(points.map(|&p| m.points[p].sketch));
    if own > 0.0 { own } else { sketch_size(m) }
}

/// The length scale of loop `l` (m): the [`extent`] of its [`loop_points`]; where those
/// coincide (a crank's loop: its pivot is its reference point), the extent of every point
/// of the links it places; where that is 0 too, the mechanism's [`sketch_size`].
fn loop_length(m: &Mechanism, eq: &Equations, l: &Loop) -> f64 {
    let own = extent(loop_points(m, eq, l));
    if own > 0.0 {
        return own;
    }
    let carried = (l.columns.iter().map(|&c| c / 3 + 1))
        .flat_map(|k| m.links[k].points.iter().map(|&p| m.points[p].sketch));
    let carried = extent(carried);
    if carried > 0.0 {
        carried
    } else {
        sketch_size(m)
    }
}

/// Each loop's own length scale, and through it each row's and each coordinate's: the
/// scales every threshold of the solver is measured in (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct LoopLengths {
    /// Per loop (in solving order), its length scale (m).
    pub loops: Vec<f64>,
    /// Per row of Φ, the length scale of its loop.
    pub rows: Vec<f64>,
    /// Per coordinate of q, the length scale of its loop.
    pub columns: Vec<f64>,
    /// The linkage's length scale (m; see [`linkage_length`]), for what concerns the whole
    /// mechanism: a displacement drive's longest step and the range searched for its
    /// limits, Newton's tolerance in generated code.
    pub linkage: f64,
}

impl LoopLengths {
    /// The scales of `loops` (a partition of `eq`'s rows and coordinates).
    pub fn new(m: &Mechanism, eq: &Equations, loops: &[Loop]) -> Self {
        let mut rows = vec![1.0; eq.rows()];
        let mut columns = vec![1.0; eq.coordinates()];
        let lengths: Vec<f64> = loops.iter().map(|l| loop_length(m, eq, l)).collect();
        for (l, &length) in loops.iter().zip(&lengths) {
            for &r in &l.rows {
                rows[r] = length;
            }
            for &c in &l.columns {
                columns[c] = length;
            }
        }
        LoopLengths {
            loops: lengths,
            rows,
            columns,
            linkage: linkage_length(m),
        }
    }

    /// One scale for every row and coordinate: where the equations split into no loops (an
    /// over- or under-constrained mechanism), the mechanism's [`sketch_size`].
    pub fn uniform(m: &Mechanism, eq: &Equations) -> Self {
        let size = sketch_size(m);
        LoopLengths {
            loops: vec![size],
            rows: vec![size; eq.rows()],
            columns: vec![size; eq.coordinates()],
            linkage: linkage_length(m),
        }
    }

    /// The scales of `m`'s loops, or [`LoopLengths::uniform`] if there are none.
    pub fn of(m: &Mechanism, eq: &Equations) -> Self {
        match super::branch::loops(eq) {
            Some(loops) => Self::new(m, eq, &loops),
            None => Self::uniform(m, eq),
        }
    }
}
