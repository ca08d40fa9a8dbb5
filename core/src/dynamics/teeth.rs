//! Tooth forces in the bearings of meshing members.
//!
//! A rack-and-pinion or gear constraint ties rotations (and a rack's travel) together, so in
//! the equilibrium equations it acts on the pinion or gear as a couple only. The real tooth
//! force is a force at the pitch point (tangential, pressure angle 0) whose moment about the
//! wheel's centre is that couple; the wheel's bearing carries it. When the meshing members
//! turn on a common link (a frame, or one carrier), the couple's force is added back to the
//! bearing reactions: `R = λ_bearing − s·λ_mesh·F`, with `F` the force on the wheel per unit
//! mesh multiplier and `s` the mesh's efficiency factor on that side.

use super::efficiency::{CompiledEfficiency, Driving};
use super::state::{LinkState, cross, of};
use crate::geometry::{JointKind, Mechanism};

/// The tooth force carried by one bearing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Tooth {
    /// The wheel's revolute joint.
    pub bearing: usize,
    /// The mesh's row.
    pub row: usize,
    /// Force on the wheel (global) per unit mesh multiplier.
    pub force: [f64; 2],
    /// The mesh's efficiency (index) when this side is its output side.
    pub output: Option<usize>,
}

fn revolute(m: &Mechanism, j: usize) -> Option<(usize, usize)> {
    match m.joints[j].kind {
        JointKind::Revolute { link_a, point, .. } => Some((link_a, point)),
        _ => None,
    }
}

/// The efficiency index of mesh `j` if `side` is its output (not its driving) side.
fn output(efficiency: &[CompiledEfficiency], j: usize, side: Driving) -> Option<usize> {
    efficiency
        .iter()
        .position(|e| e.joint == j && e.driving != side)
}

/// The tooth forces of every mesh whose members turn on a common link.
pub(super) fn teeth(
    m: &Mechanism,
    rows: &[usize],
    states: &[LinkState],
    efficiency: &[CompiledEfficiency],
) -> Vec<Tooth> {
    let mut out = Vec::new();
    for (j, joint) in m.joints.iter().enumerate() {
        match joint.kind {
            JointKind::RackPinion { pinion, rack, .. } => {
                let Some((carrier, _)) = revolute(m, pinion) else {
                    continue;
                };
                let JointKind::Prismatic { guide, line, .. } = m.joints[rack].kind else {
                    continue;
                };
                if carrier != guide {
                    continue;
                }
                let (p, q) = (m.points[line[0]].sketch, m.points[line[1]].sketch);
                let d = [q[0] - p[0], q[1] - p[1]];
                let len = d[0].hypot(d[1]);
                // The couple R·λ on the pinion is the moment of λ·u at the pitch point.
                let u = of(states, guide).arm([d[0] / len, d[1] / len]);
                out.push(Tooth {
                    bearing: pinion,
                    row: rows[j],
                    force: u,
                    output: output(efficiency, j, Driving::First),
                });
            }
            JointKind::Gear {
                joint_a,
                joint_b,
                ratio,
            } => {
                let (Some((carrier, pa)), Some((carrier_b, pb))) =
                    (revolute(m, joint_a), revolute(m, joint_b))
                else {
                    continue;
                };
                if carrier != carrier_b {
                    continue;
                }
                let s = of(states, carrier);
                let c1 = s.position(m.local(carrier, m.points[pa].sketch));
                let c2 = s.position(m.local(carrier, m.points[pb].sketch));
                let dist = (c2[0] - c1[0]).hypot(c2[1] - c1[1]);
                if dist.is_nan() || dist <= 0.0 || ratio == 1.0 {
                    continue;
                }
                let e = [(c2[0] - c1[0]) / dist, (c2[1] - c1[1]) / dist];
                let t = [-e[1], e[0]];
                // Pitch radii from rolling, r1 |ω1| = r2 |ω2|: external mesh (ratio < 0)
                // r1 + r2 = d; internal |r2 − r1| = d. P: the pitch point on the line of centres.
                let r2 = dist / (1.0 - ratio).abs();
                let r1 = ratio.abs() * r2;
                let along = if ratio < 0.0 || r1 > r2 { r1 } else { -r1 };
                let p = [c1[0] + along * e[0], c1[1] + along * e[1]];
                // Couples per unit λ: +ratio on gear 1, −1 on gear 2 (the mesh row's gradient).
                for (bearing, c, torque, side) in [
                    (joint_a, c1, ratio, Driving::First),
                    (joint_b, c2, -1.0, Driving::Second),
                ] {
                    let arm = cross([p[0] - c[0], p[1] - c[1]], t);
                    if arm == 0.0 {
                        continue;
                    }
                    let f = torque / arm;
                    out.push(Tooth {
                        bearing,
                        row: rows[j],
                        force: [f * t[0], f * t[1]],
                        output: output(efficiency, j, side),
                    });
                }
            }
            _ => {}
        }
    }
    out
}
