//! Counterweights for linkages: a four-bar's full force balance against Berkof and Lowen's
//! conditions (derived independently below), an in-line slider-crank's least-squares crank
//! counterweight against the half-reciprocating-mass rule, and bad input.

use crate::common;

use common::{four_bar_rocker_pin, revolution};
use mechdiff_core::balancing::{Counterweight, SliderCrankUnbalance, balance_linkage};
use mechdiff_core::dynamics::Dynamics;
use mechdiff_core::geometry::{Drive, Inertia, Mechanism, MechanismBuilder, Solver};
use mechdiff_core::{DriveState, Error};

// Four-bar: frame a1 = 0.4 m (O2 at the origin, O4 on +x), crank a2 = 0.1, coupler
// a3 = 0.35, rocker a4 = 0.3 (Grashof crank-rocker), sketched at φ = 0.
const A1: f64 = 0.4;
const A2: f64 = 0.1;
const A3: f64 = 0.35;
const A4: f64 = 0.3;

/// Complex numbers as [re, im].
fn mul(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] * b[0] - a[1] * b[1], a[0] * b[1] + a[1] * b[0]]
}
fn div(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    let d = b[0] * b[0] + b[1] * b[1];
    [
        (a[0] * b[0] + a[1] * b[1]) / d,
        (a[1] * b[0] - a[0] * b[1]) / d,
    ]
}
fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}
fn scale(a: [f64; 2], k: f64) -> [f64; 2] {
    [a[0] * k, a[1] * k]
}

struct FourBar {
    a: [f64; 2],
    b: [f64; 2],
    g: [[f64; 2]; 3],
    m: [f64; 3],
}

fn four_bar() -> FourBar {
    let a = [A2, 0.0];
    let b = four_bar_rocker_pin(a, A3, A4, A1, true).unwrap();
    // Centres of gravity off the links' lines, so every condition has two components.
    let g2 = [0.04, 0.015];
    let g3 = [(a[0] + b[0]) / 2.0 + 0.03, (a[1] + b[1]) / 2.0 + 0.05];
    let g4 = [A1 + 0.5 * (b[0] - A1) + 0.02, 0.5 * b[1] - 0.01];
    FourBar {
        a,
        b,
        g: [g2, g3, g4],
        m: [0.8, 2.0, 1.5],
    }
}

fn four_bar_mechanism(f: &FourBar) -> Result<Mechanism, Error> {
    let inertia = |mass, center, moment| Inertia {
        mass,
        center,
        moment,
    };
    Mechanism::builder()
        .point("O2", [0.0, 0.0])
        .point("O4", [A1, 0.0])
        .point("A", f.a)
        .point("B", f.b)
        .ground(["O2", "O4"])
        .link("crank", ["O2", "A"])
        .link("coupler", ["A", "B"])
        .link("rocker", ["O4", "B"])
        .inertia("crank", inertia(f.m[0], f.g[0], 0.002))
        .inertia("coupler", inertia(f.m[1], f.g[1], 0.03))
        .inertia("rocker", inertia(f.m[2], f.g[2], 0.01))
        .revolute("O2", "ground", "crank", "O2")
        .revolute("A", "crank", "coupler", "A")
        .revolute("B", "coupler", "rocker", "B")
        .revolute("O4", "ground", "rocker", "O4")
        .drive(Drive::angle("O2"))
        .build()
}

fn counterweight(link: &str, line: [&str; 2], radius: f64) -> Counterweight {
    Counterweight {
        link: link.to_owned(),
        line: line.map(str::to_owned),
        radius,
    }
}

