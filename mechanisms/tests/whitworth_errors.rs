//! Bad input is a typed error at construction that names the parameter and says why; valid
//! geometry close to the limits gives finite results, never a NaN.

use mechdiff_core::PositionFunction;
use mechdiff_core::method::{Differentiator, Dual3};
use mechdiff_mechanisms::whitworth::Parameters;
use mechdiff_mechanisms::{Error, Whitworth};

/// A copy of the reference parameters with one of them changed.
fn with(name: &str, value: f64) -> Parameters {
    let mut p = Parameters::reference();
    let field = match name {
        "l0" => &mut p.l0,
        "l1" => &mut p.l1,
        "l_S1" => &mut p.l_s1,
        "l_S2" => &mut p.l_s2,
        "h" => &mut p.h,
        "c_x" => &mut p.c_x,
        "c_y" => &mut p.c_y,
        "m1" => &mut p.m1,
        "m2" => &mut p.m2,
        "m3" => &mut p.m3,
        "ω" => &mut p.crank_speed,
        _ => unreachable!("no parameter {name}"),
    };
    *field = value;
    p
}

/// Zero, negative, NaN and infinite lengths, masses and crank speeds are each rejected with an
/// `InvalidParameter` naming that parameter, with a message that names it too.
#[test]
fn zero_negative_or_non_finite_parameters_are_named_errors() {
    let positive = ["l0", "l1", "l_S1", "l_S2", "h", "m1", "m2", "m3", "ω"];
    for name in positive {
        for value in [0.0, -0.1, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let error = Whitworth::new(with(name, value)).unwrap_err();
            // The range checks come before l1 < l0: l0 = ∞ is reported as not finite.
            match &error {
                Error::InvalidParameter { name: got, .. } => assert_eq!(got, &name),
                other => panic!("{name} = {value}: {other:?}"),
            }
            let message = error.to_string();
            assert!(message.contains(name), "{message}");
            let why = if value.is_finite() {
                "positive"
            } else {
                "finite"
            };
            assert!(message.contains(why), "{message}");
        }
    }
}

/// The ram's centre-of-gravity offsets may be zero or negative, but not NaN or infinite.
#[test]
fn offsets_may_be_any_finite_number() {
    for name in ["c_x", "c_y"] {
        assert!(Whitworth::new(with(name, -0.2)).is_ok());
        let error = Whitworth::new(with(name, f64::NAN)).unwrap_err();
        assert!(matches!(error, Error::InvalidParameter { name: got, .. } if got == name));
    }
}

/// l1 ≥ l0: the rocker would turn fully round and the ram pin could not follow (at l1 = l0, ψ
/// is undefined at φ = 0). The error says which parameter and why.
#[test]
fn crank_not_shorter_than_frame_is_an_error() {
    for l1 in [0.4, 0.41, 1.0] {
        let error = Whitworth::new(with("l1", l1)).unwrap_err();
        assert_eq!(error, Error::CrankNotShorterThanFrame { l1, l0: 0.4 });
        let message = error.to_string();
        assert!(message.contains("l1") && message.contains("shorter than the frame l0"));
    }
}

/// Close to the limit (λ = 0.999) every output and its derivatives up to the third stay finite
/// over a whole revolution (including φ = 0, where y_A = l0 − l1 is smallest), and both dead
/// positions are still found.
#[test]
fn geometry_close_to_the_limit_stays_finite() {
    let shaper = Whitworth::new(with("l1", 0.3996)).unwrap();
    for k in 0..=360 {
        let phi = f64::from(k).to_radians();
        let mut finite = true;
        Whitworth::map(Dual3.jets(&shaper, phi), |x| finite &= x.is_finite());
        assert!(finite, "φ = {k}°");
        let forces = shaper.inertial_forces(phi, &shaper.drive()).unwrap();
        assert!(forces.sum.x.is_finite() && forces.sum.y.is_finite());
    }
    let [first, second] = shaper.dead_positions().unwrap();
    assert!((first.phi - shaper.lambda().acos()).abs() <= 1e-13);
    assert!(second.phi > first.phi);
}
