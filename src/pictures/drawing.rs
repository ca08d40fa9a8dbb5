//! [`Drawing`]: 2-D geometry in model units, framed automatically, written as SVG.
//!
//! Coordinates are in the model's units (m), y up. The frame (a uniform scale and an offset,
//! y flipped) is chosen so that every shape fits inside the picture with a margin; it is
//! written on the `<svg>` element (`data-scale`, `data-origin-x`, `data-origin-y`: pixel
//! `px = origin_x + scale·x`, `py = origin_y − scale·y`) so that a reader can map pixels back
//! to the model. Joints carry their exact model position in `data-x`/`data-y` and their name
//! in `data-point`.

use std::f64::consts::FRAC_1_SQRT_2;
use std::fmt::Write as _;
use std::path::Path;

use super::{FONT_FAMILY, axis, escape, raster, write_file};
use crate::error::Result;

/// How a line or area is painted.
#[derive(Debug, Clone, PartialEq)]
pub struct Style {
    /// Stroke colour (any SVG colour: `"#1f77b4"`, `"black"`).
    pub stroke: String,
    /// Stroke width in pixels.
    pub width: f64,
    /// Fill colour, if filled.
    pub fill: Option<String>,
    /// Dashed stroke.
    pub dashed: bool,
}

impl Style {
    /// A plain stroke of `colour` and `width` pixels.
    pub fn stroke(colour: &str, width: f64) -> Self {
        Style {
            stroke: colour.to_owned(),
            width,
            fill: None,
            dashed: false,
        }
    }

    /// A link drawn as a bar: dark blue, 4 px.
    pub fn link() -> Self {
        Style::stroke("#1f4e79", 4.0)
    }

    /// A traced path (coupler curve): orange, 1.5 px.
    pub fn path() -> Self {
        Style::stroke("#d95f02", 1.5)
    }

    /// A thin construction line: grey, dashed.
    pub fn construction() -> Self {
        Style {
            dashed: true,
            ..Style::stroke("#888888", 1.0)
        }
    }

    /// This style, filled with `colour`.
    pub fn filled(mut self, colour: &str) -> Self {
        self.fill = Some(colour.to_owned());
        self
    }

    fn attributes(&self) -> String {
        let fill = self.fill.as_deref().unwrap_or("none");
        let dash = if self.dashed {
            r#" stroke-dasharray="6 4""#
        } else {
            ""
        };
        format!(
            r#"stroke="{}" stroke-width="{}" fill="{}" stroke-linejoin="round" stroke-linecap="round"{dash}"#,
            escape(&self.stroke),
            self.width,
            escape(fill)
        )
    }
}

/// One shape of a drawing, in model units.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// An open or closed polyline; `class` names it in the SVG (`link`, `path`, ...).
    Polyline {
        /// Vertices.
        points: Vec<[f64; 2]>,
        /// Closed (a polygon).
        closed: bool,
        /// Paint.
        style: Style,
        /// SVG class.
        class: String,
    },
    /// A circle of a radius in model units (a gear's pitch circle).
    Circle {
        /// Centre.
        center: [f64; 2],
        /// Radius (m).
        radius: f64,
        /// Paint.
        style: Style,
    },
    /// A joint: a small ring at `at`, named.
    Joint {
        /// Point name.
        name: String,
        /// Position.
        at: [f64; 2],
    },
    /// A fixed pivot's ground symbol: a hatched base under `at`.
    Ground {
        /// The pivot.
        at: [f64; 2],
    },
    /// A straight guide fixed to the ground from `from` to `to`, hatched on its right side.
    Guide {
        /// Start.
        from: [f64; 2],
        /// End.
        to: [f64; 2],
    },
    /// A slider block centred at `center`, its long side along `direction` (radians).
    Block {
        /// Centre.
        center: [f64; 2],
        /// Direction of travel (rad, counter-clockwise from +x).
        direction: f64,
    },
    /// A text label next to `at`.
    Label {
        /// Anchor.
        at: [f64; 2],
        /// Text.
        text: String,
        /// The direction (model axes, y up) the label is set off in from its anchor: away
        /// from the links at the anchor.
        toward: [f64; 2],
    },
    /// A centre of mass: the conventional quartered circle (two opposite quarters black).
    MassCentre {
        /// Position.
        at: [f64; 2],
    },
    /// An arrow from `at` to `at + value·scale` (a velocity or an acceleration).
    Arrow {
        /// Tail.
        at: [f64; 2],
        /// The vector in its own unit (m/s, m/s²).
        value: [f64; 2],
        /// Which quantity: its colour and legend entry.
        kind: VectorKind,
    },
}

