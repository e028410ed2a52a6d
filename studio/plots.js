// SVG drawing for the studio: axes with round ticks, equal-scale planes, polylines. Every
// style is an attribute (not CSS), so an exported figure looks as it does on the page.

const NS = 'http://www.w3.org/2000/svg';
export const COLOURS = ['#1f77b4', '#d62728', '#2ca02c', '#9467bd', '#ff7f0e', '#8c564b', '#e377c2', '#17becf', '#7f7f7f'];
export const SECTION_COLOURS = { removal: '#1f77b4', conveying: '#2ca02c', planting: '#d62728', return: '#9467bd' };
export const ARM_COLOURS = ['#c0392b', '#2471a3', '#1e8449', '#8e44ad'];

/** An SVG element with attributes, appended to `parent` when given. */
export function el(tag, attrs = {}, parent = null) {
  const node = document.createElementNS(NS, tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, v);
  if (parent) parent.appendChild(node);
  return node;
}

/** Empties an SVG and sets its font (kept in exported files). */
export function clear(svg) {
  svg.replaceChildren();
  svg.axesCache = null;
  svg.setAttribute('font-family', 'system-ui, DejaVu Sans, sans-serif');
  svg.setAttribute('font-size', '11');
  el('rect', { x: 0, y: 0, width: '100%', height: '100%', fill: '#fff' }, svg);
}

/** About `n` round tick values covering [a, b]. */
export function ticks(a, b, n = 6) {
  if (!(b > a)) return [a];
  const raw = (b - a) / n;
  const mag = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 5, 10].map((m) => m * mag).find((s) => s >= raw);
  const out = [];
  for (let v = Math.ceil(a / step) * step; v <= b + 1e-9 * step; v += step) out.push(Math.abs(v) < 1e-12 * step ? 0 : v);
  return out;
}

/** Bounds [[x0, x1], [y0, y1]] of point lists, padded by `pad` of the span. */
export function bounds(lists, pad = 0.05) {
  let [x0, x1, y0, y1] = [Infinity, -Infinity, Infinity, -Infinity];
  for (const pts of lists) for (const [x, y] of pts) {
    if (!Number.isFinite(x) || !Number.isFinite(y)) continue;
    x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y);
  }
  if (!(x1 >= x0)) return [[0, 1], [0, 1]];
  const px = (x1 - x0 || 1) * pad, py = (y1 - y0 || 1) * pad;
  return [[x0 - px, x1 + px], [y0 - py, y1 + py]];
}

/**
 * Bounds to draw `next` in: `previous` while it holds `next` and is not much larger (so a
 * drag does not rescale the plot at every step, and the axes need not be redrawn), else
 * `next` with room to grow.
 */
export function stableBounds(previous, next) {
  if (previous) {
    const fits = [0, 1].every((k) => {
      const [a, b] = previous[k], [c, d] = next[k];
      return a <= c && d <= b && (b - a) < 1.4 * (d - c);
    });
    if (fits) return previous;
  }
  return next.map(([a, b]) => [a - 0.08 * (b - a), b + 0.08 * (b - a)]);
}

/**
 * Axes in `svg` (its viewBox size) for data ranges `x`, `y`; `equal` keeps one scale for
 * both (a plane in mm). Returns the maps from data to pixels and back, the clipped plot group and an
 * overlay group (legends), both empty. Axes asked for again with the same settings are
 * kept: only the two groups are emptied (redrawing tick labels is most of a redraw's cost).
 */
