//! The HTML report of a cam scene (`mechdiff run cam.toml --report cam.html`): the cam turning
//! and the follower moving with it over one turn, the SVAJ diagram with a cursor at the cam
//! angle, and s, s′, s″, s‴ and the pressure angle there. Built on the same [`Page`] as a
//! linkage's report: the profile and pitch curve are drawn once and turned about the cam's
//! centre per frame; the follower's points move to the positions the cam's contact puts them.

use std::f64::consts::TAU;

use mechdiff_core::cams::{Follower, Side};

use super::{Column, Page};
use crate::error::Result;
use crate::pictures::drawing::{Drawing, Style};
use crate::scene::cam::CamScene;
use crate::scene::units::Dimension;

/// Frames over the turn: one every half degree.
pub const FRAMES: usize = 721;
/// Points of the drawn profile and pitch curve.
const OUTLINE_POINTS: usize = 720;

/// The points of the drawing at cam angle `theta` (rad), in the file's length unit, fixed
/// frame (cam centre at the origin): 0 the cam centre, 1 the follower's reference point
/// (roller centre, knife edge, foot of the face), 2 the contact on the profile, 3 the
/// follower's far end (its guide's top, or the oscillating arm's pivot), and for a flat face
/// 4 and 5 the face's ends.
pub fn points(scene: &CamScene, theta: f64) -> Vec<[f64; 2]> {
    let cam = &scene.mechanism;
    let to_unit = 1.0 / scene.units.factor(Dimension::Length);
    let (sin, cos) = theta.sin_cos();
    let fixed = |p: [f64; 2]| {
        [
            (p[0] * cos - p[1] * sin) * to_unit,
            (p[0] * sin + p[1] * cos) * to_unit,
        ]
    };
    let contact = cam.contact(theta, Side::Right);
    let centre = fixed(contact.pitch);
    let dims = &cam.dimensions;
    let base = dims.base_radius * to_unit;
    let (_, s_max) = cam.program.displacement_range();
    let mut out = vec![[0.0, 0.0], centre, fixed(contact.profile)];
    match dims.follower {
        Follower::KnifeEdge { offset } | Follower::Roller { offset, .. } => {
            let r = dims.follower.roller_radius() * to_unit;
            out.push([
                offset * to_unit,
                (dims.rest + s_max) * to_unit + 2.0 * r.max(base * 0.2),
            ]);
        }
        Follower::FlatFaced => {
            out.push([0.0, (dims.rest + s_max) * to_unit + 0.5 * base]);
            let (low, high) = cam
                .analyse()
                .face_extent
                .unwrap_or((-0.3 * dims.base_radius, 0.3 * dims.base_radius));
            let margin = 0.1 * dims.base_radius;
            out.push([(low - margin) * to_unit, centre[1]]);
            out.push([(high + margin) * to_unit, centre[1]]);
        }
        Follower::OscillatingRoller { pivot_distance, .. } => {
            out.push([pivot_distance * to_unit, 0.0]);
        }
    }
    out
}

