//! The CSV file of a rotor's answers (`mechdiff run rotor.toml --csv FILE`).
//!
//! One row per answer, in this order, with the same 13 columns:
//!
//! | `row` | `index` | what the row is |
//! |---|---|---|
//! | `mass` | 1, 2, … | a mass of `[rotor] masses`, in file order |
//! | `resultant` | | the polygons' gaps `Σ Uᵢ`, `Σ Uᵢ (zᵢ − z₀)` |
//! | `static` | | the static correction `−Σ Uᵢ`, in the reference plane |
//! | `two_plane` | 1, 2 | the corrections in the two `planes` (if given) |
//! | `couple_plane` | | the one mass of `couple_mass_radius` that cancels the couple (if given) |
//! | `couple_plane_gap` | | the force polygon's gap with that mass added |
//!
//! Columns: `row,index,plane [L],mass [kg],radius [L],m r x [kg m],m r y [kg m],m r [kg m],
//! m r angle [A],m r d x [kg m^2],m r d y [kg m^2],m r d [kg m^2],m r d angle [A]`, `L` and
//! `A` the scene's length and angle units; m r and m r d are always in kg m and kg m² (as
//! printed). `m r d` is the row's couple about the reference plane, `m r (z − z₀)`. The
//! `mass` and `radius` of a correction are given with `correction_radius` (mass = m r /
//! radius). An angle is empty where its vector is rounding noise (at most 1e-12 of the
//! polygon's largest term, as in the printed report); `plane`, `mass`, `radius` and the
//! m r d cells are empty where they do not apply. Numbers have the fewest digits that
//! read back as the same `f64` (an exponent below 1e-6 and from 1e15).

use std::io::{self, Write};

use mechdiff_core::balancing::{Correction, Rotor};

use crate::scene::balancing::{RotorAnswers, RotorScene};
use crate::scene::units::{Dimension, Units};

/// One row: its name, index, plane (m), mass (kg), radius (m), m r and m r d vectors, and
/// the scales below which each vector is noise.
struct Row {
    name: &'static str,
    index: Option<usize>,
    plane: Option<f64>,
    mass_radius: Option<(f64, f64)>,
    force: [f64; 2],
    couple: Option<[f64; 2]>,
    scale: [f64; 2],
}

/// `x` with the fewest digits that read back as the same `f64`: plain from 1e-6 to 1e15,
/// with an exponent outside (`2.0816681711721685e-17`, not 17 zeros).
fn number(x: f64) -> String {
    let x = x + 0.0;
    if x == 0.0 || (1e-6..1e15).contains(&x.abs()) {
        x.to_string()
    } else {
        format!("{x:e}")
    }
}

fn cells(units: &Units, v: [f64; 2], scale: f64) -> [String; 4] {
    let size = v[0].hypot(v[1]);
    let angle = if size <= Rotor::NEGLIGIBLE * scale {
        String::new()
    } else {
        number(units.from_si(v[1].atan2(v[0]), Dimension::Angle))
    };
    [number(v[0]), number(v[1]), number(size), angle]
}

/// Writes the rotor's answers as CSV (layout in the module documentation).
pub fn write_csv(
    scene: &RotorScene,
    answers: &RotorAnswers,
    out: &mut impl Write,
) -> io::Result<()> {
    let (header, rows) = table(scene, answers);
    writeln!(out, "{}", header.join(","))?;
    for row in rows {
        writeln!(out, "{}", row.join(","))?;
    }
    Ok(())
}

