//! The `mechdiff` binary's default command: the Whitworth report, `--help`, and README.md's copy of the report.

use std::process::Command;

fn mechdiff(args: &[&str]) -> String {
    let output = Command::new(env!("CARGO_BIN_EXE_mechdiff"))
        .args(args)
        .output()
        .expect("the mechdiff binary runs");
    assert!(output.status.success(), "{output:?}");
    String::from_utf8(output.stdout).expect("UTF-8 output")
}

/// The cells of one printed row, split on whitespace.
fn row<'a>(text: &'a str, name: &str) -> Vec<&'a str> {
    let line = text
        .lines()
        .find(|l| l.starts_with(name))
        .unwrap_or_else(|| panic!("no row {name} in\n{text}"));
    line.split_whitespace().collect()
}

/// Without arguments (and with `whitworth`): the table at 0°, 180° and the exact dead
/// positions, with units, then the dead positions and the stroke. Numbers are those of the
/// reference `whitworth_000.json` (notes `whitworth_000.md`), rounded as printed.
#[test]
fn default_command_prints_the_whitworth_table() {
    let text = mechdiff(&[]);
    assert_eq!(text, mechdiff(&["whitworth"]));
    assert!(
        text.contains("φ = 0°  φ = 180°  φ = 67.976°  φ = 292.024°"),
        "{text}"
    );
    assert_eq!(
        row(&text, "ẍ_S3"),
        ["ẍ_S3", "m/s²", "0.0000", "0.0000", "-33.5527", "33.5527"]
    );
    assert_eq!(
        row(&text, "ÿ_S2"),
        ["ÿ_S2", "m/s²", "-5.9218", "-1.2235", "2.4953", "2.4953"]
    );
    assert_eq!(
        row(&text, "ΣF_x"),
        ["ΣF_x", "N", "0.00", "0.00", "1923.69", "-1923.69"]
    );
    assert_eq!(
        row(&text, "ΣF_y"),
        ["ΣF_y", "N", "111.86", "102.50", "-99.53", "-99.53"]
    );
    assert_eq!(
        row(&text, "first"),
        [
            "first",
            "67.9756871630",
            "1.18639955229926",
            "0.384396774496",
            "-0.404519917478",
            "0.262937946361"
        ]
    );
    assert!(
        text.contains("stroke |x_C(φ₁) − x_C(φ₂)| = 0.525875892721 m"),
        "{text}"
    );
}

/// Columns are aligned: every row of the force table has the same width.
#[test]
fn table_columns_are_aligned() {
    let text = mechdiff(&[]);
    let widths: Vec<usize> = text
        .lines()
        .skip_while(|l| !l.starts_with("quantity"))
        .take(13)
        .map(|l| l.chars().count())
        .collect();
    assert_eq!(widths.len(), 13);
    assert!(widths.iter().all(|&w| w == widths[0]), "{widths:?}\n{text}");
}

/// `--help` explains what the default command prints.
#[test]
fn help_explains_the_default_report() {
    let help = mechdiff(&["--help"]);
    assert!(
        help.contains("Whitworth") && help.contains("dead positions"),
        "{help}"
    );
}

/// README.md shows the real default output (regenerate it there when the report changes).
#[test]
fn readme_shows_the_default_output() {
    let readme = include_str!("../README.md");
    assert!(
        readme.contains(&mechdiff(&[])),
        "README.md's default output is stale"
    );
}
