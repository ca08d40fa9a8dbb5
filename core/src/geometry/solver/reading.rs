//! Reading the tracker's current pose: the lifted [`Kinematics`], or resolved outputs read
//! straight from the tracker's q, q′, q″ (no allocation).

use super::{Loops, Tracker, amax};
use crate::geometry::constraints::Frames;
use crate::geometry::implicit;
use crate::geometry::kinematics::{self, Kinematics};
use crate::geometry::output::{PointOutput, ScalarOutput};
use crate::{Error, Jet, JetDual, Scalar};
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
        if N == 3 {
            self.third_derivatives(&mut dddq)?;
        }
        let (q, dq, ddq) = (self.q.as_slice(), self.dq.as_slice(), self.ddq.as_slice());
        let mut coordinates = Vec::with_capacity(q.len());
        for (i, ((&x, &dx), &ddx)) in q.iter().zip(dq).zip(ddq).enumerate() {
            let d = [dx, ddx, dddq.get(i).copied().unwrap_or(0.0)];
            coordinates.push(Jet::new(x, std::array::from_fn(|k| d[k])));
        }
        Ok(Kinematics::new(self.mechanism, self.phi, coordinates))
    }

    /// q‴ of the current pose into `dddq` (resized to the coordinates): from the loops'
    /// closed forms evaluated once in `Dual3_64`, or on the Newton path by implicit
    /// differentiation with the factorisation already computed for the pose. Nothing is
    /// allocated once `dddq` has the capacity (for up to 8 moving links).
    ///
    /// # Errors
    /// The closed form's failure at the current position (it was accepted, so only by
    /// rounding), or [`Error::Singular`] where Φ_q cannot be solved.
    pub fn third_derivatives(&self, dddq: &mut Vec<f64>) -> Result<(), Error> {
        let n = self.q.len();
        dddq.clear();
        dddq.resize(n, 0.0);
        if self.closed_only {
            let phi = Dual3_64::new(self.phi, 1.0, 0.0, 0.0);
            let zero = Dual3_64::from(0.0);
            let loops = self.margins.len();
            let solve = |q: &mut [Dual3_64], frames: &mut [(Dual3_64, Dual3_64)], m| {
                self.closed
                    .solve_all(phi, self.q.as_slice(), q, frames, m)
                    .map_err(|(l, failure)| self.closed_failure(self.phi, l, failure))
            };
            if n <= 24 && loops <= 8 {
                let (mut q, mut frames) = ([zero; 24], [(zero, zero); 8]);
                let mut margins = [zero; 8];
                solve(&mut q[..n], &mut frames[..n / 3], &mut margins[..loops])?;
                for (x, d) in dddq.iter_mut().zip(&q[..n]) {
                    *x = d.v3;
                }
            } else {
                let (mut q, mut frames) = (vec![zero; n], vec![(zero, zero); n / 3]);
                let mut margins = vec![zero; loops];
                solve(&mut q, &mut frames, &mut margins)?;
                for (x, d) in dddq.iter_mut().zip(&q) {
                    *x = d.v3;
                }
            }
            return Ok(());
        }
        let lu = Loops {
            jac: &self.jac,
            lu: &self.lu,
        };
        let (q, dq, ddq) = (self.q.as_slice(), self.dq.as_slice(), self.ddq.as_slice());
        if !implicit::third_derivative(&self.eq, &lu, q, dq, ddq, self.phi, dddq) {
            return Err(self.singular(self.phi));
        }
        Ok(())
    }

    /// The pose coordinates with q′ and q″ into `out` (cleared first): the coordinates of
    /// `kinematics::<2>()` (and the first two derivatives of `kinematics::<3>()`), bit for
    /// bit, without building a [`Kinematics`] (nothing allocated once `out` has the
    /// capacity).
    pub fn coordinates_into(&self, out: &mut Vec<Jet<2>>) {
        out.clear();
        // Slices' iterators: the extension's length known up front (no check per element).
        let (q, dq, ddq) = (self.q.as_slice(), self.dq.as_slice(), self.ddq.as_slice());
        let jets =
            (q.iter().zip(dq.iter().zip(ddq))).map(|(&x, (&dx, &ddx))| Jet::new(x, [dx, ddx]));
        out.extend(jets);
    }

    /// The current pose as the move solved it, to be read at the order of a [`JetDual`]:
    /// q, q′, q″ (q‴ read as 0: for the third order see [`Tracker::pose_jets_with`]) and the
    /// bodies' `(sin θ, cos θ)` the solver computed, nothing evaluated again.
    pub fn pose_jets(&self) -> PoseJets<'_> {
        self.pose_jets_with(&[])
    }

    /// [`Tracker::pose_jets`] with q‴ `dddq` (from [`Tracker::third_derivatives`]; empty:
    /// read as 0).
    pub fn pose_jets_with<'a>(&'a self, dddq: &'a [f64]) -> PoseJets<'a> {
        PoseJets {
            q: self.q.as_slice(),
            dq: self.dq.as_slice(),
            ddq: self.ddq.as_slice(),
            dddq,
            frames: &self.frames,
        }
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

/// A tracker's pose as its move solved it (see [`Tracker::pose_jets`]), read at the order of
/// any [`JetDual`]: a point's position or an angle or displacement with exactly the
/// derivatives that order carries. The bodies' sines and cosines are the solver's own, their
/// derivatives by the chain rule from θ′, θ″, θ‴: no `sin_cos` per point or output, no
/// `atan2` for a link's rotation.
#[derive(Debug, Clone, Copy)]
pub struct PoseJets<'a> {
    q: &'a [f64],
    dq: &'a [f64],
    ddq: &'a [f64],
    /// q‴, or empty (read as 0).
    dddq: &'a [f64],
    frames: &'a [(f64, f64)],
}

