//! Exact derivatives of the `[[dynamics]]` columns with respect to one parameter p: the
//! same row code as the table ([`super::run::row`]) evaluated with `Dual64` numbers from
//! [`mechdiff_core::dynamics::tangent`].

use mechdiff_core::dynamics::tangent::{
    EffectsTangent, ModelTangent, NotCarried, SolutionTangent, TangentError, carried,
};
use mechdiff_core::geometry::{Parametric, Solver};
use mechdiff_core::num_dual::Dual64;

use crate::error::{Error, Result};
use crate::scene::error_context::ErrorContext;

use super::format::DynamicQuantity;
use super::model::SceneDynamics;
use super::run::{SolutionValues, StepValues, drive_state, output_columns, push_output_row};

/// The exact derivatives d/dp of the dynamic columns of a run, or why a column has none.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicsTangent {
    /// Per column (the order of the table's dynamic columns): `None` when its derivative is
    /// exact, else why the exact route does not reach it (the caller then uses another
    /// method for that column and says so).
    pub not_carried: Vec<Option<String>>,
    /// One row per drive position: d/dp of each column, in SI units like
    /// [`super::DynamicsReport::rows`]; `None` in a column that is not carried.
    pub rows: Vec<Vec<Option<f64>>>,
}

/// Does output `quantity` read the equilibrium (reactions, drive torque, power balance)?
fn needs_equilibrium(quantity: DynamicQuantity) -> bool {
    matches!(
        quantity,
        DynamicQuantity::Reactions | DynamicQuantity::DriveTorque | DynamicQuantity::PowerBalance
    )
}

