//! The diagrams of a run with `[simulate]`: ω(t), the motor's torque over t, and ω(φ) at the
//! steady state, each its own SVG file, drawn from the curves the run thinned as it went.

use std::path::{Path, PathBuf};

use crate::error::Result;
use crate::scene::motion::MotionReport;

use super::diagram::{Diagram, Panel};

/// The diagrams of `report` with a title `title`, each with its file name (empty curves
/// are left out).
pub fn diagrams(title: &str, report: &MotionReport) -> Vec<(&'static str, Diagram)> {
    let c = &report.curves;
    let [time, angle, speed, torque] = &c.labels;
    let mut out = Vec::new();
    if !c.omega_time.points.is_empty() {
        out.push((
            "omega_time.svg",
            Diagram::new(&format!("{title}: speed over time"), time)
                .panel(Panel::new(speed).series("omega", c.omega_time.points.clone())),
        ));
        out.push((
            "motor_torque.svg",
            Diagram::new(&format!("{title}: motor torque over time"), time)
                .panel(Panel::new(torque).series("M_motor", c.motor_torque.points.clone())),
        ));
    }
    if !c.omega_angle.points.is_empty() {
        out.push((
            "omega_angle.svg",
            Diagram::new(&format!("{title}: steady-state speed over one turn"), angle)
                .panel(Panel::new(speed).series("omega", c.omega_angle.points.clone())),
        ));
    }
    out
}

/// Writes the diagrams of `report` into `dir` (created if missing); returns the files.
///
/// # Errors
/// The folder's or a file's write error, or a diagram that cannot be drawn.
pub fn write_dir(title: &str, report: &MotionReport, dir: &Path) -> Result<Vec<PathBuf>> {
    let diagrams = diagrams(title, report);
    let written: Vec<PathBuf> = diagrams.iter().map(|(name, _)| dir.join(name)).collect();
    // As every `--plot` folder: no picture lands on a file the run read.
    crate::files::refuse_inputs(written.iter().map(PathBuf::as_path))?;
    crate::files::create_output_folder(dir)?;
    for ((_, diagram), path) in diagrams.iter().zip(&written) {
        diagram.write_svg(path)?;
    }
    Ok(written)
}
