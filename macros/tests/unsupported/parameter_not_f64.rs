use mechdiff_macros::derivatives;

#[derivatives(wrt = x, order = 1)]
fn scaled(x: f64, _n: i32) -> f64 {
    x * 2.0
}

fn main() {}
