//! Exact parameter sensitivities of the pose (`geometry::parametric`) against independent
//! references: closed forms written by hand in a generic scalar and differentiated with
//! num-dual (exact in f64 as well), hand derivatives for the rack and pinion, the gear and
//! the drive's sketch value, a hand-written Φ_q for the Jacobian, and Richardson-extrapolated
//! central differences of the solver for a model with every joint kind.

use mechdiff_core::geometry::{DataTangent, Drive, Mechanism, Parametric, Solver};
use mechdiff_core::num_dual::{Dual3, Dual64, DualNum};
use mechdiff_core::{Error, Scalar, atan2, hypot};

type D3 = Dual3<Dual64>;

/// A four-bar: crank O–A (a) about O = (0, 0), coupler A–B (b), rocker C–B (c) about the
/// ground pivot C = (cx, cy). Any scalar: the parameter's derivative rides along.
#[derive(Clone, Copy)]
struct FourBar<T> {
    a: T,
    b: T,
    c: T,
    cx: T,
    cy: T,
}

impl<T: Scalar> FourBar<T> {
    /// The crank pin A and the coupler–rocker pin B at absolute crank angle `phi`, on the
    /// branch with B to the left of A → C (by hand: the triangle A, B, C with sides b, c
    /// and |AC|, angle at A by the law of cosines).
    fn pins(&self, phi: T) -> ([T; 2], [T; 2]) {
        let a = [self.a * phi.cos(), self.a * phi.sin()];
        let e = [self.cx - a[0], self.cy - a[1]];
        let l = hypot(e[0], e[1]);
        let alpha = ((self.b * self.b + l * l - self.c * self.c) / (self.b * l * 2.0)).acos();
        let gamma = atan2(e[1], e[0]) + alpha;
        (
            a,
            [a[0] + self.b * gamma.cos(), a[1] + self.b * gamma.sin()],
        )
    }

    /// The rocker's absolute angle ψ (direction C → B).
    fn psi(&self, phi: T) -> T {
        let (_, b) = self.pins(phi);
        atan2(b[1] - self.cy, b[0] - self.cx)
    }
}

const PHI_S: f64 = 1.0;

/// The dimensions as f64, then with the parameter `which` (0..5: a, b, c, cx, cy) carrying
/// ε = 1 in the given scalar built by `lift`.
fn dims<T: Scalar>(which: usize, lift: impl Fn(f64, f64) -> T) -> FourBar<T> {
    let v = [1.0, 3.0, 2.5, 3.0, 0.2];
    let d = |i: usize| lift(v[i], if i == which { 1.0 } else { 0.0 });
    FourBar {
        a: d(0),
        b: d(1),
        c: d(2),
        cx: d(3),
        cy: d(4),
    }
}

/// The four-bar drawn at crank angle `PHI_S` (φ = the absolute crank angle), and the tangent
/// of its sketch when parameter `which` moves (O, A, B, C in that order).
fn four_bar(which: usize) -> (Mechanism, DataTangent) {
    let p = dims(which, Dual64::new);
    let (a, b) = p.pins(Dual64::from(PHI_S));
    let zero = Dual64::from(0.0);
    let points = [[zero, zero], a, b, [p.cx, p.cy]];
    let re = |x: [Dual64; 2]| [x[0].re, x[1].re];
    let m = Mechanism::builder()
        .point("O", re(points[0]))
        .point("A", re(points[1]))
        .point("B", re(points[2]))
        .point("C", re(points[3]))
        .ground(["O", "C"])
        .link("crank", ["O", "A"])
        .link("coupler", ["A", "B"])
        .link("rocker", ["C", "B"])
        .revolute("O", "ground", "crank", "O")
        .revolute("A", "crank", "coupler", "A")
        .revolute("B", "coupler", "rocker", "B")
        .revolute("C", "ground", "rocker", "C")
        .drive(Drive::angle("O").at_sketch(PHI_S))
        .build()
        .unwrap();
    let mut tangent = DataTangent::zero(&m);
    tangent.points = points.iter().map(|x| [x[0].eps, x[1].eps]).collect();
    (m, tangent)
}

