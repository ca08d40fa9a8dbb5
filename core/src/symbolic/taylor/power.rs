//! Powers of a series, including at a zero of the base: `uᵖ` with a constant exponent,
//! `√u`, `∛u`, `|u|`.
//!
//! Where the base vanishes, `u = tᵐ·ũ` with `m` leading zeros and `ũ(0) = a ≠ 0`, and
//! `uᵖ = tᵐᵖ·ũᵖ` where that is real. With `q = m·p`:
//! - an integer exponent `p` (or `∛` with `3 | m`): `tᵠ·ũᵖ`, a Taylor series on both sides;
//! - `powf`/`√` with `p` not an integer is real only where `u ≥ 0`: above the point if
//!   `a > 0`, below it if `a·(−1)ᵐ > 0`. On a side where it is real it equals `|t|ᵠ·|ũ|ᵖ`:
//!   - `q` even, both sides: `tᵠ·|ũ|ᵖ`, a Taylor series (`√(x⁴) = x²`);
//!   - `q` an integer, one side only: the one-sided series `(±t)ᵠ·|ũ|ᵖ`, and the limit is
//!     flagged one-sided ([`Side`]);
//!   - `q` odd, both sides: `|t|ᵠ`: derivatives below order `q` are 0, from order `q` on
//!     the two sides differ (`√(x²) = |x|`): not differentiable, never a one-sided answer
//!     passed off as two-sided;
//!   - `q` not an integer: derivatives below order `q` are 0 (`x³·⁵` at 0: 0, 0, 0, 0, as the
//!     limits of `3.5·2.5·1.5·x⁰·⁵` etc.), above it infinite; one-sided if real on one side;
//!   - real on neither side: not defined beside the point;
//! - `∛` with `3 ∤ m`: `|t|^(m/3)` up to sign on both sides: zeros below order `m/3`,
//!   infinite above.
//!
//! `q` counts as an integer when it is one within 4 ulp: `powf(x³, 1/3)` is `x`, as the
//! rounded exponent `1/3` gives within 1e-16 relative for any `f64` argument.
//!
//! Unknown coefficients are NaN, and the reason is kept for the error
//! ([`crate::error::Error::NotDifferentiable`]).

use super::{Side, TERMS, Taylor, TaylorArithmetic, nan, zero};
use crate::Scalar;

/// The power function taken.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Power<T> {
    /// `√u`.
    Sqrt,
    /// `∛u`, real for negative `u` too.
    Cbrt,
    /// `u.powf(p)` with a constant `p`.
    Powf(T),
}

impl<T: Scalar> Power<T> {
    fn name(self) -> &'static str {
        match self {
            Power::Sqrt => "sqrt",
            Power::Cbrt => "cbrt",
            Power::Powf(_) => "powf",
        }
    }

    fn exponent(self) -> T {
        match self {
            Power::Sqrt => T::from(0.5),
            Power::Cbrt => T::from(1.0) / T::from(3.0),
            Power::Powf(p) => p,
        }
    }

    /// `a^p` for `a ≠ 0` (positive unless the power is real for negative bases).
    fn of(self, a: T) -> T {
        match self {
            Power::Sqrt => a.sqrt(),
            Power::Cbrt => a.cbrt(),
            Power::Powf(p) if p.re().fract() == 0.0 && p.re().abs() <= 1e9 => a.powi(p.re() as i32),
            Power::Powf(p) => a.powd(p),
        }
    }
}

/// The series of `ũᵖ` for `ũ(0) ≠ 0` from `ũ·f′ = p·f·ũ′`:
/// `k·ũ₀·f_k = Σ_{j=1..k} (p·j − (k − j))·ũ_j·f_{k−j}`.
fn power_series<T: Scalar>(u: &[T], p: T, f0: T) -> Vec<T> {
    let mut f = Vec::with_capacity(u.len());
    f.push(f0);
    for k in 1..u.len() {
        let s: T = (1..=k)
            .map(|j| (p * T::from(j as f64) - T::from((k - j) as f64)) * u[j] * f[k - j])
            .sum();
        f.push(s / (T::from(k as f64) * u[0]));
    }
    f
}

/// `q` rounded to the nearest integer if within 4 ulp of it (an exponent such as `1/3`
/// rounded to `f64`, times 3), else `q`.
fn integral(q: f64) -> f64 {
    let nearest = q.round();
    if (q - nearest).abs() <= 4.0 * f64::EPSILON * nearest.abs() {
        nearest
    } else {
        q
    }
}

/// `sign·tᵠ·w`: `q` zeros, then `w` (scaled), NaN beyond what `w` knows.
fn shifted<T: Scalar>(w: &[T], q: usize, sign: f64) -> Taylor<T> {
    Taylor {
        c: std::array::from_fn(|k| match k.checked_sub(q) {
            None => T::from(0.0),
            Some(j) if j < w.len() => w[j] * T::from(sign),
            Some(_) => nan(),
        }),
    }
}

