//! The equilibrium system of one drive position and its iteration on friction signs and
//! directions of power flow (see [`super::kinetostatics`]).

use super::efficiency::CompiledEfficiency;
use super::energy;
use super::friction::{self, CompiledFriction};
use super::inertia::InertialLoad;
use super::model::CompiledModel;
use super::plan::{Effects, Trace};
use super::solution::{JointReaction, Solution};
use super::state::{Generalized, LinkState, of};
use super::teeth::{self, Tooth};
use crate::geometry::JointKind;
use crate::{DriveState, Error, Scalar, hypot};
use nalgebra::{DMatrix, DVector};

/// Iterations allowed for friction and efficiency before a position is reported self-locking.
const MAX_ITERATIONS: usize = 100;

/// The signs, directions and flows the friction and efficiency columns are built with.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Signs {
    /// Per friction: the sign of the normal force (sliding) or the unit direction of the
    /// reaction (revolute).
    normal: Vec<[f64; 2]>,
    /// Per efficiency: `κ = η` (direct flow) or `1/η` (reverse).
    kappa: Vec<f64>,
}

/// Everything fixed at one position: the Jacobian, the loads, the friction geometry.
pub(super) struct Assembly<'a, 'm> {
    model: &'a CompiledModel<'m>,
    states: Vec<LinkState>,
    jac: DMatrix<f64>,
    rhs: DVector<f64>,
    friction: &'a [CompiledFriction],
    efficiency: &'a [CompiledEfficiency],
    /// Per friction: the generalized friction load per unit normal force.
    directions: Vec<Vec<f64>>,
    /// Per friction: the relative velocity (m/s or rad/s).
    velocities: Vec<f64>,
    /// Per friction: its sign (0 at rest).
    slips: Vec<f64>,
    /// Per efficiency: the driving side's part of the mesh row.
    inputs: Vec<Vec<f64>>,
    /// q̇.
    qdot: Vec<f64>,
    /// Meshes whose tooth forces pass through the wheels' bearings (see [`teeth`]).
    teeth: Vec<Tooth>,
}

impl<'a, 'm> Assembly<'a, 'm> {
    /// The assembly at one position: the friction loads per unit normal force from the
    /// relative velocities, the meshes' driving sides, the wheel bearings' tooth forces.
    pub(super) fn new(
        model: &'a CompiledModel<'m>,
        friction: &'a [CompiledFriction],
        efficiency: &'a [CompiledEfficiency],
        states: Vec<LinkState>,
        jac: DMatrix<f64>,
        rhs: DVector<f64>,
        qdot: Vec<f64>,
    ) -> Self {
        let m = model.mechanism;
        let qdot_max = qdot.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let speed_scale = qdot_max * super::energy::size(m);
        let mut directions = Vec::with_capacity(friction.len());
        let mut velocities = Vec::with_capacity(friction.len());
        let mut slips = Vec::with_capacity(friction.len());
        for f in friction {
            let mut g = Generalized::zeros(m.links.len() - 1);
            match *f {
                CompiledFriction::Sliding {
                    guide,
                    slider,
                    coefficient,
                    ..
                } => {
                    let sl = f.sliding(&states).expect("a sliding friction");
                    let s = friction::sign(sl.velocity, speed_scale);
                    let t = [-s * coefficient * sl.u[0], -s * coefficient * sl.u[1]];
                    g.force(&states, slider, sl.contact, t);
                    g.force(&states, guide, sl.contact, [-t[0], -t[1]]);
                    velocities.push(sl.velocity);
                    slips.push(s);
                }
                CompiledFriction::Revolute { a, b, radius, .. } => {
                    let w = f.relative_rotation(&states).expect("a revolute friction");
                    let s = friction::sign(w, qdot_max);
                    g.couple(b, -s * radius);
                    g.couple(a, s * radius);
                    velocities.push(w);
                    slips.push(s);
                }
            }
            directions.push(g.0);
        }
        let inputs = efficiency
            .iter()
            .map(|e| {
                let row: Vec<f64> = jac.row(e.row).iter().copied().collect();
                e.input_part(&row)
            })
            .collect();
        let teeth = teeth::teeth(m, &model.rows, &states, efficiency);
        Assembly {
            teeth,
            model,
            states,
            rhs,
            jac,
            friction,
            efficiency,
            directions,
            velocities,
            slips,
            inputs,
            qdot,
        }
    }
}

