//! `mechdiff codegen` reads the piecewise form `if(a < b, then, otherwise)`: the cam laws of
//! reference 002 (peak 80 mm at π, back to 0 at 2π), each written as one `if` formula, are
//! generated into `tests/data/codegen_piecewise.rs` (regenerate it with
//! `sh tests/data/codegen_piecewise.sh`), compiled into this test, and checked against the
//! reference's values and the closed form of each piece on both sides of every break.

mod generated {
    include!("data/codegen_piecewise.rs");
}

use mechdiff::codegen::{Args, generate};
use std::f64::consts::PI;

const PARABOLIC: &str = "if(x < pi/2, 160*x^2/pi^2, if(x < 3*pi/2, -160*x^2/pi^2 + 320*x/pi - 80, 160*x^2/pi^2 - 640*x/pi + 640))";
const UNIFORM: &str = "if(x <= pi, 80*x/pi, 160 - 80*x/pi)";

#[test]
fn the_compiled_fixture_is_what_codegen_writes() {
    let fixture = include_str!("data/codegen_piecewise.rs");
    for (formula, name, order) in [
        (PARABOLIC, "parabolic", 3),
        (UNIFORM, "uniform_velocity", 2),
    ] {
        let mut args = Args::new(formula, "x", order);
        args.name = name.to_owned();
        let text = generate(&args).unwrap();
        // A nested `if` is emitted as `else if` (clippy's `collapsible_else_if`).
        assert!(
            name != "parabolic" || text.contains("} else if x < "),
            "{text}"
        );
        assert!(
            fixture.contains(&text),
            "regenerate tests/data/codegen_piecewise.rs: `{formula}` now gives\n{text}"
        );
    }
}

/// The parabolic law's closed form on each piece (reference 002's `.md`, derived by hand):
/// y, y′, y″.
fn parabolic_piece(piece: usize, x: f64) -> [f64; 3] {
    let c = 160.0 / (PI * PI);
    match piece {
        0 => [c * x * x, 2.0 * c * x, 2.0 * c],
        1 => [
            -c * x * x + 320.0 * x / PI - 80.0,
            -2.0 * c * x + 320.0 / PI,
            -2.0 * c,
        ],
        _ => [
            c * x * x - 640.0 * x / PI + 640.0,
            2.0 * c * x - 640.0 / PI,
            2.0 * c,
        ],
    }
}

/// Reference 002 (`cams_balancing_002.json`, uniform acceleration–retardation) at x = kπ/8,
/// k = 0…16: y [mm], y′ [mm/rad], y″ [mm/rad²] (right-hand values at the breaks π/2, 3π/2).
const REFERENCE: [[f64; 3]; 17] = {
    const V: f64 = 12.732395447351626; // 40/π
    const A: f64 = 32.42277876554809; // 320/π²
    [
        [0.0, 0.0, A],
        [2.5, V, A],
        [10.0, 2.0 * V, A],
        [22.5, 3.0 * V, A],
        [40.0, 4.0 * V, -A],
        [57.5, 3.0 * V, -A],
        [70.0, 2.0 * V, -A],
        [77.5, V, -A],
        [80.0, 0.0, -A],
        [77.5, -V, -A],
        [70.0, -2.0 * V, -A],
        [57.5, -3.0 * V, -A],
        [40.0, -4.0 * V, A],
        [22.5, -3.0 * V, A],
        [10.0, -2.0 * V, A],
        [2.5, -V, A],
        [0.0, 0.0, A],
    ]
};

#[test]
fn the_generated_parabolic_law_matches_reference_002_and_each_side_of_its_breaks() {
    // 1e-12 of each quantity's peak (80 mm, 160/π mm/rad, 320/π² mm/rad²): the last piece
    // cancels terms of 640 mm down to 0, a few ulp of 640.
    let peaks = [80.0, 160.0 / PI, 320.0 / (PI * PI)];
    let close = |got: &[f64], want: &[f64; 3], at: &str| {
        for d in 0..3 {
            assert!(
                (got[d] - want[d]).abs() <= 1e-12 * peaks[d],
                "{at}, derivative {d}: {} vs {}",
                got[d],
                want[d]
            );
        }
    };
    for (k, want) in REFERENCE.iter().enumerate() {
        let x = k as f64 * PI / 8.0;
        let got = generated::parabolic(x);
        close(&got, want, &format!("x = {k}π/8"));
        assert_eq!(
            got[3], 0.0,
            "jerk of a parabola is exactly 0 inside each piece"
        );
    }
    // One ulp either side of each break: the left piece below, the right piece at and above.
    for (piece, b) in [(0, PI / 2.0), (1, 3.0 * PI / 2.0)] {
        let below = f64::from_bits(b.to_bits() - 1);
        let above = f64::from_bits(b.to_bits() + 1);
        close(
            &generated::parabolic(below),
            &parabolic_piece(piece, below),
            "below",
        );
        close(
            &generated::parabolic(b),
            &parabolic_piece(piece + 1, b),
            "at",
        );
        close(
            &generated::parabolic(above),
            &parabolic_piece(piece + 1, above),
            "above",
        );
        // y″ jumps by 2·320/π² there (reference: ±32.4227787655).
        let jump = generated::parabolic(b)[2] - generated::parabolic(below)[2];
        assert!(
            (jump.abs() - 640.0 / (PI * PI)).abs() < 1e-12 * peaks[2],
            "{jump}"
        );
    }
}

#[test]
fn the_generated_uniform_velocity_law_has_its_slope_jump_at_pi() {
    // Exact pieces 80x/π and 160 − 80x/π; 1e-12 relative to the 80 mm peak.
    let below = f64::from_bits(PI.to_bits() - 1);
    let above = f64::from_bits(PI.to_bits() + 1);
    for (x, slope) in [(below, 80.0 / PI), (PI, 80.0 / PI), (above, -80.0 / PI)] {
        let [y, d1, d2] = generated::uniform_velocity(x);
        let want = if x <= PI {
            80.0 * x / PI
        } else {
            160.0 - 80.0 * x / PI
        };
        assert!((y - want).abs() < 1e-12 * 80.0, "{x}: {y} vs {want}");
        assert!((d1 - slope).abs() < 1e-12 * 80.0, "{x}: {d1}");
        assert_eq!(d2, 0.0);
    }
}
