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
//! `pow` for `powf`). `pi`, `PI` and `std::f64::consts::PI` are π; other paths must name a
//! constant of `std::f64::consts` (see [`super::constants`]). Errors carry the character
//! position of the problem.
//!
//! Checked while parsing, each an error at the column of the problem:
//! - a number too large for `f64` (`1e309`);
//! - a part of the formula without variables whose `f64` value is not finite: division by
//!   zero (`1/0`, `0/0`), `ln(0)`, `sqrt(-1)`, `acos(2)`, `exp(1000)`;
//! - nesting (parentheses, calls, signs, powers) deeper than [`MAX_NESTING`] levels.

use std::collections::HashMap;

use super::constants;
use super::eval::{Arithmetic, DualArithmetic};
use super::graph::{Graph, Id};
use super::ops::{Binary, Unary};
use crate::error::Error;

/// The deepest nesting of parentheses, function calls, signs and powers a formula may have.
pub const MAX_NESTING: usize = 1024;

/// A formula with at most this many `(`, `-` and `^` is parsed on the caller's stack.
const SHALLOW: usize = 64;

/// The stack of the thread that parses a deeper formula: room for [`MAX_NESTING`] levels
/// (about 10 kB each in a debug build; memory is committed only as it is used).
const DEEP_PARSER_STACK: usize = 64 << 20;

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
            if !value.is_finite() {
                return Err(Error::formula(
                    input,
                    at,
                    format!(
                        "`{text}` is too large for an f64 (the largest is about 1.8e308); \
                         rescale the formula"
                    ),
                ));
            }
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
    /// The `f64` value of each node built so far that has no variables.
    constants: HashMap<Id, f64>,
    /// How deeply the parser is nested.
    depth: usize,
}

