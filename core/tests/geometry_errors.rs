//! Every failure is a typed error naming what is wrong and where; none is a panic.

use crate::common;

use common::{crank_rod, four_bar, revolution, slider_crank};
use mechdiff_core::Error;
use mechdiff_core::geometry::{Drive, Mechanism, Solver, check_mobility};

#[test]
fn four_bar_with_a_short_coupler_names_the_drive_position_and_the_loop() {
    // a = 0.4, b = 0.3, c = 0.45, d = 0.6: |A − B0| grows from 0.2 at φ = 0 beyond
    // b + c = 0.75 at cos φ = (a² + d² − 0.75²)/(2ad), φ ≈ 95.08°.
    let m = four_bar(0.4, 0.3, 0.45, 0.6, 0.0, true).unwrap();
    let limit = ((0.16 + 0.36 - 0.5625) / 0.48f64).acos();
    let err = Solver::default()
        .sweep::<1>(&m, &revolution(1.0, &[]))
        .unwrap_err();
    match &err {
        Error::Blocked {
            from,
            to,
            limit: found,
            joints,
        } => {
            // The sweep's step from 95° to the first drive position beyond the limit, 96°.
            assert_eq!((*from, *to), (95f64.to_radians(), 96f64.to_radians()));
            // The limit position to 1e-13 (acos near −0.09, slope 1: rounding).
            assert!((found - limit).abs() < 1e-13, "{found} vs {limit}");
            // The coupler–rocker loop, not the crank.
            assert_eq!(joints, &["A", "B", "B0"]);
        }
        other => panic!("expected Blocked, got {other:?}"),
    }
    let text = err.to_string();
    assert!(
        text.contains("φ = 1.67")
            && text.contains("first fails at φ = 1.659")
            && text.contains("A, B, B0"),
        "{text}"
    );
}

#[test]
fn slider_driven_into_its_dead_centre_is_a_singular_toggle() {
    // Driven by the slider, the crank toggles where crank and rod are collinear, at
    // s = r + l (top dead centre): Φ_q is singular there.
    let (r, l) = (0.1, 0.35);
    let m = slider_crank(r, l, 1.0, true).unwrap();
    let mut t = Solver::default().track(&m).unwrap();
    let mut s = t.phi();
    while s + 0.01 < r + l {
        s += 0.01;
        t.move_to(s).unwrap();
    }
    match t.move_to(r + l).unwrap_err() {
        Error::Singular {
            phi,
            condition,
            joints,
        } => {
            assert_eq!(phi, r + l);
            assert!(
                condition > Solver::default().singular_threshold(),
                "{condition:e}"
            );
            assert!(joints.contains(&"A".to_owned()) && joints.contains(&"O".to_owned()));
        }
        other => panic!("expected Singular, got {other:?}"),
    }
}

#[test]
fn near_toggle_positions_still_solve() {
    // 1 µm before the dead centre the pose is regular (condition ~1e3): it must solve.
    let (r, l) = (0.1, 0.35);
    let m = slider_crank(r, l, 1.0, true).unwrap();
    let mut t = Solver::default().track(&m).unwrap();
    t.move_to(r + l - 1e-6).unwrap();
    let k = t.kinematics::<1>().unwrap();
    assert!(k.rotation("crank").unwrap().d1().is_finite());
}

#[test]
fn a_doubled_guide_is_over_constrained_and_named() {
    let m = crank_rod(0.1, 0.4, 0.0)
        .prismatic("guide", "ground", ["O", "X"], "slider", "B")
        .prismatic("guide 2", "ground", ["O", "X"], "slider", "B")
        .drive(Drive::angle("O"))
        .build()
        .unwrap();
    match check_mobility(&m).unwrap_err() {
        Error::Overconstrained {
            redundant,
            equations,
            coordinates,
        } => {
            assert_eq!((equations, coordinates), (11, 9));
            assert_eq!(redundant, ["guide", "guide 2"]);
        }
        other => panic!("expected Overconstrained, got {other:?}"),
    }
    // The solver refuses it too, with the same error.
    assert!(matches!(
        Solver::default().track(&m),
        Err(Error::Overconstrained { .. })
    ));
}

