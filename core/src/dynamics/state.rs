//! The motion of every link at one instant, and the rigid-body formulas every effect uses.

use crate::{DriveState, Jet};

/// Position, velocity and acceleration of one moving link at an instant: its reference point
/// `r` (the link's first point), its rotation `θ` since the sketch, and their time derivatives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinkState {
    /// Reference point (m).
    pub r: [f64; 2],
    /// Velocity of the reference point (m/s).
    pub v: [f64; 2],
    /// Acceleration of the reference point (m/s²).
    pub a: [f64; 2],
    /// Rotation since the sketch (rad).
    pub theta: f64,
    /// Angular velocity (rad/s).
    pub omega: f64,
    /// Angular acceleration (rad/s²).
    pub alpha: f64,
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

    /// Global vector `ρ = A(θ)·local` from the reference point to the point at `local`.
    pub fn arm(&self, local: [f64; 2]) -> [f64; 2] {
        let (s, c) = self.theta.sin_cos();
        [c * local[0] - s * local[1], s * local[0] + c * local[1]]
    }

    /// Global position of the point at `local` (m).
    pub fn position(&self, local: [f64; 2]) -> [f64; 2] {
        let rho = self.arm(local);
        [self.r[0] + rho[0], self.r[1] + rho[1]]
    }

    /// Velocity `v + ω k×ρ` of the point of this link that is at global position `p` (m/s).
    pub fn velocity_at(&self, p: [f64; 2]) -> [f64; 2] {
        let rho = [p[0] - self.r[0], p[1] - self.r[1]];
        [
            self.v[0] - self.omega * rho[1],
            self.v[1] + self.omega * rho[0],
        ]
    }

    /// Acceleration `a + α k×ρ − ω² ρ` of the point of this link at global position `p`.
    pub fn acceleration_at(&self, p: [f64; 2]) -> [f64; 2] {
        let rho = [p[0] - self.r[0], p[1] - self.r[1]];
        let w2 = self.omega * self.omega;
        [
            self.a[0] - self.alpha * rho[1] - w2 * rho[0],
            self.a[1] + self.alpha * rho[0] - w2 * rho[1],
        ]
    }

    /// Moment about the reference point of a force `f` acting at global position `p`.
    pub fn moment(&self, p: [f64; 2], f: [f64; 2]) -> f64 {
        cross([p[0] - self.r[0], p[1] - self.r[1]], f)
    }
}

/// The states of all moving links (index `k − 1` for link `k`) from the pose coordinates and
/// their φ-derivatives, for the drive state `drive`: `q̇ = ω q′`, `q̈ = α q′ + ω² q″`.
pub(crate) fn link_states(coordinates: &[Jet<2>], drive: &DriveState) -> Vec<LinkState> {
    let vel = |j: &Jet<2>| drive.omega * j.derivatives[0];
    let acc =
        |j: &Jet<2>| drive.alpha * j.derivatives[0] + drive.omega * drive.omega * j.derivatives[1];
    coordinates
        .chunks_exact(3)
        .map(|c| LinkState {
            r: [c[0].value, c[1].value],
            v: [vel(&c[0]), vel(&c[1])],
            a: [acc(&c[0]), acc(&c[1])],
            theta: c[2].value,
            omega: vel(&c[2]),
            alpha: acc(&c[2]),
        })
        .collect()
}

/// State of link `link` (0 = ground) among `states`.
pub(crate) fn of(states: &[LinkState], link: usize) -> LinkState {
    if link == 0 {
        LinkState::GROUND
    } else {
        states[link - 1]
    }
}

/// The planar cross product `a_x b_y − a_y b_x`.
pub(crate) fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// The dot product.
pub(crate) fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// Generalized loads: 3 per moving link (`F_x`, `F_y`, moment about the reference point).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Generalized(pub Vec<f64>);

impl Generalized {
    pub fn zeros(links: usize) -> Self {
        Generalized(vec![0.0; 3 * links])
    }

    /// Adds force `f` at global point `p` on link `link` (nothing for the ground).
    pub fn force(&mut self, states: &[LinkState], link: usize, p: [f64; 2], f: [f64; 2]) {
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
    pub fn couple(&mut self, link: usize, c: f64) {
        if link > 0 {
            self.0[3 * (link - 1) + 2] += c;
        }
    }
}
