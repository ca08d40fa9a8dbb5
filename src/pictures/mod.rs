//! Pictures of results: diagrams, drawings of the mechanism, and the HTML report.
//!
//! Everything drawn by mechdiff goes through this module, so that every picture has the same
//! look, the same bundled font and the same checks.
//!
//! # The API other rooms draw with (stable)
//!
//! - [`Diagram`]: panels of y(x) curves sharing one x axis (the drive position), one panel per
//!   quantity, axis labels with units, vertical [`Marker`]s (dead and limit positions, segment
//!   boundaries), and optional [`Polar`] panels (a vector's tip over the sweep: joint reactions,
//!   shaking force). Drawn by plotters' SVG backend with the bundled font.
//!   [`Diagram::to_svg`], [`Diagram::write_svg`], [`Diagram::write_png`].
//! - [`Drawing`]: 2-D geometry in model units (m), framed automatically (equal scale on both
//!   axes, y up): polylines and polygons, circles, joints (named, with their exact position in
//!   `data-x`/`data-y`), hatched ground, slider blocks and guides, labels, traced paths.
//!   [`Drawing::to_svg`], [`Drawing::write_svg`], [`Drawing::write_png`], [`Drawing::frame`].
//! - [`raster::render`] turns any SVG into pixels (resvg, with the bundled font), and
//!   [`raster::write_png`] writes it as PNG.
//!
//! ```
//! use mechdiff::pictures::{Diagram, Drawing, Marker, MarkerKind, Panel, Style};
//! let phi: Vec<f64> = (0..=36).map(|k| k as f64 * 10.0).collect();
//! let s: Vec<[f64; 2]> = phi.iter().map(|&p| [p, p.to_radians().sin()]).collect();
//! let diagram = Diagram::new("follower", "φ [deg]")
//!     .panel(Panel::new("s [mm]").series("s", s))
//!     .marker(Marker::new(90.0, "limit", MarkerKind::Limit));
//! let svg = diagram.to_svg().unwrap();
//! assert!(svg.starts_with("<svg"));
//!
//! let drawing = Drawing::new("crank")
//!     .polyline(&[[0.0, 0.0], [0.1, 0.0]], Style::link())
//!     .ground([0.0, 0.0])
//!     .joint("O", [0.0, 0.0])
//!     .joint("A", [0.1, 0.0]);
//! let svg = drawing.to_svg();
//! assert!(svg.contains(r#"data-point="A""#));
//! let pixels = mechdiff::pictures::raster::render(&svg).unwrap();
//! assert!(pixels.width > 0);
//! ```
//!
//! Scenes are drawn by [`scene`] (the poses and how a mechanism is drawn) and [`run`] (the
//! diagram of every column, the drawings at the sketch pose and the `[plot]` positions with
//! the traced paths, all written to a folder); a whole run becomes one self-contained HTML
//! file in [`report`]. Long sweeps are drawn through `decimate` (never the CSV or JSON).

pub(crate) mod axis;
pub mod balancing;
pub mod cam;
pub(crate) mod curve;
pub(crate) mod decimate;
pub mod diagram;
pub(crate) mod drawing;
pub mod motion;
pub mod path;
pub mod raster;
pub mod report;
pub mod run;
pub mod scene;
pub mod study;
pub mod symbols;
pub mod synthesis;
pub(crate) mod vectors;

use std::path::Path;

use crate::error::Result;

pub use diagram::{Diagram, Marker, MarkerKind, Panel, Polar, Series};
pub use drawing::{Drawing, Frame, Style, VectorKind};

/// The font every picture is drawn with: DejaVu Sans (Bitstream Vera licence, see
/// `assets/fonts/LICENSE-DejaVu.txt`), bundled so that a fresh machine renders the same
/// picture.
pub const FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

/// The font's family name, as written in the SVG files.
pub const FONT_FAMILY: &str = "DejaVu Sans";

/// Writes `bytes` to `path` through [`crate::files::write_atomically`] (a reader never sees
/// half a picture; an input is never overwritten).
pub(crate) fn write_file(path: &Path, bytes: &[u8]) -> Result<()> {
    crate::files::write_atomically(path, |out| out.write_all(bytes))
}

pub(crate) use crate::escape::xml as escape;
