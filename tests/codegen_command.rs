//! `mechdiff codegen`: the generated function for the Whitworth ψ, and positioned errors.

use mechdiff::codegen::{Args, generate};

fn args(expression: &str, order: usize) -> Args {
    Args {
        expression: expression.into(),
        wrt: "phi".into(),
        order,
        name: "derivatives".into(),
    }
}

#[test]
fn whitworth_psi_codegen_prints_function_and_operation_count() {
    let text = generate(&args("atan2(lambda*sin(phi), 1 - lambda*cos(phi))", 2)).unwrap();
    assert!(
        text.contains("pub fn derivatives(phi: f64, lambda: f64) -> [f64; 3]"),
        "{text}"
    );
    // sin and cos of φ are computed once; one atan2 for the value
    assert!(text.contains("phi.sin_cos()"), "{text}");
    assert!(
        text.contains("// operations: ") && text.contains("1 atan2, 1 sin_cos"),
        "{text}"
    );
    assert!(
        text.contains("without common-subexpression elimination"),
        "{text}"
    );
}

#[test]
fn malformed_expression_error_shows_the_position() {
    let error = generate(&args("atan2(lambda*sin(phi) 1 - lambda*cos(phi))", 1)).unwrap_err();
    let message = error.to_string();
    // the problem is the missing comma before `1`, character 23 (column 23, 1-based)
    assert!(
        message.starts_with("expected `)`, found a number (column 23)"),
        "{message}"
    );
    let caret_line = message.lines().last().unwrap();
    assert_eq!(caret_line.find('^'), Some(2 + 22), "{message}");
}

#[test]
fn wrt_must_be_an_identifier() {
    let mut bad = args("sin(phi)", 1);
    bad.wrt = "phi prime".into();
    assert!(
        generate(&bad)
            .unwrap_err()
            .to_string()
            .contains("--wrt must be a Rust identifier")
    );
}