/// What an arrow of a drawing shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VectorKind {
    /// A velocity (m/s): green.
    Velocity,
    /// An acceleration (m/s²): magenta.
    Acceleration,
}

impl VectorKind {
    fn colour(self) -> &'static str {
        match self {
            VectorKind::Velocity => "#2ca02c",
            VectorKind::Acceleration => "#c2185b",
        }
    }

    fn words(self) -> (&'static str, &'static str) {
        match self {
            VectorKind::Velocity => ("v", "m/s"),
            VectorKind::Acceleration => ("a", "m/s²"),
        }
    }
}

/// Colours of traced paths, in order (the Dark2 palette, distinct from links and joints).
const PATH_COLOURS: [&str; 6] = [
    "#d95f02", "#7570b3", "#1b9e77", "#e7298a", "#66a61e", "#a6761d",
];

/// The mapping from model units to pixels chosen by the automatic framing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// Pixels per model unit.
    pub scale: f64,
    /// Pixel x of the model origin.
    pub origin_x: f64,
    /// Pixel y of the model origin.
    pub origin_y: f64,
    /// Picture width (px).
    pub width: f64,
    /// Picture height (px).
    pub height: f64,
}

impl Frame {
    /// The pixel position of model point `p`.
    pub fn pixel(&self, p: [f64; 2]) -> [f64; 2] {
        [
            self.origin_x + self.scale * p[0],
            self.origin_y - self.scale * p[1],
        ]
    }

    /// The model point at pixel `q`.
    pub fn model(&self, q: [f64; 2]) -> [f64; 2] {
        [
            (q[0] - self.origin_x) / self.scale,
            (self.origin_y - q[1]) / self.scale,
        ]
    }
}

/// A drawing: shapes in model units, a title, and a picture size.
#[derive(Debug, Clone, PartialEq)]
pub struct Drawing {
    /// Printed at the top left.
    pub title: String,
    /// The shapes, drawn in order (later on top), except that joints and labels are always
    /// drawn last.
    pub shapes: Vec<Shape>,
    /// Picture width (px).
    pub width: u32,
    /// Picture height (px).
    pub height: u32,
    /// Extra points the frame must include (e.g. the whole sweep's extent, so that every
    /// frame of an animation shares one framing).
    pub extent: Vec<[f64; 2]>,
    /// Animation bindings: shape index and key, written as `data-bind` (see
    /// [`Drawing::bind`]).
    pub binds: Vec<(usize, String)>,
    /// The length unit the axes and the scale bar are labelled in, and its size in model
    /// units (`("mm", 1e-3)`).
    pub unit: (String, f64),
    /// Model length of an arrow per unit of each vector kind (m per m/s, m per m/s²).
    pub vector_scales: Vec<(VectorKind, f64)>,
}

/// Margin around the framed shapes, as a fraction of the picture's smaller side.
const MARGIN: f64 = 0.06;
/// Room for the title at the top (px).
const TITLE_HEIGHT: f64 = 24.0;
/// Size of ground symbols, slider blocks and joints, as a fraction of the shapes' extent.
const SYMBOL: f64 = 0.035;

impl Drawing {
    /// An empty drawing, 800 × 600 px.
    pub fn new(title: &str) -> Self {
        Drawing {
            title: title.to_owned(),
            shapes: Vec::new(),
            width: 800,
            height: 600,
            extent: Vec::new(),
            binds: Vec::new(),
            unit: ("m".to_owned(), 1.0),
            vector_scales: Vec::new(),
        }
    }

    /// Labels the axes and the scale bar in `symbol`, a unit of `size` model units.
    pub fn unit(mut self, symbol: &str, size: f64) -> Self {
        if size.is_finite() && size > 0.0 {
            self.unit = (symbol.to_owned(), size);
        }
        self
    }

    /// Adds a centre of mass at `at`, drawn as a quartered circle.
    pub fn mass_centre(mut self, at: [f64; 2]) -> Self {
        self.shapes.push(Shape::MassCentre { at });
        self
    }

