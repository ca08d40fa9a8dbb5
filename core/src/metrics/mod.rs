//! Linkage metrics: what a designer reads first about a linkage — Grashof's class, the
//! transmission angle and its extremes, the time ratio of a quick return, the stroke or
//! swing, and how far the input moves.
//!
//! [`LinkageMetrics::of`] finds the four-bar and slider-crank loops of any mechanism model
//! ([`Loops::find`], four-bars inside larger mechanisms included) and gives, per loop:
//!
//! - **Grashof's class** ([`Grashof`]) with the inequality s + l vs p + q and the links it
//!   names; for a slider-crank, r + |e| vs l ([`SliderCrankCriterion`]);
//! - **the input's range** from the loop's lengths ([`InputRange`]): a full turn, or
//!   between the toggle positions where coupler and follower fold or stretch in line;
//! - **the transmission angle** μ ([`TransmissionAngle`]): in closed form by the law of
//!   cosines (cos μ = (b² + c² − a² − d² + 2ad cos θ)/(2bc) for a four-bar with input a,
//!   coupler b, output c, frame d; cos μ = (r sin θ − e)/l for a slider-crank), its
//!   extremes over the input's range and where ([`TransmissionExtremes`]), and at any
//!   solved pose from the pose itself, with derivatives by dual numbers
//!   ([`FourBarLoop::transmission_at`]);
//! - **the quick return** of the loop's output when its input is the drive and turns
//!   fully ([`QuickReturn`]: the dead positions, forward and return crank angles, time
//!   ratio, stroke or swing) — found for any output with [`QuickReturn::find`].
//!
//! and, for the mechanism, **the drive's motion range** in words ([`DriveMotion`]).
//!
//! ```text
//!   four-bar:        A ──── b ──── B           slider-crank:      A
//!                   /   μ at B ─→   \                          r /  \ l
//!                  a                 c                          /    \
//!                 / θ                 \                        O θ→u  B ══ (path, e from O)
//!               O_in ────── d ────── O_out
//! ```
//!
//! Everything is plain data in SI units (m, rad): the command line and reports format it.
//!
//! ```
//! use mechdiff_core::geometry::{Drive, Mechanism, Solver};
//! use mechdiff_core::metrics::{GrashofClass, LinkageMetrics};
//! // The crank-rocker of scenes/four_bar.toml: d = 0.4, a = 0.1, b = √0.2, c = 0.3 (m).
//! let m = Mechanism::builder()
//!     .point("O2", [0.0, 0.0]).point("O4", [0.4, 0.0])
//!     .point("A", [0.0, 0.1]).point("B", [0.4, 0.3])
//!     .ground(["O2", "O4"]).link("crank", ["O2", "A"])
//!     .link("coupler", ["A", "B"]).link("rocker", ["O4", "B"])
//!     .revolute("O2", "ground", "crank", "O2").revolute("A", "crank", "coupler", "A")
//!     .revolute("B", "coupler", "rocker", "B").revolute("O4", "ground", "rocker", "O4")
//!     .drive(Drive::angle("O2"))
//!     .build().unwrap();
//! let metrics = LinkageMetrics::of(&m, &Solver::default()).unwrap();
//! let four_bar = &metrics.four_bars[0];
//! assert_eq!(four_bar.grashof.class, GrashofClass::CrankRocker);
//! assert!(four_bar.input_range.is_full() && metrics.drive.turns_fully());
//! let q = four_bar.quick_return.as_ref().unwrap();
//! assert!(q.time_ratio > 1.0);
//! ```

mod drive;
mod error;
mod four_bar;
mod grashof;
mod input_range;
mod loops;
mod quick_return;
mod slider_crank;
mod transmission;
mod words;

pub use drive::DriveMotion;
pub use error::MetricsError;
pub use four_bar::FourBarLoop;
pub use grashof::{
    FourBarLengths, Grashof, GrashofClass, LengthTerm, ROUNDING_ULPS, Role, SliderCrankClass,
    SliderCrankCriterion, SliderCrankLengths, length_tolerance,
};
pub use input_range::{
    InputEnd, InputPosition, InputRange, Toggle, TransmissionAt, TransmissionExtremes,
};
pub use loops::{Loops, NotApplicable};
pub use quick_return::{QuickReturn, Stroke};
pub use slider_crank::SliderCrankLoop;
pub use transmission::{
    TransmissionAngle, four_bar_transmission_angle, slider_crank_transmission_angle,
};

