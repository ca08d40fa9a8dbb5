//! One self-contained HTML file per run (`mechdiff run scene.toml --report run.html`): the
//! mechanism animated over the sweep with a slider to scrub the drive position, the diagram
//! with a cursor there, the values at the cursor, and buttons that save the current frame
//! and diagram as SVG. No network is needed to open it: the SVG, the data, the style and the
//! script are all inline.
//!
//! The page is laid out for any width from a phone's (400 px) to 4K: one column on a phone
//! (the mechanism and the controls stay at the top while the diagram, its cursor in view, and
//! then the table scroll under them), two columns from 760 px (mechanism over diagram, the values beside them), and
//! from 1400 px the mechanism over the values, held in view, beside the diagram. It plays the sweep in real time
//! at the scene's drive speed (a speed factor ×0.1…×10), steps with the keys (← →, Shift for
//! ten frames, Home, End, space to play and pause), zooms the mechanism with the wheel and pans
//! it by dragging (double-click resets), and draws the velocity and acceleration arrows of the
//! points whose columns the run has when asked.
//!
//! Its size is bounded whatever the sweep's length: at most [`super::run::FRAMES`] frames
//! (every point's position and every column's value per frame) and diagram curves decimated
//! to [`super::run::BUCKETS`] buckets; for the scenes in `scenes/` it stays under
//! [`MAX_BYTES`].
//!
//! The page opens at the frame named in its address: `report.html#frame=10` or
//! `report.html#phi=90` (the nearest frame), `&mark=C` paints joint `C` red and `&vectors=1`
//! shows the arrows. A script
//! driving the page finds `window.mechdiffReport` there (`show(frame)`, `frame()`, `frames`):
//! the browser test `tests/report_in_browser.rs` drives every shipped scene's report in
//! headless Chromium through it.
//!
//! Cam scenes get their report from [`cam`] (the cam turning, the follower moving, the SVAJ
//! diagram), rotor scenes from [`rotor`] (the force and couple polygons and the answers),
//! scenes with `[simulate]` from [`motion`] (the machine played on its simulated clock).

pub mod cam;
pub mod motion;
pub mod rotor;

use serde_json::json;

use super::escape;
use super::run::Animation;
use crate::error::Result;
use crate::scene::Scene;
use crate::scene::format::Quantity;
use crate::scene::model::OutputKind;
use crate::scene::run::Report;
use crate::scene::table::write_dead_positions;

/// Draws the run's diagram and animation and writes the HTML report to `path`.
pub fn write(scene: &Scene, report: &Report, path: &std::path::Path) -> Result<()> {
    let diagram = super::run::diagram(scene, report)?.to_svg()?;
    let animation = Animation::of(scene, report)?;
    super::write_file(path, html(scene, report, &animation, &diagram)?.as_bytes())
}

/// The bound on a report's size stated in the docs and checked by the tests (bytes).
pub const MAX_BYTES: usize = 4_000_000;

/// A column of the value table: its name and unit.
#[derive(Debug, Clone, PartialEq)]
pub struct Column {
    /// The column's name (`x_C`, `psi'`).
    pub name: String,
    /// Its unit symbol.
    pub unit: String,
}

/// An arrow drawn at a point, from two columns of the table.
#[derive(Debug, Clone, PartialEq)]
pub struct Arrow {
    /// The point (index into [`Page::points`]).
    pub point: usize,
    /// `"v"` for a velocity, `"a"` for an acceleration.
    pub kind: &'static str,
    /// The columns of its x and y components.
    pub columns: [usize; 2],
    /// Their unit.
    pub unit: String,
}

/// What a report page shows, whatever the scene's kind: a drawing whose `data-bind` shapes
/// follow the frames, an optional diagram with a cursor, and the table of values per frame.
#[derive(Debug, Clone, Default)]
pub struct Page {
    /// The page's title.
    pub title: String,
    /// Text shown under the title (the plan, the dead positions), each block preformatted.
    pub notes: Vec<String>,
    /// The drawing at the first frame (a [`super::Drawing`]'s SVG, with its frame and binds).
    pub drawing: String,
    /// The diagram (with `rect.plot-frame` elements carrying `data-x0`/`data-x1`), if any.
    pub diagram: Option<String>,
    /// The drive's symbol (`φ`, `θ`).
    pub drive: String,
    /// The table's columns, the drive first.
    pub columns: Vec<Column>,
    /// The values per frame, in the columns' units (non-finite shown as "—").
    pub values: Vec<Vec<f64>>,
    /// The names of the points the binds refer to.
    pub points: Vec<String>,
    /// Per frame, the points' model coordinates (x, y), in the drawing's units.
    pub xy: Vec<Vec<[f64; 2]>>,
    /// Per frame, the angle (rad, counterclockwise) by which shapes bound with `r k` are turned
    /// about point `k`, if any shape is.
    pub rotation: Option<Vec<f64>>,
    /// The drive's speed in the drive column's unit per second, if the scene gives one.
    pub rate: Option<f64>,
    /// The arrows that the "vectors" box shows.
    pub arrows: Vec<Arrow>,
}

