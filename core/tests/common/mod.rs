//! Whole mechanisms defined by geometry only, shared by the geometry tests.
#![allow(dead_code)] // each test binary uses a subset

use mechdiff_core::Error;
use mechdiff_core::geometry::{Drive, Inertia, Mechanism, MechanismBuilder};
use num_dual::{Dual3_64, DualNum};

/// Whitworth parameters of whitworth_000.md: l0 = 0.400 m, l1 = 0.150 m, h = 0.650 m.
pub const L0: f64 = 0.4;
/// Crank length (m).
pub const L1: f64 = 0.15;
/// Height of the ram's line (m).
pub const H: f64 = 0.65;

/// The Whitworth of whitworth_000.md, sketched at φ = 0: rocker pivot B0 at the origin,
/// crank pivot O = (0, l0), crank pin A = (0, l0 − l1) sliding in the rocker's slot, ram pin C
/// at height h sliding in the same slot, ram translating along y = h. φ is the crank's
/// rotation (A = (l1 sin φ, l0 − l1 cos φ)), ψ = −(rocker rotation), x_C = ram displacement.
pub fn whitworth() -> Result<Mechanism, Error> {
    whitworth_with_moments([0.0, 0.0])
}

/// [`whitworth`] with the masses recovered in whitworth_000.md (crank 15 kg with S1 at 0.04 m
/// from O, rocker 30 kg with S2 at 0.15 m from B0, ram 50 kg at C) and the given moments of
/// inertia of crank and rocker (kg·m²; the source gives none).
pub fn whitworth_with_moments(moments: [f64; 2]) -> Result<Mechanism, Error> {
    let inertia = |mass, center, moment| Inertia {
        mass,
        center,
        moment,
    };
    Mechanism::builder()
        .point("O", [0.0, L0])
        .point("B0", [0.0, 0.0])
        .point("A", [0.0, L0 - L1])
        .point("S", [0.0, H])
        .point("C", [0.0, H])
        .point("H0", [0.0, H])
        .point("H1", [1.0, H])
        .point("S1", [0.0, L0 - 0.04])
        .ground(["O", "B0", "H0", "H1"])
        .link("crank", ["O", "A", "S1"])
        .link("rocker", ["B0", "S"])
        .link("ram", ["C"])
        .inertia("crank", inertia(15.0, [0.0, L0 - 0.04], moments[0]))
        .inertia("rocker", inertia(30.0, [0.0, 0.15], moments[1]))
        .inertia("ram", inertia(50.0, [0.0, H], 0.0))
        .revolute("O", "ground", "crank", "O")
        .revolute("B0", "ground", "rocker", "B0")
        .pin_in_slot("slot A", "rocker", ["B0", "S"], "crank", "A")
        .prismatic("ram guide", "ground", ["H0", "H1"], "ram", "C")
        .pin_in_slot("slot C", "rocker", ["B0", "S"], "ram", "C")
        .drive(Drive::angle("O"))
        .build()
}

/// Data of rack_slotted_link_001.md (Table 1 of the source, θ8 = 60° assumed there).
pub mod rack001 {
    /// ρ1 (m).
    pub const RHO1: f64 = 0.332;
    /// ρ2 (m).
    pub const RHO2: f64 = 0.25;
    /// ρ4 at θ3 = 63° (m), `rho4_m_30digits` of rack_slotted_link_001.json.
    pub const RHO4: f64 = 0.419162449232150365090550694535;
    /// ρ5 (m).
    pub const RHO5: f64 = 1.065;
    /// ρ6 (m).
    pub const RHO6: f64 = 0.723;
    /// ρ7 (m).
    pub const RHO7: f64 = 0.458;
    /// ρ9 (m).
    pub const RHO9: f64 = 0.234;
    /// θ3 at the instant (rad).
    pub const THETA3: f64 = 63.0 * std::f64::consts::PI / 180.0;
    /// θ7 (rad).
    pub const THETA7: f64 = 285.0 * std::f64::consts::PI / 180.0;
    /// θ8 (rad), assumed.
    pub const THETA8: f64 = 60.0 * std::f64::consts::PI / 180.0;
}

/// Which closure of loop 2 of mechanism 001 the sketch draws.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Closure001 {
    /// Slider beyond C along u8 (ρ8 = 2.0027 m), the reference's primary case.
    Primary,
    /// The other intersection of the rod's circle with the incline (ρ8 = 0.7721 m).
    Other,
}

/// Mechanism 001 (gear rack, slotted link, coupler rod, slider on an incline) sketched at
/// θ3 = 63°. The pin A of the rack is modelled as a block hinged to the rack and sliding in
/// the link's slot, so that ρ3 is the displacement of prismatic joint "slot". With `pinion`,
/// a gear wheel of radius 0.04 m above the rack drives it (rack-and-pinion), else the rack's
/// displacement ρ4 is the drive.
pub fn rack_slotted_link(closure: Closure001, pinion: bool) -> Result<Mechanism, Error> {
    rack_slotted_link_incline(closure, pinion, rack001::THETA8)
}

