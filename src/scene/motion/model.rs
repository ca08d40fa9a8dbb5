//! The sections of the machine in motion checked, in SI (see `resolve`).

use mechdiff_core::machine::{Characteristic, MeanSpeed, Tolerances};

use crate::error::Location;

use super::format::Find;

/// A checked `[simulate]` with the motor's characteristic (SI).
#[derive(Debug, Clone, PartialEq)]
pub struct SceneMotion {
    /// The motor's characteristic on its own shaft.
    pub characteristic: Characteristic,
    /// Where `[motor] characteristic` is written.
    pub characteristic_at: Location,
    /// The analyses, each once, in the order they run.
    pub find: Vec<Find>,
    /// The start-up's start and the steady state's reference angle (drive unit, SI).
    pub start: f64,
    /// The drive speed a start-up runs to (SI), when given.
    pub speed: Option<f64>,
    /// The longest simulated time of a start-up and of a coast-down (s).
    pub time: f64,
    /// The most turns of the steady-state search (each flywheel iteration too).
    pub turns: usize,
    /// A flywheel on the drive shaft (kg·m², or kg for a sliding drive).
    pub flywheel: f64,
    /// The δ to size a flywheel for.
    pub delta: Option<f64>,
    /// The mean speed of that δ.
    pub mean: MeanSpeed,
    /// The integration's tolerances and step limit.
    pub tolerances: Tolerances,
    /// Where `[simulate]` is.
    pub location: Location,
    /// Where `turns` is written (the section without it).
    pub turns_at: Location,
    /// Where `time` is written (the section without it).
    pub time_at: Location,
}

impl SceneMotion {
    /// Whether the analysis `find` is asked for.
    pub fn finds(&self, find: Find) -> bool {
        self.find.contains(&find)
    }
}
