//! An answer checked by core's geometry solver: the linkage built as a [`Mechanism`] in its
//! pose at the first target and moved through every target by [`Solver`]'s proven moves
//! (every loop kept on its branch over each whole move, limit positions and change points
//! found, never jumped), its points compared with the synthesis's closed forms.

use super::linkage::Linkage;
use super::problem::Problem;
use crate::Error;
use crate::geometry::{Drive, Mechanism, Solver};

/// What core's geometry solver says of an answer.
#[derive(Debug, Clone, PartialEq)]
pub struct Certificate {
    /// The largest distance between a point as the geometry solver places it and as the
    /// synthesis's closed forms do, over every target (m).
    pub deviation: f64,
    /// The drive angle of each target, in the order moved through (rad).
    pub drive_angles: Vec<f64>,
}

impl Problem {
    /// The linkage with the variables `x` as a core [`Mechanism`], sketched in its pose at
    /// the first target's drive angle, driven by the crank's absolute angle (`Drive::angle`
    /// of joint `O2`, with that angle at the sketch). Points `O2`, `A`, `B`, `O4` (or the
    /// guide's `G0`, `G1`), `P`, and for the six-bar `E`, `O6`, `Q`; links `crank`,
    /// `coupler` (or `rod` and `slider`), `rocker`, `link5`, `link6`.
    pub fn mechanism(&self, x: &[f64]) -> Result<Mechanism, Error> {
        let phi = self.drive_angles(x)[0];
        let pose = self
            .linkage
            .pose(x, phi, &self.branch)
            .map_err(|e| Error::Unassemblable {
                phi,
                last_assembled: phi,
                joints: vec![format!("dyad {}", e.dyad)],
                residual: e.margin,
            })?;
        let [a, b, p] = [pose.points[0], pose.points[1], pose.points[2]];
        let mut m = Mechanism::builder()
            .point("O2", [x[0], x[1]])
            .point("A", a)
            .point("B", b)
            .point("P", p)
            .link("crank", ["O2", "A"])
            .revolute("O2", "ground", "crank", "O2")
            .drive(Drive::angle("O2").at_sketch(phi));
        if self.linkage == Linkage::SliderCrank {
            let (offset, guide) = (x[4], x[5]);
            let (u, n) = ([guide.cos(), guide.sin()], [-guide.sin(), guide.cos()]);
            let origin = [x[0] + n[0] * offset, x[1] + n[1] * offset];
            m = m
                .point("G0", [origin[0] - u[0], origin[1] - u[1]])
                .point("G1", [origin[0] + u[0], origin[1] + u[1]])
                .ground(["O2", "G0", "G1"])
                .link("rod", ["A", "B", "P"])
                .link("slider", ["B"])
                .revolute("A", "crank", "rod", "A")
                .revolute("B", "rod", "slider", "B")
                .prismatic("guide", "ground", ["G0", "G1"], "slider", "B");
        } else {
            m = m
                .point("O4", [x[2], x[3]])
                .ground(["O2", "O4"])
                .link("coupler", ["A", "B", "P"])
                .link("rocker", ["O4", "B"])
                .revolute("A", "crank", "coupler", "A")
                .revolute("B", "coupler", "rocker", "B")
                .revolute("O4", "ground", "rocker", "O4");
        }
        if self.linkage == Linkage::StephensonSix {
            m = m
                .point("E", pose.points[3])
                .point("O6", [x[9], x[10]])
                .point("Q", pose.points[4])
                .ground(["O6"])
                .link("link5", ["P", "E", "Q"])
                .link("link6", ["O6", "E"])
                .revolute("C", "coupler", "link5", "P")
                .revolute("E", "link5", "link6", "E")
                .revolute("O6", "ground", "link6", "O6");
        }
        m.build()
    }

    /// Moves the [`Problem::mechanism`] of `x` through every target with core's geometry
    /// solver and compares each point with the synthesis's closed forms: an error if it
    /// cannot move from one target to the next (a blocked range, a branch change), the
    /// largest deviation otherwise.
    pub fn certify(&self, x: &[f64]) -> Result<Certificate, Error> {
        let m = self.mechanism(x)?;
        let mut tracker = Solver::default().track(&m)?;
        let names = self.linkage.point_names();
        let carriers = |name: &str| match (name, self.linkage) {
            ("A", _) => "crank",
            ("B" | "P", Linkage::SliderCrank) => "rod",
            ("B" | "P", _) => "coupler",
            _ => "link5",
        };
        let outputs = names
            .iter()
            .map(|n| m.point_output(carriers(n), n))
            .collect::<Result<Vec<_>, _>>()?;
        let phis = self.drive_angles(x);
        let mut deviation = 0.0f64;
        for &phi in &phis {
            tracker.move_to(phi)?;
            let pose =
                self.linkage
                    .pose(x, phi, &self.branch)
                    .map_err(|e| Error::Unassemblable {
                        phi,
                        last_assembled: phi,
                        joints: vec![format!("dyad {}", e.dyad)],
                        residual: e.margin,
                    })?;
            for (output, expected) in outputs.iter().zip(&pose.points) {
                let [px, py] = tracker.position(output);
                deviation = deviation.max((px.value - expected[0]).hypot(py.value - expected[1]));
            }
        }
        Ok(Certificate {
            deviation,
            drive_angles: phis,
        })
    }
}
