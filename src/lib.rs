//! # mechdiff
//!
//! Kinematics and dynamics of planar mechanisms in which nobody derives a derivative by hand.
//! This facade re-exports the derivative core ([`core`]), the closed-form mechanisms
//! ([`mechanisms`]) and the [`derivatives`] attribute, and holds what the `mechdiff`
//! command-line tool does: scene files ([`scene`]), reports ([`report`]), code generation
//! ([`codegen`]) and the care of the user's files ([`files`]).

pub mod accuracy;
pub mod codegen;

pub use mechdiff_core as core;
pub use mechdiff_mechanisms as mechanisms;

/// Symbolic derivatives generated at compile time (see `mechdiff_macros::derivatives`). The
/// generated code names `::mechdiff_core::Jet`, so the calling crate depends on
/// `mechdiff-core` as well.
pub use mechdiff_macros::derivatives;

pub mod error;
pub mod escape;
pub mod evaluator;
pub mod files;
pub mod import;
pub mod pictures;
pub mod report;
pub mod scene;
pub mod sensitivity;
pub mod stream;

pub use error::{Error, Result};

/// The Rust examples of `README.md`, compiled and run as doc-tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
