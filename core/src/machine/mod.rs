//! The machine in motion under its motor: the reduced equation of motion of a mechanism with
//! one degree of freedom, integrated with error control.
//!
//! A real machine does not turn at a prescribed speed: its speed follows from its varying
//! reduced inertia, its loads and its motor's characteristic,
//!
//! `J(φ)·φ̈ + ½·J′(φ)·φ̇² = M_motor(φ̇/τ)/τ − M_res(φ, φ̇)`,
//!
//! with `J(φ)` and `J′(φ)` exact from the mechanism's velocity and acceleration coefficients
//! ([`energy`](mod@crate::dynamics::energy)) and the right-hand side the mechanism's kinetostatics
//! ([`crate::dynamics::kinetostatics`]) with exactly the effects asked for (see [`equation`]
//! for the relation between `M_motor` and the kinetostatic `M_drive`).
//!
//! - [`Characteristic`]: constant torque, linear (DC shunt), induction motor (Kloss), table;
//! - [`Machine`]: a compiled model, its effects, a characteristic and a flywheel;
//!   [`Machine::state`] gives φ̈ at a state;
//! - [`simulate`]: the motion in time, load switches, turns, a speed and rest located as
//!   events, records streamed to a sink; [`start_up`], [`coast_down`];
//! - [`steady_state`]: the periodic state by shooting in the energy form (`E = ½Jφ̇²`
//!   integrated over φ), with ω(φ), t(φ), the period, ω_min, ω_max and δ;
//! - [`flywheel()`]: the flywheel for a requested δ, exactly and by the classic energy method.
//!
//! Integration: DOP853 (order 8, dense output of order 7) of the `differential-equations`
//! crate, behind the `simulate` feature.
//!
//! ```
//! use mechdiff_core::dynamics::{Dynamics, Effects};
//! use mechdiff_core::geometry::{Drive, Inertia, Mechanism};
//! use mechdiff_core::machine::{Characteristic, Machine, Start, Stop, Tolerances, simulate_collect};
//! // A crank of 1 kg at 0.5 m (J = 0.25 kg·m² about O) under a constant torque of 0.5 N·m:
//! // φ̈ = 2 rad/s², so after 1 s φ̇ = 2 rad/s.
//! let m = Mechanism::builder()
//!     .point("O", [0.0, 0.0]).point("A", [1.0, 0.0])
//!     .ground(["O"]).link("crank", ["O", "A"])
//!     .inertia("crank", Inertia { mass: 1.0, center: [0.5, 0.0], moment: 0.0 })
//!     .revolute("O", "ground", "crank", "O")
//!     .drive(Drive::angle("O"))
//!     .build().unwrap();
//! let model = Dynamics::new().compile(&m).unwrap();
//! let machine = Machine::new(&model, Effects { inertia: true, ..Effects::none() })
//!     .with_motor(Characteristic::ConstantTorque { torque: 0.5 });
//! let stop = Stop { time: Some(1.0), ..Stop::default() };
//! let (run, _) = simulate_collect(&machine, Default::default(), &stop, &Tolerances::default()).unwrap();
//! assert!((run.end.omega - 2.0).abs() < 1e-9 && (run.end.phi - 1.0).abs() < 1e-9);
//! ```

pub mod angle;
pub mod characteristic;
pub mod equation;
pub mod error;
pub mod flywheel;
pub mod integrate;
pub mod steady;
pub mod time;
pub mod transient;

pub use angle::{AngleSample, Extremes};
pub use characteristic::{Characteristic, TorqueTable};
pub use equation::{Machine, MachineState};
pub use error::MotionError;
pub use flywheel::{FlywheelSizing, MeanSpeed, flywheel};
pub use integrate::Tolerances;
pub use steady::{InTimeCheck, SteadySettings, SteadyState, steady_state};
pub use time::{
    Event, EventKind, Record, Sample, Simulation, Start, Stop, StopReason, simulate,
    simulate_collect,
};
pub use transient::{CoastDown, StartUp, coast_down, start_up};
