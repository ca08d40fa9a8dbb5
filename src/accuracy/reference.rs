//! Reference values in extended precision: formulas differentiated by the symbolic engine
//! and evaluated at 256 bits (≈ 77 digits), kept as double-double numbers.
//!
//! The inputs (drive position, parameters) are the exact `f64` values the methods under test
//! see, so the reference is the exact function at exactly their inputs: what remains in a
//! method's error is its own rounding (and, for finite differences, truncation).

use mechdiff_core::symbolic::{Arithmetic, BigArithmetic, BigReal, Graph, Id};

use super::double_double::DoubleDouble;
use super::method::MAX_ORDER;
use crate::Error;

/// Bits of the reference evaluation.
pub const BITS: usize = 256;

/// A reference value as an unevaluated sum hi + lo of two `f64` (double-double, ≈ 32 digits):
/// enough to measure an `f64` result's error to its last bit ([`DoubleDouble::error`]).
pub type Reference = DoubleDouble;

/// A set of formulas of a drive variable, with their derivatives to order 3 and their
/// condition numbers, ready to be evaluated at 256 bits.
#[derive(Debug)]
pub struct Formulas {
    graph: Graph,
    /// `jets[output]`: the output and its first three derivatives.
    jets: Vec<[Id; MAX_ORDER + 1]>,
    /// `sensitivities[output][order]`: ∂f⁽ᵏ⁾/∂x for every input x (drive first).
    sensitivities: Vec<[Vec<Id>; MAX_ORDER + 1]>,
    /// The inputs: the drive variable, then the parameters.
    inputs: Vec<String>,
}

impl Formulas {
    /// The outputs `roots` of `graph`, functions of `drive` and of `parameters`, differentiated
    /// to order 3 in `drive`, and each derivative's gradient with respect to every input.
    pub fn new(mut graph: Graph, roots: &[Id], drive: &str, parameters: &[&str]) -> Self {
        let inputs: Vec<String> = std::iter::once(drive)
            .chain(parameters.iter().copied())
            .map(str::to_owned)
            .collect();
        let names: Vec<&str> = inputs.iter().map(String::as_str).collect();
        let mut jets = Vec::new();
        let mut sensitivities = Vec::new();
        for &root in roots {
            let d = graph.derivatives(root, drive, MAX_ORDER);
            let jet: [Id; MAX_ORDER + 1] = std::array::from_fn(|k| d[k]);
            let gradients = jet.map(|f| graph.gradient(f, &names));
            jets.push(jet);
            sensitivities.push(gradients);
        }
        Formulas {
            graph,
            jets,
            sensitivities,
            inputs,
        }
    }

    /// The graph (to evaluate the formulas in other arithmetics).
    pub fn graph(&self) -> &Graph {
        &self.graph
    }

    /// The ids of each output's value and derivatives.
    pub fn jets(&self) -> &[[Id; MAX_ORDER + 1]] {
        &self.jets
    }

    /// The reference values `[output][order]` at drive position `drive` with `parameters`
    /// (in the order given to [`Formulas::new`]), as big reals (inputs exact).
    ///
    /// # Errors
    /// [`Error::Reference`] if the formulas do not evaluate (an unbound symbol).
    pub fn evaluate_big(
        &self,
        drive: &BigReal,
        parameters: &[BigReal],
    ) -> Result<Vec<[BigReal; MAX_ORDER + 1]>, Error> {
        let ids: Vec<Id> = self.jets.iter().flatten().copied().collect();
        let values = self.evaluate_ids(&ids, drive, parameters)?;
        Ok(values
            .chunks(MAX_ORDER + 1)
            .map(|c| std::array::from_fn(|k| c[k].clone()))
            .collect())
    }

    /// The reference `[output][order]` and the condition numbers Σ |x ∂f⁽ᵏ⁾/∂x| at the `f64`
    /// inputs (exact).
    ///
    /// # Errors
    /// [`Error::Reference`] if the formulas do not evaluate.
    #[allow(clippy::type_complexity)]
    pub fn reference(
        &self,
        drive: f64,
        parameters: &[f64],
    ) -> Result<(Vec<[Reference; MAX_ORDER + 1]>, Vec<[f64; MAX_ORDER + 1]>), Error> {
        let mut arithmetic = BigArithmetic::new(BITS);
        let big_drive = arithmetic.constant(drive);
        let big: Vec<BigReal> = parameters.iter().map(|&p| arithmetic.constant(p)).collect();
        let values = self.evaluate_big(&big_drive, &big)?;
        let reference = values
            .iter()
            .map(|jet| std::array::from_fn(|k| Reference::from_big(&jet[k])))
            .collect();
        let inputs: Vec<f64> = std::iter::once(drive)
            .chain(parameters.iter().copied())
            .collect();
        let ids: Vec<Id> = self
            .sensitivities
            .iter()
            .flat_map(|orders| orders.iter().flatten().copied())
            .collect();
        let gradients = self.evaluate_ids(&ids, &big_drive, &big)?;
        let n = self.inputs.len();
        let condition = gradients
            .chunks(n * (MAX_ORDER + 1))
            .map(|output| {
                std::array::from_fn(|k| {
                    output[k * n..(k + 1) * n]
                        .iter()
                        .zip(&inputs)
                        .map(|(g, x)| (g.to_f64() * x).abs())
                        .sum()
                })
            })
            .collect();
        Ok((reference, condition))
    }

    fn evaluate_ids(
        &self,
        ids: &[Id],
        drive: &BigReal,
        parameters: &[BigReal],
    ) -> Result<Vec<BigReal>, Error> {
        let lookup = |name: &str| {
            let index = self.inputs.iter().position(|n| n == name)?;
            Some(if index == 0 {
                drive.clone()
            } else {
                parameters.get(index - 1)?.clone()
            })
        };
        self.graph
            .evaluate(&mut BigArithmetic::new(BITS), ids, &lookup)
            .map_err(|source| Error::Reference {
                what: "the formulas".into(),
                reason: source.to_string(),
            })
    }
}
