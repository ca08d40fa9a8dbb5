//! The balancing sections of a scene: a rotor to balance in one or two planes, and
//! counterweights to size for the linkage. The logic is in
//! [`mechdiff_core::balancing`]; this module only reads the sections, converts units and
//! prints the answers.
//!
//! A file with only a title, `[units]` and `[rotor]` is a rotor scene of its own
//! ([`rotor_scene`]): no linkage is needed to balance a rotor.
//!
//! ```toml
//! [rotor]                      # masses on a rigid shaft (independent of the linkage)
//! masses = [
//!   { mass = 0.5, radius = 150, angle = 0, plane = 300 },   # kg, length, angle, length
//!   { mass = 0.5, radius = 150, angle = 120, plane = 0 },
//! ]
//! planes = [0, 600]            # optional: two correction planes → dynamic balance
//! reference = 0                # plane of the couple polygon (default 0)
//! correction_radius = 100      # optional: radius of the correcting masses → their masses
//! couple_mass_radius = 0.075   # optional (kg m): where one mass of this m·r cancels the couple
//!
//! [balancing]                  # needs [masses] for every moving link and the drive speed
//! counterweights = [ { link = "crank", line = ["A0", "A"], radius = 0.1 } ]
//! slider_crank = { crank = "crank", rod = "rod", slider = "slider", fraction = 0.5 }
//! ```

mod answers;
mod format;
mod model;
mod resolve;
pub mod rotor_scene;
mod run;

pub use answers::RotorAnswers;
pub use format::{BalancingDef, CounterweightDef, RotorDef, RotorMassDef, SliderCrankDef};
pub use model::{SceneBalancing, SceneRotor, SceneSliderCrank};
pub(crate) use resolve::resolve;
pub use rotor_scene::RotorScene;
pub use run::BalancingReport;
pub(crate) use run::{BalancingSweep, before_solving, columns, report, rotor_lines};
