//! Reference 002, cam part: a rise–return cam with peak 80 mm at x = π, back to 0 at 2π,
//! for the uniform velocity, parabolic (uniform acceleration–retardation) and simple
//! harmonic laws. The values y, y′, y″ at x = kπ/8, with the one-sided values at the jumps,
//! are in `data/cams_reference_002.json` (copied from the project's reference material
//! `cams_balancing_002.json`, section `cams`; computed there in 30-digit arithmetic).
//!
//! Each law is built twice: from the standard laws (two segments of π: rise 80, return 80)
//! and from the reference's own formula pieces as formula segments.

use std::f64::consts::PI;

use mechdiff_core::Error;
use mechdiff_core::cams::{
    BoundaryKind, CamProgram, ContinuityReport, Formula, MotionLaw, Segment, Side,
};
use serde_json::Value;

fn reference() -> Value {
    serde_json::from_str(include_str!("data/cams_reference_002.json")).unwrap()
}

fn standard(law: MotionLaw) -> CamProgram {
    CamProgram::new(
        vec![Segment::law(law, 80.0, PI), Segment::law(law, -80.0, PI)],
        0.0,
    )
    .unwrap()
}

/// A program of formula segments from the reference's `"[a,b]: y = …"` pieces.
fn from_pieces(pieces: &[Value]) -> Result<CamProgram, Error> {
    let mut segments = Vec::new();
    for piece in pieces {
        let text = piece.as_str().unwrap();
        let (range, formula) = text.split_once(": y = ").unwrap();
        let ends: Vec<f64> = range
            .trim_matches(|c| c == '[' || c == ']')
            .split(',')
            .map(|end| match end {
                "0" => 0.0,
                "pi/2" => PI / 2.0,
                "pi" => PI,
                "3pi/2" => 1.5 * PI,
                "2pi" => 2.0 * PI,
                other => panic!("unexpected end {other}"),
            })
            .collect();
        // The reference writes products by juxtaposition ("80 x/pi", "40 cos x").
        let infix = formula
            .replace(" x", "*x")
            .replace("cos*x", "cos(x)")
            .replace(" cos", "*cos");
        segments.push(Segment::formula(Formula::parse(&infix)?, ends[1] - ends[0]));
    }
    CamProgram::new(segments, 0.0)
}

/// 1e-12 relative, or 1e-12 of the law's scale (80 mm, or the peak of y′, y″) where the
/// reference value is 0: every value is a few roundings away from exact in f64.
fn assert_close(what: &str, got: f64, want: f64, scale: f64) {
    let error = (got - want).abs();
    let allowed = 1e-12 * if want == 0.0 { scale } else { want.abs() };
    assert!(
        error <= allowed,
        "{what}: {got} vs {want} (error {error:e})"
    );
}

fn check_table(name: &str, program: &CamProgram, how: &str) {
    let data = reference();
    let table = data["cams"][name]["table"].as_array().unwrap();
    assert_eq!(table.len(), 17, "x = kπ/8 for k = 0..16");
    for row in table {
        let k = row["k_pi_over_8"].as_u64().unwrap();
        let x = row["x_rad"].as_f64().unwrap();
        // The table's x is kπ/8 rounded to f64 (1 ulp from k·PI/8 here and there).
        assert!((x - k as f64 * PI / 8.0).abs() <= 1e-15 * x);
        let sides: &[(Side, &str)] = if row.get("y_p_left_mm_per_rad").is_some() {
            &[(Side::Left, "_left"), (Side::Right, "_right")]
        } else {
            &[(Side::Right, "")]
        };
        for &(side, suffix) in sides {
            let svaj = program.svaj(x, side);
            let at = format!("{name} ({how}) at {k}π/8 {side:?}");
            let want =
                |key: &str, unit: &str| row[format!("{key}{suffix}_{unit}")].as_f64().unwrap();
            assert_close(&at, svaj.value, row["y_mm"].as_f64().unwrap(), 80.0);
            assert_close(&at, svaj.d1(), want("y_p", "mm_per_rad"), 80.0);
            assert_close(&at, svaj.d2(), want("y_pp", "mm_per_rad2"), 80.0);
        }
    }
}

#[test]
fn three_laws_match_the_reference_table_with_one_sided_values() {
    let data = reference();
    for (name, law) in [
        ("uniform_velocity", MotionLaw::UniformVelocity),
        ("uniform_acceleration_retardation", MotionLaw::Parabolic),
        ("simple_harmonic_motion", MotionLaw::SimpleHarmonic),
    ] {
        check_table(name, &standard(law), "standard law");
        let pieces = data["cams"][name]["formula_pieces"].as_array().unwrap();
        check_table(name, &from_pieces(pieces).unwrap(), "formula pieces");
    }
}

