//! The plan of a run: what is computed, printed before the table.

use std::fmt;

use mechdiff_core::DriveState;

use super::model::Scene;
use super::outputs::columns;
use super::units::Units;

/// What a run computes, printed before the table.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// Number of drive positions.
    pub positions: usize,
    /// Smallest and largest position of the sweep (SI): drive positions, or values of the
    /// output named by `given_by`.
    pub range: (f64, f64),
    /// The output whose values the sweep gives (`[sweep] of`), if any.
    pub given_by: Option<String>,
    /// Highest derivative order with respect to the drive that the outputs need.
    pub order: usize,
    /// The drive state used for velocities and accelerations, if any is asked for.
    pub drive: Option<DriveState>,
    /// Number of output columns (the drive column excluded).
    pub columns: usize,
    /// Outputs whose dead positions are searched.
    pub dead_positions: Vec<String>,
    /// The plan of the `[[dynamics]]` outputs: derivative order and effects.
    pub dynamics: Option<mechdiff_core::dynamics::Plan>,
    /// Each loop and the path that evaluates it, once the sweep is set up
    /// ([`super::Sweeper::loops`]); empty before.
    pub loops: Vec<crate::evaluator::LoopPlan>,
    /// The run-time evaluator's back end, when it evaluates the sweep (set with `loops`).
    pub backend: Option<mechdiff_core::trace::Backend>,
}

impl Plan {
    /// The plan of a scene.
    pub fn of(scene: &Scene) -> Self {
        let (lo, hi) = scene.positions.range();
        let times = scene
            .outputs
            .iter()
            .any(|o| o.quantities.iter().any(|q| q.is_time_derivative()));
        let drive = match (times, scene.drive.speed) {
            (true, Some(omega)) => Some(DriveState::accelerating(omega, scene.drive.acceleration)),
            _ => None,
        };
        let drive_dimension = scene.drive.kind.dimension();
        Plan {
            positions: scene.positions.len(),
            range: (lo, hi),
            given_by: scene.sweep_of.map(|k| scene.outputs[k].name.clone()),
            order: scene.order(),
            drive,
            columns: scene
                .outputs
                .iter()
                .map(|o| columns(o, &scene.units, drive_dimension).len())
                .sum(),
            dead_positions: scene
                .outputs
                .iter()
                .filter(|o| o.dead_positions)
                .map(|o| o.name.clone())
                .collect(),
            dynamics: scene
                .dynamics
                .as_ref()
                .filter(|d| !d.outputs.is_empty())
                .and_then(|d| super::build::mechanism(scene).ok().map(|m| d.plan(&m))),
            loops: Vec::new(),
            backend: None,
        }
    }
    /// Records who evaluates `sweeper`'s positions: each loop's path and the run-time
    /// evaluator's back end (for the plan line).
    pub(crate) fn evaluated_by(&mut self, sweeper: &super::Sweeper<'_>) {
        self.loops = sweeper.loops();
        self.backend = sweeper.backend();
    }

    /// The plan as one line, in the scene's units.
    pub fn describe(&self, scene: &Scene) -> String {
        let what = match self.order {
            0 => "positions only (order 0)",
            1 => "positions and velocity coefficients (order 1)",
            2 => "positions, velocity and acceleration coefficients (order 2)",
            _ => "positions, velocity, acceleration and jerk coefficients (order 3)",
        };
        let range = if let Some(k) = scene.sweep_of {
            let output = &scene.outputs[k];
            let text = |v: f64| {
                let d = output.kind.dimension();
                let u = &scene.units;
                format!("{} {}", Units::tidy(u.from_si(v, d)), u.symbol(d))
            };
            let values = if self.positions == 1 {
                format!(
                    "1 drive position where {} = {}",
                    output.name,
                    text(self.range.0)
                )
            } else {
                format!(
                    "{} drive positions where {} goes from {} to {}",
                    self.positions,
                    output.name,
                    text(self.range.0),
                    text(self.range.1)
                )
            };
            format!(
                "{values} (drive positions solved by Newton on {}')",
                output.name
            )
        } else if self.positions == 1 {
            format!("1 drive position, phi = {}", scene.drive_text(self.range.0))
        } else {
            format!(
                "{} drive positions, phi from {} to {}",
                self.positions,
                scene.drive_text(self.range.0),
                scene.drive_text(self.range.1)
            )
        };
        let motion = match self.drive {
            Some(d) => {
                let kind = scene.drive.kind;
                let u = &scene.units;
                format!(
                    "; {} for speed {} {}, acceleration {} {}",
                    if self.order >= 3 {
                        "velocities, accelerations and jerks"
                    } else {
                        "velocities and accelerations"
                    },
                    Units::tidy(u.from_si(d.omega, kind.speed_dimension())),
                    u.symbol(kind.speed_dimension()),
                    Units::tidy(u.from_si(d.alpha, kind.acceleration_dimension())),
                    u.symbol(kind.acceleration_dimension()),
                )
            }
            None => String::new(),
        };
        let dead = if self.dead_positions.is_empty() {
            String::new()
        } else {
            format!("; dead positions of {}", self.dead_positions.join(", "))
        };
        let dynamics = match &self.dynamics {
            Some(p) => format!("\ndynamics plan: {p}"),
            None => String::new(),
        };
        let by = if self.loops.is_empty() {
            "by the geometry solver (exact: loops in closed form where they match a standard \
             group, else Newton with implicit differentiation)"
                .to_owned()
        } else {
            crate::evaluator::describe(&self.loops, self.backend)
        };
        format!(
            "plan: {range}; {what} {by}{motion}; {} columns{dead}{dynamics}",
            self.columns
        )
    }
}

impl fmt::Display for Plan {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} drive positions, derivative order {}",
            self.positions, self.order
        )
    }
}