/// Berkof–Lowen, derived here: with complex link vectors, ρᵢ the centre of gravity of link
/// i in the frame of its line (crank O2→A, coupler A→B, rocker O4→B), and the loop
/// a2 e^{iφ2} + a3 e^{iφ3} = a1 + a4 e^{iφ4}, the total mass moment is
/// Σ mᵢ zᵢ = const + e^{iφ2} [m2ρ2 + m3 a2 (1 − ρ3/a3)] + e^{iφ4} [m4ρ4 + m3 ρ3 a4/a3];
/// e^{iφ2} and e^{iφ4} vary independently, so the centre of mass is stationary iff
/// m2ρ2 = m3 a2 (ρ3/a3 − 1) and m4ρ4 = −m3 ρ3 a4/a3. The counterweights are the differences
/// from the links' own m ρ, turned into global axes at the sketch.
#[test]
fn four_bar_full_force_balance_matches_berkof_lowen() {
    let f = four_bar();
    let m = four_bar_mechanism(&f).unwrap();
    let cws = [
        counterweight("crank", ["O2", "A"], 0.05),
        counterweight("rocker", ["O4", "B"], 0.08),
    ];
    let phis = revolution(5.0, &[]);
    let drive = DriveState::accelerating(10.0, 2.0);
    let r = balance_linkage(&m, &Dynamics::new(), &cws, &phis, drive, &Solver::default()).unwrap();

    let dir2 = [1.0, 0.0]; // crank line at the sketch, unit
    let dir3 = scale(sub(f.b, f.a), 1.0 / A3);
    let dir4 = scale(sub(f.b, [A1, 0.0]), 1.0 / A4);
    let rho3 = div(sub(f.g[1], f.a), dir3);
    let rho2 = div(f.g[0], dir2);
    let rho4 = div(sub(f.g[2], [A1, 0.0]), dir4);
    let need2 = scale(sub(scale(rho3, 1.0 / A3), [1.0, 0.0]), f.m[1] * A2);
    let need4 = scale(rho3, -f.m[1] * A4 / A3);
    let cw2 = mul(sub(need2, scale(rho2, f.m[0])), dir2);
    let cw4 = mul(sub(need4, scale(rho4, f.m[2])), dir4);
    for (placed, expected) in r.counterweights.iter().zip([cw2, cw4]) {
        let err = sub(placed.vector, expected);
        // The least squares has a zero residual here; its solution carries rounding of the
        // kinematics (≈ 1e-15) times the condition number of its matrix: 1e-12 relative leaves
        // a margin that a wrong formula (off by the size of the terms) cannot meet.
        let size = expected[0].hypot(expected[1]);
        assert!(
            err[0].hypot(err[1]) <= 1e-12 * size,
            "{placed:?} vs {expected:?}"
        );
        assert!((placed.mass - size / placed.request.radius).abs() <= 1e-12 * placed.mass);
    }
    assert!(r.full_force_balance());
    // The shaking force of the balanced mechanism, from the dynamics code with the
    // counterweights added as point masses: ≤ 1e-10 of before at every drive position.
    let before = r.before.max_force();
    for (phi, force) in r.after.phi.iter().zip(&r.after.force) {
        assert!(
            force[0].hypot(force[1]) <= 1e-10 * before,
            "φ = {phi}: {force:?}"
        );
    }
    // The price, reported: shaking moment and drive torque before and after.
    println!(
        "four-bar: max |ΣF| {before:.6} → {:.3e} N; max |M_shaking| {:.6} → {:.6} N m; \
         max |M_drive| {:.6} → {:.6} N m",
        r.after.max_force(),
        r.before.max_moment(),
        r.after.max_moment(),
        r.before.max_drive_torque(),
        r.after.max_drive_torque()
    );
    assert!(r.after.max_drive_torque() != r.before.max_drive_torque());
    assert!(r.after.drive_torque.iter().all(|t| t.is_finite()));
}

/// With `rod = Some((mass, centre))` the rod has mass data, else none.
fn slider_crank(rod: Option<(f64, [f64; 2])>) -> MechanismBuilder {
    let r = 0.1;
    let l = 0.4;
    let b = Mechanism::builder()
        .point("O", [0.0, 0.0])
        .point("A", [r, 0.0])
        .point("B", [r + l, 0.0])
        .point("X", [1.0, 0.0])
        .ground(["O", "X"])
        .link("crank", ["O", "A"])
        .link("rod", ["A", "B"])
        .link("slider", ["B"])
        .inertia(
            "crank",
            Inertia {
                mass: 1.0,
                center: [0.03, 0.0],
                moment: 0.001,
            },
        )
        .inertia(
            "slider",
            Inertia {
                mass: 2.0,
                center: [r + l, 0.0],
                moment: 0.0,
            },
        );
    let b = match rod {
        Some((mass, center)) => b.inertia(
            "rod",
            Inertia {
                mass,
                center,
                moment: 0.0,
            },
        ),
        None => b,
    };
    b.revolute("O", "ground", "crank", "O")
        .revolute("A", "crank", "rod", "A")
        .revolute("B", "rod", "slider", "B")
        .prismatic("guide", "ground", ["O", "X"], "slider", "B")
        .drive(Drive::angle("O"))
}

