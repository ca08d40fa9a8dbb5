//! One self-contained HTML file per run (`mechdiff run scene.toml --report run.html`): the
//! mechanism animated over the sweep with a slider to scrub the drive position, the diagram
//! with a cursor there, the values at the cursor, and buttons that save the current frame
//! and diagram as SVG. No network is needed to open it: the SVG, the data and the script are
//! all inline.
//!
//! Its size is bounded whatever the sweep's length: at most [`super::run::FRAMES`] frames
//! (every point's position and every column's value per frame) and diagram curves decimated
//! to [`super::run::BUCKETS`] buckets; for the scenes in `scenes/` it stays under
//! [`MAX_BYTES`].
//!
//! The page opens at the frame named in its address: `report.html#frame=10` or
//! `report.html#phi=90` (the nearest frame), and `&mark=C` paints joint `C` red (for the
//! headless-browser check in `scripts/check_report_in_chromium.sh`).

use serde_json::json;

use super::escape;
use super::run::Animation;
use crate::error::Result;
use crate::scene::Scene;
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

/// The HTML report of a run; `diagram_svg` is the run's diagram (see [`super::run::diagram`]).
pub fn html(
    scene: &Scene,
    report: &Report,
    animation: &Animation,
    diagram_svg: &str,
) -> Result<String> {
    let title = scene.title.clone().unwrap_or_else(|| scene.file.clone());
    let first = animation.poses.xy.first().cloned().unwrap_or_default();
    let mechanism = animation.drawing(scene, &title, &first).to_svg();
    let columns: Vec<_> = report
        .columns
        .iter()
        .map(|c| json!({"name": c.name, "unit": c.unit}))
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
    let xy: Vec<Vec<f64>> = animation
        .poses
        .xy
        .iter()
        .map(|pose| pose.iter().flatten().copied().collect())
        .collect();
    let names: Vec<&str> = scene.points.iter().map(|p| p.name.as_str()).collect();
    // serde_json writes non-finite numbers as null; the page shows them as "—".
    let data = json!({
        "names": names,
        "columns": columns,
        "values": values,
        "xy": xy,
    })
    .to_string();
    let data = crate::escape::script_json(&data);
    let mut dead = Vec::new();
    write_dead_positions(scene, report, &mut dead).map_err(|source| crate::Error::Write {
        path: "<report>".into(),
        source,
    })?;
    let dead = String::from_utf8_lossy(&dead).trim().to_owned();
    let plan = report.plan.describe(scene);
    Ok(format!(
        r#"<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>{title}</title>
<style>
body {{ margin: 0; font-family: "DejaVu Sans", sans-serif; font-size: 14px; }}
#mechanism {{ position: absolute; left: 0; top: 0; width: 800px; height: 600px; }}
#side {{ position: absolute; left: 820px; top: 10px; width: 420px; }}
#below {{ position: absolute; left: 0; top: 610px; }}
#scrub {{ width: 780px; }}
table {{ border-collapse: collapse; }} td {{ padding: 1px 8px; border-bottom: 1px solid #eee; }}
td.v {{ text-align: right; font-variant-numeric: tabular-nums; }}
pre {{ white-space: pre-wrap; }}
</style></head><body>
<div id="mechanism">{mechanism}</div>
<div id="side"><b>{title}</b><pre>{plan}</pre><pre>{dead}</pre>
<div id="where"></div><table id="values"></table></div>
<div id="below">
<div><input type="range" id="scrub" min="0" max="{last}" value="0"></div>
<div><button id="play">play / pause</button> <button id="save-frame">save frame (SVG)</button>
<button id="save-diagram">save diagram (SVG)</button> <span id="phi"></span></div>
<div id="diagram">{diagram_svg}</div>
</div>
<script type="application/json" id="data">{data}</script>
<script>
{SCRIPT}
</script>
</body></html>
"#,
        title = escape(&title),
        plan = escape(&plan),
        dead = escape(&dead),
        last = animation.rows.len().saturating_sub(1),
    ))
}

/// The page's script: moves the bound shapes of the mechanism drawing to a frame, the
/// diagram's cursor to its drive position, and fills the table of values.
const SCRIPT: &str = r#"
const D = JSON.parse(document.getElementById('data').textContent);
const mech = document.querySelector('#mechanism svg');
const scale = +mech.getAttribute('data-scale');
const ox = +mech.getAttribute('data-origin-x'), oy = +mech.getAttribute('data-origin-y');
const diagram = document.querySelector('#diagram svg');
const scrub = document.getElementById('scrub');
const fmt = v => (v === null ? '—' : (Math.abs(v) >= 1e6 || (Math.abs(v) < 1e-3 && v !== 0)) ? v.toExponential(6) : v.toPrecision(9));
function px(k, f) { const xy = D.xy[f]; return [ox + scale * xy[2 * k], oy - scale * xy[2 * k + 1]]; }
const cursors = [];
if (diagram) {
  for (const r of diagram.querySelectorAll('rect.plot-frame')) {
    const line = document.createElementNS('http://www.w3.org/2000/svg', 'line');
    line.setAttribute('stroke', 'black'); line.setAttribute('stroke-width', '1.5');
    line.setAttribute('y1', r.getAttribute('y'));
    line.setAttribute('y2', +r.getAttribute('y') + +r.getAttribute('height'));
    diagram.appendChild(line);
    cursors.push([r, line]);
  }
}
const table = document.getElementById('values');
for (const c of D.columns) {
  const tr = table.insertRow(); tr.insertCell().textContent = c.name;
  const v = tr.insertCell(); v.className = 'v'; tr.insertCell().textContent = c.unit;
}
let frame = 0;
function show(f) {
  frame = Math.max(0, Math.min(D.xy.length - 1, f));
  scrub.value = frame;
  for (const el of mech.querySelectorAll('[data-bind]')) {
    const b = el.getAttribute('data-bind').split(' ');
    const k = b.slice(1).map(Number);
    const [x, y] = px(k[0], frame);
    if (b[0] === 'p') {
      el.setAttribute('points', k.map(i => px(i, frame).map(v => v.toFixed(3)).join(',')).join(' '));
    } else if (b[0] === 'c') {
      el.setAttribute('cx', x); el.setAttribute('cy', y);
    } else if (b[0] === 't') {
      el.setAttribute('x', x + 7); el.setAttribute('y', y - 7);
    } else if (b[0] === 'b') {
      const [ax, ay] = px(k[1], frame), [bx, by] = px(k[2], frame);
      const w = +el.getAttribute('width'), h = +el.getAttribute('height');
      const deg = Math.atan2(by - ay, bx - ax) * 180 / Math.PI;
      el.setAttribute('x', x - w / 2); el.setAttribute('y', y - h / 2);
      el.setAttribute('transform', 'rotate(' + deg + ' ' + x + ' ' + y + ')');
    }
  }
  const row = D.values[frame];
  const phi = row[0];
  for (const [r, line] of cursors) {
    const x0 = +r.getAttribute('data-x0'), x1 = +r.getAttribute('data-x1');
    const x = +r.getAttribute('x') + (phi - x0) / (x1 - x0) * +r.getAttribute('width');
    line.setAttribute('x1', x); line.setAttribute('x2', x);
  }
  row.forEach((v, i) => { table.rows[i].cells[1].textContent = fmt(v); });
  document.getElementById('phi').textContent =
    'frame ' + frame + ' of ' + (D.xy.length - 1) + ': φ = ' + fmt(phi) + ' ' + D.columns[0].unit;
}
scrub.addEventListener('input', () => show(+scrub.value));
let timer = null;
document.getElementById('play').addEventListener('click', () => {
  if (timer) { clearInterval(timer); timer = null; return; }
  timer = setInterval(() => show((frame + 1) % D.xy.length), 40);
});
function save(svg, name) {
  const text = new XMLSerializer().serializeToString(svg);
  const a = document.createElement('a');
  a.href = URL.createObjectURL(new Blob([text], { type: 'image/svg+xml' }));
  a.download = name; a.click();
}
document.getElementById('save-frame').addEventListener('click', () => save(mech, 'frame_' + frame + '.svg'));
document.getElementById('save-diagram').addEventListener('click', () => save(diagram, 'diagram_frame_' + frame + '.svg'));
const hash = new URLSearchParams(location.hash.slice(1));
let start = 0;
if (hash.has('frame')) start = +hash.get('frame');
if (hash.has('phi')) {
  const want = +hash.get('phi');
  let best = Infinity;
  D.values.forEach((row, i) => { const d = Math.abs(row[0] - want); if (d < best) { best = d; start = i; } });
}
if (hash.has('mark')) {
  for (const el of mech.querySelectorAll('circle.joint')) {
    if (el.getAttribute('data-point') === hash.get('mark')) {
      el.setAttribute('fill', '#ff0000'); el.setAttribute('stroke', '#ff0000');
      el.parentNode.appendChild(el);
    }
  }
}
show(start);
"#;
