//! Pyslvs's mechanism expression (as `parse_vpoints` reads it):
//!
//! ```text
//! M[
//!   J[R, color[Green], P[0.0, 0.0], L[ground, L1]],
//!   J[P, A[30.0], color[Green], P[51.38, -12.63], L[ground, L2]],
//! ]
//! ```
//!
//! A joint is `J[type, A[angle]?, color[...]?, P[x, y], L[links]]`: `type` is `R`, `P` or
//! `RP` (the angle, in degrees, is required for `P` and `RP`); the colour (a name, or
//! `(r, g, b)`) is skipped. `#` starts a comment to the end of the line. The expression has
//! no driving input (Pyslvs keeps the inputs apart): the first ground pivot of a crank is
//! driven.

use std::ops::Range;

use crate::error::Result;
use crate::scene::Source;

use super::linkage::{Joint, JointKind, Linkage, error};

#[derive(Debug, Clone, PartialEq)]
enum Token {
    Word(String),
    Number(f64),
    Open,
    Close,
    OpenParen,
    CloseParen,
    Comma,
}

fn describe(t: Option<&(Token, Range<usize>)>) -> String {
    match t.map(|t| &t.0) {
        None => "the end of the file".to_owned(),
        Some(Token::Word(w)) => format!("`{w}`"),
        Some(Token::Number(v)) => format!("the number {v}"),
        Some(Token::Open) => "`[`".to_owned(),
        Some(Token::Close) => "`]`".to_owned(),
        Some(Token::OpenParen) => "`(`".to_owned(),
        Some(Token::CloseParen) => "`)`".to_owned(),
        Some(Token::Comma) => "`,`".to_owned(),
    }
}

fn tokens(source: &Source) -> Result<Vec<(Token, Range<usize>)>> {
    let text = &source.text;
    let mut out = Vec::new();
    let mut chars = text.char_indices().peekable();
    while let Some((i, c)) = chars.next() {
        let single = match c {
            '[' => Some(Token::Open),
            ']' => Some(Token::Close),
            '(' => Some(Token::OpenParen),
            ')' => Some(Token::CloseParen),
            ',' => Some(Token::Comma),
            _ => None,
        };
        if let Some(t) = single {
            out.push((t, i..i + 1));
            continue;
        }
        if c.is_whitespace() {
            continue;
        }
        if c == '#' {
            while chars.next_if(|&(_, c)| c != '\n').is_some() {}
            continue;
        }
        let mut end = i + c.len_utf8();
        while let Some(&(j, d)) = chars.peek() {
            if d.is_whitespace() || "[](),#".contains(d) {
                break;
            }
            end = j + d.len_utf8();
            chars.next();
        }
        let word = &text[i..end];
        if c.is_ascii_digit() || matches!(c, '+' | '-' | '.') {
            let v: f64 = word
                .parse()
                .map_err(|_| error(source, i..end, format!("`{word}` is not a number")))?;
            if !v.is_finite() {
                return Err(error(
                    source,
                    i..end,
                    format!("`{word}` is not a finite number"),
                ));
            }
            out.push((Token::Number(v), i..end));
        } else {
            out.push((Token::Word(word.to_owned()), i..end));
        }
    }
    Ok(out)
}

struct Parser<'s> {
    source: &'s Source,
    tokens: Vec<(Token, Range<usize>)>,
    at: usize,
}

