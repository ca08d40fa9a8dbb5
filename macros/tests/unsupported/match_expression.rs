use mechdiff_macros::derivatives;

#[derivatives(wrt = x, order = 1)]
fn matches(x: f64) -> f64 {
    match x > 0.0 {
        true => x,
        false => -x,
    }
}

fn main() {}
