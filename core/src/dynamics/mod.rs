//! Dynamics of geometry-defined mechanisms: the forces the accelerations cause, with exactly
//! the effects asked for.
//!
//! Each effect is a small independent piece ([`inertia`], [`gravity`], [`loads`],
//! [`friction`], [`efficiency`], [`motor`]); [`kinetostatics`] assembles the equilibrium
//! equations of every moving link (Newton–Euler with d'Alembert's inertial loads) and solves
//! them for the joint reactions and the drive torque at one drive position; [`energy`](mod@energy) checks
//! the result against the power balance and gives the kinetic energy and the reduced moment of
//! inertia; [`shaking`] sums the inertial forces on the frame; [`tangent`] gives the exact
//! derivative of every result with respect to one parameter, through the same
//! (scalar-generic) effect code. A [`Plan`] (see [`plan`]) says
//! which derivative order and which effects the requested outputs need, and nothing else is
//! evaluated (the [`Trace`] of a solution counts every effect evaluation).
//!
//! ## Formulation
//!
//! With the pose coordinates `q` of the geometry model (`x, y, θ` per moving link) and the
//! square constraint Jacobian `Φ_q` (joint equations plus the drive row), the equilibrium of
//! every link is `Φ_qᵀ λ = Q`, where `Q` holds the generalized applied and inertial loads
//! (a force `F` at point `P` of link `k` contributes `(F_x, F_y, (P − r_k) × F)` to link `k`'s
//! three rows). The multipliers `λ` are the joint reactions, one per constraint equation
//! (revolute: the force of link a on link b; prismatic: the couple and the normal force;
//! pin in slot: the normal force; rack-and-pinion and gear: the tooth force or torque; rigid:
//! force and couple), and the drive row's multiplier is minus the drive torque (or force).
//! One LU of `Φ_qᵀ` per drive position; friction and efficiency make some columns depend on
//! the signs of the reactions and the direction of power flow, resolved by iteration
//! ([`kinetostatics`]).
//!
//! ```
//! use mechdiff_core::DriveState;
//! use mechdiff_core::dynamics::{Dynamics, Effects, Gravity, Plan, Request, kinetostatics};
//! use mechdiff_core::geometry::{Drive, Inertia, Mechanism, Solver};
//! // A crank of 1 kg with its centre of gravity at 0.5 m, held horizontal against gravity.
//! let m = Mechanism::builder()
//!     .point("O", [0.0, 0.0]).point("A", [1.0, 0.0])
//!     .ground(["O"]).link("crank", ["O", "A"])
//!     .inertia("crank", Inertia { mass: 1.0, center: [0.5, 0.0], moment: 0.0 })
//!     .revolute("O", "ground", "crank", "O")
//!     .drive(Drive::angle("O"))
//!     .build().unwrap();
//! let dynamics = Dynamics::new().with_gravity(Gravity::down(9.81));
//! let plan = Plan::for_requests(&[Request::DriveTorque], dynamics.available(&m));
//! assert_eq!(plan.effects, Effects { gravity: true, inertia: true, ..Effects::none() });
//! let model = dynamics.compile(&m).unwrap();
//! let k = Solver::default().track(&m).unwrap().kinematics::<2>().unwrap();
//! let s = kinetostatics::solve(&model, &plan.effects, &k, &DriveState::constant_speed(0.0)).unwrap();
//! assert!((s.drive_torque - 9.81 * 0.5).abs() < 1e-12); // holds the weight's moment
//! ```

pub mod efficiency;
pub mod energy;
mod equilibrium;
pub mod friction;
pub mod gravity;
pub mod inertia;
pub mod kinetostatics;
pub mod loads;
mod model;
pub mod motor;
pub mod plan;
pub mod run;
pub mod shaking;
mod solution;
pub(crate) mod state;
pub mod tangent;
mod teeth;

pub use efficiency::{Driving, Efficiency};
pub use energy::Energy;
pub use energy::energy;
pub use friction::Friction;
pub use gravity::Gravity;
pub use inertia::InertialLoad;
pub use loads::{Load, LoadKind};
pub use model::{CompiledModel, Dynamics};
pub use motor::{Motor, MotorState};
pub use plan::{Effects, Plan, Request, Trace};
pub use shaking::{Extreme, ShakingForce, ShakingSummary, shaking_force};
pub use solution::{JointReaction, PowerBalance, Solution};
pub use state::LinkState;
pub use tangent::{
    EffectsTangent, ModelTangent, NotCarried, SolutionTangent, TangentError, carried,
};
