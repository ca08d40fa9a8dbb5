//! # mechdiff-core
//!
//! The derivative machinery of mechdiff: a mechanism's position equations are written once, as
//! a [`PositionFunction`] generic over the [`Scalar`] type, and their derivatives with respect
//! to the drive variable φ follow by any [`method`] — dual numbers (exact), central differences,
//! or formulas derived by hand — as [`Jet`]s. A [`DriveState`] turns them into velocities,
//! accelerations and jerks ([`Motion`]), of single coordinates or of [`Point`]s;
//! [`DeadPositionSearch`] finds where a coefficient changes sign. [`geometry`] derives, solves
//! and differentiates the equations of a mechanism given only as points, links, joints and a
//! drive.
//!
//! # Features
//!
//! The heavy parts are off by default, so that a user of the derivatives, the solver and
//! dynamics compiles num-dual, nalgebra and thiserror only:
//! - `jit`: the run-time evaluator compiled to native code (`trace::JitProgram`, cranelift);
//! - `emit`: expressions emitted as Rust tokens and formatted source (`symbolic::emit`: syn,
//!   quote, prettyplease), for the proc-macros and code generation;
//! - `big-float`: evaluation in arbitrary precision (`symbolic::bigfloat`, astro-float), the
//!   references accuracy is measured against;
//! - `simulate`: the machine in motion under its motor (`machine`: motor characteristics,
//!   the reduced equation of motion integrated with error control and events, start-up,
//!   steady state, flywheel sizing; differential-equations);
//! - `synthesis`: dimensions from what a linkage must do (`synthesis`: path, function and
//!   motion generation as least squares with exact Jacobians from dual numbers; fastrand).
#![cfg_attr(docsrs, feature(doc_cfg))]

pub mod balancing;
pub mod cams;
pub mod dead_position;
pub mod dynamics;
pub mod error;
pub mod geometry;
pub mod jet;
#[cfg(feature = "simulate")]
#[cfg_attr(docsrs, doc(cfg(feature = "simulate")))]
pub mod machine;
pub mod method;
pub mod metrics;
pub mod motion;
pub mod point;
pub mod position;
pub mod scalar;
pub mod sweep;
pub mod symbolic;
#[cfg(feature = "synthesis")]
#[cfg_attr(docsrs, doc(cfg(feature = "synthesis")))]
pub mod synthesis;
pub mod trace;

pub use dead_position::{DeadPosition, DeadPositionSearch};
pub use error::{Error, Result};
pub use jet::{Jet, JetDual};
pub use motion::{DriveState, Motion};
pub use num_dual;
pub use point::Point;
pub use position::PositionFunction;
pub use scalar::{Scalar, atan2, hypot, tanh};