/// What is wrong when `op` of constant arguments has no finite value.
fn domain_problem(op: &str, arguments: &[f64]) -> String {
    let x = arguments[0];
    match (op, arguments) {
        ("/", [_, b]) if *b == 0.0 => "division by zero".to_owned(),
        ("sqrt", _) => format!("the square root of a negative number ({x})"),
        ("ln", _) if x == 0.0 => "the logarithm of zero".to_owned(),
        ("ln", _) => format!("the logarithm of a negative number ({x})"),
        ("asin" | "acos", _) => format!("`{op}` of {x}, outside [-1, 1]"),
        ("powf" | "powi", [a, _]) if *a == 0.0 => "zero to a negative power".to_owned(),
        ("powf", [a, b]) if *a < 0.0 => {
            format!("a negative base ({a}) to a non-integer power ({b})")
        }
        _ => format!("`{op}` of {arguments:?} overflows f64"),
    }
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

    /// The `f64` value of `id` if it has no variables.
    fn constant(&self, id: Id) -> Option<f64> {
        self.graph
            .as_number(id)
            .or_else(|| self.constants.get(&id).copied())
    }

    /// Records the value of `built` = `op(arguments)` when the arguments are constants, or
    /// fails at `at` if that value is not finite.
    fn checked(&mut self, built: Id, at: usize, op: &str, arguments: &[Id]) -> Result<Id, Error> {
        let Some(values) = arguments
            .iter()
            .map(|&a| self.constant(a))
            .collect::<Option<Vec<f64>>>()
        else {
            return Ok(built);
        };
        let mut f64s = DualArithmetic::<f64>::new();
        let value = match (Unary::from_name(op), Binary::from_name(op), op, &values[..]) {
            (_, _, "powi", [a, n]) => f64s.powi(a, *n as i32),
            (Some(unary), _, _, [x]) => f64s.unary(unary, x),
            (_, Some(binary), _, [a, b]) => f64s.binary(binary, a, b),
            _ => unreachable!("unary and binary operations only"),
        };
        if !value.is_finite() {
            return Err(self.error(
                at,
                format!(
                    "{}: this part of the formula is a constant whose value is {value}; change \
                     the constants so that it is finite",
                    domain_problem(op, &values)
                ),
            ));
        }
        if self.graph.as_number(built).is_none() {
            self.constants.insert(built, value);
        }
        Ok(built)
    }

    fn binary_at(&mut self, op: Binary, a: Id, b: Id, at: usize) -> Result<Id, Error> {
        if op == Binary::Div && self.constant(b) == Some(0.0) {
            return Err(self.error(
                at,
                "division by zero: the divisor is the constant 0; change the formula so that \
                 it is finite",
            ));
        }
        let built = self.graph.binary(op, a, b);
        self.checked(built, at, op.name(), &[a, b])
    }

    fn sum(&mut self) -> Result<Id, Error> {
        let mut left = self.product()?;
        loop {
            let at = self.peek().at;
            if self.eat('+') {
                let right = self.product()?;
                left = self.binary_at(Binary::Add, left, right, at)?;
            } else if self.eat('-') {
                let right = self.product()?;
                left = self.binary_at(Binary::Sub, left, right, at)?;
            } else {
                return Ok(left);
            }
        }
    }

    fn product(&mut self) -> Result<Id, Error> {
        let mut left = self.unary()?;
        loop {
            let at = self.peek().at;
            if self.eat('*') {
                let right = self.unary()?;
                left = self.binary_at(Binary::Mul, left, right, at)?;
            } else if self.eat('/') {
                let right = self.unary()?;
                left = self.binary_at(Binary::Div, left, right, at)?;
            } else {
                return Ok(left);
            }
        }
    }

    /// A signed power, one level deeper (every nesting passes here, so the depth limit
    /// is checked once).
    fn unary(&mut self) -> Result<Id, Error> {
        if self.depth >= MAX_NESTING {
            return Err(self.error(
                self.peek().at,
                format!(
                    "the formula nests deeper than the limit of {MAX_NESTING} levels \
                     (parentheses, calls, signs, powers); write it with less nesting"
                ),
            ));
        }
        self.depth += 1;
        let result = self.signed_power();
        self.depth -= 1;
        result
    }

    fn signed_power(&mut self) -> Result<Id, Error> {
        let at = self.peek().at;
        if self.eat('-') {
            let operand = self.unary()?;
            let negated = self.graph.neg(operand);
            return self.checked(negated, at, "neg", &[operand]);
        }
        let base = self.atom()?;
        let at = self.peek().at;
        if self.eat('^') {
            let exponent = self.unary()?;
            return self.binary_at(Binary::Powf, base, exponent, at);
        }
        Ok(base)
    }

    fn atom(&mut self) -> Result<Id, Error> {
        let token = self.peek().clone();
        self.next += 1;
        match token.kind {
            Kind::Number(value) => Ok(self
                .graph
                .try_number(value)
                .expect("the tokenizer keeps finite numbers only")),
            Kind::Symbol('(') => {
                let inner = self.sum()?;
                self.expect(')')?;
                Ok(inner)
            }
            Kind::Name(name) if self.eat('(') => self.call(&name, token.at),
            Kind::Name(name) => match constants::canonical(&name) {
                Some(path) => {
                    let id = self.graph.symbol(&path);
                    let value = DualArithmetic::<f64>::new()
                        .named_constant(&path)
                        .expect("a known constant");
                    self.constants.insert(id, value);
                    Ok(id)
                }
                None if name.contains("::") => Err(self.error(
                    token.at,
                    format!(
                        "unknown constant `{name}`; known: {}",
                        constants::known_names()
                    ),
                )),
                None => Ok(self.graph.symbol(&name)),
            },
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
            let built = self.graph.unary(op, ids[0]);
            return self.checked(built, at, name, &ids);
        }
        match name {
            "pow" => self.binary_at(Binary::Powf, ids[0], ids[1], at),
            "powi" => {
                let n = self
                    .graph
                    .as_number(ids[1])
                    .filter(|n| n.fract() == 0.0 && n.abs() <= f64::from(i32::MAX));
                let n = n.ok_or_else(|| {
                    self.error(arguments[1].0, "`powi` needs an integer constant exponent")
                })?;
                let built = self.graph.powi(ids[0], n as i32);
                self.checked(built, at, "powi", &ids)
            }
            _ => {
                let op = Binary::from_name(name).expect("checked above");
                self.binary_at(op, ids[0], ids[1], at)
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
        // the parser recurses once per level of nesting: a deeply nested formula is parsed
        // on a thread with a stack large enough for `MAX_NESTING` levels in any build
        let openings = input.chars().filter(|c| "(-^".contains(*c)).count();
        if openings <= SHALLOW {
            return self.parse_infix_here(input);
        }
        std::thread::scope(|scope| {
            let parser = std::thread::Builder::new()
                .name("formula parser".to_owned())
                .stack_size(DEEP_PARSER_STACK)
                .spawn_scoped(scope, || self.parse_infix_here(input))
                .map_err(|e| {
                    Error::formula(input, 0, format!("cannot start the formula parser: {e}"))
                })?;
            parser
                .join()
                .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
        })
    }

    fn parse_infix_here(&mut self, input: &str) -> Result<Id, Error> {
        let tokens = tokenize(input)?;
        let mut parser = Parser {
            input,
            tokens,
            next: 0,
            graph: self,
            constants: HashMap::new(),
            depth: 0,
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
