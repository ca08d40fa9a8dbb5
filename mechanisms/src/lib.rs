//! # mechdiff-mechanisms
//!
//! Concrete planar mechanisms with closed-form position functions and the formulas derived by
//! hand in their source texts: one mechanism per module, each verified against its reference.
//!
//! | module | mechanism |
//! |---|---|
//! | [`whitworth`] | Whitworth shaping machine: crank, slotted rocker, ram (inertial forces on the frame) |

pub mod error;
pub mod whitworth;

pub use error::{Error, Result};
pub use whitworth::Whitworth;
