//! The library without the command line: read a scene, set one of its parameters, run it to
//! columns, stream its rows as CSV, and read the exact sensitivity of an output to the
//! parameter.
//!
//! `cargo run --example library` (or with `--no-default-features`: none of clap, plotters,
//! resvg, rayon or indicatif is compiled).

use mechdiff::{Error, Report, Setting, Sink, Sinks};

/// Norton's non-Grashof four-bar, written with its link lengths as `[parameters]`.
const SCENE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/norton_four_bar.toml");

fn main() -> Result<(), Error> {
    // Read the scene with its coupler `b` lengthened from 1.85 m to 1.9 m (a number or a
    // formula of the other parameters, as `--set b=1.9` would give it).
    let b = Setting {
        name: "b".into(),
        value: "1.9".into(),
    };
    let scene = mechdiff::load_with(SCENE, std::slice::from_ref(&b))?;

    // Run its sweep: a report of columns (name, unit) and rows (SI values).
    let report = mechdiff::run(&scene)?;
    print_table(&report);

    // Stream the same rows as CSV, here into memory: any `Write` is a sink, and memory stays
    // flat in the number of drive positions.
    let mut csv = Vec::new();
    let mut sinks = Sinks {
        csv: Some(Sink {
            path: "<memory>".into(),
            out: &mut csv,
        }),
        ..Sinks::default()
    };
    let streamed = mechdiff::stream::run(&scene, &mut sinks, &Default::default())?;
    let csv = String::from_utf8_lossy(&csv);
    println!(
        "\nstreamed {} rows; the CSV's header: {}",
        streamed.rows,
        csv.lines().next().unwrap_or_default()
    );

    // The exact sensitivity dψ/db: a `[sensitivity]` table asks for the column, computed
    // with dual numbers through the pose's implicit differentiation (no finite difference).
    let text = std::fs::read_to_string(SCENE).map_err(|source| Error::Read {
        path: SCENE.into(),
        source,
    })?;
    let text = text + "\n[sensitivity]\ncolumns = [\"d(psi)/d(b)\"]\n";
    let options = mechdiff::sensitivity::Options::default();
    let (_, report, study) = mechdiff::sensitivity::run(SCENE, &text, &[b], &options)?;
    if let Some(study) = study {
        for column in &study.derivatives {
            let how = if column.is_exact() {
                "exact"
            } else {
                "Richardson-extrapolated"
            };
            println!("\n{} ({how}, rad per m of b):", column.name);
        }
    }
    let phi = report.column("phi").unwrap_or_default();
    let dpsi_db = report.column("d(psi)/d(b)").unwrap_or_default();
    for (phi, d) in phi.iter().zip(&dpsi_db) {
        println!("  φ = {:>5.1}°  dψ/db = {d:+.15}", phi.to_degrees());
    }
    Ok(())
}

/// The report as a table, each column in its own unit.
fn print_table(report: &Report) {
    for column in &report.columns {
        print!("{:>22}", column.header());
    }
    println!();
    for row in &report.rows {
        for (value, column) in row.iter().zip(&report.columns) {
            print!("{:>22.12}", value / column.factor);
        }
        println!();
    }
}
