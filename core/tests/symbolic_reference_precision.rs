//! The symbolic engine's derivatives, evaluated in arbitrary precision, reproduce the
//! 30-digit reference values of the Whitworth mechanism: ψ and x_C with their first three
//! derivatives with respect to φ, every 10° and at both dead positions
//! (`tests/data/whitworth_sweep_30digits.json`, copied from the project's reference
//! material `whitworth_000.json`, section `sweep_30digits`).
//!
//! Tolerance 1e-25 relative: the evaluation runs at 256 bits (≈ 77 digits) and the inputs φ
//! are given to 30 significant digits, so the reference values themselves are good to about
//! 1e-29. Where a reference value is below 1e-25 in magnitude (ψ′ and x_C′ at the dead
//! positions are ~1e-41, i.e. zero up to the rounding of φ) the comparison is absolute,
//! |value − reference| ≤ 1e-25.
// The engine is evaluated at 256 bits (feature `big-float`).
#![cfg(feature = "big-float")]

use mechdiff_core::symbolic::{BigReal, Graph};
use serde_json::Value;

const BITS: usize = 256;

fn reference_rows() -> Vec<Value> {
    let text = include_str!("data/whitworth_sweep_30digits.json");
    let data: Value = serde_json::from_str(text).unwrap();
    data["rows"].as_array().unwrap().clone()
}

fn assert_matches(what: &str, phi_deg: &str, value: &BigReal, reference: &str) {
    let reference = BigReal::parse(reference, BITS).unwrap();
    let magnitude = reference.to_f64().abs();
    let error = if magnitude < 1e-25 {
        value
            .relative_difference(&BigReal::parse("0", BITS).unwrap())
            .max(reference.relative_difference(&BigReal::parse("0", BITS).unwrap()))
    } else {
        value.relative_difference(&reference)
    };
    assert!(
        error <= 1e-25,
        "{what} at φ = {phi_deg}°: {value} vs {reference} (error {error:e})"
    );
}

#[test]
fn psi_and_x_c_derivatives_match_30_digit_references() {
    let mut graph = Graph::new();
    let psi = graph
        .parse_infix("atan2(lambda*sin(phi), 1 - lambda*cos(phi))")
        .unwrap();
    let h = graph.symbol("h");
    let tan_psi = graph.tan(psi);
    let x_c = graph.mul(h, tan_psi);
    let mut outputs = graph.derivatives(psi, "phi", 3);
    outputs.extend(graph.derivatives(x_c, "phi", 3));
    let keys = [
        "psi_rad",
        "psi_p",
        "psi_pp",
        "psi_ppp",
        "x_C_m",
        "x_C_p_m",
        "x_C_pp_m",
        "x_C_ppp_m",
    ];
    let rows = reference_rows();
    assert_eq!(rows.len(), 38, "36 angles every 10° and 2 dead positions");
    for row in rows {
        let phi = row["phi_rad"].as_str().unwrap();
        let phi_deg = row["phi_deg"].as_str().unwrap();
        let bindings = [("phi", phi), ("lambda", "0.375"), ("h", "0.65")];
        let values = graph.evaluate_big(&outputs, &bindings, BITS).unwrap();
        for (key, value) in keys.iter().zip(&values) {
            assert_matches(key, phi_deg, value, row[*key].as_str().unwrap());
        }
    }
}
