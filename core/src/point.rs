//! Planar (x, y) pairs: points of a mechanism, and their derivatives.

use crate::jet::Jet;
use crate::motion::DriveState;

/// A pair of planar coordinates (x, y), generic over what each coordinate is: a scalar of a
/// position function (`Point<D>`), a coordinate with its derivatives (`Point<Jet<2>>`), or a
/// vector quantity in f64 — a velocity, an acceleration, a force (`Point<f64>` then holds its
/// x and y components).
///
/// ```
/// use mechdiff_core::{DriveState, Jet, Point};
/// // A crank pin on a circle of radius 0.1 m at φ = 0, as jets in φ.
/// let pin = Point::new(Jet::new(0.1, [0.0, -0.1]), Jet::new(0.0, [0.1, 0.0]));
/// let a = pin.acceleration(&DriveState::constant_speed(2.0));
/// assert_eq!((a.x, a.y), (-0.4, 0.0)); // centripetal: −ω² r towards the pivot
/// assert_eq!(Point::new(1.0, 2.0).map(|c| 2.0 * c), Point::new(2.0, 4.0));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Point<T> {
    /// The x coordinate (or component).
    pub x: T,
    /// The y coordinate (or component).
    pub y: T,
}

impl<T> Point<T> {
    /// The point (x, y).
    pub const fn new(x: T, y: T) -> Self {
        Self { x, y }
    }

    /// Applies `f` to x, then to y (the order [`crate::PositionFunction::map`] relies on).
    pub fn map<U>(self, mut f: impl FnMut(T) -> U) -> Point<U> {
        let x = f(self.x);
        Point { x, y: f(self.y) }
    }
}

impl<const N: usize> Point<Jet<N>> {
    /// The coordinates without their derivatives.
    pub fn value(&self) -> Point<f64> {
        Point::new(self.x.value, self.y.value)
    }

    /// The velocity components ω x′, ω y′.
    pub fn velocity(&self, drive: &DriveState) -> Point<f64> {
        Point::new(self.x.velocity(drive), self.y.velocity(drive))
    }

    /// The acceleration components α x′ + ω² x″, α y′ + ω² y″ (a jet of order below 2 does not
    /// compile).
    pub fn acceleration(&self, drive: &DriveState) -> Point<f64> {
        Point::new(
            self.x.motion(drive).acceleration,
            self.y.motion(drive).acceleration,
        )
    }
}

impl std::ops::Add for Point<f64> {
    type Output = Self;

    /// Component-wise sum (of forces, say).
    fn add(self, other: Self) -> Self {
        Self::new(self.x + other.x, self.y + other.y)
    }
}

impl std::ops::Mul<Point<f64>> for f64 {
    type Output = Point<f64>;

    /// Scales both components.
    fn mul(self, p: Point<f64>) -> Point<f64> {
        Point::new(self * p.x, self * p.y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `map` visits x before y: the order flatten/rebuild of the derivative methods rely on.
    #[test]
    fn map_visits_x_then_y() {
        let mut seen = Vec::new();
        let p = Point::new('x', 'y').map(|c| seen.push(c));
        assert_eq!(p, Point::new((), ()));
        assert_eq!(seen, ['x', 'y']);
    }

    /// With a drive acceleration α the tangential term α x′ appears (never assumed zero):
    /// x′ = 1, x″ = 0 with ω = 3, α = 2 gives ẍ = 2 exactly.
    #[test]
    fn acceleration_includes_the_drive_acceleration() {
        let p = Point::new(Jet::new(0.0, [1.0, 0.0]), Jet::new(0.0, [0.0, 1.0]));
        let a = p.acceleration(&DriveState::accelerating(3.0, 2.0));
        assert_eq!(a, Point::new(2.0, 9.0));
        assert_eq!(
            p.velocity(&DriveState::constant_speed(3.0)),
            Point::new(3.0, 0.0)
        );
        assert_eq!(-2.0 * a + a, Point::new(-2.0, -9.0));
    }
}
