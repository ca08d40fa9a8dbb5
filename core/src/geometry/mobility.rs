//! Mobility: the Grübler count and the rank of Φ_q at the sketch pose.
//!
//! A planar mechanism with `n` moving links has `3n` pose coordinates; each joint removes as
//! many freedoms as it has equations. The Grübler–Kutzbach count is
//! `F = 3n − Σ equations(joints)`; with the drive it must leave no freedom. The count alone
//! is blind to redundant joints (a parallelogram's extra link, a slider guided twice), so the
//! rank of the (scaled) Jacobian at the sketch pose decides:
//! - rows in the left null space of Φ_q ⇒ **over-constrained**: the joints owning those rows
//!   are named (together they say the same thing twice);
//! - columns in the right null space ⇒ **under-constrained**: the links that can still move
//!   with the drive fixed, and the joints attached to them, are named;
//! - a square system whose structure fixes every coordinate (a perfect matching of
//!   equations to coordinates exists) but whose Jacobian is rank deficient is drawn at a
//!   **singular** pose (a toggle): [`Error::Singular`] at the sketch's drive value.

use super::branch::SVD_ITERATIONS;
use super::constraints::Equations;
use super::length::LoopLengths;
use super::model::{JointKind, Mechanism};
use crate::Error;
use nalgebra::DMatrix;

/// Singular values below this fraction of the largest count as zero (the sketch is exact
/// to ~1e-15 relative, so a true dependency gives ~1e-15 and a weak but real constraint
/// stays well above).
const RANK_TOLERANCE: f64 = 1e-9;

/// The most pose coordinates (3 per moving link: 1000 moving links) whose Jacobian the
/// check holds, dense, in memory (72 MB at the limit).
pub const MAX_COORDINATES: usize = 3000;

/// Up to this many coordinates, the rank is that of one SVD of the whole Jacobian; beyond,
/// a square Jacobian whose structure splits into loops is judged loop by loop (it is block
/// triangular, so it is singular exactly when one of its diagonal blocks is): time
/// O(Σ loop³) instead of O(n³), about a second for an 800-link chain of four-bars instead of
/// minutes.
const WHOLE_SVD_UP_TO: usize = 120;

/// The outcome of a successful mobility check.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Mobility {
    /// Pose coordinates (3 per moving link).
    pub coordinates: usize,
    /// Joint equations, drive excluded.
    pub joint_equations: usize,
    /// Grübler–Kutzbach degrees of freedom `3n − Σ equations` (1 for a drivable mechanism).
    pub degrees_of_freedom: i64,
    /// Rank of Φ_q (drive included) at the sketch pose.
    pub rank: usize,
}

/// Φ_q at `q` with angular rows and angular columns multiplied by their loop's length (see
/// [`LoopLengths`]), so that every entry of a row is a length or every one dimensionless.
pub(crate) fn scaled_jacobian(eq: &Equations, q: &[f64], lengths: &LoopLengths) -> DMatrix<f64> {
    let mut jac = DMatrix::zeros(eq.rows(), eq.coordinates());
    eq.jacobian(q, &mut jac);
    scale(eq, &mut jac, lengths);
    jac
}

/// Applies the scaling of [`scaled_jacobian`] in place.
pub(crate) fn scale(eq: &Equations, jac: &mut DMatrix<f64>, lengths: &LoopLengths) {
    for (r, &angular) in eq.angular.iter().enumerate() {
        if angular {
            jac.row_mut(r).scale_mut(lengths.rows[r]);
        }
    }
    for k in 0..eq.coordinates() / 3 {
        jac.column_mut(3 * k + 2)
            .scale_mut(lengths.columns[3 * k + 2]);
    }
}

/// Scales every non-zero column of `jac` to unit length: what is left is independent of
/// the units of the coordinates (a translation in m, a rotation in rad), so singular values
/// compare the equations, not the scales.
pub(crate) fn unit_columns(jac: &mut DMatrix<f64>) {
    for mut c in jac.column_iter_mut() {
        let norm = c.norm();
        if norm > 0.0 {
            c /= norm;
        }
    }
}

