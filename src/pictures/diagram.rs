//! [`Diagram`]: panels of y(x) curves over the drive position, with markers and polar panels,
//! drawn by plotters' SVG backend with the bundled font.
//!
//! Every cartesian panel's plotting rectangle is written into the SVG as an invisible
//! `<rect class="plot-frame">` with its data range (`data-x0`, `data-x1`, `data-y0`,
//! `data-y1`): `data-x0` maps to its left edge and `data-x1` to its right edge, `data-y0` to
//! its bottom and `data-y1` to its top, linearly, so that the HTML report can draw a cursor at
//! a drive position. The curves are `<path class="curve">` elements of cubic Hermite segments
//! (with a series' exact slopes where it has them, see [`Series::slopes`]), drawn over the
//! grid and the markers and under the legend.

use std::fmt::Write as _;
use std::ops::Range;
use std::path::Path;
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::coord::ranged1d::{KeyPointHint, NoDefaultFormatting, ValueFormatter};
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::FontStyle;

use super::curve::{PixelMap, path_data};
use super::{FONT, FONT_FAMILY, axis, raster, write_file};
use crate::error::{Error, Result};

/// One curve: `[x, y]` points in drawing order; non-finite points break the curve.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend text.
    pub name: String,
    /// The points.
    pub points: Vec<[f64; 2]>,
    /// The exact slope dy/dx at each point (same length as `points`), if known: the curve is
    /// then drawn as cubic Hermite segments with these slopes (a non-finite slope, or none,
    /// is estimated from the neighbouring points).
    pub slopes: Option<Vec<f64>>,
}

impl Series {
    /// A curve named `name` through `points`, slopes unknown.
    pub fn new(name: &str, points: Vec<[f64; 2]>) -> Self {
        Series {
            name: name.to_owned(),
            points,
            slopes: None,
        }
    }
}

/// One panel: one quantity (one unit) against the shared x axis.
#[derive(Debug, Clone, PartialEq)]
pub struct Panel {
    /// The y axis label with its unit, e.g. `"a_C [m/s²]"`.
    pub y_label: String,
    /// The curves.
    pub series: Vec<Series>,
}

impl Panel {
    /// An empty panel labelled `y_label` (name and unit).
    pub fn new(y_label: &str) -> Self {
        Panel {
            y_label: y_label.to_owned(),
            series: Vec::new(),
        }
    }

    /// Adds a curve.
    pub fn series(mut self, name: &str, points: Vec<[f64; 2]>) -> Self {
        self.series.push(Series::new(name, points));
        self
    }

    /// Adds a curve with the exact slope dy/dx at each point (see [`Series::slopes`]).
    pub fn series_with_slopes(
        mut self,
        name: &str,
        points: Vec<[f64; 2]>,
        slopes: Vec<f64>,
    ) -> Self {
        self.series.push(Series {
            slopes: Some(slopes),
            ..Series::new(name, points)
        });
        self
    }
}

/// What a vertical marker marks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MarkerKind {
    /// A dead position (an output's velocity coefficient changes sign): red, dashed.
    Dead,
    /// A limit position (the mechanism cannot go further, or a toggle): purple, solid.
    Limit,
    /// A segment boundary (cam program segments, sweep pieces): grey, dashed.
    Boundary,
}

impl MarkerKind {
    fn colour(self) -> RGBColor {
        match self {
            MarkerKind::Dead => RGBColor(0xd6, 0x27, 0x28),
            MarkerKind::Limit => RGBColor(0x94, 0x67, 0xbd),
            MarkerKind::Boundary => RGBColor(0x88, 0x88, 0x88),
        }
    }
}

/// A vertical line at `x` across every cartesian panel, labelled in the first.
#[derive(Debug, Clone, PartialEq)]
pub struct Marker {
    /// Position on the x axis.
    pub x: f64,
    /// Short label, e.g. `"dead 67.98°"`.
    pub label: String,
    /// Colour and dash by kind.
    pub kind: MarkerKind,
}

