//! The geometry model: what a designer draws.
//!
//! A mechanism is a set of named **points** with global coordinates at the *sketch pose* (the
//! assembly as drawn, which also fixes the assembly branch), **links** (rigid bodies, each
//! carrying some of the points; the ground is the link named [`GROUND`]), **joints** between
//! links, and one **drive**.
//!
//! Internally each moving link `k` has pose coordinates `(x_k, y_k, θ_k)`: the position of
//! its first point and its rotation since the sketch (so every `θ_k = 0` at the sketch pose).
//! A point `p` of link `k` is at `r_k + A(θ_k)·(p_sketch − r_k,sketch)`.
//!
//! ```
//! use mechdiff_core::geometry::{Drive, Mechanism};
//! // A slider-crank: crank O–A (0.1 m), rod A–B (0.4 m), slider B on the x axis.
//! let m = Mechanism::builder()
//!     .point("O", [0.0, 0.0])
//!     .point("A", [0.1, 0.0])
//!     .point("B", [0.5, 0.0])
//!     .point("X", [1.0, 0.0])
//!     .ground(["O", "X"])
//!     .link("crank", ["O", "A"])
//!     .link("rod", ["A", "B"])
//!     .link("slider", ["B"])
//!     .revolute("O", "ground", "crank", "O")
//!     .revolute("A", "crank", "rod", "A")
//!     .revolute("B", "rod", "slider", "B")
//!     .prismatic("guide", "ground", ["O", "X"], "slider", "B")
//!     .drive(Drive::angle("O"))
//!     .build()
//!     .unwrap();
//! assert_eq!(m.coordinate_count(), 9);
//! ```

use crate::Error;

/// Name of the ground link, present in every model.
pub const GROUND: &str = "ground";

/// A named point at its sketch position (m).
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    /// Name, unique in the model.
    pub name: String,
    /// Global coordinates at the sketch pose (m).
    pub sketch: [f64; 2],
}

/// Mass properties of a link (used by the dynamics; the kinematics ignore them).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inertia {
    /// Mass (kg).
    pub mass: f64,
    /// Centre of gravity at the sketch pose, global coordinates (m).
    pub center: [f64; 2],
    /// Moment of inertia about the centre of gravity (kg·m²).
    pub moment: f64,
}

impl Inertia {
    /// A uniform slender bar from `a` to `b` of mass `density` per length (kg/m): mass
    /// m = ρ·L at the midpoint, moment m·L²/12 about it.
    ///
    /// ```
    /// use mechdiff_core::geometry::Inertia;
    ///
    /// let bar = Inertia::uniform_bar(2.0, [0.0, 0.0], [3.0, 4.0]);
    /// assert_eq!((bar.mass, bar.center, bar.moment), (10.0, [1.5, 2.0], 10.0 * 25.0 / 12.0));
    /// ```
    pub fn uniform_bar(density: f64, a: [f64; 2], b: [f64; 2]) -> Inertia {
        let length = (b[0] - a[0]).hypot(b[1] - a[1]);
        let (mass, center, moment) = uniform_bar_of(density, length, a, b);
        Inertia {
            mass,
            center,
            moment,
        }
    }
}

/// The mass properties `(mass, centre, moment about the centre)` of a uniform slender bar
/// from `a` to `b` of mass `density` per length, in any scalar (a `Dual64` carries their
/// derivatives with respect to a parameter): m = ρ·L at the midpoint, m·L²/12.
///
/// `length` is |b − a|, computed by the caller so that it rounds as the caller's other
/// lengths do ([`Inertia::uniform_bar`] uses [`f64::hypot`]).
pub fn uniform_bar_of<D: crate::Scalar>(
    density: D,
    length: D,
    a: [D; 2],
    b: [D; 2],
) -> (D, [D; 2], D) {
    let mass = density * length;
    let center = [(a[0] + b[0]) * 0.5, (a[1] + b[1]) * 0.5];
    (mass, center, mass * length * length / 12.0)
}

/// A rigid body carrying named points.
#[derive(Debug, Clone, PartialEq)]
pub struct Link {
    /// Name, unique in the model ([`GROUND`] for the ground).
    pub name: String,
    /// Indices into [`Mechanism::points`] of the points this link carries; the first one is the
    /// link's reference point (its pose coordinates `x, y`).
    pub points: Vec<usize>,
    /// Mass properties, if given.
    pub inertia: Option<Inertia>,
}

