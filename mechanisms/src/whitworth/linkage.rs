//! The same Whitworth defined by geometry only: points, links, joints and a drive for the
//! constraint solver of [`mechdiff_core::geometry`], built from the closed form's parameters.
//!
//! The sketch is drawn at φ = 0 (crank pin A straight below the crank pivot O = (0, l0)):
//! the rocker hinged at B0 = (0, 0) carries the slot B0–S, the crank's pin A and the ram's pin
//! C (at height h) slide in it, and the ram translates along y = h. The centres of gravity are
//! S1 (at l_S1 from O on the crank), S2 (at l_S2 from B0 on the rocker) and S3 = C (the ram;
//! c_x, c_y are offsets that never enter a velocity, acceleration or force).

use super::Whitworth;
use mechdiff_core::geometry::{Drive, Inertia, Mechanism};

impl Whitworth {
    /// The mechanism by geometry only, with the masses of the parameters and the given moments
    /// of inertia (kg·m²) of the crank and the rocker about their centres of gravity (the
    /// source gives none; they do not enter the inertial forces of its table).
    ///
    /// Drive: the crank's angle φ at the pivot O (φ = 0 in the sketch). Links `crank`,
    /// `rocker`, `ram`; joints `O`, `B0`, `slot A`, `ram guide`, `slot C`.
    ///
    /// ```
    /// use mechdiff_core::geometry::Solver;
    /// use mechdiff_mechanisms::whitworth::{Whitworth, hand};
    /// let shaper = Whitworth::reference();
    /// let linkage = shaper.linkage([0.0, 0.0])?;
    /// let mut tracker = Solver::default().track(&linkage)?;
    /// tracker.move_to(1.0)?;
    /// // ψ is measured from +y towards +x, clockwise: the rocker's rotation is −ψ.
    /// let psi = -tracker.kinematics::<1>()?.rotation("rocker")?.value;
    /// assert!((psi - hand::rocker_angle(shaper.lambda(), 1.0).value).abs() < 1e-14);
    /// # Ok::<(), mechdiff_core::Error>(())
    /// ```
    pub fn linkage(&self, moments: [f64; 2]) -> Result<Mechanism, mechdiff_core::Error> {
        let p = &self.parameters;
        let (l0, l1, h) = (p.l0, p.l1, p.h);
        Mechanism::builder()
            .point("O", [0.0, l0])
            .point("B0", [0.0, 0.0])
            .point("A", [0.0, l0 - l1])
            .point("S", [0.0, h])
            .point("C", [0.0, h])
            .point("H0", [0.0, h])
            .point("H1", [1.0, h])
            .ground(["O", "B0", "H0", "H1"])
            .link("crank", ["O", "A"])
            .link("rocker", ["B0", "S"])
            .link("ram", ["C"])
            .inertia(
                "crank",
                Inertia {
                    mass: p.m1,
                    center: [0.0, l0 - p.l_s1],
                    moment: moments[0],
                },
            )
            .inertia(
                "rocker",
                Inertia {
                    mass: p.m2,
                    center: [0.0, p.l_s2],
                    moment: moments[1],
                },
            )
            .inertia(
                "ram",
                Inertia {
                    mass: p.m3,
                    center: [0.0, h],
                    moment: 0.0,
                },
            )
            .revolute("O", "ground", "crank", "O")
            .revolute("B0", "ground", "rocker", "B0")
            .pin_in_slot("slot A", "rocker", ["B0", "S"], "crank", "A")
            .prismatic("ram guide", "ground", ["H0", "H1"], "ram", "C")
            .pin_in_slot("slot C", "rocker", ["B0", "S"], "ram", "C")
            .drive(Drive::angle("O"))
            .build()
    }
}
