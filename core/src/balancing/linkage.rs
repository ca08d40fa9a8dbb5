//! Counterweights for linkages, from the shaking force.
//!
//! A counterweight on a link that turns about a fixed pivot `O` is a point mass `m` at
//! `O + A(θ)·c`, with `θ` the link's rotation since the sketch. Its inertial force is
//! `−m·d²/dt²(A(θ)c) = (ω² A(θ) − α J A(θ))·b` with `b = m c` its **mass-radius vector**
//! (kg·m, at the sketch) and `J` the quarter turn — linear in `b`. The shaking force of the
//! balanced linkage at drive position `φⱼ` is therefore
//!
//! ```text
//! F(φⱼ) = F₀(φⱼ) + Σₖ Mₖ(φⱼ) bₖ,   Mₖ = ω²ₖ A(θₖ) − αₖ J A(θₖ)
//! ```
//!
//! and the counterweights that minimise `Σⱼ |F(φⱼ)|²` over the sweep solve a linear
//! least-squares problem (by SVD). Where full force balance is possible — the total centre of
//! mass made stationary, as for a four-bar with counterweights on crank and rocker
//! (Berkof–Lowen) — the minimum is zero and the least-squares solution is that balance; the
//! result says which case it is ([`LinkageBalance::full_force_balance`]). Full force balance
//! raises the shaking moment and the drive torque's swing, so both are reported before and
//! after, computed by the [`crate::dynamics`] code on the mechanism with the counterweights
//! added to the links' mass properties.

use nalgebra::{DMatrix, DVector};

use crate::dynamics::run::{Step, check, step_from};
use crate::dynamics::state::link_states;
use crate::dynamics::{CompiledModel, Dynamics, Plan, Request, Trace};
use crate::geometry::{Inertia, JointKind, Mechanism, Solver, Tracker};
use crate::sweep::{Consumer, Sweep};
use crate::{DriveState, Error, Jet};

/// A counterweight to size: on `link`, at `radius` from its fixed pivot `line[0]`, its angle
/// measured from the link's line `line[0] → line[1]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Counterweight {
    /// The link (it must turn about a fixed pivot).
    pub link: String,
    /// The pivot (a revolute joint between the link and the ground) and a second point of
    /// the link: the line angles are measured from.
    pub line: [String; 2],
    /// Distance of the counterweight's centre from the pivot (m, > 0).
    pub radius: f64,
}

/// A sized counterweight.
#[derive(Debug, Clone, PartialEq)]
pub struct PlacedCounterweight {
    /// The request.
    pub request: Counterweight,
    /// Mass-radius vector at the sketch pose, global axes, from the pivot (kg·m).
    pub vector: [f64; 2],
    /// Its magnitude `m r` (kg·m).
    pub mass_radius: f64,
    /// Its angle from the link's line, counter-clockwise (rad, in (−π, π]).
    pub angle: f64,
    /// The mass at the requested radius (kg).
    pub mass: f64,
    /// Its centre at the sketch pose (m).
    pub center: [f64; 2],
}

/// Shaking force, shaking moment and drive torque over the sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkageSweep {
    /// Drive positions.
    pub phi: Vec<f64>,
    /// Shaking force `Σ −m a_G` (N).
    pub force: Vec<[f64; 2]>,
    /// Shaking moment about the origin (N·m).
    pub moment: Vec<f64>,
    /// Drive torque (N·m) or force (N).
    pub drive_torque: Vec<f64>,
}

impl LinkageSweep {
    /// Largest `|ΣF|` over the sweep (N).
    pub fn max_force(&self) -> f64 {
        self.force
            .iter()
            .map(|f| f[0].hypot(f[1]))
            .fold(0.0, f64::max)
    }

    /// Largest `|M|` of the shaking moment (N·m).
    pub fn max_moment(&self) -> f64 {
        self.moment.iter().map(|m| m.abs()).fold(0.0, f64::max)
    }

    /// Largest `|M_drive|` (N·m or N).
    pub fn max_drive_torque(&self) -> f64 {
        self.drive_torque
            .iter()
            .map(|m| m.abs())
            .fold(0.0, f64::max)
    }

