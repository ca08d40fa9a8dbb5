//! The pictures of a cam scene: the SVAJ diagram (s, s′, s″, s‴ over the cam angle, segment
//! boundaries marked, each jump drawn as a gap between one-sided ends) and a drawing of the
//! cam profile with its follower (`mechdiff run cam.toml --plot DIR`).

use std::f64::consts::TAU;
use std::path::Path;

use mechdiff_core::cams::{Follower, Side};

use super::diagram::{Diagram, Marker, MarkerKind, Panel};
use super::drawing::{Drawing, Style};
use crate::error::Result;
use crate::scene::cam::CamScene;
use crate::scene::units::Dimension;

/// Points of the SVAJ curves over the turn.
const CURVE_POINTS: usize = 1440;
/// Points of the drawn profile and pitch curve.
const OUTLINE_POINTS: usize = 720;

/// The SVAJ diagram: one panel per derivative, in the scene's units.
pub fn svaj_diagram(scene: &CamScene) -> Diagram {
    let cam = &scene.mechanism;
    let u = &scene.units;
    let angle = u.symbol(Dimension::Angle);
    let dimension = scene.displacement_dimension();
    let (unit, k) = match dimension {
        Dimension::Angle => ("rad".to_owned(), 1.0),
        _ => (
            u.symbol(Dimension::Length).to_owned(),
            1.0 / u.factor(Dimension::Length),
        ),
    };
    let mut curves: [Vec<[f64; 2]>; 4] = Default::default();
    // The exact slopes of s, s′ and s″ in printed units (s‴'s would need s⁗).
    let mut slopes: [Vec<f64>; 3] = Default::default();
    let per_angle = u.factor(Dimension::Angle);
    let s_factor = u.factor(dimension);
    for (lo, hi) in cam.pieces() {
        let n = ((hi - lo) / TAU * CURVE_POINTS as f64).ceil().max(2.0) as usize;
        for i in 0..=n {
            let t = lo + (hi - lo) * i as f64 / n as f64;
            let side = if i == 0 { Side::Right } else { Side::Left };
            let j = cam.program.svaj(t, side);
            let x = u.from_si(t, Dimension::Angle);
            let values = [
                u.from_si(j.value, dimension),
                j.d1() * k,
                j.d2() * k,
                j.d3() * k,
            ];
            for (curve, v) in curves.iter_mut().zip(values) {
                curve.push([x, v]);
            }
            let exact = [
                j.d1() * per_angle / s_factor,
                j.d2() * k * per_angle,
                j.d3() * k * per_angle,
            ];
            for (slope, m) in slopes.iter_mut().zip(exact) {
                slope.push(m);
            }
        }
        // A gap between pieces: a jump is never drawn as a steep line.
        for curve in curves.iter_mut() {
            let x = u.from_si(hi, Dimension::Angle);
            curve.push([x, f64::NAN]);
        }
        for slope in slopes.iter_mut() {
            slope.push(f64::NAN);
        }
    }
    let [s, v, a, j] = curves;
    let [ds, dv, da] = slopes;
    let s_unit = if dimension == Dimension::Angle {
        angle.to_owned()
    } else {
        unit.clone()
    };
    let mut diagram = Diagram::new(
        scene.title.as_deref().unwrap_or("cam: follower motion"),
        &format!("cam angle θ [{angle}]"),
    )
    .panel(Panel::new(&format!("s [{s_unit}]")).series_with_slopes("s", s, ds))
    .panel(Panel::new(&format!("s′ [{unit}/rad]")).series_with_slopes("s′", v, dv))
    .panel(Panel::new(&format!("s″ [{unit}/rad²]")).series_with_slopes("s″", a, da))
    .panel(Panel::new(&format!("s‴ [{unit}/rad³]")).series("s‴", j));
    for index in 0..cam.program.len() {
        let x = u.from_si(cam.program.start(index), Dimension::Angle);
        diagram = diagram.marker(Marker::new(
            x,
            &format!("segment {}", index + 1),
            MarkerKind::Boundary,
        ));
    }
    diagram
}

