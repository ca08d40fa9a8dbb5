//! How reading a scene grows with its number of names: a generated four-bar with n coupler
//! points and n/10 point outputs, read (parse and resolve: `scene::parse`) and checked
//! (`scene::check`: model, mobility, loops, motion range) at n = 10³, 10⁴, 10⁵; the times
//! and their ratio to the previous n (10 for linear growth).
//!
//! `cargo run --release --example reading_names` (BENCHMARKS.md, "Reading a scene of n
//! names").

use std::time::Instant;

use mechdiff::scene;

#[path = "../tests/common/many_names.rs"]
mod many_names;

fn main() -> Result<(), mechdiff::Error> {
    println!(
        "{:>8} {:>12} {:>8} {:>12} {:>8}",
        "n", "read (s)", "ratio", "check (s)", "ratio"
    );
    let mut previous: Option<(f64, f64)> = None;
    for n in [1_000, 10_000, 100_000] {
        let text = many_names::many_names(n, n / 10);
        // The fastest of three, so that a busy machine disturbs less.
        let (mut read, mut check) = (f64::INFINITY, f64::INFINITY);
        for _ in 0..3 {
            let start = Instant::now();
            let s = scene::parse("many_names.toml", &text)?;
            read = read.min(start.elapsed().as_secs_f64());
            let start = Instant::now();
            std::hint::black_box(scene::check(&s)?);
            check = check.min(start.elapsed().as_secs_f64());
        }
        let ratio = |now: f64, before: Option<f64>| {
            before.map_or_else(String::new, |b| format!("{:.1}", now / b))
        };
        println!(
            "{n:>8} {read:>12.4} {:>8} {check:>12.4} {:>8}",
            ratio(read, previous.map(|p| p.0)),
            ratio(check, previous.map(|p| p.1)),
        );
        previous = Some((read, check));
    }
    Ok(())
}