#[test]
fn a_parallelogram_with_an_extra_crank_is_over_constrained_though_it_moves() {
    // Grübler counts 0 freedoms (and −1 with the drive), yet it moves: only the rank sees
    // that the third crank repeats the others.
    let m = Mechanism::builder()
        .point("O1", [0.0, 0.0])
        .point("O2", [1.0, 0.0])
        .point("O3", [0.5, 0.0])
        .point("A1", [0.0, 0.4])
        .point("A2", [1.0, 0.4])
        .point("A3", [0.5, 0.4])
        .ground(["O1", "O2", "O3"])
        .link("crank 1", ["O1", "A1"])
        .link("crank 2", ["O2", "A2"])
        .link("crank 3", ["O3", "A3"])
        .link("coupler", ["A1", "A2", "A3"])
        .revolute("O1", "ground", "crank 1", "O1")
        .revolute("O2", "ground", "crank 2", "O2")
        .revolute("O3", "ground", "crank 3", "O3")
        .revolute("A1", "crank 1", "coupler", "A1")
        .revolute("A2", "crank 2", "coupler", "A2")
        .revolute("A3", "crank 3", "coupler", "A3")
        .drive(Drive::angle("O1"))
        .build()
        .unwrap();
    match check_mobility(&m).unwrap_err() {
        Error::Overconstrained { redundant, .. } => {
            // Every revolute of the redundant loop takes part; the driven crank's hinge O1
            // does not (its equations are independent of the drive's).
            for j in ["O2", "O3", "A1", "A2", "A3"] {
                assert!(redundant.contains(&j.to_owned()), "{redundant:?}");
            }
        }
        other => panic!("expected Overconstrained, got {other:?}"),
    }
}

#[test]
fn a_five_bar_with_one_drive_is_under_constrained_and_names_the_free_links() {
    let m = Mechanism::builder()
        .point("O1", [0.0, 0.0])
        .point("O2", [1.0, 0.0])
        .point("A", [0.0, 0.3])
        .point("B", [0.5, 0.6])
        .point("C", [1.0, 0.3])
        .ground(["O1", "O2"])
        .link("crank", ["O1", "A"])
        .link("left", ["A", "B"])
        .link("right", ["B", "C"])
        .link("crank 2", ["O2", "C"])
        .revolute("O1", "ground", "crank", "O1")
        .revolute("A", "crank", "left", "A")
        .revolute("B", "left", "right", "B")
        .revolute("C", "right", "crank 2", "C")
        .revolute("O2", "ground", "crank 2", "O2")
        .drive(Drive::angle("O1"))
        .build()
        .unwrap();
    match check_mobility(&m).unwrap_err() {
        Error::Underconstrained {
            free,
            links,
            joints,
        } => {
            assert_eq!(free, 1);
            assert_eq!(links, ["left", "right", "crank 2"]);
            assert_eq!(joints, ["A", "B", "C", "O2"]);
        }
        other => panic!("expected Underconstrained, got {other:?}"),
    }
}

#[test]
fn builder_errors_name_the_item() {
    let dup = Mechanism::builder()
        .point("A", [0.0, 0.0])
        .point("A", [1.0, 0.0])
        .build();
    assert_eq!(
        dup.unwrap_err(),
        Error::DuplicateName {
            what: "point",
            name: "A".into()
        }
    );

    let unknown = crank_rod(0.1, 0.4, 0.0)
        .revolute("Z", "crank", "wheel", "A")
        .drive(Drive::angle("O"))
        .build();
    assert!(matches!(unknown.unwrap_err(),
        Error::UnknownName { what: "link", name, context } if name == "wheel" && context == "joint `Z`"));

    let off = crank_rod(0.1, 0.4, 0.0)
        .revolute("Z", "crank", "slider", "A")
        .drive(Drive::angle("O"))
        .build();
    assert!(matches!(off.unwrap_err(),
        Error::PointNotOnLink { point, link, .. } if point == "A" && link == "slider"));

    let zero = crank_rod(0.1, 0.4, 0.0)
        .prismatic("guide", "ground", ["O", "O"], "slider", "B")
        .drive(Drive::angle("O"))
        .build();
    assert!(matches!(zero.unwrap_err(),
        Error::NonPositiveLength { what, length } if what.contains("guide") && length == 0.0));

    let nan = Mechanism::builder().point("A", [f64::NAN, 0.0]).build();
    assert!(matches!(nan.unwrap_err(), Error::InvalidValue { what, .. } if what.contains("`A`")));

    let no_drive = crank_rod(0.1, 0.4, 0.0)
        .prismatic("guide", "ground", ["O", "X"], "slider", "B")
        .build();
    assert_eq!(no_drive.unwrap_err(), Error::MissingDrive);

    let wrong_drive = crank_rod(0.1, 0.4, 0.0)
        .prismatic("guide", "ground", ["O", "X"], "slider", "B")
        .drive(Drive::angle("guide"))
        .build();
    assert!(
        matches!(wrong_drive.unwrap_err(), Error::InvalidJoint { joint, .. } if joint == "guide")
    );

    // A pin drawn 1 cm off its slot line: the sketch must satisfy every joint.
    let off_slot = Mechanism::builder()
        .point("O", [0.0, 0.0])
        .point("S", [1.0, 0.0])
        .point("P", [0.5, 0.01])
        .ground(["O", "P"])
        .link("bar", ["O", "S"])
        .revolute("O", "ground", "bar", "O")
        .pin_in_slot("slot", "bar", ["O", "S"], "ground", "P")
        .drive(Drive::angle("O"))
        .build();
    assert!(matches!(off_slot.unwrap_err(),
        Error::SketchNotAssembled { joint, residual } if joint == "slot" && (residual - 0.01).abs() < 1e-15));
}