impl Page {
    /// The page as a self-contained HTML document.
    pub fn html(&self) -> String {
        let columns: Vec<_> = self
            .columns
            .iter()
            .map(|c| json!({"name": c.name, "unit": c.unit}))
            .collect();
        let xy: Vec<Vec<f64>> = self
            .xy
            .iter()
            .map(|pose| pose.iter().flatten().copied().collect())
            .collect();
        let vectors: Vec<_> = self
            .arrows
            .iter()
            .map(|a| {
                json!({"point": a.point, "kind": a.kind, "x": a.columns[0], "y": a.columns[1],
                       "unit": a.unit})
            })
            .collect();
        // serde_json writes non-finite numbers as null; the page shows them as "—".
        let data = json!({
            "names": self.points,
            "drive": self.drive,
            "columns": columns,
            "values": self.values,
            "xy": xy,
            "rot": self.rotation,
            "rate": self.rate.filter(|r| r.is_finite() && *r > 0.0),
            "vectors": vectors,
        })
        .to_string();
        let data = crate::escape::script_json(&data);
        let notes: String = self
            .notes
            .iter()
            .filter(|n| !n.is_empty())
            .map(|n| format!("<pre>{}</pre>\n", escape(n)))
            .collect();
        let speeds: String = [0.1, 0.25, 0.5, 1.0, 2.0, 5.0, 10.0]
            .iter()
            .map(|s| {
                let selected = if *s == 1.0 { " selected" } else { "" };
                format!(r#"<option value="{s}"{selected}>×{s}</option>"#)
            })
            .collect();
        format!(
            r#"<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{title}</title>
<style>
{STYLE}</style></head><body>
<div id="report">
<div id="pane">
<section id="stage">
<div id="controls">
<input type="range" id="scrub" min="0" max="{last}" value="0" aria-label="drive position">
<span id="playback"><button id="play">▶ play</button>
<label>speed <select id="speed">{speeds}</select></label> <span id="rate"></span></span>
<label id="vectors-control"><input type="checkbox" id="vectors"> vectors</label>
<button id="reset-view" title="or double-click the drawing">reset view</button>
<button id="save-frame">save frame (SVG)</button>
<button id="save-diagram">save diagram (SVG)</button>
<span id="phi"></span>
</div>
<div id="mechanism">{drawing}</div>
<div id="legend" class="hidden"></div>
</section>
<aside id="side"><h1>{title}</h1>
<table id="values"></table>
{notes}</aside>
</div>
<section id="diagram">{diagram}</section>
</div>
<script type="application/json" id="data">{data}</script>
<script>
{SCRIPT}</script>
</body></html>
"#,
            title = escape(&self.title),
            last = self.xy.len().saturating_sub(1),
            drawing = self.drawing,
            diagram = self.diagram.as_deref().unwrap_or(""),
        )
    }
}

/// The HTML report of a run; `diagram_svg` is the run's diagram (see [`super::run::diagram`]).
pub fn html(
    scene: &Scene,
    report: &Report,
    animation: &Animation,
    diagram_svg: &str,
) -> Result<String> {
    let title = scene.title.clone().unwrap_or_else(|| scene.file.clone());
    let first = animation.poses.xy.first().cloned().unwrap_or_default();
    let drawing = animation.drawing(scene, &title, &first).to_svg();
    let columns = report
        .columns
        .iter()
        .map(|c| Column {
            name: c.name.clone(),
            unit: c.unit.clone(),
        })
        .collect();
    let values: Vec<Vec<f64>> = animation
        .rows
        .iter()
        .map(|&r| {
            report.rows[r]
                .iter()
                .zip(&report.columns)
                .map(|(v, c)| v / c.factor)
                .collect()
        })
        .collect();
    let mut dead = Vec::new();
    write_dead_positions(scene, report, &mut dead).map_err(|source| crate::Error::Write {
        path: "<report>".into(),
        source,
    })?;
    let dead = String::from_utf8_lossy(&dead).trim().to_owned();
    let drive = &report.columns[0];
    Ok(Page {
        title,
        notes: vec![report.plan.describe(scene), dead],
        drawing,
        diagram: Some(diagram_svg.to_owned()),
        drive: "φ".to_owned(),
        columns,
        values,
        points: scene.points.iter().map(|p| p.name.clone()).collect(),
        xy: animation.poses.xy.clone(),
        rotation: None,
        rate: scene.drive.speed.map(|w| w / drive.factor),
        arrows: arrows(scene, report),
    }
    .html())
}

/// The velocity and acceleration arrows of the run: one per `[[output]] point` whose
/// velocity or acceleration columns the run has.
fn arrows(scene: &Scene, report: &Report) -> Vec<Arrow> {
    let column = |name: &str| report.columns.iter().position(|c| c.name == name);
    let mut out = Vec::new();
    for output in &scene.outputs {
        let OutputKind::Point(p) = &output.kind else {
            continue;
        };
        let Some(point) = scene.points.iter().position(|q| q.name == *p) else {
            continue;
        };
        for (q, kind) in [(Quantity::Velocity, "v"), (Quantity::Acceleration, "a")] {
            if !output.quantities.contains(&q) {
                continue;
            }
            let n = &output.name;
            if let (Some(x), Some(y)) = (
                column(&format!("{kind}x_{n}")),
                column(&format!("{kind}y_{n}")),
            ) {
                out.push(Arrow {
                    point,
                    kind,
                    columns: [x, y],
                    unit: report.columns[x].unit.clone(),
                });
            }
        }
    }
    out
}

/// The page's style sheet: the responsive layout.
const STYLE: &str = include_str!("report/page.css");

/// The page's script: moves the bound shapes of the drawing to a frame, the diagram's cursor
/// to its drive position, fills the table of values; plays, steps, zooms and pans.
const SCRIPT: &str = include_str!("report/page.js");
