//! The machine in motion under its motor: the motor's characteristic and `[simulate]`.
//!
//! A scene with `[simulate]` is not swept at a prescribed speed: its speed follows from the
//! reduced equation of motion ([`mechdiff_core::machine`]),
//!
//! `J(φ)·φ̈ + ½·J′(φ)·φ̇² = M_motor(φ̇/τ)/τ − M_res(φ, φ̇)`, `J = J_d/τ² + J_m(φ) + J_f`,
//!
//! with exactly the effects the scene gives (masses, gravity, loads with their active
//! ranges, friction, efficiencies, the motor behind its gearbox, a flywheel). The motor's
//! torque `M_motor` is the characteristic's, on the motor shaft; the kinetostatic drive
//! torque `M_drive` of `[[dynamics]] drive_torque` is the torque the drive joint applies to
//! the mechanism: it leaves out the rotor's own inertia torque `J_d·φ̈/τ` and the gearbox, so
//! that `M_motor = J_d·φ̈/τ + τ·f·(M_drive + J_f·φ̈)` (`f = 1/η` while power flows to the
//! mechanism, `η` while it flows back), and at constant speed without losses
//! `M_motor = τ·M_drive`.
//!
//! ```toml
//! [motor]                      # the gearbox as for [[dynamics]], and the characteristic
//! rotor_inertia = 0.01         # kg·m²
//! ratio = 0.0666666666666667   # drive speed / motor speed
//! efficiency = 0.95
//! characteristic = { type = "induction", synchronous_speed = 1500, breakdown_torque = 60,
//!                    breakdown_slip = 0.25 }   # speeds in the angular_velocity unit
//! # or { type = "constant", torque = 20 }, { type = "linear", stall_torque = 40,
//! # no_load_speed = 3000 }, { type = "table", speeds = [0, 1000, 1500], torques = [30, 25, 0] }
//!
//! [simulate]
//! find = ["start_up", "steady_state", "coast_down", "flywheel"]
//! start = 0                    # drive position of the start from rest (drive unit)
//! speed = 95                   # start-up until this drive speed (default 0.95 × no-load)
//! time = 60                    # s: the longest start-up or coast-down
//! turns = 200                  # the most turns of the steady-state search
//! flywheel = 0                 # on the drive shaft (moment-of-inertia unit)
//! delta = 0.02                 # "flywheel": the δ to size it for
//! mean_speed = "time"          # or "mid_range": the mean speed of δ
//! tolerance = 1e-10            # relative and absolute, per step
//! max_steps = 1000000          # per run
//! ```

mod curves;
mod equation;
mod format;
mod model;
pub mod playback;
mod resolve;
pub mod run;
mod words;

pub use curves::{CURVE_POINTS, Curves, Thinned};
pub use equation::describe;
pub use format::{CharacteristicDef, CharacteristicKind, Find, MeanSpeedDef, SimulateDef};
pub use model::SceneMotion;
pub use playback::{PLAYBACK_FRAMES, Part, Playback};
pub(crate) use resolve::resolve;
pub use resolve::{LARGEST_TOLERANCE, MAX_STEPS, MAX_TIME, MAX_TURNS, SMALLEST_TOLERANCE};
pub use run::{MotionOptions, MotionReport, run, run_with};
