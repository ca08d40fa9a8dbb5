//! Importing linkages written for other tools into scene files (`mechdiff import FILE`).
//!
//! Two formats are read, each into a [`Linkage`] (joints at sketch coordinates, each joining
//! one or more named links), which [`Linkage::to_scene`] writes as a scene TOML:
//!
//! - `pyslvs`: Pyslvs's mechanism expression, `M[J[R, color[Green], P[0.0, 0.0],
//!   L[ground, L1]], ...]`;
//! - `pmks`: PMKS's text format, one joint a line: `ground,input,R,0,0,tfft` (links, type,
//!   x, y, an optional angle in degrees, optional flags whose fourth says "driving input").
//!
//! Both tools name the frame `ground`, as scenes do. Revolute joints may join any number of
//! links (a scene joint with the same list); prismatic joints join two links and slide along
//! the joint's angle. Other joint types (Pyslvs `RP`, PMKS `RP` and `G`) are refused with
//! the line and column of the joint. Lengths are taken as millimetres (neither format has
//! units: the scene says so in a comment, change `[units] length` if they are not mm).

mod linkage;
pub(crate) mod pmks;
pub(crate) mod pyslvs;

pub use linkage::{Joint, JointKind, Linkage};

use crate::error::Result;
use crate::scene::Source;
use linkage::GROUND;

/// Which format a file is in: Pyslvs's expression starts with `M[` (after comments and
/// white space); anything else is read as PMKS text.
pub fn read(source: &Source) -> Result<Linkage> {
    let first = source
        .text
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty() && !l.starts_with('#'));
    let mut linkage = if first.is_some_and(|l| l.starts_with("M[")) {
        pyslvs::parse(source)?
    } else {
        pmks::parse(source)?
    };
    // A slide on the ground: the ground carries the guide (the same motion either way).
    for j in &mut linkage.joints {
        if matches!(j.kind, JointKind::Prismatic { .. })
            && j.links.len() == 2
            && j.links[1] == GROUND
        {
            j.links.swap(0, 1);
        }
    }
    linkage.check(source)?;
    Ok(linkage)
}
