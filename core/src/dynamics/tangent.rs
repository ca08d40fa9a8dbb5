//! Exact derivatives of the dynamics with respect to one parameter `p` (a mass, a length, the
//! drive speed, …): forward-mode dual numbers (`Dual64`, whose `eps` part is d/dp) through the
//! same generic effect code the `f64` run uses.
//!
//! The inputs are the pose and its φ-derivatives with their d/dp
//! ([`crate::geometry::Parametric::pose`]), `Φ_q` with its d/dp
//! ([`crate::geometry::Parametric::jacobian`]), and the d/dp of every number of the data: the
//! geometry's (sketch points, masses, centres of gravity, moments: [`DataTangent`]) and the
//! effects' own ([`EffectsTangent`]: gravity, loads, motor, the drive's ω and α).
//!
//! The equilibrium `Φ_qᵀ λ = Q` is not solved by a generic LU: with `A = Φ_qᵀ` the real part
//! is solved by the `f64` LU of `A.re`, and the derivative by one more back-substitution with
//! the same factors, `A λ_p = Q_p − A_p λ` (the derivative of `A λ = Q`).
//!
//! Carried: inertia, gravity, loads, the motor (with the direction of power flow of the
//! nominal run fixed: exact wherever the result is smooth in `p`), kinetic energy, reduced
//! inertia, shaking force, power balance. Not carried ([`NotCarried`]): friction, mesh
//! efficiencies and tooth forces in the bearings of meshes whose wheels turn on a common link;
//! a scene that uses them gets its derivatives another way, labelled.
//! A load's active range is a discrete choice: its ends are not differentiated (the
//! derivative is exact away from them).

use super::energy::{self, Energy};
use super::equilibrium::ideal_reaction;
use super::inertia::{InertialLoad, Mass};
use super::kinetostatics;
use super::loads::{CompiledLoad, LoadKind};
use super::model::{CompiledModel, Data, Dynamics};
use super::motor::{Motor, MotorState};
use super::plan::{Effects, Trace};
use super::shaking::{self, ShakingForce};
use super::solution::JointReaction;
use super::state::{self, LinkState};
use super::teeth;
use super::{PowerBalance, energy::energy_of};
use crate::Error;
use crate::geometry::DataTangent;
use nalgebra::{DMatrix, DVector};
use num_dual::{Dual3, Dual64};

/// The derivative with respect to one parameter `p` of the effects' numbers (those the
/// geometry's `DataTangent` does not hold), in the order of [`Dynamics`]' fields.
///
/// ```
/// use mechdiff_core::dynamics::{Dynamics, EffectsTangent, Gravity, Load};
/// let d = Dynamics::new().with_gravity(Gravity::down(9.81)).with_load(Load::torque("crank", 5.0));
/// let t = EffectsTangent::zero(&d);
/// assert_eq!((t.gravity, t.loads.len(), t.omega), ([0.0; 2], 1, 0.0));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct EffectsTangent {
    /// d/dp of the gravity vector (m/s² per unit of p).
    pub gravity: [f64; 2],
    /// d/dp of each load's force or torque, in the order of [`Dynamics::loads`] (same kind
    /// as the load).
    pub loads: Vec<LoadKind>,
    /// d/dp of the motor's rotor inertia, ratio and efficiency (`None` without a motor).
    pub motor: Option<Motor>,
    /// d/dp of the drive speed ω.
    pub omega: f64,
    /// d/dp of the drive acceleration α.
    pub alpha: f64,
}

impl EffectsTangent {
    /// The tangent of a parameter that changes none of the effects' numbers of `d`.
    pub fn zero(d: &Dynamics) -> Self {
        EffectsTangent {
            gravity: [0.0; 2],
            loads: (d.loads.iter())
                .map(|l| match l.kind {
                    LoadKind::Force(_) => LoadKind::Force([0.0; 2]),
                    LoadKind::Torque(_) => LoadKind::Torque(0.0),
                })
                .collect(),
            motor: d.motor.map(|_| Motor {
                rotor_inertia: 0.0,
                ratio: 0.0,
                efficiency: 0.0,
            }),
            omega: 0.0,
            alpha: 0.0,
        }
    }
}

