//! Generated code with constant subexpressions compiles and computes the right values.
//!
//! Constants such as `sin(1/3)` used to be emitted as `(1.0 / 3.0).sin()`, which rustc
//! rejects (E0689: a method on an ambiguous float type). `tests/data/codegen_constants.rs`
//! is `mechdiff codegen` output for such formulas (regenerate it with
//! `sh tests/data/codegen_constants.sh`); it is compiled into this test, so the error class
//! cannot return, and the first test checks that it is what `codegen` writes today.

mod generated {
    include!("data/codegen_constants.rs");
}

use mechdiff::codegen::{Args, generate};

/// The formulas of the fixture, in order (as in `tests/data/codegen_constants.sh`).
const FORMULAS: [&str; 7] = [
    "sin(1/3)*phi",
    "exp(1/3)*phi",
    "phi*sqrt(1/3)",
    "(1/3)^phi",
    "sin(1/3) + cos(1/3)*phi",
    "powi(1/3, 3)*phi + cosh(0.1)^phi",
    "pi*phi^2 + atan2(1, 3)*ln(3)",
];

#[test]
fn the_compiled_fixture_is_what_codegen_writes() {
    let fixture = include_str!("data/codegen_constants.rs");
    for (k, formula) in FORMULAS.iter().enumerate() {
        let mut args = Args::new(formula, "phi", 2);
        args.name = format!("constants_{}", k + 1);
        let text = generate(&args).unwrap();
        assert!(
            fixture.contains(&text),
            "regenerate tests/data/codegen_constants.rs: `{formula}` now gives\n{text}"
        );
    }
}

#[test]
fn generated_constants_have_the_values_of_the_formulas() {
    let third: f64 = 1.0 / 3.0;
    for phi in [-1.3, 0.0, 0.4, 2.5] {
        // each derivative written by hand; 4 ulp relative: the same f64 operations up to
        // the order of a product or two
        let cases: [([f64; 3], [f64; 3]); 7] = [
            (
                generated::constants_1(phi),
                [third.sin() * phi, third.sin(), 0.0],
            ),
            (
                generated::constants_2(phi),
                [third.exp() * phi, third.exp(), 0.0],
            ),
            (
                generated::constants_3(phi),
                [phi * third.sqrt(), third.sqrt(), 0.0],
            ),
            (
                generated::constants_4(phi),
                [
                    third.powf(phi),
                    third.powf(phi) * third.ln(),
                    third.powf(phi) * third.ln().powi(2),
                ],
            ),
            (
                generated::constants_5(phi),
                [third.sin() + third.cos() * phi, third.cos(), 0.0],
            ),
            (
                generated::constants_6(phi),
                [
                    third.powi(3) * phi + 0.1f64.cosh().powf(phi),
                    third.powi(3) + 0.1f64.cosh().powf(phi) * 0.1f64.cosh().ln(),
                    0.1f64.cosh().powf(phi) * 0.1f64.cosh().ln().powi(2),
                ],
            ),
            (
                generated::constants_7(phi),
                [
                    std::f64::consts::PI * phi * phi + 1f64.atan2(3.0) * 3f64.ln(),
                    2.0 * std::f64::consts::PI * phi,
                    2.0 * std::f64::consts::PI,
                ],
            ),
        ];
        for (k, (generated, expected)) in cases.iter().enumerate() {
            for (order, (g, e)) in generated.iter().zip(expected).enumerate() {
                assert!(
                    (g - e).abs() <= 4.0 * f64::EPSILON * e.abs().max(1e-300),
                    "constants_{} order {order} at phi = {phi}: {g} vs {e}",
                    k + 1
                );
            }
        }
    }
}
