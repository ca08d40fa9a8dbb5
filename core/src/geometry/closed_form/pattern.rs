//! The shapes a loop's closed form takes: a hinged or sliding link, or a dyad of two links,
//! and how each angle or displacement is found (matched in `matching`, solved in the
//! parent module).

use crate::geometry::constraints::{Body, Line, Slide};

/// A revolute joint seen from the unknown link: the point of the known link it turns about.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Hinge {
    pub(super) known: Body,
    pub(super) at_known: [f64; 2],
    pub(super) at_body: [f64; 2],
}

impl Hinge {
    /// The revolute joint between bodies `a` (point `pa`) and `b` (point `pb`) seen from the
    /// body `me` being solved (one of the two): the other body is the known one.
    pub(super) fn seen_from(
        me: Body,
        (a, pa): (Body, [f64; 2]),
        (b, pb): (Body, [f64; 2]),
    ) -> Self {
        if b == me {
            Self {
                known: a,
                at_known: pa,
                at_body: pb,
            }
        } else {
            Self {
                known: b,
                at_known: pb,
                at_body: pa,
            }
        }
    }
}

/// How a hinged link's angle is found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Angle {
    /// `θ = θ_other + sign·(φ − φ₀)`.
    Driven { other: Body, sign: f64, phi0: f64 },
    /// The link's slot (unit direction `direction`, local) passes through a known pin:
    /// `cross(A d, P − K) = c`.
    SlotThroughPin {
        direction: [f64; 2],
        c: f64,
        pin: Body,
        at: [f64; 2],
    },
    /// The link's pin, at `r` from the hinge (local), lies on a known line.
    PinInKnownSlot { line: Line, r: [f64; 2] },
    /// A pinion rolling on a known rack: `θ = θ_other + sign·(s − s₀)/radius`, `s` the
    /// rack's displacement along its guide.
    Rolling {
        other: Body,
        sign: f64,
        slide: Slide,
        s0: f64,
        radius: f64,
    },
    /// A gear meshing with known ones: `θ = Σ kᵢ θᵢ` over the other links of the gear pair.
    Geared { terms: [(Body, f64); 4] },
}

/// How a sliding link's displacement is found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Shift {
    /// `s = s₀ + φ − φ₀`.
    Driven { s0: f64, phi0: f64 },
    /// The link's slot (line local to it) passes through a known pin.
    SlotThroughPin { line: Line, pin: Body, at: [f64; 2] },
    /// The link's pin (local `p`) lies on a known line.
    PinInKnownSlot { line: Line, p: [f64; 2] },
    /// A rack driven by a known pinion (joint between `a` and `b`):
    /// `s = s₀ + radius·(θ_b − θ_a)`.
    Rolling {
        a: Body,
        b: Body,
        s0: f64,
        radius: f64,
    },
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Pattern {
    /// A link turning about a hinge; with a `rider`, a second link that slides on it (same
    /// angle) and is hinged to a known link (the RPR dyad: its hinge is the pin the first
    /// link's line passes through).
    Hinged {
        hinge: Hinge,
        angle: Angle,
        rider: Option<(usize, Hinge)>,
    },
    Sliding {
        slide: Slide,
        offset: f64,
        shift: Shift,
    },
    /// Two links joined by a revolute (`joint`: its local point on each), the first hinged
    /// to a known link, the second hinged (RRR) or sliding (RRP) on one.
    Dyad {
        hinge: Hinge,
        joint: [[f64; 2]; 2],
        second: usize,
        end: End,
    },
}

/// How the second link of a dyad is attached to the known links.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum End {
    Hinge(Hinge),
    Slide { slide: Slide, offset: f64 },
}

/// The vector `a − b`.
pub(super) fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}