/// An effect of the plan that the exact route does not carry.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum NotCarried {
    /// Coulomb friction (its forces depend on the signs of the reactions, resolved by
    /// iteration).
    #[error("friction (joint `{joint}`)")]
    Friction {
        /// The joint.
        joint: String,
    },
    /// The efficiency of a rack-and-pinion or gear mesh.
    #[error("the efficiency of mesh `{joint}`")]
    Efficiency {
        /// The mesh joint.
        joint: String,
    },
    /// The tooth force of a mesh carried by its wheels' bearings (the wheels turn on a common
    /// link).
    #[error("the tooth forces of mesh `{joint}` in its wheels' bearings")]
    ToothForces {
        /// The mesh joint.
        joint: String,
    },
}

/// Why an exact derivative of the dynamics was not computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum TangentError {
    /// The plan has an effect the exact route does not carry: use another method (labelled).
    #[error("the exact derivative of the dynamics does not carry {0}")]
    NotCarried(NotCarried),
    /// A tangent's length does not match the model.
    #[error("the tangent has {found} {what}, the model {expected}")]
    Length {
        /// What is counted (`"points"`, `"links"`, `"loads"`, …).
        what: &'static str,
        /// The model's count.
        expected: usize,
        /// The tangent's count.
        found: usize,
    },
    /// A tangent's entry does not match the model's (named in `what`).
    #[error("the tangent does not match the model: {what}")]
    Mismatch {
        /// Which entry, and how.
        what: String,
    },
    /// The dynamics failed at a drive position (a singular equilibrium, …).
    #[error(transparent)]
    Model(#[from] Error),
}

/// Checks that the exact route carries every effect of `effects` for `model`: the first effect
/// it does not carry, else `Ok`.
pub fn carried(model: &CompiledModel<'_>, effects: &Effects) -> Result<(), NotCarried> {
    let m = model.mechanism;
    let name = |j: usize| m.joints[j].name.clone();
    if effects.friction
        && let Some(f) = model.friction.first()
    {
        return Err(NotCarried::Friction {
            joint: name(f.joint()),
        });
    }
    if effects.efficiency
        && let Some(e) = model.efficiency.first()
    {
        return Err(NotCarried::Efficiency {
            joint: name(e.joint),
        });
    }
    // The bearings' tooth forces depend on the states only through the carrier's rotation,
    // but on the sketch through the pitch geometry: not carried.
    let states = vec![LinkState::GROUND; m.links.len() - 1];
    if let Some(t) = teeth::teeth(m, &model.rows, &states, &[]).first() {
        let mesh = model.rows.iter().position(|&r| r == t.row).unwrap_or(0);
        return Err(NotCarried::ToothForces { joint: name(mesh) });
    }
    Ok(())
}

/// The equilibrium at one drive position with the d/dp of every number (`eps` parts).
#[derive(Debug, Clone, PartialEq)]
pub struct SolutionTangent {
    /// Drive position.
    pub phi: f64,
    /// The multipliers λ (joints in order, the drive last).
    pub multipliers: Vec<Dual64>,
    /// The drive torque (N·m) or force (N).
    pub drive_torque: Dual64,
    /// The reaction in every joint, in the model's joint order (no friction, no power loss).
    pub reactions: Vec<JointReaction<Dual64>>,
    /// The motor, if the model has one and the plan includes it.
    pub motor: Option<MotorState<Dual64>>,
    /// Inertial loads of the links with mass (empty when inertia is not evaluated).
    pub inertial: Vec<InertialLoad<Dual64>>,
    /// The power balance.
    pub balance: PowerBalance<Dual64>,
}

/// A compiled model with the derivative of each of its numbers with respect to one parameter
/// `p`: the dynamics at a pose with its d/dp (see the [module](self) doc).
#[derive(Debug, Clone)]
pub struct ModelTangent<'a, 'm> {
    model: &'a CompiledModel<'m>,
    effects: Effects,
    /// Whether the equilibrium is carried (see [`carried`]).
    equilibrium: Result<(), NotCarried>,
    masses: Vec<Mass<Dual64>>,
    gravity: Option<[Dual64; 2]>,
    loads: Vec<CompiledLoad<Dual64>>,
    motor: Option<Motor<Dual64>>,
    /// Sketch positions with d/dp.
    points: Vec<[Dual64; 2]>,
    omega: Dual64,
    alpha: Dual64,
}

fn length(what: &'static str, expected: usize, found: usize) -> Result<(), TangentError> {
    if expected == found {
        Ok(())
    } else {
        Err(TangentError::Length {
            what,
            expected,
            found,
        })
    }
}

