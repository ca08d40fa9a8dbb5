//! Cams: motion laws written once, cam programs, their discontinuities, and the geometry of
//! the cam and its follower.
//!
//! - [`law`]: the standard motion laws as one generic function each ([`MotionLaw`]);
//! - [`program`]: segments over one turn ([`CamProgram`]), s, s′, s″, s‴ at any cam angle;
//! - [`continuity`]: where a program's derivatives jump ([`ContinuityReport`]);
//! - [`peaks`]: the peak coefficients of a law (C_v, C_a, C_j);
//! - [`follower`] and [`profile`]: pitch curve, profile, pressure angle, curvature,
//!   undercutting; [`sizing`]: the smallest base circle;
//! - [`joint`]: a cam program as the drive of a linkage ([`CamJoint`]); [`travel`]: where
//!   the follower turns back between two cam angles, so that the linkage's proof of motion
//!   covers every displacement the cam passes.
//!
//! Angles are in radians, the cam turns counter-clockwise; the displacement is in the unit of
//! the lifts (a length for a translating follower, an angle in radians for an oscillating
//! one). ′ means d/dθ, θ the cam angle.

pub mod continuity;
pub mod extrema;
pub mod follower;
pub mod joint;
pub mod law;
pub mod peaks;
pub mod profile;
pub mod program;
pub mod sizing;
pub mod travel;

pub use continuity::{Boundary, BoundaryKind, ContinuityReport};
pub use follower::{Dimensions, Follower};
pub use joint::{CamJoint, CamRun, CamStep};
pub use law::{MotionLaw, Side};
pub use peaks::PeakCoefficients;
pub use profile::{CamAnalysis, CamMechanism, Contact, Extreme};
pub use program::{CamProgram, Formula, Segment, SegmentMotion};