/// Relative error of `x` against `reference`, for numbers of order 1 or above (an absolute
/// error below 1).
fn error(x: f64, reference: f64) -> f64 {
    (x - reference).abs() / reference.abs().max(1.0)
}

/// The four parts (value, ′, ″, ‴) of x's d/dp.
fn tangents(x: D3) -> [f64; 4] {
    [x.re.eps, x.v1.eps, x.v2.eps, x.v3.eps]
}

/// The four parts of x's value.
fn values(x: D3) -> [f64; 4] {
    [x.re.re, x.v1.re, x.v2.re, x.v3.re]
}

/// ∂ψ/∂p, ∂ψ′/∂p, ∂ψ″/∂p, ∂ψ‴/∂p of the four-bar (each parameter in turn, closed-form
/// loops and Newton forced) equal the hand closed form's, differentiated by num-dual.
///
/// Tolerance 1e-12 relative: both sides are exact derivatives evaluated in f64 (no
/// difference quotient); they differ only by rounding, amplified by the conditioning of
/// Φ_q (condition numbers ~10 here) and by the third derivative's size (up to ~30).
#[test]
fn four_bar_rocker_angle_derivatives_match_the_hand_closed_form() {
    let mut worst = 0.0f64;
    for which in 0..5 {
        let (m, tangent) = four_bar(which);
        let exact = Parametric::new(&m, &tangent).unwrap();
        let psi = exact.angle_output("rocker", "C", "B").unwrap();
        let pin = exact.point_output("rocker", "B").unwrap();
        let reference = dims(which, |v, d| D3::from_re(Dual64::new(v, d)));
        for closed_form in [true, false] {
            let mut t = Solver::default()
                .with_closed_form(closed_form)
                .track(&m)
                .unwrap();
            for step in 0..12 {
                let phi = PHI_S + 0.5 * step as f64;
                t.move_to(phi).unwrap();
                let pose = exact.pose(&t.kinematics::<3>().unwrap()).unwrap();
                let at = D3::new(Dual64::from(phi), Dual64::from(1.0), 0.0.into(), 0.0.into());
                let want = reference.psi(at);
                let got = psi.value(&pose);
                let (_, want_b) = reference.pins(at);
                let got_b = pin.position(&pose);
                let pairs = [(got, want), (got_b[0], want_b[0]), (got_b[1], want_b[1])];
                for (got, want) in pairs {
                    for k in 0..4 {
                        let e = error(tangents(got)[k], tangents(want)[k]);
                        worst = worst.max(e);
                        assert!(
                            e < 1e-12,
                            "parameter {which}, φ = {phi}, order {k}: {} vs {}",
                            tangents(got)[k],
                            tangents(want)[k]
                        );
                        // The values themselves are the solver's (1e-12: its tolerance).
                        assert!(error(values(got)[k], values(want)[k]) < 1e-12);
                    }
                }
            }
        }
    }
    eprintln!("four-bar: worst relative error of d/dp {worst:e}");
}

/// φ₀'s tangent: with the sketch fixed, moving the drive's sketch value p shifts the crank
/// angle: the absolute crank angle is φ_s + φ − p, so ∂ψ/∂p = −ψ′, ∂ψ′/∂p = −ψ″, … (the
/// closed form at φ_s + φ − p, p carrying ε). 1e-12 relative, as above.
#[test]
fn the_drive_sketch_value_enters_through_the_drive_row() {
    let (m, _) = four_bar(0);
    let mut tangent = DataTangent::zero(&m);
    tangent.drive_at_sketch = 1.0;
    let exact = Parametric::new(&m, &tangent).unwrap();
    let psi = exact.angle_output("rocker", "C", "B").unwrap();
    let reference = dims(9, |v, _| D3::from_re(Dual64::from(v)));
    let mut t = Solver::default().track(&m).unwrap();
    for phi in [0.3, 1.0, 2.2, 4.0] {
        t.move_to(phi).unwrap();
        let pose = exact.pose(&t.kinematics::<3>().unwrap()).unwrap();
        // Absolute crank angle φ_s + φ − p with p = φ_s: value φ, d/dp = −1.
        let crank = D3::new(
            Dual64::new(phi, -1.0),
            Dual64::from(1.0),
            0.0.into(),
            0.0.into(),
        );
        let want = reference.psi(crank);
        let got = psi.value(&pose);
        for k in 0..4 {
            assert!(
                error(tangents(got)[k], tangents(want)[k]) < 1e-12,
                "φ = {phi}, order {k}"
            );
        }
    }
}

