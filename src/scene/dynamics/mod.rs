//! The dynamic part of a scene: masses, gravity, loads, friction, efficiencies, a motor, and
//! the `[[dynamics]]` outputs that need them (forces, reactions, drive torque, energy,
//! shaking force).
//!
//! ```toml
//! [masses]                     # kg, centre (point of the link, or [x, y] in the length
//! rocker = { mass = 30, center = "S2", inertia = 1.2 }   # unit), kg·m² about the centre
//! [gravity]
//! g = 9.81                     # m/s², along −y
//! [[load]]                     # a force (N) at a point of a link, or a torque (N·m)
//! link = "ram"
//! point = "C"
//! force = [-2000, 0]
//! active = [292.024, 67.976]   # optional: only for drive positions in this range
//! [friction]                   # per joint: Coulomb coefficient; revolute: pin_radius
//! slot = { coefficient = 0.15 }
//! [efficiency]                 # per rack-and-pinion or gear joint, in (0, 1]
//! mesh = { efficiency = 0.95 } # driving = "first" (pinion, first gear; default) | "second"
//! [motor]                      # at the drive joint: rotor inertia behind a gear ratio
//! rotor_inertia = 0.002        # kg·m²; ratio = drive speed / motor speed
//! ratio = 0.0333333333333333
//! efficiency = 0.9
//! [[dynamics]]
//! output = "drive_torque"      # shaking_force | inertial_forces | reactions | drive_torque
//!                              # | kinetic_energy | reduced_inertia | power_balance
//! ```
//!
//! From the `[[dynamics]]` outputs mechdiff derives a [`Plan`](mechdiff_core::dynamics::Plan): the derivative order and the
//! effects needed; effects whose data is given but which no output needs are not computed.

mod format;
mod model;
mod resolve;
mod run;
mod tangent;

pub use format::{
    CenterDef, DrivingSide, DynamicQuantity, DynamicsOutputDef, DynamicsSections, EfficiencyDef,
    FrictionDef, GravityDef, LoadDef, MassDef, MotorDef,
};
pub use model::{DynamicsOutput, SceneDynamics};
pub(crate) use resolve::{numbers_in, resolve};
pub use run::DynamicsReport;
pub(crate) use run::{DynamicsSweep, before_solving, columns, error};
pub use tangent::{DynamicsTangent, column_derivatives};