/// Checks that the drive fixes the pose at the sketch, naming the joints if it does not.
///
/// ```
/// use mechdiff_core::geometry::{check_mobility, Drive, Mechanism};
/// let crank = Mechanism::builder()
///     .point("O", [0.0, 0.0]).point("A", [1.0, 0.0])
///     .ground(["O"]).link("crank", ["O", "A"])
///     .revolute("O", "ground", "crank", "O")
///     .drive(Drive::angle("O"))
///     .build().unwrap();
/// let mobility = check_mobility(&crank).unwrap();
/// assert_eq!((mobility.degrees_of_freedom, mobility.rank), (1, 3));
/// ```
pub fn check_mobility(m: &Mechanism) -> Result<Mobility, Error> {
    let eq = Equations::new(m);
    let (rows, cols) = (eq.rows(), eq.coordinates());
    let joint_equations = rows - 1;
    if rows.max(cols) > MAX_COORDINATES {
        return Err(Error::TooLarge {
            what: "pose coordinates (3 per moving link)",
            count: cols,
            limit: MAX_COORDINATES,
        });
    }
    // each loop's rows and columns in its own length scale, the columns then of unit length:
    // the rank and the condition are those of the mechanism's shape, whatever its size
    let lengths = LoopLengths::of(m, &eq);
    let mut jac = scaled_jacobian(&eq, &m.sketch_coordinates(), &lengths);
    unit_columns(&mut jac);
    if rows == cols
        && rows > WHOLE_SVD_UP_TO
        && let Some(loops) = super::branch::loops(&eq)
    {
        return by_loops(m, &eq, &jac, &loops);
    }
    // Pad to a square matrix so that the SVD gives both complete null spaces.
    let size = rows.max(cols);
    let mut square = DMatrix::zeros(size, size);
    square.view_mut((0, 0), (rows, cols)).copy_from(&jac);
    // Bounded: an SVD of a matrix with non-finite entries (a radius of 1e308 squared)
    // would iterate forever.
    let svd = square
        .iter()
        .all(|x| x.is_finite())
        .then(|| {
            square
                .clone()
                .try_svd(true, true, f64::EPSILON, SVD_ITERATIONS)
        })
        .flatten()
        .ok_or(Error::NonFinite {
            phi: m.drive_at_sketch,
            quantity: "the constraint Jacobian at the sketch (a length too large for f64?)",
        })?;
    let (u, v_t) = (svd.u.expect("requested"), svd.v_t.expect("requested"));
    let sigma_max = svd.singular_values.max();
    let null: Vec<usize> = (0..size)
        .filter(|&i| svd.singular_values[i] <= RANK_TOLERANCE * sigma_max.max(f64::MIN_POSITIVE))
        .collect();
    let rank = size - null.len();
    let name_of_row = |r: usize| {
        let j = eq.row_joint[r];
        if j == m.joints.len() {
            format!("drive `{}`", m.joints[m.drive_joint].name)
        } else {
            m.joints[j].name.clone()
        }
    };
    if rank < rows {
        // Left null space: rows that combine to zero.
        let mut joints: Vec<String> = Vec::new();
        for r in 0..rows {
            let weight = null.iter().map(|&i| u[(r, i)].abs()).fold(0.0, f64::max);
            let name = name_of_row(r);
            if weight > 1e-6 && !joints.contains(&name) {
                joints.push(name);
            }
        }
        if rows == cols && super::branch::loops(&eq).is_some() {
            // The count is right and every coordinate is structurally fixed: the Jacobian is
            // singular only because of where the sketch is drawn (a toggle, or a dead centre
            // of a driven slider).
            let sigma_min = svd.singular_values.min();
            return Err(singular_sketch(m, sigma_max, sigma_min, joints));
        }
        return Err(Error::Overconstrained {
            redundant: joints,
            equations: rows,
            coordinates: cols,
        });
    }
    if rank < cols {
        // Right null space: coordinate motions that no equation sees.
        let mut free_links: Vec<usize> = Vec::new();
        for k in 0..cols / 3 {
            let weight = null
                .iter()
                .flat_map(|&i| (0..3).map(move |c| (i, 3 * k + c)))
                .map(|(i, c)| v_t[(i, c)].abs())
                .fold(0.0, f64::max);
            if weight > 1e-6 {
                free_links.push(k + 1);
            }
        }
        let joints = m
            .joints
            .iter()
            .filter(|j| links_of(&j.kind, m).iter().any(|l| free_links.contains(l)))
            .map(|j| j.name.clone())
            .collect();
        return Err(Error::Underconstrained {
            free: cols - rank,
            links: free_links
                .iter()
                .map(|&k| m.links[k].name.clone())
                .collect(),
            joints,
        });
    }
    Ok(Mobility {
        coordinates: cols,
        joint_equations,
        degrees_of_freedom: cols as i64 - joint_equations as i64,
        rank,
    })
}