/// A slider-crank with guide offset e: x_B = a cos φ + √(b² − (a sin φ − e)²) by hand.
#[derive(Clone, Copy)]
struct SliderCrank<T> {
    a: T,
    b: T,
    e: T,
}

impl<T: Scalar> SliderCrank<T> {
    fn x(&self, phi: T) -> T {
        let h = self.a * phi.sin() - self.e;
        self.a * phi.cos() + (self.b * self.b - h * h).sqrt()
    }
}

/// The slider's displacement and its derivatives: d/dp for p = a, b, e against the hand
/// closed form (the guide through (0, e) and (1, e), so the displacement is x_B). 1e-12
/// relative, as for the four-bar.
#[test]
fn slider_crank_displacement_derivatives_match_the_hand_closed_form() {
    let v = [0.1, 0.4, 0.03];
    for which in 0..3 {
        let p = |i: usize| Dual64::new(v[i], if i == which { 1.0 } else { 0.0 });
        let dims = SliderCrank {
            a: p(0),
            b: p(1),
            e: p(2),
        };
        let x_b = dims.x(Dual64::from(PHI_S));
        let a = [dims.a * PHI_S.cos(), dims.a * PHI_S.sin()];
        let zero = Dual64::from(0.0);
        let one = Dual64::from(1.0);
        let points = [
            [zero, zero],
            a,
            [x_b, dims.e],
            [zero, dims.e],
            [one, dims.e],
        ];
        let re = |i: usize| [points[i][0].re, points[i][1].re];
        let m = Mechanism::builder()
            .point("O", re(0))
            .point("A", re(1))
            .point("B", re(2))
            .point("G", re(3))
            .point("H", re(4))
            .ground(["O", "G", "H"])
            .link("crank", ["O", "A"])
            .link("rod", ["A", "B"])
            .link("slider", ["B"])
            .revolute("O", "ground", "crank", "O")
            .revolute("A", "crank", "rod", "A")
            .revolute("B", "rod", "slider", "B")
            .prismatic("guide", "ground", ["G", "H"], "slider", "B")
            .drive(Drive::angle("O").at_sketch(PHI_S))
            .build()
            .unwrap();
        let mut tangent = DataTangent::zero(&m);
        tangent.points = points.iter().map(|x| [x[0].eps, x[1].eps]).collect();
        let exact = Parametric::new(&m, &tangent).unwrap();
        let s = exact.displacement_output("guide").unwrap();
        let reference = SliderCrank {
            a: D3::from_re(dims.a),
            b: D3::from_re(dims.b),
            e: D3::from_re(dims.e),
        };
        let mut t = Solver::default().track(&m).unwrap();
        for step in 0..12 {
            let phi = PHI_S + 0.5 * step as f64;
            t.move_to(phi).unwrap();
            let pose = exact.pose(&t.kinematics::<3>().unwrap()).unwrap();
            let at = D3::new(Dual64::from(phi), one, zero, zero);
            let (got, want) = (s.value(&pose), reference.x(at));
            for k in 0..4 {
                assert!(
                    error(tangents(got)[k], tangents(want)[k]) < 1e-12,
                    "parameter {which}, φ = {phi}, order {k}: {} vs {}",
                    tangents(got)[k],
                    tangents(want)[k]
                );
            }
        }
    }
}