    /// Adds an arrow of `kind` from `at` showing `value` (m/s or m/s²), drawn `scale` model
    /// units long per unit of the quantity; the legend states the scale. The first scale
    /// given for a kind holds for every arrow of that kind, so that arrows compare.
    pub fn vector(mut self, kind: VectorKind, at: [f64; 2], value: [f64; 2], scale: f64) -> Self {
        if !self.vector_scales.iter().any(|(k, _)| *k == kind) && scale.is_finite() && scale > 0.0 {
            self.vector_scales.push((kind, scale));
        }
        self.shapes.push(Shape::Arrow { at, value, kind });
        self
    }

    /// The model length of one unit of `kind`, if any arrow of that kind was added.
    fn vector_scale(&self, kind: VectorKind) -> Option<f64> {
        self.vector_scales
            .iter()
            .find(|(k, _)| *k == kind)
            .map(|(_, s)| *s)
    }

    /// Adds a text label beside `at`, set off in the direction `toward` (model axes).
    pub fn label_toward(mut self, at: [f64; 2], text: &str, toward: [f64; 2]) -> Self {
        self.shapes.push(Shape::Label {
            at,
            text: text.to_owned(),
            toward,
        });
        self
    }

    /// The picture's size in pixels.
    pub fn size(mut self, width: u32, height: u32) -> Self {
        self.width = width.max(64);
        self.height = height.max(64);
        self
    }

    /// Adds an open polyline (a link drawn as a bar, or a chain of bars).
    pub fn polyline(mut self, points: &[[f64; 2]], style: Style) -> Self {
        self.shapes.push(Shape::Polyline {
            points: points.to_vec(),
            closed: false,
            style,
            class: "link".to_owned(),
        });
        self
    }

    /// Adds a closed polygon (a link with three or more joints).
    pub fn polygon(mut self, points: &[[f64; 2]], style: Style) -> Self {
        self.shapes.push(Shape::Polyline {
            points: points.to_vec(),
            closed: true,
            style,
            class: "link".to_owned(),
        });
        self
    }

    /// Adds the path traced by point `name` (a coupler curve), each path in its own colour,
    /// named in the legend.
    pub fn path(mut self, name: &str, points: &[[f64; 2]]) -> Self {
        let index = self.paths().len();
        self.shapes.push(Shape::Polyline {
            points: points.to_vec(),
            closed: false,
            style: Style {
                stroke: PATH_COLOURS[index % PATH_COLOURS.len()].to_owned(),
                ..Style::path()
            },
            class: format!("path path-{}", escape(name)),
        });
        self
    }

    /// Adds a circle of `radius` model units (a gear's pitch circle).
    pub fn circle(mut self, center: [f64; 2], radius: f64, style: Style) -> Self {
        self.shapes.push(Shape::Circle {
            center,
            radius,
            style,
        });
        self
    }

    /// Adds a joint named `name` at `at`.
    pub fn joint(mut self, name: &str, at: [f64; 2]) -> Self {
        self.shapes.push(Shape::Joint {
            name: name.to_owned(),
            at,
        });
        self
    }

    /// Adds a ground symbol (hatched base) under the fixed pivot `at`.
    pub fn ground(mut self, at: [f64; 2]) -> Self {
        self.shapes.push(Shape::Ground { at });
        self
    }

    /// Adds a fixed straight guide (hatched on its right side) from `from` to `to`.
    pub fn guide(mut self, from: [f64; 2], to: [f64; 2]) -> Self {
        self.shapes.push(Shape::Guide { from, to });
        self
    }

    /// Adds a slider block at `center` travelling along `direction` (rad).
    pub fn block(mut self, center: [f64; 2], direction: f64) -> Self {
        self.shapes.push(Shape::Block { center, direction });
        self
    }

    /// Adds a text label beside `at`.
    pub fn label(mut self, at: [f64; 2], text: &str) -> Self {
        self.shapes.push(Shape::Label {
            at,
            text: text.to_owned(),
            toward: [1.0, 1.0],
        });
        self
    }

    /// Tags the shape added last with `key`, written as its `data-bind` attribute: the HTML
    /// report moves tagged shapes from frame to frame (`"p i j k"`: a polyline through points
    /// i, j, k; `"c i"`: a circle at point i; `"t i"`: a label at point i; `"b i a b"`: a block at
    /// point i along the line a → b).
    pub fn bind(mut self, key: &str) -> Self {
        if let Some(last) = self.shapes.len().checked_sub(1) {
            self.binds.push((last, key.to_owned()));
        }
        self
    }

