'use strict';
const D = JSON.parse(document.getElementById('data').textContent);
const NS = 'http://www.w3.org/2000/svg';
const mech = document.querySelector('#mechanism svg');
const scale = +mech.getAttribute('data-scale');
const ox = +mech.getAttribute('data-origin-x'), oy = +mech.getAttribute('data-origin-y');
const diagram = document.querySelector('#diagram svg');
const scrub = document.getElementById('scrub');
const frames = D.xy.length;
const fmt = v => (v === null ? '—' : (Math.abs(v) >= 1e6 || (Math.abs(v) < 1e-3 && v !== 0)) ? v.toExponential(6) : v.toPrecision(9));
function px(k, f) { const xy = D.xy[f]; return [ox + scale * xy[2 * k], oy - scale * xy[2 * k + 1]]; }

// The bound shapes, with what each needs from the first frame (a label keeps its offset from
// its point; a rotated shape keeps its points, turned about its centre).
const bound = [];
for (const el of mech.querySelectorAll('[data-bind]')) {
  const b = el.getAttribute('data-bind').split(' ');
  const item = { el, kind: b[0], k: b.slice(1).map(Number) };
  if (item.kind === 't') {
    const [x, y] = px(item.k[0], 0);
    item.dx = +el.getAttribute('x') - x; item.dy = +el.getAttribute('y') - y;
  }
  bound.push(item);
}

// The diagram's cursor: one vertical line per plot frame.
const cursors = [];
const held = document.querySelectorAll('#diagram [data-column]');
if (diagram && held.length === 0) {
  for (const r of diagram.querySelectorAll('rect.plot-frame')) {
    const line = document.createElementNS(NS, 'line');
    line.setAttribute('class', 'cursor');
    line.setAttribute('stroke', 'black'); line.setAttribute('stroke-width', '1.5');
    line.setAttribute('y1', r.getAttribute('y'));
    line.setAttribute('y2', +r.getAttribute('y') + +r.getAttribute('height'));
    diagram.appendChild(line);
    cursors.push([r, line]);
  }
}

// Diagrams held in an element with data-column (a report of the machine in motion): each
// plot frame's cursor at that column's value and a dot on its panel's curve (the column
// data-y-columns names for it), shown during the frames data-frames names.
const markers = [];
for (const holder of held) {
  const svg = holder.querySelector('svg');
  const ys = (holder.dataset.yColumns || '').split(' ').filter(s => s !== '').map(Number);
  const [from, to] = (holder.dataset.frames || '0 ' + frames).split(' ').map(Number);
  for (const r of svg.querySelectorAll('rect.plot-frame')) {
    const line = document.createElementNS(NS, 'line');
    line.setAttribute('class', 'cursor');
    line.setAttribute('stroke', 'black'); line.setAttribute('stroke-width', '1.5');
    line.setAttribute('y1', r.getAttribute('y'));
    line.setAttribute('y2', +r.getAttribute('y') + +r.getAttribute('height'));
    const dot = document.createElementNS(NS, 'circle');
    dot.setAttribute('class', 'marker'); dot.setAttribute('r', '4');
    dot.setAttribute('fill', '#d62728'); dot.setAttribute('stroke', 'white');
    svg.appendChild(line); svg.appendChild(dot);
    markers.push({ r, line, dot, x: +holder.dataset.column, y: ys[+r.getAttribute('data-panel')], from, to });
  }
}
function showMarkers(f) {
  const row = D.values[f];
  for (const m of markers) {
    const x0 = +m.r.getAttribute('data-x0'), x1 = +m.r.getAttribute('data-x1');
    const y0 = +m.r.getAttribute('data-y0'), y1 = +m.r.getAttribute('data-y1');
    const vx = row[m.x], vy = m.y === undefined ? null : row[m.y];
    const on = f >= m.from && f < m.to && vx !== null && vx >= Math.min(x0, x1) && vx <= Math.max(x0, x1);
    m.line.style.display = on ? '' : 'none';
    m.dot.style.display = on && vy !== null ? '' : 'none';
    if (!on) continue;
    const x = +m.r.getAttribute('x') + (vx - x0) / (x1 - x0) * +m.r.getAttribute('width');
    m.line.setAttribute('x1', x); m.line.setAttribute('x2', x);
    if (vy !== null) {
      const top = +m.r.getAttribute('y'), h = +m.r.getAttribute('height');
      m.dot.setAttribute('cx', x); m.dot.setAttribute('cy', top + (y1 - vy) / (y1 - y0) * h);
    }
  }
}

