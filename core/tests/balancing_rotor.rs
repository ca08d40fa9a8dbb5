//! Rotor balancing: reference 002's static example, its dynamic example's method on a fully
//! specified variant, two-plane balancing of random rotors, and bad input.

use std::f64::consts::{FRAC_PI_2, PI};

use mechdiff_core::Error;
use mechdiff_core::balancing::{Polygons, Rotor, RotorMass};
use nalgebra::{Matrix4, Vector4};
use proptest::prelude::*;

fn mass(mass: f64, radius: f64, angle: f64, axial: f64) -> RotorMass {
    RotorMass {
        mass,
        radius,
        angle,
        axial,
    }
}

/// Reference 002 (cams_balancing_002.md, "The source's static example"): the open mr polygon
/// leaves 0.003 kg·m along m1 and 0.0470 kg·m perpendicular to it; the balancing mass-radius
/// is mr4 = √(0.0470² + 0.003²) at θ = 180° + atan2(0.0470, 0.003). Values from
/// cams_balancing_002.json: mr4_kg_m and theta_deg_exact.
#[test]
fn static_example_of_reference_002() {
    const MR4_KG_M: f64 = 0.04709564735726647;
    const THETA_DEG_EXACT: f64 = 266.3477772196937;
    // Two masses that leave exactly those components (m1 along the x axis).
    let rotor = Rotor::new(vec![
        mass(1.0, 0.003, 0.0, 0.0),
        mass(1.0, 0.0470, FRAC_PI_2, 0.1),
    ])
    .unwrap();
    let fix = rotor.static_balance(0.0);
    // 1e-12 relative (the tolerance); the only rounding is in hypot and in
    // cos(π/2) ≈ 6e-17, which adds 3e-18 kg·m to the 0.003 component.
    assert!((fix.mass_radius - MR4_KG_M).abs() <= 1e-12 * MR4_KG_M);
    assert!((fix.mass_radius - 0.0470956473573).abs() <= 1e-12);
    let theta = fix.angle.to_degrees().rem_euclid(360.0);
    assert!((theta - THETA_DEG_EXACT).abs() <= 1e-12 * THETA_DEG_EXACT);
    assert!((theta - 266.348).abs() < 5e-4); // the printed 266.348° to its 3 decimals
    // The polygon with the correction closes: its last vertex is the origin (to rounding of
    // three terms of 0.05 kg·m: 1e-17).
    let closed = rotor.with_corrections(&[fix]).polygons(0.0);
    let end = *Polygons::vertices(&closed.force).last().unwrap();
    assert!(end[0].abs() < 1e-17 && end[1].abs() < 1e-17, "{end:?}");
}

/// Reference 002's dynamic example lacks its angles and distances; its method is
/// d_new = |Σ mᵢ rᵢ dᵢ e^{iθᵢ}| / (m r) at the angle of −Σ mᵢ rᵢ dᵢ e^{iθᵢ}. Variant stated
/// here: three cranks of 0.5 kg at 150 mm, at 0°, 120°, 240°, in planes d = +0.3 m, 0 (the
/// reference plane, so m r₂ d₂ = 0) and −0.2 m (m r₃ d₃ negative, as in the source); one more
/// crank of the same m r balances the couple about plane 2. By hand:
/// Σ e^{iθ} d = 0.3 − 0.2·(−1/2 − i√3/2) = 0.4 + 0.1√3 i, so d_new = √(0.16 + 0.03) = √0.19 m
/// and the angle is atan2(−0.1√3, −0.4).
#[test]
fn dynamic_example_method_on_a_stated_variant() {
    let crank = |deg: f64, d: f64| mass(0.5, 0.150, deg.to_radians(), d);
    let rotor = Rotor::new(vec![crank(0.0, 0.3), crank(120.0, 0.0), crank(240.0, -0.2)]).unwrap();
    let answer = rotor.couple_plane(0.5 * 0.150, 0.0).unwrap();
    // 1e-14 relative: a handful of roundings of O(1) terms.
    assert!((answer.distance - 0.19f64.sqrt()).abs() <= 1e-14);
    assert!((answer.correction.axial - 0.19f64.sqrt()).abs() <= 1e-14);
    let expected = (-0.1 * 3f64.sqrt()).atan2(-0.4);
    assert!((answer.correction.angle - expected).abs() <= 1e-14);
    assert!((answer.correction.mass_radius - 0.075).abs() <= 1e-16);
    // Couple about the reference plane closed; the three cranks at 120° spacing were already
    // in static balance, so the added crank leaves its own m r = 0.075 kg·m as force.
    let after = rotor.with_corrections(&[answer.correction]);
    let c = after.resultant_couple(0.0);
    assert!(c[0].hypot(c[1]) <= 1e-16, "{c:?}"); // terms of 0.02 kg·m², a few roundings
    let f = answer.force_after;
    assert!((f[0].hypot(f[1]) - 0.075).abs() <= 1e-16);
}

#[test]
fn a_correction_plane_at_a_mass_is_not_singular() {
    // Planes at the masses' own positions: the 4×4 system's determinant is (z_R − z_L)² = 1.
    let rotor = Rotor::new(vec![mass(1.0, 0.1, 0.3, 0.0), mass(2.0, 0.05, 2.0, 1.0)]).unwrap();
    let two = rotor.two_plane_balance(0.0, 1.0).unwrap();
    // Each plane's correction is minus the mass in it (the other mass has no couple about it).
    assert!((two.left.mass_radius - 0.1).abs() < 1e-16);
    assert!((two.right.mass_radius - 0.1).abs() < 1e-16);
    assert!((two.left.angle - (0.3 - PI)).abs() < 1e-15);
}