impl Marker {
    /// A marker at `x`.
    pub fn new(x: f64, label: &str, kind: MarkerKind) -> Self {
        Marker {
            x,
            label: label.to_owned(),
            kind,
        }
    }
}

/// A polar panel: the tip of a vector over the sweep (a force's components), on equal axes
/// through the origin.
#[derive(Debug, Clone, PartialEq)]
pub struct Polar {
    /// Panel title, e.g. `"reaction in joint A on the ground"`.
    pub title: String,
    /// Unit of both components, e.g. `"N"`.
    pub unit: String,
    /// The curves of `[x, y]` components.
    pub series: Vec<Series>,
}

/// A diagram: cartesian panels sharing one x axis, then polar panels two per row.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagram {
    /// Printed at the top.
    pub title: String,
    /// The x axis label with its unit, e.g. `"φ [deg]"`.
    pub x_label: String,
    /// Cartesian panels, top to bottom.
    pub panels: Vec<Panel>,
    /// Vertical markers.
    pub markers: Vec<Marker>,
    /// A cursor line at this x (an exported animation frame), if any.
    pub cursor: Option<f64>,
    /// Polar panels.
    pub polars: Vec<Polar>,
    /// Width (px).
    pub width: u32,
    /// Height of one cartesian panel (px).
    pub panel_height: u32,
}

/// Room for the title (px).
const TITLE: u32 = 30;
/// Height of a row of polar panels (px).
const POLAR_HEIGHT: u32 = 380;
/// Curves of at most this many points are drawn with a dot at every point (a sweep of a
/// few positions is not a smooth curve).
const SPARSE: usize = 60;
/// Series colours, in order (the Tableau 10 palette).
const PALETTE: [RGBColor; 6] = [
    RGBColor(0x1f, 0x77, 0xb4),
    RGBColor(0xff, 0x7f, 0x0e),
    RGBColor(0x2c, 0xa0, 0x2c),
    RGBColor(0x8c, 0x56, 0x4b),
    RGBColor(0xe3, 0x77, 0xc2),
    RGBColor(0x17, 0xbe, 0xcf),
];

/// Registers the bundled font with plotters once.
fn font() -> Result<()> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| {
        plotters::style::register_font(FONT_FAMILY, FontStyle::Normal, FONT).is_ok()
    });
    if ok {
        Ok(())
    } else {
        Err(Error::Picture {
            message: "the bundled font could not be read".to_owned(),
        })
    }
}

fn draw_error(e: impl std::fmt::Debug) -> Error {
    Error::Picture {
        message: format!("plotters: {e:?}"),
    }
}

/// The pixel rectangle and data range of one cartesian panel.
#[derive(Debug, Clone, PartialEq)]
struct PlotFrame {
    pixels: (Range<i32>, Range<i32>),
    x: Range<f64>,
    y: Range<f64>,
}

impl Diagram {
    /// An empty diagram, 900 px wide, 220 px per panel.
    pub fn new(title: &str, x_label: &str) -> Self {
        Diagram {
            title: title.to_owned(),
            x_label: x_label.to_owned(),
            panels: Vec::new(),
            markers: Vec::new(),
            cursor: None,
            polars: Vec::new(),
            width: 900,
            panel_height: 220,
        }
    }

    /// Adds a cartesian panel.
    pub fn panel(mut self, panel: Panel) -> Self {
        self.panels.push(panel);
        self
    }

    /// Adds a vertical marker.
    pub fn marker(mut self, marker: Marker) -> Self {
        self.markers.push(marker);
        self
    }

    /// Adds a polar panel.
    pub fn polar(mut self, polar: Polar) -> Self {
        self.polars.push(polar);
        self
    }

    /// Draws a cursor line at `x` in every cartesian panel.
    pub fn with_cursor(mut self, x: f64) -> Self {
        self.cursor = Some(x);
        self
    }

    /// The picture's height (px).
    pub fn height(&self) -> u32 {
        let rows = self.polars.len().div_ceil(2) as u32;
        TITLE + self.panel_height * self.panels.len() as u32 + POLAR_HEIGHT * rows
    }

