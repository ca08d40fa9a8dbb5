//! Rotor scenes (`scenes/rotor_balancing.toml`) in the accuracy report.
//!
//! A rotor has no drive sweep and nothing to differentiate, so there is no method table: no
//! derivative method applies, and there is one way to compute each answer. What can still be
//! measured is what the user relies on: how many digits of each balancing answer (the
//! correction's mass·radius and angle, the two-plane corrections, the couple plane) the `f64`
//! arithmetic keeps. Each answer is computed as `mechdiff run` computes it, and again by the
//! same generic code of the engine ([`Rotor::resultant_force_in`],
//! [`Rotor::two_plane_vectors_in`], [`Rotor::couple_plane_in`]) in double-double
//! ([`DoubleDouble`], ≈ 32 digits) from the same `f64` inputs; the error is relative to the
//! reference's magnitude (absolute, in rad, for an angle), and digits lost = log₁₀(error /
//! ε).
//!
//! A polygon that closes in exact arithmetic (a statically balanced rotor's force polygon)
//! leaves a gap of rounding noise: its correction is then below 1e-12 of the polygon's
//! largest term ([`Rotor::NEGLIGIBLE`]), flagged `negligible`, and its angle means nothing
//! (`mechdiff run` says so too); the rows are kept, with the reference showing the gap of
//! the `f64` inputs.

use std::fmt::Write as _;

use mechdiff_core::balancing::{Correction, Rotor};
use mechdiff_core::{atan2, hypot};

use super::EPSILON;
use super::double_double::DoubleDouble;
use crate::Error;
use crate::report::Table;
use crate::scene::balancing::RotorScene;
use crate::stream::record::csv_quoted;

/// One balancing answer in `f64` and in double-double.
#[derive(Clone, Debug, PartialEq)]
pub struct Answer {
    /// What it is ("two-plane correction, plane 1: m·r").
    pub name: String,
    /// Its unit ("kg·m", "rad", "m").
    pub unit: &'static str,
    /// The `f64` value `mechdiff run` prints.
    pub value: f64,
    /// The double-double reference.
    pub reference: DoubleDouble,
    /// Relative error (absolute for an angle, in rad).
    pub error: f64,
    /// Below [`Rotor::NEGLIGIBLE`] of its polygon's largest term: rounding noise.
    pub negligible: bool,
}

impl Answer {
    /// log₁₀(error / ε), at least 0.
    pub fn digits_lost(&self) -> f64 {
        (self.error / EPSILON).log10().max(0.0)
    }
}

/// The rotor's accuracy report: every balancing answer against its double-double value.
#[derive(Clone, Debug, PartialEq)]
pub struct RotorReport {
    /// The scene's title.
    pub title: String,
    /// The answers, in the order `mechdiff run` prints them.
    pub answers: Vec<Answer>,
}

/// Magnitude and angle of a mass-radius vector in double-double.
fn polar(v: [DoubleDouble; 2]) -> [DoubleDouble; 2] {
    [hypot(v[0], v[1]), atan2(v[1], v[0])]
}

/// The two rows (m·r, angle) of one correction.
fn rows(
    what: &str,
    correction: &Correction,
    reference: [DoubleDouble; 2],
    polygon_scale: f64,
) -> [Answer; 2] {
    let negligible = reference[0].hi.abs() <= Rotor::NEGLIGIBLE * polygon_scale;
    let magnitude = Answer {
        name: format!("{what}: m·r"),
        unit: "kg·m",
        value: correction.mass_radius,
        reference: reference[0],
        error: reference[0].error(correction.mass_radius) / reference[0].hi.abs(),
        negligible,
    };
    // Angles compared on the reference's turn (atan2 in (−π, π] both: a difference of 2π
    // only where both are at ±π).
    let angle = correction.angle;
    let turned =
        angle - std::f64::consts::TAU * ((angle - reference[1].hi) / std::f64::consts::TAU).round();
    let angle = Answer {
        name: format!("{what}: angle"),
        unit: "rad",
        value: correction.angle,
        reference: reference[1],
        error: reference[1].error(turned),
        negligible,
    };
    [magnitude, angle]
}

