//! S-expressions: the IR's text form, for tests, rules and inspection.
//!
//! ```text
//! (+ a b)  (- a b)  (- a)  (* a b)  (/ a b)  (neg a)  (powi a 3)  (powf a b)
//! (sin a) … (abs a)  (atan2 y x)  (hypot a b)  (if (< a b) then otherwise)
//! (d x e)   ; parsing only: the derivative of e with respect to x
//! ```
//! `+` and `*` take two or more arguments; numbers are decimal `f64` literals; every other
//! atom is a symbol.

use super::graph::{Graph, Id, Node};
use super::ops::{Binary, Comparison, Unary};
use crate::error::Error;

/// Formats a constant: integers without a fraction, exponent notation when very large or
/// small.
pub(crate) fn format_number(value: f64) -> String {
    let magnitude = value.abs();
    if magnitude == 0.0 || (1e-5..1e16).contains(&magnitude) {
        format!("{value}")
    } else {
        format!("{value:e}")
    }
}

#[derive(Debug)]
enum Token<'a> {
    Open(usize),
    Close(usize),
    Atom(usize, &'a str),
}

fn tokenize(input: &str) -> Vec<Token<'_>> {
    let mut tokens = Vec::new();
    let mut start: Option<usize> = None;
    let char_position = |byte: usize| input[..byte].chars().count();
    for (byte, c) in input.char_indices() {
        if c == '(' || c == ')' || c.is_whitespace() {
            if let Some(s) = start.take() {
                tokens.push(Token::Atom(char_position(s), &input[s..byte]));
            }
            if c == '(' {
                tokens.push(Token::Open(char_position(byte)));
            } else if c == ')' {
                tokens.push(Token::Close(char_position(byte)));
            }
        } else if start.is_none() {
            start = Some(byte);
        }
    }
    if let Some(s) = start {
        tokens.push(Token::Atom(char_position(s), &input[s..]));
    }
    tokens
}

struct Parser<'a, 'g> {
    input: &'a str,
    tokens: Vec<Token<'a>>,
    next: usize,
    graph: &'g mut Graph,
}

impl Parser<'_, '_> {
    fn error(&self, position: usize, message: impl Into<String>) -> Error {
        Error::formula(self.input, position, message)
    }

    fn end(&self) -> usize {
        self.input.chars().count()
    }

    fn expression(&mut self) -> Result<Id, Error> {
        let Some(token) = self.tokens.get(self.next) else {
            return Err(self.error(self.end(), "expected an expression, found the end"));
        };
        self.next += 1;
        match *token {
            Token::Close(at) => Err(self.error(at, "unexpected `)`")),
            Token::Atom(_, text) => Ok(self.atom(text)),
            Token::Open(at) => self.list(at),
        }
    }

    fn atom(&mut self, text: &str) -> Id {
        let numeric = text.starts_with(|c: char| c.is_ascii_digit() || c == '.')
            || (text.len() > 1 && text.starts_with('-'));
        match text.parse::<f64>() {
            Ok(value) if numeric => self.graph.number(value),
            _ => self.graph.symbol(text),
        }
    }

    fn arguments(&mut self) -> Result<Vec<(usize, Id)>, Error> {
        let mut arguments = Vec::new();
        loop {
            match self.tokens.get(self.next) {
                None => return Err(self.error(self.end(), "expected `)`, found the end")),
                Some(Token::Close(_)) => {
                    self.next += 1;
                    return Ok(arguments);
                }
                Some(Token::Open(at) | Token::Atom(at, _)) => {
                    let at = *at;
                    arguments.push((at, self.expression()?));
                }
            }
        }
    }

