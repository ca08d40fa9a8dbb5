//! Gravity: the weight `m·g` of every link with mass, at its centre of gravity.

use super::inertia::Mass;
use super::state::{Generalized, LinkState, dot, of};
use crate::{Error, Scalar};

/// The gravitational acceleration vector (m/s²).
///
/// ```
/// use mechdiff_core::dynamics::Gravity;
/// assert_eq!(Gravity::down(9.81).g, [0.0, -9.81]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gravity {
    /// Acceleration of gravity, global components (m/s²).
    pub g: [f64; 2],
}

impl Gravity {
    /// Gravity of magnitude `g` along −y.
    pub fn down(g: f64) -> Self {
        Gravity { g: [0.0, -g] }
    }

    /// Checks that the vector is finite.
    pub(crate) fn validate(&self) -> Result<(), Error> {
        for (axis, v) in ["x", "y"].iter().zip(self.g) {
            if !v.is_finite() {
                return Err(Error::InvalidValue {
                    what: format!("gravity, {axis} component"),
                    value: v,
                });
            }
        }
        Ok(())
    }
}

/// Adds the weights of `masses` under gravity `g` (m/s²) to the generalized loads.
pub(crate) fn load<T: Scalar>(
    g: [T; 2],
    masses: &[Mass<T>],
    states: &[LinkState<T>],
    q: &mut Generalized<T>,
) {
    for m in masses {
        let s = of(states, m.link);
        q.force(
            states,
            m.link,
            s.position(m.center),
            [m.mass * g[0], m.mass * g[1]],
        );
    }
}

/// Power of the weights under gravity `g` (W): `Σ m g·v_G`.
pub(crate) fn power<T: Scalar>(g: [T; 2], masses: &[Mass<T>], states: &[LinkState<T>]) -> T {
    masses
        .iter()
        .map(|m| {
            let s = of(states, m.link);
            m.mass * dot(g, s.velocity_at(s.position(m.center)))
        })
        .sum()
}
