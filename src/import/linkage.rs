//! The linkage an imported file describes: joints at sketch coordinates, each joining one or
//! more named links, and the scene TOML it is written as ([`Linkage::to_scene`]).

use std::fmt::Write as _;
use std::ops::Range;

use crate::error::{Error, Result};
use crate::scene::Source;

/// The frame's name in Pyslvs, PMKS and scene files.
pub(super) const GROUND: &str = "ground";

/// The kind of an imported joint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum JointKind {
    /// A pin joining every listed link at the joint's point.
    Revolute,
    /// A slide of the second link on the first along `angle` (degrees, counter-clockwise
    /// from +x).
    Prismatic {
        /// The direction of the slide (deg).
        angle: f64,
    },
}

/// One joint as the imported file gives it.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    /// Its kind.
    pub kind: JointKind,
    /// The links it joins (one link: only a point of that link, e.g. a coupler point).
    pub links: Vec<String>,
    /// Sketch coordinates (file units).
    pub at: [f64; 2],
    /// Where the joint is written in the file (bytes).
    pub span: Range<usize>,
}

/// A linkage read from another tool's format.
#[derive(Debug, Clone, PartialEq)]
pub struct Linkage {
    /// The format's name, for the scene's header and messages.
    pub format: &'static str,
    /// The joints in file order (named `J1`, `J2`, … in the scene).
    pub joints: Vec<Joint>,
    /// The joint marked as the driving input, if the format marks one.
    pub drive: Option<usize>,
}
/// An error of the imported file at `span`.
pub(crate) fn error(source: &Source, span: Range<usize>, message: impl Into<String>) -> Error {
    Error::Import {
        location: source.location(span),
        message: message.into(),
    }
}

fn quoted(name: &str) -> String {
    toml::Value::String(name.to_owned()).to_string()
}

fn number(v: f64) -> String {
    // The shortest decimal that reads back to the same f64, never in exponent form.
    let text = v.to_string();
    if text.contains('.') || text.contains('e') {
        text
    } else {
        format!("{text}.0")
    }
}

impl Linkage {
    /// The scene name of joint `k` (0-based) and of its point.
    fn name(k: usize) -> String {
        format!("J{}", k + 1)
    }

    /// Checks what the scene needs: a ground, prismatic joints of two links, a joint to
    /// drive.
    pub(super) fn check(&self, source: &Source) -> Result<()> {
        if self.joints.is_empty() {
            return Err(error(
                source,
                0..0,
                format!("the {} file has no joint", self.format),
            ));
        }
        for j in &self.joints {
            if let JointKind::Prismatic { .. } = j.kind
                && j.links.len() != 2
            {
                return Err(error(
                    source,
                    j.span.clone(),
                    format!(
                        "a prismatic joint joins two links, this one lists {}: {}; split it \
                         into a prismatic joint of two links and a revolute joint",
                        j.links.len(),
                        j.links.join(", ")
                    ),
                ));
            }
            for (i, l) in j.links.iter().enumerate() {
                if j.links[..i].contains(l) {
                    return Err(error(
                        source,
                        j.span.clone(),
                        format!("the joint lists link `{l}` twice"),
                    ));
                }
            }
        }
        if !self
            .joints
            .iter()
            .any(|j| j.links.iter().any(|l| l == GROUND))
        {
            return Err(error(
                source,
                0..0,
                "no joint is on `ground` (the frame); name the fixed link `ground`",
            ));
        }
        self.drive_joint(source).map(|_| ())
    }

    /// The driven joint: the one the file marks, else the first revolute joint of two
    /// links one of which is `ground`; with the driven link and another point of it.
    fn drive_joint(&self, source: &Source) -> Result<(usize, String, usize)> {
        let candidate = |j: &Joint| {
            j.kind == JointKind::Revolute && j.links.len() == 2 && j.links.contains(&GROUND.into())
        };
        let k = match self.drive {
            Some(k) if candidate(&self.joints[k]) => k,
            Some(k) => {
                return Err(error(
                    source,
                    self.joints[k].span.clone(),
                    "the driving input is not a revolute joint of `ground` and one other \
                     link; mechdiff imports a crank drive only: mark a ground pivot of a crank",
                ));
            }
            None => self.joints.iter().position(candidate).ok_or_else(|| {
                error(
                    source,
                    0..0,
                    "no joint can be the drive: expected a revolute joint of `ground` and one \
                     other link (a crank's pivot)",
                )
            })?,
        };
        let crank = (self.joints[k].links.iter())
            .find(|l| *l != GROUND)
            .expect("a link besides ground")
            .clone();
        let other = (self.joints.iter().enumerate())
            .find(|(i, j)| *i != k && j.links.contains(&crank))
            .map(|(i, _)| i)
            .ok_or_else(|| {
                error(
                    source,
                    self.joints[k].span.clone(),
                    format!(
                        "the driven link `{crank}` has no other joint or point, so its angle \
                         cannot be measured; add a point of `{crank}`"
                    ),
                )
            })?;
        Ok((k, crank, other))
    }

