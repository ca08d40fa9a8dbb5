//! The text of a scene file, for turning byte spans into `file:line:column`.

use std::ops::Range;
use std::sync::{Arc, OnceLock};

use super::dimension::ParameterDimensions;

use crate::error::{Error, Location};

/// A scene file's name and text, with an index of its lines so that a place is found in
/// time logarithmic in the file's length (a scene of 10⁵ names is located 10⁵ times).
#[derive(Debug, Clone)]
pub struct Source {
    /// The name printed in messages (the path as given, or `<string>`).
    pub file: String,
    /// The whole text.
    pub text: String,
    /// The name as messages share it.
    shared_file: Arc<str>,
    /// Each line's first byte, and whether the line is ASCII (its columns are bytes).
    lines: Vec<(usize, bool)>,
    /// The dimensions of the parameters written with a unit of their own and of those
    /// defined by formulas of them.
    parameter_dimensions: OnceLock<ParameterDimensions>,
}

impl Source {
    /// Wraps a file's name and text.
    pub fn new(file: impl Into<String>, text: impl Into<String>) -> Self {
        let (file, text) = (file.into(), text.into());
        let mut lines = Vec::new();
        let mut start = 0;
        for line in text.split_inclusive('\n') {
            lines.push((start, line.is_ascii()));
            start += line.len();
        }
        if lines.is_empty() || text.ends_with('\n') {
            lines.push((text.len(), true));
        }
        Source {
            shared_file: file.as_str().into(),
            file,
            text,
            lines,
            parameter_dimensions: OnceLock::new(),
        }
    }

    /// Records the dimensions of the parameters (by the reader of `[parameters]`; the first
    /// record stands).
    pub(crate) fn set_parameter_dimensions(&self, dimensions: ParameterDimensions) {
        let _ = self.parameter_dimensions.set(dimensions);
    }

    /// The dimensions of the parameters, once `[parameters]` is read.
    pub(crate) fn parameter_dimensions(&self) -> Option<&ParameterDimensions> {
        self.parameter_dimensions.get()
    }

    /// The line and column (1-based, columns in characters) where byte `span.start` is.
    pub fn location(&self, span: Range<usize>) -> Location {
        let start = floor_char_boundary(&self.text, span.start.min(self.text.len()));
        let line = self.lines.partition_point(|&(first, _)| first <= start);
        let (line_start, ascii) = self.lines[line - 1];
        let column = if ascii {
            start - line_start
        } else {
            self.text[line_start..start].chars().count()
        } + 1;
        Location {
            file: Arc::clone(&self.shared_file),
            line,
            column,
        }
    }

    /// The place of an error inside a quoted formula: the message's "(column N of the
    /// formula)" counted from the opening quote, when the string is written plainly (no
    /// escapes); otherwise `span` itself.
    pub(crate) fn inside_formula(&self, span: Range<usize>, message: &str) -> Range<usize> {
        const MARK: &str = "(column ";
        let column = message
            .find(MARK)
            .map(|i| &message[i + MARK.len()..])
            .filter(|rest| rest.contains(" of the formula)"))
            .and_then(|rest| rest.split(' ').next())
            .and_then(|n| n.parse::<usize>().ok());
        let quoted = self.text.get(span.clone()).filter(|t| {
            t.len() >= 2 && t.starts_with('"') && t.ends_with('"') && !t.contains('\\')
        });
        match (column, quoted) {
            (Some(column), Some(quoted)) => {
                let inner = &quoted[1..quoted.len() - 1];
                match inner.char_indices().nth(column.saturating_sub(1)) {
                    Some((offset, _)) => {
                        let at = span.start + 1 + offset;
                        at..at + 1
                    }
                    None => span,
                }
            }
            _ => span,
        }
    }

    /// The error of the formula at `span` that cannot be read or evaluated (`message` says
    /// why): at the column inside the formula the message names, else at the formula, as a
    /// [`Error::Syntax`] like a value the format does not take.
    pub(crate) fn formula_error(&self, span: Range<usize>, message: &str) -> Error {
        Error::Syntax {
            location: self.location(self.inside_formula(span, message)),
            message: tidy_toml_message(message),
        }
    }

    /// Turns a TOML parse or deserialisation error into [`Error::Syntax`] at its place.
    pub fn syntax_error(&self, error: &toml::de::Error) -> Error {
        let location = match error.span() {
            Some(span) => self.location(self.inside_formula(span, error.message())),
            None => Location {
                file: self.file.as_str().into(),
                line: 1,
                column: 1,
            },
        };
        let mut message = tidy_toml_message(error.message());
        // A missing top-level section is reported for the whole document (no span, or one
        // starting at byte 0).
        let top_level = error.span().is_none_or(|s| s.start == 0);
        if top_level && message.starts_with("missing field") {
            message.push_str(
                "; a scene file needs the sections `[points]`, `[links]`, `[joints]`, `[drive]` \
                 and `[sweep]`",
            );
        }
        if message.starts_with("duplicate key")
            && let Some(span) = error.span()
        {
            return self.duplicate_key(span, location);
        }
        if let Some(span) = error.span()
            && let Some(hint) = self
                .dotted_key(span.start)
                .or_else(|| self.formula(span.start))
        {
            message = hint;
        }
        Error::Syntax { location, message }
    }

