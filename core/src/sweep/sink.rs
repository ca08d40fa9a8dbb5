//! Where a sweep's rows go: kept, or passed on as they come.

use crate::Error;

/// Where the rows of a [`super::Sweep`] go, in drive order.
pub trait Sink {
    /// Takes one row: the drive position, then every consumer's values.
    ///
    /// # Errors
    /// The sink's own (a write that failed): the sweep stops.
    fn row(&mut self, row: &[f64]) -> Result<(), Error>;
}

/// A sink that keeps every row.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Collect {
    /// The rows, in drive order.
    pub rows: Vec<Vec<f64>>,
}

impl Sink for Collect {
    fn row(&mut self, row: &[f64]) -> Result<(), Error> {
        self.rows.push(row.to_vec());
        Ok(())
    }
}

/// A sink that passes each row on to a function as it comes and keeps none (a writer, a
/// running summary): constant memory for any number of rows.
pub struct Stream<F>(pub F);

impl<F: FnMut(&[f64]) -> Result<(), Error>> Sink for Stream<F> {
    fn row(&mut self, row: &[f64]) -> Result<(), Error> {
        (self.0)(row)
    }
}

/// A sink that drops every row (a sweep run for what its consumers keep).
impl Sink for () {
    fn row(&mut self, _: &[f64]) -> Result<(), Error> {
        Ok(())
    }
}