    /// Root mean square of `|ΣF|` over the sweep (N).
    pub fn rms_force(&self) -> f64 {
        let n = self.force.len().max(1) as f64;
        (self
            .force
            .iter()
            .map(|f| f[0] * f[0] + f[1] * f[1])
            .sum::<f64>()
            / n)
            .sqrt()
    }
}

/// The counterweights and the linkage's shaking before and after.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkageBalance {
    /// The counterweights, in the order asked.
    pub counterweights: Vec<PlacedCounterweight>,
    /// Without counterweights.
    pub before: LinkageSweep,
    /// With them.
    pub after: LinkageSweep,
    /// The mechanism with the counterweights added to the links' mass properties.
    pub balanced: Mechanism,
}

impl LinkageBalance {
    /// Relative tolerance below which the shaking force counts as cancelled: the largest
    /// `|ΣF|` after is at most this fraction of the largest before.
    pub const FULL_BALANCE: f64 = 1e-9;

    /// Whether the counterweights cancel the shaking force at every position of the sweep
    /// (to [`Self::FULL_BALANCE`] of its largest value before): full force balance.
    pub fn full_force_balance(&self) -> bool {
        self.after.max_force() <= Self::FULL_BALANCE * self.before.max_force()
    }
}

/// The checks of [`balance_linkage`] that need no solved position, in its order: every
/// moving link has mass data, no link carries two counterweights, and each counterweight's
/// link is pivoted to the ground at its line's first point with a positive radius. A caller
/// that validates before running (`mechdiff check`) gets the same errors.
///
/// # Errors
/// As [`balance_linkage`] gives them before solving.
pub fn check_balance_request(
    mechanism: &Mechanism,
    counterweights: &[Counterweight],
) -> Result<(), Error> {
    check_request(mechanism, counterweights).map(drop)
}

fn check_request(
    mechanism: &Mechanism,
    counterweights: &[Counterweight],
) -> Result<Vec<Site>, Error> {
    let massless: Vec<&str> = (mechanism.links.iter().skip(1))
        .filter(|l| l.inertia.is_none())
        .map(|l| l.name.as_str())
        .collect();
    if !massless.is_empty() {
        return Err(Error::MissingData {
            what: "balancing a linkage".to_owned(),
            missing: format!(
                "mass data for every moving link; link(s) {} have none (give `mass = 0` for a \
                 massless link)",
                massless.join(", ")
            ),
        });
    }
    counterweights
        .iter()
        .enumerate()
        .map(|(i, c)| {
            if counterweights[..i].iter().any(|d| d.link == c.link) {
                return Err(Error::DuplicateName {
                    what: "counterweight link",
                    name: c.link.clone(),
                });
            }
            site(mechanism, c)
        })
        .collect::<Result<Vec<_>, _>>()
}

/// Sizes `counterweights` for `mechanism` (with the effect data `dynamics`) so that the
/// shaking force over the drive positions `phis` at drive state `drive` is cancelled, or
/// smallest in the least-squares sense.
///
/// Errors: a moving link without mass data ([`Error::MissingData`]: give `mass = 0` for a
/// massless link), a counterweight on a link not pivoted to the ground at `line[0]`
/// ([`Error::NotPivoted`]), a radius that is not positive or coincident line points
/// ([`Error::NonPositiveLength`]), two counterweights on one link
/// ([`Error::DuplicateName`]), and an empty sweep or one that does not determine the
/// counterweights (a link that never turns, a zero speed: [`Error::MissingData`]).
pub fn balance_linkage(
    mechanism: &Mechanism,
    dynamics: &Dynamics,
    counterweights: &[Counterweight],
    phis: &[f64],
    drive: DriveState,
    solver: &Solver,
) -> Result<LinkageBalance, Error> {
    let mut balancing = LinkageBalancing::new(mechanism, dynamics, counterweights, drive)?;
    if phis.is_empty() {
        return Err(no_position());
    }
    Sweep::new(mechanism, solver)?
        .with(&mut balancing)
        .run(phis.iter().copied(), &mut ())?;
    balancing.finish()
}