    /// Makes the frame include these points too (see [`Drawing::extent`]).
    pub fn include(mut self, points: &[[f64; 2]]) -> Self {
        self.extent.extend_from_slice(points);
        self
    }

    /// The extent of the geometry: the bounding box `[min, max]` of every vertex, circle,
    /// joint and extra extent point (symbols excluded), or a unit box if there is none.
    pub fn bounds(&self) -> [[f64; 2]; 2] {
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        let mut add = |p: [f64; 2], r: f64| {
            if p[0].is_finite() && p[1].is_finite() && r.is_finite() {
                for k in 0..2 {
                    lo[k] = lo[k].min(p[k] - r);
                    hi[k] = hi[k].max(p[k] + r);
                }
            }
        };
        for shape in &self.shapes {
            match shape {
                Shape::Polyline { points, .. } => points.iter().for_each(|&p| add(p, 0.0)),
                Shape::Circle { center, radius, .. } => add(*center, radius.abs()),
                Shape::Joint { at, .. }
                | Shape::Ground { at }
                | Shape::Label { at, .. }
                | Shape::MassCentre { at } => add(*at, 0.0),
                Shape::Arrow { at, value, kind } => {
                    add(*at, 0.0);
                    if let Some(scale) = self.vector_scale(*kind) {
                        add([at[0] + scale * value[0], at[1] + scale * value[1]], 0.0);
                    }
                }
                Shape::Guide { from, to } => {
                    add(*from, 0.0);
                    add(*to, 0.0)
                }
                Shape::Block { center, .. } => add(*center, 0.0),
            }
        }
        for &p in &self.extent {
            add(p, 0.0);
        }
        if lo[0] > hi[0] {
            return [[-0.5, -0.5], [0.5, 0.5]];
        }
        [lo, hi]
    }

    /// The size of symbols (ground, blocks, joints) in model units.
    fn symbol(&self) -> f64 {
        let [lo, hi] = self.bounds();
        let size = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        if size > 0.0 { SYMBOL * size } else { 0.05 }
    }

    /// The framing: a uniform scale and an offset that put the geometry and its symbols
    /// inside the picture with a margin, centred.
    pub fn frame(&self) -> Frame {
        let [mut lo, mut hi] = self.bounds();
        let s = self.symbol();
        // Ground hatching hangs below its pivot; blocks and joints stick out by their size.
        for k in 0..2 {
            lo[k] -= 2.5 * s;
            hi[k] += 1.5 * s;
        }
        let (w, h) = (f64::from(self.width), f64::from(self.height));
        let margin = MARGIN * w.min(h);
        let (aw, ah) = (w - 2.0 * margin, h - 2.0 * margin - TITLE_HEIGHT);
        let (dx, dy) = ((hi[0] - lo[0]).max(1e-300), (hi[1] - lo[1]).max(1e-300));
        let scale = (aw / dx).min(ah / dy);
        let cx = 0.5 * (lo[0] + hi[0]);
        let cy = 0.5 * (lo[1] + hi[1]);
        Frame {
            scale,
            origin_x: 0.5 * w - scale * cx,
            origin_y: TITLE_HEIGHT + margin + 0.5 * ah + scale * cy,
            width: w,
            height: h,
        }
    }

    /// The drawing as a standalone SVG document.
    pub fn to_svg(&self) -> String {
        let frame = self.frame();
        let mut out = String::new();
        let _ = write!(
            out,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" data-scale="{}" data-origin-x="{}" data-origin-y="{}" font-family="{FONT_FAMILY}">"#,
            frame.scale,
            frame.origin_x,
            frame.origin_y,
            w = self.width,
            h = self.height,
        );
        out.push('\n');
        out.push_str(&self.body(&frame));
        out.push_str("</svg>\n");
        out
    }

