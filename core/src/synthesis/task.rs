//! What the mechanism must do: path, function or motion generation, and the timing of the
//! targets along the drive.

/// The drive angles at which the targets must be met.
#[derive(Debug, Clone, PartialEq)]
pub enum Timing {
    /// The drive angle of each target, absolute (rad).
    Absolute(Vec<f64>),
    /// The drive angle of each target relative to an unknown starting angle `drive0` (a design
    /// variable): φᵢ = drive0 + the i-th given angle (rad).
    Relative(Vec<f64>),
    /// Free: each target's drive angle is a design variable (`drive1`, `drive2`, …), the
    /// targets met in the order given along one counter-clockwise turn of the crank
    /// (φ₁ < φ₂ < … < φ₁ + 2π).
    Free,
}

/// A synthesis task.
#[derive(Debug, Clone, PartialEq)]
pub enum Task {
    /// Path generation: `point` passes through `targets` (m).
    Path {
        /// The traced point (one of [`super::Linkage::point_names`]).
        point: String,
        /// The points it must pass through (m).
        targets: Vec<[f64; 2]>,
        /// When.
        timing: Timing,
    },
    /// Function generation: `output` changes by `pairs[i][1] − pairs[0][1]` while the drive
    /// turns by `pairs[i][0] − pairs[0][0]` from an unknown starting angle `drive0`.
    Function {
        /// The output (one of [`super::Linkage::output_names`]: a link angle, rad, or the
        /// slider's displacement, m).
        output: String,
        /// (drive angle, output) pairs; only differences from the first pair count.
        pairs: Vec<[f64; 2]>,
    },
    /// Motion generation: `link` takes the poses (x, y, angle): its traced point at (x, y),
    /// its frame at the angle, up to a constant angle `pose_angle` (a design variable).
    Motion {
        /// The guided link ([`super::Linkage::traced_link`]).
        link: String,
        /// The poses: x, y (m), angle (rad).
        poses: Vec<[f64; 3]>,
        /// When.
        timing: Timing,
        /// The length (m per rad) an angle error is weighed with against a distance.
        angle_weight: f64,
    },
}

impl Task {
    /// The number of targets (points, pairs or poses).
    pub fn target_count(&self) -> usize {
        match self {
            Task::Path { targets, .. } => targets.len(),
            Task::Function { pairs, .. } => pairs.len(),
            Task::Motion { poses, .. } => poses.len(),
        }
    }

    /// The timing of the targets (function generation: relative to `drive0`).
    pub(crate) fn timing(&self) -> Timing {
        match self {
            Task::Path { timing, .. } | Task::Motion { timing, .. } => timing.clone(),
            Task::Function { pairs, .. } => Timing::Relative(pairs.iter().map(|p| p[0]).collect()),
        }
    }

    /// The number of residuals: 2 per point, 1 per pair after the first, 3 per pose.
    pub fn residual_count(&self) -> usize {
        match self {
            Task::Path { targets, .. } => 2 * targets.len(),
            Task::Function { pairs, .. } => pairs.len().saturating_sub(1),
            Task::Motion { poses, .. } => 3 * poses.len(),
        }
    }
}
