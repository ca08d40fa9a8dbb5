//! The HTML report of a rotor scene (`mechdiff run rotor.toml --report rotor.html`): the force
//! polygon (m r) as the drawing, the couple polygon (m r d) beside it, both closed by the
//! corrections, the magnitude of every row of the answers in the table and the printed
//! report under it. A rotor has no drive: the page has one frame and no playback.

use super::{Column, Page};
use crate::error::Result;
use crate::pictures::balancing::rotor_polygons;
use crate::scene::balancing::RotorScene;

/// The rotor report as a self-contained HTML page.
pub fn html(scene: &RotorScene) -> Result<String> {
    let answers = scene.rotor.answers()?;
    let (header, rows) = crate::report::rotor::table(scene, &answers);
    let [force, couple] = rotor_polygons(&scene.rotor)?;
    let at = |name: &str| header.iter().position(|h| h.starts_with(name));
    let mut columns = Vec::new();
    let mut values = Vec::new();
    for row in &rows {
        let name = match row[1].as_str() {
            "" => row[0].clone(),
            index => format!("{} {index}", row[0]),
        };
        for (what, unit) in [("m r [", "kg m"), ("m r d [", "kg m²")] {
            let Some(cell) = at(what).and_then(|c| row.get(c)) else {
                continue;
            };
            if cell.is_empty() {
                continue;
            }
            columns.push(Column {
                name: format!("{name}: {}", what.trim_end_matches(" [")),
                unit: unit.to_owned(),
            });
            values.push(cell.parse::<f64>().unwrap_or(f64::NAN));
        }
    }
    Ok(Page {
        title: scene.title.clone().unwrap_or_else(|| scene.file.clone()),
        notes: vec![scene.lines()?.join("\n")],
        drawing: force.to_svg(),
        diagram: Some(couple.to_svg()),
        drive: "—".to_owned(),
        columns,
        values: vec![values],
        points: vec!["0".to_owned()],
        xy: vec![vec![[0.0, 0.0]]],
        rotation: None,
        rate: None,
        arrows: Vec::new(),
    }
    .html())
}

/// Writes the rotor report to `path`.
pub fn write(scene: &RotorScene, path: &std::path::Path) -> Result<()> {
    crate::pictures::write_file(path, html(scene)?.as_bytes())
}
