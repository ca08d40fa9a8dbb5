//! A checked scene: names resolved, numbers in SI, every item with its place in the file.

use crate::error::Location;

use super::quantity::{Quantity, Sense};
use super::units::{Dimension, Units};

/// A scene after parsing and checking: ready to build into a geometry model and run.
#[derive(Debug, Clone)]
pub struct Scene {
    /// The file name used in messages.
    pub file: String,
    /// The scene's title, if it has one.
    pub title: Option<String>,
    /// The units of the file and of the printed results.
    pub units: Units,
    /// Points in file order, sketch coordinates in m.
    pub points: Vec<Point>,
    /// Links in file order, the ground first.
    pub links: Vec<Link>,
    /// Joints in file order.
    pub joints: Vec<Joint>,
    /// The drive.
    pub drive: Drive,
    /// The drive positions to compute (SI: rad or m), in order; or, when [`Scene::sweep_of`]
    /// names an output, the values of that output (SI) whose drive positions are solved for.
    pub positions: super::positions::Positions,
    /// Index into [`Scene::outputs`] of the output whose values the sweep gives (`[sweep] of`).
    pub sweep_of: Option<usize>,
    /// The outputs, in column order.
    pub outputs: Vec<Output>,
    /// Masses, effects and dynamic outputs, if the scene has any.
    pub dynamics: Option<super::dynamics::SceneDynamics>,
    /// The rotor and counterweights to balance, if the scene has them.
    pub balancing: Option<super::balancing::SceneBalancing>,
    /// The machine moving under its motor (`[simulate]` and the motor's characteristic).
    pub motion: Option<super::motion::SceneMotion>,
    /// What the pictures show (`[plot]`; empty when the file has none).
    pub plot: Plot,
    /// The position solver every solve of the scene uses (`[solver]`; the default solver
    /// when the file has none).
    pub solver: mechdiff_core::geometry::Solver,
    /// The values of `[parameters]` (after `--set`), in the order they were evaluated, in
    /// the units of the fields that use them.
    pub parameters: Vec<(String, f64)>,
}

/// `[plot]` checked: names resolved, numbers in SI, places kept.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Plot {
    /// Points whose paths are traced; `None`: the points of the `[[output]] point` entries.
    pub trace: Option<Vec<String>>,
    /// Drive positions (SI) to draw the mechanism at, each with its place in the file.
    pub positions: Vec<(f64, Location)>,
    /// Panel selection (output or column names, with their places); `None`: every column.
    pub panels: Option<Vec<(String, Location)>>,
    /// Points whose velocity and acceleration are drawn as arrows in the still drawings,
    /// with the place of the list (they need the drive speed, checked when drawn).
    pub vectors: Option<(Vec<String>, Location)>,
}

/// A named point at its sketch position.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    /// Name.
    pub name: String,
    /// Sketch coordinates (m).
    pub sketch: [f64; 2],
    /// Where it is defined.
    pub location: Location,
}

/// A rigid body and the points it carries.
#[derive(Debug, Clone, PartialEq)]
pub struct Link {
    /// Name (`ground` for the frame).
    pub name: String,
    /// Names of its points, as listed.
    pub points: Vec<String>,
    /// Where it is defined.
    pub location: Location,
}

/// A named joint.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    /// Name.
    pub name: String,
    /// Type and connected items.
    pub kind: JointKind,
    /// Where it is defined.
    pub location: Location,
}

/// A joint's type with the names it connects.
#[derive(Debug, Clone, PartialEq)]
pub enum JointKind {
    /// `links[0]` and `links[1]` turn about the common point `at`.
    Revolute {
        /// The two links; the drive angle is `links[1]` relative to `links[0]`.
        links: [String; 2],
        /// The common point.
        at: String,
    },
    /// `links[1]` translates along `line` (points of `links[0]`); `point` (of `links[1]`)
    /// measures the displacement from `line[0]`.
    Prismatic {
        /// Guide and slider.
        links: [String; 2],
        /// Two points of the guide.
        line: [String; 2],
        /// The slider's point on the line.
        point: String,
    },
    /// `pin` (of `links[1]`) lies on `slot` (two points of `links[0]`).
    PinInSlot {
        /// Slotted link and pin link.
        links: [String; 2],
        /// Two points of the slotted link on the slot's centre line.
        slot: [String; 2],
        /// The pin.
        pin: String,
    },
    /// Rolling of the pinion in revolute joint `pinion` on the rack of prismatic joint `rack`.
    RackPinion {
        /// The pinion's revolute joint.
        pinion: String,
        /// The rack's prismatic joint.
        rack: String,
        /// Signed pitch radius (m): positive when a counter-clockwise turn of the pinion moves
        /// the rack forwards along its line (pinion centre to the left of the line).
        radius: f64,
    },
    /// `Δθ` in revolute joint `joints[1]` = `ratio` × `Δθ` in revolute joint `joints[0]`.
    Gear {
        /// The two revolute joints.
        joints: [String; 2],
        /// Signed transmission ratio.
        ratio: f64,
    },
    /// The links are welded together.
    Weld {
        /// The two links.
        links: [String; 2],
    },
}