/// A slider-crank driven by the slider's displacement x (no `at_sketch`: φ₀ is implied by
/// the sketch, and moves with the crank length a). The crank angle by hand, from the law of
/// cosines: θ = acos((a² + x² − b²)/(2ax)). Moving a moves A, B and φ₀
/// ([`DataTangent::implied_drive_at_sketch`]); at fixed φ = x, ∂θ/∂a and its φ-derivatives
/// against the hand formula in `Dual3<Dual64>`: 1e-12 relative, as above.
#[test]
fn a_displacement_drive_with_an_implied_sketch_value_matches_the_hand_closed_form() {
    let (theta_s, b) = (1.0f64, 0.4);
    let a = Dual64::new(0.1, 1.0);
    let pin = [a * theta_s.cos(), a * theta_s.sin()];
    let x_s = pin[0] + (a * a * (-theta_s.sin() * theta_s.sin()) + b * b).sqrt();
    let re = |x: Dual64| x.re;
    let m = Mechanism::builder()
        .point("O", [0.0, 0.0])
        .point("A", [re(pin[0]), re(pin[1])])
        .point("B", [re(x_s), 0.0])
        .point("X", [1.0, 0.0])
        .ground(["O", "X"])
        .link("crank", ["O", "A"])
        .link("rod", ["A", "B"])
        .link("slider", ["B"])
        .revolute("O", "ground", "crank", "O")
        .revolute("A", "crank", "rod", "A")
        .revolute("B", "rod", "slider", "B")
        .prismatic("guide", "ground", ["O", "X"], "slider", "B")
        .drive(Drive::displacement("guide"))
        .build()
        .unwrap();
    let mut tangent = DataTangent::zero(&m);
    tangent.points[1] = [pin[0].eps, pin[1].eps];
    tangent.points[2] = [x_s.eps, 0.0];
    tangent.drive_at_sketch = tangent.implied_drive_at_sketch(&m).unwrap();
    // The implied φ₀ is x_B at the sketch: its d/dp is x_B's (1e-15: a few roundings).
    assert!((tangent.drive_at_sketch - x_s.eps).abs() < 1e-15);
    let exact = Parametric::new(&m, &tangent).unwrap();
    let theta = exact.angle_output("crank", "O", "A").unwrap();
    let mut t = Solver::default().track(&m).unwrap();
    for phi in [0.36, 0.40, 0.44, 0.48] {
        t.move_to(phi).unwrap();
        let pose = exact.pose(&t.kinematics::<3>().unwrap()).unwrap();
        let x = D3::new(Dual64::from(phi), Dual64::from(1.0), 0.0.into(), 0.0.into());
        let (a, b) = (D3::from_re(a), D3::from_re(Dual64::from(b)));
        let want = ((a * a + x * x - b * b) / (a * x * 2.0)).acos();
        let got = theta.value(&pose);
        for k in 0..4 {
            assert!(
                error(tangents(got)[k], tangents(want)[k]) < 1e-12,
                "φ = {phi}, order {k}: {} vs {}",
                tangents(got)[k],
                tangents(want)[k]
            );
        }
    }
}

/// A pinion driven about W, a rack on a ground guide (`s − s₀ = R θ`), and a gear about V
/// (`θ_V = ratio · θ_W`).
fn rack_and_gear() -> Mechanism {
    Mechanism::builder()
        .point("W", [0.0, 0.0])
        .point("V", [0.5, 0.0])
        .point("G", [-1.0, -0.2])
        .point("H", [1.0, -0.2])
        .point("R", [0.1, -0.2])
        .ground(["W", "V", "G", "H"])
        .link("pinion", ["W"])
        .link("wheel", ["V"])
        .link("rack", ["R"])
        .revolute("W", "ground", "pinion", "W")
        .revolute("V", "ground", "wheel", "V")
        .prismatic("guide", "ground", ["G", "H"], "rack", "R")
        .rack_pinion("mesh", "W", "guide", 0.2)
        .gear("gear", "W", "V", -1.5)
        .drive(Drive::angle("W"))
        .build()
        .unwrap()
}

