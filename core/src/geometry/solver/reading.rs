//! Reading the tracker's current pose: the lifted [`Kinematics`], or resolved outputs read
//! straight from the tracker's q, q′, q″ (no allocation).

use super::{Loops, Tracker, amax};
use crate::geometry::constraints::Frames;
use crate::geometry::implicit;
use crate::geometry::kinematics::{self, Kinematics};
use crate::geometry::output::{PointOutput, ScalarOutput};
use crate::{Error, Jet, Scalar};
use num_dual::Dual3_64;

impl<'m> Tracker<'m> {
    /// The loops' closed forms evaluated in any scalar `D` at drive position `phi` (its
    /// derivative parts are those of φ itself): the pose `(x, y, θ)` per moving link, on the
    /// tracker's branches, each angle on the turn nearest to the current pose's. Move the
    /// tracker near `phi.re()` first. With `D = Dual3<DoubleDouble>` (a higher-precision
    /// scalar) this is the accuracy report's reference for geometry scenes.
    ///
    /// # Errors
    /// [`Error::NoClosedForm`] naming the first loop solved by Newton (with the closed forms
    /// switched off: every loop); [`Error::Unassemblable`] or [`Error::Singular`] where a
    /// loop's formula fails at `phi`.
    pub fn closed_form_pose<D: Scalar>(&self, phi: D) -> Result<Vec<D>, Error> {
        if !self.closed_only {
            let on = self.seeding;
            let l = self.closed.matched().position(|m| !(m && on)).unwrap_or(0);
            return Err(Error::NoClosedForm {
                what: "the pose in closed form".into(),
                joints: self.loop_joints(&self.loops[l]),
            });
        }
        let n = self.q.len();
        let zero = D::from(0.0);
        let (mut q, mut frames) = (vec![zero; n], vec![(zero, zero); n / 3]);
        let mut margins = vec![zero; self.margins.len()];
        self.closed
            .solve_all(phi, self.q.as_slice(), &mut q, &mut frames, &mut margins)
            .map_err(|(l, failure)| self.closed_failure(phi.re(), l, failure))?;
        Ok(q)
    }

    /// The pose at the current drive position with its first `N` (1 ≤ N ≤ 3) exact
    /// derivatives with respect to φ, by implicit differentiation with the factorisation
    /// already computed for the pose (see [`crate::geometry::implicit`]).
    pub fn kinematics<const N: usize>(&self) -> Result<Kinematics<'m, N>, Error> {
        const {
            assert!(
                N >= 1 && N <= 3,
                "the geometry solver lifts derivatives of order 1 to 3"
            )
        };
        let mut dddq = Vec::new();
        if N == 3 && self.closed_only {
            let n = self.q.len();
            let zero = Dual3_64::from(0.0);
            let (mut q, mut frames) = (vec![zero; n], vec![(zero, zero); n / 3]);
            let mut margins = vec![zero; self.margins.len()];
            let phi = Dual3_64::new(self.phi, 1.0, 0.0, 0.0);
            self.closed
                .solve_all(phi, self.q.as_slice(), &mut q, &mut frames, &mut margins)
                .map_err(|(l, failure)| self.closed_failure(self.phi, l, failure))?;
            dddq.extend(q.iter().map(|x| x.v3));
        } else if N == 3 {
            dddq.resize(self.q.len(), 0.0);
            let lu = Loops {
                jac: &self.jac,
                lu: &self.lu,
            };
            let (q, dq, ddq) = (self.q.as_slice(), self.dq.as_slice(), self.ddq.as_slice());
            if !implicit::third_derivative(&self.eq, &lu, q, dq, ddq, self.phi, &mut dddq) {
                return Err(self.singular(self.phi));
            }
        }
        let (q, dq, ddq) = (self.q.as_slice(), self.dq.as_slice(), self.ddq.as_slice());
        let mut coordinates = Vec::with_capacity(q.len());
        for (i, ((&x, &dx), &ddx)) in q.iter().zip(dq).zip(ddq).enumerate() {
            let d = [dx, ddx, dddq.get(i).copied().unwrap_or(0.0)];
            coordinates.push(Jet::new(x, std::array::from_fn(|k| d[k])));
        }
        Ok(Kinematics::new(self.mechanism, self.phi, coordinates))
    }

    /// Coordinate `i` of the current pose with q′, q″ (q‴ zero).
    fn dual(&self, i: usize) -> Dual3_64 {
        Dual3_64::new(self.q[i], self.dq[i], self.ddq[i], 0.0)
    }

    /// Value of a resolved angle or displacement (rad or m) at the current pose, with its
    /// first two derivatives: the same as `kinematics::<2>()?.value(output)`, read straight
    /// from the tracker without building a [`Kinematics`] (nothing allocated; q′ and q″ are
    /// already computed by [`Tracker::move_to`]). For q‴ use [`Tracker::kinematics`].
    ///
    /// ```
    /// use mechdiff_core::geometry::{Drive, Mechanism, Solver};
    /// let m = Mechanism::builder()
    ///     .point("O", [0.0, 0.0]).point("A", [2.0, 0.0])
    ///     .ground(["O"]).link("crank", ["O", "A"])
    ///     .revolute("O", "ground", "crank", "O")
    ///     .drive(Drive::angle("O"))
    ///     .build().unwrap();
    /// let (tip, turn) = (m.point_output("crank", "A").unwrap(), m.rotation_output("crank").unwrap());
    /// let mut t = Solver::default().track(&m).unwrap();
    /// t.move_to(0.5).unwrap();
    /// assert_eq!(t.value(&turn).value, 0.5); // θ = φ
    /// let [_, y] = t.position(&tip);
    /// assert!((y.d2() + 2.0 * 0.5f64.sin()).abs() < 1e-14); // y″ = −2 sin φ
    /// ```
    pub fn value(&self, output: &ScalarOutput) -> Jet<2> {
        kinematics::jet(kinematics::value(|i| self.dual(i), output))
    }

    /// Position `[x, y]` of a resolved point (m) at the current pose, with its first two
    /// derivatives, read straight from the tracker (see [`Tracker::value`]).
    pub fn position(&self, point: &PointOutput) -> [Jet<2>; 2] {
        kinematics::position(|i| self.dual(i), point).map(kinematics::jet)
    }

    /// max |Φ| (m or rad) at the current pose, evaluated on request (on the closed-form path
    /// [`Tracker::move_to`] does not evaluate it, see [`super::SolveReport::residual`]).
    pub fn residual(&self) -> f64 {
        let mut residual = vec![0.0; self.q.len()];
        let f = Frames {
            q: self.q.as_slice(),
            frames: &self.frames,
        };
        self.eq.evaluate_with(&f, self.phi, &mut residual);
        amax(&residual)
    }
}
