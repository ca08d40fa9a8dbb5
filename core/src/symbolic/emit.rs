//! Emission of expressions as Rust: tokens (for the proc-macro) and formatted source.
//!
//! The emitted code is straight-line `f64` code: every node the outputs need is computed
//! once; a node used more than once (or returned) is bound with `let`, a node used once is
//! written inline where it is used; `sin` and `cos` of one argument become one
//! `sin_cos()` call; `x²` of a named value is `x * x`. Parentheses are written only where
//! precedence or the evaluation order needs them, so the `f64` operations are exactly those
//! of the graph. Symbols are emitted as written (`phi`, `std::f64::consts::PI`).

use std::collections::{HashMap, HashSet};

use proc_macro2::{Ident, Literal, Span, TokenStream, TokenTree};
use quote::{ToTokens, quote};

use super::count::{sin_cos_pairs, use_counts};
use super::graph::{Graph, Id, Node};
use super::ops::{Binary, Unary};
use crate::error::Error;

/// Binding strength of an emitted expression, weakest first.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Precedence {
    Block,
    Sum,
    Product,
    Prefix,
    Postfix,
}

/// How deeply operations may nest in one emitted expression before a value is bound with
/// `let`: deep formulas (1000 nested `sin`, a sum of 8000 terms) become `let` chains that
/// rustc parses without exhausting its stack, and each token is copied a bounded number of
/// times (emission stays linear in the size of the graph).
const MAX_INLINE_DEPTH: usize = 16;

/// An emitted expression, how strongly it binds and how deeply its operations nest.
#[derive(Clone)]
struct Emitted {
    tokens: TokenStream,
    precedence: Precedence,
    depth: usize,
}

impl Emitted {
    fn name(tokens: TokenStream) -> Self {
        Emitted {
            tokens,
            precedence: Precedence::Postfix,
            depth: 0,
        }
    }
}

/// The tokens of a symbol: an identifier or a path.
fn symbol_tokens(name: &str) -> TokenStream {
    match syn::parse_str::<syn::Path>(name) {
        Ok(path) => path.to_token_stream(),
        Err(_) => Ident::new(name, Span::call_site()).to_token_stream(),
    }
}

struct Emitter<'g> {
    graph: &'g Graph,
    /// Whether each node's Rust expression has no float type of its own: literals and
    /// arithmetic or branches of them (`1.0 / 3.0`, `if x < a { 0.5 } else { 2.0 }`).
    /// `(1.0 / 3.0).sin()` is error E0689, so such a receiver is written
    /// `f64::sin(1.0 / 3.0)` (a typed value) and such a value is bound as `let t: f64 = …`.
    untyped: Vec<bool>,
    emitted: HashMap<Id, Emitted>,
    bound: HashSet<Id>,
    statements: Vec<TokenStream>,
    taken: HashSet<String>,
    next_temporary: usize,
}

