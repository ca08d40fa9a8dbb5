use mechdiff_macros::derivatives;

#[derivatives(wrt = theta, order = 2)]
fn psi(phi: f64, lambda: f64) -> f64 {
    (lambda * phi.sin()).atan2(1.0 - lambda * phi.cos())
}

fn main() {}
