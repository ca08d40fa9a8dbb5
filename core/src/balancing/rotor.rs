//! Rotors: masses on a rigid shaft, balanced in one plane (static) or two (dynamic).
//!
//! A mass `m` at radius `r` and angle `θ` in the plane at axial position `z` is the
//! mass-radius vector `U = m r e^{iθ}` (kg·m). Turning at speed ω, it pulls on the shaft with
//! the centrifugal force `ω² U` and, about the axial position `z₀`, the couple `ω² U (z − z₀)`.
//! The rotor is balanced when the **force polygon** (mr) and the **couple polygon** (mrd)
//! close:
//!
//! ```text
//! Σ Uᵢ = 0                 (static balance: the centre of mass on the axis)
//! Σ Uᵢ (zᵢ − z₀) = 0       (dynamic balance: no couple, for every z₀ once Σ Uᵢ = 0)
//! ```
//!
//! One correction `U_c = −Σ Uᵢ` closes the force polygon; two corrections in distinct planes
//! `z_L ≠ z_R` close both, uniquely:
//! `U_R = −Σ Uᵢ (zᵢ − z_L)/(z_R − z_L)`, `U_L = −Σ Uᵢ (zᵢ − z_R)/(z_L − z_R)`.
//! Angles are returned by `atan2`, well conditioned at every angle (reference 002's `asin`
//! route loses digits near 90°).
//!
//! ```
//! use mechdiff_core::balancing::{Rotor, RotorMass};
//! let rotor = Rotor::new(vec![
//!     RotorMass { mass: 2.0, radius: 0.1, angle: 0.0, axial: 0.0 },
//!     RotorMass { mass: 1.0, radius: 0.1, angle: std::f64::consts::FRAC_PI_2, axial: 0.5 },
//! ]).unwrap();
//! let fix = rotor.static_balance(0.0);
//! // Σ U = (0.2, 0.1) kg·m, so the correction is (−0.2, −0.1) kg·m.
//! assert!((fix.mass_radius - 0.05f64.sqrt()).abs() < 1e-15);
//! assert!((fix.angle - (-0.1f64).atan2(-0.2)).abs() < 1e-15);
//! let two = rotor.two_plane_balance(0.0, 0.5).unwrap();
//! let after = rotor.with_corrections(&two.corrections());
//! assert!(after.resultant_force().iter().all(|c| c.abs() < 1e-15));
//! ```

use crate::{Error, Scalar};

/// One mass on the rotor, in its plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RotorMass {
    /// Mass (kg, > 0).
    pub mass: f64,
    /// Radius of its centre from the shaft axis (m, ≥ 0).
    pub radius: f64,
    /// Angle in the rotor's frame, counter-clockwise (rad).
    pub angle: f64,
    /// Axial position of its plane along the shaft (m).
    pub axial: f64,
}

impl RotorMass {
    /// The mass-radius vector `m r (cos θ, sin θ)` (kg·m).
    pub fn mass_radius(&self) -> [f64; 2] {
        self.mass_radius_in()
    }

    /// [`RotorMass::mass_radius`] computed in the scalar `D` (the same operations; with a
    /// higher-precision `D`, the accuracy report's reference for the `f64` answers).
    pub fn mass_radius_in<D: Scalar>(&self) -> [D; 2] {
        let angle = D::from(self.angle);
        let mr = D::from(self.mass) * self.radius;
        [mr * angle.cos(), mr * angle.sin()]
    }
}

/// A rigid rotor: masses on a shaft.
#[derive(Debug, Clone, PartialEq)]
pub struct Rotor {
    masses: Vec<RotorMass>,
}

/// A correction in one plane: the mass-radius vector to add, as magnitude and angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Correction {
    /// Axial position of the correction plane (m).
    pub axial: f64,
    /// Components of the mass-radius vector `m r (cos θ, sin θ)` (kg·m).
    pub vector: [f64; 2],
    /// Its magnitude `m r` (kg·m).
    pub mass_radius: f64,
    /// Its angle θ = atan2 (rad, in (−π, π]).
    pub angle: f64,
}

impl Correction {
    /// The correction with mass-radius vector `vector` in the plane at `axial`.
    pub fn new(axial: f64, vector: [f64; 2]) -> Self {
        Correction {
            axial,
            vector,
            mass_radius: vector[0].hypot(vector[1]),
            angle: vector[1].atan2(vector[0]),
        }
    }

    /// The mass needed at `radius` (kg); zero, negative or non-finite radius is an error.
    pub fn mass_at_radius(&self, radius: f64) -> Result<f64, Error> {
        positive_length(radius, "radius of a correcting mass")?;
        Ok(self.mass_radius / radius)
    }

    /// The radius needed for `mass` (m); zero, negative or non-finite mass is an error.
    pub fn radius_for_mass(&self, mass: f64) -> Result<f64, Error> {
        if !(mass.is_finite() && mass > 0.0) {
            return Err(Error::InvalidValue {
                what: "mass of a correcting mass (kg, must be > 0)".to_owned(),
                value: mass,
            });
        }
        Ok(self.mass_radius / mass)
    }