/// [`rack_slotted_link`] with the incline at `theta8` (rad) instead of the assumed 60°.
pub fn rack_slotted_link_incline(
    closure: Closure001,
    pinion: bool,
    theta8: f64,
) -> Result<Mechanism, Error> {
    use rack001::*;
    let b = [RHO2, -RHO1];
    let e3 = [THETA3.cos(), THETA3.sin()];
    let u8 = [theta8.cos(), theta8.sin()];
    let c = [b[0] + RHO5 * e3[0], b[1] + RHO5 * e3[1]];
    let g1 = [b[0] + RHO9 * e3[0], b[1] + RHO9 * e3[1]];
    let p = [b[0] + RHO7 * THETA7.cos(), b[1] + RHO7 * THETA7.sin()];
    // D = P + ρ8 u8 with |D − C| = ρ6: ρ8 = (C−P)·u ± √(((C−P)·u)² − |C−P|² + ρ6²).
    let cp = [c[0] - p[0], c[1] - p[1]];
    let proj = cp[0] * u8[0] + cp[1] * u8[1];
    let root = (proj * proj - (cp[0] * cp[0] + cp[1] * cp[1]) + RHO6 * RHO6).sqrt();
    let rho8 = match closure {
        Closure001::Primary => proj + root,
        Closure001::Other => proj - root,
    };
    let d = [p[0] + rho8 * u8[0], p[1] + rho8 * u8[1]];
    let mut builder = Mechanism::builder()
        .point("O'", [0.0, 0.0])
        .point("X", [1.0, 0.0])
        .point("A", [RHO4, 0.0])
        .point("B", b)
        .point("C", c)
        .point("G1", g1)
        .point("P", p)
        .point("P2", [p[0] + u8[0], p[1] + u8[1]])
        .point("D", d)
        .ground(["O'", "X", "B", "P", "P2"])
        .link("rack", ["A"])
        .link("block", ["A"])
        .link("slotted link", ["B", "C", "G1"])
        .link("rod", ["C", "D"])
        .link("slider", ["D"])
        .prismatic("rack guide", "ground", ["O'", "X"], "rack", "A")
        .revolute("A", "rack", "block", "A")
        .prismatic("slot", "slotted link", ["B", "C"], "block", "A")
        .revolute("B", "ground", "slotted link", "B")
        .revolute("C", "slotted link", "rod", "C")
        .revolute("D", "rod", "slider", "D")
        .prismatic("incline", "ground", ["P", "P2"], "slider", "D");
    if pinion {
        builder = builder
            .point("W", [RHO4, 0.04])
            .ground(["W"])
            .link("pinion", ["W"])
            .revolute("W", "ground", "pinion", "W")
            .rack_pinion("mesh", "W", "rack guide", 0.04)
            .drive(Drive::angle("W"));
    } else {
        builder = builder.drive(Drive::displacement("rack guide"));
    }
    builder.build()
}

/// Two gear wheels about O1 = (0, 0) and O2 = (0.3, 0) (mesh ratio −2), optionally with a
/// plate welded to the second, carrying P = (0.3, 0.3); driven by either wheel.
pub fn gear_pair(drive_second: bool, plate: bool) -> Mechanism {
    let mut b = Mechanism::builder()
        .point("O1", [0.0, 0.0])
        .point("O2", [0.3, 0.0])
        .point("P", [0.3, 0.3])
        .ground(["O1", "O2"])
        .link("wheel 1", ["O1"])
        .link("wheel 2", ["O2"])
        .revolute("O1", "ground", "wheel 1", "O1")
        .revolute("O2", "ground", "wheel 2", "O2")
        .gear("mesh", "O1", "O2", -2.0)
        .drive(Drive::angle(if drive_second { "O2" } else { "O1" }));
    if plate {
        b = b.link("plate", ["P"]).rigid("weld", "wheel 2", "plate");
    }
    b.build().unwrap()
}

/// The links and revolutes of a slider-crank, without its guide and drive: crank `r` from
/// O = (0, 0), rod `l` to the slider's pin B on the x axis (X = (1, 0) marks the guide's
/// direction), sketched at crank angle `phi0`.
pub fn crank_rod(r: f64, l: f64, phi0: f64) -> MechanismBuilder {
    let a = [r * phi0.cos(), r * phi0.sin()];
    let x = a[0] + (l * l - a[1] * a[1]).sqrt();
    Mechanism::builder()
        .point("O", [0.0, 0.0])
        .point("A", a)
        .point("B", [x, 0.0])
        .point("X", [1.0, 0.0])
        .ground(["O", "X"])
        .link("crank", ["O", "A"])
        .link("rod", ["A", "B"])
        .link("slider", ["B"])
        .revolute("O", "ground", "crank", "O")
        .revolute("A", "crank", "rod", "A")
        .revolute("B", "rod", "slider", "B")
}

