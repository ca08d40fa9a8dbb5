//! `[plot]`: what the pictures of a run show (see the `pictures` module).
//!
//! This module only translates the section: point names are checked here; the drive
//! positions and the panels are checked against the run's own sweep and columns when the
//! pictures are drawn (a `[sweep] of` scene knows its drive positions only then), with the
//! places kept here for the messages.

use serde::Deserialize;
use toml::Spanned;

use crate::error::{Location, Result};

use super::context::{Context, Geometry};
use super::model::DriveKind;
pub use super::model::Plot;
use super::values::{Name, Number};

/// `[plot]` as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlotDef {
    /// Points whose paths over the sweep are drawn (coupler curves).
    pub trace: Option<Spanned<Vec<Name>>>,
    /// Drive positions (drive unit) at which the mechanism is drawn, inside the sweep.
    pub positions: Option<Spanned<Vec<Spanned<f64>>>>,
    /// The diagram's panels: output names (every column of the output) or column names.
    pub panels: Option<Spanned<Vec<Name>>>,
    /// Points whose velocity and acceleration arrows are drawn in the still drawings.
    pub vectors: Option<Spanned<Vec<Name>>>,
}

/// Checks `[plot]`: every traced point and every point with vectors exists, no list is
/// empty, every position is a finite number.
pub(crate) fn resolve(
    cx: &Context,
    def: Option<&Spanned<PlotDef>>,
    geometry: &Geometry,
    drive: DriveKind,
) -> Result<Plot> {
    let Some(def) = def else {
        return Ok(Plot::default());
    };
    let d = def.get_ref();
    let nonempty = |what: &str, empty: bool, at: Location| -> Result<()> {
        if empty {
            return Err(crate::Error::Invalid {
                location: at,
                message: format!("`[plot] {what}` is empty: name at least one, or leave it out"),
            });
        }
        Ok(())
    };
    let trace = match &d.trace {
        None => None,
        Some(list) => {
            nonempty("trace", list.get_ref().is_empty(), cx.at(list))?;
            let mut names = Vec::new();
            for name in list.get_ref() {
                let point = cx.point(name, geometry.names, "`[plot] trace`")?;
                names.push(point.to_owned());
            }
            Some(names)
        }
    };
    let mut positions = Vec::new();
    if let Some(list) = &d.positions {
        nonempty("positions", list.get_ref().is_empty(), cx.at(list))?;
        for value in list.get_ref() {
            // `[plot]` positions are numbers only (no formulas).
            let written = Spanned::new(value.span(), Number::Literal(*value.get_ref()));
            let si = cx.number(&written, "a `[plot]` position", drive.dimension())?;
            positions.push((si, cx.at(value)));
        }
    }
    let panels = match &d.panels {
        None => None,
        Some(list) => {
            nonempty("panels", list.get_ref().is_empty(), cx.at(list))?;
            Some(
                list.get_ref()
                    .iter()
                    .map(|n| (n.get_ref().clone(), cx.at(n)))
                    .collect(),
            )
        }
    };
    let vectors = match &d.vectors {
        None => None,
        Some(list) => {
            nonempty("vectors", list.get_ref().is_empty(), cx.at(list))?;
            let mut names = Vec::new();
            for name in list.get_ref() {
                let point = cx.point(name, geometry.names, "`[plot] vectors`")?;
                names.push(point.to_owned());
            }
            Some((names, cx.at(list)))
        }
    };
    Ok(Plot {
        trace,
        positions,
        panels,
        vectors,
    })
}