impl Parser<'_> {
    fn peek(&self) -> Option<&(Token, Range<usize>)> {
        self.tokens.get(self.at)
    }

    fn span(&self) -> Range<usize> {
        self.peek()
            .map_or(self.source.text.len()..self.source.text.len(), |t| {
                t.1.clone()
            })
    }

    fn expect(&mut self, want: &Token, what: &str) -> Result<Range<usize>> {
        match self.peek() {
            Some((t, span)) if t == want => {
                let span = span.clone();
                self.at += 1;
                Ok(span)
            }
            other => Err(error(
                self.source,
                self.span(),
                format!("expected {what}, found {}", describe(other)),
            )),
        }
    }

    /// `NAME[`: a keyword and its bracket.
    fn head(&mut self, name: &str) -> Result<Range<usize>> {
        let span = match self.peek() {
            Some((Token::Word(w), span)) if w == name => span.clone(),
            other => {
                return Err(error(
                    self.source,
                    self.span(),
                    format!("expected `{name}[`, found {}", describe(other)),
                ));
            }
        };
        self.at += 1;
        self.expect(&Token::Open, &format!("`[` after `{name}`"))?;
        Ok(span)
    }

    fn is_head(&self, name: &str) -> bool {
        matches!(self.peek(), Some((Token::Word(w), _)) if w == name)
    }

    fn number(&mut self, what: &str) -> Result<f64> {
        match self.peek() {
            Some((Token::Number(v), _)) => {
                let v = *v;
                self.at += 1;
                Ok(v)
            }
            other => Err(error(
                self.source,
                self.span(),
                format!("expected {what} (a number), found {}", describe(other)),
            )),
        }
    }

    /// `,` then `]`, or `]`: the end of a list that may have a trailing comma. Returns
    /// whether the list ended.
    fn list_end(&mut self, what: &str) -> Result<bool> {
        match self.peek().map(|t| &t.0) {
            Some(Token::Close) => {
                self.at += 1;
                Ok(true)
            }
            Some(Token::Comma) => {
                self.at += 1;
                if matches!(self.peek().map(|t| &t.0), Some(Token::Close)) {
                    self.at += 1;
                    return Ok(true);
                }
                Ok(false)
            }
            _ => Err(error(
                self.source,
                self.span(),
                format!(
                    "expected `,` or `]` in {what}, found {}",
                    describe(self.peek())
                ),
            )),
        }
    }

    fn joint(&mut self) -> Result<Joint> {
        let start = self.head("J")?.start;
        let (type_name, type_span) = match self.peek() {
            Some((Token::Word(w), span)) if matches!(w.as_str(), "R" | "P" | "RP") => {
                (w.clone(), span.clone())
            }
            other => {
                return Err(error(
                    self.source,
                    self.span(),
                    format!(
                        "expected a joint type `R`, `P` or `RP`, found {}",
                        describe(other)
                    ),
                ));
            }
        };
        self.at += 1;
        self.expect(&Token::Comma, "`,` after the joint type")?;
        let mut angle = None;
        if self.is_head("A") {
            self.head("A")?;
            angle = Some(self.number("the slide angle in degrees")?);
            self.expect(&Token::Close, "`]` after the angle")?;
            self.expect(&Token::Comma, "`,` after `A[...]`")?;
        }
        if self.is_head("color") {
            self.head("color")?;
            let mut depth = 1;
            while depth > 0 {
                match self.peek().map(|t| &t.0) {
                    Some(Token::Open) => depth += 1,
                    Some(Token::Close) => depth -= 1,
                    None => {
                        return Err(error(self.source, self.span(), "`color[` is not closed"));
                    }
                    _ => {}
                }
                self.at += 1;
            }
            self.expect(&Token::Comma, "`,` after `color[...]`")?;
        }
        self.head("P")?;
        let x = self.number("the x coordinate")?;
        self.expect(&Token::Comma, "`,` between the coordinates")?;
        let y = self.number("the y coordinate")?;
        self.expect(&Token::Close, "`]` after the coordinates")?;
        self.expect(&Token::Comma, "`,` after `P[x, y]`")?;
        self.head("L")?;
        let mut links = Vec::new();
        if matches!(self.peek().map(|t| &t.0), Some(Token::Close)) {
            self.at += 1;
        } else {
            loop {
                match self.peek() {
                    Some((Token::Word(w), _)) => {
                        links.push(w.clone());
                        self.at += 1;
                    }
                    other => {
                        return Err(error(
                            self.source,
                            self.span(),
                            format!(
                                "expected a link name in `L[...]`, found {}",
                                describe(other)
                            ),
                        ));
                    }
                }
                if self.list_end("`L[...]`")? {
                    break;
                }
            }
        }
        let end = self
            .expect(&Token::Close, "`]` closing the joint `J[...]`")?
            .end;
        let span = start..end;
        if links.is_empty() {
            return Err(error(self.source, span, "the joint lists no link in `L[]`"));
        }
        let kind = match type_name.as_str() {
            "R" => JointKind::Revolute,
            "P" => JointKind::Prismatic {
                angle: angle.ok_or_else(|| {
                    error(
                        self.source,
                        type_span,
                        "a `P` joint needs its angle: `J[P, A[30.0], ...]`",
                    )
                })?,
            },
            _ => {
                return Err(error(
                    self.source,
                    type_span,
                    "an `RP` joint (a pin sliding in a turning slot) is not imported yet; write \
                     it in the scene as a `pin_in_slot` joint (docs/scene-format.md)",
                ));
            }
        };
        Ok(Joint {
            kind,
            links,
            at: [x, y],
            span,
        })
    }
}

/// Reads a Pyslvs expression.
///
/// # Errors
/// [`crate::Error::Import`] at the first token that does not fit the grammar, or at an
/// `RP` joint.
pub fn parse(source: &Source) -> Result<Linkage> {
    let mut p = Parser {
        source,
        tokens: tokens(source)?,
        at: 0,
    };
    p.head("M")?;
    let mut joints = Vec::new();
    if matches!(p.peek().map(|t| &t.0), Some(Token::Close)) {
        p.at += 1;
    } else {
        loop {
            joints.push(p.joint()?);
            if p.list_end("the mechanism `M[...]`")? {
                break;
            }
        }
    }
    if let Some((_, span)) = p.peek() {
        return Err(error(
            source,
            span.clone(),
            format!(
                "unexpected {} after the mechanism `M[...]`",
                describe(p.peek())
            ),
        ));
    }
    Ok(Linkage {
        format: "Pyslvs expression",
        joints,
        drive: None,
    })
}