    fn list(&mut self, open: usize) -> Result<Id, Error> {
        let (head_at, head) = match self.tokens.get(self.next) {
            Some(Token::Atom(at, text)) => (*at, *text),
            Some(Token::Open(at) | Token::Close(at)) => {
                return Err(self.error(*at, "expected an operator after `(`"));
            }
            None => return Err(self.error(open, "unclosed `(`")),
        };
        self.next += 1;
        if head == "if" {
            return self.select(head_at);
        }
        let arguments = self.arguments()?;
        let ids: Vec<Id> = arguments.iter().map(|(_, id)| *id).collect();
        let arity = |n: usize| -> Result<(), Error> {
            if ids.len() == n {
                Ok(())
            } else {
                let message = format!("`{head}` takes {n} argument(s), found {}", ids.len());
                Err(Error::formula(self.input, head_at, message))
            }
        };
        match head {
            "+" | "*" if ids.len() >= 2 => {
                let op = if head == "+" {
                    Binary::Add
                } else {
                    Binary::Mul
                };
                let g = &mut *self.graph;
                Ok(ids[1..].iter().fold(ids[0], |acc, &x| g.binary(op, acc, x)))
            }
            "-" if ids.len() == 1 => Ok(self.graph.neg(ids[0])),
            "powi" => {
                arity(2)?;
                let exponent = self
                    .graph
                    .as_number(ids[1])
                    .filter(|n| n.fract() == 0.0 && n.abs() <= f64::from(i32::MAX));
                let Some(n) = exponent else {
                    return Err(self.error(arguments[1].0, "`powi` needs an integer exponent"));
                };
                Ok(self.graph.powi(ids[0], n as i32))
            }
            "d" => {
                arity(2)?;
                let Node::Sym(variable) = self.graph.node(ids[0]).clone() else {
                    return Err(self.error(arguments[0].0, "`d` needs a variable name first"));
                };
                Ok(self.graph.derivative(ids[1], &variable))
            }
            _ => {
                if let Some(op) = Unary::from_name(head) {
                    arity(1)?;
                    Ok(self.graph.unary(op, ids[0]))
                } else if let Some(op) = Binary::from_name(head) {
                    arity(2)?;
                    Ok(self.graph.binary(op, ids[0], ids[1]))
                } else {
                    Err(self.error(head_at, format!("unknown operator `{head}`")))
                }
            }
        }
    }

    fn select(&mut self, head_at: usize) -> Result<Id, Error> {
        let condition = match self.tokens.get(self.next) {
            Some(Token::Open(_)) => self.next + 1,
            _ => return Err(self.error(head_at, "`if` needs a condition like `(< a b)`")),
        };
        let cmp = match self.tokens.get(condition) {
            Some(Token::Atom(at, text)) => Comparison::from_name(text)
                .ok_or_else(|| self.error(*at, format!("`{text}` is not a comparison")))?,
            _ => return Err(self.error(head_at, "`if` needs a condition like `(< a b)`")),
        };
        self.next = condition + 1;
        let compared = self.arguments()?;
        if compared.len() != 2 {
            return Err(self.error(head_at, "a comparison takes 2 arguments"));
        }
        let branches = self.arguments()?;
        if branches.len() != 2 {
            return Err(self.error(head_at, "`if` takes a condition and 2 branches"));
        }
        let [(_, a), (_, b)] = [compared[0], compared[1]];
        Ok(self.graph.select(cmp, a, b, branches[0].1, branches[1].1))
    }
}

impl Graph {
    /// Parses an s-expression into this graph (simplifying as it builds).
    ///
    /// ```
    /// use mechdiff_core::symbolic::Graph;
    ///
    /// let mut graph = Graph::new();
    /// let lhs = graph.parse_sexpr("(d x (sin x))").unwrap();
    /// let rhs = graph.parse_sexpr("(cos x)").unwrap();
    /// assert_eq!(lhs, rhs);
    /// assert!(graph.parse_sexpr("(sin x").is_err());
    /// ```
    pub fn parse_sexpr(&mut self, input: &str) -> Result<Id, Error> {
        let mut parser = Parser {
            input,
            tokens: tokenize(input),
            next: 0,
            graph: self,
        };
        let id = parser.expression()?;
        match parser.tokens.get(parser.next) {
            None => Ok(id),
            Some(Token::Open(at) | Token::Close(at) | Token::Atom(at, _)) => {
                Err(parser.error(*at, "unexpected text after the expression"))
            }
        }
    }

    /// The expression `id` as an s-expression (shared subexpressions are written out).
    pub fn to_sexpr(&self, id: Id) -> String {
        let mut out = String::new();
        self.write_sexpr(id, &mut out);
        out
    }

    fn write_sexpr(&self, id: Id, out: &mut String) {
        let list = |head: &str, children: &[Id], out: &mut String| {
            out.push('(');
            out.push_str(head);
            for &c in children {
                out.push(' ');
                self.write_sexpr(c, out);
            }
            out.push(')');
        };
        match self.node(id) {
            Node::Num(n) => out.push_str(&format_number(n.value())),
            Node::Sym(name) => out.push_str(name),
            Node::Unary(op, a) => list(op.name(), &[*a], out),
            Node::Binary(op, a, b) => list(op.name(), &[*a, *b], out),
            Node::Powi(a, n) => {
                out.push_str("(powi ");
                self.write_sexpr(*a, out);
                out.push_str(&format!(" {n})"));
            }
            Node::Select(cmp, [a, b, t, e]) => {
                out.push_str("(if ");
                list(cmp.name(), &[*a, *b], out);
                for c in [t, e] {
                    out.push(' ');
                    self.write_sexpr(*c, out);
                }
                out.push(')');
            }
        }
    }
}
