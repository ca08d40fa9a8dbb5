//! LU factorisation of Φ_q by loops: one small dense LU per diagonal block of the block
//! triangular form (see [`super::branch`]), and block forward substitution.
//!
//! For the Whitworth this is three 3×3 factorisations instead of one 9×9. Everything the
//! factorisation and the solves index (block entries, coupling entries) is resolved to
//! positions in the Jacobian's storage once, when the buffers are made; after that nothing
//! is allocated. Each block's determinant is the loop's branch certificate and its size the
//! singularity screen.

use super::branch::Loop;
use nalgebra::DMatrix;

/// One loop's block: where its data lives in the flat buffers of [`BlockLu`].
#[derive(Debug, Clone, PartialEq)]
struct Block {
    /// Size k of the block.
    size: usize,
    /// Start of its k rows / k columns in `BlockLu::rows` / `BlockLu::columns`, and of its
    /// pivots.
    start: usize,
    /// Start of its k×k entries (row-major) in `BlockLu::lu` and `BlockLu::entries`.
    lu_start: usize,
    /// Its coupling entries: `BlockLu::coupling[coupling.0..coupling.1]`.
    coupling: (usize, usize),
}

/// The factorisation of a whole Φ_q, loop by loop.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct BlockLu {
    blocks: Vec<Block>,
    /// Every loop's rows, then its columns, concatenated in loop order.
    rows: Vec<usize>,
    columns: Vec<usize>,
    /// Position in the (column-major) Jacobian of every block entry, row-major per block.
    entries: Vec<usize>,
    /// (index of the row in its loop, position in the Jacobian, column) of every entry
    /// coupling a loop to the loops before it (structurally non-zero).
    coupling: Vec<(usize, usize, usize)>,
    /// The LU factors (unit lower triangle below the diagonal), row-major per block.
    lu: Vec<f64>,
    pivots: Vec<usize>,
    /// Per block, the sign of its row permutation (±1).
    parity: Vec<f64>,
    valid: bool,
}

impl BlockLu {
    /// Buffers for the loops `loops` of an n×n Φ_q; `row_columns[r]` lists the columns row
    /// `r` depends on.
    pub fn new(loops: &[Loop], row_columns: &[Vec<usize>]) -> Self {
        let n = row_columns.len();
        let mut lu = BlockLu {
            blocks: Vec::with_capacity(loops.len()),
            rows: Vec::with_capacity(n),
            columns: Vec::with_capacity(n),
            entries: Vec::new(),
            coupling: Vec::new(),
            lu: Vec::new(),
            pivots: vec![0; n],
            parity: vec![1.0; loops.len()],
            valid: false,
        };
        for l in loops {
            let size = l.rows.len();
            let coupling_start = lu.coupling.len();
            for (i, &r) in l.rows.iter().enumerate() {
                for &c in &row_columns[r] {
                    if lu.columns.contains(&c) {
                        lu.coupling.push((i, c * n + r, c));
                    }
                }
            }
            lu.blocks.push(Block {
                size,
                start: lu.rows.len(),
                lu_start: lu.entries.len(),
                coupling: (coupling_start, lu.coupling.len()),
            });
            for &r in &l.rows {
                lu.entries.extend(l.columns.iter().map(|&c| c * n + r));
            }
            lu.rows.extend_from_slice(&l.rows);
            lu.columns.extend_from_slice(&l.columns);
        }
        lu.lu = vec![0.0; lu.entries.len()];
        lu
    }

    /// Factorises the diagonal blocks of `jac`. Returns false if a pivot is exactly zero
    /// (the factorisation is then unusable).
    pub fn factor(&mut self, jac: &DMatrix<f64>) -> bool {
        let jac = jac.as_slice();
        for (dst, &at) in self.lu.iter_mut().zip(&self.entries) {
            *dst = jac[at];
        }
        self.valid = true;
        for (b, parity) in self.blocks.iter().zip(&mut self.parity) {
            let a = &mut self.lu[b.lu_start..b.lu_start + b.size * b.size];
            let pivots = &mut self.pivots[b.start..b.start + b.size];
            if !factor_block(a, b.size, pivots, parity) {
                self.valid = false;
                break;
            }
        }
        self.valid
    }

    /// Determinant of loop `i`'s block (valid after [`BlockLu::factor`]).
    pub fn determinant(&self, i: usize) -> f64 {
        let b = &self.blocks[i];
        let a = &self.lu[b.lu_start..b.lu_start + b.size * b.size];
        (0..b.size).map(|d| a[d * b.size + d]).product::<f64>() * self.parity[i]
    }

    /// Solves Φ_q x = b by block forward substitution (`jac` is the matrix factorised).
    pub fn solve(&self, jac: &DMatrix<f64>, b: &[f64], x: &mut [f64]) -> bool {
        if !self.valid {
            return false;
        }
        let jac = jac.as_slice();
        for block in &self.blocks {
            match block.size {
                1 => self.solve_block::<1>(block, jac, b, x),
                2 => self.solve_block::<2>(block, jac, b, x),
                3 => self.solve_block::<3>(block, jac, b, x),
                4 => self.solve_block::<4>(block, jac, b, x),
                _ => self.solve_block_any(block, jac, b, x),
            }
        }
        x.iter().all(|v| v.is_finite())
    }

    /// One K×K block of [`BlockLu::solve`].
    fn solve_block<const K: usize>(&self, block: &Block, jac: &[f64], b: &[f64], x: &mut [f64]) {
        let rows: &[usize; K] = self.rows[block.start..block.start + K]
            .try_into()
            .expect("K rows");
        let mut r: [f64; K] = std::array::from_fn(|i| b[rows[i]]);
        self.subtract_coupling(block, jac, x, &mut r);
        let pivots = &self.pivots[block.start..block.start + K];
        substitute::<K>(
            &self.lu[block.lu_start..block.lu_start + K * K],
            pivots,
            &mut r,
        );
        for (&c, v) in self.columns[block.start..block.start + K].iter().zip(r) {
            x[c] = v;
        }
    }