    /// The x range shared by the panels: every finite x of every curve and marker.
    fn x_range(&self) -> Range<f64> {
        let xs = self
            .panels
            .iter()
            .flat_map(|p| p.series.iter().flat_map(|s| s.points.iter().map(|q| q[0])))
            .chain(self.markers.iter().map(|m| m.x));
        padded(finite_range(xs), 0.0)
    }

    /// The diagram as an SVG document.
    pub fn to_svg(&self) -> Result<String> {
        font()?;
        let mut svg = String::new();
        let mut frames = Vec::new();
        let mut curves = Vec::new();
        {
            let size = (self.width.max(200), self.height());
            let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
            root.fill(&WHITE).map_err(draw_error)?;
            let (top, mut rest) = root.split_vertically(TITLE);
            top.draw_text(
                &self.title,
                &(FONT_FAMILY, 16).into_font().color(&BLACK),
                (10, 8),
            )
            .map_err(draw_error)?;
            let x = self.x_range();
            for (k, panel) in self.panels.iter().enumerate() {
                let (area, below) = rest.split_vertically(self.panel_height);
                rest = below;
                let (frame, drawn) = self.draw_panel(&area, panel, x.clone(), k)?;
                frames.push(frame);
                curves.push(drawn);
            }
            for pair in self.polars.chunks(2) {
                let (row, below) = rest.split_vertically(POLAR_HEIGHT);
                rest = below;
                for (area, polar) in row.split_evenly((1, 2)).iter().zip(pair) {
                    draw_polar(area, polar)?;
                }
            }
            root.present().map_err(draw_error)?;
        }
        put_curves(&mut svg, &curves);
        let mut extra = String::from("<g class=\"plot-frames\">\n");
        for (k, f) in frames.iter().enumerate() {
            // The pixels plotters maps the data range onto: the last column and row of the
            // plotting rectangle are outside (plotters' `build_cartesian_2d`).
            let (px, py) = (
                f.pixels.0.start..f.pixels.0.end - 1,
                f.pixels.1.start..f.pixels.1.end - 1,
            );
            let _ = writeln!(
                extra,
                r#"<rect class="plot-frame" data-panel="{k}" data-x0="{:e}" data-x1="{:e}" data-y0="{:e}" data-y1="{:e}" x="{}" y="{}" width="{}" height="{}" fill="none" stroke="none"/>"#,
                f.x.start,
                f.x.end,
                f.y.start,
                f.y.end,
                px.start,
                py.start,
                px.end - px.start,
                py.end - py.start
            );
        }
        extra.push_str("</g>\n</svg>");
        if let Some(end) = svg.rfind("</svg>") {
            svg.replace_range(end.., &extra);
        }
        // A control character in a title or a name would leave the document ill-formed.
        Ok(match crate::escape::controls(&svg) {
            std::borrow::Cow::Borrowed(_) => svg,
            std::borrow::Cow::Owned(shown) => shown,
        })
    }

