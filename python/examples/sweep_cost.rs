//! The Rust library's run of a scene over many drive positions, timed: the baseline of the
//! Python package's per-position cost (`examples/sweep_cost.py` runs this and the same
//! sweep through Python, and prints the ratio).
//!
//! `cargo run --release -p mechdiff-python --example sweep_cost -- SCENE FROM TO COUNT`
//! prints the seconds of `mechdiff::run` (and freeing its report) of COUNT positions from FROM to TO (the scene's
//! unit of the drive), the best of three.

use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [scene, from, to, count] = args.as_slice() else {
        eprintln!("usage: sweep_cost SCENE FROM TO COUNT");
        return ExitCode::FAILURE;
    };
    let (Ok(from), Ok(to), Ok(count)) = (
        from.parse::<f64>(),
        to.parse::<f64>(),
        count.parse::<usize>(),
    ) else {
        eprintln!("sweep_cost: FROM and TO are numbers, COUNT a whole number");
        return ExitCode::FAILURE;
    };
    let positions: Vec<f64> = (0..count)
        .map(|i| from + (to - from) * i as f64 / (count.max(2) - 1) as f64)
        .collect();
    let run = || -> Result<f64, mechdiff::Error> {
        let scene = mechdiff::load(scene)?.with_positions(&positions)?;
        let start = cpu_seconds();
        let report = mechdiff::run(&scene)?;
        // Freed inside the time, as the Python call frees the rows it transposes.
        drop(std::hint::black_box(report));
        Ok(cpu_seconds() - start)
    };
    let mut best = f64::INFINITY;
    for _ in 0..3 {
        match run() {
            Ok(seconds) => best = best.min(seconds),
            Err(e) => {
                eprintln!("sweep_cost: {e}");
                return ExitCode::FAILURE;
            }
        }
    }
    println!("{best}");
    ExitCode::SUCCESS
}

/// The CPU time this process has used, in seconds.
fn cpu_seconds() -> f64 {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `t` is a valid, writable timespec; CLOCK_PROCESS_CPUTIME_ID is a clock every
    // POSIX system has, so the call only writes `t`.
    unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut t) };
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
}
