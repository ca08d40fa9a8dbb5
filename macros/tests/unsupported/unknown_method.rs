use mechdiff_macros::derivatives;

#[derivatives(wrt = x, order = 1)]
fn rounds(x: f64) -> f64 {
    x.floor() * 2.0
}

fn main() {}
