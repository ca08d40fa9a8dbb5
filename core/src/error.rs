//! The errors of mechdiff-core.

use thiserror::Error;

/// Everything that can go wrong in mechdiff-core.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum Error {
    /// A sweep over the drive variable is not a finite, non-empty range with a positive step.
    #[error("invalid sweep from {start} to {end} with step {step}: {reason}")]
    InvalidSweep {
        /// First drive position.
        start: f64,
        /// Last drive position.
        end: f64,
        /// Step between drive positions.
        step: f64,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// A computed quantity is NaN or infinite at a drive position where it should be finite.
    #[error("{quantity} is not finite at drive position φ = {phi}")]
    NonFinite {
        /// The drive position.
        phi: f64,
        /// Which quantity.
        quantity: &'static str,
    },
    /// A formula (s-expression or infix) is malformed; `position` is the character offset of
    /// the problem in `input`.
    #[error("{}", show_position(input, *position, message))]
    Formula {
        /// The formula as given.
        input: String,
        /// Character offset (0-based) of the problem.
        position: usize,
        /// What is wrong there.
        message: String,
    },
    /// A symbolic evaluation needs the value of a symbol that was not given.
    #[error("no value given for `{symbol}`")]
    UnboundSymbol {
        /// The symbol without a value.
        symbol: String,
    },
    /// A decimal string is not a number.
    #[error("`{text}` is not a decimal number")]
    BadDecimal {
        /// The string as given.
        text: String,
    },
    /// Emitted Rust did not parse back (a bug in the emitter).
    #[error("emitted Rust is not valid: {reason}")]
    InvalidEmittedRust {
        /// The parser's message.
        reason: String,
    },
}

/// `message` followed by the input with a caret under character `position`.
fn show_position(input: &str, position: usize, message: &str) -> String {
    let column = position + 1;
    format!("{message} (column {column})\n  {input}\n  {:>column$}", "^")
}

impl Error {
    /// A formula error at character `position` of `input`.
    pub(crate) fn formula(input: &str, position: usize, message: impl Into<String>) -> Self {
        Error::Formula {
            input: input.to_owned(),
            position,
            message: message.into(),
        }
    }
}

/// The result type of mechdiff-core.
pub type Result<T, E = Error> = std::result::Result<T, E>;
