//! A run's [`Report`] as Python values: one NumPy array per column, in the column's unit,
//! and the run's findings (plan, dead positions, limits, counterweights, warnings) as plain
//! values.

use mechdiff::scene::units::Dimension;
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
    /// The limit positions, change points and toggles the sweep reaches: drive position in
    /// the drive's unit, what it is, the joints of the loop that stops the drive.
    limits: Vec<(f64, String, Vec<String>)>,
    /// The balancing lines printed after the table (`[balancing]`), empty without.
    balancing: Vec<String>,
    /// The counterweights sized by `[balancing]`: link, mass (kg), mass-radius (kg m), its
    /// angle from the link's line (in the scene's angle unit), its centre at the sketch pose
    /// (in the scene's length unit).
    counterweights: Vec<(String, f64, f64, f64, [f64; 2])>,
}

impl Columns {
    /// Takes the report apart (without the GIL: the rows are transposed here).
    pub fn of(scene: &Scene, report: &Report) -> Self {
        let mut after_rows = Vec::new();
        // Writing into a vector cannot fail.
        let _ = scene.after_rows(report, &mut after_rows);
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
        let limits = (report.limits.iter())
            .map(|l| {
                (
                    scene.units.from_si(l.limit.phi, drive),
                    mechdiff::scene::kind_words(l.limit.kind).to_owned(),
                    l.limit.joints.clone(),
                )
            })
            .collect();
        let (angle, length) = (Dimension::Angle, Dimension::Length);
        let counterweights = (report.balancing.iter())
            .filter_map(|b| b.linkage.as_ref())
            .flat_map(|l| &l.counterweights)
            .map(|c| {
                (
                    c.request.link.clone(),
                    c.mass,
                    c.mass_radius,
                    scene.units.from_si(c.angle, angle),
                    c.center.map(|x| scene.units.from_si(x, length)),
                )
            })
            .collect();
        let balancing = (report.balancing.iter())
            .flat_map(|b| b.lines.clone())
            .collect();
        let plan = report.plan.describe(scene);
        let (columns, rows) = (&report.columns, &report.rows);
        let mut values: Vec<Vec<f64>> = (columns.iter())
            .map(|_| Vec::with_capacity(rows.len()))
            .collect();
        for row in rows {
            for ((column, value), c) in values.iter_mut().zip(row).zip(columns) {
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
            warnings: report.warnings.clone(),
            dead_positions,
            limits,
            balancing,
            counterweights,
        }
    }

    /// As a dict: `names`, `headers`, `units`, `factors` (SI per unit of each column), `values` (one
    /// array per column, handed to NumPy without a copy), `plan`, `after_rows`, `warnings`,
    /// `dead_positions` (`[(output, [(phi, value), ...]), ...]`), `limits` (`[(phi, kind,
    /// joints), ...]`), `balancing` (lines), `counterweights` (`[(link, mass, mass_radius,
    /// angle, (x, y)), ...]`).
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
        dict.set_item("limits", self.limits)?;
        dict.set_item("balancing", self.balancing)?;
        dict.set_item("counterweights", self.counterweights)?;
        Ok(dict)
    }
}
