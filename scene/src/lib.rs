//! # mechdiff-scene
//!
//! The reading side of mechdiff's scene files, in a crate of its own so that what only reads
//! a scene (the `mechdiff_scene!` proc-macro, a library user) compiles neither the command
//! line nor the runner. A scene is read in layers, each naming only the ones below it:
//!
//! - [`units`]: the units a file declares (`[units]`) and their conversion to and from SI;
//!   [`limits`]: the range of every number in SI;
//! - [`bindings`] and [`scalar`]: the evaluated `[parameters]` and the scalar (`f64`, or
//!   `Dual64` with a derivative) the numbers are resolved in;
//! - [`values`]: numbers and names as written (a literal or a formula with its span), and
//!   the formulas' parser;
//! - [`quantity`]: words of the file that the checked scene keeps (what an output reports);
//! - [`construct`]: the ruler-and-compass constructions that place sketch points.
//!
//! The file format, the parameters' evaluation, the resolver and the checked scene are still
//! in the facade (`mechdiff::scene`), which re-exports these modules under their old paths.

pub mod bindings;
pub mod construct;
pub mod limits;
pub mod quantity;
pub mod scalar;
pub mod units;
pub mod values;
