// The design studio: edit a design, see the mechanism and its objectives on every change,
// search in a worker, export. All numbers come from the noncirc core compiled to
// WebAssembly (pkg/, built by studio/build.sh): the page draws, it computes nothing.

import init, { Design, builtinScene, builtinScenes, dynamicsQuantities } from './pkg/noncirc_wasm.js';
import * as P from './plots.js';
import { openSolidView } from './solid.js';

const $ = (id) => document.getElementById(id);

/** The train's parameters: path, the paper's symbol, unit, meaning. */
const TRAIN = [
  ['train.phi0_deg', 'Φ0', 'deg', 'initial carrier (housing) angle'],
  ['train.beta0_deg', 'β0', 'deg', 'arm installation angle'],
  ['train.arm_length_mm', 'S', 'mm', 'arm length'],
  ['train.pusher_offset_mm', 'H1', 'mm', 'pusher offset'],
  ['train.gamma0_deg', 'γ0', 'deg', 'initial planet-carrier angle'],
];
/** Agronomic inputs, the arm sets and the carrier speed (not used while a picking rate is
 * set): path, label, unit. */
const AGRONOMY = [
  ['train.arms', 'arm sets', ''],
  ['train.picks_per_minute', 'picking rate', '1/min', { optional: 'empty: the carrier speed sets the working speed' }],
  ['train.carrier_speed_rpm', 'carrier speed', 'rpm'],
  ['agronomy.tray_normal_deg', 'tray normal', 'deg'],
  ['agronomy.tray_depth_mm', 'tray depth', 'mm'],
  ['agronomy.plant_spacing_mm', 'plant spacing', 'mm'],
  ['agronomy.seedling_height_mm', 'seedling height', 'mm'],
  ['agronomy.planting_depth_mm', 'planting depth', 'mm'],
  ['agronomy.arm_half_width_mm', 'arm half width', 'mm'],
  ['agronomy.housing_margin_mm', 'housing margin', 'mm'],
];
const RESOLUTION = [['resolution.samples_per_turn', 'samples per turn', '1/turn']];
/** The dynamics' inputs beside the picking rate (the scene's `[dynamics]`; the rest keep
 *  their values from the file): path, label, unit. */
const DYNAMICS = [
  ['dynamics.face_width_mm', 'face width', 'mm'],
  ['dynamics.arm_mass_kg', 'arm mass', 'kg'],
  ['dynamics.picking_force_n', 'picking force', 'N'],
  ['dynamics.planting_force_n', 'planting force', 'N'],
  ['dynamics.flywheel_inertia_kg_m2', 'flywheel Jf', 'kg·m²'],
  ['dynamics.speed_fluctuation_allowed', 'allowed δ', ''],
  ['dynamics.samples_per_turn', 'samples per turn', '1/turn'],
];
/** The stresses over the cycle, plotted once the teeth's strength is computed: name →
 *  [label, unit, the field of each gear's strength]. */
const STRESSES = {
  root_stress: ['root stress σF, tooth in mesh', 'MPa', 'bending_mpa'],
  contact_stress: ['contact stress σH, flank in mesh', 'MPa', 'contact_mpa'],
};
/** How long the design rests before the dynamics panel follows it (ms): its update costs
 *  about half a drag step's, so a drag shows it when the pointer pauses. */
const DYNAMICS_DELAY_MS = 120;
/** Most samples per turn at which the guide and the sweep follow every change. */
const LIVE_SAMPLES = 1440;
/** Measures shown in the table (the report has every measure). */
const SHOWN_MEASURES = /^(loop_|picking_|planting_|return_|trajectory_|section_)/;

const state = {
  design: null,
  /** The last good evaluation: `{report, view}`. */
  out: null,
  free: [],
  /** History steps `{toml, origin}`: the scene text and where the design came from. */
  undo: [],
  redo: [],
  /** Where the design came from, for the scene menu: `{name, file, toml}` (a built-in's
   *  or a file's name, and its text as loaded: the menu says "modified" once it differs). */
  origin: null,
  /** The scene text of the last committed change (the undo stack's next entry). */
  committed: '',
  carrier: 0,
  playing: false,
  worker: null,
  /** Whether the worker is running a search (one at a time). */
  searching: false,
  searchResult: null,
  /** Milliseconds of each live update (set, evaluate, draw, style and layout), for the browser test. */
  timings: [],
  /** Bounds of the mechanism and trajectory plots, kept while they hold the drawing (so
   *  that a drag does not rescale the picture at every step). */
  mechanismBounds: null,
  trajectoryBounds: null,
  /** What a click on the trajectory does: null, 'draw' (add a target point), 'picking' or
   *  'planting' (place that pose). */
  tool: null,
  /** The target's points while it is drawn (mm), before it has the four a path needs. */
  draft: [],
  /** Whether the worker's job is a fit or a repair, and its last result. */
  fitJob: null,
  fitResult: null,
  /** The dynamics panel's numbers and curves (the wasm `dynamics` view), the teeth's
   *  strength once asked for (dropped on every change), the plot's kept bounds. */
  dynamics: null,
  strength: null,
  dynamicsBounds: null,
  /** The timer of the panel's next update while the design changes (null: up to date). */
  dynamicsTimer: null,
  /** Milliseconds of each panel update (wasm, draw, style and layout), for the browser test. */
  dynamicsTimings: [],
  /** The open 3D view of the solids (`openSolidView`), or null. */
  solid: null,
};
window.studio = {
  state,
  ready: null,
  /** Where the point `[x, y]` (mm) of a plot is on the screen (client px), for the tests. */
  toScreen(id, [x, y]) {
    const svg = $(id);
    const { sx, sy } = svg.axesCache;
    const pt = svg.createSVGPoint(); pt.x = sx(x); pt.y = sy(y);
    const p = pt.matrixTransform(svg.getScreenCTM());
    return { x: p.x, y: p.y };
  },
};

// ---------------------------------------------------------------- fields and messages

/** Shows `message` beside `field` (the field keeps what the user typed), or clears it. */
function fieldMessage(field, message) {
  const box = field.closest('.row, td')?.querySelector('.msg') ?? $('file-error');
  field.classList.toggle('invalid', Boolean(message));
  field.setAttribute('aria-invalid', message ? 'true' : 'false');
  if (box) { box.textContent = message ?? ''; box.hidden = !message && box.id === 'file-error'; }
}

/**
 * Applies `key=value` assignments; on success redraws and returns true, on an error shows
 * the core's message beside `field` and keeps the last good design.
 */
function apply(assignments, field = null) {
  return change(() => state.design.set(assignments), field);
}

/** Removes the optional value at `path` (its field emptied), as `apply` sets one. */
function unset(path, field) {
  return change(() => state.design.unset(path), field);
}

/** Runs `call`, a change of the design that returns its evaluation; on success redraws
 *  and returns true, on an error shows the message beside `field` (or above the page). */
function change(call, field) {
  const t0 = performance.now();
  let text;
  try {
    text = call();
  } catch (e) {
    if (field) fieldMessage(field, e.message); else showFileError(e.message);
    return false;
  }
  if (field) fieldMessage(field, null);
  closeSolid('the design changed: open the 3D view again');
  show(JSON.parse(text), field);
  // Style and layout now, so that the timing covers them (the browser would do them before
  // the next paint anyway; raster happens off this thread).
  void document.body.offsetHeight;
  state.timings.push(performance.now() - t0);
  return true;
}

/** Records the current design as a step of the undo history, if it changed. */
function commit() {
  const now = state.design.toToml();
  if (now === state.committed) return;
  state.undo.push({ toml: state.committed, origin: state.origin });
  state.redo = [];
  state.committed = now;
  updateUndoButtons();
  markOrigin();
}

/**
 * Loads scene text as a new step of the history: a built-in or a file (`origin`
 * `{name, file}`, which the scene menu then names), or a fit's result (the origin kept).
 */
function loadStep(text, name, origin = null) {
  const before = { toml: state.design.toToml(), origin: state.origin };
  if (!load(text, name)) return false;
  state.undo.push(before);
  state.redo = [];
  state.committed = state.design.toToml();
  if (origin) {
    state.origin = { ...origin, toml: state.committed };
    // A search's or a fit's result belongs to the scene it ran on, not to this one.
    state.searchResult = null;
    state.fitResult = null;
    $('search-load').disabled = true;
    $('fit-load').disabled = true;
  }
  updateUndoButtons();
  markOrigin();
  return true;
}

/** Steps the history from `from` to `to` (undo or redo). */
function step(from, to) {
  if (!from.length) return;
  const { toml, origin } = from.pop();
  to.push({ toml: state.design.toToml(), origin: state.origin });
  load(toml, 'undo history');
  state.origin = origin;
  state.committed = state.design.toToml();
  updateUndoButtons();
  markOrigin();
}

/** The scene menu: the built-in or file the design came from, "(modified)" once it differs. */
function markOrigin() {
  const menu = $('builtin');
  const o = state.origin;
  if (!o) return;
  const modified = state.committed !== o.toml;
  let file = menu.querySelector('option[data-file]');
  if (o.file) {
    if (!file) {
      file = new Option('', '');
      file.dataset.file = 'true';
      file.disabled = true;
      menu.add(file, 0);
    }
    file.selected = true;
  } else {
    file?.remove();
    menu.value = o.name;
  }
  for (const option of menu.options) {
    const name = option.dataset.file ? `file: ${o.name}` : option.value;
    option.textContent = option.selected && modified ? `${name} (modified)` : name;
  }
  menu.title = modified ? `${o.name}, changed since it was loaded` : o.name;
}