impl Assembly<'_, '_> {
    fn matrix(&self, signs: Option<&Signs>) -> DMatrix<f64> {
        let mut a = self.jac.transpose();
        let Some(signs) = signs else { return a };
        // Efficiencies first: they replace the mesh columns, friction then adds to them.
        for (i, e) in self.efficiency.iter().enumerate() {
            let kappa = signs.kappa[i];
            let input = &self.inputs[i];
            for (r, inp) in input.iter().enumerate() {
                // Column = input part + κ·(output part), output = row − input.
                a[(r, e.row)] = inp + kappa * (self.jac[(e.row, r)] - inp);
            }
        }
        for (i, f) in self.friction.iter().enumerate() {
            let g = &self.directions[i];
            let w = signs.normal[i];
            match *f {
                CompiledFriction::Sliding { row, .. } => {
                    for (r, gv) in g.iter().enumerate() {
                        a[(r, row)] -= w[0] * gv;
                    }
                }
                CompiledFriction::Revolute { row, joint, .. } => {
                    for (r, gv) in g.iter().enumerate() {
                        a[(r, row)] -= w[0] * gv;
                        a[(r, row + 1)] -= w[1] * gv;
                    }
                    // |R| ≈ R̂·(λ_bearing − s λ_mesh F) for a wheel's bearing.
                    for t in self.teeth.iter().filter(|t| t.bearing == joint) {
                        let c = self.tooth_scale(t, Some(signs))
                            * (w[0] * t.force[0] + w[1] * t.force[1]);
                        for (r, gv) in g.iter().enumerate() {
                            a[(r, t.row)] += c * gv;
                        }
                    }
                }
            }
        }
        a
    }

    fn signs_of(&self, lambda: &DVector<f64>) -> Signs {
        let kappa = self
            .efficiency
            .iter()
            .enumerate()
            .map(|(i, e)| {
                if self.input_power(i, lambda) >= 0.0 {
                    e.eta
                } else {
                    1.0 / e.eta
                }
            })
            .collect();
        let mut signs = Signs {
            normal: Vec::new(),
            kappa,
        };
        signs.normal = self
            .friction
            .iter()
            .map(|f| match *f {
                CompiledFriction::Sliding { row, .. } => {
                    [if lambda[row] < 0.0 { -1.0 } else { 1.0 }, 0.0]
                }
                CompiledFriction::Revolute { joint, row, .. } => {
                    let [x, y] = self.bearing_force(joint, row, lambda, Some(&signs));
                    let r = x.hypot(y);
                    if r == 0.0 { [1.0, 0.0] } else { [x / r, y / r] }
                }
            })
            .collect();
        signs
    }

    /// The factor of the mesh's multiplier on a tooth's side (κ if that side is the
    /// output side of an efficiency, else 1).
    fn tooth_scale(&self, t: &Tooth, signs: Option<&Signs>) -> f64 {
        match (t.output, signs) {
            (Some(i), Some(s)) => s.kappa[i],
            _ => 1.0,
        }
    }

    /// The force of link a on link b in revolute joint `joint` (first row `row`), the tooth
    /// force of a mesh included when `joint` is a wheel's bearing.
    fn bearing_force(
        &self,
        joint: usize,
        row: usize,
        lambda: &DVector<f64>,
        signs: Option<&Signs>,
    ) -> [f64; 2] {
        let mut f = [lambda[row], lambda[row + 1]];
        for t in self.teeth.iter().filter(|t| t.bearing == joint) {
            let s = self.tooth_scale(t, signs) * lambda[t.row];
            f[0] -= s * t.force[0];
            f[1] -= s * t.force[1];
        }
        f
    }

    /// Power the nominal driving side of mesh `i` delivers to the mesh, `λ·(J_in q̇)`.
    fn input_power(&self, i: usize, lambda: &DVector<f64>) -> f64 {
        let rate: f64 = self.inputs[i]
            .iter()
            .zip(&self.qdot)
            .map(|(a, b)| a * b)
            .sum();
        lambda[self.efficiency[i].row] * rate
    }

    fn joints(&self) -> Vec<String> {
        let m = self.model.mechanism;
        let mut names: Vec<String> = self
            .friction
            .iter()
            .map(|f| m.joints[f.joint()].name.clone())
            .collect();
        names.extend(
            self.efficiency
                .iter()
                .map(|e| m.joints[e.joint].name.clone()),
        );
        names
    }

