//! mechdiff-core: derivative machinery, geometry solver and dynamics of mechdiff.
#![warn(missing_docs)]

pub mod geometry;
