//! Truncated Taylor series: the limit of a formula at a removable singularity.
//!
//! A [`Taylor`] holds the normalised coefficients `c_k = f⁽ᵏ⁾(x₀)/k!` of a function of one
//! variable at a point, to order [`TERMS`]` − 1`. Every primitive follows the standard
//! recurrences (products by convolution; `exp`, `sin`, `cos`, `sinh`, `cosh` by
//! `f′ = g·u′`; `ln`, `atan`, `asin`, `acos`, `atan2` by integrating their derivative series).
//! Division cancels common leading zeros — L'Hôpital in series form: if `a = tᵏ·ã` and
//! `b = tᵏ·b̃` with `b̃(0) ≠ 0`, then `a/b = ã/b̃` — which resolves a 0/0 whose limit exists.
//! Each cancelled zero costs one coefficient at the top (set to NaN, so that a result which
//! needed more is seen as unresolved, never as a wrong number).
//!
//! Powers through a zero of their base (`x³·⁵`, `∛(x³)`, `√(x⁴)` at 0) follow `uᵖ = tᵐᵖ·ũᵖ`
//! (`power`): a Taylor series where there is one, a one-sided series (flagged with its
//! [`Side`]) where the power is real on one side only, and an error naming the reason
//! where the derivatives do not exist (`√(x²) = |x|` at 0).
//!
//! [`Graph::limit_jets`] evaluates formulas this way and returns value and derivatives to
//! order 3.

mod power;

use self::power::Power;
use super::graph::{Graph, Id};
use super::ops::{Binary, Comparison, Unary};
use crate::Scalar;
use crate::error::Error;

use super::eval::Arithmetic;

/// Coefficients carried: orders 0 to 7, so that up to 4 leading zeros can be cancelled and
/// the value and three derivatives still come out.
pub const TERMS: usize = 8;

/// A truncated Taylor series in `T` (`f64` or any [`Scalar`] of higher precision).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Taylor<T> {
    /// `c[k] = f⁽ᵏ⁾(x₀)/k!`; NaN where not known.
    pub c: [T; TERMS],
}

fn nan<T: Scalar>() -> T {
    T::from(f64::NAN)
}

/// Whether a coefficient is exactly zero (not merely tiny).
fn zero<T: Scalar>(x: &T) -> bool {
    x.re() == 0.0 && x.is_zero()
}

/// The side of the point on which a formula is real, where that is one side only: its
/// limits there are one-sided.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// Real for `x ≥ x₀` only (`x³·⁵` at 0).
    Above,
    /// Real for `x ≤ x₀` only (`(−x)³·⁵` at 0).
    Below,
}

impl<T: Scalar> Taylor<T> {
    /// The constant `value`.
    pub fn constant(value: T) -> Self {
        let mut c = [T::from(0.0); TERMS];
        c[0] = value;
        Taylor { c }
    }

    /// The variable itself at `x0`: `x0 + t`.
    pub fn variable(x0: T) -> Self {
        let mut s = Self::constant(x0);
        s.c[1] = T::from(1.0);
        s
    }

    /// The value and derivatives to order 3: `k!·c_k`.
    pub fn jet(&self) -> [T; 4] {
        [
            self.c[0],
            self.c[1],
            self.c[2] * T::from(2.0),
            self.c[3] * T::from(6.0),
        ]
    }

    fn map2(a: &Self, b: &Self, f: impl Fn(T, T) -> T) -> Self {
        Taylor {
            c: std::array::from_fn(|k| f(a.c[k], b.c[k])),
        }
    }

    fn mul(a: &Self, b: &Self) -> Self {
        Taylor {
            c: std::array::from_fn(|k| (0..=k).map(|j| a.c[j] * b.c[k - j]).sum()),
        }
    }

    fn scale(&self, s: T) -> Self {
        Taylor {
            c: self.c.map(|x| x * s),
        }
    }

    /// The derivative series (one coefficient fewer: the top one is NaN).
    fn derivative(&self) -> Self {
        Taylor {
            c: std::array::from_fn(|k| {
                if k + 1 < TERMS {
                    self.c[k + 1] * T::from((k + 1) as f64)
                } else {
                    nan()
                }
            }),
        }
    }

    /// The series whose derivative is `self` and whose value is `c0`.
    fn integral(&self, c0: T) -> Self {
        Taylor {
            c: std::array::from_fn(|k| {
                if k == 0 {
                    c0
                } else {
                    self.c[k - 1] / T::from(k as f64)
                }
            }),
        }
    }