    /// Solves, iterating on signs and flows; returns λ, the signs used and the solves done.
    pub(super) fn iterate(
        &self,
        phi: f64,
        trace: &mut Trace,
    ) -> Result<(DVector<f64>, Option<Signs>, usize), Error> {
        let lu = self.matrix(None).lu();
        let lambda = lu
            .solve(&self.rhs)
            .ok_or(Error::SingularEquilibrium { phi })?;
        if self.friction.is_empty() && self.efficiency.is_empty() {
            return Ok((lambda, None, 1));
        }
        let ideal_sign = lu.determinant().signum();
        let mut signs = self.signs_of(&lambda);
        let mut lambda = lambda;
        let mut seen: Vec<Signs> = Vec::new();
        for it in 1..=MAX_ITERATIONS {
            trace.friction += usize::from(!self.friction.is_empty());
            trace.efficiency += usize::from(!self.efficiency.is_empty());
            let lu = self.matrix(Some(&signs)).lu();
            let next = lu.solve(&self.rhs).ok_or_else(|| Error::SelfLocking {
                phi,
                joints: self.joints(),
                reason: "the equilibrium equations with friction are singular".to_owned(),
            })?;
            let flipped = lu.determinant().signum() != ideal_sign;
            let new_signs = self.signs_of(&next);
            let scale = next.amax().max(f64::MIN_POSITIVE);
            // Settled: the same signs and flows, and λ and the reaction directions unchanged
            // up to rounding (64 ulp: the last iterations of a revolute friction circle
            // alternate at the rounding level of the LU).
            let tol = 64.0 * f64::EPSILON;
            let settled = new_signs.kappa == signs.kappa
                && new_signs
                    .normal
                    .iter()
                    .zip(&signs.normal)
                    .all(|(a, b)| (a[0] - b[0]).abs() <= tol && (a[1] - b[1]).abs() <= tol)
                && (&next - &lambda).amax() <= tol * scale;
            lambda = next;
            if settled {
                // Consistent signs whose friction turns the determinant's sign: the equations
                // passed through singularity (infinite drive torque) as friction grew from 0,
                // so no finite drive torque moves the mechanism in the prescribed sense.
                if flipped {
                    return Err(Error::SelfLocking {
                        phi,
                        joints: self.joints(),
                        reason: "with consistent friction forces the equilibrium determinant has \
                                 the opposite sign of the frictionless one: the drive cannot move \
                                 the mechanism in this sense"
                            .to_owned(),
                    });
                }
                return Ok((lambda, Some(signs), it + 1));
            }
            // Sliding signs and flows only: a repeated pattern that is not consistent is a cycle.
            if self
                .friction
                .iter()
                .all(|f| matches!(f, CompiledFriction::Sliding { .. }))
            {
                if seen.contains(&new_signs) && new_signs != signs {
                    break;
                }
                seen.push(signs.clone());
            }
            signs = new_signs;
        }
        Err(Error::SelfLocking {
            phi,
            joints: self.joints(),
            reason: "the signs of the normal forces or the direction of power flow keep changing"
                .to_owned(),
        })
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn finish(
        &self,
        effects: &Effects,
        phi: f64,
        drive: &DriveState,
        lambda: DVector<f64>,
        signs: Option<Signs>,
        iterations: usize,
        inertial: Vec<InertialLoad>,
        mut trace: Trace,
    ) -> Result<Solution, Error> {
        let model = self.model;
        let m = model.mechanism;
        let drive_torque = -lambda[model.drive_row];
        let mut reactions: Vec<JointReaction> = (0..m.joints.len())
            .map(|j| {
                ideal_reaction(
                    model,
                    j,
                    &self.states,
                    &lambda,
                    |i| m.points[i].sketch,
                    || self.bearing_force(j, model.rows[j], &lambda, signs.as_ref()),
                )
            })
            .collect();
        if let Some(signs) = &signs {
            for (i, f) in self.friction.iter().enumerate() {
                let r = &mut reactions[f.joint()];
                match *f {
                    CompiledFriction::Sliding { coefficient, .. } => {
                        let sl = f.sliding(&self.states).expect("a sliding friction");
                        let t = -self.slips[i] * coefficient * r.normal.abs();
                        r.friction = t;
                        r.force[0] += t * sl.u[0];
                        r.force[1] += t * sl.u[1];
                        r.power_loss = t * self.velocities[i];
                    }
                    CompiledFriction::Revolute { radius, .. } => {
                        let t = -self.slips[i] * radius * r.normal;
                        r.friction = t;
                        r.couple = t;
                        r.power_loss = t * self.velocities[i];
                    }
                }
            }
            for (i, e) in self.efficiency.iter().enumerate() {
                let kappa = signs.kappa[i];
                let p_in = self.input_power(i, &lambda);
                let r = &mut reactions[e.joint];
                r.power_loss = -(1.0 - kappa) * p_in;
                // The second side carries κ·λ when the first side drives, and λ otherwise.
                let second_scale = match e.driving {
                    super::Driving::First => kappa,
                    super::Driving::Second => 1.0,
                };
                r.normal *= second_scale;
                r.force = [r.force[0] * second_scale, r.force[1] * second_scale];
                if let JointKind::Gear { .. } = m.joints[e.joint].kind {
                    r.couple *= second_scale;
                }
            }
        }
        let motor = match (effects.motor, &model.motor) {
            (true, Some(mo)) => {
                trace.motor += 1;
                Some(mo.state(drive_torque, drive, effects.inertia, effects.efficiency))
            }
            _ => None,
        };
        let balance = energy::balance(
            m,
            &model.data(),
            effects,
            phi,
            drive.omega,
            &self.states,
            drive_torque,
            &reactions,
            motor.as_ref(),
        );
        Ok(Solution {
            phi,
            drive: *drive,
            multipliers: lambda.iter().copied().collect(),
            drive_torque,
            reactions,
            motor,
            inertial,
            balance,
            iterations,
            trace,
        })
    }
}

/// The reaction of joint `j` from the multipliers `lambda`, without friction or efficiency, in
/// any scalar: `sketch(i)` is point `i`'s sketch position, `bearing()` the force of a revolute
/// joint (its multipliers, plus the tooth force of a mesh whose wheel turns in it).
pub(super) fn ideal_reaction<T: Scalar>(
    model: &CompiledModel<'_>,
    j: usize,
    states: &[LinkState<T>],
    lambda: &DVector<T>,
    sketch: impl Fn(usize) -> [T; 2],
    bearing: impl FnOnce() -> [T; 2],
) -> JointReaction<T> {
    let m = model.mechanism;
    let joint = &m.joints[j];
    let r = model.rows[j];
    let l = |i: usize| lambda[r + i];
    let zero = T::zero();
    let mut out = JointReaction {
        joint: joint.name.clone(),
        force: [zero; 2],
        couple: zero,
        normal: zero,
        friction: zero,
        power_loss: zero,
    };
    let guide_dir = |guide: usize, line: [usize; 2]| {
        let (a, b) = (sketch(line[0]), sketch(line[1]));
        let d = [b[0] - a[0], b[1] - a[1]];
        let len = hypot(d[0], d[1]);
        of(states, guide).arm([d[0] / len, d[1] / len])
    };
    match joint.kind {
        // Row r_a(p) − r_b(p): the force on link b is +λ.
        // (plus the tooth force of a mesh whose wheel turns in this joint).
        JointKind::Revolute { .. } => {
            out.force = bearing();
            out.normal = hypot(out.force[0], out.force[1]);
        }
        // Rows θ_s − θ_g and c(u, r_s(p) − r_g(a)): couple −λ₀, normal force −λ₁ along n.
        JointKind::Prismatic { guide, line, .. } => {
            let u = guide_dir(guide, line);
            out.couple = -l(0);
            out.normal = -l(1);
            out.force = [-(out.normal * u[1]), out.normal * u[0]];
        }
        JointKind::PinInSlot {
            slot_link, line, ..
        } => {
            let u = guide_dir(slot_link, line);
            out.normal = -l(0);
            out.force = [-(out.normal * u[1]), out.normal * u[0]];
        }
        // Row (s − s₀) − R(θ_b − θ_a): force −λ on the rack along u.
        JointKind::RackPinion { rack, .. } => {
            if let JointKind::Prismatic { guide, line, .. } = m.joints[rack].kind {
                let u = guide_dir(guide, line);
                out.normal = -l(0);
                out.force = [out.normal * u[0], out.normal * u[1]];
            }
        }
        // Row (θ_b2 − θ_a2) − ratio(θ_b1 − θ_a1): torque −λ on the second gear's link.
        JointKind::Gear { .. } => {
            out.normal = -l(0);
            out.couple = -l(0);
        }
        // Rows r_b − r_a(p), θ_b − θ_a: force −λ and couple −λ₂ on link b.
        JointKind::Rigid { .. } => {
            out.force = [-l(0), -l(1)];
            out.couple = -l(2);
            out.normal = hypot(l(0), l(1));
        }
    }
    out
}