/// The rack's displacement is s₀ + R φ: ∂s/∂R = φ, ∂s′/∂R = 1, ∂s″/∂R = ∂s‴/∂R = 0; the
/// wheel turns ratio · φ: ∂θ/∂ratio = φ, ∂θ′/∂ratio = 1. By hand; 1e-14 absolute (numbers
/// of order 1, a few roundings).
#[test]
fn rack_radius_and_gear_ratio_tangents_enter_their_rows() {
    let m = rack_and_gear();
    let s0 = 1.1; // R − G along the guide
    for (joint, output_is_rack) in [(3, true), (4, false)] {
        let mut tangent = DataTangent::zero(&m);
        tangent.joints[joint] = 1.0;
        let exact = Parametric::new(&m, &tangent).unwrap();
        let out = if output_is_rack {
            exact.displacement_output("guide").unwrap()
        } else {
            exact.rotation_output("wheel").unwrap()
        };
        let mut t = Solver::default().track(&m).unwrap();
        for phi in [-0.7, 0.4, 1.3] {
            t.move_to(phi).unwrap();
            let pose = exact.pose(&t.kinematics::<3>().unwrap()).unwrap();
            let got = out.value(&pose);
            let want = [phi, 1.0, 0.0, 0.0];
            for (k, (g, w)) in tangents(got).iter().zip(want).enumerate() {
                assert!(
                    (g - w).abs() < 1e-14,
                    "joint {joint}, order {k}: {g} vs {w}"
                );
            }
            let value = if output_is_rack {
                s0 + 0.2 * phi
            } else {
                -1.5 * phi
            };
            assert!((got.re.re - value).abs() < 1e-13);
        }
    }
}

/// Φ_q of the four-bar written by hand (coordinates x, y, θ of crank, coupler, rocker; rows
/// in joint order O, A, B, C, then the drive), evaluated in Dual64 with the closed form's
/// pose q(p) and the sketch's local vectors with their d/dp.
fn hand_jacobian(p: &FourBar<Dual64>, phi: f64) -> Vec<Vec<Dual64>> {
    let phi_s = Dual64::from(PHI_S);
    let (a_s, b_s) = p.pins(phi_s);
    let (a, b) = p.pins(Dual64::from(phi));
    let c = [p.cx, p.cy];
    let angle = |u: [Dual64; 2], v: [Dual64; 2]| atan2(v[1] - u[1], v[0] - u[0]);
    // Rotations since the sketch.
    let t1 = Dual64::from(phi - PHI_S);
    let t2 = angle(a, b) - angle(a_s, b_s);
    let t3 = angle(c, b) - angle(c, b_s);
    // ∂/∂θ of A(θ)v: (−sin θ v_x − cos θ v_y, cos θ v_x − sin θ v_y).
    let turn = |t: Dual64, v: [Dual64; 2]| {
        let (s, co) = t.sin_cos();
        [-s * v[0] - co * v[1], co * v[0] - s * v[1]]
    };
    let local_a = a_s; // A − O on the crank
    let coupler_b = [b_s[0] - a_s[0], b_s[1] - a_s[1]]; // B − A on the coupler
    let rocker_b = [b_s[0] - c[0], b_s[1] - c[1]]; // B − C on the rocker
    let z = Dual64::from(0.0);
    let o = Dual64::from(1.0);
    let mut j = vec![vec![z; 9]; 9];
    // O (ground first): O − r_crank.
    j[0][0] = -o;
    j[1][1] = -o;
    // A: r_crank + A(θ1)(A − O) − r_coupler.
    let d = turn(t1, local_a);
    for i in 0..2 {
        j[2 + i][i] = o;
        j[2 + i][2] = d[i];
        j[2 + i][3 + i] = -o;
    }
    // B: r_coupler + A(θ2)(B − A) − r_rocker − A(θ3)(B − C).
    let (d2, d3) = (turn(t2, coupler_b), turn(t3, rocker_b));
    for i in 0..2 {
        j[4 + i][3 + i] = o;
        j[4 + i][5] = d2[i];
        j[4 + i][6 + i] = -o;
        j[4 + i][8] = -d3[i];
    }
    // C (ground first): C − r_rocker.
    j[6][6] = -o;
    j[7][7] = -o;
    // Drive: θ1 − (φ − φ₀).
    j[8][2] = o;
    j
}