/// Whether the drive is an angle or a displacement.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DriveKind {
    /// A revolute joint's angle (rad).
    Angle,
    /// A prismatic joint's displacement (m).
    Displacement,
}

impl DriveKind {
    /// The dimension of the drive variable.
    pub fn dimension(self) -> Dimension {
        match self {
            DriveKind::Angle => Dimension::Angle,
            DriveKind::Displacement => Dimension::Length,
        }
    }

    /// The dimension of the drive speed.
    pub fn speed_dimension(self) -> Dimension {
        match self {
            DriveKind::Angle => Dimension::AngularVelocity,
            DriveKind::Displacement => Dimension::Velocity,
        }
    }

    /// The dimension of the drive acceleration.
    pub fn acceleration_dimension(self) -> Dimension {
        match self {
            DriveKind::Angle => Dimension::AngularAcceleration,
            DriveKind::Displacement => Dimension::Acceleration,
        }
    }
}

/// The driven joint and its motion.
#[derive(Debug, Clone, PartialEq)]
pub struct Drive {
    /// The driven joint's name.
    pub joint: String,
    /// Angle or displacement.
    pub kind: DriveKind,
    /// The drive variable φ at the sketch pose (rad or m), measured as the file says.
    pub at_sketch: f64,
    /// φ̇ (rad/s or m/s), if given.
    pub speed: Option<f64>,
    /// φ̈ (rad/s² or m/s²); 0 if not given.
    pub acceleration: f64,
    /// Where `[drive]` is.
    pub location: Location,
    /// The cam moving the joint, if `[drive] cam` names one.
    pub cam: Option<DriveCam>,
}

impl Drive {
    /// The kind of the driven joint's variable (for a cam drive, the follower's, while
    /// [`Drive::kind`] is the cam angle's).
    pub fn joint_kind(&self) -> DriveKind {
        self.cam.as_ref().map_or(self.kind, |c| c.joint_kind)
    }

    /// The driven joint's position (rad or m) at drive position `phi` (for a cam drive, the
    /// cam angle: the sketch's value plus the follower's displacement s(θ)).
    pub fn joint_position(&self, phi: f64) -> f64 {
        match &self.cam {
            Some(c) => self.at_sketch + c.joint.svaj(phi).value,
            None => phi,
        }
    }
}

/// A cam driving the joint (`[drive] cam = "file"`): the drive position is the cam angle θ,
/// the speed and acceleration are the cam's, and the joint moves by the follower's
/// displacement s(θ) from the sketch (the sketch shows the follower at s = 0).
#[derive(Debug, Clone)]
pub struct DriveCam {
    /// The cam scene file, as resolved.
    pub file: String,
    /// The cam program as a drive.
    pub joint: mechdiff_core::cams::CamJoint,
    /// The driven joint's kind: a displacement for a translating follower, an angle for an
    /// oscillating one.
    pub joint_kind: DriveKind,
}

impl PartialEq for DriveCam {
    /// Two cam drives are equal when they come from the same file for the same joint kind.
    fn eq(&self, other: &Self) -> bool {
        self.file == other.file && self.joint_kind == other.joint_kind
    }
}

