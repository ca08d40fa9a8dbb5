//! Infix formulas, as a user writes them: `atan2(lambda*sin(phi), 1 - lambda*cos(phi))`.
//!
//! ```text
//! sum     = product (("+" | "-") product)*
//! product = unary (("*" | "/") unary)*
//! unary   = "-" unary | power
//! power   = atom ("^" unary)?          (integer constant exponent: powi, else powf)
//! atom    = number | name | name "(" sum ("," sum)* ")" | "(" sum ")"
//! ```
//! Functions are the primitives by name (`sin`, `atan2`, `hypot`, `powf`, `powi`, …, and
//! `pow` for `powf`). Names may be paths (`std::f64::consts::PI`). Errors carry the
//! character position of the problem.

use super::graph::{Graph, Id};
use super::ops::{Binary, Unary};
use crate::error::Error;

#[derive(Clone, Debug, PartialEq)]
enum Kind {
    Number(f64),
    Name(String),
    Symbol(char),
    End,
}

#[derive(Clone, Debug)]
struct Token {
    kind: Kind,
    at: usize,
}

fn tokenize(input: &str) -> Result<Vec<Token>, Error> {
    let chars: Vec<char> = input.chars().collect();
    let mut tokens = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let at = i;
        if c.is_whitespace() {
            i += 1;
        } else if c.is_ascii_digit()
            || (c == '.' && chars.get(i + 1).is_some_and(char::is_ascii_digit))
        {
            while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.') {
                i += 1;
            }
            if i < chars.len() && (chars[i] == 'e' || chars[i] == 'E') {
                let sign = usize::from(matches!(chars.get(i + 1), Some('+' | '-')));
                if chars.get(i + 1 + sign).is_some_and(char::is_ascii_digit) {
                    i += 1 + sign;
                    while i < chars.len() && chars[i].is_ascii_digit() {
                        i += 1;
                    }
                }
            }
            let text: String = chars[at..i].iter().collect();
            let value = text
                .parse::<f64>()
                .map_err(|_| Error::formula(input, at, format!("`{text}` is not a number")))?;
            tokens.push(Token {
                kind: Kind::Number(value),
                at,
            });
        } else if c.is_alphabetic() || c == '_' {
            while i < chars.len()
                && (chars[i].is_alphanumeric()
                    || chars[i] == '_'
                    || (chars[i] == ':' && chars.get(i + 1) == Some(&':')))
            {
                i += if chars[i] == ':' { 2 } else { 1 };
            }
            tokens.push(Token {
                kind: Kind::Name(chars[at..i].iter().collect()),
                at,
            });
        } else if "+-*/^(),".contains(c) {
            tokens.push(Token {
                kind: Kind::Symbol(c),
                at,
            });
            i += 1;
        } else {
            return Err(Error::formula(
                input,
                at,
                format!("unexpected character `{c}`"),
            ));
        }
    }
    tokens.push(Token {
        kind: Kind::End,
        at: chars.len(),
    });
    Ok(tokens)
}

struct Parser<'a, 'g> {
    input: &'a str,
    tokens: Vec<Token>,
    next: usize,
    graph: &'g mut Graph,
}

impl Parser<'_, '_> {
    fn peek(&self) -> &Token {
        &self.tokens[self.next]
    }

    fn eat(&mut self, symbol: char) -> bool {
        let found = self.peek().kind == Kind::Symbol(symbol);
        self.next += usize::from(found);
        found
    }

    fn error(&self, at: usize, message: impl Into<String>) -> Error {
        Error::formula(self.input, at, message)
    }

    fn describe(kind: &Kind) -> String {
        match kind {
            Kind::Number(_) => "a number".to_owned(),
            Kind::Name(name) => format!("`{name}`"),
            Kind::Symbol(c) => format!("`{c}`"),
            Kind::End => "the end".to_owned(),
        }
    }

    fn expect(&mut self, symbol: char) -> Result<(), Error> {
        if self.eat(symbol) {
            Ok(())
        } else {
            let token = self.peek();
            Err(self.error(
                token.at,
                format!("expected `{symbol}`, found {}", Self::describe(&token.kind)),
            ))
        }
    }

    fn sum(&mut self) -> Result<Id, Error> {
        let mut left = self.product()?;
        loop {
            if self.eat('+') {
                let right = self.product()?;
                left = self.graph.add(left, right);
            } else if self.eat('-') {
                let right = self.product()?;
                left = self.graph.sub(left, right);
            } else {
                return Ok(left);
            }
        }
    }

