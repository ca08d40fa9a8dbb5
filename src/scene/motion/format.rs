//! The sections of the machine in motion as written (serde, every value with its span): the
//! motor's `characteristic` inside `[motor]`, and `[simulate]`.

use serde::Deserialize;
use toml::Spanned;

use crate::scene::values::Number;

/// Which motor characteristic a `[motor] characteristic` is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CharacteristicKind {
    /// The same torque at every speed: `torque`.
    Constant,
    /// A DC shunt motor, `M = M_s (1 − ω/ω₀)`: `stall_torque`, `no_load_speed`.
    Linear,
    /// An induction motor by the Kloss formula: `synchronous_speed`, `breakdown_torque`,
    /// `breakdown_slip`.
    Induction,
    /// A measured curve, linearly interpolated: `speeds`, `torques`.
    Table,
}

/// `[motor] characteristic = { type = "...", ... }`: the torque on the motor shaft against
/// the motor's speed (torques in the file's torque unit, speeds in its angular-velocity
/// unit, a slip as a fraction).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CharacteristicDef {
    /// Which characteristic.
    #[serde(rename = "type")]
    pub kind: Spanned<CharacteristicKind>,
    /// `constant`: the torque.
    #[serde(default)]
    pub torque: Option<Spanned<Number>>,
    /// `linear`: the torque at standstill.
    #[serde(default)]
    pub stall_torque: Option<Spanned<Number>>,
    /// `linear`: the speed without load (> 0).
    #[serde(default)]
    pub no_load_speed: Option<Spanned<Number>>,
    /// `induction`: the synchronous speed (> 0).
    #[serde(default)]
    pub synchronous_speed: Option<Spanned<Number>>,
    /// `induction`: the breakdown (pull-out) torque (> 0).
    #[serde(default)]
    pub breakdown_torque: Option<Spanned<Number>>,
    /// `induction`: the breakdown slip, in (0, 1].
    #[serde(default)]
    pub breakdown_slip: Option<Spanned<Number>>,
    /// `table`: the speeds, strictly increasing.
    #[serde(default)]
    pub speeds: Option<Spanned<Vec<Spanned<Number>>>>,
    /// `table`: the torques at those speeds.
    #[serde(default)]
    pub torques: Option<Spanned<Vec<Spanned<Number>>>>,
}

/// An analysis `[simulate] find` names.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Find {
    /// From rest at `start` until the drive reaches `speed`: time to speed, peak motor
    /// torque, the motion in time.
    StartUp,
    /// The periodic steady state (by shooting): ω(φ), t(φ), period, ω_min, ω_max, δ.
    SteadyState,
    /// With the motor switched off, from the end of the start-up (or from the steady state)
    /// until rest.
    CoastDown,
    /// The flywheel that brings δ to `delta`: exactly and by the classic energy method.
    Flywheel,
}

/// The mean speed of the coefficient of speed fluctuation δ the flywheel is sized for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MeanSpeedDef {
    /// The time mean `2π / T`.
    Time,
    /// The mid-range `(ω_max + ω_min) / 2`.
    MidRange,
}

/// `[simulate]`: what to find about the machine moving under its motor, with its tolerances
/// and bounds.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SimulateDef {
    /// The analyses, in any order (they run in the order of [`Find`]).
    pub find: Spanned<Vec<Spanned<Find>>>,
    /// Where a start-up starts from rest, and the steady state's reference angle (drive
    /// unit; default 0).
    #[serde(default)]
    pub start: Option<Spanned<Number>>,
    /// The drive speed a start-up runs to (drive speed unit; default 0.95 of the motor's
    /// no-load speed at the drive).
    #[serde(default)]
    pub speed: Option<Spanned<Number>>,
    /// The longest simulated time of a start-up and of a coast-down (s; default 60).
    #[serde(default)]
    pub time: Option<Spanned<Number>>,
    /// The most turns the steady-state search (and each flywheel iteration) integrates
    /// (default 200).
    #[serde(default)]
    pub turns: Option<Spanned<Number>>,
    /// A flywheel on the drive shaft (moment-of-inertia unit; default 0).
    #[serde(default)]
    pub flywheel: Option<Spanned<Number>>,
    /// The coefficient of speed fluctuation the flywheel is sized for, in (0, 2).
    #[serde(default)]
    pub delta: Option<Spanned<Number>>,
    /// The mean speed of that δ (default `time`).
    #[serde(default)]
    pub mean_speed: Option<Spanned<MeanSpeedDef>>,
    /// The integration's relative and absolute tolerance per step (default 1e-10).
    #[serde(default)]
    pub tolerance: Option<Spanned<Number>>,
    /// The most integration steps of one run (default 10⁶).
    #[serde(default)]
    pub max_steps: Option<Spanned<Number>>,
}