fn no_position() -> Error {
    Error::MissingData {
        what: "balancing a linkage".to_owned(),
        missing: "at least one drive position (sweep one whole cycle)".to_owned(),
    }
}

/// Counterweights sized from a sweep solved by the caller, one position at a time: at each
/// position [`LinkageBalancing::add`] reads the pose the caller's tracker stands at (nothing
/// is solved here), then [`LinkageBalancing::finish`] sizes them and evaluates the balanced
/// linkage at the same poses — the counterweights change the masses, not the motion. The
/// poses are kept until then (the coordinates with two derivatives per position): a sweep
/// that streams its rows holds these, and nothing else, until the counterweights are known.
/// [`balance_linkage`] is this fed by a tracker of its own.
#[derive(Debug, Clone)]
pub struct LinkageBalancing<'m> {
    mechanism: &'m Mechanism,
    dynamics: Dynamics,
    counterweights: Vec<Counterweight>,
    sites: Vec<Site>,
    drive: DriveState,
    plan: Plan,
    model: CompiledModel<'m>,
    before: LinkageSweep,
    /// Per position, the least-squares matrix's two rows (`2 k` values each).
    rows: Vec<f64>,
    /// Per position, the pose's coordinates (`coordinates` values each).
    poses: Vec<Jet<2>>,
    coordinates: usize,
    trace: Trace,
}

impl<'m> LinkageBalancing<'m> {
    /// Starts sizing `counterweights` for `mechanism` with the effect data `dynamics` at
    /// drive state `drive`.
    ///
    /// # Errors
    /// The request's errors ([`check_balance_request`]) and the model's.
    pub fn new(
        mechanism: &'m Mechanism,
        dynamics: &Dynamics,
        counterweights: &[Counterweight],
        drive: DriveState,
    ) -> Result<Self, Error> {
        let sites = check_request(mechanism, counterweights)?;
        let (model, plan) = model(mechanism, dynamics)?;
        Ok(Self {
            mechanism,
            dynamics: dynamics.clone(),
            counterweights: counterweights.to_vec(),
            sites,
            drive,
            plan,
            model,
            before: LinkageSweep {
                phi: Vec::new(),
                force: Vec::new(),
                moment: Vec::new(),
                drive_torque: Vec::new(),
            },
            rows: Vec::new(),
            poses: Vec::new(),
            coordinates: 0,
            trace: Trace::default(),
        })
    }

    /// Reads the pose `tracker` stands at, drive position `phi` (the caller moved it there).
    ///
    /// # Errors
    /// The lift's or the equilibrium's error at `phi`, or a value that overflowed.
    pub fn add(&mut self, tracker: &Tracker<'_>, phi: f64) -> Result<(), Error> {
        let kin = tracker.kinematics::<2>()?;
        let step = step_from(
            &self.plan,
            &self.model,
            phi,
            self.drive,
            &kin.coordinates,
            &mut self.trace,
        )?;
        push(&mut self.before, &step);
        let states = link_states(&kin.coordinates, &self.drive);
        let k = self.sites.len();
        let at = self.rows.len();
        self.rows.resize(at + 4 * k, 0.0);
        let (x, y) = self.rows[at..].split_at_mut(2 * k);
        for (i, s) in self.sites.iter().enumerate() {
            let st = states[s.link - 1];
            let (sn, cs) = st.theta.sin_cos();
            let (w2, al) = (st.omega * st.omega, st.alpha);
            x[2 * i] = w2 * cs + al * sn;
            x[2 * i + 1] = -w2 * sn + al * cs;
            y[2 * i] = w2 * sn - al * cs;
            y[2 * i + 1] = w2 * cs + al * sn;
        }
        self.coordinates = kin.coordinates.len();
        self.poses.extend_from_slice(&kin.coordinates);
        Ok(())
    }