impl Emitter<'_> {
    fn fresh(&mut self, wanted: &str) -> Ident {
        let mut name = wanted.to_owned();
        while !self.taken.insert(name.clone()) {
            name.push('_');
        }
        Ident::new(&name, Span::call_site())
    }

    fn temporary(&mut self) -> Ident {
        let name = format!("t{}", self.next_temporary);
        self.next_temporary += 1;
        self.fresh(&name)
    }

    fn leaf(&self, id: Id, receiver: bool) -> Option<Emitted> {
        match self.graph.node(id) {
            Node::Num(n) => {
                let c = n.value();
                let literal = |v: f64| {
                    if receiver {
                        Literal::f64_suffixed(v)
                    } else {
                        Literal::f64_unsuffixed(v)
                    }
                };
                Some(if c < 0.0 {
                    let positive = literal(-c);
                    Emitted {
                        tokens: quote!(-#positive),
                        precedence: Precedence::Prefix,
                        depth: 0,
                    }
                } else {
                    Emitted::name(literal(c).to_token_stream())
                })
            }
            Node::Sym(name) => Some(Emitted::name(symbol_tokens(name))),
            _ => None,
        }
    }

    /// The expression of child `id`, parenthesized if it binds weaker than `at_least`, and
    /// its nesting depth. An expression written inline is used once: it is taken out.
    fn operand(&mut self, id: Id, at_least: Precedence) -> (TokenStream, usize) {
        let receiver = at_least == Precedence::Postfix;
        let emitted = match self.leaf(id, receiver) {
            Some(leaf) => leaf,
            None if self.bound.contains(&id) => self.emitted[&id].clone(),
            None => self
                .emitted
                .remove(&id)
                .expect("children are emitted before their parents"),
        };
        if emitted.precedence < at_least {
            let tokens = emitted.tokens;
            (quote!((#tokens)), emitted.depth)
        } else {
            (emitted.tokens, emitted.depth)
        }
    }

    /// `receiver.method(arguments)`, or `f64::method(receiver, arguments)` when the
    /// receiver is a constant (whose float type a method call cannot infer).
    fn call(
        &mut self,
        receiver: Id,
        method: &str,
        arguments: &[TokenStream],
    ) -> (TokenStream, usize) {
        let method = Ident::new(method, Span::call_site());
        if self.untyped[receiver.index()] {
            let (r, depth) = self.operand(receiver, Precedence::Block);
            (quote!(f64::#method(#r #(, #arguments)*)), depth)
        } else {
            let (r, depth) = self.operand(receiver, Precedence::Postfix);
            (quote!(#r.#method(#(#arguments),*)), depth)
        }
    }

    fn is_named(&self, id: Id) -> bool {
        self.graph.node(id).is_leaf() || self.bound.contains(&id)
    }

    fn expression(&mut self, node: &Node) -> Emitted {
        use Precedence::{Block, Postfix, Prefix, Product, Sum};
        let (tokens, precedence, depth) = match *node {
            Node::Num(_) | Node::Sym(_) => unreachable!("leaves are not bound"),
            Node::Unary(Unary::Neg, a) => {
                let (a, depth) = self.operand(a, Prefix);
                (quote!(-#a), Prefix, depth)
            }
            Node::Unary(op, a) => {
                let (tokens, depth) = self.call(a, op.name(), &[]);
                (tokens, Postfix, depth)
            }
            Node::Binary(op, a, b) if op.is_infix() => {
                let (level, symbol) = match op {
                    Binary::Add => (Sum, quote!(+)),
                    Binary::Sub => (Sum, quote!(-)),
                    Binary::Mul => (Product, quote!(*)),
                    _ => (Product, quote!(/)),
                };
                let right_level = if level == Sum { Product } else { Prefix };
                let (a, depth_a) = self.operand(a, level);
                let (b, depth_b) = self.operand(b, right_level);
                (quote!(#a #symbol #b), level, depth_a.max(depth_b))
            }
            Node::Binary(op, a, b) => {
                let (b, depth_b) = self.operand(b, Block);
                let (tokens, depth_a) = self.call(a, op.name(), &[b]);
                (tokens, Postfix, depth_a.max(depth_b))
            }
            Node::Powi(a, 2) if self.is_named(a) => {
                let (a, depth) = self.operand(a, Postfix);
                (quote!(#a * #a), Product, depth)
            }
            Node::Powi(a, n) => {
                let n = Literal::i32_unsuffixed(n).to_token_stream();
                let (tokens, depth) = self.call(a, "powi", &[n]);
                (tokens, Postfix, depth)
            }
            Node::Select(cmp, [a, b, t, e]) => {
                let cmp: TokenStream = cmp.name().parse().expect("a comparison operator");
                let (a, depth_a) = self.operand(a, Sum);
                let (b, depth_b) = self.operand(b, Sum);
                let (t, depth_t) = self.operand(t, Block);
                let (e, depth_e) = self.operand(e, Block);
                let depth = depth_a.max(depth_b).max(depth_t).max(depth_e);
                // A nested select continues the chain (`else if`, as clippy's
                // `collapsible_else_if` asks of the generated code).
                let chained = e
                    .clone()
                    .into_iter()
                    .next()
                    .is_some_and(|t| matches!(&t, TokenTree::Ident(i) if i == "if"));
                let e = if chained { e } else { quote!({ #e }) };
                (quote!(if #a #cmp #b { #t } else #e), Block, depth)
            }
        };
        Emitted {
            tokens,
            precedence,
            depth: depth + 1,
        }
    }

    fn bind(&mut self, id: Id, name: Ident, value: TokenStream) {
        if self.untyped[id.index()] {
            self.statements.push(quote!(let #name: f64 = #value;));
        } else {
            self.statements.push(quote!(let #name = #value;));
        }
        self.bound.insert(id);
        self.emitted
            .insert(id, Emitted::name(name.into_token_stream()));
    }
}

/// Straight-line Rust computing some outputs: `let` statements, then one expression per
/// output (a name, a constant or a symbol).
#[derive(Clone, Debug)]
pub struct Emission {
    /// The `let` statements, in order.
    pub statements: Vec<TokenStream>,
    /// The expression of each output, in order.
    pub results: Vec<TokenStream>,
}

#[cfg_attr(docsrs, doc(cfg(feature = "emit")))]
impl Graph {
    /// The statements and the final array expression computing `outputs`, as the body of a
    /// function: `{ let …; [o0, o1, …] }`. See [`Graph::emit`].
    pub fn emit_body(&self, outputs: &[Id], output_names: &[&str]) -> TokenStream {
        let Emission {
            statements,
            results,
        } = self.emit(outputs, output_names);
        quote! { #(#statements)* [#(#results),*] }
    }

    /// Straight-line code computing `outputs`. `output_names` name the bound outputs
    /// (`value`, `d1`, …); temporaries are `t0`, `t1`, … (avoiding every symbol's name).
    pub fn emit(&self, outputs: &[Id], output_names: &[&str]) -> Emission {
        let (reachable, uses) = use_counts(self, outputs);
        let pairs = sin_cos_pairs(self, &reachable);
        let mut untyped: Vec<bool> = Vec::with_capacity(self.len());
        for node in self.nodes() {
            let of = |id: &Id| untyped[id.index()];
            untyped.push(match node {
                Node::Num(_) => true,
                Node::Sym(_) => false,
                Node::Unary(Unary::Neg, a) => of(a),
                Node::Binary(op, a, b) if op.is_infix() => of(a) && of(b),
                Node::Select(_, [_, _, then, otherwise]) => of(then) && of(otherwise),
                // method calls: on a typed receiver, or written `f64::method(…)`
                Node::Unary(..) | Node::Binary(..) | Node::Powi(..) => false,
            });
        }
        let mut emitter = Emitter {
            graph: self,
            untyped,
            emitted: HashMap::new(),
            bound: HashSet::new(),
            statements: Vec::new(),
            taken: self
                .symbols(outputs)
                .into_iter()
                .map(str::to_owned)
                .collect(),
            next_temporary: 0,
        };
        let output_name: HashMap<Id, &str> = outputs
            .iter()
            .zip(output_names)
            .rev()
            .map(|(id, name)| (*id, *name))
            .collect();
        for (index, node) in self.nodes().iter().enumerate() {
            let id = Id::at(index);
            if !reachable[index] || node.is_leaf() || emitter.emitted.contains_key(&id) {
                continue;
            }
            if let Node::Unary(Unary::Sin | Unary::Cos, u) = node
                && let Some(&(sin, cos)) = pairs.get(u)
            {
                let (call, _) = emitter.call(*u, "sin_cos", &[]);
                let (s, c) = (emitter.temporary(), emitter.temporary());
                emitter.statements.push(quote!(let (#s, #c) = #call;));
                for (node, name) in [(sin, s), (cos, c)] {
                    emitter.bound.insert(node);
                    emitter
                        .emitted
                        .insert(node, Emitted::name(name.into_token_stream()));
                }
                continue;
            }
            let expression = emitter.expression(node);
            if let Some(name) = output_name.get(&id) {
                let name = emitter.fresh(name);
                emitter.bind(id, name, expression.tokens);
            } else if uses[index] >= 2 || expression.depth > MAX_INLINE_DEPTH {
                let name = emitter.temporary();
                emitter.bind(id, name, expression.tokens);
            } else {
                emitter.emitted.insert(id, expression);
            }
        }
        let results: Vec<TokenStream> = outputs
            .iter()
            .map(|&id| emitter.operand(id, Precedence::Block).0)
            .collect();
        Emission {
            statements: emitter.statements,
            results,
        }
    }

    /// A complete function `pub fn name(p: f64, …) -> [f64; N]` returning `outputs`.
    pub fn emit_function(
        &self,
        name: &str,
        parameters: &[&str],
        outputs: &[Id],
        output_names: &[&str],
    ) -> TokenStream {
        let name = Ident::new(name, Span::call_site());
        let parameters = parameters.iter().map(|p| Ident::new(p, Span::call_site()));
        let body = self.emit_body(outputs, output_names);
        let count = Literal::usize_unsuffixed(outputs.len());
        quote! {
            pub fn #name(#(#parameters: f64),*) -> [f64; #count] {
                #body
            }
        }
    }
}

/// Formats Rust tokens (a file's items) as source text with prettyplease.
///
/// # Errors
/// [`Error::InvalidEmittedRust`] if the tokens are not a valid Rust file.
pub fn format_rust(tokens: TokenStream) -> Result<String, Error> {
    let file: syn::File = syn::parse2(tokens).map_err(|e| Error::InvalidEmittedRust {
        reason: e.to_string(),
    })?;
    Ok(prettyplease::unparse(&file))
}