    /// `a/b` with `b(0) ≠ 0` (plain series division).
    fn quotient(a: &[T], b: &[T]) -> Vec<T> {
        let mut q: Vec<T> = Vec::with_capacity(a.len());
        for k in 0..a.len() {
            let s: T = (1..=k).map(|j| b[j] * q[k - j]).sum();
            q.push((a[k] - s) / b[0]);
        }
        q
    }

    /// `a/b`, cancelling common leading zeros; the second value says whether any were.
    pub fn div(a: &Self, b: &Self) -> (Self, bool) {
        let Some(k) = b.c.iter().position(|x| !zero(x)) else {
            return (Self::constant(nan()), false);
        };
        if !b.c[k].re().is_finite() {
            // Zeros as far as the series is known: unresolved.
            return (Self::constant(nan()), false);
        }
        if let Some(j) = a.c[..k].iter().position(|x| !zero(x)) {
            // A true pole: a/0 with a ≠ 0.
            let mut pole = Self::constant(a.c[j] / T::from(0.0));
            pole.c[1..].fill(nan());
            return (pole, false);
        }
        let q = Self::quotient(&a.c[k..], &b.c[k..]);
        let mut c = [nan(); TERMS];
        c[..q.len()].copy_from_slice(&q);
        (Taylor { c }, k > 0)
    }

    /// `exp u`, from `f′ = f·u′`.
    fn exp(u: &Self) -> Self {
        let mut f = [T::from(0.0); TERMS];
        f[0] = u.c[0].exp();
        for k in 1..TERMS {
            let s: T = (1..=k).map(|j| u.c[j] * f[k - j] * T::from(j as f64)).sum();
            f[k] = s / T::from(k as f64);
        }
        Taylor { c: f }
    }

    /// `(sin u, cos u)`, or `(sinh u, cosh u)` when `hyperbolic`.
    fn sin_cos(u: &Self, hyperbolic: bool) -> (Self, Self) {
        let mut s = [T::from(0.0); TERMS];
        let mut c = [T::from(0.0); TERMS];
        (s[0], c[0]) = if hyperbolic {
            (u.c[0].sinh(), u.c[0].cosh())
        } else {
            (u.c[0].sin(), u.c[0].cos())
        };
        for k in 1..TERMS {
            let (mut ss, mut cc) = (T::from(0.0), T::from(0.0));
            for j in 1..=k {
                let ju = u.c[j] * T::from(j as f64);
                ss += ju * c[k - j];
                cc += ju * s[k - j];
            }
            let kt = T::from(k as f64);
            s[k] = ss / kt;
            c[k] = if hyperbolic { cc / kt } else { -cc / kt };
        }
        (Taylor { c: s }, Taylor { c })
    }

    fn powi(u: &Self, n: i32) -> (Self, bool) {
        let mut result = Self::constant(T::from(1.0));
        let mut base = *u;
        let mut m = n.unsigned_abs();
        while m > 0 {
            if m & 1 == 1 {
                result = Self::mul(&result, &base);
            }
            base = Self::mul(&base, &base);
            m >>= 1;
        }
        if n < 0 {
            Self::div(&Self::constant(T::from(1.0)), &result)
        } else {
            (result, false)
        }
    }
}

/// Evaluation in truncated Taylor series of `T`; records whether a 0/0 was cancelled.
#[derive(Debug, Clone)]
pub struct TaylorArithmetic<T> {
    /// Whether a division cancelled common leading zeros, or a power through a zero of its
    /// base had a chain rule of 0·∞ (a removable singularity: the limit is taken).
    pub removed: bool,
    /// The side on which the formula is real, where only one is (see [`Side`]).
    pub side: Option<Side>,
    /// Whether one part is real only above the point and another only below.
    conflict: bool,
    /// Why a coefficient became unknown, first reason first.
    reason: Option<String>,
    scalar: std::marker::PhantomData<T>,
}

impl<T: Scalar> TaylorArithmetic<T> {
    /// An arithmetic that has resolved nothing yet.
    pub fn new() -> Self {
        TaylorArithmetic {
            removed: false,
            side: None,
            conflict: false,
            reason: None,
            scalar: std::marker::PhantomData,
        }
    }

    /// Keeps `reason` for the error if no earlier one is kept.
    fn note(&mut self, reason: String) {
        self.reason.get_or_insert(reason);
    }

    fn divide(&mut self, a: &Taylor<T>, b: &Taylor<T>) -> Taylor<T> {
        let (q, removed) = Taylor::div(a, b);
        self.removed |= removed;
        q
    }
}