    /// The scene: a point per joint (`J1`, …), the links with their points, the joints,
    /// the drive, a full turn of the crank in 5° steps and every moving point's position
    /// and velocity coefficients as outputs. `file` is named in the header comment.
    pub fn to_scene(&self, source: &Source) -> Result<String> {
        let (drive, crank, other) = self.drive_joint(source)?;
        let mut out = String::new();
        let w = &mut out;
        let _ = writeln!(
            w,
            "# Imported from {} ({}) by `mechdiff import`.",
            source.file, self.format
        );
        let _ = writeln!(
            w,
            "# {} has no units: lengths are taken as mm (change `length` below if not).",
            self.format
        );
        let _ = writeln!(
            w,
            "title = {}\n",
            quoted(&format!("{} (imported)", source.file))
        );
        let _ = writeln!(w, "[units]\nlength = \"mm\"\nangle = \"deg\"\n");
        // Sketch size: the direction point of a slide is placed this far along it.
        let size = (self.joints.iter())
            .flat_map(|a| {
                self.joints
                    .iter()
                    .map(move |b| (a.at[0] - b.at[0]).hypot(a.at[1] - b.at[1]))
            })
            .fold(0.0, f64::max)
            .max(1.0);
        let _ = writeln!(w, "[points]");
        let mut links: Vec<(String, Vec<String>)> = Vec::new();
        let mut carry = |link: &str, point: String| match links.iter_mut().find(|(l, _)| l == link)
        {
            Some((_, points)) if !points.contains(&point) => points.push(point),
            Some(_) => {}
            None => links.push((link.to_owned(), vec![point])),
        };
        for (k, j) in self.joints.iter().enumerate() {
            let name = Self::name(k);
            let _ = writeln!(w, "{name} = [{}, {}]", number(j.at[0]), number(j.at[1]));
            let prismatic = matches!(j.kind, JointKind::Prismatic { .. });
            for l in &j.links[usize::from(prismatic)..] {
                carry(l, name.clone());
            }
            if let JointKind::Prismatic { angle } = j.kind {
                let (s, c) = angle.to_radians().sin_cos();
                let along = [j.at[0] + size * c, j.at[1] + size * s];
                // The guide's own points: the slider carries `name` itself.
                let _ = writeln!(
                    w,
                    "{name}_guide = [{}, {}]\n{name}_line = [{}, {}]   # the guide, along {angle}°",
                    number(j.at[0]),
                    number(j.at[1]),
                    number(along[0]),
                    number(along[1])
                );
                carry(&j.links[0], format!("{name}_guide"));
                carry(&j.links[0], format!("{name}_line"));
            }
        }
        let _ = writeln!(w, "\n[links]");
        for (link, points) in &links {
            let points: Vec<String> = points.iter().map(|p| quoted(p)).collect();
            let _ = writeln!(w, "{} = [{}]", quoted(link), points.join(", "));
        }
        let _ = writeln!(w, "\n[joints]");
        for (k, j) in self.joints.iter().enumerate() {
            let name = Self::name(k);
            let mut names: Vec<&String> = j.links.iter().collect();
            if k == drive && names[0] != GROUND {
                names.reverse();
            }
            let list: Vec<String> = names.iter().map(|l| quoted(l)).collect();
            let list = list.join(", ");
            match j.kind {
                JointKind::Revolute if j.links.len() >= 2 => {
                    let _ = writeln!(
                        w,
                        "{name} = {{ type = \"revolute\", at = \"{name}\", links = [{list}] }}"
                    );
                }
                JointKind::Revolute => {} // a point of one link
                JointKind::Prismatic { .. } => {
                    let _ = writeln!(
                        w,
                        "{name} = {{ type = \"prismatic\", links = [{list}], line = [\"{name}_guide\", \
                         \"{name}_line\"], point = \"{name}\" }}"
                    );
                }
            }
        }
        let driven = Self::name(drive);
        // The crank's second point: the other joint's point, or its guide's when the crank
        // carries that slide's guide.
        let mut second = Self::name(other);
        if matches!(self.joints[other].kind, JointKind::Prismatic { .. })
            && self.joints[other].links[0] == crank
        {
            second.push_str("_guide");
        }
        let _ = writeln!(
            w,
            "\n[drive]\njoint = \"{driven}\"\nline = [\"{driven}\", \"{second}\"]   # the angle of `{crank}`\nspeed = 1   # rad/s\n"
        );
        let _ = writeln!(
            w,
            "[sweep]   # a full turn; a rocking crank needs a smaller range\nfrom = 0\nto = 360\nstep = 5\n"
        );
        for (k, j) in self.joints.iter().enumerate() {
            if j.links.iter().all(|l| l == GROUND)
                || j.links.iter().any(|l| l == GROUND) && j.kind == JointKind::Revolute
            {
                continue; // fixed
            }
            let _ = writeln!(
                w,
                "[[output]]\npoint = \"{}\"\nquantities = [\"position\", \"velocity_coefficient\"]\n",
                Self::name(k)
            );
        }
        Ok(out)
    }
}
