use mechdiff_macros::derivatives;

#[derivatives(wrt = x, order = 1)]
fn prints(x: f64) -> f64 {
    println!("{x}");
    x
}

fn main() {}