use crate::Jet;
use crate::geometry::{Kinematics, Mechanism, Solver};

/// The metrics of one four-bar loop.
#[derive(Debug, Clone, PartialEq)]
pub struct FourBarMetrics {
    /// The loop: links, joints, lengths.
    pub linkage: FourBarLoop,
    /// Grashof's class and inequality.
    pub grashof: Grashof,
    /// How far the input turns (from the loop's lengths).
    pub input_range: InputRange,
    /// μ's extremes over that range.
    pub transmission: TransmissionExtremes,
    /// The output's quick return (its swing is [`QuickReturn::travel`]), or why there is
    /// none (the output turns fully, the input is not the drive or does not turn, …).
    pub quick_return: Result<QuickReturn, MetricsError>,
}

/// The metrics of one slider-crank loop.
#[derive(Debug, Clone, PartialEq)]
pub struct SliderCrankMetrics {
    /// The loop: links, joints, lengths.
    pub linkage: SliderCrankLoop,
    /// Whether the crank turns fully: r + |e| vs l.
    pub criterion: SliderCrankCriterion,
    /// How far the crank turns (from the loop's lengths).
    pub input_range: InputRange,
    /// μ's extremes over that range.
    pub transmission: TransmissionExtremes,
    /// The slider's quick return (its stroke is [`QuickReturn::travel`]), or why there is
    /// none.
    pub quick_return: Result<QuickReturn, MetricsError>,
}

/// The linkage metrics of a mechanism.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkageMetrics {
    /// The drive's motion range, for the words.
    pub drive: DriveMotion,
    /// Per four-bar loop.
    pub four_bars: Vec<FourBarMetrics>,
    /// Per slider-crank loop.
    pub slider_cranks: Vec<SliderCrankMetrics>,
    /// The solver loops without linkage metrics, and why.
    pub not_applicable: Vec<NotApplicable>,
}

impl LinkageMetrics {
    /// The metrics of `m`, solved by `solver` (for the drive's range and the quick returns).
    ///
    /// # Errors
    /// [`MetricsError::Geometry`] when `m` cannot be tracked from its sketch (mobility,
    /// loops) or the drive's range cannot be walked.
    pub fn of(m: &Mechanism, solver: &Solver) -> Result<LinkageMetrics, MetricsError> {
        let drive = DriveMotion::of(m, solver)?;
        let loops = Loops::find(m)?;
        // The quick return of a loop's output, when the loop's input is the drive.
        let quick_return =
            |driven: bool, input: &str, output: &dyn Fn(&Kinematics<'_, 3>) -> Jet<3>| {
                if driven {
                    QuickReturn::over_turn(&drive, solver.track(m)?, output)
                } else {
                    Err(MetricsError::InputNotDriven {
                        input: input.to_owned(),
                    })
                }
            };
        let four_bars = (loops.four_bars.into_iter())
            .map(|l| {
                let rotation = l.output_rotation();
                let output = |k: &Kinematics<'_, 3>| k.value(&rotation);
                FourBarMetrics {
                    grashof: l.grashof(),
                    input_range: l.input_range(),
                    transmission: l.transmission_extremes(),
                    quick_return: quick_return(l.driven, &l.links[1], &output),
                    linkage: l,
                }
            })
            .collect();
        let slider_cranks = (loops.slider_cranks.into_iter())
            .map(|l| {
                let output = |k: &Kinematics<'_, 3>| l.slider_position(k);
                SliderCrankMetrics {
                    criterion: l.criterion(),
                    input_range: l.input_range(),
                    transmission: l.transmission_extremes(),
                    quick_return: quick_return(l.driven, &l.crank, &output),
                    linkage: l,
                }
            })
            .collect();
        Ok(LinkageMetrics {
            drive,
            four_bars,
            slider_cranks,
            not_applicable: loops.not_applicable,
        })
    }
}
