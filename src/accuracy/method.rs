//! The methods a [`Case`](super::Case) compares and what they give: a method evaluates
//! every output's value and derivatives ′, ″, ‴ at a drive position, exactly or with a step.

use crate::Error;

/// The highest derivative order compared (value, ′, ″, ‴).
pub const MAX_ORDER: usize = 3;

/// The machine epsilon of `f64`, 2⁻⁵² (the spacing of floats at 1).
pub const EPSILON: f64 = f64::EPSILON;

/// One output at one drive position: value and derivatives ′, ″, ‴ (NaN above the method's
/// order, never read).
pub type Values = [f64; MAX_ORDER + 1];

/// Evaluates a method at drive position φ into one [`Values`] per output.
pub type Evaluate<'a> = Box<dyn FnMut(f64, &mut [Values]) -> Result<(), Error> + 'a>;

/// What kind of derivative a method gives.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// Exact up to rounding (dual numbers, symbolic, hand-derived, implicit differentiation).
    Exact,
    /// An approximation with a step h in the drive variable (finite differences).
    Approximate {
        /// The step h (rad, or the drive's unit).
        step: f64,
    },
}

/// A derivative method as the report runs it.
pub struct Method<'a> {
    /// The name printed in the table ("Dual3", "central h=1e-4", …).
    pub name: String,
    /// Exact or approximate.
    pub kind: Kind,
    /// The highest derivative order it computes (0 to 3).
    pub order: usize,
    /// The evaluation at one drive position.
    pub evaluate: Evaluate<'a>,
}

impl<'a> Method<'a> {
    /// An exact method of the given order.
    pub fn exact(
        name: &str,
        order: usize,
        evaluate: impl FnMut(f64, &mut [Values]) -> Result<(), Error> + 'a,
    ) -> Self {
        Method {
            name: name.to_owned(),
            kind: Kind::Exact,
            order,
            evaluate: Box::new(evaluate),
        }
    }
}

/// A function of the drive position to the outputs' values in `f64`: what finite
/// differences differentiate.
pub type Positions<'a> = Box<dyn Fn(f64, &mut [f64]) -> Result<(), Error> + 'a>;

/// Where a method first returned NaN or an infinite value.
#[derive(Clone, Debug, PartialEq)]
pub struct Failure {
    /// The output.
    pub output: String,
    /// The derivative order (0: the value).
    pub order: usize,
    /// The drive position (rad).
    pub phi: f64,
    /// What the method returned (NaN where it returned an error).
    pub value: f64,
    /// The method's error, where it returned one instead of a value.
    pub reason: Option<String>,
}
