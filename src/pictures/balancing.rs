//! Pictures of the balancing answers: a rotor's force (mr) and couple (mrd) polygons closed
//! by their corrections, and a linkage's shaking force locus before and after its
//! counterweights (with |ΣF| over the drive position).

use mechdiff_core::balancing::{Polygons, Rotor};

use crate::error::Result;
use crate::scene::balancing::SceneRotor;
use crate::scene::{Report, Scene};

use super::diagram::{Diagram, Panel, Polar, Series};
use super::drawing::{Drawing, Style};

/// Colour of the correction's sides.
const CORRECTION: &str = "#c0392b";

/// The balancing pictures of a run, as `(file stem, SVG)`: `rotor_force_polygon`,
/// `rotor_couple_polygon` for a `[rotor]`, `shaking_force_balancing` for `[balancing]`.
pub fn pictures(scene: &Scene, report: &Report) -> Result<Vec<(String, String)>> {
    let mut out = Vec::new();
    if let Some(r) = scene.balancing.as_ref().and_then(|b| b.rotor.as_ref()) {
        let [force, couple] = rotor_polygons(r)?;
        out.push(("rotor_force_polygon".to_owned(), force.to_svg()));
        out.push(("rotor_couple_polygon".to_owned(), couple.to_svg()));
    }
    if let Some(linkage) = report.balancing.as_ref().and_then(|b| b.linkage.as_ref()) {
        let drive = &report.columns[0];
        let phi: Vec<f64> = linkage
            .before
            .phi
            .iter()
            .map(|p| p / drive.factor)
            .collect();
        let magnitude = |f: &[[f64; 2]]| -> Vec<[f64; 2]> {
            phi.iter()
                .zip(f)
                .map(|(p, v)| [*p, v[0].hypot(v[1])])
                .collect()
        };
        let diagram = Diagram::new(
            "shaking force before and after the counterweights",
            &format!("φ [{}]", drive.unit),
        )
        .panel(
            Panel::new("|ΣF| [N]")
                .series("before", magnitude(&linkage.before.force))
                .series("after", magnitude(&linkage.after.force)),
        )
        .polar(Polar {
            title: "shaking force ΣF: locus of its tip".to_owned(),
            unit: "N".to_owned(),
            series: vec![
                Series::new("before", linkage.before.force.clone()),
                Series::new("after", linkage.after.force.clone()),
            ],
        });
        for (name, page) in diagram.named_pages("shaking_force_balancing") {
            out.push((name, page.to_svg()?));
        }
    }
    Ok(out)
}

/// Writes a rotor's polygons into `dir` (created if needed): `rotor_force_polygon.svg/png`
/// and `rotor_couple_polygon.svg/png`.
pub fn write_rotor_dir(r: &SceneRotor, dir: &std::path::Path) -> Result<()> {
    let names = ["rotor_force_polygon", "rotor_couple_polygon"];
    let paths: Vec<_> = names
        .iter()
        .flat_map(|name| ["svg", "png"].map(|ext| dir.join(format!("{name}.{ext}"))))
        .collect();
    crate::files::refuse_inputs(paths.iter().map(std::path::PathBuf::as_path))?;
    crate::files::create_output_folder(dir)?;
    let [force, couple] = rotor_polygons(r)?;
    for (name, drawing) in names.into_iter().zip([force, couple]) {
        drawing.write_svg(&dir.join(format!("{name}.svg")))?;
        drawing.write_png(&dir.join(format!("{name}.png")))?;
    }
    Ok(())
}

/// The force and couple polygons of a rotor, head to tail from the origin, closed by the
/// corrections: with two planes, both corrections close the force polygon and the second
/// closes the couple polygon taken about the first plane; otherwise the static correction
/// closes the force polygon and the couple polygon about the reference plane is left open
/// (its gap drawn dashed).
pub fn rotor_polygons(r: &SceneRotor) -> Result<[Drawing; 2]> {
    let rotor: &Rotor = &r.rotor;
    let (reference, corrections) = match r.planes {
        Some([left, right]) => {
            let two = rotor
                .two_plane_balance(left, right)
                .map_err(|e| crate::Error::Picture {
                    message: e.to_string(),
                })?;
            (left, two.corrections().to_vec())
        }
        None => (r.reference, vec![rotor.static_balance(r.reference)]),
    };
    let open = rotor.polygons(reference);
    let closed = rotor.with_corrections(&corrections).polygons(reference);
    let draw = |title: &str, sides: &[[f64; 2]], given: usize| {
        let vertices = Polygons::vertices(sides);
        let mut d = Drawing::new(title).size(600, 600);
        d = d.polyline(&vertices[..=given], Style::link());
        if vertices.len() > given + 1 {
            d = d.polyline(&vertices[given..], Style::stroke(CORRECTION, 2.5));
        }
        for (i, w) in vertices.windows(2).enumerate() {
            let mid = [(w[0][0] + w[1][0]) / 2.0, (w[0][1] + w[1][1]) / 2.0];
            let name = if i < given {
                format!("{}", i + 1)
            } else {
                format!("c{}", i + 1 - given)
            };
            d = d.label(mid, &name);
        }
        let end = *vertices.last().expect("one vertex");
        if end[0].hypot(end[1]) > 0.0 && vertices.len() > 1 {
            d = d.polyline(&[end, [0.0, 0.0]], Style::construction());
        }
        d.joint("0", [0.0, 0.0])
    };
    let n = open.force.len();
    Ok([
        draw(
            "rotor: force polygon m r [kg m], closed by the corrections (c)",
            &closed.force,
            n,
        ),
        draw(
            &format!(
                "rotor: couple polygon m r d [kg m²] about the plane at {} m",
                reference
            ),
            &closed.couple,
            n,
        ),
    ])
}
