//! `mechdiff run <formula scene>`: a formula scene's outputs and their derivatives to order
//! 3 at its drive positions, with a note naming every position where a limit was taken.

use std::io::Write;

use mechdiff::accuracy::formula::{self, FormulaScene, Table};
use mechdiff::{Error, files};

use super::run::RunArgs;

/// Prints the table of the formula scene `args.scene`, read by `scene::any::read` (and
/// writes `--csv`); the options it cannot honour were refused by [`super::refuse_options`].
///
/// # Errors
/// The errors of [`formula::table`]; [`Error::Write`] if the output fails.
pub fn run(args: &RunArgs, scene: &FormulaScene) -> Result<(), Error> {
    let file = args.scene.display().to_string();
    let table = formula::table(scene, &file)?;
    if let Some(path) = &args.csv {
        files::write_atomically(path, |out| write_csv(&table, out))?;
    }
    let mut out = mechdiff::escape::Terminal::new(std::io::stdout().lock());
    match write_table(&scene.title, &table, &mut out).and_then(|()| out.flush()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        result => result.map_err(|source| Error::Write {
            path: "<stdout>".into(),
            source,
        }),
    }
}

/// The column headers: `phi [rad]`, then per output its value and `'`, `''`, `'''` (as the
/// linkage CSV writes derivatives).
fn headers(table: &Table) -> Vec<String> {
    let mut headers = vec!["phi [rad]".to_owned()];
    for name in &table.outputs {
        for mark in ["", "'", "''", "'''"] {
            headers.push(format!("{name}{mark}"));
        }
    }
    headers
}

/// The aligned table, then the notes (`note: removable singularity at φ = 0 rad: limit
/// taken`).
fn write_table(title: &str, table: &Table, out: &mut dyn Write) -> std::io::Result<()> {
    writeln!(out, "{title}")?;
    let line = |cells: &[String]| {
        cells
            .iter()
            .map(|c| format!("{c:>18}"))
            .collect::<Vec<_>>()
            .join(" ")
    };
    writeln!(out, "{}", line(&headers(table)))?;
    for (phi, row) in table.positions.iter().zip(&table.rows) {
        let mut cells = vec![format!("{phi:.9}")];
        cells.extend(row.iter().flatten().map(|x| format!("{x:.10e}")));
        writeln!(out, "{}", line(&cells))?;
    }
    for note in &table.notes {
        writeln!(out, "note: {note}")?;
    }
    Ok(())
}

/// The table as CSV, every number to its shortest exact `f64` form.
fn write_csv(table: &Table, out: &mut dyn Write) -> std::io::Result<()> {
    out.write_all(mechdiff::stream::record::csv_record(headers(table)).as_bytes())?;
    for (phi, row) in table.positions.iter().zip(&table.rows) {
        let cells: Vec<String> = std::iter::once(*phi)
            .chain(row.iter().flatten().copied())
            .map(|x| x.to_string())
            .collect();
        writeln!(out, "{}", cells.join(","))?;
    }
    Ok(())
}
