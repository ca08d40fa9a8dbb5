//! Position functions: a mechanism's position equations, written once.

use crate::scalar::Scalar;

/// A mechanism's position equations as a function of the drive variable φ, written once,
/// generic over the scalar type.
///
/// `Output<T>` is the family of outputs: a scalar (`type Output<T> = T`), an array
/// (`[T; 3]`), or a struct of the mechanism's points and angles (`Pose<T>`). Evaluating with
/// `f64` gives positions; with a num-dual number, exact derivatives (see [`crate::method`]).
///
/// [`map`](Self::map) turns an output of one scalar type into the same output of another; it
/// must visit every scalar exactly once, always in the same order (the derivative methods rely
/// on it to flatten and rebuild outputs).
///
/// ```
/// use mechdiff_core::{PositionFunction, Scalar, atan2};
///
/// /// The Whitworth rocker angle ψ(φ) for λ = l1/l0.
/// struct Rocker { lambda: f64 }
///
/// impl PositionFunction for Rocker {
///     type Output<T> = T;
///     fn evaluate<D: Scalar>(&self, phi: D) -> D {
///         atan2(phi.sin() * self.lambda, -phi.cos() * self.lambda + 1.0)
///     }
///     fn map<A, B>(psi: A, mut f: impl FnMut(A) -> B) -> B {
///         f(psi)
///     }
/// }
/// assert!((Rocker { lambda: 0.375 }.evaluate(std::f64::consts::PI)).abs() < 1e-16);
/// ```
pub trait PositionFunction {
    /// The outputs (points, angles, displacements) for scalar type `T`.
    type Output<T>;

    /// The outputs at drive position `phi`.
    fn evaluate<D: Scalar>(&self, phi: D) -> Self::Output<D>;

    /// Applies `f` to every scalar of an output, in a fixed order.
    fn map<A, B>(output: Self::Output<A>, f: impl FnMut(A) -> B) -> Self::Output<B>;
}

/// The scalars of an output in [`PositionFunction::map`] order, and the output's shape.
pub(crate) fn flatten<F: PositionFunction, T>(output: F::Output<T>) -> (F::Output<()>, Vec<T>) {
    let mut scalars = Vec::new();
    let shape = F::map(output, |x| scalars.push(x));
    (shape, scalars)
}

/// An output of the given shape, with scalars taken in order from `scalars`.
pub(crate) fn rebuild<F: PositionFunction, U>(
    shape: F::Output<()>,
    scalars: impl IntoIterator<Item = U>,
) -> F::Output<U> {
    let mut scalars = scalars.into_iter();
    F::map(shape, |()| {
        scalars
            .next()
            .expect("PositionFunction::map visits the same scalars on every call")
    })
}
