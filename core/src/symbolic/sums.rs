//! Sums as linear combinations: `a + b` and `a - b` are built from a constant plus
//! coefficient × term pairs, so that like terms cancel or merge (`x + (1 - x) = 1`,
//! `2x - x = x`, `x - x = 0`) and a factor shared by every term is taken out
//! (`a·b + a·c = a·(b + c)`).
//!
//! Sums are flattened through nested sums, negations and constant factors only when that
//! makes terms cancel or merge; otherwise the sum keeps its two operands, so simplification
//! never makes code longer. Coefficients are combined only where the `f64` arithmetic is
//! exact (see [`super::simplify`]).

use super::graph::{Graph, Id, Node};
use super::ops::{Binary, Unary};

fn exact_add(x: f64, y: f64) -> Option<f64> {
    let s = x + y;
    let bb = s - x;
    (s.is_finite() && (x - (s - bb)) + (y - bb) == 0.0).then_some(s)
}

fn exact_mul(x: f64, y: f64) -> Option<f64> {
    let p = x * y;
    (p.is_finite() && x.mul_add(y, -p) == 0.0).then_some(p)
}

/// A constant part plus coefficient × term pairs.
#[derive(Default)]
struct Linear {
    constants: Vec<f64>,
    terms: Vec<(f64, Id)>,
}

impl Linear {
    fn size(&self) -> usize {
        self.constants.len() + self.terms.len()
    }

    /// Merges equal terms and the constants where the coefficient arithmetic is exact;
    /// drops zero coefficients.
    fn collect(self) -> Linear {
        let mut constants: Vec<f64> = Vec::new();
        for c in self.constants {
            match constants
                .iter_mut()
                .find_map(|k| exact_add(*k, c).map(|s| (k, s)))
            {
                Some((k, s)) => *k = s,
                None => constants.push(c),
            }
        }
        constants.retain(|c| *c != 0.0);
        let mut terms: Vec<(f64, Id)> = Vec::new();
        for (c, id) in self.terms {
            let merged = terms.iter_mut().find_map(|(k, t)| {
                if *t == id {
                    exact_add(*k, c).map(|s| (k, s))
                } else {
                    None
                }
            });
            match merged {
                Some((k, s)) => *k = s,
                None => terms.push((c, id)),
            }
        }
        terms.retain(|(c, _)| *c != 0.0);
        Linear { constants, terms }
    }
}

impl Graph {
    /// `id` as coefficient × term, looking through negation and constant factors.
    fn split_coefficient(&self, id: Id) -> (f64, Id) {
        match *self.node(id) {
            Node::Unary(Unary::Neg, x) => {
                let (c, t) = self.split_coefficient(x);
                (-c, t)
            }
            Node::Binary(Binary::Mul, a, x) => match self.as_number(a) {
                Some(k) => {
                    let (c, t) = self.split_coefficient(x);
                    exact_mul(k, c).map_or((1.0, id), |p| (p, t))
                }
                None => (1.0, id),
            },
            _ => (1.0, id),
        }
    }

    /// Adds `coefficient × id` to `out`, flattening nested sums.
    fn flatten(&self, id: Id, coefficient: f64, out: &mut Linear) {
        match *self.node(id) {
            Node::Num(n) => match exact_mul(coefficient, n.value()) {
                Some(c) => out.constants.push(c),
                None => out.terms.push((coefficient, id)),
            },
            Node::Binary(op @ (Binary::Add | Binary::Sub), a, b) => {
                self.flatten(a, coefficient, out);
                self.flatten(
                    b,
                    if op == Binary::Add {
                        coefficient
                    } else {
                        -coefficient
                    },
                    out,
                );
            }
            _ => {
                let (c, term) = self.split_coefficient(id);
                match exact_mul(coefficient, c) {
                    Some(k) if term != id => self.flatten(term, k, out),
                    _ => out.terms.push((coefficient, id)),
                }
            }
        }
    }

    /// The linear combination of `a + sign × b`, shallow: two terms with their coefficients.
    fn shallow(&self, a: Id, sign: f64, b: Id) -> Linear {
        let mut linear = Linear::default();
        for (s, id) in [(1.0, a), (sign, b)] {
            let (c, term) = self.split_coefficient(id);
            match (self.as_number(term), exact_mul(s, c)) {
                (Some(v), Some(k)) if exact_mul(k, v).is_some() => {
                    linear.constants.push(k * v);
                }
                (None, Some(k)) => linear.terms.push((k, term)),
                _ => linear.terms.push((s, id)),
            }
        }
        linear
    }

    /// `a + sign × b` (`sign` is ±1), simplified as a linear combination.
    pub(super) fn sum(&mut self, a: Id, sign: f64, b: Id) -> Id {
        let mut deep = Linear::default();
        self.flatten(a, 1.0, &mut deep);
        self.flatten(b, sign, &mut deep);
        let before = deep.size();
        let deep = deep.collect();
        let linear = if deep.size() < before {
            deep
        } else {
            self.shallow(a, sign, b).collect()
        };
        self.build(linear)
    }