impl PoseJets<'_> {
    /// Coordinate `i` with its derivatives.
    #[inline(always)]
    fn coordinate<D: JetDual>(&self, i: usize) -> D {
        let d3 = if D::ORDER >= 3 {
            self.dddq.get(i).copied().unwrap_or(0.0)
        } else {
            0.0
        };
        D::from_derivatives([self.q[i], self.dq[i], self.ddq[i], d3])
    }

    /// `(sin θ_k, cos θ_k)` of body `k` with their derivatives: the solver's sine and cosine,
    /// differentiated through θ′, θ″, θ‴ (e.g. (sin θ)″ = θ″ cos θ − θ′² sin θ).
    #[inline(always)]
    fn frame<D: JetDual>(&self, k: usize) -> (D, D) {
        let (s, c) = self.frames[k];
        let [_, t1, t2, t3] = self.coordinate::<D>(3 * k + 2).derivatives();
        let (sin, cos) = if D::ORDER >= 3 {
            let (t11, t12) = (t1 * t1, 3.0 * t1 * t2);
            (
                [s, c * t1, c * t2 - s * t11, c * t3 - s * t12 - c * t11 * t1],
                [
                    c,
                    -s * t1,
                    -s * t2 - c * t11,
                    -s * t3 - c * t12 + s * t11 * t1,
                ],
            )
        } else {
            let t11 = t1 * t1;
            (
                [s, c * t1, c * t2 - s * t11, 0.0],
                [c, -s * t1, -s * t2 - c * t11, 0.0],
            )
        };
        (D::from_derivatives(sin), D::from_derivatives(cos))
    }

    /// Position `[x, y]` of a resolved point (m) with the derivatives `D` carries.
    #[inline]
    pub fn position<D: JetDual>(&self, point: &PointOutput) -> [D; 2] {
        let coordinate = |i| self.coordinate::<D>(i);
        kinematics::place_with(&coordinate, &|k| self.frame(k), point.body, point.local)
    }

    /// Value of a resolved angle or displacement (rad or m) with the derivatives `D`
    /// carries (a link's rotation is its angle itself: no trigonometry).
    #[inline]
    pub fn value<D: JetDual>(&self, output: &ScalarOutput) -> D {
        let coordinate = |i| self.coordinate::<D>(i);
        kinematics::scalar_with(&coordinate, &|k| self.frame(k), &output.0)
    }
}
