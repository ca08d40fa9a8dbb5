use mechdiff_macros::derivatives;

fn helper(x: f64) -> f64 {
    x * x
}

#[derivatives(wrt = x, order = 1)]
fn calls_a_function(x: f64) -> f64 {
    helper(x) + f64::sin(x)
}

fn main() {}
