//! LU factorisation of Φ_q by loops: one small dense LU per diagonal block of the block
//! triangular form (see [`super::branch`]), and block forward substitution.
//!
//! For the Whitworth this is three 3×3 factorisations instead of one 9×9, with no
//! allocation after the first use; each block's determinant is the loop's branch
//! certificate and its size the singularity screen.

use super::branch::Loop;
use nalgebra::DMatrix;

/// LU with partial pivoting of one loop's block, stored row-major in `lu`.
#[derive(Debug, Clone, PartialEq)]
struct Factor {
    lu: Vec<f64>,
    pivots: Vec<usize>,
    /// Sign of the row permutation (±1).
    parity: f64,
}

/// The factorisation of a whole Φ_q, loop by loop.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct BlockLu {
    factors: Vec<Factor>,
    valid: bool,
}

impl BlockLu {
    /// Buffers for the loops `loops`.
    pub fn new(loops: &[Loop]) -> Self {
        let factors = loops
            .iter()
            .map(|l| {
                let k = l.rows.len();
                Factor { lu: vec![0.0; k * k], pivots: vec![0; k], parity: 1.0 }
            })
            .collect();
        BlockLu { factors, valid: false }
    }

    /// Factorises the diagonal blocks of `jac`. Returns false if a pivot is exactly zero
    /// (the factorisation is then unusable).
    pub fn factor(&mut self, jac: &DMatrix<f64>, loops: &[Loop]) -> bool {
        self.valid = loops.iter().zip(&mut self.factors).all(|(l, f)| factor_block(jac, l, f));
        self.valid
    }

    /// Determinant of loop `i`'s block (valid after [`BlockLu::factor`]).
    pub fn determinant(&self, i: usize) -> f64 {
        let f = &self.factors[i];
        let k = f.pivots.len();
        (0..k).map(|d| f.lu[d * k + d]).product::<f64>() * f.parity
    }

    /// Solves Φ_q x = b by block forward substitution (`jac` is the matrix factorised).
    pub fn solve(&self, jac: &DMatrix<f64>, loops: &[Loop], b: &[f64], x: &mut [f64]) -> bool {
        if !self.valid {
            return false;
        }
        x.iter_mut().for_each(|v| *v = 0.0);
        let mut rhs = [0.0; 16];
        let mut buf = Vec::new();
        for (l, f) in loops.iter().zip(&self.factors) {
            let k = l.rows.len();
            let r: &mut [f64] = if k <= 16 {
                &mut rhs[..k]
            } else {
                buf.resize(k, 0.0);
                &mut buf[..]
            };
            // Right-hand side minus the coupling to the loops solved before (later loops'
            // unknowns are still 0, and this block's own columns are skipped).
            for (i, &row) in l.rows.iter().enumerate() {
                let mut s = b[row];
                for c in 0..x.len() {
                    if x[c] != 0.0 {
                        s -= jac[(row, c)] * x[c];
                    }
                }
                r[i] = s;
            }
            for i in 0..k {
                r.swap(i, f.pivots[i]);
            }
            for i in 0..k {
                for j in 0..i {
                    r[i] -= f.lu[i * k + j] * r[j];
                }
            }
            for i in (0..k).rev() {
                for j in i + 1..k {
                    r[i] -= f.lu[i * k + j] * r[j];
                }
                r[i] /= f.lu[i * k + i];
            }
            for (i, &c) in l.columns.iter().enumerate() {
                x[c] = r[i];
            }
        }
        x.iter().all(|v| v.is_finite())
    }
}

/// Doolittle LU with partial pivoting of `jac[l.rows, l.columns]` into `f`.
fn factor_block(jac: &DMatrix<f64>, l: &Loop, f: &mut Factor) -> bool {
    let k = l.rows.len();
    for (i, &r) in l.rows.iter().enumerate() {
        for (j, &c) in l.columns.iter().enumerate() {
            f.lu[i * k + j] = jac[(r, c)];
        }
    }
    f.parity = 1.0;
    for d in 0..k {
        let p = (d..k)
            .max_by(|&a, &b| f.lu[a * k + d].abs().total_cmp(&f.lu[b * k + d].abs()))
            .unwrap_or(d);
        f.pivots[d] = p;
        if p != d {
            for j in 0..k {
                f.lu.swap(d * k + j, p * k + j);
            }
            f.parity = -f.parity;
        }
        let pivot = f.lu[d * k + d];
        if pivot == 0.0 || !pivot.is_finite() {
            return false;
        }
        for i in d + 1..k {
            let m = f.lu[i * k + d] / pivot;
            f.lu[i * k + d] = m;
            for j in d + 1..k {
                f.lu[i * k + j] -= m * f.lu[d * k + j];
            }
        }
    }
    true
}