#[test]
fn non_finite_drive_positions_and_unknown_outputs_are_errors() {
    let m = slider_crank(0.1, 0.35, 0.0, false).unwrap();
    let mut t = Solver::default().track(&m).unwrap();
    assert!(matches!(t.move_to(f64::NAN), Err(Error::NonFinite { .. })));
    let k = t.kinematics::<1>().unwrap();
    assert!(matches!(
        k.point("rod", "O"),
        Err(Error::InvalidOutput { .. })
    ));
    assert!(matches!(
        k.displacement("O"),
        Err(Error::InvalidOutput { .. })
    ));
    assert!(matches!(
        k.rotation("wheel"),
        Err(Error::InvalidOutput { .. })
    ));
    assert!(matches!(
        k.center_of_gravity("rod"),
        Err(Error::InvalidOutput { .. })
    ));
}

#[test]
fn a_sketch_drawn_at_a_toggle_is_reported_singular_at_the_sketch() {
    // Slider-driven slider-crank drawn at its dead centre (crank and rod collinear): the
    // count is right, the structure is fine, but Φ_q is singular there.
    let m = slider_crank(0.1, 0.35, 0.0, true).unwrap();
    match check_mobility(&m).unwrap_err() {
        Error::Singular { phi, joints, .. } => {
            // The drive value at the sketch is the slider's displacement r + l (rounding).
            assert!((phi - 0.45).abs() < 1e-15);
            assert!(joints.contains(&"A".to_owned()), "{joints:?}");
        }
        other => panic!("expected Singular, got {other:?}"),
    }
    // Driven by the crank, the same sketch is regular (a dead position of the output only).
    assert!(check_mobility(&slider_crank(0.1, 0.35, 0.0, false).unwrap()).is_ok());
}

#[test]
fn unlimited_subdivision_still_ends_with_an_error() {
    // With (practically) unlimited halvings the walk creeps up to the four-bar's limit
    // position (coupler and rocker collinear, ≈ 95.08°) until φ stops moving or the pose
    // there is singular; either way the move must end with an error, not loop forever.
    let m = four_bar(0.4, 0.3, 0.45, 0.6, 0.0, true).unwrap();
    let limit = ((0.16 + 0.36 - 0.5625) / 0.48f64).acos();
    let mut t = Solver::default()
        .with_max_subdivisions(usize::MAX)
        .track(&m)
        .unwrap();
    match t.move_to(2.0) {
        Err(Error::Unassemblable { phi, .. }) => assert_eq!(phi, 2.0),
        // The closed form locates the limit itself (to rounding: acos of a value near
        // −0.09, 1e-13).
        Err(Error::Blocked { limit: found, .. }) => assert!((found - limit).abs() < 1e-13),
        // The limit position is a toggle of the coupler–rocker loop (1e-6 rad: the
        // condition reaches the threshold ~1e-11 rad before it).
        Err(Error::Singular { phi, joints, .. }) => {
            assert!((phi - limit).abs() < 1e-6, "{phi}");
            assert_eq!(joints, ["A", "B", "B0"]);
        }
        other => panic!("expected an error, got {other:?}"),
    }
}