// Velocity and acceleration arrows of the points whose columns the run has, each kind to one
// scale: its largest value over the sweep is drawn 15 % of the drawing's smaller side long.
const arrows = document.createElementNS(NS, 'g');
arrows.setAttribute('class', 'vectors');
mech.appendChild(arrows);
const colours = { v: '#2ca02c', a: '#c2185b' };
const side = Math.min(+mech.getAttribute('width'), +mech.getAttribute('height'));
const vectorScale = {};
for (const v of D.vectors) {
  let most = 0;
  for (const row of D.values) {
    if (row[v.x] !== null && row[v.y] !== null) most = Math.max(most, Math.hypot(row[v.x], row[v.y]));
  }
  if (most > 0) vectorScale[v.kind] = Math.max(vectorScale[v.kind] || 0, most);
  v.line = document.createElementNS(NS, 'polyline');
  v.line.setAttribute('fill', 'none'); v.line.setAttribute('stroke', colours[v.kind]);
  v.line.setAttribute('stroke-width', '2');
  arrows.appendChild(v.line);
}
const legend = [];
for (const kind of Object.keys(vectorScale)) {
  const most = vectorScale[kind];
  vectorScale[kind] = 0.15 * side / most;
  const unit = D.vectors.find(v => v.kind === kind).unit;
  legend.push((kind === 'v' ? 'velocity' : 'acceleration') + ' arrows: 10 px = ' + fmt(10 / vectorScale[kind]) + ' ' + unit);
}
const vectorBox = document.getElementById('vectors');
if (D.vectors.length === 0) document.getElementById('vectors-control').classList.add('hidden');
document.getElementById('legend').textContent = legend.join('; ');
function showVectors(f) {
  arrows.style.display = vectorBox.checked ? '' : 'none';
  document.getElementById('legend').classList.toggle('hidden', !vectorBox.checked);
  if (!vectorBox.checked) return;
  const row = D.values[f];
  for (const v of D.vectors) {
    const s = vectorScale[v.kind];
    if (!s || row[v.x] === null || row[v.y] === null) { v.line.setAttribute('points', ''); continue; }
    const [x, y] = px(v.point, f);
    const tx = x + s * row[v.x], ty = y - s * row[v.y];
    const l = Math.hypot(tx - x, ty - y);
    if (l < 1e-9) { v.line.setAttribute('points', ''); continue; }
    const ux = (tx - x) / l, uy = (ty - y) / l, h = Math.min(8, 0.4 * l);
    const a = [tx - h * ux + 0.5 * h * uy, ty - h * uy - 0.5 * h * ux];
    const b = [tx - h * ux - 0.5 * h * uy, ty - h * uy + 0.5 * h * ux];
    v.line.setAttribute('points', [[x, y], [tx, ty], a, [tx, ty], b].map(p => p[0].toFixed(2) + ',' + p[1].toFixed(2)).join(' '));
  }
}
vectorBox.addEventListener('change', () => showVectors(frame));

const table = document.getElementById('values');
for (const c of D.columns) {
  const tr = table.insertRow();
  const n = tr.insertCell(); n.className = 'name'; n.textContent = c.name;
  const v = tr.insertCell(); v.className = 'v'; tr.insertCell().textContent = c.unit;
}

let frame = 0;
function show(f) {
  frame = Math.max(0, Math.min(frames - 1, Math.round(f)));
  scrub.value = frame;
  const turn = D.rot ? D.rot[frame] : 0;
  for (const { el, kind, k, dx, dy } of bound) {
    const [x, y] = px(k[0], frame);
    if (kind === 'p') {
      el.setAttribute('points', k.map(i => px(i, frame).map(v => v.toFixed(3)).join(',')).join(' '));
    } else if (kind === 'c') {
      el.setAttribute('cx', x); el.setAttribute('cy', y);
    } else if (kind === 't') {
      el.setAttribute('x', x + dx); el.setAttribute('y', y + dy);
    } else if (kind === 'r') {
      el.setAttribute('transform', 'rotate(' + (-turn * 180 / Math.PI) + ' ' + x + ' ' + y + ')');
    } else if (kind === 'b') {
      const [ax, ay] = px(k[1], frame), [bx, by] = px(k[2], frame);
      const w = +el.getAttribute('width'), h = +el.getAttribute('height');
      const deg = Math.atan2(by - ay, bx - ax) * 180 / Math.PI;
      el.setAttribute('x', x - w / 2); el.setAttribute('y', y - h / 2);
      el.setAttribute('transform', 'rotate(' + deg + ' ' + x + ' ' + y + ')');
    }
  }
  showVectors(frame);
  const row = D.values[frame];
  const phi = row[0];
  showMarkers(frame);
  for (const [r, line] of cursors) {
    const x0 = +r.getAttribute('data-x0'), x1 = +r.getAttribute('data-x1');
    const x = +r.getAttribute('x') + (phi - x0) / (x1 - x0) * +r.getAttribute('width');
    line.setAttribute('x1', x); line.setAttribute('x2', x);
  }
  row.forEach((v, i) => { table.rows[i].cells[1].textContent = fmt(v); });
  document.getElementById('phi').textContent =
    'frame ' + frame + ' of ' + (frames - 1) + ': ' + D.drive + ' = ' + fmt(phi) + ' ' + D.columns[0].unit;
}
scrub.addEventListener('input', () => { stop(); show(+scrub.value); });

