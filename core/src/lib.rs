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

pub mod balancing;
pub mod cams;
pub mod dead_position;
pub mod dynamics;
pub mod error;
pub mod geometry;
pub mod jet;
pub mod method;
pub mod motion;
pub mod point;
pub mod position;
pub mod scalar;
pub mod symbolic;

pub use dead_position::{DeadPosition, DeadPositionSearch};
pub use error::{Error, Result};
pub use jet::Jet;
pub use motion::{DriveState, Motion};
pub use num_dual;
pub use point::Point;
pub use position::PositionFunction;
pub use scalar::{Scalar, atan2, hypot, tanh};