/// The rank check of a square Jacobian whose structure splits into `loops`, one block at
/// a time: each diagonal block must be non-singular, relative to the largest singular value
/// of all blocks; a singular block is a drawing at a singular pose ([`Error::Singular`], as
/// the whole-matrix check says), naming the joints of its dependent rows.
fn by_loops(
    m: &Mechanism,
    eq: &Equations,
    jac: &DMatrix<f64>,
    loops: &[super::branch::Loop],
) -> Result<Mobility, Error> {
    let non_finite = Error::NonFinite {
        phi: m.drive_at_sketch,
        quantity: "the constraint Jacobian at the sketch (a length too large for f64?)",
    };
    if !jac.iter().all(|x| x.is_finite()) {
        return Err(non_finite);
    }
    let mut blocks = Vec::with_capacity(loops.len());
    for l in loops {
        let block = jac.select_rows(&l.rows).select_columns(&l.columns);
        let svd = block
            .try_svd(true, false, f64::EPSILON, SVD_ITERATIONS)
            .ok_or(non_finite.clone())?;
        blocks.push(svd);
    }
    let sigma_max = blocks
        .iter()
        .map(|svd| svd.singular_values.max())
        .fold(f64::MIN_POSITIVE, f64::max);
    for (l, svd) in loops.iter().zip(&blocks) {
        let sigma_min = svd.singular_values.min();
        if sigma_min > RANK_TOLERANCE * sigma_max {
            continue;
        }
        let u = svd.u.as_ref().expect("requested");
        let null: Vec<usize> = (0..l.rows.len())
            .filter(|&i| svd.singular_values[i] <= RANK_TOLERANCE * sigma_max)
            .collect();
        let mut joints: Vec<String> = Vec::new();
        for (r, &row) in l.rows.iter().enumerate() {
            let weight = null.iter().map(|&i| u[(r, i)].abs()).fold(0.0, f64::max);
            let j = eq.row_joint[row];
            let name = if j == m.joints.len() {
                format!("drive `{}`", m.joints[m.drive_joint].name)
            } else {
                m.joints[j].name.clone()
            };
            if weight > 1e-6 && !joints.contains(&name) {
                joints.push(name);
            }
        }
        return Err(singular_sketch(m, sigma_max, sigma_min, joints));
    }
    let size = eq.coordinates();
    Ok(Mobility {
        coordinates: size,
        joint_equations: size - 1,
        degrees_of_freedom: 1,
        rank: size,
    })
}

/// The sketch is a singular position: the condition of the scaled Jacobian (infinite for a
/// zero singular value), naming the joints of its null space.
fn singular_sketch(m: &Mechanism, sigma_max: f64, sigma_min: f64, joints: Vec<String>) -> Error {
    Error::Singular {
        phi: m.drive_at_sketch,
        condition: if sigma_min > 0.0 {
            sigma_max / sigma_min
        } else {
            f64::INFINITY
        },
        joints,
    }
}

/// The links a joint connects (for rack/gear joints, those of the joints they couple).
fn links_of(kind: &JointKind, m: &Mechanism) -> Vec<usize> {
    if let Some(links) = kind.joined_links() {
        return links.to_vec();
    }
    match *kind {
        JointKind::RackPinion {
            pinion: a, rack: b, ..
        }
        | JointKind::Gear {
            joint_a: a,
            joint_b: b,
            ..
        } => {
            let mut v = links_of(&m.joints[a].kind, m);
            v.extend(links_of(&m.joints[b].kind, m));
            v
        }
        // every other joint joins two links (above)
        _ => Vec::new(),
    }
}
