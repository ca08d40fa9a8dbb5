//! Shared by the Whitworth integration tests: the reference data and one table row.
#![allow(dead_code)]

use mechdiff_core::DriveState;
use mechdiff_mechanisms::Whitworth;
use serde_json::Value;

/// The project's copy of the reference values (`tests/data/whitworth_000.json`, copied from
/// the reference `whitworth_000.json`; see its `source` entry).
pub fn reference() -> Value {
    serde_json::from_str(include_str!("../data/whitworth_000.json"))
        .expect("tests/data/whitworth_000.json is valid JSON")
}

/// A number of the reference data.
pub fn number(value: &Value) -> f64 {
    value
        .as_f64()
        .unwrap_or_else(|| panic!("expected a number, found {value}"))
}

/// A 30-digit string of the reference data, rounded to f64.
pub fn digits(value: &Value) -> f64 {
    value
        .as_str()
        .unwrap_or_else(|| panic!("expected a digit string, found {value}"))
        .parse()
        .expect("a decimal number")
}

/// The quantities of the source's table, with the keys of the reference data.
pub const TABLE_KEYS: [&str; 12] = [
    "xdd_S1_m_s2",
    "ydd_S1_m_s2",
    "xdd_S2_m_s2",
    "ydd_S2_m_s2",
    "xdd_S3_m_s2",
    "F_x1_N",
    "F_y1_N",
    "F_x2_N",
    "F_y2_N",
    "F_x3_N",
    "SumF_x_N",
    "SumF_y_N",
];

/// One column of the source's table, computed by mechdiff at crank angle `phi` (rad) and the
/// reference machine's constant crank speed, in the order of [`TABLE_KEYS`].
pub fn table_column(shaper: &Whitworth, phi: f64) -> [f64; 12] {
    let drive: DriveState = shaper.drive();
    let a = shaper.centre_accelerations(phi, &drive).unwrap();
    let f = shaper.inertial_forces(phi, &drive).unwrap();
    [
        a.s1.x, a.s1.y, a.s2.x, a.s2.y, a.s3.x, f.f1.x, f.f1.y, f.f2.x, f.f2.y, f.f3.x, f.sum.x,
        f.sum.y,
    ]
}