    fn draw_panel(
        &self,
        area: &DrawingArea<SVGBackend, Shift>,
        panel: &Panel,
        x: Range<f64>,
        index: usize,
    ) -> Result<(PlotFrame, String)> {
        let first = index == 0;
        let ys = panel
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(|q| q[1]));
        let y = padded(finite_range(ys), 0.05);
        let keys = if self.x_label.ends_with("[deg]") {
            axis::angle_ticks(&x)
        } else {
            axis::ticks(&x, 10)
        };
        let mut chart = ChartBuilder::on(area)
            .margin(6)
            .margin_right(20)
            .x_label_area_size(36)
            .y_label_area_size(80)
            .build_cartesian_2d(Ticked::new(x.clone(), keys), y.clone())
            .map_err(draw_error)?;
        let text = text_style;
        chart
            .configure_mesh()
            .x_desc(self.x_label.as_str())
            .y_desc(panel.y_label.as_str())
            .label_style(text(12))
            .axis_desc_style(text(13))
            .light_line_style(RGBColor(0xee, 0xee, 0xee))
            .x_labels(10)
            .y_labels(5)
            .x_label_formatter(&|v| tick(*v, x.end - x.start))
            .y_label_formatter(&|v| tick(*v, y.end - y.start))
            .draw()
            .map_err(draw_error)?;
        for marker in &self.markers {
            let style = marker.kind.colour().stroke_width(1);
            let line = [(marker.x, y.start), (marker.x, y.end)];
            if marker.kind == MarkerKind::Limit {
                chart
                    .draw_series(LineSeries::new(line, style))
                    .map_err(draw_error)?;
            } else {
                chart
                    .draw_series(DashedLineSeries::new(line, 6, 4, style))
                    .map_err(draw_error)?;
            }
        }
        if first {
            let plot_columns = chart.plotting_area().get_pixel_range().0;
            let placed = place_marker_labels(&self.markers, &x, plot_columns, |v| {
                chart.backend_coord(&(v, y.end)).0
            });
            let top = chart.backend_coord(&(x.start, y.end)).1;
            for (left, row, text, kind) in placed {
                area.draw_text(
                    &text,
                    &text_style(11).color(&kind.colour()),
                    (left, top + 2 + row * MARKER_ROW),
                )
                .map_err(draw_error)?;
            }
        }
        let (pixels_x, pixels_y) = chart.plotting_area().get_pixel_range();
        let map = PixelMap {
            x: x.clone(),
            y: y.clone(),
            columns: (f64::from(pixels_x.start), f64::from(pixels_x.end - 1)),
            rows: (f64::from(pixels_y.end - 1), f64::from(pixels_y.start)),
        };
        // The curves are put where this placeholder is drawn (see `put_curves`): over the
        // grid and the markers, under the dots, the legend and the cursor.
        area.draw(&Rectangle::new(
            [(0, 0), (0, 0)],
            placeholder(index).filled(),
        ))
        .map_err(draw_error)?;
        let mut drawn = String::new();
        for (k, series) in panel.series.iter().enumerate() {
            let colour = PALETTE[k % PALETTE.len()];
            let sparse = series.points.len() <= SPARSE;
            let d = path_data(
                &series.points,
                series.slopes.as_deref(),
                series.slopes.is_some() || !sparse,
                &map,
            );
            if !d.is_empty() {
                let _ = writeln!(
                    drawn,
                    r#"<path class="curve" d="{d}" fill="none" stroke="{}" stroke-width="2" stroke-linejoin="round"/>"#,
                    hex(colour)
                );
            }
            chart
                .draw_series(std::iter::empty::<PathElement<(f64, f64)>>())
                .map_err(draw_error)?
                .label(series.name.as_str())
                .legend(move |(x, y)| {
                    PathElement::new([(x, y), (x + 16, y)], colour.stroke_width(2))
                });
            if sparse {
                for run in finite_runs(&series.points) {
                    chart
                        .draw_series(
                            run.iter()
                                .map(|p| Circle::new((p[0], p[1]), 3, colour.filled())),
                        )
                        .map_err(draw_error)?;
                }
            }
        }
        if panel.series.len() > 1 {
            let corner = emptiest_corner(
                panel,
                |p| chart.backend_coord(&(p[0], p[1])),
                (&pixels_x, &pixels_y),
            );
            chart
                .configure_series_labels()
                .label_font(text(12))
                .background_style(WHITE.mix(0.8))
                .border_style(RGBColor(0xcc, 0xcc, 0xcc))
                .position(corner)
                .draw()
                .map_err(draw_error)?;
        }
        if let Some(c) = self.cursor {
            chart
                .draw_series(LineSeries::new([(c, y.start), (c, y.end)], BLACK))
                .map_err(draw_error)?;
        }
        Ok((
            PlotFrame {
                pixels: chart.plotting_area().get_pixel_range(),
                x,
                y,
            },
            drawn,
        ))
    }

    /// Writes the SVG to `path` (through a temporary file).
    pub fn write_svg(&self, path: &Path) -> Result<()> {
        write_file(path, self.to_svg()?.as_bytes())
    }

    /// Renders the SVG with the bundled font and writes it as PNG to `path`.
    pub fn write_png(&self, path: &Path) -> Result<()> {
        raster::write_png(&self.to_svg()?, path)
    }
}