/// `Parametric::jacobian` (Φ_q with its total d/dp) equals the hand-written Φ_q evaluated
/// on the closed form's q(p): 1e-12 relative, exact on both sides up to rounding.
#[test]
fn jacobian_and_its_parameter_derivative_match_a_hand_derivative() {
    for which in [0, 2, 3] {
        let (m, tangent) = four_bar(which);
        let exact = Parametric::new(&m, &tangent).unwrap();
        let mut t = Solver::default().track(&m).unwrap();
        for phi in [0.4, 1.7, 3.5] {
            t.move_to(phi).unwrap();
            let pose = exact.pose(&t.kinematics::<1>().unwrap()).unwrap();
            let got = exact.jacobian(&pose);
            let want = hand_jacobian(&dims(which, Dual64::new), phi);
            for r in 0..9 {
                for c in 0..9 {
                    let (g, w) = (got[(r, c)], want[r][c]);
                    assert!(error(g.re, w.re) < 1e-12, "({r}, {c}) value");
                    assert!(
                        error(g.eps, w.eps) < 1e-12,
                        "parameter {which}, φ = {phi}, ({r}, {c}): {} vs {}",
                        g.eps,
                        w.eps
                    );
                }
            }
        }
    }
}

/// Wrong shapes are typed errors naming what does not fit.
#[test]
fn tangents_of_the_wrong_shape_are_errors() {
    let m = rack_and_gear();
    let mismatch = |t: &DataTangent| match Parametric::new(&m, t) {
        Err(Error::ParametricMismatch { what, problem }) => format!("{what}: {problem}"),
        other => panic!("expected a mismatch, got {other:?}"),
    };
    let mut t = DataTangent::zero(&m);
    t.points.pop();
    assert!(mismatch(&t).contains("points"));
    let mut t = DataTangent::zero(&m);
    t.joints.push(0.0);
    assert!(mismatch(&t).contains("joints"));
    let mut t = DataTangent::zero(&m);
    t.inertias.clear();
    assert!(mismatch(&t).contains("links"));
    // A revolute joint has no number to move.
    let mut t = DataTangent::zero(&m);
    t.joints[0] = 1.0;
    assert!(mismatch(&t).contains("joint `W`"));
    // An inertia tangent for a link without inertia.
    let mut t = DataTangent::zero(&m);
    t.inertias[1] = t.inertias[1].or(Some(mechdiff_core::geometry::Inertia {
        mass: 1.0,
        center: [0.0, 0.0],
        moment: 0.0,
    }));
    assert!(mismatch(&t).contains("inertia"));
    // Not finite.
    let mut t = DataTangent::zero(&m);
    t.points[2][1] = f64::NAN;
    assert!(matches!(
        Parametric::new(&m, &t),
        Err(Error::InvalidValue { .. })
    ));
}

/// A pose of another mechanism is refused.
#[test]
fn a_pose_of_another_mechanism_is_an_error() {
    let (m, tangent) = four_bar(0);
    let other = rack_and_gear();
    let exact = Parametric::new(&m, &tangent).unwrap();
    let t = Solver::default().track(&other).unwrap();
    assert!(matches!(
        exact.pose(&t.kinematics::<1>().unwrap()),
        Err(Error::ParametricMismatch { .. })
    ));
}

/// A model with every joint kind: a crank O–A whose pin A runs in the slot P → Q of a lever
/// pivoted at P (Q drawn at A), a slider S on the lever (a prismatic joint on a moving guide)
/// held by a rack on the lever's pivot, a wheel geared to the crank, and a link welded to the
/// slider. `ax` is A's x (A and Q move together, S stays at P + 1.5 (Q − P)).
fn every_joint(ax: f64) -> (Mechanism, DataTangent) {
    let a = [ax, 0.15];
    let p = [0.0, -0.5];
    let s = [p[0] + 1.5 * (a[0] - p[0]), p[1] + 1.5 * (a[1] - p[1])];
    let m = Mechanism::builder()
        .point("O", [0.0, 0.0])
        .point("A", a)
        .point("P", p)
        .point("Q", a)
        .point("S", s)
        .point("V", [0.4, 0.1])
        .point("E", [0.3, 0.4])
        .ground(["O", "P", "V"])
        .link("crank", ["O", "A"])
        .link("lever", ["P", "Q"])
        .link("slider", ["S"])
        .link("wheel", ["V"])
        .link("weld", ["E"])
        .revolute("O", "ground", "crank", "O")
        .revolute("P", "ground", "lever", "P")
        .pin_in_slot("slot", "lever", ["P", "Q"], "crank", "A")
        .prismatic("guide", "lever", ["P", "Q"], "slider", "S")
        .rack_pinion("rack", "P", "guide", 0.05)
        .revolute("V", "ground", "wheel", "V")
        .gear("gear", "O", "V", -1.5)
        .rigid("weld", "slider", "weld")
        .drive(Drive::angle("O"))
        .build()
        .unwrap();
    let mut tangent = DataTangent::zero(&m);
    tangent.points[1] = [1.0, 0.0];
    tangent.points[3] = [1.0, 0.0];
    tangent.points[4] = [1.5, 0.0];
    (m, tangent)
}