    /// The nodes of the product tree of `id`: itself and, through products, every sub-product
    /// and factor (`a·(b·c)` → `[a·(b·c), a, b·c, b, c]`).
    fn product_nodes(&self, id: Id, out: &mut Vec<Id>) {
        out.push(id);
        match *self.node(id) {
            Node::Binary(Binary::Mul, a, b) => {
                self.product_nodes(a, out);
                self.product_nodes(b, out);
            }
            // the base of a power is a factor (but not its own factors: `without` takes one
            // power of the base, it does not split it)
            Node::Powi(base, n) if n >= 2 => out.push(base),
            _ => {}
        }
    }

    /// The product `id` with one occurrence of the sub-product `factor` replaced by 1
    /// (`xⁿ` counts as a product of n factors x).
    pub(super) fn without(&mut self, id: Id, factor: Id) -> Option<Id> {
        if id == factor {
            return Some(self.number(1.0));
        }
        if let Node::Powi(base, n) = *self.node(id) {
            return (base == factor && n >= 1).then(|| self.powi(base, n - 1));
        }
        let Node::Binary(Binary::Mul, a, b) = *self.node(id) else {
            return None;
        };
        if let Some(rest) = self.without(a, factor) {
            return Some(self.mul(rest, b));
        }
        let rest = self.without(b, factor)?;
        Some(self.mul(a, rest))
    }

    /// Takes the largest sub-product shared by every term out: `a·b + a·c = a·(b + c)`,
    /// `u + 2·(v·u) = u·(1 + 2v)`.
    fn factor_out(&mut self, linear: &Linear) -> Option<Id> {
        if !linear.constants.is_empty() || linear.terms.len() < 2 {
            return None;
        }
        let node_lists: Vec<Vec<Id>> = linear
            .terms
            .iter()
            .map(|(_, t)| {
                let mut list = Vec::new();
                self.product_nodes(*t, &mut list);
                list
            })
            .collect();
        // the largest common sub-product: parents are stored after their children, so the
        // highest id is the largest
        let common = node_lists[0]
            .iter()
            .filter(|f| {
                self.as_number(**f).is_none() && node_lists[1..].iter().all(|l| l.contains(f))
            })
            .max()
            .copied()?;
        let mut inner: Option<Id> = None;
        for (coefficient, t) in &linear.terms {
            let cofactor = self
                .without(*t, common)
                .expect("the common factor is in every term");
            let c = self.number(*coefficient);
            let term = self.mul(c, cofactor);
            inner = Some(match inner {
                None => term,
                Some(acc) => self.add(acc, term),
            });
        }
        let inner = inner.expect("two or more terms");
        Some(self.mul(common, inner))
    }

    /// The node of a collected linear combination: positive constants first, then the terms
    /// in id order (a canonical order, so equal sums are one node), negative constants last.
    fn build(&mut self, linear: Linear) -> Id {
        if let Some(factored) = self.factor_out(&linear) {
            return factored;
        }
        let Linear {
            constants,
            mut terms,
        } = linear;
        terms.sort_by_key(|(_, id)| *id);
        let (positive, negative): (Vec<f64>, Vec<f64>) = constants.iter().partition(|c| **c > 0.0);
        let mut parts: Vec<(bool, Id)> = Vec::new();
        for c in positive {
            parts.push((true, self.number(c)));
        }
        for (c, term) in terms {
            let magnitude = self.number(c.abs());
            let value = self.mul(magnitude, term);
            parts.push((c > 0.0, value));
        }
        for c in negative {
            parts.push((false, self.number(-c)));
        }
        // start with a positive part if there is one, so that `-a + b` is written `b - a`;
        // else with a negative constant, a literal (`-1 - a`, not `-a - 1`)
        let start = parts.iter().position(|(p, _)| *p).or_else(|| {
            parts
                .iter()
                .position(|(_, id)| self.as_number(*id).is_some())
        });
        if let Some(first) = start {
            let part = parts.remove(first);
            parts.insert(0, part);
        }
        let mut result: Option<Id> = None;
        for (positive, value) in parts {
            result = Some(match (result, positive) {
                (None, true) => value,
                (None, false) => match self.as_number(value) {
                    Some(c) => self.number(-c),
                    None => self.intern(Node::Unary(Unary::Neg, value)),
                },
                (Some(acc), true) => self.intern(Node::Binary(Binary::Add, acc, value)),
                (Some(acc), false) => self.intern(Node::Binary(Binary::Sub, acc, value)),
            });
        }
        result.unwrap_or_else(|| self.number(0.0))
    }
}