fn dual(re: f64, eps: f64) -> Dual64 {
    Dual64::new(re, eps)
}

fn dual2(re: [f64; 2], eps: [f64; 2]) -> [Dual64; 2] {
    [dual(re[0], eps[0]), dual(re[1], eps[1])]
}

impl<'a, 'm> ModelTangent<'a, 'm> {
    /// The model `model` evaluated with `effects` (the plan's) at drive speed and acceleration
    /// `omega`, `alpha`, with the derivatives: `data` for the mechanism's numbers (the sketch
    /// points and the links' inertias are read here; the joints' numbers and the drive's
    /// sketch value enter through the pose and `Φ_q` given to [`ModelTangent::solve`]),
    /// `tangent` for the effects' numbers.
    ///
    /// Errors: [`TangentError::Length`] or [`TangentError::Mismatch`] for a tangent that does
    /// not match the model. An effect the route does not carry (see [`carried`]) is reported
    /// by [`ModelTangent::solve`], the only result it changes.
    pub fn new(
        model: &'a CompiledModel<'m>,
        effects: &Effects,
        data: &DataTangent,
        tangent: &EffectsTangent,
        omega: f64,
        alpha: f64,
    ) -> Result<Self, TangentError> {
        let m = model.mechanism;
        let (points, inertias) = (&data.points, &data.inertias);
        length("points", m.points.len(), points.len())?;
        length("links (inertias)", m.links.len(), inertias.len())?;
        length("loads", model.loads.len(), tangent.loads.len())?;
        length(
            "motors",
            usize::from(model.motor.is_some()),
            usize::from(tangent.motor.is_some()),
        )?;
        let points: Vec<[Dual64; 2]> = (m.points.iter().zip(points))
            .map(|(p, t)| dual2(p.sketch, *t))
            .collect();
        // Link-local coordinates relative to the link's reference point (its first point).
        let reference = |k: usize| match m.links[k].points.first() {
            Some(&p) if k > 0 => points[p],
            _ => [Dual64::from(0.0); 2],
        };
        let local = |k: usize, at: [Dual64; 2]| {
            let r = reference(k);
            [at[0] - r[0], at[1] - r[1]]
        };
        let masses = (model.masses.iter())
            .map(|mass| {
                let d = inertias[mass.link].ok_or_else(|| TangentError::Mismatch {
                    what: format!(
                        "link `{}` has mass properties but no inertia tangent",
                        m.links[mass.link].name
                    ),
                })?;
                let sketch = m.links[mass.link].inertia.map_or([0.0; 2], |i| i.center);
                Ok(Mass {
                    link: mass.link,
                    mass: dual(mass.mass, d.mass),
                    center: local(mass.link, dual2(sketch, d.center)),
                    moment: dual(mass.moment, d.moment),
                })
            })
            .collect::<Result<Vec<_>, TangentError>>()?;
        let loads = (model.loads.iter().zip(&tangent.loads))
            .enumerate()
            .map(|(i, (l, t))| {
                let kind = match (l.kind, *t) {
                    (LoadKind::Force(f), LoadKind::Force(d)) => LoadKind::Force(dual2(f, d)),
                    (LoadKind::Torque(f), LoadKind::Torque(d)) => LoadKind::Torque(dual(f, d)),
                    _ => {
                        return Err(TangentError::Mismatch {
                            what: format!(
                                "load {} is a force and its tangent a torque, or the reverse",
                                i + 1
                            ),
                        });
                    }
                };
                Ok(CompiledLoad {
                    link: l.link,
                    point: l.point,
                    local: l
                        .point
                        .map_or([Dual64::from(0.0); 2], |p| local(l.link, points[p])),
                    kind,
                    active: l.active,
                    periodic: l.periodic,
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let motor = model.motor.zip(tangent.motor).map(|(mo, d)| Motor {
            rotor_inertia: dual(mo.rotor_inertia, d.rotor_inertia),
            ratio: dual(mo.ratio, d.ratio),
            efficiency: dual(mo.efficiency, d.efficiency),
        });
        Ok(ModelTangent {
            model,
            effects: *effects,
            equilibrium: carried(model, effects),
            masses,
            gravity: model.gravity.map(|g| dual2(g.g, tangent.gravity)),
            loads,
            motor,
            points,
            omega: dual(omega, tangent.omega),
            alpha: dual(alpha, tangent.alpha),
        })
    }

    fn data(&self) -> Data<'_, Dual64> {
        Data {
            masses: &self.masses,
            gravity: self.gravity,
            loads: &self.loads,
            motor: self.motor,
        }
    }

    fn states(&self, pose: &[Dual3<Dual64>]) -> Result<Vec<LinkState<Dual64>>, TangentError> {
        length(
            "pose coordinates",
            self.model.equations.coordinates(),
            pose.len(),
        )?;
        Ok(state::states_of(
            pose,
            |c| [c.re, c.v1, c.v2],
            self.omega,
            self.alpha,
        ))
    }

    /// The equilibrium at drive position `phi` from the pose `pose` (q, q′, q″ per coordinate,
    /// each with its d/dp) and `jacobian`, `Φ_q` at that pose with its d/dp.
    ///
    /// The f64 LU of `Φ_qᵀ` solves both the value and (one more back-substitution) the
    /// derivative; a singular `Φ_qᵀ` is [`Error::SingularEquilibrium`]. An effect of the plan
    /// that the route does not carry is [`TangentError::NotCarried`].
    pub fn solve(
        &self,
        phi: f64,
        pose: &[Dual3<Dual64>],
        jacobian: &DMatrix<Dual64>,
    ) -> Result<SolutionTangent, TangentError> {
        self.equilibrium.clone().map_err(TangentError::NotCarried)?;
        let n = self.model.equations.coordinates();
        length("rows of the Jacobian", n, jacobian.nrows())?;
        length("columns of the Jacobian", n, jacobian.ncols())?;
        let states = self.states(pose)?;
        let data = self.data();
        let (load, inertial) =
            kinetostatics::applied(&data, &self.effects, phi, &states, &mut Trace::default());
        let a = jacobian.transpose();
        let lu = a.map(|x| x.re).lu();
        let singular = || TangentError::Model(Error::SingularEquilibrium { phi });
        let q_re = DVector::from_iterator(n, load.0.iter().map(|x| x.re));
        let lambda_re = lu.solve(&q_re).ok_or_else(singular)?;
        // A λ = Q  ⇒  A λ_p = Q_p − A_p λ.
        let q_eps = DVector::from_iterator(n, load.0.iter().map(|x| x.eps));
        let lambda_eps = lu
            .solve(&(q_eps - a.map(|x| x.eps) * &lambda_re))
            .ok_or_else(singular)?;
        let lambda = lambda_re.zip_map(&lambda_eps, Dual64::new);
        let m = self.model.mechanism;
        let reactions = (0..m.joints.len())
            .map(|j| {
                let r = self.model.rows[j];
                ideal_reaction(
                    self.model,
                    j,
                    &states,
                    &lambda,
                    |i| self.points[i],
                    || [lambda[r], lambda[r + 1]],
                )
            })
            .collect::<Vec<_>>();
        let drive_torque = -lambda[self.model.drive_row];
        let motor = match (self.effects.motor, &self.motor) {
            (true, Some(mo)) => Some(mo.state_of(
                drive_torque,
                self.omega,
                self.alpha,
                self.effects.inertia,
                self.effects.efficiency,
            )),
            _ => None,
        };
        let balance = energy::balance(
            m,
            &data,
            &self.effects,
            phi,
            self.omega,
            &states,
            drive_torque,
            &reactions,
            motor.as_ref(),
        );
        Ok(SolutionTangent {
            phi,
            multipliers: lambda.iter().copied().collect(),
            drive_torque,
            reactions,
            motor,
            inertial,
            balance,
        })
    }

    /// The kinetic energy and reduced inertia (and their d/dp) at the pose `pose`.
    pub fn energy(&self, pose: &[Dual3<Dual64>]) -> Result<Energy<Dual64>, TangentError> {
        length(
            "pose coordinates",
            self.model.equations.coordinates(),
            pose.len(),
        )?;
        Ok(energy_of(
            &self.data(),
            pose,
            |c| [c.re, c.v1, c.v2],
            self.omega,
            self.alpha,
        ))
    }

    /// The shaking force (and its d/dp) at drive position `phi`, pose `pose`.
    pub fn shaking_force(
        &self,
        phi: f64,
        pose: &[Dual3<Dual64>],
    ) -> Result<ShakingForce<Dual64>, TangentError> {
        Ok(shaking::shaking_of(&self.masses, phi, &self.states(pose)?))
    }
}