    /// The shapes as SVG elements (no `<svg>` wrapper) in the given frame: for embedding
    /// several drawings or animation frames in one document.
    pub fn body(&self, frame: &Frame) -> String {
        let mut out = String::new();
        let _ = writeln!(
            out,
            r#"<rect width="{}" height="{}" fill="white"/>"#,
            frame.width, frame.height
        );
        // A long title gets a smaller font, so that it fits (DejaVu Sans: ~0.62 em per
        // character on average).
        let characters = self.title.chars().count().max(1) as f64;
        let size = ((frame.width - 16.0) / (0.62 * characters)).clamp(7.0, 14.0);
        let _ = writeln!(
            out,
            r#"<text x="8" y="18" font-size="{size:.1}" fill="black">{}</text>"#,
            escape(&self.title)
        );
        self.grid(&mut out, frame);
        self.legend(&mut out, frame);
        let s = self.symbol();
        let px = |p: [f64; 2]| frame.pixel(p);
        let (last, first): (Vec<_>, Vec<_>) = self
            .shapes
            .iter()
            .enumerate()
            .partition(|(_, shape)| matches!(shape, Shape::Joint { .. } | Shape::Label { .. }));
        for (k, shape) in first.into_iter().chain(last) {
            let bind = self
                .binds
                .iter()
                .find(|(i, _)| *i == k)
                .map_or_else(String::new, |(_, key)| {
                    format!(r#" data-bind="{}""#, escape(key))
                });
            match shape {
                Shape::Polyline {
                    points,
                    closed,
                    style,
                    class,
                } => {
                    let tag = if *closed { "polygon" } else { "polyline" };
                    let _ = writeln!(
                        out,
                        r#"<{tag} class="{class}"{bind} points="{}" {}/>"#,
                        points_attribute(points.iter().map(|&p| px(p))),
                        style.attributes()
                    );
                }
                Shape::Circle {
                    center,
                    radius,
                    style,
                } => {
                    let [x, y] = px(*center);
                    let _ = writeln!(
                        out,
                        r#"<circle class="pitch"{bind} cx="{x}" cy="{y}" r="{}" {}/>"#,
                        radius.abs() * frame.scale,
                        style.attributes()
                    );
                }
                Shape::Joint { name, at } => {
                    let [x, y] = px(*at);
                    let _ = writeln!(
                        out,
                        r##"<circle class="joint"{bind} data-point="{}" data-x="{:e}" data-y="{:e}" cx="{x}" cy="{y}" r="{}" stroke="#1f4e79" stroke-width="2" fill="white"/>"##,
                        escape(name),
                        at[0],
                        at[1],
                        (0.35 * s * frame.scale).clamp(3.0, 7.0),
                    );
                }
                Shape::Label { at, text, toward } => {
                    let [x, y] = px(*at);
                    let length = toward[0].hypot(toward[1]);
                    let (ux, uy) = if length > 0.0 && length.is_finite() {
                        (toward[0] / length, -toward[1] / length)
                    } else {
                        (FRAC_1_SQRT_2, -FRAC_1_SQRT_2)
                    };
                    // The text's box (13 px font, ~0.62 em per character) is set off 10 px
                    // from the anchor along the direction, its near side towards the anchor.
                    let width = 0.62 * 13.0 * text.chars().count() as f64;
                    let (cx, cy) = (x + ux * (10.0 + 0.5 * width), y + uy * 16.0);
                    let _ = writeln!(
                        out,
                        r#"<text class="label"{bind} x="{:.3}" y="{:.3}" font-size="13" fill="black">{}</text>"#,
                        // Inside the picture, clear of its white border.
                        (cx - 0.5 * width).clamp(6.0, (frame.width - 6.0 - width).max(6.0)),
                        (cy + 4.5).clamp(TITLE_HEIGHT + 12.0, frame.height - 6.0),
                        escape(text)
                    );
                }
                Shape::MassCentre { at } => {
                    mass_centre(&mut out, px(*at), (0.5 * s * frame.scale).clamp(4.0, 9.0))
                }
                Shape::Arrow { at, value, kind } => {
                    if let Some(scale) = self.vector_scale(*kind) {
                        let tip = [at[0] + scale * value[0], at[1] + scale * value[1]];
                        arrow(&mut out, px(*at), px(tip), kind.colour());
                    }
                }
                Shape::Ground { at } => ground(&mut out, px(*at), s * frame.scale),
                Shape::Guide { from, to } => guide(&mut out, px(*from), px(*to), s * frame.scale),
                Shape::Block { center, direction } => {
                    block(&mut out, px(*center), *direction, s * frame.scale, &bind)
                }
            }
        }
        out
    }

    /// Writes the SVG to `path` (through a temporary file).
    pub fn write_svg(&self, path: &Path) -> Result<()> {
        write_file(path, self.to_svg().as_bytes())
    }

    /// Renders the SVG with the bundled font and writes it as PNG to `path`.
    pub fn write_png(&self, path: &Path) -> Result<()> {
        raster::write_png(&self.to_svg(), path)
    }
}

impl Drawing {
    /// The traced paths: their names and colours.
    fn paths(&self) -> Vec<(&str, &str)> {
        self.shapes
            .iter()
            .filter_map(|shape| match shape {
                Shape::Polyline { class, style, .. } => class
                    .strip_prefix("path path-")
                    .map(|name| (name, style.stroke.as_str())),
                _ => None,
            })
            .collect()
    }