/// A linear axis with chosen ticks (plotters' `WithKeyPoints` has no formatter for `f64`).
struct Ticked {
    inner: RangedCoordf64,
    bold: Vec<f64>,
    light: Vec<f64>,
}

impl Ticked {
    /// The axis over `range` with ticks at `bold` and light grid lines halfway between.
    fn new(range: Range<f64>, bold: Vec<f64>) -> Self {
        let light = bold.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect();
        Ticked {
            inner: range.into(),
            bold,
            light,
        }
    }
}

impl Ranged for Ticked {
    type ValueType = f64;
    type FormatOption = NoDefaultFormatting;

    fn range(&self) -> Range<f64> {
        self.inner.range()
    }

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        self.inner.map(value, limit)
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            self.light.clone()
        } else {
            self.bold.clone()
        }
    }
}

impl ValueFormatter<f64> for Ticked {
    fn format(value: &f64) -> String {
        value.to_string()
    }
}

/// The colour of panel `index`'s placeholder: a zero-sized rectangle that [`put_curves`]
/// replaces with the panel's curves (no picture element has this colour; text cannot hold it,
/// since plotters escapes quotes).
fn placeholder(index: usize) -> RGBColor {
    RGBColor(0x01, (index >> 8) as u8, index as u8)
}

/// `#RRGGBB`, as plotters writes colours.
fn hex(c: RGBColor) -> String {
    format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2)
}

/// Replaces the panels' placeholders in `svg`, in order, with their curves (`curves[k]`:
/// panel `k`'s `<path>` elements). Each is searched after the one before, so that panel
/// numbers sharing a colour (beyond 65 536) still go to their own panel.
fn put_curves(svg: &mut String, curves: &[String]) {
    let mut from = 0;
    for (k, drawn) in curves.iter().enumerate() {
        let key = format!(r#"fill="{}""#, hex(placeholder(k)));
        let Some(at) = svg[from..].find(&key).map(|i| from + i) else {
            continue;
        };
        let start = svg[..at].rfind("<rect").unwrap_or(at);
        let end = svg[at..].find("/>").map_or(at, |i| at + i + 2);
        svg.replace_range(start..end, drawn.trim_end());
        from = start + drawn.trim_end().len();
    }
}

/// The bundled font at `size` px.
fn text_style(size: i32) -> FontDesc<'static> {
    (FONT_FAMILY, size).into_font()
}

/// Height of one row of marker labels (px).
const MARKER_ROW: i32 = 13;
/// Average advance of a character of the bundled font, as a fraction of its size.
const ADVANCE: f64 = 0.62;

/// The labels of the markers, placed so that none prints over another nor crosses its own
/// line, and all stay inside the plotting rectangle's columns `plot` where they fit: markers
/// at the same position (several outputs dead at one drive position) share one label
/// (`"ψ, x_C: dead"`); a label stands right of its line, or left of it where the right side
/// has no room; a label that would run into one placed before it moves down a row. Returns
/// the left pixel, the row, the text and the kind; `pixel` maps a drive position to its pixel
/// column.
fn place_marker_labels(
    markers: &[Marker],
    x: &Range<f64>,
    plot: Range<i32>,
    pixel: impl Fn(f64) -> i32,
) -> Vec<(i32, i32, String, MarkerKind)> {
    let same = 1e-9 * (x.end - x.start).abs().max(1e-300);
    let mut merged: Vec<(f64, Vec<&str>, MarkerKind)> = Vec::new();
    let mut sorted: Vec<&Marker> = markers.iter().filter(|m| m.x.is_finite()).collect();
    sorted.sort_by(|a, b| a.x.total_cmp(&b.x));
    for m in sorted {
        match merged.last_mut() {
            Some((at, labels, kind)) if (m.x - *at).abs() <= same && *kind == m.kind => {
                if !labels.contains(&m.label.as_str()) {
                    labels.push(&m.label);
                }
            }
            _ => merged.push((m.x, vec![&m.label], m.kind)),
        }
    }
    // The columns taken in each row so far.
    let mut rows: Vec<Vec<Range<i32>>> = Vec::new();
    let mut out = Vec::new();
    for (at, labels, kind) in merged {
        let text = join_labels(&labels);
        let line = pixel(at);
        let width = label_width(&text);
        let right_side = line + MARKER_GAP;
        let left_side = line - MARKER_GAP - width;
        let left = if right_side + width <= plot.end || left_side < plot.start {
            right_side
        } else {
            left_side
        };
        let taken = left..left + width;
        let row = match rows.iter().position(|r| {
            r.iter()
                .all(|t| t.end <= taken.start || taken.end <= t.start)
        }) {
            Some(r) => r,
            None => {
                rows.push(Vec::new());
                rows.len() - 1
            }
        };
        rows[row].push(taken);
        out.push((left, row as i32, text, kind));
    }
    out
}