/// The cam profile (filled), its base circle and pitch curve, and the follower in place at
/// cam angle `theta`, in the fixed frame (cam centre at the origin).
pub fn profile_drawing(scene: &CamScene, theta: f64) -> Drawing {
    let cam = &scene.mechanism;
    let to_unit = 1.0 / scene.units.factor(Dimension::Length);
    // The cam turned by θ: a cam-frame point X is R(θ)X in the fixed frame.
    let (sin, cos) = theta.sin_cos();
    let fixed = |p: [f64; 2]| {
        [
            (p[0] * cos - p[1] * sin) * to_unit,
            (p[0] * sin + p[1] * cos) * to_unit,
        ]
    };
    let outline = cam.outline(OUTLINE_POINTS);
    let profile: Vec<[f64; 2]> = outline.iter().map(|(_, _, p)| fixed(*p)).collect();
    let mut pitch: Vec<[f64; 2]> = outline.iter().map(|(_, p, _)| fixed(*p)).collect();
    pitch.push(pitch[0]);
    let contact = cam.contact(theta, Side::Right);
    let centre = fixed(contact.pitch);
    let touch = fixed(contact.profile);
    let dims = &cam.dimensions;
    let base = dims.base_radius * to_unit;
    let mut drawing = Drawing::new(scene.title.as_deref().unwrap_or("cam profile"))
        .polygon(&profile, Style::link().filled("#cfe2f3"))
        .circle([0.0, 0.0], base, Style::construction())
        .polyline(&pitch, Style::path())
        .ground([0.0, 0.0]);
    let (_, s_max) = cam.program.displacement_range();
    match dims.follower {
        Follower::KnifeEdge { offset } | Follower::Roller { offset, .. } => {
            let r = dims.follower.roller_radius() * to_unit;
            let top = [
                offset * to_unit,
                (dims.rest + s_max) * to_unit + 2.0 * r.max(base * 0.2),
            ];
            drawing = drawing.polyline(&[centre, top], Style::link());
            drawing = drawing.guide(
                [offset * to_unit - base * 0.15, top[1]],
                [offset * to_unit + base * 0.15, top[1]],
            );
            if r > 0.0 {
                drawing = drawing.circle(centre, r, Style::link());
            }
        }
        Follower::FlatFaced => {
            let analysis = cam.analyse();
            let (low, high) = analysis.face_extent.unwrap_or((-base * 0.3, base * 0.3));
            let margin = 0.1 * base / to_unit;
            let y = centre[1];
            drawing = drawing.polyline(
                &[
                    [(low - margin) * to_unit, y],
                    [(high + margin) * to_unit, y],
                ],
                Style::link(),
            );
            let top = [0.0, (dims.rest + s_max) * to_unit + 0.5 * base];
            drawing = drawing.polyline(&[[0.0, y], top], Style::link());
        }
        Follower::OscillatingRoller {
            pivot_distance,
            radius,
            ..
        } => {
            let pivot = [pivot_distance * to_unit, 0.0];
            drawing = drawing
                .polyline(&[pivot, centre], Style::link())
                .circle(centre, radius * to_unit, Style::link())
                .ground(pivot);
        }
    }
    drawing.joint("contact", touch).label(centre, "follower")
}

/// Writes `svaj.svg`, `svaj.png` (and `svaj_2.svg`, … when the diagram is higher than
/// [`super::diagram::MAX_HEIGHT`]), `profile.svg`, `profile.png` into `dir` (created if
/// missing).
pub fn write_dir(scene: &CamScene, dir: &Path) -> Result<()> {
    let pages = svaj_diagram(scene).named_pages("svaj");
    let mut names: Vec<String> = (pages.iter())
        .flat_map(|(stem, _)| [format!("{stem}.svg"), format!("{stem}.png")])
        .collect();
    names.extend(["profile.svg".to_owned(), "profile.png".to_owned()]);
    let paths: Vec<std::path::PathBuf> = names.iter().map(|name| dir.join(name)).collect();
    crate::files::refuse_inputs(paths.iter().map(std::path::PathBuf::as_path))?;
    crate::files::create_output_folder(dir)?;
    for (stem, page) in &pages {
        page.write_svg(&dir.join(format!("{stem}.svg")))?;
        page.write_png(&dir.join(format!("{stem}.png")))?;
    }
    let drawing = profile_drawing(scene, 0.0);
    drawing.write_svg(&dir.join("profile.svg"))?;
    drawing.write_png(&dir.join("profile.png"))
}
