//! The motion of every link at one instant, and the rigid-body formulas every effect uses.
//!
//! Everything here is generic over the scalar `T` ([`Scalar`]): `f64` for a run, and
//! `Dual64` for the exact derivative of every result with respect to a parameter (see
//! [`super::tangent`]); one implementation serves both.

use crate::{DriveState, Jet, Scalar};

/// Position, velocity and acceleration of one moving link at an instant: its reference point
/// `r` (the link's first point), its rotation `θ` since the sketch, and their time derivatives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinkState<T = f64> {
    /// Reference point (m).
    pub r: [T; 2],
    /// Velocity of the reference point (m/s).
    pub v: [T; 2],
    /// Acceleration of the reference point (m/s²).
    pub a: [T; 2],
    /// Rotation since the sketch (rad).
    pub theta: T,
    /// Angular velocity (rad/s).
    pub omega: T,
    /// Angular acceleration (rad/s²).
    pub alpha: T,
}

impl LinkState {
    /// The ground: at rest, unrotated, its frame the global one.
    pub const GROUND: LinkState = LinkState {
        r: [0.0; 2],
        v: [0.0; 2],
        a: [0.0; 2],
        theta: 0.0,
        omega: 0.0,
        alpha: 0.0,
    };
}

impl<T: Scalar> LinkState<T> {
    /// The ground in scalar `T` (see [`LinkState::GROUND`]).
    pub fn ground() -> Self {
        let z = T::zero();
        LinkState {
            r: [z; 2],
            v: [z; 2],
            a: [z; 2],
            theta: z,
            omega: z,
            alpha: z,
        }
    }

    /// Global vector `ρ = A(θ)·local` from the reference point to the point at `local`.
    pub fn arm(&self, local: [T; 2]) -> [T; 2] {
        let (s, c) = self.theta.sin_cos();
        [c * local[0] - s * local[1], s * local[0] + c * local[1]]
    }

    /// Global position of the point at `local` (m).
    pub fn position(&self, local: [T; 2]) -> [T; 2] {
        let rho = self.arm(local);
        [self.r[0] + rho[0], self.r[1] + rho[1]]
    }

    /// Velocity `v + ω k×ρ` of the point of this link that is at global position `p` (m/s).
    pub fn velocity_at(&self, p: [T; 2]) -> [T; 2] {
        let rho = [p[0] - self.r[0], p[1] - self.r[1]];
        [
            self.v[0] - self.omega * rho[1],
            self.v[1] + self.omega * rho[0],
        ]
    }

    /// Acceleration `a + α k×ρ − ω² ρ` of the point of this link at global position `p`.
    pub fn acceleration_at(&self, p: [T; 2]) -> [T; 2] {
        let rho = [p[0] - self.r[0], p[1] - self.r[1]];
        let w2 = self.omega * self.omega;
        [
            self.a[0] - self.alpha * rho[1] - w2 * rho[0],
            self.a[1] + self.alpha * rho[0] - w2 * rho[1],
        ]
    }

    /// Moment about the reference point of a force `f` acting at global position `p`.
    pub fn moment(&self, p: [T; 2], f: [T; 2]) -> T {
        cross([p[0] - self.r[0], p[1] - self.r[1]], f)
    }
}

/// The states of all moving links (index `k − 1` for link `k`) from the pose coordinates and
/// their φ-derivatives, for the drive state `drive`: `q̇ = ω q′`, `q̈ = α q′ + ω² q″`.
pub(crate) fn link_states(coordinates: &[Jet<2>], drive: &DriveState) -> Vec<LinkState> {
    let mut states = Vec::new();
    link_states_into(coordinates, drive, &mut states);
    states
}

/// [`link_states`] into `states` (cleared first; nothing allocated once it has the
/// capacity).
pub(crate) fn link_states_into(
    coordinates: &[Jet<2>],
    drive: &DriveState,
    states: &mut Vec<LinkState>,
) {
    states_into(
        coordinates,
        |j| [j.value, j.derivatives[0], j.derivatives[1]],
        drive.omega,
        drive.alpha,
        states,
    );
}

/// [`link_states`] in any scalar: `jet` gives `(q, q′, q″)` of one coordinate, `omega` and
/// `alpha` are the drive's speed and acceleration.
pub(crate) fn states_of<C, T: Scalar>(
    coordinates: &[C],
    jet: impl Fn(&C) -> [T; 3],
    omega: T,
    alpha: T,
) -> Vec<LinkState<T>> {
    let mut states = Vec::with_capacity(coordinates.len() / 3);
    states_into(coordinates, jet, omega, alpha, &mut states);
    states
}

/// [`states_of`] into `states` (cleared first).
pub(crate) fn states_into<C, T: Scalar>(
    coordinates: &[C],
    jet: impl Fn(&C) -> [T; 3],
    omega: T,
    alpha: T,
    states: &mut Vec<LinkState<T>>,
) {
    let drive = DriveState {
        omega,
        alpha,
        jerk: T::zero(),
    };
    states.clear();
    states.extend(coordinates.chunks_exact(3).map(|c| {
        let [x, y, t] = [jet(&c[0]), jet(&c[1]), jet(&c[2])];
        let vel = |j: [T; 3]| drive.velocity(j[1]);
        let acc = |j: [T; 3]| drive.acceleration(j[1], j[2]);
        LinkState {
            r: [x[0], y[0]],
            v: [vel(x), vel(y)],
            a: [acc(x), acc(y)],
            theta: t[0],
            omega: vel(t),
            alpha: acc(t),
        }
    }));
}

/// State of link `link` (0 = ground) among `states`.
pub(crate) fn of<T: Scalar>(states: &[LinkState<T>], link: usize) -> LinkState<T> {
    if link == 0 {
        LinkState::ground()
    } else {
        states[link - 1]
    }
}

/// The planar cross product `a_x b_y − a_y b_x`.
pub(crate) fn cross<T: Scalar>(a: [T; 2], b: [T; 2]) -> T {
    a[0] * b[1] - a[1] * b[0]
}

/// The dot product.
pub(crate) fn dot<T: Scalar>(a: [T; 2], b: [T; 2]) -> T {
    a[0] * b[0] + a[1] * b[1]
}

/// Generalized loads: 3 per moving link (`F_x`, `F_y`, moment about the reference point).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Generalized<T = f64>(pub Vec<T>);

impl<T: Scalar> Generalized<T> {
    pub fn zeros(links: usize) -> Self {
        Generalized(vec![T::zero(); 3 * links])
    }

    /// Adds force `f` at global point `p` on link `link` (nothing for the ground).
    pub fn force(&mut self, states: &[LinkState<T>], link: usize, p: [T; 2], f: [T; 2]) {
        if link == 0 {
            return;
        }
        let s = &states[link - 1];
        let i = 3 * (link - 1);
        self.0[i] += f[0];
        self.0[i + 1] += f[1];
        self.0[i + 2] += s.moment(p, f);
    }

    /// Adds couple `c` on link `link` (nothing for the ground).
    pub fn couple(&mut self, link: usize, c: T) {
        if link > 0 {
            self.0[3 * (link - 1) + 2] += c;
        }
    }
}