/// Writes the rotor's answers as JSON (`--json`): `{"file", "title", "rows"}`, `rows` one
/// object per CSV row keyed by the CSV's headers, numbers as numbers, empty cells `null`.
pub fn write_json(
    scene: &RotorScene,
    answers: &RotorAnswers,
    out: &mut impl Write,
) -> io::Result<()> {
    let (header, rows) = table(scene, answers);
    let rows: Vec<serde_json::Map<String, serde_json::Value>> = rows
        .into_iter()
        .map(|row| {
            header
                .iter()
                .zip(row)
                .map(|(key, cell)| {
                    let value = if cell.is_empty() {
                        serde_json::Value::Null
                    } else if let Some(n) = cell
                        .parse::<f64>()
                        .ok()
                        .and_then(serde_json::Number::from_f64)
                    {
                        serde_json::Value::Number(n)
                    } else {
                        serde_json::Value::String(cell)
                    };
                    (key.clone(), value)
                })
                .collect()
        })
        .collect();
    let json = serde_json::json!({
        "file": scene.file,
        "title": scene.title,
        "rows": rows,
    });
    serde_json::to_writer_pretty(&mut *out, &json)?;
    writeln!(out)
}

/// The header and the cells of the CSV (layout in the module documentation).
pub(crate) fn table(scene: &RotorScene, answers: &RotorAnswers) -> (Vec<String>, Vec<Vec<String>>) {
    let u = &scene.units;
    let (length, angle) = (u.symbol(Dimension::Length), u.symbol(Dimension::Angle));
    let header = format!(
        "row,index,plane [{length}],mass [kg],radius [{length}],m r x [kg m],m r y [kg m],\
         m r [kg m],m r angle [{angle}],m r d x [kg m^2],m r d y [kg m^2],m r d [kg m^2],\
         m r d angle [{angle}]"
    )
    .split(',')
    .map(str::to_owned)
    .collect();
    let r = &scene.rotor;
    let couple = |c: &Correction| {
        [
            c.vector[0] * (c.axial - r.reference),
            c.vector[1] * (c.axial - r.reference),
        ]
    };
    let correction = |name, index, c: &Correction| Row {
        name,
        index,
        plane: Some(c.axial),
        mass_radius: r
            .correction_radius
            .map(|radius| (c.mass_radius / radius, radius)),
        force: c.vector,
        couple: Some(couple(c)),
        scale: answers.scale,
    };
    let mut rows = Vec::new();
    let p = &answers.polygons;
    for (i, m) in r.rotor.masses().iter().enumerate() {
        rows.push(Row {
            name: "mass",
            index: Some(i + 1),
            plane: Some(m.axial),
            mass_radius: Some((m.mass, m.radius)),
            force: p.force[i],
            couple: Some(p.couple[i]),
            scale: answers.scale,
        });
    }
    rows.push(Row {
        name: "resultant",
        index: None,
        plane: None,
        mass_radius: None,
        force: answers.resultant[0],
        couple: Some(answers.resultant[1]),
        scale: answers.scale,
    });
    rows.push(correction("static", None, &answers.static_balance));
    if let Some(two) = &answers.two_plane {
        for (k, c) in two.corrections().iter().enumerate() {
            rows.push(correction("two_plane", Some(k + 1), c));
        }
    }
    if let (Some(c), Some(mr)) = (&answers.couple_plane, r.couple_mass_radius) {
        rows.push(correction("couple_plane", None, &c.correction));
        rows.push(Row {
            name: "couple_plane_gap",
            index: None,
            plane: None,
            mass_radius: None,
            force: c.force_after,
            couple: None,
            scale: [answers.scale[0].max(mr), answers.scale[1]],
        });
    }
    let mut lines = Vec::new();
    for row in rows {
        let mut line = vec![
            row.name.to_owned(),
            row.index.map_or_else(String::new, |i| i.to_string()),
            row.plane
                .map_or_else(String::new, |z| number(u.from_si(z, Dimension::Length))),
        ];
        match row.mass_radius {
            Some((mass, radius)) => {
                line.push(number(mass));
                line.push(number(u.from_si(radius, Dimension::Length)));
            }
            None => line.extend([String::new(), String::new()]),
        }
        line.extend(cells(u, row.force, row.scale[0]));
        match row.couple {
            Some(v) => line.extend(cells(u, v, row.scale[1])),
            None => line.extend(std::iter::repeat_n(String::new(), 4)),
        }
        lines.push(line);
    }
    (header, lines)
}
