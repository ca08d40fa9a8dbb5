//! The standard motion laws: peak coefficients against their closed forms and textbook
//! tables, and derivatives against an independent 256-bit evaluation.
//!
//! (The printed textbook values are compared as printed; `6.283` is one of them, not τ.)
#![allow(clippy::approx_constant)]

use std::f64::consts::PI;

use mechdiff_core::cams::MotionLaw;
// The 256-bit reference (feature `big-float`).
#[cfg(feature = "big-float")]
use mechdiff_core::{cams::Side, symbolic::Graph};
#[cfg(feature = "big-float")]
use num_dual::Dual3_64;

/// The peak coefficients C_v = max|f′|, C_a = max|f″|, C_j = max|f‴| of each law in closed
/// form, derived here from the formulas (f normalised: rise 1 over u ∈ [0, 1]):
///
/// - uniform velocity f = u: 1, 0, 0 (the jumps at the ends are impulses, not in f″).
/// - parabolic f = 2u²: f′ = 4u ≤ 2, f″ = ±4, f‴ = 0.
/// - simple harmonic f = (1 − cos πu)/2: π/2, π²/2, π³/2 (f‴ = (π³/2) sin… at the ends).
/// - cycloidal f = u − sin 2πu/2π: f′ = 1 − cos 2πu ≤ 2, f″ = 2π sin 2πu, f‴ = 4π² cos 2πu:
///   2, 2π, 4π².
/// - 3-4-5: f′ = 30u²(1−u)² ≤ 30/16 = 1.875; f″ = 60u(1−u)(1−2u), largest where
///   u(1−u) = 1/6, 1 − 2u = 1/√3: 10/√3 = 5.7735; f‴ = 60 at the ends.
/// - 4-5-6-7: f′ = 140u³(1−u)³ ≤ 140/64 = 35/16; f″ = 420u²(1−u)²(1−2u), largest where
///   v = u(1−u) = 1/5: 420/(25√5) = 84/(5√5) = 7.5132; f‴ = 52.5 at u = ½ (the other
///   extrema, at u = ½ ± √15/10, give 42).
/// - modified trapezoidal: acceleration amplitude C = 8π/(2+π) = 4.8881 (from f(1) = 1),
///   velocity at u = ½: C(¼ + 1/2π) = 2; jerk 4πC = 32π²/(2+π) = 61.426.
/// - modified sine: C = 4π²/(π+4) = 5.5280, velocity at ½: 4π/(π+4) = 1.7596, jerk
///   4πC = 16π³/(π+4) = 69.466.
///
/// Printed values: Norton, *Design of Machinery* (McGraw-Hill), the table of peak velocity,
/// acceleration and jerk factors of cam functions: cycloidal 2.000 / 6.283 / 39.48, modified
/// trapezoid 2.000 / 4.888 / 61.43, modified sine 1.760 / 5.528 / 69.47; the modified sine
/// also in the MechDesigner help ("Modified-Sinusoid Motion-Law", mechdesigner.support:
/// C_v = 1.76, C_a = 5.53, C_j = 69.47); 3-4-5: C_v = 1.875, C_a = 5.7735, C_j = 60 as
/// cited in issue 11.
fn closed_forms(law: MotionLaw) -> [f64; 3] {
    let s5 = 5f64.sqrt();
    match law {
        MotionLaw::Dwell => [0.0, 0.0, 0.0],
        MotionLaw::UniformVelocity => [1.0, 0.0, 0.0],
        MotionLaw::Parabolic => [2.0, 4.0, 0.0],
        MotionLaw::SimpleHarmonic => [PI / 2.0, PI * PI / 2.0, PI.powi(3) / 2.0],
        MotionLaw::Cycloidal => [2.0, 2.0 * PI, 4.0 * PI * PI],
        MotionLaw::Polynomial345 => [1.875, 10.0 / 3f64.sqrt(), 60.0],
        MotionLaw::Polynomial4567 => [35.0 / 16.0, 84.0 / (5.0 * s5), 52.5],
        MotionLaw::ModifiedTrapezoidal => [2.0, 8.0 * PI / (2.0 + PI), 32.0 * PI * PI / (2.0 + PI)],
        MotionLaw::ModifiedSine => [
            4.0 * PI / (PI + 4.0),
            4.0 * PI * PI / (PI + 4.0),
            16.0 * PI.powi(3) / (PI + 4.0),
        ],
    }
}

/// The peak coefficients found by search equal the closed forms to 1e-12 relative (a
/// smooth maximum located to √ε in u is exact in value up to rounding; 1e-12 leaves room
/// for the polynomials' cancellation), and the textbook's rounded values to their printed
/// digits.
#[test]
fn peak_coefficients_match_closed_forms_and_textbooks() {
    for &law in MotionLaw::ALL {
        let c = law.peak_coefficients();
        let found = [c.velocity, c.acceleration, c.jerk];
        for (k, (got, want)) in found.iter().zip(closed_forms(law)).enumerate() {
            let error = (got - want).abs();
            assert!(
                error <= 1e-12 * want.abs().max(1.0),
                "{law} C{k}: {got} vs {want} ({error:e})"
            );
        }
    }
    // Printed values (see `closed_forms`), to half a unit of their last digit.
    let printed = [
        (
            MotionLaw::Cycloidal,
            [2.000, 6.283, 39.48],
            [5e-4, 5e-4, 5e-3],
        ),
        (
            MotionLaw::ModifiedTrapezoidal,
            [2.000, 4.888, 61.43],
            [5e-4, 5e-4, 5e-3],
        ),
        (
            MotionLaw::ModifiedSine,
            [1.760, 5.528, 69.47],
            [5e-4, 5e-4, 5e-3],
        ),
        (
            MotionLaw::Polynomial345,
            [1.875, 5.7735, 60.0],
            [5e-4, 5e-5, 5e-3],
        ),
    ];
    for (law, values, half_units) in printed {
        let c = law.peak_coefficients();
        for ((got, want), tol) in [c.velocity, c.acceleration, c.jerk]
            .iter()
            .zip(values)
            .zip(half_units)
        {
            assert!((got - want).abs() <= tol, "{law}: {got} vs printed {want}");
        }
    }
}

