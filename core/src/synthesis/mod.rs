//! Dimensional synthesis: from what a linkage must do to its dimensions, driven by exact
//! derivatives.
//!
//! A [`Problem`] names a [`Linkage`] (four-bar, slider-crank, Stephenson III six-bar), a
//! [`Task`] — path generation (a point through target points, with the drive angles given,
//! given up to a common offset, or free), function generation (an output angle or the
//! slider's displacement against the drive angle) or motion generation (a link's poses) —,
//! bounds on every design variable (link lengths, ground pivots, coupler points, free drive
//! angles), the assembly branch and [`Constraints`]. The objective is the sum of squared
//! residuals (m, rad; a pose's angle error weighed by a length).
//!
//! [`Synthesis::solve`] samples the bounds alone (a seeded Latin hypercube), ranks the
//! usable samples by their objective, and polishes the best ones by Levenberg–Marquardt in
//! the box with the **exact** Jacobian: the residuals are written once generic over the
//! scalar and evaluated in `Dual64` numbers, one pass per free variable (no difference
//! quotient; [`Derivatives::CentralDifferences`] is the baseline). Every candidate — sample
//! or trial step — is checked for defects ([`Defect`]): it must assemble at every target on
//! the branch asked for, keep assembling between consecutive targets (so it cannot change
//! branch or pass a limit position), meet the targets in order, and satisfy the constraints;
//! a defective trial step is rejected like a step that does not lower the objective, so
//! every answer is a defect-free mechanism. The same seed gives the same answer.
//!
//! ```
//! use mechdiff_core::synthesis::{Linkage, Problem, Synthesis, Task, Timing};
//! // A crank O2–A of unknown length and angle offset must carry A through three points
//! // of the circle of radius 0.5 about the origin, 0.4 rad apart.
//! let targets = (0..3)
//!     .map(|i| { let t = 0.3 + 0.4 * i as f64; [0.5 * t.cos(), 0.5 * t.sin()] })
//!     .collect();
//! let task = Task::Path {
//!     point: "A".into(),
//!     targets,
//!     timing: Timing::Relative(vec![0.0, 0.4, 0.8]),
//! };
//! let problem = Problem::builder(Linkage::FourBar, task)
//!     .fix("o2x", 0.0).fix("o2y", 0.0).fix("o4x", 1.0).fix("o4y", 0.0)
//!     .bound("crank", 0.1, 0.9).fix("coupler", 1.0).fix("rocker", 1.0)
//!     .fix("px", 0.0).fix("py", 0.0)
//!     .build()
//!     .unwrap();
//! let report = Synthesis::seeded(1).with_starts(20, 5).solve(&problem).unwrap();
//! assert!(report.objective < 1e-24);
//! assert!((report.value("crank").unwrap() - 0.5).abs() < 1e-12);
//! assert!((report.value("drive0").unwrap() - 0.3).abs() < 1e-12);
//! ```

mod certify;
mod error;
mod evaluator;
mod evolution;
mod grashof;
mod history;
mod inequalities;
mod linkage;
mod lm;
mod problem;
mod search;
mod seeding;
mod task;
mod workers;

pub use certify::Certificate;
pub use error::{Defect, SynthesisError};
pub use evaluator::Derivatives;
pub use grashof::GrashofClass;
pub use history::{History, Improvement, MAX_HISTORY};
pub use linkage::{Linkage, LinkagePose, NoAssembly};
pub use lm::LocalStop;
pub use problem::{Constraints, MAX_CHECKS, MAX_TARGETS, Problem, ProblemBuilder};
pub use search::{MAX_ROUNDS, MAX_STARTS, Report, StopReason, Synthesis};
pub use task::{Task, Timing};
pub use workers::{InOrder, Workers};
