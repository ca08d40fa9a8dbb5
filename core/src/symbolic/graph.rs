//! The expression IR: a flat, hash-consed arena of nodes.
//!
//! Nodes refer to their children by [`Id`]; a child is always stored before its parents, so
//! walking the arena in order evaluates every node after its arguments (as egg's `RecExpr`).
//! Every node is stored once: adding a node that is already present returns the existing
//! [`Id`], so structurally equal subexpressions are shared and common-subexpression
//! elimination across the value and all its derivatives comes for free.
//!
//! Nodes are added through the simplifying constructors of [`super::simplify`]
//! ([`Graph::add`], [`Graph::sin`], …); [`Graph::intern`] stores a node as it is.

use std::collections::HashMap;
use std::fmt;

use super::ops::{Binary, Comparison, Unary};
use super::range::Range;

/// Index of a node in a [`Graph`] (the default: the first node).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Id(u32);

impl Id {
    /// Position of the node in the arena.
    pub fn index(self) -> usize {
        self.0 as usize
    }

    /// The id of the node at position `index` (ids are dense positions in the arena).
    pub(super) fn at(index: usize) -> Self {
        Id(u32::try_from(index).expect("fewer than 2^32 nodes"))
    }
}

impl fmt::Display for Id {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "#{}", self.0)
    }
}

/// A finite `f64` constant, hashed by its bits (`-0.0` is stored as `0.0`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Number(u64);

impl Number {
    /// The constant `value`, or `None` if it is not finite.
    pub fn new(value: f64) -> Option<Self> {
        value
            .is_finite()
            .then(|| Number(if value == 0.0 { 0.0f64 } else { value }.to_bits()))
    }

    /// The value.
    pub fn value(self) -> f64 {
        f64::from_bits(self.0)
    }
}

/// One node of the expression IR.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    /// A literal constant.
    Num(Number),
    /// A variable, parameter or named constant (`phi`, `lambda`, `std::f64::consts::PI`).
    Sym(Box<str>),
    /// A primitive of one argument.
    Unary(Unary, Id),
    /// A primitive of two arguments.
    Binary(Binary, Id, Id),
    /// An integer power `u.powi(n)`.
    Powi(Id, i32),
    /// A piecewise expression `if a <cmp> b { then } else { otherwise }`, as
    /// `[a, b, then, otherwise]`.
    Select(Comparison, [Id; 4]),
}

impl Node {
    /// The children of the node, in order.
    pub fn children(&self) -> Vec<Id> {
        match self {
            Node::Num(_) | Node::Sym(_) => Vec::new(),
            Node::Unary(_, a) | Node::Powi(a, _) => vec![*a],
            Node::Binary(_, a, b) => vec![*a, *b],
            Node::Select(_, ids) => ids.to_vec(),
        }
    }

    /// Whether the node is a constant or a symbol.
    pub fn is_leaf(&self) -> bool {
        matches!(self, Node::Num(_) | Node::Sym(_))
    }
}

/// The work of the simplification under way (see [`super::simplify`]): how deeply
/// constructors are nested and how many were entered since the outermost one.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Rewriting {
    pub(super) depth: usize,
    pub(super) spent: usize,
}

/// A hash-consed arena of expression nodes, children before parents.
///
/// ```
/// use mechdiff_core::symbolic::Graph;
///
/// let mut graph = Graph::new();
/// let phi = graph.symbol("phi");
/// let a = graph.sin(phi);
/// let b = graph.sin(phi);
/// assert_eq!(a, b); // stored once
/// assert_eq!(graph.to_sexpr(a), "(sin phi)");
/// ```
#[derive(Clone, Debug, Default)]
pub struct Graph {
    nodes: Vec<Node>,
    index: HashMap<Node, Id>,
    /// The range of each node (see [`super::range`]), computed as it is stored.
    ranges: Vec<Range>,
    pub(super) derivative_cache: HashMap<(Id, Box<str>), Id>,
    /// The work of the simplification under way (see [`super::simplify`]'s budget).
    pub(super) rewriting: Rewriting,
}

impl Graph {
    /// An empty graph.
    pub fn new() -> Self {
        Self::default()
    }

    /// Number of distinct nodes stored.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether no node is stored.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The node stored at `id`.
    pub fn node(&self, id: Id) -> &Node {
        &self.nodes[id.index()]
    }

    /// An interval holding every real value of the node `id`, whatever its symbols are
    /// (see [`super::range`]): what the simplifier knows of its sign.
    pub fn range(&self, id: Id) -> Range {
        self.ranges[id.index()]
    }

    /// All nodes, children before parents.
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// Stores `node` as it is (no simplification) and returns its id; a node that is already
    /// stored is not stored again.
    pub fn intern(&mut self, node: Node) -> Id {
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        debug_assert!(node.children().iter().all(|c| c.index() < self.nodes.len()));
        let id = Id::at(self.nodes.len());
        let range = self.range_of(&node);
        self.ranges.push(range);
        self.nodes.push(node.clone());
        self.index.insert(node, id);
        id
    }

    /// The symbol `name` (a variable, parameter or named constant).
    pub fn symbol(&mut self, name: &str) -> Id {
        self.intern(Node::Sym(name.into()))
    }

    /// The constant `value`, or `None` if it is not finite.
    pub fn try_number(&mut self, value: f64) -> Option<Id> {
        Number::new(value).map(|n| self.intern(Node::Num(n)))
    }

    /// The constant `value`.
    ///
    /// # Panics
    /// If `value` is not finite (use [`Graph::try_number`] for values from outside).
    pub fn number(&mut self, value: f64) -> Id {
        self.try_number(value)
            .unwrap_or_else(|| panic!("constant {value} is not finite"))
    }

    /// The value of `id` if it is a constant.
    pub fn as_number(&self, id: Id) -> Option<f64> {
        match self.node(id) {
            Node::Num(n) => Some(n.value()),
            _ => None,
        }
    }

    /// Whether `id` is the constant `value`.
    pub fn is_number(&self, id: Id, value: f64) -> bool {
        self.as_number(id) == Some(value)
    }

    /// Marks the nodes reachable from `roots` (the roots included).
    pub fn reachable(&self, roots: &[Id]) -> Vec<bool> {
        let mut seen = vec![false; self.nodes.len()];
        let mut stack: Vec<Id> = roots.to_vec();
        while let Some(id) = stack.pop() {
            if !std::mem::replace(&mut seen[id.index()], true) {
                stack.extend(self.node(id).children());
            }
        }
        seen
    }

    /// The distinct symbols that `roots` depend on, sorted by name.
    pub fn symbols(&self, roots: &[Id]) -> Vec<&str> {
        let seen = self.reachable(roots);
        let mut names: Vec<&str> = self
            .nodes
            .iter()
            .zip(&seen)
            .filter_map(|(node, &s)| match node {
                Node::Sym(name) if s => Some(&**name),
                _ => None,
            })
            .collect();
        names.sort_unstable();
        names
    }
}

impl Graph {
    /// The id of `node` if it is stored.
    pub fn lookup(&self, node: &Node) -> Option<Id> {
        self.index.get(node).copied()
    }
}