    /// The line holding byte `at`, and `at`'s offset in it.
    fn line_at(&self, at: usize) -> (&str, usize) {
        let at = floor_char_boundary(&self.text, at.min(self.text.len()));
        let start = self.text[..at].rfind('\n').map_or(0, |i| i + 1);
        let end = self.text[at..]
            .find('\n')
            .map_or(self.text.len(), |i| at + i);
        (&self.text[start..end], at - start)
    }

    /// An error on a line `CoM.AB = …`: TOML read the dotted key as a table `CoM` with a key
    /// `AB`, whatever the error that followed; say so, and how to quote the name.
    fn dotted_key(&self, at: usize) -> Option<String> {
        let (line, _) = self.line_at(at);
        let (key, value) = line.split_once('=')?;
        let key = key.trim();
        let bare = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == '-' || c == '.';
        if !key.contains('.') || !key.chars().all(bare) {
            return None;
        }
        let (table, rest) = key.split_once('.')?;
        Some(format!(
            "`{key} = …` is a dotted key: TOML reads it as a table `{table}` holding the key \
             `{rest}`, not as one name `{key}`; a name with a dot must be quoted: \
             `\"{key}\" = {}`",
            value.split('#').next().unwrap_or("").trim()
        ))
    }

    /// An error inside an unquoted formula (`mass = 23.4791*0.86`): say that a formula must
    /// be a quoted string.
    fn formula(&self, at: usize) -> Option<String> {
        let (line, column) = self.line_at(at);
        let is_start = |c: char| matches!(c, '=' | '[' | ',' | '{');
        let start = line[..column].rfind(is_start).map_or(0, |i| i + 1);
        let mut depth = 0i32;
        let mut end = line.len();
        for (i, c) in line[start..].char_indices() {
            match c {
                '(' => depth += 1,
                ')' if depth > 0 => depth -= 1,
                ',' | ']' | '}' | '#' | ')' if depth == 0 => {
                    end = start + i;
                    break;
                }
                _ => {}
            }
        }
        let text = line.get(start..end)?.trim();
        let operator = text.char_indices().any(|(i, c)| {
            matches!(c, '*' | '/' | '^' | '(')
                || (matches!(c, '+' | '-') && i > 0 && !text[..i].ends_with(['e', 'E']))
        });
        if !operator || !text.chars().any(|c| c.is_ascii_digit()) || text.contains(['"', '\'']) {
            return None;
        }
        Some(format!(
            "`{text}` is a formula, and TOML reads a formula only as a quoted string: write \
             `\"{text}\"` (a constant formula in quotes is accepted wherever a number is: \
             numbers, + - * / ^, parentheses, sqrt, sin, cos, atan2, pi)"
        ))
    }

    /// toml says only "duplicate key": name the key and its table, and treat a point defined
    /// twice as [`Error::DuplicatePoint`].
    fn duplicate_key(&self, span: Range<usize>, location: Location) -> Error {
        let key = self
            .text
            .get(span.clone())
            .unwrap_or("")
            .trim()
            .trim_matches('"')
            .to_owned();
        let table = self.text[..span.start.min(self.text.len())]
            .lines()
            .rev()
            .map(str::trim)
            .find(|l| l.starts_with('['))
            .map(|l| l.split('#').next().unwrap_or(l).trim().to_owned());
        match table.as_deref() {
            Some("[points]") => Error::DuplicatePoint {
                location,
                name: key,
                context: "`[points]`".to_owned(),
            },
            Some(table) => Error::Syntax {
                location,
                message: format!("duplicate key `{key}` in `{table}`; each key may appear once"),
            },
            None => Error::Syntax {
                location,
                message: format!("duplicate key `{key}`; each key may appear once"),
            },
        }
    }
}

fn floor_char_boundary(text: &str, mut index: usize) -> usize {
    while !text.is_char_boundary(index) {
        index -= 1;
    }
    index
}

/// toml's messages end with a newline and sometimes say "TOML parse error"; keep one line.
fn tidy_toml_message(message: &str) -> String {
    message
        .trim()
        .replace('\n', "; ")
        .replace("unknown variant", "unknown value")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spans_become_one_based_lines_and_columns() {
        let source = Source::new("a.toml", "x = 1\n[units]\n  length = \"ft\"\n");
        let at = source.text.find("\"ft\"").unwrap();
        let location = source.location(at..at + 4);
        assert_eq!((location.line, location.column), (3, 12));
        assert_eq!(location.to_string(), "a.toml:3:12");
    }

    #[test]
    fn the_line_index_agrees_with_counting_newlines_at_every_byte() {
        let text = "a = 1\n\n# ψ″ = 2\r\nb = \"ψ\"\nlast";
        let source = Source::new("a.toml", text);
        for at in (0..=text.len()).filter(|&i| text.is_char_boundary(i)) {
            let before = &text[..at];
            let line_start = before.rfind('\n').map_or(0, |i| i + 1);
            let location = source.location(at..at);
            assert_eq!(location.line, before.matches('\n').count() + 1, "byte {at}");
            assert_eq!(
                location.column,
                before[line_start..].chars().count() + 1,
                "byte {at}"
            );
        }
    }

    #[test]
    fn columns_count_characters_not_bytes() {
        let source = Source::new("a.toml", "# ψ″\nψ = 1");
        let at = source.text.rfind('=').unwrap();
        assert_eq!(source.location(at..at + 1).column, 3);
    }
}
