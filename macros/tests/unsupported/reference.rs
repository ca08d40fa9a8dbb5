use mechdiff_macros::derivatives;

#[derivatives(wrt = x, order = 1)]
fn borrows(x: f64) -> f64 {
    let r = &x;
    *r * 2.0
}

fn main() {}