    /// The correction as a rotor mass of `mass_radius` kg·m at 1 m.
    pub fn as_mass(&self) -> RotorMass {
        RotorMass {
            mass: self.mass_radius,
            radius: 1.0,
            angle: self.angle,
            axial: self.axial,
        }
    }
}

/// Two-plane (dynamic) balance: a correction in each plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwoPlaneBalance {
    /// The correction in the first plane.
    pub left: Correction,
    /// The correction in the second plane.
    pub right: Correction,
}

impl TwoPlaneBalance {
    /// Both corrections.
    pub fn corrections(&self) -> [Correction; 2] {
        [self.left, self.right]
    }
}

/// One correcting mass of a given mass-radius placed to cancel the couple about a reference
/// plane (reference 002's dynamic example): `d = |Σ Uᵢ (zᵢ − z₀)| / (m r)` from `z₀`, at the
/// angle of `−Σ Uᵢ (zᵢ − z₀)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CouplePlane {
    /// The correction (in the plane found).
    pub correction: Correction,
    /// Distance of its plane from the reference plane, `z − z₀` (m, ≥ 0).
    pub distance: f64,
    /// The resultant force polygon's gap after adding it, `Σ Uᵢ + U` (kg·m): the couple is
    /// cancelled about `z₀` only; with this non-zero the rotor is not dynamically balanced.
    pub force_after: [f64; 2],
}

/// The force and couple polygons: the vectors in the order drawn, head to tail.
#[derive(Debug, Clone, PartialEq)]
pub struct Polygons {
    /// The reference plane of the couple polygon (m).
    pub reference: f64,
    /// Mass-radius vectors `Uᵢ` (kg·m).
    pub force: Vec<[f64; 2]>,
    /// Couple vectors `Uᵢ (zᵢ − z₀)` (kg·m²).
    pub couple: Vec<[f64; 2]>,
}

impl Polygons {
    /// The vertices of a polygon drawn head to tail from the origin (one more than sides).
    pub fn vertices(sides: &[[f64; 2]]) -> Vec<[f64; 2]> {
        let mut at = [0.0, 0.0];
        let mut out = vec![at];
        for s in sides {
            at = [at[0] + s[0], at[1] + s[1]];
            out.push(at);
        }
        out
    }
}

fn positive_length(value: f64, what: &str) -> Result<(), Error> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(Error::NonPositiveLength {
            what: what.to_owned(),
            length: value,
        })
    }
}

fn scale<D: Scalar>(v: [D; 2], k: D) -> [D; 2] {
    [v[0] * k, v[1] * k]
}

fn sum<D: Scalar>(vs: impl IntoIterator<Item = [D; 2]>) -> [D; 2] {
    let zero = D::from(0.0);
    vs.into_iter()
        .fold([zero, zero], |a, v| [a[0] + v[0], a[1] + v[1]])
}

impl Rotor {
    /// Relative size (of the largest term of a polygon) below which a resultant or a
    /// correction is rounding noise: its angle means nothing and it counts as zero.
    pub const NEGLIGIBLE: f64 = 1e-12;

    /// A rotor with these masses. Every number must be finite, masses positive and radii
    /// non-negative; the error names the mass (counted from 1).
    pub fn new(masses: Vec<RotorMass>) -> Result<Self, Error> {
        for (i, m) in masses.iter().enumerate() {
            let n = i + 1;
            let bad = |what: &str, value: f64| Error::InvalidValue {
                what: format!("{what} of rotor mass {n}"),
                value,
            };
            if !(m.mass.is_finite() && m.mass > 0.0) {
                return Err(bad("mass (kg, must be > 0)", m.mass));
            }
            if !(m.radius.is_finite() && m.radius >= 0.0) {
                return Err(bad("radius (m, must be ≥ 0)", m.radius));
            }
            if !m.angle.is_finite() {
                return Err(bad("angle", m.angle));
            }
            if !m.axial.is_finite() {
                return Err(bad("axial position", m.axial));
            }
        }
        Ok(Rotor { masses })
    }

    /// The masses.
    pub fn masses(&self) -> &[RotorMass] {
        &self.masses
    }

    /// This rotor with the corrections added as masses.
    pub fn with_corrections(&self, corrections: &[Correction]) -> Rotor {
        let mut masses = self.masses.clone();
        masses.extend(corrections.iter().map(Correction::as_mass));
        Rotor { masses }
    }

    /// `Σ Uᵢ` (kg·m): the gap of the force polygon.
    pub fn resultant_force(&self) -> [f64; 2] {
        self.resultant_force_in()
    }

    /// [`Rotor::resultant_force`] computed in the scalar `D`.
    pub fn resultant_force_in<D: Scalar>(&self) -> [D; 2] {
        sum(self.masses.iter().map(RotorMass::mass_radius_in))
    }

    /// `Σ Uᵢ (zᵢ − z₀)` (kg·m²): the gap of the couple polygon about the plane at `reference`.
    pub fn resultant_couple(&self, reference: f64) -> [f64; 2] {
        self.resultant_couple_in(reference)
    }