/// What one output column group measures.
#[derive(Debug, Clone, PartialEq)]
pub enum OutputKind {
    /// The x and y of a point.
    Point(String),
    /// The angle of the line `line[0] → line[1]`, from `reference` (or +x), in `sense`.
    Angle {
        /// The measured line.
        line: [String; 2],
        /// The line it is measured from; `None`: the +x axis.
        reference: Option<[String; 2]>,
        /// Counter-clockwise or clockwise positive.
        sense: Sense,
    },
    /// The displacement of a prismatic or pin-in-slot joint along its line, measured from the
    /// line's first point.
    Slider {
        /// Name of the joint.
        joint: String,
        /// Point on the moving link (the prismatic joint's point, or the pin).
        point: String,
        /// The line (two points of the guide or slotted link).
        line: [String; 2],
    },
    /// The transmission angle μ of the four-bar or slider-crank loop whose follower is the
    /// link `follower` (see docs/scene-format.md, "Linkage metrics").
    Transmission {
        /// The follower link named in the file: a four-bar's output link, a slider-crank's
        /// slider (or its rod when the rod's pin runs in a slot of the ground).
        follower: String,
        /// The form reported.
        form: super::quantity::TransmissionForm,
        /// The points μ is read from: B (coupler–follower), A (coupler–input), then the
        /// follower's pivot O_out (four-bar) or the two points of the slider's path line
        /// (slider-crank). Empty until the loop is found in the model, when the scene has
        /// been read whole.
        points: Vec<String>,
    },
}

impl OutputKind {
    /// The dimension of the output's value.
    pub fn dimension(&self) -> Dimension {
        match self {
            OutputKind::Angle { .. } | OutputKind::Transmission { .. } => Dimension::Angle,
            OutputKind::Point(_) | OutputKind::Slider { .. } => Dimension::Length,
        }
    }
}

/// One requested output.
#[derive(Debug, Clone, PartialEq)]
pub struct Output {
    /// Column name.
    pub name: String,
    /// What is measured.
    pub kind: OutputKind,
    /// What is reported, in column order.
    pub quantities: Vec<Quantity>,
    /// Whether to search the sweep range for its dead positions.
    pub dead_positions: bool,
    /// Where it is defined.
    pub location: Location,
}

impl Scene {
    /// Every link's lengths at the sketch, which the solver holds rigid, as `(link, point,
    /// point, length)` (SI): the distance between each pair of its points when the link has
    /// at most [`Scene::ALL_PAIRS_UP_TO`] points; for a larger link, the distance of each
    /// point to the first two listed (which fix it rigidly), so that the list grows with
    /// the number of points, not with its square.
    pub fn link_lengths(&self) -> Vec<(&str, &str, &str, f64)> {
        let sketch: std::collections::HashMap<&str, [f64; 2]> = self
            .points
            .iter()
            .map(|p| (p.name.as_str(), p.sketch))
            .collect();
        let mut lengths = Vec::new();
        for link in &self.links {
            let firsts = if link.points.len() <= Self::ALL_PAIRS_UP_TO {
                link.points.len()
            } else {
                2
            };
            for (i, a) in link.points.iter().enumerate().take(firsts) {
                for b in &link.points[i + 1..] {
                    if let (Some(p), Some(q)) = (sketch.get(a.as_str()), sketch.get(b.as_str())) {
                        let length = (q[0] - p[0]).hypot(q[1] - p[1]);
                        lengths.push((link.name.as_str(), a.as_str(), b.as_str(), length));
                    }
                }
            }
        }
        lengths
    }

    /// The most points of a link whose every pair [`Scene::link_lengths`] lists.
    pub const ALL_PAIRS_UP_TO: usize = 8;

    /// The highest derivative order any output needs (0: positions only).
    pub fn order(&self) -> usize {
        let asked = self
            .outputs
            .iter()
            .flat_map(|o| o.quantities.iter().map(|q| q.order()));
        let dead = self.outputs.iter().filter(|o| o.dead_positions).map(|_| 2);
        asked.chain(dead).max().unwrap_or(0)
    }

    /// A drive value (SI) printed with the scene's unit, e.g. `"67.5 deg"` (see
    /// [`super::error_context::ErrorContext::drive_text`]).
    pub fn drive_text(&self, value: f64) -> String {
        self.error_context().drive_text(value)
    }

    /// A cam angle (SI) of a cam drive with the follower's position there (see
    /// [`super::error_context::ErrorContext::cam_angle_text`]).
    pub fn cam_angle_text(&self, theta: f64) -> String {
        self.error_context().cam_angle_text(theta)
    }

    /// A position (SI) of the driven joint (see
    /// [`super::error_context::ErrorContext::joint_text`]).
    pub fn joint_text(&self, value: f64) -> String {
        self.error_context().joint_text(value)
    }
}