function updateUndoButtons() {
  $('undo').disabled = state.undo.length === 0;
  $('redo').disabled = state.redo.length === 0;
}

/** Replaces the design with scene text (a file, a built-in, an undo step); false on error. */
function load(text, origin) {
  let design, out;
  try {
    design = new Design(text, origin);
    out = JSON.parse(design.evaluate());
  } catch (e) {
    design?.free();
    showFileError(e.message);
    return false;
  }
  state.design?.free();
  state.design = design;
  state.mechanismBounds = null;
  state.trajectoryBounds = null;
  $('teeth').checked = false;
  $('teeth-msg').textContent = '';
  closeSolid('');
  $('solid-status').textContent = '';
  showFileError(null);
  buildFields();
  show(out, null);
  return true;
}

function showFileError(message) {
  const box = $('file-error');
  box.textContent = message ?? '';
  box.hidden = !message;
}

/**
 * Binds a number field to `path`. Typed, pasted or deleted text is evaluated when it is
 * complete: on Enter or when the field is left, never a prefix (no "-5" on the way to
 * "-50", no two arm sets on the way to "2.5"); a step of the field's arrows or of the arrow
 * keys at once. Evaluated on leaving, the change is a step of the history. `optional`:
 * emptied, the value is unset; `onApplied` runs after each value the design took.
 */
function bindField(input, path, { optional = false, onApplied = null } = {}) {
  const evaluate = () => {
    let ok;
    if (optional && input.value.trim() === '' && input.checkValidity()) {
      ok = unset(path, input);
    } else if (input.value.trim() === '' || !input.checkValidity()) {
      fieldMessage(input, `${path}: expected a finite number`);
      return false;
    } else {
      ok = apply(`${path}=${input.value}`, input);
    }
    if (ok) onApplied?.();
    return ok;
  };
  // An arrow's step has no `inputType`; typing, pasting and deleting have one.
  input.addEventListener('input', (ev) => { if (!ev.inputType) evaluate(); });
  input.addEventListener('change', () => { if (evaluate()) commit(); });
}

/** A labelled numeric field (with a slider when `range` is given) bound to `path`; an
 *  `optional` one (its text says what an empty field means) is unset when emptied. */
function numberRow(parent, path, label, unit, { range = null, title = '', optional = null } = {}) {
  const row = document.createElement('div');
  row.className = range ? 'row slider' : 'row';
  const id = 'f-' + path.replace(/[^a-z0-9]/gi, '-');
  row.innerHTML = `<label for="${id}" title="${title}">${label}</label>`;
  let slider = null;
  if (range) {
    slider = document.createElement('input');
    Object.assign(slider, { type: 'range', min: range[0], max: range[1], step: (range[1] - range[0]) / 400 });
    // The label's text, not its markup (`Φ0 <span class="unit">…</span>`).
    slider.setAttribute('aria-label', `${label.replace(/<[^>]*>/g, '')} (${unit})`);
    row.appendChild(slider);
  }
  const input = document.createElement('input');
  Object.assign(input, { type: 'number', id, step: 'any' });
  input.dataset.path = path;
  row.appendChild(input);
  const u = document.createElement('span'); u.className = 'unit'; u.textContent = unit; row.appendChild(u);
  const guide = document.createElement('span'); guide.className = 'guide'; guide.dataset.guide = path; row.appendChild(guide);
  const msg = document.createElement('span'); msg.className = 'msg'; row.appendChild(msg);
  parent.appendChild(row);
  if (optional) input.placeholder = 'unset';
  if (optional) input.title = optional;
  bindField(input, path, { optional: Boolean(optional), onApplied: () => { if (slider) slider.value = input.value; } });
  if (slider) {
    slider.addEventListener('input', () => { if (apply(`${path}=${slider.value}`, input)) input.value = slider.value; });
    slider.addEventListener('change', commit);
  }
}

/** The editing fields of the current design (its kind, control points and train). */
function buildFields() {
  state.free = JSON.parse(state.design.freeParameters());
  const range = (path) => state.free.find((f) => f.name === path);
  const train = $('train'); train.replaceChildren();
  for (const [path, sym, unit, title] of TRAIN) {
    const f = range(path);
    numberRow(train, path, `${sym} <span class="unit">${path.split('.')[1]}</span>`, unit, { range: f ? [f.lower, f.upper] : null, title });
  }
  const agro = $('agronomy'); agro.replaceChildren();
  for (const [path, label, unit, options] of AGRONOMY) numberRow(agro, path, label, unit, options);
  const res = $('resolution'); res.replaceChildren();
  for (const [path, label, unit] of RESOLUTION) numberRow(res, path, label, unit);
  const dyn = $('dynamics-fields'); dyn.replaceChildren();
  for (const [path, label, unit] of DYNAMICS) numberRow(dyn, path, label, unit);
  const body = $('points').tBodies[0]; body.replaceChildren();
  const radii = pointValues('radii_mm');
  radii.forEach((_, i) => {
    const tr = body.insertRow();
    tr.insertCell().textContent = i;
    for (const list of ['radii_mm', 'angles_deg']) {
      const td = tr.insertCell();
      const input = document.createElement('input');
      const path = `gear.curve.${list}[${i}]`;
      Object.assign(input, { type: 'number', step: 'any' });
      input.dataset.path = path;
      input.setAttribute('aria-label', `control point ${i} ${list === 'radii_mm' ? 'radius (mm)' : 'angle (deg)'}`);
      td.appendChild(input);
      const msg = document.createElement('span'); msg.className = 'msg'; td.appendChild(msg);
      bindField(input, path);
    }
    const guide = tr.insertCell();
    guide.className = 'guide';
    guide.dataset.guide = `gear.curve.radii_mm[${i}]`;
  });
  const sweep = $('sweep-param');
  const chosen = sweep.value;
  sweep.replaceChildren(...state.free.map((f) => new Option(f.name, f.name)));
  if (state.free.some((f) => f.name === chosen)) sweep.value = chosen;
}

/** The control points' list (`radii_mm` or `angles_deg`) of the current design. */
function pointValues(list) {
  const out = [];
  for (let i = 0; ; i++) {
    try { out.push(state.design.get(`gear.curve.${list}[${i}]`)); } catch { return out; }
  }
}

/** Writes the design's values into every field not being edited or in error. */
function refreshFields(except) {
  for (const input of document.querySelectorAll('input[data-path]')) {
    if (input === except || input.classList.contains('invalid')) continue;
    let text = '';
    try { text = String(+state.design.get(input.dataset.path).toPrecision(7)); } catch { /* unset */ }
    if (input.value === text) continue;
    input.value = text;
    const slider = input.parentElement.querySelector('input[type=range]');
    if (slider) slider.value = text;
  }
  // The carrier speed follows the picking rate while one is set.
  const rpm = document.querySelector('input[data-path="train.carrier_speed_rpm"]');
  const rate = document.querySelector('input[data-path="train.picks_per_minute"]');
  if (rpm && rate) {
    rpm.disabled = rate.value !== '';
    rpm.title = rpm.disabled ? 'set by the picking rate: picks per minute / arm sets' : '';
  }
  const kind = $('curve-kind');
  const current = state.design.curveKind();
  if (![...kind.options].some((o) => o.value === current)) kind.add(new Option(current, current));
  kind.value = current;
}

// ---------------------------------------------------------------- drawing

/** Redraws everything from an evaluation. */
function show(out, except) {
  state.out = out;
  refreshFields(except);
  drawGauges(out.report);
  drawFitGauges(out);
  drawPolar(out.view);
  drawTrajectory(out.view, out.report);
  drawMechanism();
  drawMeasures(out.report);
  state.strength = null;
  drawStrength();
  scheduleDynamics();
  // The guide and the sweep evaluate about 80 neighbours: live at the usual resolutions,
  // on request above LIVE_SAMPLES (at 786 432 samples a turn they would take seconds).
  const live = out.report.samples_per_turn <= LIVE_SAMPLES;
  $('update-response').hidden = live;
  if (live) { drawGuide(); drawSweep(); } else clearGuide();
  const r = out.report;
  $('status').textContent = `${r.scene} — ${r.samples_per_turn} samples/turn` +
    (r.centre_distance_mm ? `, centre distance ${r.centre_distance_mm.toFixed(3)} mm` : '');
}

/** The gauges, the objectives' then the search constraints': built once per set of
 *  them, then updated in place. */
