//! `mechdiff check <scene.toml>`: validate a scene without running its sweep.

use std::path::PathBuf;

use clap::Args;
use mechdiff::Error;
use mechdiff::scene;

/// Arguments of `mechdiff check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    /// The scene file (TOML; see docs/scene-format.md).
    pub scene: PathBuf,
}

/// Reads the scene, builds its model and checks its mobility at the sketch pose; prints a
/// summary and the plan a run would carry out.
pub fn check(args: &CheckArgs) -> Result<(), Error> {
    match super::scene_kind(&args.scene) {
        scene::Kind::Cam => return check_cam(args),
        scene::Kind::Rotor => return super::rotor::check(args),
        scene::Kind::Linkage => {}
    }
    let scene = scene::load(&args.scene)?;
    let checked = scene::check(&scene)?;
    let m = &checked.mechanism;
    println!(
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
        println!(
            "loop {}: {} (branch certificate {branch:+} in the sketch; solved by {how})",
            k + 1,
            joints.join(", ")
        );
    }
    match &checked.motion_range {
        Ok(range) => println!(
            "drive motion range: {}",
            scene::run::describe_motion_range(&scene, range)
        ),
        Err(why) => println!("drive motion range: not found ({why})"),
    }
    println!("{}", checked.plan.describe(&scene));
    Ok(())
}

/// Checks a cam scene and prints its summary.
fn check_cam(args: &CheckArgs) -> Result<(), Error> {
    let cam = scene::cam::load(&args.scene)?;
    let m = &cam.mechanism;
    println!(
        "{}: ok: cam program of {} segment(s) over 360°, {} follower",
        cam.file,
        m.program.len(),
        m.dimensions.follower.describe()
    );
    Ok(())
}