/// [`crank_rod`] with the slider's guide (`guide`, along the x axis): add inertia, loads and
/// a drive.
pub fn slider_crank_parts(r: f64, l: f64, phi0: f64) -> MechanismBuilder {
    crank_rod(r, l, phi0).prismatic("guide", "ground", ["O", "X"], "slider", "B")
}

/// Slider-crank: crank `r` from O = (0, 0), rod `l`, slider on the x axis; sketched at crank
/// angle `phi0`, φ = crank angle (or slider displacement from O when `drive_slider`).
pub fn slider_crank(r: f64, l: f64, phi0: f64, drive_slider: bool) -> Result<Mechanism, Error> {
    let b = slider_crank_parts(r, l, phi0);
    if drive_slider {
        b.drive(Drive::displacement("guide")).build()
    } else {
        b.drive(Drive::angle("O").at_sketch(phi0)).build()
    }
}

/// Four-bar: ground pivots A0 = (0, 0) and B0 = (d, 0), crank `a`, coupler `b`, rocker `c`,
/// sketched at crank angle `phi0` with the coupler–rocker joint above (`up`) or below the line
/// from the crank pin to B0. φ = crank angle.
pub fn four_bar(a: f64, b: f64, c: f64, d: f64, phi0: f64, up: bool) -> Result<Mechanism, Error> {
    let pa = [a * phi0.cos(), a * phi0.sin()];
    let bp = four_bar_rocker_pin(pa, b, c, d, up).unwrap_or([f64::NAN, f64::NAN]);
    Mechanism::builder()
        .point("A0", [0.0, 0.0])
        .point("B0", [d, 0.0])
        .point("A", pa)
        .point("B", bp)
        .ground(["A0", "B0"])
        .link("crank", ["A0", "A"])
        .link("coupler", ["A", "B"])
        .link("rocker", ["B0", "B"])
        .revolute("A0", "ground", "crank", "A0")
        .revolute("A", "crank", "coupler", "A")
        .revolute("B", "coupler", "rocker", "B")
        .revolute("B0", "ground", "rocker", "B0")
        .drive(Drive::angle("A0").at_sketch(phi0))
        .build()
}

/// Intersection of the circles (A, b) and (B0, c), on the side `up` (left of A → B0).
pub fn four_bar_rocker_pin(a: [f64; 2], b: f64, c: f64, d: f64, up: bool) -> Option<[f64; 2]> {
    let f = [d - a[0], -a[1]];
    let dist = f[0].hypot(f[1]);
    let along = (b * b - c * c + dist * dist) / (2.0 * dist);
    let h2 = b * b - along * along;
    if h2 < 0.0 {
        return None;
    }
    let (e, n) = ([f[0] / dist, f[1] / dist], [-f[1] / dist, f[0] / dist]);
    let s = if up { h2.sqrt() } else { -h2.sqrt() };
    Some([
        a[0] + along * e[0] + s * n[0],
        a[1] + along * e[1] + s * n[1],
    ])
}

/// The drive positions of a full revolution from 0 at `step_deg` steps, plus `extra`
/// (sorted in).
pub fn revolution(step_deg: f64, extra: &[f64]) -> Vec<f64> {
    let n = (360.0 / step_deg).round() as usize;
    let mut v: Vec<f64> = (0..=n)
        .map(|i| (i as f64 * step_deg).to_radians())
        .collect();
    v.extend_from_slice(extra);
    v.sort_by(f64::total_cmp);
    v
}

/// max |a − b| over a list, divided by max |b| (the scale of the quantity over the sweep).
pub fn scaled_error(pairs: &[(f64, f64)]) -> f64 {
    let scale = pairs.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
    let err = pairs.iter().map(|p| (p.0 - p.1).abs()).fold(0.0, f64::max);
    if scale == 0.0 { err } else { err / scale }
}

/// The four-bar's coupler–rocker pin B(φ) in closed form (crank `a` from the origin, coupler
/// `b`, rocker `c` hinged at (d, 0), `up`: the closure above the line from A to the rocker
/// pivot), with third-order dual numbers: the reference the geometry paths are checked against.
pub fn four_bar_pin(a: f64, b: f64, c: f64, d: f64, phi: f64, up: bool) -> [Dual3_64; 2] {
    let phi = Dual3_64::new(phi, 1.0, 0.0, 0.0);
    let (ax, ay) = (phi.cos() * a, phi.sin() * a);
    let (fx, fy) = (-ax + d, -ay);
    let dist = (fx * fx + fy * fy).sqrt();
    let along = (dist * dist + b * b - c * c) / (dist * 2.0);
    let h = (-(along * along) + b * b).sqrt();
    let h = if up { h } else { -h };
    let (ex, ey) = (fx / dist, fy / dist);
    [ax + along * ex - h * ey, ay + along * ey + h * ex]
}