function drawGauges(report) {
  const box = $('gauges');
  const constraints = report.constraints ?? [];
  const rows = [...report.objectives, ...constraints];
  const names = rows.map((o) => o.label).join();
  if (box.dataset.names !== names) {
    box.replaceChildren();
    for (const [k, o] of rows.entries()) {
      const g = document.createElement('div');
      if (k < report.objectives.length) g.dataset.objective = o.name; else g.dataset.constraint = o.label;
      g.innerHTML = `<div class="head"><span>${o.label}</span><span><b class="value-text"></b> ${o.unit} <span class="unit bound"></span> <span class="verdict"></span></span></div>
        <div class="bar" role="meter" aria-label="${o.label}"><div class="ok"></div><div class="value"></div><span class="offscale" aria-hidden="true"></span></div>
        <div class="margin unit"></div>`;
      box.appendChild(g);
    }
    box.dataset.names = names;
  }
  let met = 0;
  rows.forEach((o, k) => {
    const ok = o.violation === 0;
    const lo = o.lower ?? null, hi = o.upper ?? null;
    const g = box.children[k];
    g.querySelector('.bound').textContent = lo !== null && hi !== null ? `[${lo}, ${hi}]` : lo !== null ? `≥ ${lo}` : `≤ ${hi}`;
    g.querySelector('.verdict').textContent = ok ? 'met' : 'missed';
    // A constrained measure the design does not have arrives as null (NaN in JSON).
    if (o.value === null) {
      g.className = 'gauge missed';
      g.querySelector('.value-text').textContent = '—';
      g.querySelector('.margin').textContent = 'the design has no such value';
      return;
    }
    met += ok;
    // The bar spans the bounds with room either side; a one-sided bound gets a span from it.
    const span = lo !== null && hi !== null ? hi - lo : Math.max(Math.abs(lo ?? hi) * 0.5, 1);
    const a = (lo ?? hi - 2 * span) - span * 0.5, b = (hi ?? lo + 2 * span) + span * 0.5;
    const raw = (o.value - a) / (b - a) * 100;
    const pos = (v) => Math.min(100, Math.max(0, (v - a) / (b - a) * 100));
    // Beyond the bar's range the marker sits at its edge with an arrow pointing on.
    const off = raw < 0 ? 'low' : raw > 100 ? 'high' : '';
    g.className = `gauge ${ok ? 'met' : 'missed'}${off ? ` off-${off}` : ''}`;
    g.querySelector('.value-text').textContent = P.fmt(+o.value.toPrecision(4));
    g.querySelector('.bar').setAttribute('aria-valuenow', o.value);
    const band = g.querySelector('.ok');
    band.style.left = `${pos(lo ?? a)}%`;
    band.style.right = `${100 - pos(hi ?? b)}%`;
    g.querySelector('.value').style.left = `calc(${pos(o.value)}% - 1px)`;
    g.querySelector('.offscale').textContent = off === 'low' ? '◀' : off === 'high' ? '▶' : '';
    // The margin in the objective's unit (negative: missed by that much) and, for a band,
    // as a share of its width.
    const share = lo !== null && hi !== null && hi > lo ? ` (${Math.round(o.margin / (hi - lo) * 100)} % of the band)` : '';
    g.querySelector('.margin').textContent = `margin ${o.margin >= 0 ? '+' : '−'}${P.fmt(+Math.abs(o.margin).toPrecision(3))} ${o.unit}${share}` +
      (off ? `, off the bar's scale (${off === 'low' ? 'below' : 'above'})` : '');
  });
  const v = $('verdict');
  v.textContent = `${met} of ${rows.length} met` + (constraints.length ? ` (${constraints.length} constraint${constraints.length > 1 ? 's' : ''})` : '');
  v.className = met === rows.length ? 'met' : 'missed';
  const field = $('constraints');
  if (document.activeElement !== field && !field.classList.contains('invalid')) {
    field.value = constraints.map((c) => c.label).join('; ');
  }
}

function drawPolar(view) {
  const svg = $('polar');
  const angles = pointValues('angles_deg'), radii = pointValues('radii_mm');
  const reach = Math.max(...view.curve.map(([, r]) => r), ...radii);
  // The scale stays while the curve fills 70 % to 100 % of it (no rescaling at each step of
  // a drag), so the grid is drawn again only when the scale changes.
  if (!(state.polarMax >= reach && state.polarMax <= reach / 0.7)) state.polarMax = reach * 1.12;
  const rmax = state.polarMax;
  const c = 180, s = 160 / rmax;
  const xy = (deg, r) => [c + r * s * Math.cos(deg * Math.PI / 180), c - r * s * Math.sin(deg * Math.PI / 180)];
  if (svg.dataset.rmax !== String(rmax)) {
    P.clear(svg);
    for (const r of P.ticks(0, rmax, 4).filter((r) => r > 0)) {
      P.el('circle', { cx: c, cy: c, r: r * s, fill: 'none', stroke: '#e3e7eb' }, svg);
      P.el('text', { x: c + 3, y: c - r * s - 2, fill: '#5b6573' }, svg).textContent = `${r} mm`;
    }
    for (let d = 0; d < 360; d += 30) {
      const [x, y] = xy(d, rmax);
      P.el('line', { x1: c, y1: c, x2: x, y2: y, stroke: '#eef1f4' }, svg);
      P.el('text', { x, y: y + 4, 'text-anchor': d > 90 && d < 270 ? 'start' : 'end', fill: '#5b6573' }, svg).textContent = `${d}°`;
    }
    P.el('g', { id: 'polar-data' }, svg);
    svg.dataset.rmax = rmax;
    svg.dataset.scale = s;
  }
  const data = svg.querySelector('#polar-data');
  const focused = document.activeElement?.dataset?.point;
  data.replaceChildren();
  const d = view.curve.map(([deg, r], i) => `${i ? 'L' : 'M'}${xy(deg, r).map((v) => v.toFixed(2)).join(',')}`).join('') + 'Z';
  P.el('path', { d, fill: '#1f5fa81a', stroke: '#1f5fa8', 'stroke-width': 2 }, data);
  radii.forEach((r, i) => {
    const [x, y] = xy(angles[i], r);
    const h = P.el('circle', { cx: x, cy: y, r: 6, fill: '#1f5fa8', stroke: '#fff', 'stroke-width': 1.5, tabindex: 0, class: 'handle', 'data-point': i, role: 'slider', 'aria-label': `control point ${i} radius (mm)`, 'aria-valuenow': r }, data);
    P.el('title', {}, h).textContent = `point ${i}: ${r.toFixed(2)} mm at ${angles[i]}°`;
  });
  if (focused !== undefined) data.querySelector(`[data-point="${focused}"]`)?.focus();
}

/** Drags control points along their rays (pointer) or steps them (arrow keys). */
function wireDragging() {
  const svg = $('polar');
  let dragging = null, pending = null;
  const toRadius = (ev, i) => {
    const pt = svg.createSVGPoint(); pt.x = ev.clientX; pt.y = ev.clientY;
    const p = pt.matrixTransform(svg.getScreenCTM().inverse());
    const a = pointValues('angles_deg')[i] * Math.PI / 180;
    const along = ((p.x - 180) * Math.cos(a) - (p.y - 180) * Math.sin(a)) / +svg.dataset.scale;
    return Math.max(0.5, +along.toFixed(3));
  };
  const flush = () => {
    if (pending) { apply(`gear.curve.radii_mm[${pending.i}]=${pending.r}`, null); pending = null; }
  };
  svg.addEventListener('pointerdown', (ev) => {
    const i = ev.target.dataset?.point;
    if (i === undefined) return;
    dragging = +i;
    svg.setPointerCapture(ev.pointerId);
    ev.preventDefault();
  });
  svg.addEventListener('pointermove', (ev) => {
    if (dragging === null) return;
    const first = pending === null;
    pending = { i: dragging, r: toRadius(ev, dragging) };
    if (first) requestAnimationFrame(flush);
  });
  const end = () => { if (dragging !== null) { flush(); dragging = null; commit(); } };
  svg.addEventListener('pointerup', end);
  svg.addEventListener('pointercancel', end);
  svg.addEventListener('keydown', (ev) => {
    const i = ev.target.dataset?.point;
    if (i === undefined) return;
    const step = { ArrowUp: 0.5, ArrowRight: 0.5, ArrowDown: -0.5, ArrowLeft: -0.5 }[ev.key];
    if (!step) return;
    ev.preventDefault();
    const r = pointValues('radii_mm')[+i] + step * (ev.shiftKey ? 10 : 1);
    if (apply(`gear.curve.radii_mm[${i}]=${r}`, null)) commit();
  });
}

