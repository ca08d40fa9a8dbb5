use mechdiff_macros::derivatives;

#[derivatives(wrt = x, order = 1)]
fn first_positive(x: f64) -> f64 {
    loop {
        break x.sin();
    }
}

fn main() {}