/// The report of a rotor scene (see the module's documentation).
///
/// # Errors
/// The scene's own errors (coincident planes, no couple to cancel), located at `[rotor]`.
pub fn report(scene: &RotorScene) -> Result<RotorReport, Error> {
    let r = &scene.rotor;
    let answers = r.answers()?;
    let rotor = &r.rotor;
    let [force_scale, couple_scale] = answers.scale;
    let mut out = Vec::new();
    let static_dd = rotor.resultant_force_in::<DoubleDouble>().map(|x| -x);
    out.extend(rows(
        "static correction",
        &answers.static_balance,
        polar(static_dd),
        force_scale,
    ));
    if let (Some(two), Some([left, right])) = (&answers.two_plane, r.planes) {
        let [in_left, in_right] = rotor.two_plane_vectors_in::<DoubleDouble>(left, right);
        // The corrections' scale: the couple polygon's largest term over the planes' gap.
        let scale = couple_scale / (right - left).abs();
        out.extend(rows(
            "two-plane correction, plane 1",
            &two.left,
            polar(in_left),
            scale,
        ));
        out.extend(rows(
            "two-plane correction, plane 2",
            &two.right,
            polar(in_right),
            scale,
        ));
    }
    if let (Some(plane), Some(mass_radius)) = (&answers.couple_plane, r.couple_mass_radius) {
        let (distance, vector) = rotor.couple_plane_in::<DoubleDouble>(mass_radius, r.reference);
        out.push(Answer {
            name: "couple plane: distance from the reference plane".into(),
            unit: "m",
            value: plane.distance,
            reference: distance,
            error: distance.error(plane.distance) / distance.hi.abs(),
            negligible: false,
        });
        let [_, angle] = rows(
            "couple plane correction",
            &plane.correction,
            polar(vector),
            couple_scale,
        );
        out.push(angle);
    }
    Ok(RotorReport {
        title: scene.title.clone().unwrap_or_else(|| scene.file.clone()),
        answers: out,
    })
}

impl RotorReport {
    /// The aligned table, with the lines that say what was measured and why there is no
    /// method table.
    pub fn table(&self) -> String {
        let mut table = Table::new(
            1,
            [
                "answer",
                "unit",
                "f64",
                "double-double",
                "error",
                "digits lost",
                "note",
            ]
            .map(String::from)
            .to_vec(),
        );
        for a in &self.answers {
            table.row(vec![
                a.name.clone(),
                a.unit.to_owned(),
                format!("{:.17e}", a.value),
                format!("{:.17e}", a.reference.hi),
                format!("{:.1e}", a.error),
                format!("{:.1}", a.digits_lost()),
                if a.negligible {
                    "negligible: rounding noise of a closed polygon, its angle means nothing"
                        .to_owned()
                } else {
                    String::new()
                },
            ]);
        }
        let mut out = format!(
            "{}: the balancing answers in f64 against the same computation in double-double\n  \
             no method table: a rotor has no drive sweep and no derivatives, so no derivative \
             method applies and nothing is timed\n  error: relative to the reference (absolute, \
             rad, for an angle); digits lost: log10(error / 2.2e-16)\n\n",
            self.title
        );
        out.push_str(&table.render());
        out
    }

    /// The answers as CSV: name, unit, f64 value, reference, error, digits lost, negligible.
    pub fn csv(&self) -> String {
        let mut out = String::from("answer,unit,value,reference,error,digits_lost,negligible\n");
        for a in &self.answers {
            let _ = writeln!(
                out,
                "{},{},{:e},{:e},{:e},{},{}",
                csv_quoted(&a.name),
                a.unit,
                a.value,
                a.reference.hi,
                a.error,
                a.digits_lost(),
                a.negligible
            );
        }
        out
    }
}
