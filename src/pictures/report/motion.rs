//! The HTML report of a scene with `[simulate]` (`mechdiff run shaper_motor.toml --report
//! motion.html`): the machine moving as it really runs under its motor, played on the
//! simulated clock — the frame at time t shows the mechanism at the simulated φ(t), so one
//! second of playback at ×1 is one simulated second (a speed factor ×0.1…×10) — with ω(t)
//! and the motor's torque over t, and the steady state's ω(φ), each with a moving marker.
//!
//! The frames are the run's [`Playback`]: the motion over time (start-up, coast-down), then
//! one period of the steady state, at equal steps of simulated time on one clock (`clock`,
//! the first column; each motion's own time is `t`), at most
//! [`crate::scene::motion::PLAYBACK_FRAMES`] in all. The values at each frame are the
//! machine's state and the scene's outputs evaluated at that frame's φ and φ̇.
//!
//! The diagrams stand side by side under the mechanism from 760 to 1400 px (so that the
//! moving marker stays in view), one over the other otherwise. Each sits in an
//! element carrying `data-column` (the column its x axis shows),
//! `data-y-columns` (per panel, the column its curve shows) and `data-frames` (the frames
//! during which its marker moves): the page's script draws a cursor and a dot there.

use super::{Column, Page};
use crate::error::{Error, Result};
use crate::pictures::diagram::{Diagram, Panel};
use crate::pictures::scene::{Rig, poses, sketch_pose};
use crate::scene::Scene;
use crate::scene::build::mechanism;
use crate::scene::model::OutputKind;
use crate::scene::motion::{MotionReport, Playback};

/// The columns of a playback row: clock, t, φ, ω, α, M_motor (then M_drive, J, outputs).
const T: usize = 1;
const PHI: usize = 2;
const OMEGA: usize = 3;
const MOTOR: usize = 5;

/// The report of a run with `[simulate]` as a self-contained HTML page; `report` must have
/// its [`Playback`] (run with [`crate::scene::motion::MotionOptions::playback`]).
///
/// # Errors
/// A report without playback frames, a pose that cannot be solved, a diagram that cannot be
/// drawn.
pub fn html(scene: &Scene, report: &MotionReport) -> Result<String> {
    let title = scene.title.clone().unwrap_or_else(|| scene.file.clone());
    let playback = match &report.playback {
        Some(p) if !p.rows.is_empty() => p,
        _ => {
            return Err(Error::Invalid {
                location: scene.drive.location.clone(),
                message: "the run has no motion to play (no start-up, steady state or \
                          coast-down in `[simulate] find`)"
                    .to_owned(),
            });
        }
    };
    let m = mechanism(scene)?;
    // Each motion solved from the sketch in its own order (a steady period after a long
    // start-up starts again at its reference angle).
    let mut xy = Vec::with_capacity(playback.rows.len());
    for part in &playback.parts {
        let phi: Vec<f64> = playback.rows[part.frames.clone()]
            .iter()
            .map(|r| r[PHI])
            .collect();
        xy.extend(poses(scene, &m, &phi)?.xy);
    }
    let mut extent: Vec<[f64; 2]> = xy.iter().flatten().copied().collect();
    extent.extend(sketch_pose(scene));
    let index = |name: &str| scene.points.iter().position(|p| p.name == name);
    let traced: Vec<usize> = match &scene.plot.trace {
        Some(names) => names.iter().filter_map(|n| index(n)).collect(),
        None => (scene.outputs.iter())
            .filter_map(|o| match &o.kind {
                OutputKind::Point(p) => index(p),
                _ => None,
            })
            .collect(),
    };
    let paths: Vec<(usize, Vec<[f64; 2]>)> = traced
        .iter()
        .map(|&k| (k, xy.iter().map(|pose| pose[k]).collect()))
        .collect();
    let drawing = Rig::of(scene)
        .drawing(scene, &title, &xy[0], &extent, &paths)
        .to_svg();
    let columns = (playback.columns.iter())
        .map(|c| Column {
            name: c.name.clone(),
            unit: c.unit.clone(),
        })
        .collect();
    let values = (playback.rows.iter())
        .map(|r| {
            (r.iter().zip(&playback.columns))
                .map(|(v, c)| v / c.factor)
                .collect()
        })
        .collect();
    let mut notes = vec![report.plan.trim_end().to_owned(), report.summary.join("\n")];
    notes.push(clock_note(playback));
    Ok(Page {
        title,
        notes,
        drawing,
        diagram: Some(diagrams(report, playback)?),
        drive: "clock".to_owned(),
        columns,
        values,
        points: scene.points.iter().map(|p| p.name.clone()).collect(),
        xy,
        rotation: None,
        // The clock's seconds per second at ×1: real time.
        rate: Some(1.0),
        arrows: Vec::new(),
    }
    .html())
}

/// What the clock plays, in words.
fn clock_note(playback: &Playback) -> String {
    let mut out = format!(
        "Playback on the simulated clock: ×1 plays one simulated second per second; a frame \
         every {} s of simulated time.",
        crate::scene::units::Units::tidy(playback.step)
    );
    for part in &playback.parts {
        let (a, b) = (part.frames.start, part.frames.end.saturating_sub(1));
        out.push_str(&format!(
            "\nframes {a} to {b}: {} (clock {} s to {} s)",
            part.name,
            crate::scene::units::Units::tidy(playback.rows[a][0]),
            crate::scene::units::Units::tidy(playback.rows[b][0]),
        ));
    }
    out
}

/// The diagrams with their markers' columns: ω and the motor's torque over t during the
/// motion over time, ω over φ during the steady period.
fn diagrams(report: &MotionReport, playback: &Playback) -> Result<String> {
    let c = &report.curves;
    let [time, angle, speed, torque] = &c.labels;
    let part = |name: &str| playback.parts.iter().find(|p| p.name.contains(name));
    let mut out = String::from("<div class=\"motion-diagrams\">\n");
    let mut holder = |diagram: Diagram, x: usize, ys: &[usize], frames: &std::ops::Range<usize>| {
        let ys: Vec<String> = ys.iter().map(usize::to_string).collect();
        diagram.to_svg().map(|svg| {
            out.push_str(&format!(
                "<div class=\"motion-diagram\" data-column=\"{x}\" data-y-columns=\"{}\" \
                 data-frames=\"{} {}\">{svg}</div>\n",
                ys.join(" "),
                frames.start,
                frames.end
            ));
        })
    };
    if let Some(p) = part("start-up").or_else(|| part("coast-down"))
        && !c.omega_time.points.is_empty()
    {
        let d = Diagram::new("speed and motor torque over time", time)
            .panel(Panel::new(speed).series("omega", c.omega_time.points.clone()))
            .panel(Panel::new(torque).series("M_motor", c.motor_torque.points.clone()));
        holder(d, T, &[OMEGA, MOTOR], &p.frames)?;
    }
    if let Some(p) = part("steady")
        && !c.omega_angle.points.is_empty()
    {
        let d = Diagram::new("steady-state speed over one turn", angle)
            .panel(Panel::new(speed).series("omega", c.omega_angle.points.clone()));
        holder(d, PHI, &[OMEGA], &p.frames)?;
    }
    out.push_str("</div>");
    Ok(out)
}

/// Writes the report of a run with `[simulate]` to `path`.
///
/// # Errors
/// As [`html`], and the file's write error.
pub fn write(scene: &Scene, report: &MotionReport, path: &std::path::Path) -> Result<()> {
    crate::pictures::write_file(path, html(scene, report)?.as_bytes())
}
