//! Errors of the symbolic engine.

/// What went wrong in parsing, differentiating, evaluating or emitting an expression.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SymbolicError {
    /// A formula (s-expression or infix) is malformed; `position` is the character offset
    /// of the problem in `input`.
    #[error("{}", show_position(input, *position, message))]
    Parse {
        /// The formula as given.
        input: String,
        /// Character offset (0-based) of the problem.
        position: usize,
        /// What is wrong there.
        message: String,
    },
    /// An evaluation needs the value of a symbol that was not given.
    #[error("no value given for `{symbol}`")]
    Unbound {
        /// The symbol without a value.
        symbol: String,
    },
    /// A decimal string is not a number.
    #[error("`{text}` is not a decimal number")]
    BadNumber {
        /// The string as given.
        text: String,
    },
    /// The emitted Rust did not parse back (a bug in the emitter).
    #[error("emitted Rust is not valid: {reason}")]
    Emit {
        /// The parser's message.
        reason: String,
    },
}

/// `message` followed by the input with a caret under character `position`.
fn show_position(input: &str, position: usize, message: &str) -> String {
    let column = position + 1;
    format!("{message} (column {column})\n  {input}\n  {:>column$}", "^")
}

impl SymbolicError {
    /// A parse error at character `position` of `input`.
    pub(crate) fn parse(input: &str, position: usize, message: impl Into<String>) -> Self {
        SymbolicError::Parse { input: input.to_owned(), position, message: message.into() }
    }
}
