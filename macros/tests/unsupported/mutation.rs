use mechdiff_macros::derivatives;

#[derivatives(wrt = x, order = 1)]
fn mutates(x: f64) -> f64 {
    let mut y = x.sin();
    y += 1.0;
    y
}

fn main() {}