    /// Sizes the counterweights over the positions added and evaluates the balanced linkage
    /// at them.
    ///
    /// # Errors
    /// No position added, or a sweep that does not determine the counterweights (see
    /// [`balance_linkage`]); an overflow.
    pub fn finish(self) -> Result<LinkageBalance, Error> {
        let phis = &self.before.phi;
        if phis.is_empty() {
            return Err(no_position());
        }
        // The least-squares matrix: two rows per drive position, two columns per counterweight.
        let (n, k) = (phis.len(), self.sites.len());
        let a = DMatrix::<f64>::from_row_slice(2 * n, 2 * k, &self.rows);
        let mut rhs = DVector::<f64>::zeros(2 * n);
        for (j, f) in self.before.force.iter().enumerate() {
            rhs[2 * j] = -f[0];
            rhs[2 * j + 1] = -f[1];
        }
        let x = if k == 0 {
            DVector::zeros(0)
        } else {
            let svd = a.svd(true, true);
            let largest = svd.singular_values.max();
            let smallest = svd.singular_values.min();
            if !(largest > 0.0 && smallest > 1e-10 * largest) {
                return Err(Error::MissingData {
                    what: "sizing counterweights".to_owned(),
                    missing: "a sweep in which every counterweight's link turns at a non-zero \
                              speed (the shaking force does not determine them: sweep a whole \
                              revolution with a drive speed)"
                        .to_owned(),
                });
            }
            svd.solve(&rhs, 0.0).map_err(|_| Error::NonFinite {
                phi: phis[0],
                quantity: "counterweight least squares",
            })?
        };
        let mut balanced = self.mechanism.clone();
        let mut placed = Vec::with_capacity(k);
        for (i, (s, c)) in self.sites.iter().zip(&self.counterweights).enumerate() {
            let vector = [x[2 * i], x[2 * i + 1]];
            let mass_radius = vector[0].hypot(vector[1]);
            if !mass_radius.is_finite() {
                return Err(Error::NonFinite {
                    phi: phis[0],
                    quantity: "counterweight mass-radius",
                });
            }
            let mass = mass_radius / c.radius;
            let (center, angle) = if mass_radius > 0.0 {
                let u = [vector[0] / mass_radius, vector[1] / mass_radius];
                let angle = wrap(vector[1].atan2(vector[0]) - s.line_angle);
                (
                    [s.pivot[0] + c.radius * u[0], s.pivot[1] + c.radius * u[1]],
                    angle,
                )
            } else {
                (s.pivot, 0.0)
            };
            let link = &mut balanced.links[s.link];
            link.inertia = Some(combine(link.inertia.expect("checked above"), mass, center));
            placed.push(PlacedCounterweight {
                request: c.clone(),
                vector,
                mass_radius,
                angle,
                mass,
                center,
            });
        }
        let after = {
            let (model, plan) = model(&balanced, &self.dynamics)?;
            let mut after = LinkageSweep {
                phi: Vec::with_capacity(n),
                force: Vec::with_capacity(n),
                moment: Vec::with_capacity(n),
                drive_torque: Vec::with_capacity(n),
            };
            let mut trace = Trace::default();
            let poses = self.poses.chunks(self.coordinates.max(1));
            for (&phi, pose) in phis.iter().zip(poses) {
                push(
                    &mut after,
                    &step_from(&plan, &model, phi, self.drive, pose, &mut trace)?,
                );
            }
            after
        };
        Ok(LinkageBalance {
            counterweights: placed,
            before: self.before,
            after,
            balanced,
        })
    }
}

/// A counterweight's link, pivot and line direction, checked.
#[derive(Debug, Clone)]
struct Site {
    link: usize,
    pivot: [f64; 2],
    line_angle: f64,
}

