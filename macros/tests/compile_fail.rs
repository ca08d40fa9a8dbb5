//! Every kind of unsupported construct is a compile error that points at it and says what
//! to do instead: one file per kind in `tests/ui/`, with the message a user sees.

#[test]
fn unsupported_constructs_are_compile_errors() {
    let cases = trybuild::TestCases::new();
    cases.compile_fail("tests/ui/*.rs");
}