export function axes(svg, options) {
  const key = JSON.stringify(options);
  if (svg.axesCache?.key === key) {
    svg.axesCache.plot.replaceChildren();
    svg.axesCache.overlay.replaceChildren();
    return svg.axesCache;
  }
  clear(svg);
  const { x, y, equal = false, xlabel = '', ylabel = '', title = '', margin = [46, 14, 22, 36] } = options;
  // The plot's own size, whatever part of it a zoom shows (`inspectable`).
  const [w, h] = plotSize(svg);
  const [l, r, t, b] = margin;
  let [x0, x1] = x, [y0, y1] = y;
  const pw = w - l - r, ph = h - t - b;
  if (equal) {
    const s = Math.max((x1 - x0) / pw, (y1 - y0) / ph);
    const cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
    [x0, x1] = [cx - s * pw / 2, cx + s * pw / 2];
    [y0, y1] = [cy - s * ph / 2, cy + s * ph / 2];
  }
  const sx = (v) => l + (v - x0) / (x1 - x0) * pw;
  const sy = (v) => t + (y1 - v) / (y1 - y0) * ph;
  // Their inverses: a point of the viewBox (a click) back to data.
  const ix = (px) => x0 + (px - l) / pw * (x1 - x0);
  const iy = (py) => y1 - (py - t) / ph * (y1 - y0);
  const g = el('g', {}, svg);
  for (const v of ticks(x0, x1, equal ? 6 : 6)) {
    el('line', { x1: sx(v), x2: sx(v), y1: t, y2: t + ph, stroke: '#edf0f3' }, g);
    el('text', { x: sx(v), y: t + ph + 14, 'text-anchor': 'middle', fill: '#1d232b' }, g).textContent = fmt(v);
  }
  for (const v of ticks(y0, y1, 5)) {
    el('line', { x1: l, x2: l + pw, y1: sy(v), y2: sy(v), stroke: '#edf0f3' }, g);
    el('text', { x: l - 4, y: sy(v) + 4, 'text-anchor': 'end', fill: '#1d232b' }, g).textContent = fmt(v);
  }
  el('rect', { x: l, y: t, width: pw, height: ph, fill: 'none', stroke: '#9aa3ad' }, g);
  if (xlabel) el('text', { x: l + pw / 2, y: h - 3, 'text-anchor': 'middle', fill: '#1d232b' }, g).textContent = xlabel;
  if (ylabel) el('text', { x: 11, y: t + ph / 2, 'text-anchor': 'middle', transform: `rotate(-90 11 ${t + ph / 2})`, fill: '#1d232b' }, g).textContent = ylabel;
  if (title) el('text', { x: l, y: t - 5, fill: '#1d232b', 'font-weight': 600 }, g).textContent = title;
  el('clipPath', { id: `${svg.id}-clip` }, svg).appendChild(el('rect', { x: l, y: t, width: pw, height: ph }));
  const plot = el('g', { 'clip-path': `url(#${svg.id}-clip)` }, svg);
  const overlay = el('g', {}, svg);
  svg.axesCache = { key, sx, sy, ix, iy, plot, overlay, box: [l, t, pw, ph], xlabel, ylabel };
  return svg.axesCache;
}

/** The point of `svg`'s viewBox under a pointer event (zoomed or not). */
function viewBoxAt(svg, ev) {
  const pt = svg.createSVGPoint(); pt.x = ev.clientX; pt.y = ev.clientY;
  return pt.matrixTransform(svg.getScreenCTM().inverse());
}

/** The data point `[x, y]` under a pointer event, through the plot's axes. */
export function dataAt(svg, ev) {
  const p = viewBoxAt(svg, ev);
  return [svg.axesCache.ix(p.x), svg.axesCache.iy(p.y)];
}

/**
 * Makes a plot inspectable: the wheel zooms around the pointer (up to 64×), a drag on the
 * plot pans a zoomed plot, a double click shows it whole again, and `readout` (an element
 * beside the plot) gives the data coordinates under the pointer in the axes' units. A drag
 * that starts on a handle (`.handle`), or while `canPan()` is false (the page uses clicks
 * on the plot), is left to the page.
 */
export function inspectable(svg, readout, { canPan = () => true } = {}) {
  const b = svg.viewBox.baseVal;
  svg.fullBox = [b.x, b.y, b.width, b.height];
  const set = (box) => svg.setAttribute('viewBox', box.map((v) => +v.toFixed(4)).join(' '));
  const current = () => { const v = svg.viewBox.baseVal; return [v.x, v.y, v.width, v.height]; };
  const toBox = (ev) => viewBoxAt(svg, ev);
  svg.addEventListener('wheel', (ev) => {
    ev.preventDefault();
    const [x, y, w, h] = current();
    const p = toBox(ev);
    const k = ev.deltaY < 0 ? 1 / 1.25 : 1.25;
    const [fw, fh] = svg.fullBox.slice(2);
    const nw = Math.min(fw, Math.max(fw / 64, w * k)), nh = nw * h / w;
    if (nw >= fw) { set(svg.fullBox); return; }
    set([p.x - (p.x - x) * nw / w, p.y - (p.y - y) * nh / h, nw, nh]);
  }, { passive: false });
  let pan = null;
  svg.addEventListener('pointerdown', (ev) => {
    const zoomed = current()[2] < svg.fullBox[2];
    if (ev.button !== 0 || !zoomed || ev.target.closest?.('.handle') || !canPan()) return;
    pan = { start: toBox(ev), box: current() };
    svg.setPointerCapture(ev.pointerId);
  });
  svg.addEventListener('pointermove', (ev) => {
    if (pan) {
      // The point under the pointer stays under it.
      const p = toBox(ev);
      const [x, y, w, h] = current();
      set([x - (p.x - pan.start.x), y - (p.y - pan.start.y), w, h]);
    }
    const a = svg.axesCache;
    if (!a || !readout) return;
    const [x, y] = dataAt(svg, ev);
    readout.textContent = `${a.xlabel || 'x'} ${fmt(+x.toPrecision(5))}, ${a.ylabel || 'y'} ${fmt(+y.toPrecision(5))}`;
  });
  const end = () => { pan = null; };
  svg.addEventListener('pointerup', end);
  svg.addEventListener('pointercancel', end);
  svg.addEventListener('pointerleave', () => { if (readout) readout.textContent = ''; });
  svg.addEventListener('dblclick', () => set(svg.fullBox));
}