/// For every joint kind at once (pin in slot, prismatic on a moving guide, rack, gear,
/// weld), moving the crank pin: d/dp of every coordinate and its φ-derivatives against
/// central differences of the solver at p ± h and p ± h/2, Richardson-extrapolated
/// (truncation O(h⁴) ≈ 1e-12 × the fifth p-derivative with h = 1e-3, plus the rounding of
/// the solver's poses, ~1e-15 amplified by Φ_q's conditioning and divided by h: measured
/// 1e-11): 1e-9 relative. An independent route (no dual numbers in p), looser than the
/// exact comparisons above.
#[test]
fn every_joint_kind_agrees_with_central_differences_of_the_solver() {
    let ax = 0.1;
    let pose_at = |x: f64, phi: f64| -> Vec<[f64; 3]> {
        let (m, _) = every_joint(x);
        let mut t = Solver::default().track(&m).unwrap();
        t.move_to(phi).unwrap();
        let k = t.kinematics::<2>().unwrap();
        k.coordinates
            .iter()
            .map(|j| [j.value, j.derivatives[0], j.derivatives[1]])
            .collect()
    };
    let (m, tangent) = every_joint(ax);
    let exact = Parametric::new(&m, &tangent).unwrap();
    let mut t = Solver::default().track(&m).unwrap();
    let h = 1e-3;
    let mut worst = 0.0f64;
    for phi in [0.3, -0.4] {
        t.move_to(phi).unwrap();
        let pose = exact.pose(&t.kinematics::<2>().unwrap()).unwrap();
        let (p1, m1) = (pose_at(ax + h, phi), pose_at(ax - h, phi));
        let (p2, m2) = (pose_at(ax + h / 2.0, phi), pose_at(ax - h / 2.0, phi));
        for (i, x) in pose.iter().enumerate() {
            for k in 0..3 {
                let d1 = (p1[i][k] - m1[i][k]) / (2.0 * h);
                let d2 = (p2[i][k] - m2[i][k]) / h;
                let reference = (4.0 * d2 - d1) / 3.0;
                let got = tangents(*x)[k];
                worst = worst.max(error(got, reference));
                assert!(
                    error(got, reference) < 1e-9,
                    "φ = {phi}, coordinate {i}, order {k}: {got} vs {reference}"
                );
            }
        }
        // Every link moves with p somewhere (the check is not vacuous).
        assert!(pose.iter().filter(|x| x.re.eps.abs() > 1e-3).count() >= 5);
    }
    eprintln!("every joint: worst relative difference {worst:e}");
}

/// The value parts of the lifted pose are the solver's q, q′, q″ unchanged, and q‴ is zero
/// when only two orders are asked (the PoseTangent's documented layout).
#[test]
fn the_pose_carries_the_solvers_derivatives_up_to_the_order_asked() {
    let (m, tangent) = four_bar(1);
    let exact = Parametric::new(&m, &tangent).unwrap();
    let mut t = Solver::default().track(&m).unwrap();
    t.move_to(2.0).unwrap();
    let k = t.kinematics::<2>().unwrap();
    let pose = exact.pose(&k).unwrap();
    for (x, j) in pose.iter().zip(&k.coordinates) {
        assert_eq!([x.re.re, x.v1.re, x.v2.re], [j.value, j.d1(), j.d2()]);
        assert_eq!((x.v3.re, x.v3.eps), (0.0, 0.0));
    }
    // And q_p is nonzero somewhere (the parameter b moves the coupler and rocker).
    assert!(pose.iter().any(|x| x.re.eps.abs() > 1e-3));
}