    /// [`Rotor::resultant_couple`] computed in the scalar `D`.
    pub fn resultant_couple_in<D: Scalar>(&self, reference: f64) -> [D; 2] {
        sum(self
            .masses
            .iter()
            .map(|m| scale(m.mass_radius_in(), D::from(m.axial) - reference)))
    }

    /// The force and couple polygons, the couple about the plane at `reference`.
    pub fn polygons(&self, reference: f64) -> Polygons {
        Polygons {
            reference,
            force: self.masses.iter().map(RotorMass::mass_radius).collect(),
            couple: self
                .masses
                .iter()
                .map(|m| scale(m.mass_radius(), m.axial - reference))
                .collect(),
        }
    }

    /// The largest single term of the force polygon (kg·m) and of the couple polygon about
    /// `reference` (kg·m²): the scale of rounding errors in the resultants.
    pub fn largest_terms(&self, reference: f64) -> [f64; 2] {
        self.masses.iter().fold([0.0, 0.0], |acc, m| {
            let mr = m.mass * m.radius;
            [acc[0].max(mr), acc[1].max(mr * (m.axial - reference).abs())]
        })
    }

    /// Static balance: the one correction `−Σ Uᵢ` that closes the force polygon, placed in
    /// the plane at `plane` (static balance holds in any plane; the couple left depends on it).
    pub fn static_balance(&self, plane: f64) -> Correction {
        let f = self.resultant_force();
        Correction::new(plane, [-f[0], -f[1]])
    }

    /// Dynamic balance with corrections in the planes at `left` and `right`: the unique pair
    /// that closes both polygons. Coincident planes are an error (the two corrections would
    /// act as one, leaving the couple), as are planes so close that the corrections lose all
    /// accuracy (`|z_R − z_L|` ≤ 1e-12 of the rotor's axial extent).
    pub fn two_plane_balance(&self, left: f64, right: f64) -> Result<TwoPlaneBalance, Error> {
        for (v, what) in [(left, "first"), (right, "second")] {
            if !v.is_finite() {
                return Err(Error::InvalidValue {
                    what: format!("axial position of the {what} correction plane"),
                    value: v,
                });
            }
        }
        let extent = self
            .masses
            .iter()
            .map(|m| m.axial.abs())
            .fold(left.abs().max(right.abs()), f64::max);
        let gap = right - left;
        if gap.abs() <= 1e-12 * extent || gap == 0.0 {
            return Err(Error::CoincidentPlanes { left, right });
        }
        let [in_left, in_right] = self.two_plane_vectors_in(left, right);
        Ok(TwoPlaneBalance {
            left: Correction::new(left, in_left),
            right: Correction::new(right, in_right),
        })
    }

    /// The mass-radius vectors of [`Rotor::two_plane_balance`] (left, right) computed in the
    /// scalar `D`, without its checks of the planes.
    pub fn two_plane_vectors_in<D: Scalar>(&self, left: f64, right: f64) -> [[D; 2]; 2] {
        let about_left = self.resultant_couple_in(left);
        let about_right = self.resultant_couple_in(right);
        let inverse_gap = (D::from(right) - left).recip();
        [
            scale(about_right, inverse_gap),
            scale(about_left, -inverse_gap),
        ]
    }

    /// The inverse question of reference 002's dynamic example: where one correcting mass of
    /// mass-radius `mass_radius` (kg·m) must go to cancel the couple about the plane at
    /// `reference`. An error if `mass_radius` is not positive, or if there is no couple
    /// (then no plane is determined: any mass in the reference plane leaves it zero).
    pub fn couple_plane(&self, mass_radius: f64, reference: f64) -> Result<CouplePlane, Error> {
        if !(mass_radius.is_finite() && mass_radius > 0.0) {
            return Err(Error::InvalidValue {
                what: "mass-radius of the correcting mass (kg m, must be > 0)".to_owned(),
                value: mass_radius,
            });
        }
        let c = self.resultant_couple(reference);
        let size = c[0].hypot(c[1]);
        if size <= 1e-15 * self.largest_terms(reference)[1] || size == 0.0 {
            return Err(Error::AlreadyBalanced {
                what: "the couple about the reference plane".to_owned(),
            });
        }
        let (distance, vector) = self.couple_plane_in(mass_radius, reference);
        let correction = Correction::new(reference + distance, vector);
        let f = self.resultant_force();
        Ok(CouplePlane {
            correction,
            distance,
            force_after: [f[0] + correction.vector[0], f[1] + correction.vector[1]],
        })
    }

    /// The distance `|C|/(m r)` and the mass-radius vector `−C m r/|C|` of
    /// [`Rotor::couple_plane`] (C the couple about `reference`) computed in the scalar `D`,
    /// without its checks.
    pub fn couple_plane_in<D: Scalar>(&self, mass_radius: f64, reference: f64) -> (D, [D; 2]) {
        let c = self.resultant_couple_in::<D>(reference);
        let size = crate::hypot(c[0], c[1]);
        (size / mass_radius, scale(c, D::from(-mass_radius) / size))
    }
}