function drawTrajectory(view, report) {
  const svg = $('trajectory');
  if (!view.trajectory.length) { P.clear(svg); return; }
  const target = view.target;
  const asked = (target?.table.poses ?? []).map((p) => [p.x_mm, p.y_mm]);
  state.trajectoryBounds = P.stableBounds(state.trajectoryBounds,
    P.bounds([view.trajectory, view.tray ?? [], [[0, 0]], target?.path ?? [], asked, state.draft], 0));
  const [x, y] = state.trajectoryBounds;
  const { sx, sy, plot, overlay, box } = P.axes(svg, { x, y, equal: true, xlabel: 'x (mm)', ylabel: 'y (mm)' });
  P.el('circle', { cx: sx(0), cy: sy(0), r: 3, fill: '#5b6573' }, plot);
  if (view.ground_y_mm !== null) P.line(plot, [[x[0] - 1e4, view.ground_y_mm], [x[1] + 1e4, view.ground_y_mm]], sx, sy, { stroke: '#8d5a2b', 'stroke-width': 2 });
  if (view.tray) P.line(plot, view.tray, sx, sy, { stroke: '#7f8c8d', 'stroke-width': 2, 'stroke-dasharray': '6 3' });
  for (const [name, , pts] of view.sections) P.line(plot, pts, sx, sy, { stroke: P.SECTION_COLOURS[name], 'stroke-width': 2.5 });
  if (view.picking_mm) P.dot(plot, view.picking_mm, sx, sy, { fill: '#000', r: 5 });
  if (view.planting_mm) P.dot(plot, view.planting_mm, sx, sy, { fill: '#fff', stroke: '#000', 'stroke-width': 2, r: 5 });
  drawTarget(plot, sx, sy, target, report.fit);
  const ev = report.events;
  const items = view.sections.map(([name, label]) => [label, P.SECTION_COLOURS[name]]);
  items.push(['ground', '#8d5a2b'], ['tray surface', '#7f8c8d']);
  if (target || state.draft.length) items.push(['target', TARGET_COLOUR]);
  P.legend(overlay, box, items);
  if (ev) {
    const anchor = (p) => (sx(p[0]) > box[0] + box[2] * 0.6 ? { x: sx(p[0]) - 8, 'text-anchor': 'end' } : { x: sx(p[0]) + 8 });
    P.el('text', { ...anchor(view.picking_mm), y: sy(view.picking_mm[1]) - 8, fill: '#000' }, plot).textContent =
      `picking θ=${ev.picking_carrier_deg.toFixed(1)}°, ${ev.picking_tip_speed_m_s.toFixed(2)} m/s`;
    P.el('text', { ...anchor(view.planting_mm), y: sy(view.planting_mm[1]) + 16, fill: '#000' }, plot).textContent =
      `planting θ=${ev.planting_carrier_deg.toFixed(1)}°`;
  }
}

// ---------------------------------------------------------------- the target

const TARGET_COLOUR = '#6a1b9a';
/** Length (mm) of the attitude strokes drawn at the poses. */
const ATTITUDE_STROKE_MM = 40;

/** The target on the trajectory plot: its path dashed, its points (handles of a drawn
 *  spline), each asked pose with its attitude stroke joined to where the arm is, and where
 *  the paths are farthest apart; or the points of a target being drawn. */
function drawTarget(plot, sx, sy, target, fit) {
  const points = target ? target.table.x_mm.map((x, i) => [x, target.table.y_mm[i]]) : [];
  const drawing = state.tool === 'draw' ? state.draft : [];
  if (target) P.line(plot, target.path, sx, sy, { stroke: TARGET_COLOUR, 'stroke-width': 2, 'stroke-dasharray': '7 4', fill: 'none' });
  if (drawing.length > 1 && drawing.length < MIN_TARGET_POINTS) P.line(plot, drawing, sx, sy, { stroke: TARGET_COLOUR, 'stroke-dasharray': '2 3', fill: 'none' });
  const handles = drawing.length ? drawing : points.length <= MAX_HANDLES ? points : [];
  handles.forEach(([x, y], i) => {
    P.el('rect', { x: sx(x) - 3.5, y: sy(y) - 3.5, width: 7, height: 7, fill: '#fff', stroke: TARGET_COLOUR, 'stroke-width': 1.5, class: 'target-point', 'data-target-point': i }, plot);
  });
  for (const [k, pose] of (target?.table.poses ?? []).entries()) {
    const at = [pose.x_mm, pose.y_mm];
    if (pose.attitude_deg !== undefined) {
      // The pusher's dip below the horizontal, drawn forward from the asked position.
      const a = -pose.attitude_deg * Math.PI / 180;
      P.line(plot, [at, [at[0] + ATTITUDE_STROKE_MM * Math.cos(a), at[1] + ATTITUDE_STROKE_MM * Math.sin(a)]], sx, sy, { stroke: TARGET_COLOUR, 'stroke-width': 2 });
    }
    P.el('path', { d: `M${sx(at[0]) - 6},${sy(at[1]) - 6}L${sx(at[0]) + 6},${sy(at[1]) + 6}M${sx(at[0]) - 6},${sy(at[1]) + 6}L${sx(at[0]) + 6},${sy(at[1]) - 6}`, stroke: TARGET_COLOUR, 'stroke-width': 2, class: 'target-pose', 'data-pose': pose.name }, plot);
    const got = fit?.poses[k];
    if (got) {
      P.line(plot, [at, got.tip_mm], sx, sy, { stroke: TARGET_COLOUR, 'stroke-width': 1 });
      P.dot(plot, got.tip_mm, sx, sy, { fill: 'none', stroke: TARGET_COLOUR, 'stroke-width': 1.5, r: 6 });
    }
  }
  if (fit && target?.table.counts) P.dot(plot, fit.hausdorff_at_mm, sx, sy, { fill: 'none', stroke: '#c62828', 'stroke-width': 2, r: 8, class: 'farthest' });
}

/** Fewest distinct points of a target path (the core's `Target::MIN_POINTS`). */
const MIN_TARGET_POINTS = 4;
/** Most points drawn as handles (a measured CSV path has thousands). */
const MAX_HANDLES = 64;

/** A value as TOML inline text: numbers of lengths and angles as floats. */
function toml(value, key = '') {
  if (Array.isArray(value)) return `[${value.map((v) => toml(v, key)).join(',')}]`;
  if (value !== null && typeof value === 'object') {
    return `{${Object.entries(value).filter(([, v]) => v !== undefined && v !== null).map(([k, v]) => `${k}=${toml(v, k)}`).join(',')}}`;
  }
  if (typeof value === 'number') return /(_mm|_deg|^value|^scale)$/.test(key) && Number.isInteger(value) ? value.toFixed(1) : String(value);
  return JSON.stringify(value);
}

/** The scene's target table with `changes` (points, poses, tolerance) over it. */
function targetWith(changes) {
  const table = state.out.view.target?.table ?? { kind: 'spline', x_mm: [], y_mm: [], tolerance_mm: +$('target-tolerance').value || 0.5 };
  return { ...table, ...changes };
}

/** Sets the scene's target to `table`; false (the message shown) if the core refuses it. */
function applyTarget(table) {
  const ok = apply(`target=${toml(table)}`, $('target-tolerance'));
  if (ok) commit();
  return ok;
}

/** A click on the trajectory in mm (0.1 mm), through the plot's axes. */
function clickMm(ev) {
  return P.dataAt($('trajectory'), ev).map((v) => +v.toFixed(1));
}

function setTool(tool) {
  state.tool = state.tool === tool ? null : tool;
  if (state.tool !== 'draw') state.draft = [];
  for (const [id, t] of [['target-draw', 'draw'], ['pose-picking', 'picking'], ['pose-planting', 'planting']]) {
    $(id).setAttribute('aria-pressed', String(state.tool === t));
  }
  $('target-draw').textContent = state.tool === 'draw' ? 'Done' : 'Draw target';
  $('trajectory').classList.toggle('placing', state.tool !== null);
  $('target-msg').textContent = state.tool === 'draw'
    ? 'click the path\'s points in the order of motion (at least four; the spline closes itself); Done ends'
    : state.tool ? `click where the arm's tip should be at ${state.tool}` : '';
  drawTrajectory(state.out.view, state.out.report);
}

/** What a click on the trajectory does with the tool in hand. */
function trajectoryClick(ev) {
  if (!state.tool || !state.out?.view.trajectory.length) return;
  const [x, y] = clickMm(ev);
  if (state.tool === 'draw') {
    state.draft.push([x, y]);
    if (state.draft.length >= MIN_TARGET_POINTS) {
      const table = targetWith({ kind: 'spline', x_mm: state.draft.map((p) => p[0]), y_mm: state.draft.map((p) => p[1]) });
      if (!applyTarget(table)) $('target-msg').textContent = $('target-tolerance').closest('.row').querySelector('.msg').textContent;
      else $('target-msg').textContent = `${state.draft.length} points: Done ends the path, another click adds one`;
    }
    drawTrajectory(state.out.view, state.out.report);
    return;
  }
  // A pose: at the located event, with the attitude the design has there now.
  const ev0 = state.out.report.events;
  const attitude = ev0 ? +ev0[`${state.tool}_attitude_deg`].toFixed(2) : undefined;
  const poses = (state.out.view.target?.table.poses ?? []).filter((p) => p.name !== state.tool);
  poses.push({ name: state.tool, at: state.tool, x_mm: x, y_mm: y, attitude_deg: attitude });
  if (applyTarget(targetWith({ poses }))) setTool(null);
  else $('target-msg').textContent = $('target-tolerance').closest('.row').querySelector('.msg').textContent;
}