/// The source prints law (b)(iii) as y = 160x²/π² − 320x/π + 640: it does not meet the
/// middle piece at 3π/2 (520 instead of 40) and gives y(2π) = 640 instead of 0. The program
/// refuses it with the cam angle of the first bad join; the corrected −640x/π joins.
#[test]
fn misprinted_law_b_iii_is_refused_and_the_corrected_one_accepted() {
    let printed = Formula::parse("160*x^2/pi^2 - 320*x/pi + 640").unwrap();
    // 1e-12 relative: a few roundings of numbers of size 640.
    assert!((printed.value(2.0 * PI, 1.0) - 640.0).abs() < 640.0 * 1e-12);
    let pieces = |last: &str| {
        vec![
            Value::from("[0,pi/2]: y = 160 x^2/pi^2"),
            Value::from("[pi/2,3pi/2]: y = -160 x^2/pi^2 + 320 x/pi - 80"),
            Value::from(format!("[3pi/2,2pi]: y = {last}")),
        ]
    };
    match from_pieces(&pieces("160 x^2/pi^2 - 320 x/pi + 640")) {
        Err(Error::CamJoin {
            angle_deg,
            before,
            after,
            left,
            right,
        }) => {
            assert_eq!((angle_deg, before, after), (270.0, 2, 3));
            // 1e-12 relative: values of size 40 and 520 evaluated in f64.
            assert!((left - 40.0).abs() < 40.0 * 1e-12, "{left}");
            assert!((right - 520.0).abs() < 520.0 * 1e-12, "{right}");
        }
        other => panic!("the misprinted law was accepted: {other:?}"),
    }
    assert!(from_pieces(&pieces("160 x^2/pi^2 - 640 x/pi + 640")).is_ok());
}

/// The boundary report: uniform velocity's s′ jumps at 0 (= 2π) by +160/π and at π by
/// −160/π; the parabolic law's s″ jumps at π/2 by −640/π² and at 3π/2 by +640/π², and
/// nowhere else (s″ is continuous at 0 and π); simple harmonic motion has no jump up to s‴.
/// Jump sizes to 1e-12 relative (one-sided values exact up to rounding).
#[test]
fn boundary_report_finds_exactly_the_reference_jumps() {
    let data = reference();
    let cases = [
        ("uniform_velocity", MotionLaw::UniformVelocity),
        ("uniform_acceleration_retardation", MotionLaw::Parabolic),
        ("simple_harmonic_motion", MotionLaw::SimpleHarmonic),
    ];
    for (name, law) in cases {
        let pieces = data["cams"][name]["formula_pieces"].as_array().unwrap();
        for program in [standard(law), from_pieces(pieces).unwrap()] {
            let report = ContinuityReport::new(&program);
            let jumps: Vec<(f64, usize, f64)> = report
                .boundaries
                .iter()
                .filter_map(|b| b.first_jump().map(|k| (b.angle, k, b.jump(k))))
                .collect();
            let expected: Vec<(f64, usize, f64)> = match law {
                MotionLaw::UniformVelocity => vec![(0.0, 1, 160.0 / PI), (PI, 1, -160.0 / PI)],
                MotionLaw::Parabolic => vec![
                    (PI / 2.0, 2, -640.0 / (PI * PI)),
                    (1.5 * PI, 2, 640.0 / (PI * PI)),
                ],
                _ => vec![],
            };
            assert_eq!(jumps.len(), expected.len(), "{name}: {jumps:?}");
            for ((angle, k, jump), (want_angle, want_k, want_jump)) in jumps.iter().zip(&expected) {
                assert!((angle - want_angle).abs() < 1e-15 * PI, "{name}: {angle}");
                assert_eq!(k, want_k, "{name} at {angle}");
                assert!(
                    (jump - want_jump).abs() < 1e-12 * want_jump.abs(),
                    "{name}: {jump}"
                );
            }
            assert_eq!(
                report.satisfies_fundamental_law(),
                law == MotionLaw::SimpleHarmonic
            );
        }
    }
    // The parabolic law's jumps are inside its segments, not at the segment boundaries.
    let report = ContinuityReport::new(&standard(MotionLaw::Parabolic));
    for b in report.jumps_of(2) {
        assert!(matches!(b.kind, BoundaryKind::InsideSegment { .. }));
    }
}

/// The parabolic law as one piecewise formula over the whole turn (`if`, the symbolic
/// engine's piecewise form): the reference values, with the right-hand values at the jumps
/// (a formula takes the branch of its condition: x < π/2 is false at π/2). 1e-12 as above.
#[test]
fn a_piecewise_formula_reproduces_the_parabolic_law() {
    let formula = Formula::parse(
        "if(x < pi/2, 160*x^2/pi^2, if(x < 3*pi/2, -160*x^2/pi^2 + 320*x/pi - 80, \
         160*x^2/pi^2 - 640*x/pi + 640))",
    )
    .unwrap();
    let program = CamProgram::new(vec![Segment::formula(formula, 2.0 * PI)], 0.0).unwrap();
    let data = reference();
    for row in data["cams"]["uniform_acceleration_retardation"]["table"]
        .as_array()
        .unwrap()
    {
        let x = row["x_rad"].as_f64().unwrap();
        let suffix = if row.get("y_p_right_mm_per_rad").is_some() {
            "_right"
        } else {
            ""
        };
        let want = |key: &str, unit: &str| row[format!("{key}{suffix}_{unit}")].as_f64().unwrap();
        let svaj = program.svaj(x, Side::Right);
        assert_close(
            "piecewise y",
            svaj.value,
            row["y_mm"].as_f64().unwrap(),
            80.0,
        );
        assert_close("piecewise y′", svaj.d1(), want("y_p", "mm_per_rad"), 80.0);
        assert_close("piecewise y″", svaj.d2(), want("y_pp", "mm_per_rad2"), 80.0);
    }
}
