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
    /// Per loop: (index of the row in the loop, row, column) of every entry coupling it to
    /// the loops before it (structurally non-zero).
    coupling: Vec<Vec<(usize, usize, usize)>>,
    valid: bool,
}

impl BlockLu {
    /// Buffers for the loops `loops`; `row_columns[r]` lists the columns row `r` depends on.
    pub fn new(loops: &[Loop], row_columns: &[Vec<usize>]) -> Self {
        let mut solved: Vec<usize> = Vec::new();
        let mut coupling = Vec::with_capacity(loops.len());
        for l in loops {
            let mut entries = Vec::new();
            for (i, &r) in l.rows.iter().enumerate() {
                for &c in &row_columns[r] {
                    if solved.contains(&c) {
                        entries.push((i, r, c));
                    }
                }
            }
            coupling.push(entries);
            solved.extend_from_slice(&l.columns);
        }
        let factors = loops
            .iter()
            .map(|l| {
                let k = l.rows.len();
                Factor {
                    lu: vec![0.0; k * k],
                    pivots: vec![0; k],
                    parity: 1.0,
                }
            })
            .collect();
        BlockLu {
            factors,
            coupling,
            valid: false,
        }
    }

    /// Factorises the diagonal blocks of `jac`. Returns false if a pivot is exactly zero
    /// (the factorisation is then unusable).
    pub fn factor(&mut self, jac: &DMatrix<f64>, loops: &[Loop]) -> bool {
        self.valid = loops
            .iter()
            .zip(&mut self.factors)
            .all(|(l, f)| factor_block(jac, l, f));
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
        let n = jac.nrows();
        let entries = jac.as_slice();
        let mut rhs = [0.0; 16];
        let mut buf = Vec::new();
        for ((l, f), coupling) in loops.iter().zip(&self.factors).zip(&self.coupling) {
            let k = l.rows.len();
            let r: &mut [f64] = if k <= 16 {
                &mut rhs[..k]
            } else {
                buf.resize(k, 0.0);
                &mut buf[..]
            };
            for (i, &row) in l.rows.iter().enumerate() {
                r[i] = b[row];
            }
            // Minus the coupling to the loops solved before (column-major storage).
            for &(i, row, c) in coupling {
                r[i] -= entries[c * n + row] * x[c];
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
    let (n, entries) = (jac.nrows(), jac.as_slice());
    for (i, &r) in l.rows.iter().enumerate() {
        for (j, &c) in l.columns.iter().enumerate() {
            f.lu[i * k + j] = entries[c * n + r];
        }
    }
    f.parity = 1.0;
    for d in 0..k {
        let mut p = d;
        for i in d + 1..k {
            if f.lu[i * k + d].abs() > f.lu[p * k + d].abs() {
                p = i;
            }
        }
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
