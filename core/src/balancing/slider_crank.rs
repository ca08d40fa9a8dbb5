//! The slider-crank's primary and secondary unbalance and the classic partial balance.
//!
//! With crank `r`, connecting rod `l`, an in-line slider and the crank turning at constant
//! speed ω, the reciprocating mass `m_rec` (slider and the rod's share at the wrist pin)
//! has the acceleration `ẍ ≈ −r ω² (cos φ + (r/l) cos 2φ)` (the first two terms of the
//! series), so it shakes the frame along the line of stroke with the **primary** force
//! `m_rec r ω² cos φ` and the **secondary** force `m_rec (r²/l) ω² cos 2φ`. The rotating mass
//! (crank and the rod's share at the crank pin, as `m_rot r` at the pin) is balanced fully by
//! a crank counterweight; adding a fraction `c` of `m_rec r` to it turns a primary force
//! `(1 − c) m_rec r ω²` along the line and `c m_rec r ω²` across it: `c = 1/2` makes the
//! primary force's largest value smallest, and it is also the least-squares balance over a
//! revolution (a rotating counterweight cancels only the forward half of the
//! reciprocating `cos φ`).
//!
//! ```
//! use mechdiff_core::balancing::SliderCrankUnbalance;
//! let s = SliderCrankUnbalance::new(0.1, 0.4, 2.0, 0.3).unwrap();
//! assert!((s.primary(100.0) - 2.0 * 0.1 * 1e4).abs() < 1e-9);
//! assert!((s.secondary(100.0) - 2.0 * 0.01 / 0.4 * 1e4).abs() < 1e-9);
//! let half = s.partial_balance(0.5, 100.0).unwrap();
//! assert!((half.counterweight_mass_radius - (0.3 + 0.5 * 2.0 * 0.1)).abs() < 1e-15);
//! ```

use crate::Error;

/// The unbalance data of a slider-crank.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SliderCrankUnbalance {
    /// Crank radius `r` (m).
    pub crank: f64,
    /// Connecting-rod length `l` (m).
    pub rod: f64,
    /// Reciprocating mass `m_rec` (kg).
    pub reciprocating_mass: f64,
    /// Rotating mass-radius `m_rot r` at the crank pin (kg·m).
    pub rotating_mass_radius: f64,
}

/// A crank counterweight that balances the rotating mass and a fraction of the
/// reciprocating one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PartialBalance {
    /// The fraction `c` of `m_rec r` balanced.
    pub fraction: f64,
    /// Counterweight mass-radius `m_rot r + c m_rec r` (kg·m), opposite the crank pin.
    pub counterweight_mass_radius: f64,
    /// Primary force left along the line of stroke, amplitude `(1 − c) m_rec r ω²` (N).
    pub primary_along: f64,
    /// Primary force brought in across the line of stroke, amplitude `c m_rec r ω²` (N).
    pub primary_across: f64,
    /// Secondary force, amplitude `m_rec (r²/l) ω²` (N), which no crank counterweight touches.
    pub secondary: f64,
}

impl SliderCrankUnbalance {
    /// Checks the data: lengths positive, `l > r`, masses finite and ≥ 0.
    pub fn new(
        crank: f64,
        rod: f64,
        reciprocating_mass: f64,
        rotating_mass_radius: f64,
    ) -> Result<Self, Error> {
        for (v, what) in [(crank, "crank radius"), (rod, "connecting-rod length")] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::NonPositiveLength {
                    what: format!("the slider-crank's {what}"),
                    length: v,
                });
            }
        }
        if rod <= crank {
            return Err(Error::InvalidValue {
                what: format!(
                    "connecting-rod length (m; must exceed the crank radius {crank} m for the \
                     crank to turn fully)"
                ),
                value: rod,
            });
        }
        for (v, what) in [
            (reciprocating_mass, "reciprocating mass (kg, ≥ 0)"),
            (rotating_mass_radius, "rotating mass-radius (kg m, ≥ 0)"),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(Error::InvalidValue {
                    what: what.to_owned(),
                    value: v,
                });
            }
        }
        Ok(SliderCrankUnbalance {
            crank,
            rod,
            reciprocating_mass,
            rotating_mass_radius,
        })
    }

    /// Amplitude of the primary unbalance force `m_rec r ω²` (N).
    pub fn primary(&self, omega: f64) -> f64 {
        self.reciprocating_mass * self.crank * omega * omega
    }

    /// Amplitude of the secondary unbalance force `m_rec (r²/l) ω²` (N).
    pub fn secondary(&self, omega: f64) -> f64 {
        self.primary(omega) * self.crank / self.rod
    }

    /// The crank counterweight balancing the rotating mass and the fraction `fraction` (in
    /// [0, 1]) of the reciprocating mass, and the forces it leaves.
    pub fn partial_balance(&self, fraction: f64, omega: f64) -> Result<PartialBalance, Error> {
        if !(0.0..=1.0).contains(&fraction) {
            return Err(Error::InvalidValue {
                what: "fraction of the reciprocating mass to balance (must be in [0, 1])"
                    .to_owned(),
                value: fraction,
            });
        }
        let p = self.primary(omega);
        Ok(PartialBalance {
            fraction,
            counterweight_mass_radius: self.rotating_mass_radius
                + fraction * self.reciprocating_mass * self.crank,
            primary_along: (1.0 - fraction) * p,
            primary_across: fraction * p,
            secondary: self.secondary(omega),
        })
    }
}
