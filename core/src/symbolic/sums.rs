//! Sums as linear combinations: `a + b` and `a - b` are built from a constant plus
//! coefficient × term pairs, so that like terms cancel or merge (`x + (1 - x) = 1`,
//! `2x - x = x`, `x - x = 0`) and a factor shared by every term is taken out
//! (`a·b + a·c = a·(b + c)`).
//!
//! Sums are flattened through nested sums, negations and constant factors only when that
//! makes terms cancel or merge; otherwise the sum keeps its two operands, so simplification
//! never makes code longer. Coefficients are combined only where the `f64` arithmetic is
//! exact (see [`super::simplify`]).

use std::collections::{HashMap, VecDeque};

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

/// How many sum nodes one simplification looks through, and how many factors of a product
/// it looks at: the nearest ones first (breadth first from the top), so that a long sum
/// built term by term costs a bounded amount of work per term (near-linear in the size of
/// the expression) while like terms that are close together still cancel.
const LOOK_THROUGH: usize = 64;

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
        let mut terms: Vec<(f64, Id)> = Vec::with_capacity(self.terms.len());
        // the position in `terms` of the last entry of each term (where a new one merges):
        // found by a scan for a few terms (most sums), by a hash map for many
        let mut position: HashMap<Id, usize> = HashMap::new();
        let hashed = self.terms.len() > 16;
        for (c, id) in self.terms {
            let at = if hashed {
                position.get(&id).copied()
            } else {
                terms.iter().rposition(|(_, t)| *t == id)
            };
            let merged = at.and_then(|i| {
                let k = &mut terms[i].0;
                exact_add(*k, c).map(|s| *k = s)
            });
            if merged.is_none() {
                if hashed {
                    position.insert(id, terms.len());
                }
                terms.push((c, id));
            }
        }
        terms.retain(|(c, _)| *c != 0.0);
        Linear { constants, terms }
    }
}

impl Graph {
    /// `id` as coefficient × term, looking through negation and constant factors.
    fn split_coefficient(&self, id: Id) -> (f64, Id) {
        let (mut coefficient, mut term) = (1.0, id);
        loop {
            match *self.node(term) {
                Node::Unary(Unary::Neg, x) => {
                    coefficient = -coefficient;
                    term = x;
                }
                Node::Binary(Binary::Mul, a, x) => {
                    match self.as_number(a).and_then(|k| exact_mul(coefficient, k)) {
                        Some(product) => {
                            coefficient = product;
                            term = x;
                        }
                        None => return (coefficient, term),
                    }
                }
                _ => return (coefficient, term),
            }
        }
    }

    /// Adds `coefficient × id` to `out`, flattening nested sums: breadth first, through at
    /// most [`LOOK_THROUGH`] sums (a sum further down stays one term).
    fn flatten(&self, id: Id, coefficient: f64, out: &mut Linear) {
        let mut queue = VecDeque::from([(coefficient, id)]);
        let mut opened = 0;
        while let Some((coefficient, id)) = queue.pop_front() {
            match *self.node(id) {
                Node::Num(n) => match exact_mul(coefficient, n.value()) {
                    Some(c) => out.constants.push(c),
                    None => out.terms.push((coefficient, id)),
                },
                Node::Binary(op @ (Binary::Add | Binary::Sub), a, b) if opened < LOOK_THROUGH => {
                    opened += 1;
                    let sign = if op == Binary::Add { 1.0 } else { -1.0 };
                    queue.push_back((coefficient, a));
                    queue.push_back((sign * coefficient, b));
                }
                _ => {
                    let (c, term) = self.split_coefficient(id);
                    match exact_mul(coefficient, c) {
                        Some(k) if term != id => queue.push_back((k, term)),
                        _ => out.terms.push((coefficient, id)),
                    }
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
    /// and factor (`a·(b·c)` → `[a·(b·c), a, b·c, b, c]`), breadth first, at most
    /// [`LOOK_THROUGH`] of them.
    pub(super) fn product_nodes(&self, id: Id) -> Vec<Id> {
        let mut out = vec![id];
        let mut next = 0;
        while next < out.len() && out.len() < LOOK_THROUGH {
            match *self.node(out[next]) {
                Node::Binary(Binary::Mul, a, b) => out.extend([a, b]),
                // the base of a power is a factor (but not its own factors: `without` takes
                // one power of the base, it does not split it)
                Node::Powi(base, n) if n >= 2 => out.push(base),
                _ => {}
            }
            next += 1;
        }
        out
    }

    /// The product `id` with one occurrence of the sub-product `factor` replaced by 1
    /// (`xⁿ` counts as a product of n factors x); `None` if `factor` is not among the first
    /// [`LOOK_THROUGH`] nodes of the product tree.
    pub(super) fn without(&mut self, id: Id, factor: Id) -> Option<Id> {
        if id == factor {
            return Some(self.number(1.0));
        }
        if let Node::Powi(base, n) = *self.node(id) {
            return (base == factor && n >= 1).then(|| self.powi(base, n - 1));
        }
        // the path from `id` down to the factor, through products (breadth first)
        let mut parent: Vec<(Id, usize)> = vec![(id, usize::MAX)];
        let mut next = 0;
        let found = loop {
            if next >= parent.len() || parent.len() >= LOOK_THROUGH {
                return None;
            }
            let (node, _) = parent[next];
            if let Node::Binary(Binary::Mul, a, b) = *self.node(node) {
                for child in [a, b] {
                    parent.push((child, next));
                }
                if let Some(at) = parent[parent.len() - 2..].iter().position(|(c, _)| {
                    *c == factor
                        || matches!(*self.node(*c), Node::Powi(base, n) if base == factor && n >= 1)
                }) {
                    break parent.len() - 2 + at;
                }
            }
            next += 1;
        };
        // rebuild the products along the path, bottom up
        let (leaf, mut up) = parent[found];
        let mut rest = if leaf == factor {
            self.number(1.0)
        } else {
            let Node::Powi(base, n) = *self.node(leaf) else {
                unreachable!("matched above")
            };
            self.powi(base, n - 1)
        };
        let mut child = leaf;
        while up != usize::MAX {
            let (node, grand) = parent[up];
            let Node::Binary(Binary::Mul, a, b) = *self.node(node) else {
                unreachable!("only products are opened")
            };
            rest = if a == child {
                self.mul(rest, b)
            } else {
                self.mul(a, rest)
            };
            child = node;
            up = grand;
        }
        Some(rest)
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
            .map(|(_, t)| self.product_nodes(*t))
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
        let cofactors: Option<Vec<Id>> = linear
            .terms
            .iter()
            .map(|(_, t)| self.without(*t, common))
            .collect();
        let mut inner: Option<Id> = None;
        for ((coefficient, _), cofactor) in linear.terms.iter().zip(cofactors?) {
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