/// The exact derivative with respect to one parameter p of every `[[dynamics]]` column of
/// a scene (its words `cx`, its `solver`) at each drive position of `positions` (the run's,
/// in order), in the order of the table's dynamic columns and in SI units (as
/// [`super::DynamicsReport::rows`]).
///
/// Inputs: the scene's dynamics `d`; `parametric`, the built mechanism with the d/dp of its
/// data (`DataTangent`: sketch points, joints' numbers, the drive's sketch value, inertias);
/// `effects`, the d/dp of gravity, loads, motor, ω and α; `speed`, the drive speed the run
/// used. At each position the pose is tracked as the run tracks it and lifted with
/// `Parametric::pose` and `Parametric::jacobian`.
///
/// A column the exact route does not reach is `None` in every row, with the reason in
/// [`DynamicsTangent::not_carried`]: all columns of a cam-driven scene; the drive torque,
/// reactions and power balance when the plan has friction, mesh efficiencies or tooth
/// forces in the bearings of meshes on a common link. Errors: a singular position or
/// equilibrium (as the run's), a non-finite derivative (naming the column and the position),
/// a tangent that does not match the mechanism.
pub fn column_derivatives(
    cx: &ErrorContext<'_>,
    solver: &Solver,
    d: &SceneDynamics,
    parametric: &Parametric<'_>,
    effects: &EffectsTangent,
    positions: &[f64],
    speed: Option<f64>,
) -> Result<DynamicsTangent> {
    let mechanism = parametric.mechanism();
    let plan = d.plan(mechanism);
    let widths: Vec<usize> = (d.outputs.iter())
        .map(|o| output_columns(cx, d, mechanism, &plan, o).len())
        .collect();
    let all_not_carried = |reason: String| DynamicsTangent {
        not_carried: vec![Some(reason); widths.iter().sum()],
        rows: vec![vec![None; widths.iter().sum()]; positions.len()],
    };
    if cx.drive.cam.is_some() {
        return Ok(all_not_carried(
            "a cam drive (the exact route does not follow the cam's follower)".to_owned(),
        ));
    }
    let model = d.data.compile(mechanism).map_err(|source| Error::Model {
        file: cx.file.to_owned(),
        source,
    })?;
    let drive = drive_state(cx.drive, &plan, speed)?;
    let internal = |e: TangentError| Error::Invalid {
        location: cx.drive.location.clone(),
        message: format!("the exact derivative of the dynamics: {e}"),
    };
    // The equilibrium's columns need every effect of the plan carried; the others (shaking
    // and inertial forces, energy) need inertia only, always carried.
    let equilibrium: Option<NotCarried> = carried(&model, &plan.effects).err();
    let tangent = ModelTangent::new(
        &model,
        &plan.effects,
        parametric.tangent(),
        effects,
        drive.omega,
        drive.alpha,
    )
    .map_err(internal)?;
    let carried_output = |q: DynamicQuantity| !(needs_equilibrium(q) && equilibrium.is_some());
    let not_carried: Vec<Option<String>> = (d.outputs.iter().zip(&widths))
        .flat_map(|(o, &w)| {
            let reason = (!carried_output(o.quantity)).then(|| {
                format!(
                    "the exact route does not carry {}",
                    equilibrium.as_ref().expect("not carried")
                )
            });
            vec![reason; w]
        })
        .collect();
    let needs_solution = d
        .outputs
        .iter()
        .any(|o| needs_equilibrium(o.quantity) && carried_output(o.quantity));
    let omega = Dual64::new(drive.omega, effects.omega);
    let mut rows = Vec::with_capacity(positions.len());
    let solver_error = |e| cx.solver_error(e);
    let mut tracker = solver.track(mechanism).map_err(solver_error)?;
    for &phi in positions {
        tracker.move_to(phi).map_err(solver_error)?;
        let k = tracker.kinematics::<2>().map_err(solver_error)?;
        let pose = parametric.pose(&k).map_err(solver_error)?;
        let jacobian = parametric.jacobian(&pose);
        let solution: Option<SolutionTangent> = if plan.kinetostatics && needs_solution {
            Some(tangent.solve(phi, &pose, &jacobian).map_err(|e| match e {
                TangentError::Model(source) => cx.solver_error(source),
                other => internal(other),
            })?)
        } else {
            None
        };
        let energy = if plan.energy {
            Some(tangent.energy(&pose).map_err(internal)?)
        } else {
            None
        };
        let shaking = if plan.shaking {
            Some(tangent.shaking_force(phi, &pose).map_err(internal)?)
        } else {
            None
        };
        let step = StepValues {
            solution: solution.as_ref().map(|s| SolutionValues {
                drive_torque: s.drive_torque,
                reactions: &s.reactions,
                motor_torque: s.motor.map(|m| m.torque),
                balance: s.balance,
            }),
            energy,
            shaking: shaking.as_ref(),
        };
        let mut row = Vec::with_capacity(not_carried.len());
        let mut values = Vec::new();
        for (o, &w) in d.outputs.iter().zip(&widths) {
            if carried_output(o.quantity) {
                values.clear();
                push_output_row(cx.joints, d, mechanism, o, &step, omega, None, &mut values);
                row.extend(values.iter().map(|v| Some(v.eps)));
            } else {
                row.extend(std::iter::repeat_n(None, w));
            }
        }
        if let Some(i) = row.iter().position(|v| v.is_some_and(|x| !x.is_finite())) {
            let c = (d.outputs.iter())
                .flat_map(|o| output_columns(cx, d, mechanism, &plan, o))
                .nth(i)
                .expect("a column per value");
            return Err(Error::NotFinite {
                file: cx.file.to_owned(),
                quantity: format!("the derivative of {} [{}]", c.name, c.unit),
                value: row[i].expect("a value").to_string(),
                position: cx.drive_text(phi),
            });
        }
        rows.push(row);
    }
    Ok(DynamicsTangent { not_carried, rows })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;
    use crate::scene::parameters::Setting;
    use mechdiff_core::geometry::{DataTangent, Inertia};

    /// An offset slider-crank with the rod's mass `m2` (its moment `m2·l²/12`), every
    /// dynamic output, gravity and a load on the slider.
    const SCENE: &str = r#"
title = "slider-crank with every dynamic output"
[parameters]
m2 = 2.0
ya = 0.1
[points]
O = [0, 0]
A = [0, "ya"]
B = [0.384, -0.012]
G0 = [0, -0.012]
G1 = [1, -0.012]
[links]
ground = ["O", "G0", "G1"]
crank = ["O", "A"]
rod = ["A", "B"]
slider = ["B"]
[joints]
O = { type = "revolute", at = "O", links = ["ground", "crank"] }
A = { type = "revolute", at = "A", links = ["crank", "rod"] }
B = { type = "revolute", at = "B", links = ["rod", "slider"] }
guide = { type = "prismatic", line = ["G0", "G1"], point = "B", links = ["ground", "slider"] }
[drive]
joint = "O"
line = ["O", "A"]
speed = 30
acceleration = 4
[sweep]
from = 0
to = 6
step = 1.5
[masses]
crank = { mass = 0.8, center = [0.0, 0.04], inertia = 0.002 }
rod = { mass = "m2", center = [0.2, 0.03], inertia = "m2*0.16/12" }
slider = { mass = 1.5, center = "B" }
[gravity]
g = 9.81
[[load]]
link = "slider"
point = "B"
force = [-150, 0]
[[dynamics]]
output = "drive_torque"
[[dynamics]]
output = "reactions"
[[dynamics]]
output = "shaking_force"
[[dynamics]]
output = "inertial_forces"
[[dynamics]]
output = "kinetic_energy"
[[dynamics]]
output = "reduced_inertia"
[[dynamics]]
output = "power_balance"
"#;

    fn scene_at(text: &str, name: &str, value: f64) -> Scene {
        let set: Setting = format!("{name}={value:.17e}").parse().unwrap();
        crate::scene::parse_with("t.toml", text, &[set]).unwrap()
    }

    fn scene(text: &str, m2: f64) -> Scene {
        scene_at(text, "m2", m2)
    }

    /// The derivative rows with respect to m2 (mass 1, moment l²/12 per unit; no point moves).
    fn exact(text: &str) -> (DynamicsTangent, Vec<f64>) {
        exact_with(text, |m, data| {
            for (k, link) in m.links().iter().enumerate() {
                if link.inertia.is_some() {
                    data.inertias[k] = Some(Inertia {
                        mass: f64::from(u8::from(link.name == "rod")),
                        center: [0.0; 2],
                        moment: if link.name == "rod" { 0.16 / 12.0 } else { 0.0 },
                    });
                }
            }
        })
    }

    /// The derivative rows of the scene (at its parameters' values) for the data tangent
    /// `tangent` fills in.
    fn exact_with(
        text: &str,
        tangent: impl FnOnce(&mechdiff_core::geometry::Mechanism, &mut DataTangent),
    ) -> (DynamicsTangent, Vec<f64>) {
        let s = scene(text, 2.0);
        let m = crate::scene::build::mechanism(&s).unwrap();
        let report = crate::scene::run(&s).unwrap();
        let positions = report.column("phi").unwrap();
        let d = s.dynamics.as_ref().unwrap();
        let mut data = DataTangent::zero(&m);
        tangent(&m, &mut data);
        let parametric = Parametric::new(&m, &data).unwrap();
        let t = column_derivatives(
            &s.error_context(),
            &s.solver,
            d,
            &parametric,
            &EffectsTangent::zero(&d.data),
            &positions,
            s.drive.speed,
        )
        .unwrap();
        (t, positions)
    }

    /// Every dynamic column is affine in a link's mass and moment at a fixed pose, so central
    /// differences of the scene's own f64 run (at m2 ± 0.01) have no truncation error, only
    /// rounding, ≈ ε·|column|/h ≈ 1e-12 of the column's scale: tolerance 1e-9 of it.
    #[test]
    fn every_dynamic_column_derivative_matches_differences_of_the_run() {
        let (t, positions) = exact(SCENE);
        let h = 0.01;
        let rows = |m2: f64| {
            crate::scene::run(&scene(SCENE, m2))
                .unwrap()
                .dynamics
                .unwrap()
        };
        let (up, down) = (rows(2.0 + h), rows(2.0 - h));
        assert!(
            t.not_carried.iter().all(Option::is_none),
            "{:?}",
            t.not_carried
        );
        assert_eq!(t.rows.len(), positions.len());
        let width = up.columns.len();
        assert_eq!(t.not_carried.len(), width);
        for c in 0..width {
            let central: Vec<f64> = (up.rows.iter().zip(&down.rows))
                .map(|(a, b)| (a[c] - b[c]) / (2.0 * h))
                .collect();
            let scale = (up.rows.iter().chain(&down.rows)).fold(1.0f64, |a, r| a.max(r[c].abs()));
            for (row, want) in central.iter().enumerate() {
                let got = t.rows[row][c].unwrap();
                assert!(
                    (got - want).abs() <= 1e-9 * scale,
                    "d({})/d(m2) at row {row}: {got} vs differences {want}",
                    up.columns[c].name
                );
            }
        }
        // Not a vacuous agreement: the drive torque does depend on m2.
        assert!(t.rows.iter().any(|r| r[0].unwrap().abs() > 1e-3));
    }

    /// p = the crank pin's sketch height `ya` (the crank's and the rod's lengths; the drive
    /// line O→A keeps its direction): every dynamic column against central differences of
    /// the scene's run at ya ± h. Truncation O(h²) and rounding O(ε/h): at h = 1e-5 (1e-4
    /// of ya) about 1e-7 of the column's scale; the error must shrink ≥ 20× from h = 1e-4,
    /// so the agreement is the derivative's: tolerance 1e-6 of the scale.
    #[test]
    fn a_point_parameter_gives_every_dynamic_column_derivative() {
        let (t, _) = exact_with(SCENE, |m, data| {
            data.points[m.point_index("A").unwrap()] = [0.0, 1.0];
            // The rod's mass, centre and moment do not depend on ya (its centre is given as
            // sketch coordinates); the other links' neither.
            for (k, link) in m.links().iter().enumerate() {
                if link.inertia.is_some() {
                    data.inertias[k] = Some(Inertia {
                        mass: 0.0,
                        center: [0.0; 2],
                        moment: 0.0,
                    });
                }
            }
        });
        assert!(t.not_carried.iter().all(Option::is_none));
        let rows = |ya: f64| {
            crate::scene::run(&scene_at(SCENE, "ya", ya))
                .unwrap()
                .dynamics
                .unwrap()
        };
        let central = |h: f64| {
            let (up, down) = (rows(0.1 + h), rows(0.1 - h));
            let d: Vec<Vec<f64>> = (up.rows.iter().zip(&down.rows))
                .map(|(a, b)| {
                    (a.iter().zip(b))
                        .map(|(x, y)| (x - y) / (2.0 * h))
                        .collect()
                })
                .collect();
            (d, up)
        };
        let ((coarse, _), (fine, up)) = (central(1e-4), central(1e-5));
        for c in 0..up.columns.len() {
            let scale = (t.rows.iter()).fold(1.0f64, |a, r| a.max(r[c].unwrap().abs()));
            let error = |d: &[Vec<f64>]| {
                (t.rows.iter().zip(d))
                    .map(|(r, x)| (r[c].unwrap() - x[c]).abs())
                    .fold(0.0, f64::max)
            };
            let (e1, e2) = (error(&coarse), error(&fine));
            let name = &up.columns[c].name;
            assert!(
                e2 <= 1e-6 * scale,
                "d({name})/d(ya): {e2:e} of scale {scale}"
            );
            assert!(
                e2 <= e1 / 20.0 || e1 <= 1e-9 * scale,
                "d({name})/d(ya): no O(h²) convergence ({e1:e} → {e2:e})"
            );
        }
    }

    /// With friction in the plan, the equilibrium's columns (drive torque, reactions, power
    /// balance) say why they are not carried; the shaking force and energies stay exact.
    #[test]
    fn friction_leaves_only_the_equilibrium_columns_uncarried() {
        let text = format!("{SCENE}\n[friction]\nguide = {{ coefficient = 0.1 }}\n");
        let (t, _) = exact(&text);
        let s = scene(&text, 2.0);
        let m = crate::scene::build::mechanism(&s).unwrap();
        let d = s.dynamics.as_ref().unwrap();
        let plan = d.plan(&m);
        let mut k = 0;
        for o in &d.outputs {
            for _ in output_columns(&s.error_context(), d, &m, &plan, o) {
                let reason = &t.not_carried[k];
                if needs_equilibrium(o.quantity) {
                    let reason = reason.as_deref().unwrap();
                    assert!(reason.contains("friction (joint `guide`)"), "{reason}");
                    assert!(t.rows.iter().all(|r| r[k].is_none()));
                } else {
                    assert!(reason.is_none(), "{:?}", o.quantity);
                    assert!(t.rows.iter().all(|r| r[k].is_some()));
                }
                k += 1;
            }
        }
        assert_eq!(k, t.not_carried.len());
    }
}