/// Pixels between a marker's line and its label.
const MARKER_GAP: i32 = 3;

/// The estimated width (px) of a marker label at 11 px, with 6 px to spare.
fn label_width(text: &str) -> i32 {
    (ADVANCE * 11.0 * text.chars().count() as f64).ceil() as i32 + 6
}

/// Labels of one position joined: `"a: dead"` and `"b: dead"` become `"a, b: dead"`.
fn join_labels(labels: &[&str]) -> String {
    let split: Vec<Option<(&str, &str)>> = labels.iter().map(|l| l.rsplit_once(": ")).collect();
    if let Some(Some((_, suffix))) = split.first()
        && split.iter().all(|s| s.is_some_and(|(_, t)| t == *suffix))
    {
        let names: Vec<&str> = split.iter().flatten().map(|(n, _)| *n).collect();
        return format!("{}: {suffix}", names.join(", "));
    }
    labels.join("; ")
}

/// The corner of the plotting rectangle (`pixels`) whose legend-sized box holds the fewest
/// points of the panel's curves (`pixel` maps a point to its pixel); upper right on a tie.
fn emptiest_corner(
    panel: &Panel,
    pixel: impl Fn([f64; 2]) -> (i32, i32),
    (px, py): (&Range<i32>, &Range<i32>),
) -> SeriesLabelPosition {
    let longest = panel
        .series
        .iter()
        .map(|s| s.name.chars().count())
        .max()
        .unwrap_or(0) as f64;
    let w = (30.0 + ADVANCE * 12.0 * longest) as i32 + 10;
    let h = 18 * panel.series.len() as i32 + 10;
    let corners = [
        (
            SeriesLabelPosition::UpperRight,
            px.end - w..px.end,
            py.start..py.start + h,
        ),
        (
            SeriesLabelPosition::UpperLeft,
            px.start..px.start + w,
            py.start..py.start + h,
        ),
        (
            SeriesLabelPosition::LowerRight,
            px.end - w..px.end,
            py.end - h..py.end,
        ),
        (
            SeriesLabelPosition::LowerLeft,
            px.start..px.start + w,
            py.end - h..py.end,
        ),
    ];
    let points: Vec<(i32, i32)> = panel
        .series
        .iter()
        .flat_map(|s| s.points.iter())
        .filter(|p| p[0].is_finite() && p[1].is_finite())
        .map(|&p| pixel(p))
        .collect();
    let mut best = (usize::MAX, SeriesLabelPosition::UpperRight);
    for (position, xs, ys) in corners {
        let inside = points
            .iter()
            .filter(|(x, y)| xs.contains(x) && ys.contains(y))
            .count();
        if inside < best.0 {
            best = (inside, position);
        }
    }
    best.1
}

/// The most a diagram file is high (px): a taller diagram is split into pages.
pub const MAX_HEIGHT: u32 = 2000;

