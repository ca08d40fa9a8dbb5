//! The values of a scene's `[parameters]`: the explicit context in which the resolver
//! evaluates the formulas of the file, in `f64` and in dual numbers.

use std::collections::HashMap;

use mechdiff_core::num_dual::Dual64;

/// The scene's parameters, evaluated: the explicit context a scene's formulas are resolved
/// in ([`crate::values::Number::value_in`]); nothing is evaluated while the file is
/// deserialised. With a seeded parameter, each value also carries its derivative with
/// respect to that parameter ([`Bindings::duals`]), so that the resolver run in
/// [`Dual64`] gives the scene's tangent.
#[derive(Debug, Clone, Default)]
pub struct Bindings {
    /// `(name, value in the file's unit)`, in the order of evaluation.
    ordered: Vec<(String, f64)>,
    /// The same values by name.
    values: HashMap<String, f64>,
    /// The values as dual numbers: with the derivative with respect to the seeded
    /// parameter, or 0 without one.
    duals: HashMap<String, Dual64>,
    /// The parameter whose derivative the dual values carry.
    seed: Option<String>,
}

impl Bindings {
    /// Parameters with the given values (in the file's units), none seeded.
    pub fn new(ordered: Vec<(String, f64)>) -> Self {
        let values = ordered.iter().cloned().collect();
        let duals = (ordered.iter())
            .map(|(n, v)| (n.clone(), Dual64::from(*v)))
            .collect();
        Bindings {
            ordered,
            values,
            duals,
            seed: None,
        }
    }

    /// Parameters with the given values (in the file's units), and as dual numbers `duals`
    /// carrying their derivative with respect to the parameter `seed`.
    pub fn seeded(ordered: Vec<(String, f64)>, duals: HashMap<String, Dual64>, seed: &str) -> Self {
        Bindings {
            duals,
            seed: Some(seed.to_owned()),
            ..Bindings::new(ordered)
        }
    }

    /// The values in the order of evaluation (every parameter after those it uses).
    pub fn ordered(&self) -> &[(String, f64)] {
        &self.ordered
    }

    /// The values by name.
    pub fn values(&self) -> &HashMap<String, f64> {
        &self.values
    }

    /// The values as dual numbers, with their derivative with respect to
    /// [`Bindings::seed`] (0 without a seed).
    pub fn duals(&self) -> &HashMap<String, Dual64> {
        &self.duals
    }

    /// The parameter whose derivative the dual values carry, if any.
    pub fn seed(&self) -> Option<&str> {
        self.seed.as_deref()
    }
}