/// `|t|^q·…` with derivatives only below order `q`: zeros there, NaN from order `q` on.
fn zeros_below<T: Scalar>(q: f64) -> Taylor<T> {
    Taylor {
        c: std::array::from_fn(|k| if (k as f64) < q { T::from(0.0) } else { nan() }),
    }
}

impl<T: Scalar> TaylorArithmetic<T> {
    /// `power(u)`, through a zero of `u` where the result has derivatives (see the module).
    pub(super) fn power(&mut self, u: &Taylor<T>, power: Power<T>) -> Taylor<T> {
        let name = power.name();
        let p = power.exponent();
        let unknown = Taylor { c: [nan(); TERMS] };
        let Some(m) = u.c.iter().position(|x| !zero(x)) else {
            self.note(format!(
                "the argument of {name} is zero to the order carried ({TERMS} terms)"
            ));
            return unknown;
        };
        let a = u.c[m];
        if !a.re().is_finite() {
            return unknown;
        }
        let integer = matches!(power, Power::Powf(p) if p.re().fract() == 0.0);
        let real_for_negative = integer || power == Power::Cbrt;
        if m == 0 {
            if a.re() < 0.0 && !real_for_negative {
                self.note(format!(
                    "{name} of the negative number {:e} (exponent {}): not real",
                    a.re(),
                    p.re()
                ));
                return unknown;
            }
            let w = power_series(&u.c, p, power.of(a));
            return shifted(&w, 0, 1.0);
        }
        // The base vanishes: u = tᵐ·ũ.
        let pf = p.re();
        if pf < 0.0 {
            self.note(format!(
                "{name} of a zero of order {m} to the negative power {pf}: a pole"
            ));
            let mut pole = Taylor::constant(T::from(f64::INFINITY));
            pole.c[1..].fill(nan());
            return pole;
        }
        let q = if power == Power::Cbrt {
            m as f64 / 3.0
        } else {
            integral((T::from(m as f64) * p).re())
        };
        // ũ with a positive leading coefficient where the power needs a positive base.
        let sign = if real_for_negative {
            1.0
        } else {
            a.re().signum()
        };
        let tilde: Vec<T> = u.c[m..].iter().map(|&x| x * T::from(sign)).collect();
        let below_factor = if m.is_multiple_of(2) { 1.0 } else { -1.0 };
        let (above, below) = if real_for_negative {
            (true, true)
        } else {
            (a.re() > 0.0, a.re() * below_factor > 0.0)
        };
        if !above && !below {
            self.note(format!(
                "{name} of a quantity negative on both sides of its zero (order {m}): not \
                 real beside the point"
            ));
            return unknown;
        }
        if integer {
            // An integer power: tᵐᵖ·ũᵖ on both sides.
            let w = power_series(&tilde, p, power.of(tilde[0]));
            return shifted(&w, q as usize, 1.0);
        }
        // The chain rule is 0·∞ or ∞ here: what follows is a limit.
        self.removed = true;
        if q.fract() != 0.0 {
            let what = if power == Power::Cbrt {
                format!("cbrt of a zero of order {m}: |t|^({m}/3)")
            } else {
                format!("{name} of a zero of order {m}: |t|^{q}")
            };
            self.note(format!(
                "{what}, whose derivatives of order above {q} are infinite at the point"
            ));
            if power != Power::Cbrt {
                self.one_side(above, below);
            }
            return zeros_below(q);
        }
        let q = q as usize;
        let w = power_series(&tilde, p, power.of(tilde[0]));
        if power == Power::Cbrt || above && below && q.is_multiple_of(2) {
            return shifted(&w, q, 1.0);
        }
        if above && below {
            self.note(format!(
                "{name} of a zero of order {m}: |t|^{q}, whose derivatives of order {q} and \
                 above differ on the two sides (not differentiable there)"
            ));
            return zeros_below(q as f64);
        }
        // Real on one side only: the one-sided series (±t)^q·|ũ|^p.
        self.one_side(above, below);
        let sign = if above || q.is_multiple_of(2) {
            1.0
        } else {
            -1.0
        };
        shifted(&w, q, sign)
    }

    /// `|u|`: `±u` where `u` keeps its sign (a zero of even order included); at a zero of
    /// odd order `m`, zeros below order `m` and no derivatives from `m` on.
    pub(super) fn abs(&mut self, u: &Taylor<T>) -> Taylor<T> {
        let Some(m) = u.c.iter().position(|x| !zero(x)) else {
            return *u;
        };
        if m % 2 == 1 {
            self.note(format!(
                "abs of a quantity that changes sign at the point (a zero of order {m}): its \
                 derivatives of order {m} and above differ on the two sides"
            ));
            return zeros_below(m as f64);
        }
        if u.c[m].re() < 0.0 {
            u.scale(T::from(-1.0))
        } else {
            *u
        }
    }

    /// Records that a result is real only above (`above`) or only below the point.
    fn one_side(&mut self, above: bool, below: bool) {
        let side = match (above, below) {
            (true, false) => Side::Above,
            (false, true) => Side::Below,
            _ => return,
        };
        match self.side {
            Some(s) if s != side => self.conflict = true,
            _ => self.side = Some(side),
        }
    }
}