/// The drawing at cam angle 0 with its shapes bound to [`points`] (the profile and pitch
/// curve to the frame's turn about point 0), framed to hold every frame's points and the
/// turning profile.
fn drawing(scene: &CamScene, poses: &[Vec<[f64; 2]>]) -> Drawing {
    let cam = &scene.mechanism;
    let to_unit = 1.0 / scene.units.factor(Dimension::Length);
    let outline = cam.outline(OUTLINE_POINTS);
    let scaled = |p: [f64; 2]| [p[0] * to_unit, p[1] * to_unit];
    let profile: Vec<[f64; 2]> = outline.iter().map(|(_, _, p)| scaled(*p)).collect();
    let mut pitch: Vec<[f64; 2]> = outline.iter().map(|(_, p, _)| scaled(*p)).collect();
    pitch.push(pitch[0]);
    // The profile turns: frame the circle that holds it at every angle.
    let reach = profile
        .iter()
        .chain(&pitch)
        .map(|p| p[0].hypot(p[1]))
        .fold(0.0, f64::max);
    let ring: Vec<[f64; 2]> = (0..16)
        .map(|k| {
            let a = TAU * k as f64 / 16.0;
            [reach * a.cos() / 0.98, reach * a.sin() / 0.98]
        })
        .collect();
    let all: Vec<[f64; 2]> = poses.iter().flatten().copied().chain(ring).collect();
    let pose = &poses[0];
    let dims = &cam.dimensions;
    let base = dims.base_radius * to_unit;
    let mut d = Drawing::new(scene.title.as_deref().unwrap_or("cam and follower"))
        .unit(scene.units.symbol(Dimension::Length), 1.0)
        .include(&all)
        .polygon(&profile, Style::link().filled("#cfe2f3"))
        .bind("r 0")
        .circle([0.0, 0.0], base, Style::construction())
        .polyline(&pitch, Style::path())
        .bind("r 0")
        .ground([0.0, 0.0]);
    match dims.follower {
        Follower::KnifeEdge { offset } | Follower::Roller { offset, .. } => {
            let top = pose[3];
            d = d
                .polyline(&[pose[1], top], Style::link())
                .bind("p 1 3")
                .guide(
                    [offset * to_unit - base * 0.15, top[1]],
                    [offset * to_unit + base * 0.15, top[1]],
                );
            let r = dims.follower.roller_radius() * to_unit;
            if r > 0.0 {
                d = d.circle(pose[1], r, Style::link()).bind("c 1");
            }
        }
        Follower::FlatFaced => {
            d = d
                .polyline(&[pose[4], pose[5]], Style::link())
                .bind("p 4 5")
                .polyline(&[pose[1], pose[3]], Style::link())
                .bind("p 1 3");
        }
        Follower::OscillatingRoller { radius, .. } => {
            d = d
                .polyline(&[pose[3], pose[1]], Style::link())
                .bind("p 3 1")
                .circle(pose[1], radius * to_unit, Style::link())
                .bind("c 1")
                .ground(pose[3]);
        }
    }
    d.joint("contact", pose[2])
        .bind("c 2")
        .label(pose[1], "follower")
        .bind("t 1")
}

/// The cam report as a self-contained HTML page.
pub fn html(scene: &CamScene) -> Result<String> {
    let cam = &scene.mechanism;
    let u = &scene.units;
    let dimension = scene.displacement_dimension();
    let angle = u.symbol(Dimension::Angle).to_owned();
    let (unit, k) = match dimension {
        Dimension::Angle => ("rad".to_owned(), 1.0),
        _ => (
            u.symbol(Dimension::Length).to_owned(),
            1.0 / u.factor(Dimension::Length),
        ),
    };
    let s_unit = if dimension == Dimension::Angle {
        angle.clone()
    } else {
        unit.clone()
    };
    let column = |name: &str, unit: &str| Column {
        name: name.to_owned(),
        unit: unit.to_owned(),
    };
    let columns = vec![
        column("θ", &angle),
        column("s", &s_unit),
        column("s′", &format!("{unit}/rad")),
        column("s″", &format!("{unit}/rad²")),
        column("s‴", &format!("{unit}/rad³")),
        column("pressure angle", &angle),
    ];
    let thetas: Vec<f64> = (0..FRAMES)
        .map(|i| TAU * i as f64 / (FRAMES - 1) as f64)
        .collect();
    let values = thetas
        .iter()
        .map(|&t| {
            let j = cam.program.svaj(t, Side::Right);
            let contact = cam.contact(t, Side::Right);
            vec![
                u.from_si(t, Dimension::Angle),
                u.from_si(j.value, dimension),
                j.d1() * k,
                j.d2() * k,
                j.d3() * k,
                u.from_si(contact.pressure_angle, Dimension::Angle),
            ]
        })
        .collect();
    let xy: Vec<Vec<[f64; 2]>> = thetas.iter().map(|&t| points(scene, t)).collect();
    let diagram = crate::pictures::cam::svaj_diagram(scene).to_svg()?;
    let speed = scene.drive.omega;
    Ok(Page {
        title: scene.title.clone().unwrap_or_else(|| scene.file.clone()),
        notes: vec![format!(
            "{} segment(s) over one turn; the follower's positions, the contact and the \
             pressure angle at each frame are the cam's own (mechdiff-core's cams)",
            cam.program.len()
        )],
        drawing: drawing(scene, &xy).to_svg(),
        diagram: Some(diagram),
        drive: "θ".to_owned(),
        columns,
        values,
        points: [
            "cam centre",
            "follower",
            "contact",
            "follower end",
            "face 1",
            "face 2",
        ]
        .iter()
        .take(xy[0].len())
        .map(|s| (*s).to_owned())
        .collect(),
        xy,
        rotation: Some(thetas),
        rate: (speed != 0.0).then(|| u.from_si(speed.abs(), Dimension::Angle)),
        arrows: Vec::new(),
    }
    .html())
}

/// Writes the cam report to `path`.
pub fn write(scene: &CamScene, path: &std::path::Path) -> Result<()> {
    crate::pictures::write_file(path, html(scene)?.as_bytes())
}
