//! `mechdiff.derive`: a formula's derivatives by the symbolic engine
//! ([`mechdiff::core::symbolic`], the engine of `mechdiff codegen`): the derivative
//! expressions as s-expressions, and their values at NumPy arrays of the variables.

use mechdiff::codegen::MAX_FORMULA_BYTES;
use mechdiff::core::symbolic::constants::is_named_constant;
use mechdiff::core::symbolic::{Graph, Id, rules};
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;

use crate::errors::{argument, to_py};

/// Where a formula's errors say it came from.
const ORIGIN: &str = "mechdiff.derive";

/// The most points of one `evaluate` call (the caller splits a larger array).
pub const MAX_POINTS: usize = 10_000_000;

/// A formula differentiated: its value and derivatives 1 to `order` with respect to one
/// variable, as expressions of one graph (`mechdiff.Derivatives` wraps it).
#[pyclass(module = "mechdiff._mechdiff", name = "Formula", frozen)]
pub struct Formula {
    graph: Graph,
    /// The value, then the derivatives in order.
    outputs: Vec<Id>,
    /// The variable, then the other symbols (not the named constants) in alphabetical order.
    parameters: Vec<String>,
}

/// The engine's error as the facade's, its origin `mechdiff.derive`.
fn formula_error(py: Python<'_>, source: mechdiff::core::Error) -> PyErr {
    to_py(
        py,
        &mechdiff::Error::Codegen {
            origin: ORIGIN.to_owned(),
            source,
        },
    )
}

#[pymethods]
impl Formula {
    /// Parses the infix `expression` (the syntax of `mechdiff codegen --expr`) and
    /// differentiates it `order` times with respect to `wrt`, without the GIL.
    #[new]
    fn new(py: Python<'_>, expression: &str, wrt: &str, order: usize) -> PyResult<Self> {
        if expression.len() as u64 > MAX_FORMULA_BYTES {
            return Err(argument(
                py,
                format!(
                    "the formula has {} bytes, over the limit of {MAX_FORMULA_BYTES}",
                    expression.len()
                ),
            ));
        }
        let made = py.detach(|| {
            let mut graph = Graph::new();
            let value = graph.parse_infix_piecewise(expression)?;
            let outputs = graph.try_derivatives(value, wrt, order, rules::MAX_NODES)?;
            for (order, output) in outputs.iter().enumerate() {
                if let Some((_, value)) = graph.non_finite_constant(&[*output]) {
                    return Err(mechdiff::core::Error::NonFiniteConstant { order, value });
                }
            }
            let mut parameters = vec![wrt.to_owned()];
            parameters.extend(
                (graph.symbols(&[value]).into_iter())
                    .filter(|s| *s != wrt && !is_named_constant(s))
                    .map(str::to_owned),
            );
            Ok(Formula {
                graph,
                outputs,
                parameters,
            })
        });
        made.map_err(|e| formula_error(py, e))
    }

    /// The variable, then the formula's other symbols in alphabetical order (named
    /// constants such as `pi` are not parameters).
    #[getter]
    fn parameters(&self) -> Vec<String> {
        self.parameters.clone()
    }

    /// The value and each derivative as an s-expression (`(* l (cos phi))`), simplified
    /// and sharing common subexpressions in the engine.
    fn expressions(&self) -> Vec<String> {
        (self.outputs.iter())
            .map(|&id| self.graph.to_sexpr(id))
            .collect()
    }

    /// The value and the derivatives at each point given by `values[k]`, the values of
    /// `names[k]` (equal-length arrays, one per parameter): an array `[point, order + 1]`,
    /// without the GIL. A point where the formula is 0/0 or a derivative is infinite is an
    /// error naming it, never a NaN.
    fn evaluate<'py>(
        &self,
        py: Python<'py>,
        names: Vec<String>,
        values: Vec<PyReadonlyArray1<'py, f64>>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let missing: Vec<&str> = (self.parameters.iter())
            .filter(|p| !names.contains(p))
            .map(String::as_str)
            .collect();
        if !missing.is_empty() || names.len() != values.len() {
            return Err(argument(
                py,
                format!(
                    "the formula needs a value for each of {}; missing: {}",
                    self.parameters.join(", "),
                    missing.join(", ")
                ),
            ));
        }
        if let Some(extra) = names.iter().find(|n| !self.parameters.contains(n)) {
            return Err(argument(
                py,
                format!(
                    "`{extra}` is not a symbol of the formula; its parameters are: {}",
                    self.parameters.join(", ")
                ),
            ));
        }
        let columns: Vec<&[f64]> = values
            .iter()
            .map(|v| v.as_slice())
            .collect::<Result<_, _>>()?;
        let points = columns.first().map_or(1, |c| c.len());
        if columns.iter().any(|c| c.len() != points) {
            return Err(argument(
                py,
                "the parameters' arrays differ in length; give arrays of one shape (or \
                 scalars)"
                    .to_owned(),
            ));
        }
        if points > MAX_POINTS {
            return Err(argument(
                py,
                format!(
                    "{points} points in one call is over the limit of {MAX_POINTS}; ask in chunks"
                ),
            ));
        }
        let width = self.outputs.len();
        let found = py.detach(|| {
            let mut out = Vec::with_capacity(points * width);
            let mut bindings: Vec<(&str, f64)> = names.iter().map(|n| (n.as_str(), 0.0)).collect();
            for i in 0..points {
                for (binding, column) in bindings.iter_mut().zip(&columns) {
                    binding.1 = column[i];
                }
                let at = self.graph.evaluate_f64(&self.outputs, &bindings);
                match at {
                    Ok(v) if v.iter().all(|x| x.is_finite()) => out.extend(v),
                    Ok(v) => {
                        return Err((i, bindings_text(&bindings), format!("not finite: {v:?}")));
                    }
                    Err(e) => return Err((i, bindings_text(&bindings), e.to_string())),
                }
            }
            Ok(out)
        });
        match found {
            Ok(out) => Ok(PyArray1::from_vec(py, out).reshape([points, width])?),
            Err((i, at, why)) => Err(formula_error(
                py,
                mechdiff::core::Error::Formula {
                    input: String::new(),
                    position: 0,
                    message: format!(
                        "at point {i} (from 0: {at}) the value or a derivative is {why}; \
                         write the limit there with if(...)"
                    ),
                },
            )),
        }
    }
}

/// `phi = 0, l = 0.5`.
fn bindings_text(bindings: &[(&str, f64)]) -> String {
    (bindings.iter())
        .map(|(n, v)| format!("{n} = {v}"))
        .collect::<Vec<_>>()
        .join(", ")
}
