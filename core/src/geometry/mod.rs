//! Mechanisms defined by geometry only: points, links, joints and a drive.
//!
//! The model ([`Mechanism`], built with [`Mechanism::builder`]) is turned into constraint
//! equations Φ(q, φ) = 0 ([`Equations`], generic over the scalar type), checked for mobility
//! ([`check_mobility`]), solved for the pose at each drive position by Newton's method
//! keeping the sketch's assembly branch ([`Solver`]), and lifted to exact derivatives
//! q′, q″, q‴ with respect to φ by implicit differentiation ([`Kinematics`]), and the exact
//! derivatives of all of these with respect to a parameter of the data ([`Parametric`]).

mod block_lu;
pub mod branch;
mod builder;
pub(crate) mod closed_form;
pub(crate) mod constraints;
mod datum;
mod frames;
pub mod halving;
pub mod implicit;
mod kinematics;
pub(crate) mod length;
mod mobility;
mod model;
pub(crate) mod output;
pub mod parametric;
pub(crate) mod solver;
mod validate;

pub use builder::MechanismBuilder;
pub use constraints::Equations;
pub use kinematics::Kinematics;
pub use length::extent;
pub use mobility::{Mobility, check_mobility};
pub use model::{
    Drive, DriveKind, GROUND, Inertia, Joint, JointKind, Link, Mechanism, Point, uniform_bar_of,
};
pub use output::{PointOutput, ScalarOutput};
pub use parametric::{DataTangent, Parametric, ParametricPoint, ParametricScalar, PoseTangent};
pub use solver::{DriveLimit, LimitKind, MotionRange, PoseJets, SolveReport, Solver, Tracker};
