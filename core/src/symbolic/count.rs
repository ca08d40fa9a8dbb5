//! Operation counts of emitted code, with and without common-subexpression elimination.

use std::collections::{BTreeMap, HashMap};
use std::fmt;

use super::graph::{Graph, Id, Node};
use super::ops::{Binary, Unary};

/// How many operations of each kind a piece of code performs.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct OperationCount {
    /// Additions and subtractions.
    pub add: u64,
    /// Multiplications (`x * x` for `x²` included).
    pub mul: u64,
    /// Divisions.
    pub div: u64,
    /// Negations.
    pub neg: u64,
    /// Branch selections of piecewise functions.
    pub select: u64,
    /// Calls of each transcendental or power function, by name (`sin_cos` for a shared pair).
    pub calls: BTreeMap<String, u64>,
}

impl OperationCount {
    /// Total number of calls.
    pub fn total_calls(&self) -> u64 {
        self.calls.values().sum()
    }

    fn record(&mut self, node: &Node, times: u64) {
        let mut call = |name: &str| *self.calls.entry(name.to_owned()).or_default() += times;
        match *node {
            Node::Num(_) | Node::Sym(_) => {}
            Node::Unary(Unary::Neg, _) => self.neg += times,
            Node::Unary(op, _) => call(op.name()),
            Node::Binary(Binary::Add | Binary::Sub, ..) => self.add += times,
            Node::Binary(Binary::Mul, ..) => self.mul += times,
            Node::Binary(Binary::Div, ..) => self.div += times,
            Node::Binary(op, ..) => call(op.name()),
            // emitted as `x * x` or `u.powi(2)`: one multiplication either way
            Node::Powi(_, 2) => self.mul += times,
            Node::Powi(..) => call("powi"),
            Node::Select(..) => self.select += times,
        }
    }

    fn add_scaled(&mut self, other: &OperationCount, times: u64) {
        self.add = self.add.saturating_add(other.add.saturating_mul(times));
        self.mul = self.mul.saturating_add(other.mul.saturating_mul(times));
        self.div = self.div.saturating_add(other.div.saturating_mul(times));
        self.neg = self.neg.saturating_add(other.neg.saturating_mul(times));
        self.select = self
            .select
            .saturating_add(other.select.saturating_mul(times));
        for (name, n) in &other.calls {
            let entry = self.calls.entry(name.clone()).or_default();
            *entry = entry.saturating_add(n.saturating_mul(times));
        }
    }
}

impl fmt::Display for OperationCount {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} add, {} mul, {} div", self.add, self.mul, self.div)?;
        if self.neg > 0 {
            write!(f, ", {} neg", self.neg)?;
        }
        if self.select > 0 {
            write!(f, ", {} select", self.select)?;
        }
        for (name, n) in &self.calls {
            write!(f, ", {n} {name}")?;
        }
        Ok(())
    }
}

impl Graph {
    /// The operations of the code `Graph::emit_body` (feature `emit`) writes for `outputs`:
    /// each needed node once, `sin` and `cos` of one argument as one `sin_cos` call.
    pub fn operation_count(&self, outputs: &[Id]) -> OperationCount {
        let (reachable, _) = use_counts(self, outputs);
        let pairs = sin_cos_pairs(self, &reachable);
        let mut count = OperationCount::default();
        for (index, node) in self.nodes().iter().enumerate() {
            if !reachable[index] {
                continue;
            }
            match node {
                Node::Unary(Unary::Sin, u) if pairs.contains_key(u) => {
                    *count.calls.entry("sin_cos".to_owned()).or_default() += 1;
                }
                Node::Unary(Unary::Cos, u) if pairs.contains_key(u) => {}
                _ => count.record(node, 1),
            }
        }
        count
    }

    /// The operations of evaluating each output as a tree, without sharing anything (no
    /// common-subexpression elimination, no `sin_cos`): the cost of naive generated code.
    pub fn naive_operation_count(&self, outputs: &[Id]) -> OperationCount {
        let last = outputs
            .iter()
            .map(|id| id.index())
            .max()
            .map_or(0, |m| m + 1);
        let mut tree: Vec<OperationCount> = Vec::with_capacity(last);
        for node in &self.nodes()[..last] {
            let mut count = OperationCount::default();
            count.record(node, 1);
            for child in node.children() {
                let child_count = tree[child.index()].clone();
                count.add_scaled(&child_count, 1);
            }
            tree.push(count);
        }
        let mut total = OperationCount::default();
        for output in outputs {
            total.add_scaled(&tree[output.index()], 1);
        }
        total
    }
}

/// How often each reachable node is used by other reachable nodes and by the outputs.
pub(crate) fn use_counts(graph: &Graph, outputs: &[Id]) -> (Vec<bool>, Vec<usize>) {
    let reachable = graph.reachable(outputs);
    let mut uses = vec![0usize; reachable.len()];
    for (index, node) in graph.nodes().iter().enumerate() {
        if reachable[index] {
            for child in node.children() {
                uses[child.index()] += 1;
            }
        }
    }
    for output in outputs {
        uses[output.index()] += 1;
    }
    (reachable, uses)
}

/// For each argument whose `sin` and `cos` are both needed: the ids of the two nodes.
pub(crate) fn sin_cos_pairs(graph: &Graph, reachable: &[bool]) -> HashMap<Id, (Id, Id)> {
    let mut pairs = HashMap::new();
    for (index, node) in graph.nodes().iter().enumerate() {
        if let (true, Node::Unary(Unary::Sin, u)) = (reachable[index], node)
            && let Some(cos) = graph.lookup(&Node::Unary(Unary::Cos, *u))
            && reachable[cos.index()]
        {
            pairs.insert(*u, (Id::at(index), cos));
        }
    }
    pairs
}