    /// One block of any size of [`BlockLu::solve`].
    fn solve_block_any(&self, block: &Block, jac: &[f64], b: &[f64], x: &mut [f64]) {
        let k = block.size;
        let mut r: Vec<f64> = self.rows[block.start..block.start + k]
            .iter()
            .map(|&row| b[row])
            .collect();
        self.subtract_coupling(block, jac, x, &mut r);
        let pivots = &self.pivots[block.start..block.start + k];
        let a = &self.lu[block.lu_start..block.lu_start + k * k];
        substitute_any(a, k, pivots, &mut r);
        for (&c, v) in self.columns[block.start..block.start + k].iter().zip(r) {
            x[c] = v;
        }
    }

    /// `r −= (coupling of the block to the loops before it) · x`.
    fn subtract_coupling(&self, block: &Block, jac: &[f64], x: &[f64], r: &mut [f64]) {
        for &(i, at, c) in &self.coupling[block.coupling.0..block.coupling.1] {
            r[i] -= jac[at] * x[c];
        }
    }
}

/// Doolittle LU with partial pivoting of the k×k row-major `a`, in place; false if a pivot
/// is zero or not finite. Blocks up to 4×4 (nearly all loops) take a copy of the algorithm
/// specialised to their size, whose loops the compiler unrolls.
fn factor_block(a: &mut [f64], k: usize, pivots: &mut [usize], parity: &mut f64) -> bool {
    match k {
        1 => factor_fixed::<1>(a, pivots, parity),
        2 => factor_fixed::<2>(a, pivots, parity),
        3 => factor_fixed::<3>(a, pivots, parity),
        4 => factor_fixed::<4>(a, pivots, parity),
        _ => factor_any(a, k, pivots, parity),
    }
}

/// [`factor_any`] for K×K.
fn factor_fixed<const K: usize>(a: &mut [f64], pivots: &mut [usize], parity: &mut f64) -> bool {
    let a: &mut [[f64; K]; K] = a.as_chunks_mut::<K>().0.try_into().expect("a K×K block");
    let pivots: &mut [usize; K] = pivots.try_into().expect("K pivots");
    *parity = 1.0;
    for d in 0..K {
        let mut p = d;
        for i in d + 1..K {
            if a[i][d].abs() > a[p][d].abs() {
                p = i;
            }
        }
        pivots[d] = p;
        if p != d {
            a.swap(d, p);
            *parity = -*parity;
        }
        let pivot = a[d][d];
        if pivot == 0.0 || !pivot.is_finite() {
            return false;
        }
        for i in d + 1..K {
            let m = a[i][d] / pivot;
            a[i][d] = m;
            // Indices, not iterators: with K constant this unrolls into straight-line code
            // (the iterator form measured twice the instructions).
            #[allow(clippy::needless_range_loop)]
            for j in d + 1..K {
                a[i][j] -= m * a[d][j];
            }
        }
    }
    true
}

/// Solves with the factors of [`factor_fixed`]: `r ← U⁻¹ L⁻¹ P r`.
fn substitute<const K: usize>(a: &[f64], pivots: &[usize], r: &mut [f64]) {
    let a: &[[f64; K]; K] = a.as_chunks::<K>().0.try_into().expect("a K×K block");
    let r: &mut [f64; K] = r.try_into().expect("K values");
    for (i, &p) in pivots.iter().enumerate().take(K) {
        r.swap(i, p);
    }
    for i in 1..K {
        for j in 0..i {
            r[i] -= a[i][j] * r[j];
        }
    }
    for i in (0..K).rev() {
        for j in i + 1..K {
            r[i] -= a[i][j] * r[j];
        }
        r[i] /= a[i][i];
    }
}

/// Solves with the factors of [`factor_any`] (k×k).
fn substitute_any(a: &[f64], k: usize, pivots: &[usize], r: &mut [f64]) {
    for (i, &p) in pivots.iter().enumerate() {
        r.swap(i, p);
    }
    for i in 1..k {
        let row = &a[i * k..i * k + i];
        let s: f64 = row.iter().zip(&r[..i]).map(|(l, v)| l * v).sum();
        r[i] -= s;
    }
    for i in (0..k).rev() {
        let row = &a[i * k + i + 1..(i + 1) * k];
        let s: f64 = row.iter().zip(&r[i + 1..]).map(|(u, v)| u * v).sum();
        r[i] = (r[i] - s) / a[i * k + i];
    }
}

/// Doolittle LU with partial pivoting of the k×k row-major `a`, in place.
fn factor_any(a: &mut [f64], k: usize, pivots: &mut [usize], parity: &mut f64) -> bool {
    *parity = 1.0;
    for d in 0..k {
        let mut p = d;
        for i in d + 1..k {
            if a[i * k + d].abs() > a[p * k + d].abs() {
                p = i;
            }
        }
        pivots[d] = p;
        if p != d {
            for j in 0..k {
                a.swap(d * k + j, p * k + j);
            }
            *parity = -*parity;
        }
        let pivot = a[d * k + d];
        if pivot == 0.0 || !pivot.is_finite() {
            return false;
        }
        for i in d + 1..k {
            let m = a[i * k + d] / pivot;
            a[i * k + d] = m;
            for j in d + 1..k {
                a[i * k + j] -= m * a[d * k + j];
            }
        }
    }
    true
}