impl<T: Scalar> Default for TaylorArithmetic<T> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Scalar> Arithmetic for TaylorArithmetic<T> {
    type Value = Taylor<T>;

    fn constant(&mut self, c: f64) -> Taylor<T> {
        Taylor::constant(T::from(c))
    }

    fn unary(&mut self, op: Unary, u: &Taylor<T>) -> Taylor<T> {
        let one = Taylor::constant(T::from(1.0));
        let du = u.derivative();
        // 1 − u² and its square root, for asin and acos.
        let root = |this: &mut Self| {
            let w = Taylor::map2(&one, &Taylor::mul(u, u), |a, b| a - b);
            let r = this.power(&w, Power::Sqrt);
            this.divide(&du, &r)
        };
        match op {
            Unary::Neg => u.scale(T::from(-1.0)),
            Unary::Sqrt => self.power(u, Power::Sqrt),
            Unary::Cbrt => self.power(u, Power::Cbrt),
            Unary::Exp => Taylor::exp(u),
            Unary::Ln => self.divide(&du, u).integral(u.c[0].ln()),
            Unary::Sin => Taylor::sin_cos(u, false).0,
            Unary::Cos => Taylor::sin_cos(u, false).1,
            Unary::Tan => {
                let (s, c) = Taylor::sin_cos(u, false);
                let mut t = self.divide(&s, &c);
                t.c[0] = u.c[0].tan();
                t
            }
            Unary::Sinh => Taylor::sin_cos(u, true).0,
            Unary::Cosh => Taylor::sin_cos(u, true).1,
            // |u| ≥ 1: tanh u = s (1 − w)/(1 + w) with w = e^(−2s·u), s the sign of u(x₀):
            // w ≤ e^-2, so nothing overflows (sinh/cosh is ∞/∞ past |u| = 710) and 1 − w
            // does not cancel
            Unary::Tanh if u.c[0].re().abs() >= 1.0 => {
                let sign = T::from(u.c[0].re().signum());
                let w = Taylor::exp(&u.scale(sign * T::from(-2.0)));
                let numerator = Taylor::map2(&one, &w, |a, b| a - b);
                let denominator = Taylor::map2(&one, &w, |a, b| a + b);
                let mut t = self.divide(&numerator, &denominator).scale(sign);
                t.c[0] = u.c[0].tanh();
                t
            }
            Unary::Tanh => {
                let (s, c) = Taylor::sin_cos(u, true);
                let mut t = self.divide(&s, &c);
                t.c[0] = u.c[0].tanh();
                t
            }
            Unary::Atan => {
                let w = Taylor::map2(&one, &Taylor::mul(u, u), |a, b| a + b);
                self.divide(&du, &w).integral(u.c[0].atan())
            }
            Unary::Asin => root(self).integral(u.c[0].asin()),
            Unary::Acos => root(self).scale(T::from(-1.0)).integral(u.c[0].acos()),
            Unary::Abs => self.abs(u),
        }
    }

    fn binary(&mut self, op: Binary, a: &Taylor<T>, b: &Taylor<T>) -> Taylor<T> {
        match op {
            Binary::Add => Taylor::map2(a, b, |x, y| x + y),
            Binary::Sub => Taylor::map2(a, b, |x, y| x - y),
            Binary::Mul => Taylor::mul(a, b),
            Binary::Div => self.divide(a, b),
            // A constant exponent (a number or a subgraph of constants): the power's own
            // series, through a zero of the base.
            Binary::Powf if b.c[1..].iter().all(zero) => self.power(a, Power::Powf(b.c[0])),
            Binary::Powf => {
                if a.c[0].re() == 0.0 {
                    self.note("powf with a variable exponent at base 0: ln 0".to_owned());
                }
                let ln = self.unary(Unary::Ln, a);
                let mut f = Taylor::exp(&Taylor::mul(b, &ln));
                f.c[0] = a.c[0].powd(b.c[0]);
                f
            }
            Binary::Atan2 => {
                // (atan2(y, x))′ = (x y′ − y x′)/(x² + y²).
                let cross = Taylor::map2(
                    &Taylor::mul(b, &a.derivative()),
                    &Taylor::mul(a, &b.derivative()),
                    |p, q| p - q,
                );
                let r2 = Taylor::map2(&Taylor::mul(a, a), &Taylor::mul(b, b), |p, q| p + q);
                self.divide(&cross, &r2)
                    .integral(crate::atan2(a.c[0], b.c[0]))
            }
            Binary::Hypot => {
                let r2 = Taylor::map2(&Taylor::mul(a, a), &Taylor::mul(b, b), |p, q| p + q);
                let mut f = self.power(&r2, Power::Sqrt);
                f.c[0] = crate::scalar::hypot(a.c[0], b.c[0]);
                f
            }
        }
    }

