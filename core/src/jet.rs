//! A quantity and its derivatives with respect to the drive variable φ.

use crate::motion::{DriveState, Motion};

/// The value of a quantity and its first `N` derivatives with respect to the drive variable φ.
///
/// `derivatives[k - 1]` is dᵏx/dφᵏ: for a rocker angle ψ, `Jet<2>` holds ψ, ψ′ and ψ″. The order
/// is part of the type, so a kinematic result cannot be asked for a derivative it did not compute.
///
/// ```
/// use mechdiff_core::Jet;
/// let psi = Jet::new(0.5, [0.6, -0.2]);
/// assert_eq!((psi.value, psi.d1(), psi.d2()), (0.5, 0.6, -0.2));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Jet<const N: usize> {
    /// The value x(φ).
    pub value: f64,
    /// dᵏx/dφᵏ for k = 1..=N.
    pub derivatives: [f64; N],
}

impl<const N: usize> Jet<N> {
    /// A jet from its value and derivatives.
    pub const fn new(value: f64, derivatives: [f64; N]) -> Self {
        Self { value, derivatives }
    }

    /// dᵏx/dφᵏ, with the value as the 0th derivative; `None` above the jet's order.
    pub fn derivative(&self, k: usize) -> Option<f64> {
        match k {
            0 => Some(self.value),
            k => self.derivatives.get(k - 1).copied(),
        }
    }

    /// True if the value and every derivative are finite (neither NaN nor infinite).
    pub fn is_finite(&self) -> bool {
        self.value.is_finite() && self.derivatives.iter().all(|d| d.is_finite())
    }

    /// The jet of lower order `M ≤ N` (the first `M` derivatives).
    ///
    /// A request for more derivatives than the jet holds does not compile.
    pub fn truncate<const M: usize>(&self) -> Jet<M> {
        const { assert!(M <= N, "a jet cannot be truncated to a higher order") };
        Jet::new(self.value, std::array::from_fn(|k| self.derivatives[k]))
    }
}

impl<const N: usize> From<f64> for Jet<N> {
    /// A constant: all derivatives zero.
    fn from(value: f64) -> Self {
        Self::new(value, [0.0; N])
    }
}

impl<const N: usize> Jet<N> {
    /// dx/dφ (a jet of order 0 does not compile).
    pub fn d1(&self) -> f64 {
        const { assert!(N >= 1, "the jet has no first derivative") };
        self.derivatives[0]
    }

    /// d²x/dφ² (a jet of order below 2 does not compile).
    pub fn d2(&self) -> f64 {
        const { assert!(N >= 2, "the jet has no second derivative") };
        self.derivatives[1]
    }

    /// d³x/dφ³ (a jet of order below 3 does not compile).
    pub fn d3(&self) -> f64 {
        const { assert!(N >= 3, "the jet has no third derivative") };
        self.derivatives[2]
    }

    /// Velocity ẋ = ω x′.
    pub fn velocity(&self, drive: &DriveState) -> f64 {
        drive.omega * self.d1()
    }

    /// Position, velocity ẋ = ω x′, acceleration ẍ = α x′ + ω² x″, and for a jet of order 3
    /// the jerk x⃛ = φ⃛ x′ + 3ωα x″ + ω³ x‴ (a jet of order below 2 does not compile).
    pub fn motion(&self, drive: &DriveState) -> Motion {
        Motion::from_jet(self, drive)
    }
}

/// A dual number that carries a jet in φ: [`Dual64`] (order 1), [`Dual2_64`] (order 2),
/// [`Dual3_64`] (order 3). Generic code evaluated in it computes a quantity's derivatives up
/// to its order and no further (an order-2 sweep never computes third derivatives).
///
/// ```
/// use mechdiff_core::JetDual;
/// use mechdiff_core::num_dual::Dual2_64;
/// let x = Dual2_64::from_derivatives([1.0, 2.0, 3.0, 4.0]); // x‴ beyond the order: dropped
/// assert_eq!((x * x).derivatives(), [1.0, 4.0, 14.0, 0.0]); // (x²)″ = 2x′² + 2x x″
/// assert_eq!(x.jet::<1>().derivatives, [2.0]);
/// ```
///
/// [`Dual64`]: num_dual::Dual64
/// [`Dual2_64`]: num_dual::Dual2_64
/// [`Dual3_64`]: num_dual::Dual3_64
pub trait JetDual: crate::Scalar {
    /// The highest derivative carried.
    const ORDER: usize;

    /// The number `x` with derivatives `[x, x′, x″, x‴]` (those beyond [`JetDual::ORDER`]
    /// are dropped).
    fn from_derivatives(d: [f64; 4]) -> Self;

    /// `[x, x′, x″, x‴]`, zero beyond [`JetDual::ORDER`].
    fn derivatives(&self) -> [f64; 4];

    /// The jet of order `N` ≤ [`JetDual::ORDER`] (derivatives beyond the order read as 0).
    #[inline]
    fn jet<const N: usize>(&self) -> Jet<N> {
        let d = self.derivatives();
        Jet::new(d[0], std::array::from_fn(|k| d[k + 1]))
    }
}

impl JetDual for num_dual::Dual64 {
    const ORDER: usize = 1;

    #[inline]
    fn from_derivatives(d: [f64; 4]) -> Self {
        num_dual::Dual64::new(d[0], d[1])
    }

    #[inline]
    fn derivatives(&self) -> [f64; 4] {
        [self.re, self.eps, 0.0, 0.0]
    }
}

impl JetDual for num_dual::Dual2_64 {
    const ORDER: usize = 2;

    #[inline]
    fn from_derivatives(d: [f64; 4]) -> Self {
        num_dual::Dual2_64::new(d[0], d[1], d[2])
    }

    #[inline]
    fn derivatives(&self) -> [f64; 4] {
        [self.re, self.v1, self.v2, 0.0]
    }
}

impl JetDual for num_dual::Dual3_64 {
    const ORDER: usize = 3;

    #[inline]
    fn from_derivatives(d: [f64; 4]) -> Self {
        num_dual::Dual3_64::new(d[0], d[1], d[2], d[3])
    }

    #[inline]
    fn derivatives(&self) -> [f64; 4] {
        [self.re, self.v1, self.v2, self.v3]
    }
}
