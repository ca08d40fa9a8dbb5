//! Loops and assembly-branch certificates.
//!
//! The square system Φ(q, φ) = 0 is split into **loops**: the diagonal blocks of its block
//! triangular form (a perfect matching of equations to coordinates, then the strongly
//! connected components of the equation graph, as in the Dulmage–Mendelsohn decomposition).
//! For the Whitworth these are {crank + drive}, {rocker}, {ram}; for the rack and slotted link
//! {rack + drive}, {slotted link}, {rod + slider}. Each loop is solved for its own coordinates
//! once the coordinates of the loops before it are known, so it is what a designer calls a
//! loop (a closed vector loop or a dyad).
//!
//! **Certificate.** det Φ_q is the product of the determinants of the diagonal blocks. A
//! block's determinant is a continuous function of the pose that vanishes only where that
//! loop is singular (where its two assembly branches meet); the two branches of a loop have
//! opposite signs (a four-bar's two closures, a slider on either side of its crank). The
//! sign of each block's determinant, taken at the sketch, is therefore that loop's branch
//! certificate: along a sweep it may change only by passing through a singular pose, and a
//! Newton step that lands on the other branch changes it.

use super::constraints::Equations;
use nalgebra::DMatrix;

/// Sweeps allowed to an SVD (a few tens suffice for the small matrices of a mechanism).
pub(crate) const SVD_ITERATIONS: usize = 10_000;

/// One loop: rows (equations) and the coordinates matched to them.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Loop {
    pub rows: Vec<usize>,
    pub columns: Vec<usize>,
}

/// Which coordinates each row depends on (whole bodies: x, y, θ together).
pub(crate) fn structure(eq: &Equations) -> Vec<Vec<usize>> {
    eq.row_bodies()
        .into_iter()
        .map(|bodies| {
            bodies
                .into_iter()
                .flat_map(|k| [3 * k, 3 * k + 1, 3 * k + 2])
                .collect()
        })
        .collect()
}

/// Finds a perfect matching rows → columns (augmenting paths); `None` if there is none.
fn matching(cols_of: &[Vec<usize>], columns: usize) -> Option<Vec<usize>> {
    fn augment(
        r: usize,
        cols_of: &[Vec<usize>],
        seen: &mut [bool],
        owner: &mut [Option<usize>],
    ) -> bool {
        for &c in &cols_of[r] {
            if !seen[c] {
                seen[c] = true;
                if owner[c].is_none_or(|r2| augment(r2, cols_of, seen, owner)) {
                    owner[c] = Some(r);
                    return true;
                }
            }
        }
        false
    }
    if cols_of.len() != columns {
        return None;
    }
    let mut owner = vec![None; columns];
    for r in 0..cols_of.len() {
        let mut seen = vec![false; columns];
        if !augment(r, cols_of, &mut seen, &mut owner) {
            return None;
        }
    }
    let mut col_of_row = vec![0; cols_of.len()];
    for (c, r) in owner.iter().enumerate() {
        col_of_row[r.expect("perfect matching")] = c;
    }
    Some(col_of_row)
}

/// Splits a square, structurally non-singular system into its loops, in solving order.
/// `None` if the structure has no perfect matching (the mobility check reports that case).
pub(crate) fn loops(eq: &Equations) -> Option<Vec<Loop>> {
    let cols_of = structure(eq);
    let col_of_row = matching(&cols_of, eq.coordinates())?;
    let mut row_of_col = vec![0; col_of_row.len()];
    for (r, &c) in col_of_row.iter().enumerate() {
        row_of_col[c] = r;
    }
    // Edge r → r2: row r needs the coordinate solved by row r2.
    let edges: Vec<Vec<usize>> = cols_of
        .iter()
        .map(|cs| cs.iter().map(|&c| row_of_col[c]).collect())
        .collect();
    let components = tarjan(&edges);
    Some(
        components
            .into_iter()
            .map(|mut rows| {
                rows.sort_unstable();
                let columns = rows.iter().map(|&r| col_of_row[r]).collect();
                Loop { rows, columns }
            })
            .collect(),
    )
}

/// Strongly connected components; Tarjan's algorithm emits them dependencies first.
fn tarjan(edges: &[Vec<usize>]) -> Vec<Vec<usize>> {
    struct State<'a> {
        edges: &'a [Vec<usize>],
        index: Vec<Option<usize>>,
        low: Vec<usize>,
        on_stack: Vec<bool>,
        stack: Vec<usize>,
        next: usize,
        out: Vec<Vec<usize>>,
    }
    fn visit(s: &mut State<'_>, v: usize) {
        s.index[v] = Some(s.next);
        s.low[v] = s.next;
        s.next += 1;
        s.stack.push(v);
        s.on_stack[v] = true;
        for i in 0..s.edges[v].len() {
            let w = s.edges[v][i];
            match s.index[w] {
                None => {
                    visit(s, w);
                    s.low[v] = s.low[v].min(s.low[w]);
                }
                Some(iw) if s.on_stack[w] => s.low[v] = s.low[v].min(iw),
                Some(_) => {}
            }
        }
        if Some(s.low[v]) == s.index[v] {
            let mut component = Vec::new();
            while let Some(w) = s.stack.pop() {
                s.on_stack[w] = false;
                component.push(w);
                if w == v {
                    break;
                }
            }
            s.out.push(component);
        }
    }
    let n = edges.len();
    let mut s = State {
        edges,
        index: vec![None; n],
        low: vec![0; n],
        on_stack: vec![false; n],
        stack: Vec::new(),
        next: 0,
        out: Vec::new(),
    };
    for v in 0..n {
        if s.index[v].is_none() {
            visit(&mut s, v);
        }
    }
    s.out
}

/// The block of `jac` belonging to `l`.
pub(crate) fn block(jac: &DMatrix<f64>, l: &Loop) -> DMatrix<f64> {
    DMatrix::from_fn(l.rows.len(), l.columns.len(), |i, j| {
        jac[(l.rows[i], l.columns[j])]
    })
}

/// The condition number of loop `l`'s block of the scaled Jacobian `jac` after scaling its
/// columns to unit length.
///
/// An SVD is computed only when the Hadamard ratio |det| / Π‖column‖ does not already prove
/// the condition below `limit`: with unit columns σ_max ≤ √k and
/// σ_min ≥ |det| / σ_max^(k−1), so the condition is at most k^(k/2) / |det|; that bound is
/// returned when it is below `limit`.
pub(crate) fn condition(jac: &DMatrix<f64>, l: &Loop, limit: f64) -> f64 {
    let mut b = block(jac, l);
    for mut c in b.column_iter_mut() {
        let norm = c.norm();
        if norm > 0.0 {
            c /= norm;
        }
    }
    let k = l.rows.len() as f64;
    let bound = k.powf(0.5 * k) / b.clone().determinant().abs();
    if bound <= limit {
        return bound;
    }
    let Some(svd) = b.try_svd(false, false, f64::EPSILON, SVD_ITERATIONS) else {
        return f64::INFINITY;
    };
    let s = svd.singular_values;
    let condition = s.max() / s.min();
    if condition.is_nan() {
        f64::INFINITY
    } else {
        condition
    }
}
