//! `mechdiff codegen`: the generated function for the Whitworth ψ, and positioned errors.

use mechdiff::codegen::{Args, generate};

fn args(expression: &str, order: usize) -> Args {
    Args::new(expression, "phi", order)
}

/// The error message of `codegen` for `expression`.
fn error_of(expression: &str) -> String {
    generate(&args(expression, 1)).unwrap_err().to_string()
}

/// The column (1-based) the caret of a positioned error points at, within the formula line.
fn caret_column(message: &str) -> usize {
    let caret_line = message.lines().last().unwrap();
    caret_line.find('^').unwrap() - 2 + 1
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
        message.starts_with("--expr: expected `)`, found a number (column 23)"),
        "{message}"
    );
    assert_eq!(caret_column(&message), 23, "{message}");
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

#[test]
fn constant_too_large_for_f64_is_an_error_at_its_column() {
    let message = error_of("1e309*phi");
    assert!(
        message.contains("`1e309` is too large for an f64"),
        "{message}"
    );
    assert_eq!(caret_column(&message), 1, "{message}");
}

#[test]
fn domain_errors_of_constants_point_at_the_operation() {
    // (formula, the 1-based column of the operator or function, what the message names)
    for (formula, column, what) in [
        ("phi + 1/0", 8, "division by zero"),
        ("phi + 0/0", 8, "division by zero"),
        ("phi * ln(0)", 7, "the logarithm of zero"),
        ("phi * sqrt(-1)", 7, "the square root of a negative number"),
        ("phi * acos(2)", 7, "outside [-1, 1]"),
        ("exp(1000) * phi", 1, "overflows"),
        ("phi / (phi - phi)", 5, "division by zero"),
        ("phi * (-8)^(1/3)", 11, "a negative base"),
    ] {
        let message = error_of(formula);
        assert!(message.contains(what), "{formula}: {message}");
        assert_eq!(caret_column(&message), column, "{formula}: {message}");
    }
}

#[test]
fn nesting_beyond_the_limit_is_an_error_and_within_it_compiles_to_a_let_chain() {
    let limit = mechdiff_core::symbolic::infix::MAX_NESTING;
    let deep = |n: usize| format!("{}phi{}", "sin(".repeat(n), ")".repeat(n));
    let message = error_of(&deep(limit + 1));
    assert!(
        message.contains("nests deeper than the limit of 1024"),
        "{message}"
    );
    // 1000 nested sin at order 3 (crashed rustc's parser as one expression): every emitted
    // expression nests at most 16 operations deep, so the source has no long `((((` runs
    let text = generate(&args(&deep(1000), 3)).unwrap();
    assert!(text.contains("pub fn derivatives(phi: f64) -> [f64; 4]"));
    assert!(!text.contains(&"(".repeat(18)), "deeply nested output");
    assert!(text.matches("let ").count() > 1000, "a let chain");
}

#[test]
fn derivative_order_beyond_the_limit_is_an_error() {
    let message = generate(&args("sin(phi)", 1_000_000_000))
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("derivative order 1000000000 is above the limit of 32"),
        "{message}"
    );
}

#[test]
fn pi_in_any_spelling_is_the_named_constant_not_a_parameter() {
    let expected = generate(&args("std::f64::consts::PI * sin(phi)", 1)).unwrap();
    assert!(
        expected.contains("pub fn derivatives(phi: f64) -> [f64; 2]"),
        "{expected}"
    );
    assert!(expected.contains("std::f64::consts::PI * "), "{expected}");
    for spelling in ["pi", "PI", "f64::consts::PI", "core::f64::consts::PI"] {
        let text = generate(&args(&format!("{spelling} * sin(phi)"), 1)).unwrap();
        // the same function; only the echoed formula on the first line differs
        let body = |t: &str| t.lines().skip(1).collect::<Vec<_>>().join("\n");
        assert_eq!(body(&text), body(&expected), "{spelling}");
    }
    let message = error_of("std::f64::consts::NOPE * phi");
    assert!(message.contains("unknown constant"), "{message}");
}

fn temporary_file(name: &str, contents: &[u8]) -> std::path::PathBuf {
    let path = std::env::temp_dir().join(format!("mechdiff-codegen-{}-{name}", std::process::id()));
    std::fs::write(&path, contents).unwrap();
    path
}

#[test]
fn formula_from_a_file_equals_the_formula_from_expr() {
    let path = temporary_file(
        "psi.txt",
        b"atan2(lambda*sin(phi),\n  1 - lambda*cos(phi))\n",
    );
    let mut from_file = args("", 2);
    from_file.expression = None;
    from_file.file = Some(path.clone());
    let text = generate(&from_file).unwrap();
    let expected = generate(&args("atan2(lambda*sin(phi), 1 - lambda*cos(phi))", 2)).unwrap();
    let body = |t: &str| t.lines().skip(1).collect::<Vec<_>>().join("\n");
    assert_eq!(body(&text), body(&expected));
    std::fs::remove_file(path).unwrap();
}

#[test]
fn formula_file_errors_name_the_file() {
    let mut from_file = args("", 1);
    from_file.expression = None;
    // a malformed formula: the file is named with the column
    let path = temporary_file("bad.txt", b"sin(phi");
    from_file.file = Some(path.clone());
    let message = generate(&from_file).unwrap_err().to_string();
    assert!(message.contains("bad.txt: expected `)`"), "{message}");
    std::fs::remove_file(path).unwrap();
    // not UTF-8
    let path = temporary_file("latin1.txt", b"phi * \xe9");
    from_file.file = Some(path.clone());
    let message = generate(&from_file).unwrap_err().to_string();
    assert!(
        message.contains("not UTF-8 text (invalid byte at offset 6)"),
        "{message}"
    );
    std::fs::remove_file(path).unwrap();
    // longer than the limit (as /dev/zero would be): refused after reading the limit
    let path = temporary_file("huge.txt", b"");
    std::fs::File::options()
        .write(true)
        .open(&path)
        .unwrap()
        .set_len(mechdiff::codegen::MAX_FORMULA_BYTES + 1)
        .unwrap();
    from_file.file = Some(path.clone());
    let message = generate(&from_file).unwrap_err().to_string();
    assert!(
        message.contains("longer than the limit of 16777216 bytes"),
        "{message}"
    );
    std::fs::remove_file(path).unwrap();
}

#[test]
fn formula_from_standard_input() {
    use std::io::Write;
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_mechdiff"))
        .args(["codegen", "--file", "-", "--wrt", "x", "--order", "2"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    child.stdin.take().unwrap().write_all(b"x^3\n").unwrap();
    let output = child.wait_with_output().unwrap();
    let text = String::from_utf8(output.stdout).unwrap();
    assert!(output.status.success(), "{text}");
    assert!(
        text.contains("pub fn derivatives(x: f64) -> [f64; 3]"),
        "{text}"
    );
    // x³, 3x², 6x
    assert!(text.contains("6.0 * x"), "{text}");
}
