//! The constraints measured at an answer: how far the mechanism found is from violating
//! each (positive: satisfied with room to spare).

use std::f64::consts::TAU;

use mechdiff_core::synthesis::{GrashofClass, Linkage, Report, Task, Timing};

use super::Setup;
use crate::scene::units::Dimension;

/// One constraint's measure at the answer.
#[derive(Debug, Clone, PartialEq)]
pub struct Margin {
    /// What is measured, in words.
    pub what: String,
    /// The value (SI).
    pub value: f64,
    /// Its unit's dimension.
    pub dimension: Dimension,
    /// Whether the section requires it (a measure that is not required is informative).
    pub required: bool,
    /// The least value required (SI), where there is one.
    pub least: Option<f64>,
}

/// The constraints' margins at an answer.
#[derive(Debug, Clone, PartialEq)]
pub struct Margins {
    /// One per constraint.
    pub margins: Vec<Margin>,
}

impl Setup {
    /// The constraints measured at `report`'s answer: the crank's rotation condition
    /// (Grashof's p + q − s − l with the crank shortest, or rod − crank − |offset|), the least
    /// transmission angle at the targets and between them (over a full turn when the crank
    /// must turn), and, for free timing, the least step between consecutive targets' drive
    /// positions.
    pub fn margins(&self, report: &Report) -> Margins {
        let problem = &self.problem;
        let linkage = problem.linkage();
        let x = report.x();
        let c = (self.crank_rotates, self.min_transmission);
        let mut margins = Vec::new();
        let rotation = match linkage {
            Linkage::SliderCrank => x[3] - x[2] - x[4].abs(),
            _ => {
                let ground = (x[2] - x[0]).hypot(x[3] - x[1]);
                let mut sides = [ground, x[4], x[5], x[6]];
                sides.sort_by(f64::total_cmp);
                let grashof = sides[1] + sides[2] - sides[0] - sides[3];
                let shortest = [ground, x[5], x[6]].into_iter().fold(f64::MAX, f64::min);
                grashof.min(shortest - x[4])
            }
        };
        margins.push(Margin {
            what: match linkage {
                Linkage::SliderCrank => "crank turns fully: rod − crank − |offset|".into(),
                _ => "crank turns fully (Grashof, crank shortest): min(p + q − s − l, \
                      shortest other link − crank)"
                    .into(),
            },
            value: rotation,
            dimension: Dimension::Length,
            required: c.0,
            least: c.0.then_some(0.0),
        });
        let asked = problem.grashof();
        if asked != GrashofClass::Any {
            let ground = (x[2] - x[0]).hypot(x[3] - x[1]);
            let found = GrashofClass::of(ground, x[4], x[5], x[6]);
            margins.push(Margin {
                what: format!(
                    "Grashof class {} ({} asked): p + q − s − l",
                    found.name(),
                    asked.name()
                ),
                value: GrashofClass::margin(ground, x[4], x[5], x[6]),
                dimension: Dimension::Length,
                required: true,
                least: None,
            });
        }
        let phis = problem.drive_angles(&x);
        let mut angles: Vec<f64> = Vec::new();
        let checks = 8usize;
        for w in phis.windows(2) {
            for k in 0..checks {
                angles.push(w[0] + (w[1] - w[0]) * k as f64 / checks as f64);
            }
        }
        angles.extend(phis.last());
        if c.0 {
            angles.extend((0..72).map(|k| f64::from(k) * TAU / 72.0));
        }
        let least = angles
            .iter()
            .filter_map(|&phi| linkage.pose(&x, phi, problem.branch()).ok())
            .flat_map(|pose| pose.margins)
            .fold(f64::INFINITY, f64::min);
        if least.is_finite() {
            margins.push(Margin {
                what: if c.0 {
                    "least transmission angle over a turn and at the targets".into()
                } else {
                    "least transmission angle from the first target to the last".into()
                },
                value: least.clamp(0.0, 1.0).sqrt().asin(),
                dimension: Dimension::Angle,
                required: c.1 > 0.0,
                least: (c.1 > 0.0).then_some(c.1),
            });
        }
        let timing = match problem.task() {
            Task::Path { timing, .. } | Task::Motion { timing, .. } => timing.clone(),
            Task::Function { .. } => Timing::Absolute(vec![]),
        };
        if matches!(timing, Timing::Free) && phis.len() > 1 {
            let step = phis
                .windows(2)
                .map(|w| w[1] - w[0])
                .fold(f64::INFINITY, f64::min);
            margins.push(Margin {
                what: "targets in order: least drive step between consecutive targets".into(),
                value: step,
                dimension: Dimension::Angle,
                required: true,
                least: Some(0.0),
            });
            margins.push(Margin {
                what: "targets within one turn: a turn − (last − first drive position)".into(),
                value: TAU - (phis[phis.len() - 1] - phis[0]),
                dimension: Dimension::Angle,
                required: true,
                least: Some(0.0),
            });
        }
        Margins { margins }
    }
}