impl Diagram {
    /// The diagram split into pages of at most [`MAX_HEIGHT`] px each (one page if it fits):
    /// the cartesian panels in order, as many per page as fit, then the polar panels; every
    /// page keeps the title (with "page k of n"), the x label and the markers.
    pub fn pages(&self) -> Vec<Diagram> {
        if self.height() <= MAX_HEIGHT {
            return vec![self.clone()];
        }
        let room = MAX_HEIGHT - TITLE;
        let per_page = (room / self.panel_height.max(1)).max(1) as usize;
        let polars_per_page = 2 * (room / POLAR_HEIGHT).max(1) as usize;
        let empty = Diagram {
            panels: Vec::new(),
            polars: Vec::new(),
            ..self.clone()
        };
        let mut pages: Vec<Diagram> = self
            .panels
            .chunks(per_page)
            .map(|c| Diagram {
                panels: c.to_vec(),
                ..empty.clone()
            })
            .collect();
        pages.extend(self.polars.chunks(polars_per_page).map(|c| Diagram {
            polars: c.to_vec(),
            ..empty.clone()
        }));
        let n = pages.len();
        for (k, page) in pages.iter_mut().enumerate() {
            page.title = format!("{} (page {} of {n})", self.title, k + 1);
        }
        pages
    }

    /// The [`pages`](Self::pages) with the stems of their files: `stem` for the first,
    /// `stem_2`, `stem_3`, … for the others.
    pub fn named_pages(&self, stem: &str) -> Vec<(String, Diagram)> {
        self.pages()
            .into_iter()
            .enumerate()
            .map(|(k, page)| match k {
                0 => (stem.to_owned(), page),
                _ => (format!("{stem}_{}", k + 1), page),
            })
            .collect()
    }
}

fn draw_polar(area: &DrawingArea<SVGBackend, Shift>, polar: &Polar) -> Result<()> {
    let radius = polar
        .series
        .iter()
        .flat_map(|s| s.points.iter())
        .filter(|p| p[0].is_finite() && p[1].is_finite())
        .fold(0.0_f64, |r, p| r.max(p[0].hypot(p[1])));
    let r = if radius > 0.0 { 1.08 * radius } else { 1.0 };
    // Equal scales: stretch the longer side's range to the plotting rectangle's aspect.
    let (margin, left, bottom, top) = (8, 80, 36, 24);
    let (w, h) = area.dim_in_pixel();
    let pw = f64::from(w.saturating_sub(2 * margin + left).max(1));
    let ph = f64::from(h.saturating_sub(2 * margin + bottom + top).max(1));
    let (rx, ry) = if pw > ph {
        (r * pw / ph, r)
    } else {
        (r, r * ph / pw)
    };
    let text = |size| (FONT_FAMILY, size).into_font();
    let mut chart = ChartBuilder::on(area)
        .margin(margin)
        .caption(polar.title.as_str(), text(13))
        .x_label_area_size(bottom)
        .y_label_area_size(left)
        .build_cartesian_2d(-rx..rx, -ry..ry)
        .map_err(draw_error)?;
    chart
        .configure_mesh()
        .x_desc(format!("x [{}]", polar.unit))
        .y_desc(format!("y [{}]", polar.unit))
        .label_style(text(11))
        .axis_desc_style(text(12))
        .x_label_formatter(&|v| tick(*v, rx))
        .y_label_formatter(&|v| tick(*v, ry))
        .light_line_style(RGBColor(0xf0, 0xf0, 0xf0))
        .draw()
        .map_err(draw_error)?;
    let grey = RGBColor(0xbb, 0xbb, 0xbb);
    for line in [[(-rx, 0.0), (rx, 0.0)], [(0.0, -ry), (0.0, ry)]] {
        chart
            .draw_series(LineSeries::new(line, grey))
            .map_err(draw_error)?;
    }
    for (k, series) in polar.series.iter().enumerate() {
        let colour = PALETTE[k % PALETTE.len()];
        for run in finite_runs(&series.points) {
            chart
                .draw_series(LineSeries::new(
                    run.iter().map(|p| (p[0], p[1])),
                    colour.stroke_width(2),
                ))
                .map_err(draw_error)?;
            if series.points.len() <= SPARSE {
                chart
                    .draw_series(
                        run.iter()
                            .map(|p| Circle::new((p[0], p[1]), 3, colour.filled())),
                    )
                    .map_err(draw_error)?;
            }
        }
    }
    Ok(())
}

