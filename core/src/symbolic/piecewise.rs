//! Piecewise infix formulas: `if(a < b, then, otherwise)` anywhere in an infix formula.
//!
//! The condition compares two expressions with `<`, `<=`, `>`, `>=`, `==` or `!=`; the
//! branches are formulas (which may hold further `if`s). The result is the IR's
//! [`Node::Select`], so it differentiates (branch by branch),
//! evaluates (the branch of the condition's real part) and emits (`if a < b { … } else
//! { … }`) like every other node.
//!
//! This is a layer over [`Graph::parse_infix`]: each `if(…)` is parsed on its own and
//! stands in the surrounding formula as a placeholder symbol of the same width (so that the
//! positions of errors stay those of the text as written), which is then replaced.
//!
//! ```
//! use mechdiff_core::symbolic::Graph;
//! let mut graph = Graph::new();
//! let f = graph.parse_infix_piecewise("2*if(x < 1, x^2, 2*x - 1)").unwrap();
//! let df = graph.derivative(f, "x");
//! let at = |graph: &Graph, x: f64| graph.evaluate_f64(&[f, df], &[("x", x)]).unwrap();
//! assert_eq!(at(&graph, 0.5), vec![0.5, 2.0]);
//! assert_eq!(at(&graph, 3.0), vec![10.0, 4.0]);
//! ```

use std::collections::HashMap;

use super::graph::{Graph, Id, Node};
use super::ops::Comparison;
use crate::error::Error;

/// Comparison operators, two-character ones first so that `<=` is not read as `<`.
const COMPARISONS: [(&str, Comparison); 6] = [
    ("<=", Comparison::LessEqual),
    (">=", Comparison::GreaterEqual),
    ("==", Comparison::Equal),
    ("!=", Comparison::NotEqual),
    ("<", Comparison::Less),
    (">", Comparison::Greater),
];

impl Graph {
    /// Parses an infix formula that may contain `if(a <cmp> b, then, otherwise)`.
    ///
    /// # Errors
    /// [`Error::Formula`] with the position (in `text`) of the problem: a malformed `if`
    /// (not three arguments, no comparison), or any error of [`Graph::parse_infix`].
    pub fn parse_infix_piecewise(&mut self, text: &str) -> Result<Id, Error> {
        let chars: Vec<char> = text.chars().collect();
        self.piecewise(text, &chars, 0, chars.len())
    }

    /// Parses `chars[from..to]` of `text`.
    fn piecewise(
        &mut self,
        text: &str,
        chars: &[char],
        from: usize,
        to: usize,
    ) -> Result<Id, Error> {
        let mut outer: Vec<char> = chars[from..to].to_vec();
        let mut placeholders: HashMap<String, Id> = HashMap::new();
        let mut i = from;
        while i < to {
            let starts_word = i == from || !is_name_char(chars[i - 1]);
            if starts_word && chars[i] == 'i' && chars.get(i + 1) == Some(&'f') {
                let mut open = i + 2;
                while open < to && chars[open].is_whitespace() {
                    open += 1;
                }
                if open < to
                    && chars[open] == '('
                    && !chars.get(i + 2).is_some_and(|&c| is_name_char(c))
                {
                    let close = matching(text, chars, open, to)?;
                    let select = self.select_at(text, chars, i, open, close)?;
                    let width = close + 1 - i;
                    let name = placeholder(placeholders.len(), width);
                    outer.splice(i - from..close + 1 - from, name.chars());
                    placeholders.insert(name, select);
                    i = close + 1;
                    continue;
                }
            }
            i += 1;
        }
        let outer: String = outer.into_iter().collect();
        let parsed = self
            .parse_infix(&outer)
            .map_err(|e| relocate(e, text, from))?;
        Ok(self.substitute(parsed, &placeholders))
    }

    /// The select node of `if(…)` at `start`, its parentheses at `open` and `close`.
    fn select_at(
        &mut self,
        text: &str,
        chars: &[char],
        start: usize,
        open: usize,
        close: usize,
    ) -> Result<Id, Error> {
        let arguments = split_top_level(chars, open + 1, close, ',');
        if arguments.len() != 3 {
            return Err(Error::formula(
                text,
                start,
                format!(
                    "`if` takes three arguments, `if(a < b, then, otherwise)`; found {}",
                    arguments.len()
                ),
            ));
        }
        let (c0, c1) = arguments[0];
        let Some((at, op, cmp)) = find_comparison(chars, c0, c1) else {
            return Err(Error::formula(
                text,
                c0,
                "`if` needs a condition comparing two values, like `x < pi/2` (<, <=, >, >=, ==, !=)",
            ));
        };
        let a = self.piecewise(text, chars, c0, at)?;
        let b = self.piecewise(text, chars, at + op.len(), c1)?;
        let then = self.piecewise(text, chars, arguments[1].0, arguments[1].1)?;
        let otherwise = self.piecewise(text, chars, arguments[2].0, arguments[2].1)?;
        Ok(self.select(cmp, a, b, then, otherwise))
    }