    fn powi(&mut self, u: &Taylor<T>, n: i32) -> Taylor<T> {
        let (p, removed) = Taylor::powi(u, n);
        self.removed |= removed;
        p
    }

    fn compare(&mut self, cmp: Comparison, a: &Taylor<T>, b: &Taylor<T>) -> bool {
        cmp.holds(&a.c[0].re(), &b.c[0].re())
    }
}

/// Value and derivatives to order 3 of formulas at a point, through their limits.
#[derive(Debug, Clone, PartialEq)]
pub struct Limits<T> {
    /// `[value, ′, ″, ‴]` per output.
    pub jets: Vec<[T; 4]>,
    /// Whether a 0/0 was resolved on the way (a removable singularity: the limit was taken).
    pub removed: bool,
    /// `Some` if the formula is real on one side of the point only: the jets are that
    /// side's limits (`x^3.5` at 0: from above).
    pub side: Option<Side>,
}

impl Graph {
    /// Value and derivatives to order 3 of `outputs` with respect to `variable` at the
    /// point `bindings` (which binds `variable` too), evaluated in truncated Taylor series:
    /// a 0/0 whose limit exists (`sin x / x` at 0, `(x² − 1)/(x − 1)` at 1) gives that
    /// limit, and [`Limits::removed`] says so.
    ///
    /// ```
    /// use mechdiff_core::symbolic::Graph;
    ///
    /// let mut graph = Graph::new();
    /// let f = graph.parse_infix("sin(x)/x").unwrap();
    /// let limits = graph.limit_jets::<f64>(&[f], "x", &[("x", 0.0)]).unwrap();
    /// assert_eq!(limits.jets[0], [1.0, 0.0, -1.0 / 3.0, 0.0]);
    /// assert!(limits.removed);
    /// ```
    ///
    /// A power through a zero of its base is taken as `tᵐᵖ·ũᵖ` (see [`Side`] and the module
    /// documentation): `cbrt(x^3)` at 0 gives `x`'s jet, `x^3.5` gives zeros from above.
    ///
    /// # Errors
    /// [`Error::UnboundSymbol`] if a symbol has no value; [`Error::NotDifferentiable`] if a
    /// result is not finite for a reason found (`sqrt(x^2)` at 0 is `|x|`; `x^2.5` has no
    /// third derivative at 0; a formula real on neither side, or above in one part and below
    /// in another); [`Error::ZeroOverZero`] otherwise (a 0/0 whose cancellation needs more
    /// than four orders, or a true pole).
    pub fn limit_jets<T: Scalar>(
        &self,
        outputs: &[Id],
        variable: &str,
        bindings: &[(&str, T)],
    ) -> Result<Limits<T>, Error> {
        let lookup = |name: &str| {
            bindings.iter().find(|(n, _)| *n == name).map(|&(n, v)| {
                if n == variable {
                    Taylor::variable(v)
                } else {
                    Taylor::constant(v)
                }
            })
        };
        let mut arithmetic = TaylorArithmetic::<T>::new();
        let series = self.evaluate(&mut arithmetic, outputs, &lookup)?;
        let shortened = |id: Id| {
            let expression = self.to_sexpr(id);
            if expression.chars().count() > 80 {
                expression.chars().take(77).collect::<String>() + "..."
            } else {
                expression
            }
        };
        if arithmetic.conflict {
            return Err(Error::NotDifferentiable {
                expression: shortened(outputs[0]),
                reason: "one part is real only above the point and another only below it:                          the formula is defined at the point alone"
                    .to_owned(),
            });
        }
        let mut jets = Vec::with_capacity(series.len());
        for (s, &id) in series.iter().zip(outputs) {
            let jet = s.jet();
            if jet.iter().any(|x| !x.re().is_finite()) {
                let expression = shortened(id);
                return Err(match arithmetic.reason.take() {
                    Some(reason) => Error::NotDifferentiable { expression, reason },
                    None => Error::ZeroOverZero { expression },
                });
            }
            jets.push(jet);
        }
        Ok(Limits {
            jets,
            removed: arithmetic.removed,
            side: arithmetic.side,
        })
    }
}
