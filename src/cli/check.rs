//! `mechdiff check <scene.toml>`: validate a scene without running its sweep.

use std::path::PathBuf;

use clap::Args;
use mechdiff::scene;
use mechdiff::scene::any::AnyScene;
use mechdiff::scene::cam::CamScene;
use mechdiff::scene::units::{Dimension, Units};
use std::fmt::Write as _;

use mechdiff::{Error, escape, files, sensitivity};

/// Arguments of `mechdiff check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    /// The scene file (TOML; see docs/scene-format.md).
    pub scene: PathBuf,
    /// Replace the value of a parameter of the scene's `[parameters]` (repeatable):
    /// `--set l1=0.16`; the value may be a formula of the other parameters.
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<scene::parameters::Setting>,
}

/// Reads the scene, builds its model and checks its mobility at the sketch pose; prints a
/// summary, every link's lengths (which the solver holds) and the plan a run would carry
/// out.
pub fn check(args: &CheckArgs) -> Result<(), Error> {
    let text = files::read_scene(&args.scene)?;
    let kind = scene::kind(&text);
    super::refuse_options(kind, &[("--set", !args.set.is_empty())], &args.scene)?;
    let file = args.scene.display().to_string();
    // The reader `run` uses: the same verdict on everything up to solving.
    let scene = match scene::any::read(&file, &text, &args.set)? {
        AnyScene::Linkage(scene) => scene,
        AnyScene::Cam(cam) => return check_cam(&cam),
        AnyScene::Rotor(rotor) => return super::rotor::check(&rotor),
        AnyScene::Formula(formulas, positions) => {
            println!(
                "{file}: ok: formula scene of {} output(s) at {positions} drive position(s); \
                 `mechdiff run` prints their values and derivatives",
                formulas.outputs.len()
            );
            return Ok(());
        }
    };
    let checked = scene::check(&scene)?;
    // The study is checked against the columns a run would have, with the errors `run`
    // gives, before anything is printed.
    let study = sensitivity::check(&file, &text, &args.set, &checked.columns)?;
    let synthesis = scene::synthesize::read_if_present(&file, &text)?;
    let m = &checked.mechanism;
    // Written whole, then shown with the scene's text escaped for the terminal.
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{}: ok: {} points, {} links (ground included), {} joints; {} coordinates, {} joint \
         equations, {} degree(s) of freedom; Jacobian rank {} at the sketch pose (drive included)",
        scene.file,
        m.points().len(),
        m.links().len(),
        m.joints().len(),
        checked.mobility.coordinates,
        checked.mobility.joint_equations,
        checked.mobility.degrees_of_freedom,
        checked.mobility.rank,
    );
    for (k, ((joints, branch), &closed)) in
        checked.loops.iter().zip(&checked.closed_form).enumerate()
    {
        let how = if closed { "closed form" } else { "Newton" };
        let _ = writeln!(
            out,
            "loop {}: {} (branch certificate {branch:+} in the sketch; solved by {how})",
            k + 1,
            joints.join(", ")
        );
    }
    let _ = match &checked.motion_range {
        Ok(range) => writeln!(
            out,
            "drive motion range: {}",
            scene::run::describe_motion_range(&scene, range)
        ),
        Err(why) => writeln!(out, "drive motion range: not found ({why})"),
    };
    for (name, value) in &scene.parameters {
        let _ = writeln!(out, "parameter {name} = {}", Units::tidy(*value));
    }
    let units = scene.units;
    let unit = units.symbol(Dimension::Length);
    for (link, a, b, length) in scene.link_lengths() {
        let length = Units::tidy(units.from_si(length, Dimension::Length));
        let _ = writeln!(out, "length {link}: {a}–{b} = {length} {unit}");
    }
    let _ = writeln!(out, "{}", checked.plan.describe(&scene));
    if scene.motion.is_some() {
        // The plan `run` prints before it simulates, in the same words.
        let options = scene::motion::MotionOptions {
            plan_only: true,
            ..Default::default()
        };
        let sinks = &mut mechdiff::stream::motion::MotionSinks::default();
        let planned = scene::motion::run_with(&scene, sinks, &options)?;
        let _ = write!(out, "{}", planned.plan);
    }
    if let Some(study) = &study {
        let _ = writeln!(out, "{}", study.describe(&checked.columns));
    }
    if let Some(synthesis) = &synthesis {
        let _ = writeln!(out, "{}", scene::synthesize::describe(synthesis));
    }
    if let Some(metrics) = scene::metrics::SceneMetrics::of(&scene)? {
        for line in metrics.lines(&scene) {
            let _ = writeln!(out, "{line}");
        }
    }
    print!("{}", escape::terminal(&out));
    Ok(())
}

/// Prints a checked cam scene's summary (the scene was read whole: every error a run gives
/// before its report was given by the reader).
fn check_cam(cam: &CamScene) -> Result<(), Error> {
    let m = &cam.mechanism;
    let line = format!(
        "{}: ok: cam program of {} segment(s) over 360°, {} follower",
        cam.file,
        m.program.len(),
        m.dimensions.follower.describe()
    );
    println!("{}", escape::terminal(&line));
    Ok(())
}