/// The kind of a joint, with indices into the model's links and points.
#[derive(Debug, Clone, PartialEq)]
pub enum JointKind {
    /// Revolute (R): `point` is carried by both links and stays common to them. 2 equations.
    Revolute {
        /// First link (the drive angle is the rotation of `link_b` relative to `link_a`).
        link_a: usize,
        /// Second link.
        link_b: usize,
        /// The common point.
        point: usize,
    },
    /// Prismatic (P): `slider` translates, without rotating relative to `guide`, along the line
    /// through the guide's points `line[0] → line[1]`. The displacement is
    /// `s = u·(r_point − r_line0)` with `u` the unit direction of the line. 2 equations.
    Prismatic {
        /// The link carrying the line (ground or a moving link).
        guide: usize,
        /// Two distinct points of `guide` defining the line and its direction.
        line: [usize; 2],
        /// The translating link.
        slider: usize,
        /// The point of `slider` whose position along the line is the displacement `s`.
        point: usize,
    },
    /// Pin in slot (RP): `pin` of `pin_link` lies on the line through `slot_link`'s points
    /// `line[0], line[1]` (the slot link may rotate or translate). 1 equation.
    PinInSlot {
        /// The link with the straight slot.
        slot_link: usize,
        /// Two distinct points of `slot_link` on the slot's centre line.
        line: [usize; 2],
        /// The link carrying the pin.
        pin_link: usize,
        /// The pin point.
        pin: usize,
    },
    /// Rack and pinion (rolling contact): `Δs = radius·Δθ`, where `Δθ` is the change of the
    /// relative rotation in revolute joint `pinion` and `Δs` the change of the displacement in
    /// prismatic joint `rack`. `radius` is signed: positive when a counter-clockwise pinion
    /// rotation moves the rack towards `+u`. 1 equation.
    RackPinion {
        /// Index of the pinion's revolute joint.
        pinion: usize,
        /// Index of the rack's prismatic joint.
        rack: usize,
        /// Signed pitch radius (m).
        radius: f64,
    },
    /// Gear contact between two revolute joints: `Δθ_b = ratio·Δθ_a` (relative rotations;
    /// an external mesh has a negative ratio). 1 equation.
    Gear {
        /// Index of the first revolute joint.
        joint_a: usize,
        /// Index of the second revolute joint.
        joint_b: usize,
        /// Signed transmission ratio.
        ratio: f64,
    },
    /// Rigid attachment (weld): `link_b` keeps its sketch pose relative to `link_a`.
    /// 3 equations.
    Rigid {
        /// First link.
        link_a: usize,
        /// Second link.
        link_b: usize,
    },
}

impl JointKind {
    /// The two links this joint connects directly, or `None` for a rack-and-pinion or gear
    /// coupling (which couples two other joints).
    pub fn joined_links(&self) -> Option<[usize; 2]> {
        match *self {
            JointKind::Revolute { link_a, link_b, .. } | JointKind::Rigid { link_a, link_b } => {
                Some([link_a, link_b])
            }
            JointKind::Prismatic { guide, slider, .. } => Some([guide, slider]),
            JointKind::PinInSlot {
                slot_link,
                pin_link,
                ..
            } => Some([slot_link, pin_link]),
            JointKind::RackPinion { .. } | JointKind::Gear { .. } => None,
        }
    }

    /// Number of scalar constraint equations of this joint.
    pub fn equation_count(&self) -> usize {
        match self {
            JointKind::Revolute { .. } | JointKind::Prismatic { .. } => 2,
            JointKind::PinInSlot { .. } | JointKind::RackPinion { .. } | JointKind::Gear { .. } => {
                1
            }
            JointKind::Rigid { .. } => 3,
        }
    }

    /// Short name of the kind, as used in messages ("revolute", "prismatic", ...).
    pub fn kind_name(&self) -> &'static str {
        match self {
            JointKind::Revolute { .. } => "revolute",
            JointKind::Prismatic { .. } => "prismatic",
            JointKind::PinInSlot { .. } => "pin-in-slot",
            JointKind::RackPinion { .. } => "rack-and-pinion",
            JointKind::Gear { .. } => "gear",
            JointKind::Rigid { .. } => "rigid",
        }
    }
}

/// A named joint.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    /// Name, unique among joints.
    pub name: String,
    /// Kind and connected items.
    pub kind: JointKind,
}

/// What the drive variable φ is.
#[derive(Debug, Clone, PartialEq)]
pub enum DriveKind {
    /// Relative rotation (rad) of `link_b` with respect to `link_a` in a revolute joint.
    Angle,
    /// Displacement (m) in a prismatic joint.
    Displacement,
}

/// The drive: one revolute angle or one prismatic displacement, by joint name.
#[derive(Debug, Clone, PartialEq)]
pub struct Drive {
    /// Name of the driven joint.
    pub joint: String,
    /// Angle or displacement.
    pub kind: DriveKind,
    /// Value of φ at the sketch pose. `None`: 0 for an angle, the sketch displacement
    /// `u·(r_point − r_line0)` for a prismatic joint.
    pub at_sketch: Option<f64>,
}