// Playback in real time: the drive moves at its speed (D.rate, drive units per second) times
// the chosen factor; without a drive speed, one sweep takes four seconds at ×1.
const span = Math.abs(D.values[frames - 1][0] - D.values[0][0]);
const secondsPerFrame = frames > 1 ? (D.rate > 0 ? span / D.rate : 4) / (frames - 1) : 1;
document.getElementById('rate').textContent = D.rate > 0
  ? '×1 = ' + +D.rate.toPrecision(4) + ' ' + D.columns[0].unit + '/s'
  : 'no drive speed: ×1 = one sweep in 4 s';
const play = document.getElementById('play');
const speed = document.getElementById('speed');
let playing = false, position = 0, last = null;
function tick(now) {
  if (!playing) return;
  if (last !== null) {
    position = (position + (now - last) / 1000 * +speed.value / secondsPerFrame) % frames;
    show(Math.floor(position));
  }
  last = now;
  requestAnimationFrame(tick);
}
function start() { if (frames < 2 || playing) return; playing = true; position = frame; last = null; play.textContent = '❚❚ pause'; requestAnimationFrame(tick); }
function stop() { playing = false; play.textContent = '▶ play'; }
play.addEventListener('click', () => (playing ? stop() : start()));
document.addEventListener('keydown', e => {
  if (e.target === speed || e.altKey || e.ctrlKey || e.metaKey) return;
  const step = e.shiftKey ? 10 : 1;
  const keys = {
    ArrowRight: () => show(frame + step), ArrowLeft: () => show(frame - step),
    Home: () => show(0), End: () => show(frames - 1),
  };
  if (e.key === ' ') { e.preventDefault(); playing ? stop() : start(); return; }
  if (keys[e.key]) { e.preventDefault(); stop(); keys[e.key](); }
});

// Zoom (wheel, about the pointer) and pan (drag) of the mechanism; double-click resets.
const home = [0, 0, +mech.getAttribute('width'), +mech.getAttribute('height')];
let view = home.slice();
function setView(v) { view = v; mech.setAttribute('viewBox', v.map(n => n.toFixed(3)).join(' ')); }
function toDrawing(e) {
  const p = new DOMPoint(e.clientX, e.clientY).matrixTransform(mech.getScreenCTM().inverse());
  return [p.x, p.y];
}
mech.addEventListener('wheel', e => {
  e.preventDefault();
  const [x, y] = toDrawing(e);
  const k = Math.min(Math.max(Math.exp(e.deltaY * 0.0015), 0.2), 5);
  const w = Math.min(Math.max(view[2] * k, home[2] / 50), home[2] * 5);
  const f = w / view[2];
  setView([x - (x - view[0]) * f, y - (y - view[1]) * f, view[2] * f, view[3] * f]);
}, { passive: false });
let drag = null;
mech.addEventListener('pointerdown', e => { drag = toDrawing(e); mech.setPointerCapture(e.pointerId); });
mech.addEventListener('pointermove', e => {
  if (!drag) return;
  const [x, y] = toDrawing(e);
  setView([view[0] - (x - drag[0]), view[1] - (y - drag[1]), view[2], view[3]]);
});
mech.addEventListener('pointerup', () => { drag = null; });
mech.addEventListener('dblclick', () => setView(home));
document.getElementById('reset-view').addEventListener('click', () => setView(home));

function save(svg, name) {
  const text = new XMLSerializer().serializeToString(svg);
  const a = document.createElement('a');
  a.href = URL.createObjectURL(new Blob([text], { type: 'image/svg+xml' }));
  a.download = name; a.click();
}
document.getElementById('save-frame').addEventListener('click', () => save(mech, 'frame_' + frame + '.svg'));
const saveDiagram = document.getElementById('save-diagram');
if (diagram) saveDiagram.addEventListener('click', () => save(diagram, 'diagram_frame_' + frame + '.svg'));
else saveDiagram.classList.add('hidden');
if (frames < 2) for (const id of ['playback', 'scrub', 'phi']) document.getElementById(id).classList.add('hidden');

// The address may name the first frame (#frame=10, or #phi=90: the nearest), a joint to
// paint red (&mark=C) and whether to show the vectors (&vectors=1).
const hash = new URLSearchParams(location.hash.slice(1));
let first = 0;
if (hash.has('frame')) first = +hash.get('frame');
if (hash.has('phi')) {
  const want = +hash.get('phi');
  let best = Infinity;
  D.values.forEach((row, i) => { const d = Math.abs(row[0] - want); if (d < best) { best = d; first = i; } });
}
if (hash.has('mark')) {
  for (const el of mech.querySelectorAll('circle.joint')) {
    if (el.getAttribute('data-point') === hash.get('mark')) {
      el.setAttribute('fill', '#ff0000'); el.setAttribute('stroke', '#ff0000');
      el.parentNode.appendChild(el);
    }
  }
}
if (hash.get('vectors') === '1') vectorBox.checked = true;
show(first);
// For scripts driving the page (the browser test): the frame shown and a way to show another.
window.mechdiffReport = { show, frames, frame: () => frame };