    /// A light grid at round multiples of the unit with its values along the left and
    /// bottom edges, darker axes through the origin where it is in view, and a scale bar of
    /// a round length (1, 2 or 5 × 10ⁿ units, at most a fifth of the width) at the bottom
    /// left; all inside a 6 px inset, so the border stays white.
    fn grid(&self, out: &mut String, frame: &Frame) {
        let (unit, size) = (&self.unit.0, self.unit.1);
        let (left, right) = (6.0, frame.width - 6.0);
        let (top, bottom) = (TITLE_HEIGHT + 4.0, frame.height - 6.0);
        let lo = frame.model([left, bottom]);
        let hi = frame.model([right, top]);
        let (x_range, y_range) = (lo[0] / size..hi[0] / size, lo[1] / size..hi[1] / size);
        let step_ticks = axis::ticks(&x_range, 12);
        let step = match step_ticks.as_slice() {
            [a, b, ..] => b - a,
            _ => return,
        };
        let ys = axis::ticks(&y_range, 1_000)
            .into_iter()
            .filter(|v| ((v / step).round() * step - v).abs() <= 1e-9 * step)
            .collect::<Vec<_>>();
        out.push_str("<g class=\"grid\" font-size=\"9\" fill=\"#888888\">\n");
        for &v in &step_ticks {
            let x = frame.pixel([v * size, 0.0])[0];
            let colour = if v == 0.0 { "#aaaaaa" } else { "#eeeeee" };
            let _ = write!(
                out,
                r#"<line x1="{x:.3}" y1="{top:.3}" x2="{x:.3}" y2="{bottom:.3}" stroke="{colour}" stroke-width="1"/>"#
            );
            // A value only where it fits inside the inset (9 px font, ~0.62 em a character).
            let text = number(v);
            if x + 2.0 + 5.6 * text.chars().count() as f64 <= right {
                let _ = write!(
                    out,
                    r#"<text x="{:.3}" y="{:.3}">{text}</text>"#,
                    x + 2.0,
                    bottom - 3.0
                );
            }
            out.push('\n');
        }
        for &v in &ys {
            let y = frame.pixel([0.0, v * size])[1];
            let colour = if v == 0.0 { "#aaaaaa" } else { "#eeeeee" };
            let _ = write!(
                out,
                r#"<line x1="{left:.3}" y1="{y:.3}" x2="{right:.3}" y2="{y:.3}" stroke="{colour}" stroke-width="1"/>"#
            );
            if y - 11.0 >= top {
                let _ = write!(
                    out,
                    r#"<text x="{:.3}" y="{:.3}">{}</text>"#,
                    left + 2.0,
                    y - 2.0,
                    number(v)
                );
            }
            out.push('\n');
        }
        out.push_str("</g>\n");
        let length = axis::round_length(0.2 * (x_range.end - x_range.start));
        let pixels = length * size * frame.scale;
        let (x0, y0) = (left + 30.0, bottom - 18.0);
        let _ = writeln!(
            out,
            r#"<g class="scale-bar" data-length="{length}" data-unit="{}"><line x1="{x0:.3}" y1="{y0:.3}" x2="{:.3}" y2="{y0:.3}" stroke="black" stroke-width="2"/><line x1="{x0:.3}" y1="{:.3}" x2="{x0:.3}" y2="{:.3}" stroke="black" stroke-width="1.5"/><line x1="{:.3}" y1="{:.3}" x2="{:.3}" y2="{:.3}" stroke="black" stroke-width="1.5"/><text x="{:.3}" y="{:.3}" font-size="11" text-anchor="middle" fill="black">{} {}</text></g>"#,
            escape(unit),
            x0 + pixels,
            y0 - 4.0,
            y0 + 4.0,
            x0 + pixels,
            y0 - 4.0,
            x0 + pixels,
            y0 + 4.0,
            x0 + 0.5 * pixels,
            y0 - 6.0,
            number(length),
            escape(unit),
        );
    }

