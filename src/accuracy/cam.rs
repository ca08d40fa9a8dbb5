//! Cam scenes (`scenes/cams/*.toml`) in the accuracy report: the follower's displacement s(θ)
//! and its cam-angle derivatives s′, s″, s‴ over the scene's table, by every derivative
//! method, against the cam program evaluated in double-double.
//!
//! | method | order | what runs |
//! |---|---|---|
//! | Dual1, Dual2, HyperDual, Dual3 | 1, 2, 2, 3 | the program's displacement (written once, generic over the scalar) in num-dual numbers |
//! | central, forward, Richardson | 3 | differences of the displacement in `f64` |
//!
//! **Reference.** The same generic displacement ([`CamProgram::displacement`]: the motion
//! laws, or a segment's formula) evaluated in `Dual3<DoubleDouble>` at the exact `f64` cam
//! angle: value and derivatives from higher-precision arithmetic and forward-mode
//! differentiation. The laws' constants (π, 2π, a lift, an extent) are the `f64` numbers
//! every method uses, so the reference is the program the methods evaluate, exactly.
//!
//! **Joints.** At a segment boundary, and at a break inside a piecewise law (parabolic,
//! modified trapezoidal, modified sine), s′, s″ or s‴ may jump. There the reference and every
//! exact method take the same one-sided value, the right-hand limit (the segment or piece
//! that starts there, as the program's default); a finite difference's stencil straddles
//! the jump, so its error at the orders that jump is not counted at those positions
//! ([`Case::jumps`]; the report's notes list them): a jump is the cam's, not a method's
//! error.

use std::f64::consts::TAU;

use mechdiff_core::cams::{CamProgram, ContinuityReport, Side};
use mechdiff_core::jet::Jet;
use mechdiff_core::method::{Differentiator, Dual1, Dual2, Dual3, HyperDual};
use mechdiff_core::num_dual::Dual3 as Dual3Number;

use super::double_double::DoubleDouble;
use super::{Case, MAX_ORDER, Method, Values};
use crate::Error;
use crate::scene::cam::CamScene;
use crate::scene::units::Dimension;

/// An angle within this of a boundary is at it (the tolerance of the cam report's table).
const AT_JOINT: f64 = 1e-9;

/// The cam angles of the scene's table: every `step` from 0 to 360° inclusive.
fn positions(scene: &CamScene) -> Vec<f64> {
    let count = (TAU / scene.step + 1e-9).floor() as usize;
    (0..=count)
        .map(|k| (k as f64 * scene.step).min(TAU))
        .collect()
}

/// An angle in degrees for the notes, rounded to 1e-9° (120°, not 119.99999999999999°).
fn degrees(radians: f64) -> f64 {
    (radians.to_degrees() * 1e9).round() / 1e9
}

/// A jet of any order as the report's values (NaN above its order).
fn values<const N: usize>(jet: Jet<N>, out: &mut Values) {
    *out = [f64::NAN; MAX_ORDER + 1];
    out[0] = jet.value;
    out[1..=N].copy_from_slice(&jet.derivatives);
}

/// The method `name` of order `N`: `differentiator` applied to the program.
fn method<'a, D, const N: usize>(name: &str, program: &'a CamProgram, d: D) -> Method<'a>
where
    D: Differentiator<CamProgram, N> + 'a,
{
    Method::exact(name, N, move |theta, out: &mut [Values]| {
        values(d.jets(program, theta), &mut out[0]);
        Ok(())
    })
}

/// The accuracy case of a cam scene (see the module's documentation), at no more than
/// `count` of the table's positions (every k-th, the last kept: [`super::thin`]) if given.
///
/// # Errors
/// [`Error::Reference`] if the reference is not finite at a position (a formula segment
/// that does not evaluate there), naming the cam angle.
pub fn case(scene: &CamScene, count: Option<usize>) -> Result<Case<'_>, Error> {
    let program = &scene.mechanism.program;
    let mut positions = positions(scene);
    let all = positions.len();
    if let Some(count) = count {
        positions = super::thin(all, count.max(1))
            .into_iter()
            .map(|i| positions[i])
            .collect();
    }
    let one = DoubleDouble::new(1.0);
    let zero = DoubleDouble::new(0.0);
    let mut reference = Vec::with_capacity(positions.len());
    for &theta in &positions {
        let x = Dual3Number::new(DoubleDouble::new(theta), one, zero, zero);
        let s = program.displacement(x, Side::Right);
        let jet = [s.re, s.v1, s.v2, s.v3];
        if jet.iter().any(|r| !r.is_finite()) {
            return Err(Error::Reference {
                what: scene.file.clone(),
                reason: format!(
                    "the follower's displacement is not finite at cam angle {}° in \
                     double-double precision",
                    theta.to_degrees()
                ),
            });
        }
        reference.push(vec![jet]);
    }
    let continuity = ContinuityReport::new(program);
    let jumps: Vec<Option<usize>> = positions
        .iter()
        .map(|&theta| {
            continuity
                .boundaries
                .iter()
                .filter(|b| {
                    let d = (theta - b.angle).rem_euclid(TAU);
                    d.min(TAU - d) <= AT_JOINT
                })
                .filter_map(|b| b.first_jump())
                .min()
                // The displacement joins by construction (to 1e-9); the value is the
                // one-sided one for every method, differences included.
                .map(|order| order.max(1))
        })
        .collect();
    let joints: Vec<String> = positions
        .iter()
        .zip(&jumps)
        .filter_map(|(theta, jump)| {
            let order = (*jump)?;
            Some(format!(
                "{}° ({} jumps)",
                degrees(*theta),
                ["s", "s′", "s″", "s‴"][order]
            ))
        })
        .collect();
    let unit = match scene.displacement_dimension() {
        Dimension::Angle => "rad",
        _ => "m",
    };
    let mut notes = vec![
        "reference: the cam program (the laws' generic code) in Dual3<DoubleDouble>, at the \
         exact f64 cam angles; errors scaled by each order's max over the turn"
            .to_owned(),
    ];
    notes.push(if joints.is_empty() {
        "no derivative jumps at the table's positions".to_owned()
    } else {
        format!(
            "at the joints {}: reference and exact methods take the right-hand limit (the \
             segment or piece that starts there); finite differences straddle the jump, and \
             their errors at the orders that jump are not counted there",
            joints.join(", ")
        )
    });
    Ok(Case {
        title: format!(
            "{}: follower displacement s [{unit}] and s′, s″, s‴ per rad of cam angle, every \
             {}° of the turn, {} positions{}",
            scene.title.as_deref().unwrap_or(&scene.file),
            degrees(scene.step),
            positions.len(),
            super::scene::thinned_from(all, positions.len())
        ),
        outputs: vec![format!("s [{unit}]")],
        positions,
        reference,
        condition: None,
        relative: false,
        jumps,
        notes,
        methods: vec![
            method("Dual1", program, Dual1),
            method("Dual2", program, Dual2),
            method("HyperDual", program, HyperDual),
            method("Dual3", program, Dual3),
        ],
        positions_f64: Box::new(move |theta, out| {
            out[0] = program.displacement(theta, Side::Right);
            Ok(())
        }),
    })
}
