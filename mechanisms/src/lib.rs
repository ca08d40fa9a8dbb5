//! # mechdiff-mechanisms
//!
//! Concrete planar mechanisms with closed-form position functions and the formulas derived by
//! hand in their source texts: one mechanism per module, each verified against its reference.
#![warn(missing_docs)]
