//! The curves of a run with `[simulate]` for its diagrams, kept with bounded memory.

/// The most points of each curve kept for the diagrams (thinned as the rows stream by).
pub const CURVE_POINTS: usize = 4096;

/// The curves of the diagrams in printed units, each thinned to at most [`CURVE_POINTS`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Curves {
    /// ω over t.
    pub omega_time: Thinned,
    /// The motor's torque over t.
    pub motor_torque: Thinned,
    /// ω over φ at the steady state.
    pub omega_angle: Thinned,
    /// x and y labels with units: time, drive angle, speed, torque.
    pub labels: [String; 4],
}

/// A curve kept with bounded memory: when it holds [`CURVE_POINTS`] points every other one
/// is dropped and from then on only every other point is taken (the stride doubles).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Thinned {
    /// The points kept.
    pub points: Vec<[f64; 2]>,
    stride: usize,
    seen: usize,
}

impl Thinned {
    /// Offers a point.
    pub fn push(&mut self, point: [f64; 2]) {
        let stride = self.stride.max(1);
        if self.seen.is_multiple_of(stride) {
            self.points.push(point);
            if self.points.len() >= CURVE_POINTS {
                let mut k = 0;
                self.points.retain(|_| {
                    k += 1;
                    k % 2 == 1
                });
                self.stride = 2 * stride;
            }
        }
        self.seen += 1;
    }
}