    fn product(&mut self) -> Result<Id, Error> {
        let mut left = self.unary()?;
        loop {
            if self.eat('*') {
                let right = self.unary()?;
                left = self.graph.mul(left, right);
            } else if self.eat('/') {
                let right = self.unary()?;
                left = self.graph.div(left, right);
            } else {
                return Ok(left);
            }
        }
    }

    fn unary(&mut self) -> Result<Id, Error> {
        if self.eat('-') {
            let operand = self.unary()?;
            return Ok(self.graph.neg(operand));
        }
        let base = self.atom()?;
        if self.eat('^') {
            let exponent = self.unary()?;
            return Ok(self.graph.powf(base, exponent));
        }
        Ok(base)
    }

    fn atom(&mut self) -> Result<Id, Error> {
        let token = self.peek().clone();
        self.next += 1;
        match token.kind {
            Kind::Number(value) => Ok(self.graph.number(value)),
            Kind::Symbol('(') => {
                let inner = self.sum()?;
                self.expect(')')?;
                Ok(inner)
            }
            Kind::Name(name) if self.eat('(') => self.call(&name, token.at),
            Kind::Name(name) => Ok(self.graph.symbol(&name)),
            other => Err(self.error(
                token.at,
                format!(
                    "expected a number, a name or `(`, found {}",
                    Self::describe(&other)
                ),
            )),
        }
    }

    fn call(&mut self, name: &str, at: usize) -> Result<Id, Error> {
        let mut arguments = vec![(self.peek().at, self.sum()?)];
        while self.eat(',') {
            arguments.push((self.peek().at, self.sum()?));
        }
        self.expect(')')?;
        let ids: Vec<Id> = arguments.iter().map(|(_, id)| *id).collect();
        let arity = match (Unary::from_name(name), Binary::from_name(name), name) {
            (Some(_), ..) => 1,
            (_, Some(op), _) if !op.is_infix() => 2,
            (.., "pow" | "powi") => 2,
            _ => {
                let known: Vec<&str> = Unary::ALL.iter().map(|op| op.name()).collect();
                return Err(self.error(
                    at,
                    format!(
                        "unknown function `{name}`; known: {}, atan2, hypot, powf, powi, pow",
                        known.join(", ")
                    ),
                ));
            }
        };
        if ids.len() != arity {
            return Err(self.error(
                at,
                format!("`{name}` takes {arity} argument(s), found {}", ids.len()),
            ));
        }
        if let Some(op) = Unary::from_name(name) {
            return Ok(self.graph.unary(op, ids[0]));
        }
        match name {
            "pow" => Ok(self.graph.powf(ids[0], ids[1])),
            "powi" => {
                let n = self
                    .graph
                    .as_number(ids[1])
                    .filter(|n| n.fract() == 0.0 && n.abs() <= f64::from(i32::MAX));
                let n = n.ok_or_else(|| {
                    self.error(arguments[1].0, "`powi` needs an integer constant exponent")
                })?;
                Ok(self.graph.powi(ids[0], n as i32))
            }
            _ => {
                let op = Binary::from_name(name).expect("checked above");
                Ok(self.graph.binary(op, ids[0], ids[1]))
            }
        }
    }
}

impl Graph {
    /// Parses an infix formula into this graph.
    ///
    /// ```
    /// use mechdiff_core::symbolic::Graph;
    ///
    /// let mut graph = Graph::new();
    /// let psi = graph.parse_infix("atan2(lambda*sin(phi), 1 - lambda*cos(phi))").unwrap();
    /// assert_eq!(
    ///     graph.to_sexpr(psi),
    ///     "(atan2 (* lambda (sin phi)) (- 1 (* lambda (cos phi))))"
    /// );
    /// let error = graph.parse_infix("sin(phi").unwrap_err();
    /// assert!(error.to_string().contains("column 8"));
    /// ```
    ///
    /// # Errors
    /// [`Error::Formula`] with the position of the problem.
    pub fn parse_infix(&mut self, input: &str) -> Result<Id, Error> {
        let tokens = tokenize(input)?;
        let mut parser = Parser {
            input,
            tokens,
            next: 0,
            graph: self,
        };
        let id = parser.sum()?;
        let token = parser.peek().clone();
        if token.kind != Kind::End {
            return Err(parser.error(
                token.at,
                format!(
                    "unexpected {} after the formula",
                    Parser::describe(&token.kind)
                ),
            ));
        }
        Ok(id)
    }
}
