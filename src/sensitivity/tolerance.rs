//! A tolerance study from the sensitivities: for ± tolerances `tᵢ` of parameters `pᵢ`, the
//! first-order deviation of an output `y` is `Σ ∂y/∂pᵢ·δᵢ` with `|δᵢ| ≤ tᵢ`, so
//!
//! - **worst case** `Σ |∂y/∂pᵢ|·tᵢ` bounds it (reached at a corner of the tolerance box), and
//! - **root-sum-square** `√Σ (∂y/∂pᵢ·tᵢ)²` is the statistical stack-up (independent
//!   deviations, a common assumption in tolerancing; it is below the worst case).
//!
//! Both are first order: the true deviation differs from the linear one by the second-order
//! remainder `½ δᵀ (∂²y/∂p²) δ`, of the order of `t²`. A **Monte-Carlo** run checks them:
//! the scene is run again at parameters drawn uniformly from their ± boxes (a seeded
//! `Xoshiro256++` generator, so the same seed gives the same samples on every machine), and
//! the largest deviation sampled is reported beside the worst case.

use rand::rngs::Xoshiro256PlusPlus;
use rand::{RngExt, SeedableRng};

use crate::error::Result;
use crate::parallel::prelude::*;
use crate::scene::parameters::Setting;
use crate::scene::run::Report;

use super::spec::Parameter;

/// Per row, the worst case `Σ |dᵢ|·tᵢ` and the root-sum-square `√Σ (dᵢ·tᵢ)²` of the
/// derivatives `derivatives[i][row]` for tolerances `tolerances[i]`.
///
/// ```
/// use mechdiff::sensitivity::tolerance::stack_up;
///
/// // Two parameters: dy/dp1 = 3, dy/dp2 = −4 at one row, tolerances 1 and 1.
/// let (worst, rss) = stack_up(&[vec![3.0], vec![-4.0]], &[1.0, 1.0]);
/// assert_eq!((worst[0], rss[0]), (7.0, 5.0));
/// ```
pub fn stack_up(derivatives: &[Vec<f64>], tolerances: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let rows = derivatives.first().map_or(0, Vec::len);
    let mut worst = vec![0.0; rows];
    let mut squares = vec![0.0; rows];
    for (d, &t) in derivatives.iter().zip(tolerances) {
        for (row, &v) in d.iter().enumerate() {
            worst[row] += (v * t).abs();
            squares[row] += (v * t) * (v * t);
        }
    }
    (worst, squares.into_iter().map(f64::sqrt).collect())
}

/// The most samples of a Monte-Carlo check (`--monte-carlo N`): each sample is a whole run
/// of the scene (a million runs take hours), and the drawn parameters are held in memory.
pub const MAX_SAMPLES: usize = 1_000_000;

/// What a Monte-Carlo run found.
#[derive(Debug, Clone, PartialEq)]
pub struct MonteCarlo {
    /// Samples run.
    pub samples: usize,
    /// The seed of the generator.
    pub seed: u64,
    /// Per studied column, the largest `|y − y_nominal|` over all samples and rows (SI).
    pub max_deviation: Vec<f64>,
}

/// Runs `samples` scenes with the toleranced `parameters` drawn uniformly from their ± boxes
/// (the others at their values) and returns, per column of `studied`, the largest deviation
/// from `nominal`. `run` runs the scene with the settings given. The samples are drawn in
/// order from the seeded generator and run in parallel (rayon's pool): the result does not
/// depend on the number of threads.
///
/// # Errors
/// The error of the first sample (in sample order) whose run fails (from `run`).
pub fn monte_carlo(
    parameters: &[Parameter],
    studied: &[usize],
    nominal: &Report,
    samples: usize,
    seed: u64,
    run: impl Fn(&[Setting], &str) -> Result<Report> + Sync,
) -> Result<MonteCarlo> {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let drawn: Vec<Vec<Setting>> = (0..samples)
        .map(|_| {
            parameters
                .iter()
                .filter_map(|p| {
                    let t = p.tolerance?;
                    let u: f64 = rng.random_range(-1.0..=1.0);
                    Some(Setting {
                        name: p.name.clone(),
                        value: format!("{:e}", p.value + u * t),
                    })
                })
                .collect()
        })
        .collect();
    let deviations: Vec<Result<Vec<f64>>> = drawn
        .par_iter()
        .enumerate()
        .map(|(sample, settings)| {
            let report = run(settings, &format!("Monte-Carlo sample {}", sample + 1))?;
            Ok(studied
                .iter()
                .map(|&k| {
                    report
                        .rows
                        .iter()
                        .zip(&nominal.rows)
                        .fold(0.0_f64, |m, (row, base)| m.max((row[k] - base[k]).abs()))
                })
                .collect())
        })
        .collect();
    let mut max_deviation = vec![0.0_f64; studied.len()];
    for sample in deviations {
        for (m, d) in max_deviation.iter_mut().zip(sample?) {
            *m = m.max(d);
        }
    }
    Ok(MonteCarlo {
        samples,
        seed,
        max_deviation,
    })
}
