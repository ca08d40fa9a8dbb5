//! What exact derivatives buy in synthesis: the known-answer problems (targets generated
//! from a known four-bar (timed and untimed), slider-crank and Stephenson six-bar; function and motion
//! generation of a known four-bar) solved over ten seeds with the exact Jacobian (dual
//! numbers) and with central differences, same starts, same limits. Prints, per problem and
//! method: successes (objective ≤ 1e-20 within the limits), median and total residual
//! evaluations, median and total time.
//!
//! `cargo run --release -p mechdiff-core --features synthesis --example synthesis_exact_vs_differences`

use mechdiff_core::synthesis::{
    Derivatives, Linkage, Problem, ProblemBuilder, Synthesis, SynthesisError, Task, Timing,
};
use std::time::Duration;

const FOUR_BAR: [f64; 9] = [0.0, 0.0, 1.2, 0.1, 0.4, 1.1, 0.9, 0.5, 0.35];
const SLIDER_CRANK: [f64; 8] = [0.1, -0.2, 0.3, 1.0, 0.15, 0.2, 0.4, 0.25];
const SIX_BAR: [f64; 15] = [
    0.0, 0.0, 1.2, 0.1, 0.4, 1.1, 0.9, 0.5, 0.35, 1.0, 1.3, 1.0, 1.1, 0.3, -0.2,
];

fn four_bar_bounds(b: ProblemBuilder) -> ProblemBuilder {
    b.bound("o2x", -1.0, 1.0)
        .bound("o2y", -1.0, 1.0)
        .bound("o4x", 0.0, 2.0)
        .bound("o4y", -1.0, 1.0)
        .bound("crank", 0.1, 1.0)
        .bound("coupler", 0.1, 2.0)
        .bound("rocker", 0.1, 2.0)
        .bound("px", -1.5, 1.5)
        .bound("py", -1.5, 1.5)
}

fn timed_path(linkage: Linkage, x: &[f64], start: f64, step: f64, n: usize) -> Task {
    let rel: Vec<f64> = (0..n).map(|k| step * k as f64).collect();
    let point = linkage.point_names().len() - 1;
    let branch = vec![1.0; linkage.dyad_count()];
    let targets = rel
        .iter()
        .map(|r| {
            linkage
                .pose(x, start + r, &branch)
                .expect("assembles")
                .points[point]
        })
        .collect();
    Task::Path {
        point: linkage.traced_point().into(),
        targets,
        timing: Timing::Relative(rel),
    }
}