/// A tick label on an axis spanning `span`: six significant digits at most, no trailing
/// zeros, and `0` for what is zero but for rounding (1e-9 of the span).
fn tick(v: f64, span: f64) -> String {
    if v.abs() <= 1e-9 * span.abs() {
        return "0".to_owned();
    }
    match format!("{v:.5e}").parse::<f64>() {
        Ok(r) => (r + 0.0).to_string(),
        Err(_) => v.to_string(),
    }
}

/// The smallest and largest finite value, or `0..1` if there is none.
fn finite_range(values: impl Iterator<Item = f64>) -> Range<f64> {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if lo > hi { 0.0..1.0 } else { lo..hi }
}

/// The range widened by `fraction` of its length on each side; an empty range is widened to
/// a unit (or 10 % of its value) so that a constant curve is still drawn.
fn padded(range: Range<f64>, fraction: f64) -> Range<f64> {
    let length = range.end - range.start;
    if length > 1e-12 * range.start.abs().max(range.end.abs()) && length > 0.0 {
        let pad = fraction * length;
        return range.start - pad..range.end + pad;
    }
    let half = if range.start == 0.0 {
        1.0
    } else {
        0.1 * range.start.abs()
    };
    range.start - half..range.end + half
}

/// The runs of consecutive finite points.
fn finite_runs(points: &[[f64; 2]]) -> impl Iterator<Item = &[[f64; 2]]> {
    points
        .split(|p| !(p[0].is_finite() && p[1].is_finite()))
        .filter(|run| !run.is_empty())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A constant curve still gets a y range of positive length around its value.
    #[test]
    fn constant_curves_get_a_range() {
        let r = padded(finite_range([2.0, 2.0].into_iter()), 0.05);
        assert!(r.start < 2.0 && r.end > 2.0);
        let r = padded(finite_range([f64::NAN].into_iter()), 0.05);
        assert!(r.end > r.start);
    }

    /// The legend goes to the corner its box covers the fewest curve points in (the issue's
    /// "legends over curves"): a curve rising to the upper right puts it upper left, one
    /// falling from the upper left puts it upper right.
    #[test]
    fn the_legend_takes_the_emptiest_corner() {
        // x, y in 0..100 drawn 1:1 on a 400 × 200 px plot (y up).
        let pixel = |p: [f64; 2]| ((4.0 * p[0]) as i32, (200.0 - 2.0 * p[1]) as i32);
        let (px, py) = (0..400, 0..200);
        let rising: Vec<[f64; 2]> = (0..=100).map(|k| [k as f64, k as f64]).collect();
        let panel = Panel::new("y").series("rising", rising);
        assert!(matches!(
            emptiest_corner(&panel, pixel, (&px, &py)),
            SeriesLabelPosition::UpperLeft | SeriesLabelPosition::LowerRight
        ));
        let falling: Vec<[f64; 2]> = (0..=100).map(|k| [k as f64, 100.0 - k as f64]).collect();
        let panel = Panel::new("y").series("falling", falling);
        assert!(matches!(
            emptiest_corner(&panel, pixel, (&px, &py)),
            SeriesLabelPosition::UpperRight | SeriesLabelPosition::LowerLeft
        ));
    }

    /// NaN splits a curve into runs and is never drawn.
    #[test]
    fn non_finite_points_break_curves() {
        let p = [[0.0, 1.0], [1.0, f64::NAN], [2.0, 3.0], [3.0, 4.0]];
        let runs: Vec<_> = finite_runs(&p).collect();
        assert_eq!(runs.len(), 2);
        assert_eq!(runs[1].len(), 2);
    }
}