#[cfg(feature = "big-float")]
const PI_DIGITS: &str = "3.14159265358979323846264338327950288419716939937510582097494459";

/// Each law's pieces as infix formulas of u (the module documentation's formulas, written
/// out again), with the interval of each piece.
#[cfg(feature = "big-float")]
fn pieces(law: MotionLaw) -> Vec<(f64, f64, &'static str)> {
    match law {
        MotionLaw::Dwell => vec![(0.0, 1.0, "0*u")],
        MotionLaw::UniformVelocity => vec![(0.0, 1.0, "u")],
        MotionLaw::Parabolic => vec![(0.0, 0.5, "2*u^2"), (0.5, 1.0, "1 - 2*(1 - u)^2")],
        MotionLaw::SimpleHarmonic => vec![(0.0, 1.0, "(1 - cos(pi*u))/2")],
        MotionLaw::Cycloidal => vec![(0.0, 1.0, "u - sin(2*pi*u)/(2*pi)")],
        MotionLaw::Polynomial345 => vec![(0.0, 1.0, "10*u^3 - 15*u^4 + 6*u^5")],
        MotionLaw::Polynomial4567 => {
            vec![(0.0, 1.0, "35*u^4 - 84*u^5 + 70*u^6 - 20*u^7")]
        }
        MotionLaw::ModifiedTrapezoidal => vec![
            (0.0, 0.125, "(4*pi*u - sin(4*pi*u))/(2*pi*(2 + pi))"),
            (
                0.125,
                0.375,
                "(32*pi*u + pi^2*(64*u^2 - 16*u + 1) - 8)/(16*pi*(2 + pi))",
            ),
            (
                0.375,
                0.625,
                "(4*pi*u + pi^2*(4*u - 1) + sin(4*pi*u))/(2*pi*(2 + pi))",
            ),
            (
                0.625,
                0.875,
                "(32*pi*u + pi^2*(-64*u^2 + 112*u - 33) + 8)/(16*pi*(2 + pi))",
            ),
            (0.875, 1.0, "(2*pi*u - sin(4*pi*u)/2 + pi^2)/(pi*(2 + pi))"),
        ],
        MotionLaw::ModifiedSine => vec![
            (0.0, 0.125, "(pi*u - sin(4*pi*u)/4)/(pi + 4)"),
            (
                0.125,
                0.875,
                "(pi*u - 9*sin(pi*(4*u/3 + 1/3))/4 + 2)/(pi + 4)",
            ),
            (0.875, 1.0, "(pi*u - sin(4*pi*u)/4 + 4)/(pi + 4)"),
        ],
    }
}

/// f, f′, f″, f‴ from dual numbers (the law's code) agree with the symbolic engine's
/// derivatives of the same formulas evaluated at 256 bits, at u = (2k+1)/64 (exact in
/// binary, never on a break), to 1e-14 of the derivative's peak coefficient (of 1 for f):
/// both are exact methods, the duals in f64 with its roundings. The largest error found is
/// printed.
#[test]
#[cfg(feature = "big-float")]
fn derivatives_agree_with_a_256_bit_evaluation() {
    let mut worst = 0.0f64;
    for &law in MotionLaw::ALL {
        let c = law.peak_coefficients();
        let scales = [
            1.0,
            c.velocity.max(1.0),
            c.acceleration.max(1.0),
            c.jerk.max(1.0),
        ];
        let mut graph = Graph::new();
        let jets: Vec<(f64, f64, Vec<_>)> = pieces(law)
            .into_iter()
            .map(|(a, b, text)| {
                let f = graph.parse_infix(text).unwrap();
                (a, b, graph.derivatives(f, "u", 3))
            })
            .collect();
        for k in 0..32 {
            let u = (2 * k + 1) as f64 / 64.0;
            let (_, _, outputs) = jets.iter().find(|(a, b, _)| *a < u && u < *b).unwrap();
            let u_text = format!("{u:e}");
            let bindings = [("u", u_text.as_str()), ("pi", PI_DIGITS)];
            let reference = graph.evaluate_big(outputs, &bindings, 256).unwrap();
            let dual = law.rise(Dual3_64::from(u).derivative(), Side::Right);
            for (order, (got, want)) in [dual.re, dual.v1, dual.v2, dual.v3]
                .iter()
                .zip(&reference)
                .enumerate()
            {
                // The reference rounded to f64 (1e-16 relative) is far below the tolerance.
                let error = (got - want.to_f64()).abs() / scales[order];
                worst = worst.max(error);
                assert!(
                    error <= 1e-14,
                    "{law} order {order} at u = {u}: {got} vs {want} ({error:e})"
                );
            }
        }
    }
    println!("largest error relative to the peak coefficient: {worst:e}");
}
