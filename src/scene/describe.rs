//! A run's findings in the scene's words, printed with its table: the plan line, the
//! drive's motion range, the limits the sweep reaches. Presentation, beside the runner: it
//! reads the scene (units, drive, outputs) to word what the runner found.

use mechdiff_core::geometry::MotionRange;

use super::model::{DriveKind, Scene};
use super::plan::Plan;
use super::sweep_limits::{SweepLimit, kind_words};
use super::units::Units;

impl Plan {
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

/// The drive's motion range in words, in the scene's units: `"from … (…) to … (…)"`, or
/// that no limit was met within the distance searched.
pub fn describe_motion_range(scene: &Scene, range: &MotionRange) -> String {
    let end = |limit: &Option<mechdiff_core::geometry::DriveLimit>, sign: f64| match limit {
        Some(l) => {
            let what = kind_words(l.kind);
            let joints = l.joints.join(", ");
            format!(
                "{} ({what}, loop of joints {joints})",
                scene.drive_text(l.phi)
            )
        }
        None => format!(
            "beyond {} (no limit met)",
            scene.drive_text(scene.drive.at_sketch + sign * range.searched)
        ),
    };
    if range.lower.is_none() && range.upper.is_none() && scene.drive.kind == DriveKind::Angle {
        return "full turns (no limit position, change point or toggle in a turn)".to_owned();
    }
    format!(
        "from {} to {}",
        end(&range.lower, -1.0),
        end(&range.upper, 1.0)
    )
}

/// One line per limit the sweep reaches, in the scene's units: `phi = … deg: limit position
/// (loop of joints A, B, guide)`.
pub fn limit_lines(scene: &Scene, limits: &[SweepLimit]) -> Vec<String> {
    limits
        .iter()
        .map(|l| {
            format!(
                "  phi = {}: {} (loop of joints {}){}",
                scene.drive_text(l.limit.phi),
                kind_words(l.limit.kind),
                l.limit.joints.join(", "),
                l.tag
            )
        })
        .collect()
}
