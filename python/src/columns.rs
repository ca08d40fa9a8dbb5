//! A run's [`Report`] as Python values: one NumPy array per column, in the column's unit,
//! and the run's findings (plan, dead positions, limits, warnings) as plain values.

use mechdiff::stream::TableWords;
use mechdiff::{Report, Scene};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

/// A report's columns, each a vector of its values in the column's unit (the SI value
/// divided by the column's factor, as the table and the CSV print it), and what the run
/// found besides them.
pub struct Columns {
    names: Vec<String>,
    /// `name [unit]`, as the table's header writes it.
    headers: Vec<String>,
    units: Vec<String>,
    factors: Vec<f64>,
    values: Vec<Vec<f64>>,
    /// The plan line, in the scene's units.
    plan: String,
    /// What the table prints after its rows: dead positions, limits, summaries.
    after_rows: String,
    warnings: Vec<String>,
    /// Per output searched: its name and its dead positions (drive position in the drive's
    /// unit, value in the output's).
    dead_positions: Vec<(String, Vec<(f64, f64)>)>,
}

impl Columns {
    /// Takes the report apart (without the GIL: the rows are transposed here).
    pub fn of(scene: &Scene, report: Report) -> Self {
        let mut after_rows = Vec::new();
        // Writing into a vector cannot fail.
        let _ = scene.after_rows(&report, &mut after_rows);
        let drive = scene.drive.kind.dimension();
        let dead_positions = (report.dead_positions.iter())
            .map(|d| {
                let positions = (d.positions.iter())
                    .map(|p| {
                        (
                            scene.units.from_si(p.phi, drive),
                            scene.units.from_si(p.value, d.dimension),
                        )
                    })
                    .collect();
                (d.output.clone(), positions)
            })
            .collect();
        let plan = report.plan.describe(scene);
        let Report {
            columns,
            rows,
            warnings,
            ..
        } = report;
        let mut values: Vec<Vec<f64>> = (columns.iter())
            .map(|_| Vec::with_capacity(rows.len()))
            .collect();
        for row in rows {
            for ((column, value), c) in values.iter_mut().zip(row).zip(&columns) {
                column.push(value / c.factor);
            }
        }
        Columns {
            names: columns.iter().map(|c| c.name.clone()).collect(),
            headers: columns.iter().map(|c| c.header()).collect(),
            units: columns.iter().map(|c| c.unit.clone()).collect(),
            factors: columns.iter().map(|c| c.factor).collect(),
            values,
            plan,
            after_rows: String::from_utf8_lossy(&after_rows).into_owned(),
            warnings,
            dead_positions,
        }
    }

    /// As a dict: `names`, `headers`, `units`, `factors` (SI per unit of each column), `values` (one
    /// array per column, handed to NumPy without a copy), `plan`, `after_rows`, `warnings`,
    /// `dead_positions` (`[(output, [(phi, value), ...]), ...]`).
    pub fn into_py(self, py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
        let dict = PyDict::new(py);
        let arrays = PyList::empty(py);
        for column in self.values {
            arrays.append(PyArray1::from_vec(py, column))?;
        }
        dict.set_item("names", self.names)?;
        dict.set_item("headers", self.headers)?;
        dict.set_item("units", self.units)?;
        dict.set_item("factors", self.factors)?;
        dict.set_item("values", arrays)?;
        dict.set_item("plan", self.plan)?;
        dict.set_item("after_rows", self.after_rows)?;
        dict.set_item("warnings", self.warnings)?;
        dict.set_item("dead_positions", self.dead_positions)?;
        Ok(dict)
    }
}