/** The fit measures as gauges (`fit.json`'s rows): each against its tolerance. */
function drawFitGauges(out) {
  const box = $('fit-gauges');
  const rows = out.fit_measures ?? [];
  const target = out.view.target;
  for (const id of ['target-save', 'target-clear', 'pose-picking', 'pose-planting']) $(id).disabled = !target;
  $('fit-start').disabled = !target || state.searching;
  if (target && document.activeElement !== $('target-tolerance')) $('target-tolerance').value = target.table.tolerance_mm;
  const names = rows.map((m) => m.name).join();
  if (box.dataset.names !== names) {
    box.replaceChildren();
    for (const m of rows) {
      const g = document.createElement('div');
      g.dataset.fit = m.name;
      g.innerHTML = `<div class="head"><span>${m.name}</span><span><b class="value-text"></b> ${m.unit} <span class="unit bound"></span> <span class="verdict"></span></span></div>
        <div class="bar" role="meter" aria-label="${m.name}"><div class="ok"></div><div class="value"></div></div>`;
      box.appendChild(g);
    }
    box.dataset.names = names;
  }
  rows.forEach((m, k) => {
    const g = box.children[k];
    const tol = m.tolerance;
    // The bar spans twice the tolerance (or the value, for the reported RMS).
    const top = Math.max(2 * (tol ?? m.value), 1e-9);
    g.className = `gauge ${m.met === false ? 'missed' : 'met'}`;
    g.querySelector('.value-text').textContent = P.fmt(+m.value.toPrecision(4));
    g.querySelector('.bound').textContent = tol === null ? '' : `≤ ${tol}`;
    g.querySelector('.verdict').textContent = m.met === null ? 'reported' : m.met ? 'met' : 'missed';
    g.querySelector('.bar').setAttribute('aria-valuenow', m.value);
    const band = g.querySelector('.ok');
    band.style.left = '0%';
    band.style.right = tol === null ? '100%' : '50%';
    g.querySelector('.value').style.left = `calc(${Math.min(100, m.value / top * 100)}% - 1px)`;
  });
  const v = $('fit-verdict');
  const fit = out.report.fit;
  v.textContent = fit ? (fit.met ? 'within its tolerances' : 'not within its tolerances') : '';
  v.className = fit?.met ? 'met' : 'missed';
}

function drawMechanism() {
  const svg = $('mechanism');
  if (!state.out?.view.trajectory.length) {
    P.clear(svg);
    P.el('text', { x: 20, y: 40 }, svg).textContent = 'This scene has no three-arm mechanism.';
    return;
  }
  const frame = JSON.parse(state.design.frame(state.carrier));
  const parts = [frame.sun, state.out.view.trajectory, ...frame.arms.flatMap((a) => [a.intermediate, a.intermediate_b ?? [], a.planet, a.arm])];
  state.mechanismBounds = P.stableBounds(state.mechanismBounds, P.bounds(parts, 0));
  const [x, y] = state.mechanismBounds;
  const { sx, sy, plot } = P.axes(svg, { x, y, equal: true, xlabel: 'x (mm)', ylabel: 'y (mm)' });
  P.line(plot, state.out.view.trajectory.concat([state.out.view.trajectory[0]]), sx, sy, { stroke: '#b8c0c9', 'stroke-width': 1 });
  if (state.out.view.ground_y_mm !== null) P.line(plot, [[x[0] - 1e4, state.out.view.ground_y_mm], [x[1] + 1e4, state.out.view.ground_y_mm]], sx, sy, { stroke: '#8d5a2b', 'stroke-width': 2 });
  if (state.out.view.tray) P.line(plot, state.out.view.tray, sx, sy, { stroke: '#7f8c8d', 'stroke-width': 2, 'stroke-dasharray': '6 3' });
  const closed = (pts) => pts.concat([pts[0]]);
  P.line(plot, closed(frame.sun), sx, sy, { stroke: '#3c3c3c', 'stroke-width': 1.2, fill: '#3c3c3c14' });
  frame.arms.forEach((arm, k) => {
    const colour = P.ARM_COLOURS[k];
    P.line(plot, closed(arm.intermediate), sx, sy, { stroke: colour, 'stroke-width': 1.2 });
    // A train with two pairs: the intermediate's layer B (which drives the planet) dashed.
    if (arm.intermediate_b) P.line(plot, closed(arm.intermediate_b), sx, sy, { stroke: colour, 'stroke-width': 1.2, 'stroke-dasharray': '5 3' });
    P.line(plot, closed(arm.planet), sx, sy, { stroke: colour, 'stroke-width': 1.2 });
    P.line(plot, arm.arm, sx, sy, { stroke: colour, 'stroke-width': 5, 'stroke-linecap': 'round', 'stroke-opacity': 0.8 });
    P.dot(plot, arm.arm[1], sx, sy, { fill: colour, r: 4 });
  });
  $('carrier-out').textContent = `${Math.round(state.carrier)}°`;
  moveDynamicsMarker();
  state.solid?.place(state.carrier);
}

// ---------------------------------------------------------------- solids (3D)

/** Builds the solids (cutting the teeth first: about a second, the status says so) and
 *  opens the 3D view at the mechanism's carrier angle. */
async function openSolid() {
  const status = $('solid-status');
  status.className = '';
  status.textContent = 'cutting the teeth and building the solids…';
  await new Promise((r) => setTimeout(r, 0));
  try {
    const parts = JSON.parse(state.design.solidParts());
    closeSolid('');
    $('solid-figure').hidden = false;
    state.solid = await openSolidView(state.design, parts, $('solid'));
    state.solid.place(state.carrier);
    $('solid-stl').disabled = false;
    const copies = state.solid.placements.length;
    status.textContent = `${parts.length} parts, ${copies} copies: ${parts.map((p) => p.name).join(', ')}`;
  } catch (e) {
    status.className = 'msg';
    status.textContent = e.message;
  }
}

/** Closes the 3D view (its solids belong to a design that changed), saying `why`. */
function closeSolid(why) {
  if (!state.solid && !why) return;
  state.solid?.dispose();
  state.solid = null;
  $('solid-figure').hidden = true;
  $('solid-stl').disabled = true;
  if (why && $('solid-status').textContent) $('solid-status').textContent = why;
}

/** Each part's STL and `assembly.json` at the mechanism's carrier angle, as `noncirc cad`. */
function downloadSolids() {
  state.solid.parts.forEach((p, i) => P.download(`${p.name}.stl`, state.design.solidStl(i), 'model/stl'));
  P.download('assembly.json', state.design.solidManifest(state.carrier), 'application/json');
}

/** The measures' table: rows built once per set of measures, values updated in place. */
function drawMeasures(report) {
  const table = $('measures');
  const shown = report.measures.filter((m) => SHOWN_MEASURES.test(m.name));
  const names = shown.map((m) => m.name).join();
  if (table.dataset.names !== names) {
    table.replaceChildren();
    for (const m of shown) {
      const tr = table.insertRow();
      tr.title = m.name;
      tr.insertCell().textContent = m.description;
      tr.insertCell().className = 'num';
      tr.insertCell().textContent = m.unit;
    }
    table.dataset.names = names;
  }
  shown.forEach((m, k) => { table.rows[k].cells[1].textContent = P.fmt(+m.value.toPrecision(5)); });
}

// ---------------------------------------------------------------- dynamics

/** Updates the dynamics panel once the design has rested [`DYNAMICS_DELAY_MS`]; until then
 *  it is greyed, showing the previous design's. */
function scheduleDynamics() {
  clearTimeout(state.dynamicsTimer);
  $('dynamics-panel').classList.add('stale');
  state.dynamicsTimer = setTimeout(drawDynamics, DYNAMICS_DELAY_MS);
}

/** The dynamics panel: its numbers and the chosen quantity's curves, or why there are none. */
function drawDynamics() {
  const t0 = performance.now();
  clearTimeout(state.dynamicsTimer);
  state.dynamicsTimer = null;
  $('dynamics-panel').classList.remove('stale');
  // A stress is plotted from the strength, over the dynamics' carrier angles.
  const select = $('dynamics-quantity');
  const quantity = STRESSES[select.value] ? 'input_torque' : select.value;
  try {
    state.dynamics = JSON.parse(state.design.dynamics(quantity));
  } catch (e) {
    state.dynamics = null;
    P.clear($('dynamics-plot'));
    $('dynamics-table').replaceChildren();
    $('dynamics-table').dataset.keys = '';
    $('dynamics-msg').textContent = e.message;
    return;
  }
  $('dynamics-msg').textContent = '';
  drawDynamicsTable(state.dynamics);
  drawDynamicsPlot();
  void document.body.offsetHeight;
  state.dynamicsTimings.push(performance.now() - t0);
}

/** The quantity's curves: the view's, or each gear's stress from the strength. */
function dynamicsCurves() {
  const stress = STRESSES[$('dynamics-quantity').value];
  if (!stress || !state.strength) return state.dynamics.quantity;
  const [label, unit, field] = stress;
  return { label, unit, curves: state.strength.gears.map((g) => [g.name, g[field]]) };
}

function drawDynamicsPlot() {
  const svg = $('dynamics-plot');
  const v = state.dynamics;
  const { label, unit, curves } = dynamicsCurves();
  const lists = curves.map(([, ys]) => ys.map((y, i) => [v.carrier_deg[i], y]));
  const key = $('dynamics-quantity').value;
  const next = [[0, 360], P.bounds(lists, 0.02)[1]];
  const kept = state.dynamicsBounds?.key === key ? state.dynamicsBounds.bounds : null;
  const bounds = P.stableBounds(kept, next);
  state.dynamicsBounds = { key, bounds };
  const { sx, sy, plot, overlay, box } = P.axes(svg, { x: [0, 360], y: bounds[1], xlabel: 'carrier angle θ (°)', ylabel: `${label} (${unit})`, margin: [52, 14, 10, 36] });
  if (bounds[1][0] < 0 && bounds[1][1] > 0) P.line(plot, [[0, 0], [360, 0]], sx, sy, { stroke: '#9aa3ad', 'stroke-width': 1 });
  lists.forEach((pts, k) => P.line(plot, pts, sx, sy, { stroke: P.COLOURS[k], 'stroke-width': 1.5 }));
  P.el('line', { 'data-marker': 'carrier', y1: box[1], y2: box[1] + box[3], stroke: '#9aa3ad', 'stroke-width': 1.5 }, overlay);
  P.legend(overlay, box, curves.map(([name], k) => [name, P.COLOURS[k]]));
  moveDynamicsMarker();
}