    /// `root` with the placeholder symbols replaced, rebuilt with the simplifying
    /// constructors.
    fn substitute(&mut self, root: Id, placeholders: &HashMap<String, Id>) -> Id {
        if placeholders.is_empty() {
            return root;
        }
        let needed = self.reachable(&[root]);
        let mut map: HashMap<Id, Id> = HashMap::new();
        for (index, _) in needed
            .iter()
            .enumerate()
            .take(root.index() + 1)
            .filter(|(_, n)| **n)
        {
            let id = Id::at(index);
            let node = self.node(id).clone();
            let m = |x: &Id| map[x];
            let new = match &node {
                Node::Sym(name) => placeholders.get(name.as_ref()).copied().unwrap_or(id),
                Node::Num(_) => id,
                Node::Unary(op, a) => self.unary(*op, m(a)),
                Node::Binary(op, a, b) => self.binary(*op, m(a), m(b)),
                Node::Powi(a, n) => self.powi(m(a), *n),
                Node::Select(cmp, [a, b, t, e]) => self.select(*cmp, m(a), m(b), m(t), m(e)),
            };
            map.insert(id, new);
        }
        map[&root]
    }
}

fn is_name_char(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// A symbol name of exactly `width` characters (at least 5: `if(…)` is never shorter).
fn placeholder(k: usize, width: usize) -> String {
    let mut name = format!("__if{k}");
    while name.chars().count() < width {
        name.push('_');
    }
    name
}

/// The index of the `)` that closes the `(` at `open`.
fn matching(text: &str, chars: &[char], open: usize, to: usize) -> Result<usize, Error> {
    let mut depth = 0usize;
    for (i, &c) in chars.iter().enumerate().take(to).skip(open) {
        match c {
            '(' => depth += 1,
            ')' => {
                depth -= 1;
                if depth == 0 {
                    return Ok(i);
                }
            }
            _ => {}
        }
    }
    Err(Error::formula(
        text,
        open,
        "this `(` of `if` is never closed",
    ))
}

/// The ranges of `chars[from..to]` between top-level `separator`s.
fn split_top_level(chars: &[char], from: usize, to: usize, separator: char) -> Vec<(usize, usize)> {
    let mut parts = Vec::new();
    let (mut depth, mut start) = (0i32, from);
    for (i, &c) in chars.iter().enumerate().take(to).skip(from) {
        match c {
            '(' => depth += 1,
            ')' => depth -= 1,
            c if c == separator && depth == 0 => {
                parts.push((start, i));
                start = i + 1;
            }
            _ => {}
        }
    }
    parts.push((start, to));
    parts
}

/// The first top-level comparison operator in `chars[from..to]`.
fn find_comparison(
    chars: &[char],
    from: usize,
    to: usize,
) -> Option<(usize, &'static str, Comparison)> {
    let mut depth = 0i32;
    for (i, &c) in chars.iter().enumerate().take(to).skip(from) {
        match c {
            '(' => depth += 1,
            ')' => depth -= 1,
            _ if depth == 0 => {
                for (op, cmp) in COMPARISONS {
                    let fits = op
                        .chars()
                        .enumerate()
                        .all(|(k, c)| i + k < to && chars[i + k] == c);
                    if fits {
                        return Some((i, op, cmp));
                    }
                }
            }
            _ => {}
        }
    }
    None
}

/// An error in a piece, moved to its place in the whole text.
fn relocate(error: Error, text: &str, offset: usize) -> Error {
    match error {
        Error::Formula {
            position, message, ..
        } => Error::formula(text, position + offset, message),
        other => other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The s-expression of a parsed piecewise formula, nested `if`s included.
    #[test]
    fn nested_ifs_become_select_nodes() {
        let mut graph = Graph::new();
        let f = graph
            .parse_infix_piecewise("if(x < 1, x, if(x >= 2, 4, x^2))")
            .unwrap();
        assert_eq!(
            graph.to_sexpr(f),
            "(if (< x 1) x (if (>= x 2) 4 (powi x 2)))"
        );
    }

    /// A name that starts with `if` is a name; a formula without `if` parses as before.
    #[test]
    fn names_starting_with_if_are_names() {
        let mut graph = Graph::new();
        let f = graph.parse_infix_piecewise("iffy + sin(x)").unwrap();
        let g = graph.parse_infix("iffy + sin(x)").unwrap();
        assert_eq!(f, g);
    }

    /// Errors point at the place in the whole text: a missing comparison, two arguments, an
    /// error inside a branch.
    #[test]
    fn errors_point_into_the_whole_formula() {
        let mut graph = Graph::new();
        let position = |graph: &mut Graph, text: &str| match graph.parse_infix_piecewise(text) {
            Err(Error::Formula {
                position, input, ..
            }) => {
                assert_eq!(input, text);
                position
            }
            other => panic!("{other:?}"),
        };
        assert_eq!(position(&mut graph, "1 + if(x, 1, 2)"), 7);
        assert_eq!(position(&mut graph, "1 + if(x < 1, 2)"), 4);
        assert_eq!(position(&mut graph, "if(x < 1, 2 +* x, 3)"), 13);
        assert_eq!(position(&mut graph, "if(x < 1, 2, 3) +* 2"), 17);
    }
}