    /// The legend at the top right: a swatch and the name of each traced path, and the scale
    /// of each kind of arrow.
    fn legend(&self, out: &mut String, frame: &Frame) {
        let mut entries: Vec<(String, String)> = self
            .paths()
            .into_iter()
            .map(|(name, colour)| (format!("path of {name}"), colour.to_owned()))
            .collect();
        for (kind, scale) in &self.vector_scales {
            let (symbol, unit) = kind.words();
            let length = self.unit.1;
            entries.push((
                format!(
                    "{symbol}: 1 {unit} ≙ {} {}",
                    number(scale / length),
                    self.unit.0
                ),
                kind.colour().to_owned(),
            ));
        }
        if entries.is_empty() {
            return;
        }
        let longest = entries
            .iter()
            .map(|(t, _)| t.chars().count())
            .max()
            .unwrap_or(0);
        let width = 0.62 * 11.0 * longest as f64 + 34.0;
        let x = frame.width - 8.0 - width;
        let mut y = TITLE_HEIGHT + 6.0;
        let _ = writeln!(
            out,
            r##"<g class="legend"><rect x="{x:.3}" y="{y:.3}" width="{width:.3}" height="{:.3}" fill="white" fill-opacity="0.85" stroke="#cccccc"/>"##,
            16.0 * entries.len() as f64 + 6.0
        );
        for (text, colour) in &entries {
            y += 16.0;
            let _ = writeln!(
                out,
                r#"<line x1="{:.3}" y1="{:.3}" x2="{:.3}" y2="{:.3}" stroke="{colour}" stroke-width="2.5"/><text x="{:.3}" y="{y:.3}" font-size="11" fill="black">{}</text>"#,
                x + 6.0,
                y - 4.0,
                x + 24.0,
                y - 4.0,
                x + 28.0,
                escape(text)
            );
        }
        out.push_str("</g>\n");
    }
}

/// A grid or scale value: at most six significant digits, no trailing zeros.
fn number(v: f64) -> String {
    match format!("{v:.5e}").parse::<f64>() {
        Ok(r) => (r + 0.0).to_string(),
        Err(_) => v.to_string(),
    }
}

/// The conventional centre-of-mass symbol at pixel `p`, radius `r`: a ring with the first
/// and third quarters filled black.
fn mass_centre(out: &mut String, [x, y]: [f64; 2], r: f64) {
    let _ = writeln!(
        out,
        r#"<g class="mass-centre"><circle cx="{x:.3}" cy="{y:.3}" r="{r:.3}" fill="white" stroke="black" stroke-width="1.2"/><path d="M{x:.3},{y:.3} L{:.3},{y:.3} A{r:.3},{r:.3} 0 0 0 {x:.3},{:.3} Z M{x:.3},{y:.3} L{:.3},{y:.3} A{r:.3},{r:.3} 0 0 0 {x:.3},{:.3} Z" fill="black"/></g>"#,
        x + r,
        y - r,
        x - r,
        y + r,
    );
}

/// An arrow from pixel `a` to pixel `b` with a filled head.
fn arrow(out: &mut String, a: [f64; 2], b: [f64; 2], colour: &str) {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let length = dx.hypot(dy);
    if !(length.is_finite() && length > 0.5) {
        return;
    }
    let (ux, uy) = (dx / length, dy / length);
    let head = 9.0_f64.min(0.5 * length);
    let (bx, by) = (b[0] - ux * head, b[1] - uy * head);
    let _ = writeln!(
        out,
        r#"<g class="vector" stroke="{colour}" fill="{colour}"><line x1="{:.3}" y1="{:.3}" x2="{bx:.3}" y2="{by:.3}" stroke-width="2"/><polygon points="{:.3},{:.3} {:.3},{:.3} {:.3},{:.3}"/></g>"#,
        a[0],
        a[1],
        b[0],
        b[1],
        bx - 0.4 * head * uy,
        by + 0.4 * head * ux,
        bx + 0.4 * head * uy,
        by - 0.4 * head * ux,
    );
}

/// `x,y x,y ...` with pixel coordinates, skipping non-finite points.
fn points_attribute(points: impl Iterator<Item = [f64; 2]>) -> String {
    let mut out = String::new();
    for [x, y] in points.filter(|p| p[0].is_finite() && p[1].is_finite()) {
        let _ = write!(out, "{x:.3},{y:.3} ");
    }
    out.pop();
    out
}

/// A triangle under the pivot at pixel `p` on a hatched base, `s` pixels across.
fn ground(out: &mut String, [x, y]: [f64; 2], s: f64) {
    let (h, w) = (1.6 * s, 1.2 * s);
    let _ = writeln!(
        out,
        r##"<g class="ground"><polygon points="{x:.3},{y:.3} {:.3},{:.3} {:.3},{:.3}" fill="#dddddd" stroke="black" stroke-width="1"/>"##,
        x - w,
        y + h,
        x + w,
        y + h
    );
    let (x0, x1, yb) = (x - 1.6 * w, x + 1.6 * w, y + h);
    let _ = writeln!(
        out,
        r#"<line x1="{x0:.3}" y1="{yb:.3}" x2="{x1:.3}" y2="{yb:.3}" stroke="black" stroke-width="1.5"/>"#
    );
    hatch(out, [x0, yb], [x1, yb], 0.5 * s);
    out.push_str("</g>\n");
}

/// Short hatch strokes below (to the right of) the segment `a → b`, `depth` pixels long.
fn hatch(out: &mut String, a: [f64; 2], b: [f64; 2], depth: f64) {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let length = dx.hypot(dy);
    if length < 1.0 || depth <= 0.0 {
        return;
    }
    let (ux, uy) = (dx / length, dy / length);
    // In pixel space (y down), (−uy, ux) points to the right of the direction of travel.
    let (nx, ny) = (-uy, ux);
    let count = (length / (0.8 * depth)).floor().clamp(1.0, 400.0) as usize;
    for k in 0..=count {
        let t = length * k as f64 / count as f64;
        let (x, y) = (a[0] + ux * t, a[1] + uy * t);
        let _ = writeln!(
            out,
            r#"<line x1="{x:.3}" y1="{y:.3}" x2="{:.3}" y2="{:.3}" stroke="black" stroke-width="0.8"/>"#,
            x + depth * (nx - ux),
            y + depth * (ny - uy),
        );
    }
}

/// A fixed guide: a line with hatching on one side.
fn guide(out: &mut String, a: [f64; 2], b: [f64; 2], s: f64) {
    let _ = writeln!(
        out,
        r#"<g class="guide"><line x1="{:.3}" y1="{:.3}" x2="{:.3}" y2="{:.3}" stroke="black" stroke-width="1.5"/>"#,
        a[0], a[1], b[0], b[1]
    );
    hatch(out, a, b, 0.5 * s);
    out.push_str("</g>\n");
}

/// A slider block: a rectangle `2s × 1.2s` pixels centred at `c`, its long side along
/// `direction` (model angle, counter-clockwise; pixel y is down).
fn block(out: &mut String, [x, y]: [f64; 2], direction: f64, s: f64, bind: &str) {
    let degrees = -direction.to_degrees();
    let (w, h) = (2.0 * s, 1.2 * s);
    let _ = writeln!(
        out,
        r##"<rect class="block"{bind} x="{:.3}" y="{:.3}" width="{w:.3}" height="{h:.3}" transform="rotate({degrees:.6} {x:.3} {y:.3})" fill="#f4d58d" stroke="black" stroke-width="1.2"/>"##,
        x - 0.5 * w,
        y - 0.5 * h,
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The frame maps the bounding box into the picture and back: the inverse of `pixel` is
    /// `model` to rounding (1e-12 relative: a few f64 operations).
    #[test]
    fn frame_maps_geometry_inside_the_picture_and_back() {
        let d = Drawing::new("t")
            .polyline(&[[-1.0, 2.0], [3.0, -0.5]], Style::link())
            .joint("A", [3.0, -0.5]);
        let f = d.frame();
        for p in [[-1.0, 2.0], [3.0, -0.5]] {
            let [x, y] = f.pixel(p);
            assert!(x > 0.0 && x < f.width && y > TITLE_HEIGHT && y < f.height);
            let back = f.model([x, y]);
            assert!((back[0] - p[0]).abs() < 1e-12 * 4.0);
            assert!((back[1] - p[1]).abs() < 1e-12 * 4.0);
        }
    }
}