impl Drive {
    /// Drive the relative angle of revolute joint `joint` (φ = 0 at the sketch unless
    /// [`Drive::at_sketch`] says otherwise).
    pub fn angle(joint: impl Into<String>) -> Self {
        Drive {
            joint: joint.into(),
            kind: DriveKind::Angle,
            at_sketch: None,
        }
    }

    /// Drive the displacement of prismatic joint `joint` (φ = the sketch displacement unless
    /// [`Drive::at_sketch`] says otherwise).
    pub fn displacement(joint: impl Into<String>) -> Self {
        Drive {
            joint: joint.into(),
            kind: DriveKind::Displacement,
            at_sketch: None,
        }
    }

    /// Sets the value of φ at the sketch pose (rad or m).
    pub fn at_sketch(mut self, value: f64) -> Self {
        self.at_sketch = Some(value);
        self
    }
}

/// A validated mechanism model. Build it with [`Mechanism::builder`]; its parts are read
/// through accessors, so a model cannot be changed after validation.
#[derive(Debug, Clone, PartialEq)]
pub struct Mechanism {
    pub(crate) points: Vec<Point>,
    pub(crate) links: Vec<Link>,
    pub(crate) joints: Vec<Joint>,
    pub(crate) drive_joint: usize,
    pub(crate) drive_kind: DriveKind,
    pub(crate) drive_at_sketch: f64,
}

impl Mechanism {
    /// All points, in declaration order.
    pub fn points(&self) -> &[Point] {
        &self.points
    }

    /// All links; index 0 is the ground.
    pub fn links(&self) -> &[Link] {
        &self.links
    }

    /// All joints, in declaration order.
    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }

    /// Index of the driven joint in [`Mechanism::joints`].
    pub fn drive_joint(&self) -> usize {
        self.drive_joint
    }

    /// Whether the drive is an angle or a displacement.
    pub fn drive_kind(&self) -> &DriveKind {
        &self.drive_kind
    }

    /// Value of the drive variable φ at the sketch pose (rad or m).
    pub fn drive_at_sketch(&self) -> f64 {
        self.drive_at_sketch
    }

    /// Number of pose coordinates `q` (3 per moving link).
    pub fn coordinate_count(&self) -> usize {
        3 * (self.links.len() - 1)
    }

    /// Number of constraint equations, drive included.
    pub fn equation_count(&self) -> usize {
        self.joints
            .iter()
            .map(|j| j.kind.equation_count())
            .sum::<usize>()
            + 1
    }

    /// Index of the link named `name`.
    pub fn link_index(&self, name: &str) -> Result<usize, Error> {
        self.links
            .iter()
            .position(|l| l.name == name)
            .ok_or_else(|| Error::UnknownName {
                what: "link",
                name: name.to_owned(),
                context: "lookup".to_owned(),
            })
    }

    /// Index of the point named `name`.
    pub fn point_index(&self, name: &str) -> Result<usize, Error> {
        self.points
            .iter()
            .position(|p| p.name == name)
            .ok_or_else(|| Error::UnknownName {
                what: "point",
                name: name.to_owned(),
                context: "lookup".to_owned(),
            })
    }

    /// Index of the joint named `name`.
    pub fn joint_index(&self, name: &str) -> Result<usize, Error> {
        self.joints
            .iter()
            .position(|j| j.name == name)
            .ok_or_else(|| Error::UnknownName {
                what: "joint",
                name: name.to_owned(),
                context: "lookup".to_owned(),
            })
    }

    /// Sketch position of the reference point of link `k`: its first point, or the origin
    /// for the ground (whose frame is the global one).
    pub fn reference_sketch(&self, link: usize) -> [f64; 2] {
        if link == 0 {
            return [0.0, 0.0];
        }
        self.links[link]
            .points
            .first()
            .map_or([0.0, 0.0], |&p| self.points[p].sketch)
    }

    /// Coordinates of global sketch position `at` in the frame of link `k`
    /// (relative to its reference point, unrotated since `θ = 0` at the sketch).
    pub fn local(&self, link: usize, at: [f64; 2]) -> [f64; 2] {
        let r = self.reference_sketch(link);
        [at[0] - r[0], at[1] - r[1]]
    }

    /// Pose coordinates at the sketch pose: `(x, y, 0)` per moving link.
    pub fn sketch_coordinates(&self) -> Vec<f64> {
        (1..self.links.len())
            .flat_map(|k| {
                let r = self.reference_sketch(k);
                [r[0], r[1], 0.0]
            })
            .collect()
    }

    /// Whether link `link` carries point `point`.
    pub fn carries(&self, link: usize, point: usize) -> bool {
        self.links[link].points.contains(&point)
    }
}