/** The plot's line at the mechanism's carrier angle. */
function moveDynamicsMarker() {
  const svg = $('dynamics-plot');
  const marker = svg.querySelector('[data-marker=carrier]');
  if (!marker || !svg.axesCache) return;
  const x = svg.axesCache.sx(state.carrier);
  marker.setAttribute('x1', x); marker.setAttribute('x2', x);
}

/** The cycle's extremes and the speed with a constant drive torque, as `noncirc dynamics`
 *  prints them: rows built once, values updated in place; `data-value` holds each number. */
function drawDynamicsTable(v) {
  const s = v.summary;
  const rows = [
    ['carrier_rpm', `carrier speed (${v.arms} arm sets, ${P.fmt(+(v.carrier_rpm * v.arms).toPrecision(6))} picks/min)`, v.carrier_rpm, 'r/min'],
    ['torque_peak_nm', 'input torque, largest |T|', s.torque_peak_nm, 'N·m'],
    ['torque_rms_nm', 'input torque, RMS', s.torque_rms_nm, 'N·m'],
    ['torque_mean_nm', 'input torque, mean', s.torque_mean_nm, 'N·m'],
    ['torque_min_nm', 'input torque, least', s.torque_min_nm, 'N·m'],
    ['torque_max_nm', 'input torque, largest', s.torque_max_nm, 'N·m'],
    ['torque_fluctuation', 'torque fluctuation (T_max − T_min)/T_mean', s.torque_fluctuation, ''],
    ['mesh_force_peak_n.0', 'mesh force sun–intermediate, peak', s.mesh_force_peak_n[0], 'N'],
    ['mesh_force_peak_n.1', 'mesh force intermediate–planet, peak', s.mesh_force_peak_n[1], 'N'],
    ['sun_shaft_peak_n', 'sun shaft, peak', s.sun_shaft_peak_n, 'N'],
    ['carrier_bearing_peak_n', 'carrier bearing, peak', s.carrier_bearing_peak_n, 'N'],
    ['intermediate_axle_peak_n', 'intermediate axle, peak', s.intermediate_axle_peak_n, 'N'],
    ['planet_axle_peak_n', 'planet axle, peak', s.planet_axle_peak_n, 'N'],
    ['shaking_force_peak_n', 'shaking force, peak', s.shaking_force_peak_n, 'N'],
    ['shaking_moment_peak_nm', 'shaking moment, peak', s.shaking_moment_peak_nm, 'N·m'],
    ['drive_torque_nm', 'constant drive torque (the mean)', v.drive_torque_nm, 'N·m'],
    ['carrier_rpm_least', 'with it, carrier speed least', v.carrier_rpm_range[0], 'r/min'],
    ['carrier_rpm_largest', 'with it, carrier speed largest', v.carrier_rpm_range[1], 'r/min'],
    ['speed_fluctuation', `speed fluctuation δ with Jf = ${v.flywheel_inertia_kg_m2} kg·m²`, v.speed_fluctuation, ''],
    ['flywheel_needed_kg_m2', `flywheel needed for δ ≤ ${v.speed_fluctuation_allowed}`, v.flywheel_needed_kg_m2, 'kg·m²'],
    ['formulations_rel_diff', 'Newton–Euler vs energy torque, largest difference / peak', s.formulations_rel_diff, ''],
  ];
  const table = $('dynamics-table');
  const keys = rows.map((r) => r[0]).join();
  if (table.dataset.keys !== keys) {
    table.replaceChildren();
    for (const [k] of rows) {
      const tr = table.insertRow();
      tr.dataset.key = k;
      tr.insertCell(); tr.insertCell().className = 'num'; tr.insertCell().className = 'unit';
    }
    table.dataset.keys = keys;
  }
  rows.forEach(([, label, value, unit], i) => {
    const [name, num, u] = table.rows[i].cells;
    name.textContent = label;
    num.dataset.value = value ?? '';
    // No fluctuation coefficient when the mean torque is below 1 % of the RMS.
    num.textContent = value === null ? '— (mean ≈ 0)' : P.fmt(+value.toPrecision(5));
    u.textContent = unit;
  });
}

/** The teeth's strength per gear (after "Tooth strength"), or nothing; the stresses' plots
 *  only with it. */
function drawStrength() {
  const s = state.strength;
  const select = $('dynamics-quantity');
  for (const o of select.options) if (STRESSES[o.value]) o.disabled = !s;
  if (STRESSES[select.value] && !s) { select.value = 'input_torque'; scheduleDynamics(); }
  const table = $('strength-table');
  // Nothing to clear (a drag's every step comes here): the page's layout stays valid.
  if (!s && !table.rows.length && !$('strength-status').textContent) return;
  table.replaceChildren();
  if (!s) { $('strength-status').textContent = ''; return; }
  const head = table.createTHead().insertRow();
  for (const h of ['gear', 'teeth', 'm (mm)', 'σF peak (MPa)', 'tooth', 'at θ (°)', 'SF', 'σH peak (MPa)', 'tooth', 'at θ (°)', 'SH']) {
    head.appendChild(document.createElement('th')).textContent = h;
  }
  const body = table.createTBody();
  for (const g of s.gears) {
    const tr = body.insertRow();
    tr.dataset.gear = g.name;
    const cells = [g.name, g.teeth, g.module_mm.toFixed(3), g.bending_peak_mpa.toFixed(1), g.bending_worst_tooth, g.bending_peak_carrier_deg.toFixed(1),
      g.bending_safety.toFixed(2), g.contact_peak_mpa.toFixed(1), g.contact_worst_tooth, g.contact_peak_carrier_deg.toFixed(1), g.contact_safety.toFixed(2)];
    cells.forEach((c, k) => { const td = tr.insertCell(); td.textContent = c; if (k) td.className = 'num'; });
  }
  $('strength-status').textContent = `least safety factor: bending ${s.bending_safety_min.toFixed(2)}, contact ${s.contact_safety_min.toFixed(2)} ` +
    `(ISO 6336-3 method B on the cut teeth, Hertz at the pitch point; ${s.material}, b = ${s.face_width_mm} mm, KA = ${s.application_factor})`;
}

/** Cuts the teeth and checks their strength (a second or so: the status says so first). */
function startStrength() {
  const status = $('strength-status');
  status.className = '';
  status.textContent = 'cutting the teeth and checking them over the cycle…';
  $('strength-start').disabled = true;
  // Let the status paint before the work blocks the page.
  setTimeout(() => {
    try {
      state.strength = JSON.parse(state.design.strength());
      drawStrength();
    } catch (e) {
      state.strength = null;
      drawStrength();
      status.className = 'msg';
      status.textContent = e.message;
    }
    $('strength-start').disabled = false;
  }, 30);
}

/** The guide's advice for one parameter: which way, and how much the worst margin moves. */
function guideText(slope, worst, short) {
  if (slope === null) return 'a neighbour is refused';
  if (Math.abs(slope) < 5e-4) return short ? '· no effect' : `· no effect on ${worst}`;
  const arrow = slope > 0 ? '▲' : '▼';
  const size = `${slope > 0 ? '+' : '−'}${Math.abs(slope).toPrecision(2)}`;
  return short ? `${arrow} ${size}` : `${arrow} ${slope > 0 ? 'raise' : 'lower'} it: ${worst} margin ${size} per tenth of range`;
}

function clearGuide() {
  for (const span of document.querySelectorAll('[data-guide]')) span.textContent = '';
  $('guide-head').textContent = 'guide';
  P.clear($('sweep'));
  P.el('text', { x: 20, y: 30 }, $('sweep')).textContent = `Above ${LIVE_SAMPLES} samples per turn: press "Update guide and response".`;
}

/** The "guide by" menu: the worst objective the parameters move (automatic), or any of the
 *  scene's objectives; rebuilt when they change, the choice kept while it exists. */
function guideMenu(report) {
  const menu = $('guide-by');
  const names = report.objectives.map((o) => o.name);
  if (menu.dataset.names === names.join()) return;
  const chosen = menu.value;
  menu.replaceChildren(new Option('the worst the parameters move', ''), ...names.map((n) => new Option(n, n)));
  menu.value = names.includes(chosen) ? chosen : '';
  menu.dataset.names = names.join();
}

function drawGuide() {
  let guide;
  guideMenu(state.out.report);
  try { guide = JSON.parse(state.design.guide($('guide-by').value)); } catch (e) { $('guide-missed').textContent = e.message; return; }
  for (const span of document.querySelectorAll('[data-guide]')) span.textContent = '';
  for (const row of guide.rows) {
    const span = document.querySelector(`[data-guide="${CSS.escape(row.name)}"]`);
    const radius = /radii_mm/.test(row.name);
    const text = guideText(row.slope, guide.worst, radius);
    if (span) { span.textContent = text; span.title = `${row.name}: raising it by a tenth of its search range moves the ${guide.worst} margin (over its scale) by ${row.slope}`; }
    const handle = $('polar').querySelector(`[data-point="${row.name.match(/radii_mm\[(\d+)\]/)?.[1]}"]`);
    if (handle && row.slope !== null) handle.querySelector('title').textContent += ` — guide: ${text}`;
  }
  $('verdict').title = `${guide.chosen ? 'guided by' : 'worst objective'}: ${guide.worst} (margin/scale ${guide.worst_margin.toPrecision(3)})`;
  $('guide-head').textContent = `guide: ${guide.worst}`;
  $('guide-missed').textContent = guide.missed.length ? `missed: ${guide.missed.join(', ')}` : 'every objective met';
}