/// In-line slider-crank (r = 0.1 m, l = 0.4 m), crank 1 kg with its centre 0.03 m out along
/// the crank, massless rod, slider 2 kg, constant speed. The slider's x = r cos φ +
/// √(l² − r² sin² φ) has, besides r cos φ, only even harmonics; over 72 equally spaced
/// positions of a revolution no even harmonic aliases onto the first, so the least-squares
/// crank counterweight cancels the rotating 0.03 kg·m and the forward half of the primary:
/// m r = 0.03 + ½·2·0.1 = 0.13 kg·m opposite the crank pin — SliderCrankUnbalance's
/// partial balance with c = ½.
#[test]
fn slider_crank_least_squares_is_the_half_balance() {
    let m = slider_crank(Some((0.0, [0.1, 0.0]))).build().unwrap();
    let mut phis = revolution(5.0, &[]);
    phis.pop(); // 360° repeats 0°
    let omega = 50.0;
    let r = balance_linkage(
        &m,
        &Dynamics::new(),
        &[counterweight("crank", ["O", "A"], 0.05)],
        &phis,
        DriveState::constant_speed(omega),
        &Solver::default(),
    )
    .unwrap();
    let unbalance = SliderCrankUnbalance::new(0.1, 0.4, 2.0, 0.03).unwrap();
    let half = unbalance.partial_balance(0.5, omega).unwrap();
    let cw = &r.counterweights[0];
    // 1e-12 relative: harmonic orthogonality is exact; what is left is rounding in the
    // kinematics and the least squares.
    assert!((cw.mass_radius - half.counterweight_mass_radius).abs() <= 1e-12 * 0.13);
    assert!((cw.angle.abs() - std::f64::consts::PI).abs() <= 1e-12);
    assert!(!r.full_force_balance());
    // What is left: the across-the-line primary c·m_rec·r·ω² = ½·2·0.1·2500 = 250 N appears
    // at φ = 90° (where the slider's own force is the secondary's −m_rec(r²/l)ω²·(−1) plus
    // higher harmonics, along the line), and the mean square force is smaller than before.
    assert!((half.primary_across - 250.0).abs() < 1e-12 * 250.0);
    let at_90 = r
        .after
        .phi
        .iter()
        .position(|p| (p - 90f64.to_radians()).abs() < 1e-12);
    let across = r.after.force[at_90.unwrap()][1];
    // Across the line only the crank and its counterweight act: −(0.03 − 0.13)·ω² with the
    // crank at 90°, i.e. the half-balance's 250 N (1e-9 relative: kinematics rounding).
    assert!((across.abs() - 250.0).abs() <= 1e-9 * 250.0, "{across}");
    assert!(r.after.rms_force() < r.before.rms_force());
}

/// The two-mass split of a rod of 0.6 kg with its centre of gravity at mid-length: 0.3 kg
/// to the wrist pin, 0.3 kg to the crank pin. By hand: m_rec = 2 + 0.3 = 2.3 kg,
/// m_rot r = 1·0.03 + 0.3·0.1 = 0.06 kg·m; at ω = 100 rad/s the primary is
/// 2.3·0.1·1e4 = 2300 N and the secondary 2300·0.1/0.4 = 575 N.
#[test]
fn slider_crank_unbalance_from_the_mechanism() {
    let m = slider_crank(Some((0.6, [0.3, 0.0]))).build().unwrap();
    let u = SliderCrankUnbalance::from_mechanism(&m, "crank", "rod", "slider").unwrap();
    // 1e-15: sums and ratios of a few numbers exact to 1 ulp.
    assert!((u.crank - 0.1).abs() < 1e-15 && (u.rod - 0.4).abs() < 1e-15);
    assert!((u.reciprocating_mass - 2.3).abs() < 1e-15);
    assert!((u.rotating_mass_radius - 0.06).abs() < 1e-15);
    assert!((u.primary(100.0) - 2300.0).abs() < 1e-11);
    assert!((u.secondary(100.0) - 575.0).abs() < 1e-11);
    let no_rod = slider_crank(None).build().unwrap();
    assert!(matches!(
        SliderCrankUnbalance::from_mechanism(&no_rod, "crank", "rod", "slider"),
        Err(Error::MissingData { .. })
    ));
    assert!(matches!(
        SliderCrankUnbalance::from_mechanism(&m, "rod", "crank", "slider"),
        Err(Error::InvalidJoint { .. })
    ));
}

#[test]
fn bad_requests_give_typed_errors() {
    let f = four_bar();
    let m = four_bar_mechanism(&f).unwrap();
    let phis = revolution(30.0, &[]);
    let drive = DriveState::constant_speed(10.0);
    let solve = |m: &Mechanism, cws: &[Counterweight], phis: &[f64], drive: DriveState| {
        balance_linkage(m, &Dynamics::new(), cws, phis, drive, &Solver::default())
    };
    let coupler = counterweight("coupler", ["A", "B"], 0.05);
    assert!(matches!(
        solve(&m, &[coupler], &phis, drive),
        Err(Error::NotPivoted { .. })
    ));
    let zero = counterweight("crank", ["O2", "A"], 0.0);
    assert!(matches!(
        solve(&m, &[zero], &phis, drive),
        Err(Error::NonPositiveLength { .. })
    ));
    let twice = [
        counterweight("crank", ["O2", "A"], 0.05),
        counterweight("crank", ["O2", "A"], 0.07),
    ];
    assert!(matches!(
        solve(&m, &twice, &phis, drive),
        Err(Error::DuplicateName { .. })
    ));
    let crank = [counterweight("crank", ["O2", "A"], 0.05)];
    // A drive speed of zero: no shaking force, the counterweight is not determined.
    let e = solve(&m, &crank, &phis, DriveState::constant_speed(0.0)).unwrap_err();
    assert!(matches!(e, Error::MissingData { .. }), "{e}");
    assert!(matches!(
        solve(&m, &crank, &[], drive),
        Err(Error::MissingData { .. })
    ));
    // A rod without mass data: named in the error.
    let no_rod = slider_crank(None).build().unwrap();
    let e = solve(
        &no_rod,
        &[counterweight("crank", ["O", "A"], 0.05)],
        &phis,
        drive,
    )
    .unwrap_err();
    assert!(
        matches!(&e, Error::MissingData { missing, .. } if missing.contains("rod")),
        "{e}"
    );
}
