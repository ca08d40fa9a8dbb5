//! Every kind of unsupported construct is an error that points at it and says what to do
//! instead: one file per kind in `tests/unsupported/`, beside the message a user sees
//! (`<case>.stderr`, in rustc's rendering: message, ` --> file:line:column`, carets).
//!
//! The cases run through the macro's own expansion (`expand::generate`) rather than through
//! rustc (trybuild): the same message, start and caret width are checked without building a
//! second copy of the crate's dependencies. The position rustc prints for an error spanned at
//! the macro's call site is the attribute's, so such an error is placed there.

use std::fs;
use std::path::Path;

use proc_macro2::{LineColumn, TokenStream};
use syn::spanned::Spanned;

use crate::expand;

/// One error as rustc renders it in a `.stderr` file.
#[derive(Debug, PartialEq)]
struct Rendered {
    message: String,
    /// Line (from 1) and column (from 1) of the first character.
    line: usize,
    column: usize,
    /// The carets' count on a single-line span; 0 on a span of several lines (rustc draws
    /// those with a bracket).
    width: usize,
}

fn rendered(stderr: &str, case: &str) -> Vec<Rendered> {
    let mut errors = Vec::new();
    let mut lines = stderr.lines();
    while let Some(line) = lines.next() {
        let Some(message) = line.strip_prefix("error: ") else {
            continue;
        };
        let location = lines.next().expect("a location after the message");
        let position = location
            .trim_start()
            .strip_prefix(&format!("--> tests/unsupported/{case}.rs:"))
            .unwrap_or_else(|| panic!("{case}: unexpected location line {location:?}"));
        let (line, column) = position.split_once(':').expect("line:column");
        let width = lines
            .by_ref()
            .find(|l| l.contains('^'))
            .filter(|l| !l.contains("_^"))
            .map_or(0, |l| l.chars().filter(|&c| c == '^').count());
        errors.push(Rendered {
            message: message.to_owned(),
            line: line.parse().expect("a line number"),
            column: column.parse().expect("a column number"),
            width,
        });
    }
    errors
}

/// The errors of the expansion, placed as rustc places them.
fn expanded(source: &str) -> Vec<Rendered> {
    let mut file = syn::parse_file(source).expect("each case is valid Rust");
    let mut function = file
        .items
        .drain(..)
        .find_map(|item| match item {
            syn::Item::Fn(function) if !function.attrs.is_empty() => Some(function),
            _ => None,
        })
        .expect("each case has one function under #[derivatives]");
    let attribute = function.attrs.remove(0);
    assert!(attribute.path().is_ident("derivatives"));
    let arguments: TokenStream = attribute
        .meta
        .require_list()
        .map(|list| list.tokens.clone())
        .expect("#[derivatives(...)]");
    let error = expand::generate(arguments, &function).expect_err("each case is refused");
    let at_attribute = attribute.span().start();
    error
        .into_iter()
        .map(|error| {
            let span = error.span();
            let (start, end) = (span.start(), span.end());
            // The call site has no place in the source: rustc shows the attribute.
            let start = if start == (LineColumn { line: 1, column: 0 }) && start == end {
                at_attribute
            } else {
                start
            };
            let end = if start == at_attribute {
                attribute.span().end()
            } else {
                end
            };
            let width = if end.line == start.line {
                end.column - start.column
            } else {
                0
            };
            Rendered {
                message: error.to_string(),
                line: start.line,
                column: start.column + 1,
                width,
            }
        })
        .collect()
}

#[test]
fn unsupported_constructs_are_errors_at_the_construct() {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/unsupported");
    let mut cases: Vec<_> = fs::read_dir(&folder)
        .expect("tests/unsupported")
        .map(|entry| entry.expect("a readable entry").path())
        .filter(|path| path.extension().is_some_and(|e| e == "rs"))
        .collect();
    cases.sort();
    // Ten kinds today; a case added without its .stderr fails below.
    assert!(cases.len() >= 10, "{cases:?}");
    for path in cases {
        let case = path.file_stem().unwrap().to_str().unwrap().to_owned();
        let source = fs::read_to_string(&path).unwrap();
        let stderr = fs::read_to_string(path.with_extension("stderr"))
            .unwrap_or_else(|e| panic!("{case}: its .stderr: {e}"));
        let expected = rendered(&stderr, &case);
        assert!(!expected.is_empty(), "{case}: no error in its .stderr");
        assert_eq!(expanded(&source), expected, "{case}");
    }
}