#[test]
fn bad_input_gives_typed_errors() {
    let rotor = Rotor::new(vec![mass(1.0, 0.1, 0.0, 0.0), mass(1.0, 0.1, 1.0, 0.5)]).unwrap();
    assert!(matches!(
        rotor.two_plane_balance(0.2, 0.2),
        Err(Error::CoincidentPlanes { .. })
    ));
    assert!(matches!(
        rotor.two_plane_balance(0.2, f64::NAN),
        Err(Error::InvalidValue { .. })
    ));
    let fix = rotor.static_balance(0.0);
    assert!(matches!(
        fix.mass_at_radius(0.0),
        Err(Error::NonPositiveLength { .. })
    ));
    assert!(matches!(
        fix.radius_for_mass(-1.0),
        Err(Error::InvalidValue { .. })
    ));
    assert!(matches!(
        rotor.couple_plane(0.0, 0.0),
        Err(Error::InvalidValue { .. })
    ));
    // Two equal masses opposite in one plane: no couple to cancel, no plane determined.
    let balanced = Rotor::new(vec![mass(1.0, 0.1, 0.0, 0.3), mass(1.0, 0.1, PI, 0.3)]).unwrap();
    assert!(matches!(
        balanced.couple_plane(0.1, 0.0),
        Err(Error::AlreadyBalanced { .. })
    ));
    for bad in [
        mass(0.0, 0.1, 0.0, 0.0),
        mass(1.0, -0.1, 0.0, 0.0),
        mass(1.0, 0.1, f64::NAN, 0.0),
        mass(1.0, 0.1, 0.0, f64::INFINITY),
    ] {
        let e = Rotor::new(vec![mass(1.0, 0.1, 0.0, 0.0), bad]).unwrap_err();
        assert!(
            matches!(&e, Error::InvalidValue { what, .. } if what.contains("rotor mass 2")),
            "{e}"
        );
    }
}

fn rotor_strategy() -> impl Strategy<Value = Vec<RotorMass>> {
    prop::collection::vec(
        (0.1..10.0f64, 0.01..1.0f64, -PI..PI, -1.0..1.0f64)
            .prop_map(|(m, r, a, z)| mass(m, r, a, z)),
        1..8,
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// After two-plane balancing the force and couple polygons close to 1e-12 of their
    /// largest term (a sum of ≤ 10 terms rounds at ≈ 10·1.1e-16 of the largest); the
    /// correction equals the unique solution of the 4×4 force-and-couple system (determinant
    /// (z_R − z_L)² ≠ 0, solved by LU here) and does not depend on the reference plane: the
    /// whole rotor and its planes shifted along the shaft by `shift` get the same corrections.
    #[test]
    fn two_plane_balance_closes_both_polygons(
        masses in rotor_strategy(),
        left in -1.0..1.0f64,
        gap in prop_oneof![0.05..1.0f64, -1.0..-0.05f64],
        reference in -3.0..3.0f64,
        shift in -10.0..10.0f64,
    ) {
        let right = left + gap;
        let rotor = Rotor::new(masses.clone()).unwrap();
        let two = rotor.two_plane_balance(left, right).unwrap();
        let after = rotor.with_corrections(&two.corrections());
        let [largest_f, largest_c] = after.largest_terms(reference);
        let f = after.resultant_force();
        let c = after.resultant_couple(reference);
        prop_assert!(f[0].hypot(f[1]) <= 1e-12 * largest_f, "force {f:?} of {largest_f}");
        prop_assert!(c[0].hypot(c[1]) <= 1e-12 * largest_c, "couple {c:?} of {largest_c}");

        // The 4×4 system: Σ U + U_L + U_R = 0 and Σ U z + U_L z_L + U_R z_R = 0.
        let sf = rotor.resultant_force();
        let sc = rotor.resultant_couple(0.0);
        let a = Matrix4::new(
            1.0, 0.0, 1.0, 0.0,
            0.0, 1.0, 0.0, 1.0,
            left, 0.0, right, 0.0,
            0.0, left, 0.0, right,
        );
        let x = a.lu().solve(&Vector4::new(-sf[0], -sf[1], -sc[0], -sc[1])).unwrap();
        let size = two.left.mass_radius.max(two.right.mass_radius);
        let close = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]) <= 1e-12 * size;
        prop_assert!(close(two.left.vector, [x[0], x[1]]));
        prop_assert!(close(two.right.vector, [x[2], x[3]]));

        // Shifted along the shaft: the differences z − z_L round at eps·(|z| + |shift|)
        // ≈ 2.5e-15 m, divided by |gap| ≥ 0.05: 5e-14 relative, inside 1e-12.
        let shifted: Vec<RotorMass> = masses
            .iter()
            .map(|m| RotorMass { axial: m.axial + shift, ..*m })
            .collect();
        let moved = Rotor::new(shifted).unwrap().two_plane_balance(left + shift, right + shift).unwrap();
        prop_assert!(close(two.left.vector, moved.left.vector));
        prop_assert!(close(two.right.vector, moved.right.vector));
    }
}