function drawSweep() {
  const svg = $('sweep');
  const name = $('sweep-param').value;
  const f = state.free.find((p) => p.name === name);
  if (!f) { P.clear(svg); return; }
  let rows;
  try { rows = JSON.parse(state.design.sweep(name, f.lower, f.upper, 41)); } catch (e) { P.clear(svg); P.el('text', { x: 20, y: 30 }, svg).textContent = e.message; return; }
  const clip = (v) => Math.max(-2.5, Math.min(2.5, v));
  const { sx, sy, plot, overlay, box } = P.axes(svg, { x: [f.lower, f.upper], y: [-2.5, 2.5], xlabel: name, ylabel: 'margin / scale (clipped to ±2.5)', margin: [46, 150, 10, 36] });
  P.line(plot, [[f.lower, 0], [f.upper, 0]], sx, sy, { stroke: '#5b6573', 'stroke-width': 1, 'stroke-dasharray': '4 3' });
  const names = state.out.report.objectives.map((o) => o.name);
  names.forEach((n, k) => {
    const pts = rows.map((r) => [r.value, r.margins ? clip(r.margins[k]) : NaN]);
    P.line(plot, pts, sx, sy, { stroke: P.COLOURS[k], 'stroke-width': 1.6 });
  });
  const value = state.design.get(name);
  P.line(plot, [[value, -3], [value, 3]], sx, sy, { stroke: '#000', 'stroke-width': 1 });
  const [l, t, pw] = box;
  names.forEach((n, k) => {
    P.el('line', { x1: l + pw + 8, x2: l + pw + 24, y1: t + 10 + 14 * k, y2: t + 10 + 14 * k, stroke: P.COLOURS[k], 'stroke-width': 3 }, overlay);
    P.el('text', { x: l + pw + 28, y: t + 14 + 14 * k }, overlay).textContent = n;
  });
}

// ---------------------------------------------------------------- search

function drawConvergence(history) {
  const svg = $('convergence');
  if (!history.length) { P.clear(svg); return; }
  const evals = history.map((h) => h.evaluations);
  const logcv = history.map((h) => Math.log10(Math.max(h.best_cv, 1e-6)));
  const { sx, sy, plot } = P.axes(svg, { x: [0, Math.max(...evals)], y: [Math.min(-6.2, ...logcv), Math.max(0.5, ...logcv) + 0.2], xlabel: 'evaluations', ylabel: 'log10 best violation (−6: feasible)' });
  P.line(plot, history.map((h, i) => [h.evaluations, logcv[i]]), sx, sy, { stroke: '#c62828', 'stroke-width': 2 });
}

/** Starts a search of the current design with the page's settings, or, given a
 *  checkpoint's text, resumes it with its own scene, settings and budget. */
function startSearch(checkpoint = null) {
  if (state.searching) { $('search-status').textContent = 'a search is running: stop it first'; return; }
  const settings = checkpoint ? {} : searchSettings();
  if (!settings) return;
  state.worker ??= new Worker('worker.js', { type: 'module' });
  state.searching = true;
  const history = [];
  state.searchResult = null;
  $('search-start').disabled = true; $('search-stop').disabled = false;
  $('search-load').disabled = true; $('search-checkpoint').disabled = true;
  $('search-status').textContent = 'starting…';
  $('search-result').textContent = '';
  state.worker.onmessage = ({ data }) => {
    if (data.type === 'error') {
      state.searching = false;
      $('search-status').textContent = data.message;
      $('search-start').disabled = false; $('search-stop').disabled = true;
    } else if (data.type === 'progress') {
      const p = data.progress;
      if (p.last) history.push(p.last);
      $('search-progress').value = Math.min(1, p.evaluations / p.budget);
      const rate = p.evaluations / (data.searchingMs / 1000);
      $('search-status').textContent = `${p.evaluations} / ${p.budget} evaluations, ${Math.round(rate)} per s` +
        (p.first_feasible_evaluations !== null ? `, feasible since ${p.first_feasible_evaluations}` : ', none feasible yet');
      drawConvergence(history);
    } else if (data.type === 'result') {
      state.searching = false;
      state.searchResult = data;
      const s = data.result.summary;
      drawConvergence(data.result.history);
      $('search-start').disabled = false; $('search-stop').disabled = true;
      $('search-load').disabled = false; $('search-checkpoint').disabled = false;
      $('search-status').textContent = `${s.stopped_early ? 'stopped' : 'done'}: ${s.evaluations} evaluations in ${s.seconds.toFixed(2)} s — ` +
        (s.feasible ? 'the best design meets every objective' : 'no design meeting every objective was found');
      // In the search space's order (radius 0, 1, …, 11, then the train), not the map's.
      const order = (k) => { const i = state.free.findIndex((f) => f.name === k); return i < 0 ? Infinity : i; };
      $('search-result').textContent = Object.keys(s.best).sort((a, b) => order(a) - order(b))
        .map((k) => `${k} = ${+s.best[k].toPrecision(8)}`).join('\n');
      window.studio.lastSearch = { ...data, rate: s.evaluations / (data.searchingMs / 1000) };
    }
  };
  state.worker.postMessage(checkpoint
    ? { type: 'start', job: 'search', checkpoint }
    : { type: 'start', job: 'search', scene: state.design.toToml(), ...settings });
}

/** The search panel's budget and seed, checked as the CLI checks its flags; null (the
 *  message shown beside the field) if one is not a whole number in range. */
function searchSettings() {
  const budget = Number($('budget').value), seed = Number($('seed').value);
  for (const [field, v] of [[$('budget'), budget], [$('seed'), seed]]) {
    if (!Number.isSafeInteger(v) || v < (field.id === 'budget' ? 1 : 0)) {
      fieldMessage(field, `${field.id} = '${field.value}': expected a whole number${field.id === 'budget' ? ' ≥ 1' : ' ≥ 0'}`);
      return null;
    }
    fieldMessage(field, null);
  }
  return { algorithm: $('algorithm').value, budget, seed };
}

/** Fits the design to its target (`job` 'fit') or repairs it ('repair') in the worker,
 *  with the search panel's settings: the CLI's `noncirc fit` and `noncirc repair` on one
 *  thread. */
function startJob(job) {
  if (state.searching) { $('fit-status').textContent = 'the worker is busy: stop its job first'; return; }
  const settings = searchSettings();
  if (!settings) return;
  state.worker ??= new Worker('worker.js', { type: 'module' });
  state.searching = true;
  state.fitJob = job;
  state.fitResult = null;
  for (const id of ['fit-start', 'repair-start', 'fit-load', 'search-start']) $(id).disabled = true;
  $('fit-stop').disabled = false;
  $('fit-status').textContent = 'starting…';
  $('fit-result').textContent = '';
  const done = () => {
    state.searching = false;
    $('fit-stop').disabled = true;
    $('repair-start').disabled = false; $('search-start').disabled = false;
    $('fit-start').disabled = !state.out.view.target;
  };
  state.worker.onmessage = ({ data }) => {
    if (data.type === 'error') {
      done();
      $('fit-status').textContent = data.message;
    } else if (data.type === 'progress') {
      const p = data.progress;
      const search = job === 'repair' ? p.search : p;
      const box = job === 'repair' ? `box ${p.stage} of at most ${p.stages}: ` : '';
      if (data.phase === 'refining') $('fit-status').textContent = `${box}refining (Levenberg–Marquardt)…`;
      else if (search) {
        $('fit-progress').value = Math.min(1, search.evaluations / search.budget);
        $('fit-status').textContent = `${box}${search.evaluations} / ${search.budget} evaluations` +
          (search.first_feasible_evaluations !== null ? `, feasible since ${search.first_feasible_evaluations}` : ', none feasible yet');
      }
    } else if (data.type === 'result') {
      done();
      state.fitResult = data.result;
      $('fit-load').disabled = !(data.result.best_toml ?? data.result.repaired_toml);
      if (job === 'fit') {
        const f = data.result.fit;
        $('fit-status').textContent = f.met ? 'done: the fit is within its tolerances and meets every objective' : f.feasible ? 'done: every objective met, the target not within its tolerances' : 'done: the fitted design misses an objective';
        $('fit-result').textContent = f.measures.map((m) => `${m.name} = ${+m.value.toPrecision(6)} ${m.unit}`).join('\n');
        window.studio.lastFit = data.result;
      } else {
        const r = data.result.repair;
        $('fit-status').textContent = r.repaired ? 'done: repaired, every objective met, the teeth cut and mesh' : 'done: not repaired within the budget';
        $('fit-result').textContent = [
          r.path_hausdorff_mm === null ? '' : `tip path moved: Hausdorff ${r.path_hausdorff_mm.toFixed(2)} mm, RMS ${r.path_rms_mm.toFixed(2)} mm`,
          ...r.changes.map((c) => `${c.name} (${c.symbol}) ${+c.before.toPrecision(6)} → ${+c.after.toPrecision(6)} (${c.delta_percent_of_box >= 0 ? '+' : ''}${c.delta_percent_of_box.toFixed(1)} % of its interval)`),
          ...r.teeth_set.map((t) => `teeth: ${t}`),
        ].filter(Boolean).join('\n');
        window.studio.lastRepair = data.result;
      }
    }
  };
  state.worker.postMessage({ type: 'start', job, scene: state.design.toToml(), ...settings });
}

