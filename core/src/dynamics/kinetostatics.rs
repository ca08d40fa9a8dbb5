//! Kinetostatics: every joint reaction and the drive torque at one drive position.
//!
//! The equilibrium of every moving link, `Φ_qᵀ λ = Q` (see [`super`]), is one square linear
//! system per drive position. Without friction and efficiencies it is solved once. Friction
//! forces `f·|N|` and efficiency factors depend on the signs of the reactions and on the
//! direction of power flow, which are not known before solving; they are resolved by
//! iteration: starting from the ideal solution, the friction columns are linearized with the
//! current signs (`|N| = σ·N` in sliding joints, `|R| = R̂·R` in revolute joints, `R̂` the
//! current direction) and each mesh's output side is scaled by `η` or `1/η` for the current
//! direction of power flow; the system is solved again until the signs, directions and flows
//! repeat. In sliding joints this is exact once the signs repeat; revolute friction circles
//! converge geometrically. Signs that never settle mean that no consistent solution exists:
//! [`Error::SelfLocking`].

use super::efficiency::CompiledEfficiency;
use super::equilibrium::Assembly;
use super::friction::CompiledFriction;
use super::inertia::{self, InertialLoad};
use super::model::{CompiledModel, Data};
use super::plan::{Effects, Trace};
use super::solution::Solution;
use super::state::{self, Generalized, LinkState};
use super::{gravity, loads};
use crate::geometry::Kinematics;
use crate::{DriveState, Error, Jet, Scalar};
use nalgebra::{DMatrix, DVector};

/// Solves the equilibrium at the pose of `k` for drive state `drive`, with `effects`.
pub fn solve(
    model: &CompiledModel<'_>,
    effects: &Effects,
    k: &Kinematics<'_, 2>,
    drive: &DriveState,
) -> Result<Solution, Error> {
    solve_at(model, effects, k.phi, &k.coordinates, drive)
}

/// [`solve`] at drive position `phi` from the pose coordinates and their first two
/// φ-derivatives (`Kinematics::coordinates`).
pub fn solve_at(
    model: &CompiledModel<'_>,
    effects: &Effects,
    phi: f64,
    coordinates: &[Jet<2>],
    drive: &DriveState,
) -> Result<Solution, Error> {
    let states = state::link_states(coordinates, drive);
    let n = model.equations.coordinates();
    let q: Vec<f64> = coordinates.iter().map(|j| j.value).collect();
    let qdot: Vec<f64> = coordinates
        .iter()
        .map(|j| drive.omega * j.derivatives[0])
        .collect();
    let mut jac = DMatrix::zeros(n, n);
    model.equations.jacobian(&q, &mut jac);
    let mut trace = Trace::default();
    let (load, inertial) = applied(&model.data(), effects, phi, &states, &mut trace);
    let friction: &[CompiledFriction] = if effects.friction {
        &model.friction
    } else {
        &[]
    };
    let efficiency: &[CompiledEfficiency] = if effects.efficiency {
        &model.efficiency
    } else {
        &[]
    };
    let asm = Assembly::new(
        model,
        friction,
        efficiency,
        states,
        jac,
        DVector::from_vec(load.0),
        qdot,
    );
    let (lambda, signs, iterations) = asm.iterate(phi, &mut trace)?;
    trace.equilibrium_solves += iterations;
    asm.finish(
        effects, phi, drive, lambda, signs, iterations, inertial, trace,
    )
}

/// The generalized applied and inertial loads `Q` of the effects in `effects` (the right-hand
/// side of `Φ_qᵀ λ = Q`) and the inertial loads, in any scalar; counts what it evaluates.
pub(crate) fn applied<T: Scalar>(
    data: &Data<'_, T>,
    effects: &Effects,
    phi: f64,
    states: &[LinkState<T>],
    trace: &mut Trace,
) -> (Generalized<T>, Vec<InertialLoad<T>>) {
    let mut load = Generalized::zeros(states.len());
    let mut inertial = Vec::new();
    if effects.inertia && !data.masses.is_empty() {
        inertial = inertia::loads(data.masses, states);
        inertia::load(&inertial, states, &mut load);
        trace.inertia += 1;
    }
    if effects.gravity
        && let Some(g) = data.gravity
    {
        gravity::load(g, data.masses, states, &mut load);
        trace.gravity += 1;
    }
    if effects.loads && !data.loads.is_empty() {
        loads::load(data.loads, phi, states, &mut load);
        trace.loads += 1;
    }
    (load, inertial)
}
