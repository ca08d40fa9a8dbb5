//! The model builder: points, links, joints and a drive declared by name, validated into a
//! [`Mechanism`] by [`MechanismBuilder::build`].

use super::model::{Drive, Inertia, Mechanism, Point};
use super::validate;
use crate::Error;

impl Mechanism {
    /// Starts a builder with an empty ground link.
    pub fn builder() -> MechanismBuilder {
        MechanismBuilder::default()
    }
}

/// Declared but not yet validated items; see [`MechanismBuilder::build`].
#[derive(Debug, Clone, Default)]
pub struct MechanismBuilder {
    pub(super) points: Vec<Point>,
    pub(super) ground: Vec<String>,
    pub(super) links: Vec<(String, Vec<String>)>,
    pub(super) inertias: Vec<(String, Inertia)>,
    pub(super) joints: Vec<(String, PendingJoint)>,
    pub(super) drive: Option<Drive>,
}

#[derive(Debug, Clone)]
pub(super) enum PendingJoint {
    Revolute {
        a: String,
        b: String,
        point: String,
    },
    Prismatic {
        guide: String,
        line: [String; 2],
        slider: String,
        point: String,
    },
    PinInSlot {
        slot: String,
        line: [String; 2],
        pin_link: String,
        pin: String,
    },
    RackPinion {
        pinion: String,
        rack: String,
        radius: f64,
    },
    Gear {
        a: String,
        b: String,
        ratio: f64,
    },
    Rigid {
        a: String,
        b: String,
    },
}

impl MechanismBuilder {
    /// Declares a point at its sketch position (m).
    pub fn point(mut self, name: impl Into<String>, sketch: [f64; 2]) -> Self {
        self.points.push(Point {
            name: name.into(),
            sketch,
        });
        self
    }

    /// Puts points on the ground link.
    pub fn ground<S: Into<String>>(mut self, points: impl IntoIterator<Item = S>) -> Self {
        self.ground.extend(points.into_iter().map(Into::into));
        self
    }

    /// Declares a moving link carrying `points` (the first one is its reference point).
    pub fn link<S: Into<String>>(
        mut self,
        name: impl Into<String>,
        points: impl IntoIterator<Item = S>,
    ) -> Self {
        self.links
            .push((name.into(), points.into_iter().map(Into::into).collect()));
        self
    }

    /// Gives link `link` mass properties.
    pub fn inertia(mut self, link: impl Into<String>, inertia: Inertia) -> Self {
        self.inertias.push((link.into(), inertia));
        self
    }

    /// Revolute joint: `point` is carried by links `a` and `b` and stays common to them.
    pub fn revolute(
        mut self,
        name: impl Into<String>,
        a: impl Into<String>,
        b: impl Into<String>,
        point: impl Into<String>,
    ) -> Self {
        let j = PendingJoint::Revolute {
            a: a.into(),
            b: b.into(),
            point: point.into(),
        };
        self.joints.push((name.into(), j));
        self
    }

    /// Prismatic joint: `slider` translates along the line `line[0] → line[1]` of `guide`;
    /// its displacement is measured at `point` (a point of `slider`).
    pub fn prismatic(
        mut self,
        name: impl Into<String>,
        guide: impl Into<String>,
        line: [&str; 2],
        slider: impl Into<String>,
        point: impl Into<String>,
    ) -> Self {
        let j = PendingJoint::Prismatic {
            guide: guide.into(),
            line: line.map(str::to_owned),
            slider: slider.into(),
            point: point.into(),
        };
        self.joints.push((name.into(), j));
        self
    }

    /// Pin-in-slot joint: point `pin` of `pin_link` stays on the line through `line` of
    /// `slot_link`.
    pub fn pin_in_slot(
        mut self,
        name: impl Into<String>,
        slot_link: impl Into<String>,
        line: [&str; 2],
        pin_link: impl Into<String>,
        pin: impl Into<String>,
    ) -> Self {
        let j = PendingJoint::PinInSlot {
            slot: slot_link.into(),
            line: line.map(str::to_owned),
            pin_link: pin_link.into(),
            pin: pin.into(),
        };
        self.joints.push((name.into(), j));
        self
    }

    /// Rack and pinion: `Δs = radius·Δθ` between revolute joint `pinion` and prismatic joint
    /// `rack` (see [`super::JointKind::RackPinion`] for the sign of `radius`).
    pub fn rack_pinion(
        mut self,
        name: impl Into<String>,
        pinion: impl Into<String>,
        rack: impl Into<String>,
        radius: f64,
    ) -> Self {
        let j = PendingJoint::RackPinion {
            pinion: pinion.into(),
            rack: rack.into(),
            radius,
        };
        self.joints.push((name.into(), j));
        self
    }

    /// Gear contact: `Δθ_b = ratio·Δθ_a` between revolute joints `a` and `b`.
    pub fn gear(
        mut self,
        name: impl Into<String>,
        a: impl Into<String>,
        b: impl Into<String>,
        ratio: f64,
    ) -> Self {
        let j = PendingJoint::Gear {
            a: a.into(),
            b: b.into(),
            ratio,
        };
        self.joints.push((name.into(), j));
        self
    }

    /// Rigid attachment of link `b` to link `a`.
    pub fn rigid(
        mut self,
        name: impl Into<String>,
        a: impl Into<String>,
        b: impl Into<String>,
    ) -> Self {
        self.joints.push((
            name.into(),
            PendingJoint::Rigid {
                a: a.into(),
                b: b.into(),
            },
        ));
        self
    }

    /// Sets the drive.
    pub fn drive(mut self, drive: Drive) -> Self {
        self.drive = Some(drive);
        self
    }

    /// Validates names, references and lengths, and returns the model. Mobility is checked
    /// separately ([`crate::geometry::check_mobility`]) because it needs the Jacobian.
    pub fn build(self) -> Result<Mechanism, Error> {
        validate::build(self)
    }
}
