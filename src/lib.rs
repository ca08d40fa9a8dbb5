//! # mechdiff
//!
//! Kinematics and dynamics of planar mechanisms in which nobody derives a derivative by hand.
//! This facade re-exports the derivative core ([`core`]) and the closed-form mechanisms
//! ([`mechanisms`]), and holds what the `mechdiff` command-line tool prints.
#![warn(missing_docs)]

pub use mechdiff_core as core;
pub use mechdiff_mechanisms as mechanisms;

pub mod error;
pub mod report;
pub mod scene;

pub use error::{Error, Result};

/// The Rust examples of `README.md`, compiled and run as doc-tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