fn site(m: &Mechanism, c: &Counterweight) -> Result<Site, Error> {
    let context = format!("counterweight on `{}`", c.link);
    let link = m.link_index(&c.link).map_err(|_| Error::UnknownName {
        what: "link",
        name: c.link.clone(),
        context: context.clone(),
    })?;
    let point = |name: &str| {
        m.point_index(name).map_err(|_| Error::UnknownName {
            what: "point",
            name: name.to_owned(),
            context: context.clone(),
        })
    };
    let (p0, p1) = (point(&c.line[0])?, point(&c.line[1])?);
    if link == 0 {
        return Err(Error::NotPivoted {
            link: c.link.clone(),
            point: c.line[0].clone(),
        });
    }
    if !m.carries(link, p1) {
        return Err(Error::PointNotOnLink {
            point: c.line[1].clone(),
            link: c.link.clone(),
            context,
        });
    }
    let pivoted = m.joints.iter().any(|j| match j.kind {
        JointKind::Revolute {
            link_a,
            link_b,
            point,
        } => point == p0 && ((link_a, link_b) == (0, link) || (link_a, link_b) == (link, 0)),
        _ => false,
    });
    if !pivoted {
        return Err(Error::NotPivoted {
            link: c.link.clone(),
            point: c.line[0].clone(),
        });
    }
    if !(c.radius.is_finite() && c.radius > 0.0) {
        return Err(Error::NonPositiveLength {
            what: format!("the radius of the counterweight on `{}`", c.link),
            length: c.radius,
        });
    }
    let (a, b) = (m.points[p0].sketch, m.points[p1].sketch);
    let d = [b[0] - a[0], b[1] - a[1]];
    let length = d[0].hypot(d[1]);
    if length == 0.0 {
        return Err(Error::NonPositiveLength {
            what: format!(
                "the line {} → {} of the counterweight on `{}`",
                c.line[0], c.line[1], c.link
            ),
            length,
        });
    }
    Ok(Site {
        link,
        pivot: a,
        line_angle: d[1].atan2(d[0]),
    })
}

/// An angle wrapped into (−π, π].
fn wrap(angle: f64) -> f64 {
    let w = angle.sin().atan2(angle.cos());
    if w == -std::f64::consts::PI {
        std::f64::consts::PI
    } else {
        w
    }
}

/// `inertia` with a point mass `mass` at `center` added (parallel-axis theorem).
fn combine(inertia: Inertia, mass: f64, center: [f64; 2]) -> Inertia {
    let total = inertia.mass + mass;
    if mass == 0.0 || total == 0.0 {
        return if mass == 0.0 {
            inertia
        } else {
            Inertia {
                mass,
                center,
                moment: 0.0,
            }
        };
    }
    let c = [
        (inertia.mass * inertia.center[0] + mass * center[0]) / total,
        (inertia.mass * inertia.center[1] + mass * center[1]) / total,
    ];
    let d2 = |p: [f64; 2]| (p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2);
    Inertia {
        mass: total,
        center: c,
        moment: inertia.moment + inertia.mass * d2(inertia.center) + mass * d2(center),
    }
}

/// The counterweights read the pose of every position of a [`Sweep`] (no values in its
/// rows: their columns are known at the end, [`LinkageBalancing::finish`]).
impl Consumer for LinkageBalancing<'_> {
    fn at(&mut self, tracker: &Tracker<'_>, phi: f64, _: &mut Vec<f64>) -> Result<(), Error> {
        self.add(tracker, phi)
    }
}

/// The compiled model of `m` and the plan of the shaking force and the drive torque.
fn model<'m>(m: &'m Mechanism, dynamics: &Dynamics) -> Result<(CompiledModel<'m>, Plan), Error> {
    let model = dynamics.compile(m)?;
    let plan = Plan::for_requests(
        &[Request::ShakingForce, Request::DriveTorque],
        dynamics.available(m),
    );
    check(&plan, &model)?;
    Ok((model, plan))
}

/// Appends one position's shaking force, moment and drive torque to `sweep`.
fn push(sweep: &mut LinkageSweep, step: &Step) {
    let shaking = step.shaking.as_ref().expect("planned");
    let solution = step.solution.as_ref().expect("planned");
    sweep.phi.push(step.phi);
    sweep.force.push(shaking.force);
    sweep.moment.push(shaking.moment);
    sweep.drive_torque.push(solution.drive_torque);
}