fn problems() -> Result<Vec<(&'static str, Problem, usize, usize)>, SynthesisError> {
    let four_bar = four_bar_bounds(Problem::builder(
        Linkage::FourBar,
        timed_path(Linkage::FourBar, &FOUR_BAR, 0.3, 0.5, 10),
    ))
    .build()?;
    let slider_crank = Problem::builder(
        Linkage::SliderCrank,
        timed_path(Linkage::SliderCrank, &SLIDER_CRANK, -0.5, 0.6, 10),
    )
    .bound("o2x", -1.0, 1.0)
    .bound("o2y", -1.0, 1.0)
    .bound("crank", 0.1, 1.0)
    .bound("rod", 0.1, 2.0)
    .bound("offset", -1.0, 1.0)
    .bound("guide", -1.5, 1.5)
    .bound("px", -1.5, 1.5)
    .bound("py", -1.5, 1.5)
    .build()?;
    let six_bar = four_bar_bounds(Problem::builder(
        Linkage::StephensonSix,
        timed_path(Linkage::StephensonSix, &SIX_BAR, 0.3, 0.45, 12),
    ))
    .bound("o6x", -1.0, 2.0)
    .bound("o6y", -1.0, 2.0)
    .bound("link5", 0.1, 2.0)
    .bound("link6", 0.1, 2.0)
    .bound("qx", -1.5, 1.5)
    .bound("qy", -1.5, 1.5)
    .build()?;
    let known = [0.0, 0.0, 1.0, 0.0, 0.35, 1.1, 0.8, 0.0, 0.0];
    let pairs = (0..10)
        .map(|k| {
            let phi = 0.4 + 0.3 * k as f64;
            let pose = Linkage::FourBar
                .pose(&known, phi, &[1.0])
                .expect("assembles");
            [phi - 0.4, pose.outputs[2]]
        })
        .collect();
    let function = Problem::builder(
        Linkage::FourBar,
        Task::Function {
            output: "rocker".into(),
            pairs,
        },
    )
    .fix("o2x", 0.0)
    .fix("o2y", 0.0)
    .fix("o4x", 1.0)
    .fix("o4y", 0.0)
    .bound("crank", 0.05, 2.0)
    .bound("coupler", 0.05, 3.0)
    .bound("rocker", 0.05, 3.0)
    .fix("px", 0.0)
    .fix("py", 0.0)
    .build()?;
    let poses = (0..7)
        .map(|k| {
            let pose = Linkage::FourBar
                .pose(&FOUR_BAR, 0.2 + 0.8 * k as f64, &[1.0])
                .expect("assembles");
            [
                pose.points[2][0],
                pose.points[2][1],
                pose.traced_link_angle + 0.6,
            ]
        })
        .collect();
    let motion = four_bar_bounds(Problem::builder(
        Linkage::FourBar,
        Task::Motion {
            link: "coupler".into(),
            poses,
            timing: Timing::Free,
            angle_weight: 1.0,
        },
    ))
    .build()?;
    let untimed = four_bar_bounds(Problem::builder(
        Linkage::FourBar,
        Task::Path {
            point: "P".into(),
            targets: (0..12)
                .map(|k| {
                    let phi = 0.2 + 0.5 * k as f64;
                    Linkage::FourBar
                        .pose(&FOUR_BAR, phi, &[1.0])
                        .expect("assembles")
                        .points[2]
                })
                .collect(),
            timing: Timing::Free,
        },
    ))
    .build()?;
    Ok(vec![
        ("four-bar path, timed (10 points)", four_bar, 2000, 200),
        ("four-bar path, untimed (12 points)", untimed, 4000, 400),
        (
            "slider-crank path, timed (10 points)",
            slider_crank,
            2000,
            200,
        ),
        (
            "Stephenson six-bar path, timed (12 points)",
            six_bar,
            4000,
            400,
        ),
        ("four-bar function generation (10 pairs)", function, 500, 50),
        (
            "four-bar motion generation, untimed (7 poses)",
            motion,
            4000,
            400,
        ),
    ])
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() -> Result<(), SynthesisError> {
    println!(
        "| problem | Jacobian | successes of 10 | median evaluations | total evaluations | median time (ms) | total time (ms) |"
    );
    println!("|---|---|---|---|---|---|---|");
    for (name, problem, samples, searches) in problems()? {
        for (label, derivatives) in [
            ("exact (dual)", Derivatives::Exact),
            ("central differences", Derivatives::CentralDifferences),
        ] {
            let (mut evals, mut times, mut successes) = (Vec::new(), Vec::new(), 0);
            for seed in 0..10 {
                let settings = Synthesis::seeded(seed)
                    .with_starts(samples, searches)
                    .with_derivatives(derivatives)
                    .with_stop_objective(1e-20)
                    .with_time_limit(Duration::from_secs(10));
                let report = settings.solve(&problem)?;
                successes += usize::from(report.objective <= 1e-20);
                evals.push(report.evaluations as f64);
                times.push(report.elapsed.as_secs_f64() * 1e3);
            }
            println!(
                "| {name} | {label} | {successes} | {:.0} | {:.0} | {:.1} | {:.1} |",
                median(evals.clone()),
                evals.iter().sum::<f64>(),
                median(times.clone()),
                times.iter().sum::<f64>()
            );
        }
    }
    Ok(())
}
