//! Loops without a closed form in a traced position solution (a *mixed plan*): each is a
//! [`NewtonBlock`] of the graph, solved by Newton's method where the graph is evaluated.
//!
//! The loop's coordinates `q` enter the graph as symbols (`coordinate_<c>`, `c` the
//! coordinate's index in the solver's `q`), and so do their derivatives with respect to φ
//! (`coordinate_<c>_d<k>`). Tracing the constraint equations (generic over the scalar)
//! with those symbols leaves the loop's residual Φ(q; φ, known coordinates) in the graph;
//! the symbolic engine differentiates it for the Jacobian Φ_q and for the right-hand sides
//! of implicit differentiation: along the solution curve `Φ_q q⁽ᵏ⁾ + R_k = 0`, where `R_k`
//! is the k-th total derivative of Φ without its term in `q⁽ᵏ⁾` (see
//! [`crate::geometry::implicit`]). Every later formula (closed-form loops placed on the
//! Newton loop's links, outputs) reads the symbols, and its φ-derivatives come by the chain
//! rule through the derivative symbols: `D f = ∂f/∂φ + Σ ∂f/∂s · s′` ([`total`]).

use std::collections::HashMap;

use super::DRIVE;
use crate::Error;
use crate::symbolic::{Graph, Id, rules};

/// One loop solved by Newton's method inside the generated code.
#[derive(Debug, Clone, PartialEq)]
pub struct NewtonBlock {
    /// The loop's index in the solver's tracker (`Tracker::joints_of_loop`).
    pub loop_index: usize,
    /// The joints of the loop (as the solver's errors name them).
    pub joints: Vec<String>,
    /// The loop's coordinates: their indices in the solver's `q`.
    pub columns: Vec<usize>,
    /// The coordinates at the sketch (Newton's first start).
    pub sketch: Vec<f64>,
    /// Φ of the loop's rows (m or rad), in the loop's coordinates' symbols.
    pub residual: Vec<Id>,
    /// Φ_q, row by row (`rows × columns`).
    pub jacobian: Vec<Id>,
    /// Each row's factor in the solver's singularity check: the loop's length scale for an
    /// angular row, 1 for a length (see `mobility::scale`).
    pub row_scales: Vec<f64>,
    /// Each column's factor there: the loop's length scale for an angle, 1 for a length.
    pub column_scales: Vec<f64>,
    /// `R_k` for k = 1, 2, … (set by [`super::PositionGraph::jets`]): `Φ_q q⁽ᵏ⁾ = −R_k`.
    pub derivatives: Vec<Vec<Id>>,
}

/// The symbol of coordinate `c`'s derivative of order `k` (0: the coordinate).
pub fn coordinate_symbol(c: usize, k: usize) -> String {
    if k == 0 {
        format!("coordinate_{c}")
    } else {
        format!("coordinate_{c}_d{k}")
    }
}

/// Each derivative symbol of the blocks' coordinates below `order` and the symbol of its
/// derivative.
pub(super) fn successors(blocks: &[NewtonBlock], order: usize) -> HashMap<String, String> {
    let mut next = HashMap::new();
    for c in blocks.iter().flat_map(|b| &b.columns) {
        for k in 0..order {
            next.insert(coordinate_symbol(*c, k), coordinate_symbol(*c, k + 1));
        }
    }
    next
}

/// The total derivative of `f` along the solution curve, `∂f/∂φ + Σ ∂f/∂s · next(s)` over
/// the symbols `s` of `f` that have a successor in `next`, except those `skip` names.
///
/// # Errors
/// [`Error::ExpressionTooLarge`] beyond the symbolic engine's size limit.
pub(super) fn total(
    graph: &mut Graph,
    f: Id,
    next: &HashMap<String, String>,
    skip: &dyn Fn(&str) -> bool,
) -> Result<Id, Error> {
    let symbols: Vec<String> = graph.symbols(&[f]).into_iter().map(str::to_owned).collect();
    let mut sum = graph.number(0.0);
    for s in symbols {
        let successor = match next.get(&s) {
            _ if s == DRIVE => None,
            Some(n) if !skip(&s) => Some(n.clone()),
            _ => continue,
        };
        let partial = graph.try_derivatives(f, &s, 1, rules::MAX_NODES)?[1];
        let term = match successor {
            None => partial,
            Some(n) => {
                let symbol = graph.symbol(&n);
                graph.mul(partial, symbol)
            }
        };
        sum = graph.add(sum, term);
    }
    Ok(sum)
}

impl NewtonBlock {
    /// The Jacobian Φ_q: the partial derivatives of the residual by the coordinates'
    /// symbols.
    pub(super) fn differentiate(&mut self, graph: &mut Graph) -> Result<(), Error> {
        let mut jacobian = Vec::with_capacity(self.residual.len() * self.columns.len());
        for &r in &self.residual {
            for &c in &self.columns {
                jacobian.push(
                    graph.try_derivatives(r, &coordinate_symbol(c, 0), 1, rules::MAX_NODES)?[1],
                );
            }
        }
        self.jacobian = jacobian;
        Ok(())
    }

    /// Sets [`NewtonBlock::derivatives`] to `R_1 … R_order`.
    pub(super) fn lift(
        &mut self,
        graph: &mut Graph,
        next: &HashMap<String, String>,
        order: usize,
    ) -> Result<(), Error> {
        let mut full = self.residual.clone();
        let mut derivatives = Vec::with_capacity(order);
        for k in 1..=order {
            let own: Vec<String> = (self.columns.iter())
                .map(|&c| coordinate_symbol(c, k - 1))
                .collect();
            let skip = |s: &str| own.iter().any(|o| o == s);
            let mut rhs = Vec::with_capacity(full.len());
            for f in &mut full {
                rhs.push(total(graph, *f, next, &skip)?);
                if k < order {
                    *f = total(graph, *f, next, &|_| false)?;
                }
            }
            derivatives.push(rhs);
        }
        self.derivatives = derivatives;
        Ok(())
    }
}
