//! Define a new mechanism: write its position equations once, generic over the scalar, and
//! let mechdiff derive velocities and accelerations.
//!
//! A slider-crank: crank radius r turning about the origin, connecting rod l, piston on the
//! x axis. Run with `cargo run --example define_a_mechanism`.

use mechdiff::core::method::{Differentiator, Dual2};
use mechdiff::core::{DriveState, PositionFunction, Scalar};

/// A slider-crank with crank radius `r` and rod length `l` (m), l > r.
struct SliderCrank {
    r: f64,
    l: f64,
}

/// Its outputs: the piston position x (m) and the rod angle β (rad).
struct Outputs<T> {
    x: T,
    beta: T,
}

impl PositionFunction for SliderCrank {
    type Output<T> = Outputs<T>;

    /// The loop closure r sin φ = l sin β, x = r cos φ + l cos β, written once.
    fn evaluate<D: Scalar>(&self, phi: D) -> Outputs<D> {
        let (sin, cos) = phi.sin_cos();
        let beta = (sin * (self.r / self.l)).asin();
        Outputs {
            x: cos * self.r + beta.cos() * self.l,
            beta,
        }
    }

    /// Visits every output once, always in the same order.
    fn map<A, B>(o: Outputs<A>, mut f: impl FnMut(A) -> B) -> Outputs<B> {
        let x = f(o.x);
        Outputs { x, beta: f(o.beta) }
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let engine = SliderCrank { r: 0.05, l: 0.2 };
    let drive = DriveState::from_rpm(3000.0);
    // x, x′, x″ and β, β′, β″ at top dead centre, exact to rounding.
    let at_top = Dual2.jets(&engine, 0.0);
    let piston = at_top.x.motion(&drive);
    // Known closed form at φ = 0: ẍ = −r ω² (1 + r/l).
    let expected = -engine.r * drive.omega.powi(2) * (1.0 + engine.r / engine.l);
    assert!((piston.acceleration - expected).abs() <= 1e-12 * expected.abs());
    assert!((at_top.beta.d1() - engine.r / engine.l).abs() < 1e-15); // β′(0) = r/l
    println!(
        "piston at top dead centre: x = {:.4} m, ẍ = {:.1} m/s²; rod: β′ = {}",
        piston.position,
        piston.acceleration,
        at_top.beta.d1()
    );
    Ok(())
}