/** A number as a tick label. */
export function fmt(v) {
  const a = Math.abs(v);
  return a !== 0 && (a < 1e-3 || a >= 1e5) ? v.toExponential(1) : String(+v.toPrecision(6));
}

/** A polyline through data points `pts` ([x, y] pairs). */
export function line(parent, pts, sx, sy, attrs = {}) {
  const d = pts.filter(([x, y]) => Number.isFinite(x) && Number.isFinite(y))
    .map(([x, y], i) => `${i ? 'L' : 'M'}${sx(x).toFixed(2)},${sy(y).toFixed(2)}`).join('');
  return el('path', { d, fill: 'none', stroke: '#1d232b', 'stroke-width': 1.5, 'stroke-linejoin': 'round', ...attrs }, parent);
}

/** A dot at a data point. */
export function dot(parent, [x, y], sx, sy, attrs = {}) {
  return el('circle', { cx: sx(x), cy: sy(y), r: 4, fill: '#1d232b', ...attrs }, parent);
}

/** A legend row of coloured swatches at the plot's top left. */
export function legend(parent, [l, t], items) {
  const g = el('g', {}, parent);
  el('rect', { x: l + 4, y: t + 4, width: 8 + Math.max(...items.map(([n]) => n.length)) * 6.2 + 22, height: items.length * 14 + 6, fill: '#fff', 'fill-opacity': 0.85, stroke: '#d5dae0' }, g);
  items.forEach(([name, colour], i) => {
    el('line', { x1: l + 10, x2: l + 26, y1: t + 14 + 14 * i, y2: t + 14 + 14 * i, stroke: colour, 'stroke-width': 3 }, g);
    el('text', { x: l + 30, y: t + 18 + 14 * i, fill: '#1d232b' }, g).textContent = name;
  });
}

/** Downloads `text` as a file called `name`. */
export function download(name, text, type = 'text/plain') {
  const url = URL.createObjectURL(new Blob([text], { type }));
  const a = document.createElement('a');
  a.href = url; a.download = name; document.body.appendChild(a); a.click(); a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
}

/** A plot's own size (its viewBox's when whole; a zoom shows part of it at that size). */
function plotSize(svg) {
  return svg.fullBox ? svg.fullBox.slice(2) : [svg.viewBox.baseVal.width, svg.viewBox.baseVal.height];
}

/** An SVG element as standalone SVG text: what the plot shows (zoomed or whole) at its size. */
export function svgText(svg) {
  const copy = svg.cloneNode(true);
  copy.setAttribute('xmlns', NS);
  const [width, height] = plotSize(svg);
  copy.setAttribute('width', width); copy.setAttribute('height', height);
  return new XMLSerializer().serializeToString(copy);
}

/** Downloads an SVG element as a PNG at `scale` × its size. */
export function downloadPng(svg, name, scale = 3) {
  const [width, height] = plotSize(svg);
  const img = new Image();
  img.onload = () => {
    const canvas = document.createElement('canvas');
    canvas.width = width * scale; canvas.height = height * scale;
    const ctx = canvas.getContext('2d');
    ctx.drawImage(img, 0, 0, canvas.width, canvas.height);
    canvas.toBlob((blob) => {
      const a = document.createElement('a');
      a.href = URL.createObjectURL(blob); a.download = name; document.body.appendChild(a); a.click(); a.remove();
    }, 'image/png');
  };
  img.src = 'data:image/svg+xml;charset=utf-8,' + encodeURIComponent(svgText(svg));
}