/** Loads the fit's or the repair's scene into the editor (an undo step). */
function loadFitResult() {
  const r = state.fitResult;
  const text = r?.best_toml ?? r?.repaired_toml;
  if (!text) return;
  const before = state.design.toToml();
  loadStep(text, state.fitJob === 'fit' ? 'the fit' : 'the repair');
}

function loadSearchResult() {
  const s = state.searchResult?.result.summary;
  if (!s) return;
  const assignments = Object.entries(s.best).map(([k, v]) => `${k}=${v}`).join('\n');
  if (apply(assignments, null)) { state.mechanismBounds = null; drawMechanism(); commit(); }
}

// ---------------------------------------------------------------- wiring

function wire() {
  const builtin = $('builtin');
  for (const name of JSON.parse(builtinScenes())) builtin.add(new Option(name, name));
  builtin.value = 'paper-search';
  builtin.addEventListener('change', () => {
    if (!loadStep(builtinScene(builtin.value), builtin.value, { name: builtin.value, file: false })) markOrigin();
  });
  $('open').addEventListener('change', async (ev) => {
    const file = ev.target.files[0];
    if (!file) return;
    loadStep(await file.text(), file.name, { name: file.name, file: true });
    ev.target.value = '';
  });
  const name = () => state.out?.report.scene || 'scene';
  $('save-toml').addEventListener('click', () => P.download(`${name()}.toml`, state.design.toToml(), 'application/toml'));
  $('save-json').addEventListener('click', () => P.download(`${name()}.json`, state.design.toJson(), 'application/json'));
  $('undo').addEventListener('click', () => step(state.undo, state.redo));
  $('redo').addEventListener('click', () => step(state.redo, state.undo));
  document.addEventListener('keydown', (ev) => {
    if (!(ev.ctrlKey || ev.metaKey) || ev.target.matches('input[type=number]')) return;
    // With Shift held the key reads 'Z'.
    const key = ev.key.toLowerCase();
    if (key === 'z' && !ev.shiftKey) { ev.preventDefault(); step(state.undo, state.redo); }
    if (key === 'y' || (key === 'z' && ev.shiftKey)) { ev.preventDefault(); step(state.redo, state.undo); }
  });
  // The constraints as one line, `;` between two, applied when complete (Enter or leaving).
  $('constraints').addEventListener('change', (ev) => {
    const list = ev.target.value.split(';').map((c) => c.trim()).filter((c) => c !== '');
    if (apply(`search.constraints=${JSON.stringify(list)}`, ev.target)) commit();
  });
  $('curve-kind').addEventListener('change', (ev) => { if (apply(`gear.curve.kind="${ev.target.value}"`, ev.target)) commit(); });
  $('carrier').addEventListener('input', (ev) => { state.carrier = +ev.target.value; drawMechanism(); });
  $('play').addEventListener('click', () => {
    state.playing = !state.playing;
    $('play').textContent = state.playing ? 'Pause' : 'Play';
    let last = performance.now();
    const tick = (now) => {
      if (!state.playing) return;
      // One carrier turn in 6 s.
      state.carrier = (state.carrier + (now - last) * 0.06) % 360;
      last = now;
      $('carrier').value = Math.floor(state.carrier);
      drawMechanism();
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  });
  $('teeth').addEventListener('change', (ev) => {
    const msg = $('teeth-msg');
    if (ev.target.checked) {
      try { msg.textContent = ''; state.design.cutTeeth(); msg.className = 'guide'; msg.textContent = 'teeth cut and checked over a full turn (noncirc teeth)'; } catch (e) { msg.className = 'msg'; msg.textContent = e.message; ev.target.checked = false; }
    } else state.design.dropTeeth();
    drawMechanism();
  });
  const files = (json) => { for (const f of JSON.parse(json)) P.download(f.name, f.text); };
  $('solid-open').addEventListener('click', openSolid);
  $('solid-stl').addEventListener('click', downloadSolids);
  $('export-pitch').addEventListener('click', () => { try { files(state.design.pitchFiles()); } catch (e) { $('teeth-msg').className = 'msg'; $('teeth-msg').textContent = e.message; } });
  $('export-teeth').addEventListener('click', () => {
    const msg = $('teeth-msg');
    const force = $('export-force').checked;
    try {
      files(state.design.teethFiles(state.carrier, force));
      msg.className = 'guide';
      msg.textContent = force ? 'teeth exported (DXF, SVG, CSV), though a check may fail' : 'teeth exported (DXF, SVG, CSV)';
    } catch (e) { msg.className = 'msg'; msg.textContent = e.message; }
  });
  for (const b of document.querySelectorAll('button.fig')) {
    b.addEventListener('click', () => {
      const svg = $(b.dataset.fig);
      if (b.classList.contains('png')) P.downloadPng(svg, `${b.dataset.fig}.png`);
      else P.download(`${b.dataset.fig}.svg`, P.svgText(svg), 'image/svg+xml');
    });
  }
  $('sweep-param').addEventListener('change', drawSweep);
  $('guide-by').addEventListener('change', drawGuide);
  const quantities = $('dynamics-quantity');
  for (const [name, label] of JSON.parse(dynamicsQuantities())) quantities.add(new Option(label, name));
  for (const [name, [label]] of Object.entries(STRESSES)) quantities.add(new Option(label, name));
  quantities.addEventListener('change', () => { if (state.design) drawDynamics(); });
  $('strength-start').addEventListener('click', startStrength);
  $('update-response').addEventListener('click', () => { drawGuide(); drawSweep(); });
  $('search-start').addEventListener('click', () => startSearch());
  $('search-resume').addEventListener('change', async (ev) => {
    const file = ev.target.files[0];
    if (file) startSearch(await file.text());
    ev.target.value = '';
  });
  $('search-stop').addEventListener('click', () => state.worker?.postMessage({ type: 'stop' }));
  $('search-load').addEventListener('click', loadSearchResult);
  $('trajectory').addEventListener('click', trajectoryClick);
  $('target-draw').addEventListener('click', () => setTool('draw'));
  $('pose-picking').addEventListener('click', () => setTool('picking'));
  $('pose-planting').addEventListener('click', () => setTool('planting'));
  $('target-open').addEventListener('change', async (ev) => {
    const file = ev.target.files[0];
    if (!file) return;
    try {
      show(JSON.parse(state.design.setTarget(await file.text(), file.name, /\.toml$/i.test(file.name))), null);
      $('target-msg').textContent = '';
      commit();
    } catch (e) { $('target-msg').textContent = e.message; }
    ev.target.value = '';
  });
  $('target-save').addEventListener('click', () => P.download('target.toml', state.design.targetToml(), 'application/toml'));
  $('target-clear').addEventListener('click', () => {
    setTool(null);
    show(JSON.parse(state.design.clearTarget()), null);
    commit();
  });
  $('target-tolerance').addEventListener('change', (ev) => {
    if (state.out.view.target) applyTarget(targetWith({ tolerance_mm: Number(ev.target.value) }));
  });
  $('fit-start').addEventListener('click', () => startJob('fit'));
  $('repair-start').addEventListener('click', () => startJob('repair'));
  $('fit-stop').addEventListener('click', () => state.worker?.postMessage({ type: 'stop' }));
  $('fit-load').addEventListener('click', loadFitResult);
  $('search-checkpoint').addEventListener('click', () => P.download('checkpoint.json', state.searchResult.checkpoint, 'application/json'));
  // The file buttons are labels around hidden inputs: in the Tab order, opened with Enter
  // or Space as a button is.
  for (const label of document.querySelectorAll('label.button')) {
    label.tabIndex = 0;
    label.setAttribute('role', 'button');
    label.addEventListener('keydown', (ev) => {
      if (ev.key !== 'Enter' && ev.key !== ' ') return;
      ev.preventDefault();
      label.querySelector('input[type=file]').click();
    });
  }
  // Every plot zooms (wheel), pans (drag, when zoomed) and reads out the point under the
  // pointer; the trajectory pans only while no target tool uses its clicks.
  for (const id of ['polar', 'trajectory', 'mechanism', 'dynamics-plot', 'sweep', 'convergence']) {
    const svg = $(id);
    const readout = document.createElement('output');
    readout.className = 'readout';
    readout.setAttribute('aria-live', 'off');
    svg.closest('figure').querySelector('figcaption').appendChild(readout);
    P.inspectable(svg, readout, { canPan: id === 'trajectory' ? () => !state.tool : () => true });
  }
  wireDragging();
}

window.studio.ready = (async () => {
  await init();
  wire();
  load(builtinScene('paper-search'), 'paper-search');
  state.committed = state.design.toToml();
  state.origin = { name: 'paper-search', file: false, toml: state.committed };
  updateUndoButtons();
  markOrigin();
  document.body.dataset.ready = 'true';
})();
