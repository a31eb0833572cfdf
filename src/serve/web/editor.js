// The glyph editor: control polygon and points by kind, the fitted outline with its
// on-curve points, metric guides, components; zoom and pan; edits written through the API
// at once, with undo and redo.

import { edit, getGlyph, el, fmt, onCurvePoints } from './api.js';

const HISTORY = 500; // undo steps kept per glyph (the issue asks for at least 100)
const MARK = 5.5; // half size of a point marker, CSS pixels

export class Editor {
  constructor(app) {
    this.app = app;
    this.svg = document.getElementById('canvas');
    this.hud = document.getElementById('hud');
    this.glyph = null;
    this.name = null;
    this.sel = null; // {c, i}
    this.view = null; // {s, tx, ty}: screen = (x * s + tx, -y * s + ty)
    this.drag = null;
    this.queue = Promise.resolve();
    this.pending = 0;
    this.histories = new Map();
    this.bind();
    new ResizeObserver(() => { if (this.glyph) { if (!this.view) this.fit(); this.draw(); } }).observe(this.svg);
  }

  history() {
    if (!this.histories.has(this.name)) this.histories.set(this.name, { undo: [], redo: [] });
    return this.histories.get(this.name);
  }

  async open(name) {
    if (name !== this.name) { this.sel = null; this.view = null; }
    this.name = name;
    const g = await getGlyph(name);
    if (this.name !== name) return;
    this.set(g);
    if (!this.view) this.fit();
    this.draw();
  }

  /** Fetches the glyph again unless an edit is on its way (its answer is newer). */
  async refresh() {
    if (!this.name || this.drag || this.pending) return;
    // Queued behind edits, so an older answer never replaces a newer edit's.
    const name = this.name;
    this.queue = this.queue.then(async () => {
      const g = await getGlyph(name);
      if (name === this.name && !this.drag) this.set(g);
    }).catch((e) => this.app.toast(String(e)));
    return this.queue;
  }

  set(g) {
    this.glyph = g;
    if (this.sel && !this.point(this.sel)) this.sel = null;
    this.draw();
    this.panel();
  }

  point(sel) { return this.glyph?.contours[sel.c]?.points[sel.i]; }

  // ---- view ------------------------------------------------------------------------

  fit() {
    const info = this.app.font?.info;
    const g = this.glyph;
    if (!info || !g) return;
    let x0 = Math.min(0, g.advance), x1 = Math.max(0, g.advance);
    let y0 = info.descender, y1 = info.ascender;
    const pts = g.contours.flatMap((c) => c.points).concat(onCurvePoints(g.path));
    for (const [x, y] of pts) {
      x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y);
    }
    const w = this.svg.clientWidth || 800, h = this.svg.clientHeight || 600;
    const s = Math.min(w / ((x1 - x0) * 1.25 + 1), h / ((y1 - y0) * 1.2 + 1));
    this.view = { s, tx: w / 2 - ((x0 + x1) / 2) * s, ty: h / 2 + ((y0 + y1) / 2) * s };
  }

  zoom(factor, px, py) {
    const v = this.view;
    const s = Math.min(Math.max(v.s * factor, 0.02), 60);
    const k = s / v.s;
    this.view = { s, tx: px - (px - v.tx) * k, ty: py - (py - v.ty) * k };
    this.draw();
  }

  screen([x, y]) { const v = this.view; return [x * v.s + v.tx, -y * v.s + v.ty]; }
  font(px, py) { const v = this.view; return [(px - v.tx) / v.s, -(py - v.ty) / v.s]; }

  local(e) {
    const r = this.svg.getBoundingClientRect();
    return [e.clientX - r.left, e.clientY - r.top];
  }

  // ---- drawing ---------------------------------------------------------------------

  draw() {
    const g = this.glyph, info = this.app.font?.info;
    const svg = this.svg;
    if (!g || !info || !this.view) return;
    const w = svg.clientWidth, h = svg.clientHeight;
    svg.replaceChildren();
    const v = this.view;
    // Metric guides, across the whole view.
    const guides = el('g', { class: 'guides' }, svg);
    const [bx0, by0] = this.screen([0, info.ascender]);
    const [bx1, by1] = this.screen([g.advance, info.descender]);
    el('rect', { x: bx0, y: by0, width: Math.max(bx1 - bx0, 0), height: by1 - by0, class: 'em-box' }, guides);
    const metrics = [
      ['ascender', info.ascender], ['cap height', info.cap_height],
      ['x-height', info.x_height], ['baseline', 0], ['descender', info.descender],
    ];
    for (const [label, y] of metrics) {
      const sy = this.screen([0, y])[1];
      el('line', { x1: 0, x2: w, y1: sy, y2: sy, class: y === 0 ? 'baseline' : 'metric' }, guides);
      const t = el('text', { x: 8, y: sy - 4, class: 'metric-label' }, guides);
      t.textContent = `${label} ${fmt(y)}`;
    }
    const [ox] = this.screen([0, 0]);
    el('line', { x1: ox, x2: ox, y1: 0, y2: h, class: 'metric' }, guides);

    // Outlines in font units (one transform), strokes kept one pixel wide.
    const ink = el('g', { transform: `matrix(${v.s} 0 0 ${-v.s} ${v.tx} ${v.ty})` }, svg);
    el('path', { d: g.path, class: 'outline', 'fill-rule': 'nonzero' }, ink);
    for (const comp of g.components) {
      if (comp.path) el('path', { d: comp.path, class: 'component' }, ink).dataset.base = comp.base;
    }
    for (const comp of g.components) {
      // The label sits above the component's ink, at its left edge.
      const ink = comp.path ? onCurvePoints(comp.path) : [];
      const left = ink.length ? Math.min(...ink.map((p) => p[0])) : comp.offset[0];
      const top = ink.length ? Math.max(...ink.map((p) => p[1])) : comp.offset[1];
      const [cx, cy] = this.screen([left, top]);
      const t = el('text', { x: cx, y: cy - 6, class: 'component-label' }, svg);
      t.textContent = `${comp.base} +${fmt(comp.offset[0])},${fmt(comp.offset[1])}`;
    }

    // Advance: a line to drag, with its value.
    const [ax] = this.screen([g.advance, 0]);
    const adv = el('g', { class: 'advance' }, svg);
    el('line', { x1: ax, x2: ax, y1: 0, y2: h, class: 'advance-line' }, adv);
    el('line', { x1: ax, x2: ax, y1: 0, y2: h, class: 'advance-hit' }, adv);
    const at = el('text', { x: ax + 6, y: this.screen([0, info.descender])[1] + 16, class: 'advance-label' }, adv);
    at.textContent = `advance ${fmt(g.advance)}`;
    adv.addEventListener('pointerdown', (e) => this.startAdvance(e));

    // Control polygons; a wide invisible twin of every edge takes double-clicks.
    const polys = el('g', { class: 'polygons' }, svg);
    g.contours.forEach((c, ci) => {
      const pts = c.points.map((p) => this.screen(p));
      el('polygon', { points: pts.map((p) => p.join(',')).join(' '), class: 'polygon' }, polys);
      pts.forEach((p, i) => {
        const q = pts[(i + 1) % pts.length];
        const hit = el('line', { x1: p[0], y1: p[1], x2: q[0], y2: q[1], class: 'edge-hit' }, polys);
        hit.addEventListener('dblclick', (e) => this.insertOnEdge(e, ci, i));
      });
    });

    // On-curve points of the fitted Béziers.
    const dots = el('g', { class: 'oncurve' }, svg);
    for (const p of onCurvePoints(g.path)) {
      const [sx, sy] = this.screen(p);
      el('circle', { cx: sx, cy: sy, r: 2.2 }, dots);
    }

    // Control points by kind: squares s = 0, circles s > 0, diamonds s < 0.
    const marks = el('g', { class: 'points' }, svg);
    g.contours.forEach((c, ci) => c.points.forEach((p, i) => {
      const [sx, sy] = this.screen(p);
      const kind = p[2] === 0 ? 'sharp' : p[2] > 0 ? 'approx' : 'interp';
      const m = el('g', { class: `pt ${kind}`, transform: `translate(${sx} ${sy})` }, marks);
      Object.assign(m.dataset, { contour: ci, index: i, x: p[0], y: p[1], s: p[2] });
      if (this.sel && this.sel.c === ci && this.sel.i === i) {
        m.classList.add('selected');
        el('circle', { r: MARK + 5, class: 'halo' }, m);
      }
      if (kind === 'sharp') el('rect', { x: -MARK, y: -MARK, width: 2 * MARK, height: 2 * MARK }, m);
      else if (kind === 'approx') el('circle', { r: MARK + 0.5 }, m);
      else el('polygon', { points: `0,${-MARK - 1.5} ${MARK + 1.5},0 0,${MARK + 1.5} ${-MARK - 1.5},0` }, m);
      if (i === 0) el('circle', { r: 1.6, class: 'first' }, m);
      m.addEventListener('pointerdown', (e) => this.startPoint(e, ci, i));
    }));
    svg.dataset.version = g.version;
  }

  panel() {
    const g = this.glyph;
    const $ = (id) => document.getElementById(id);
    $('g-name').textContent = g.name;
    $('g-unicodes').textContent = g.unicodes.map((u) => 'U+' + u.toString(16).toUpperCase().padStart(4, '0')).join(' ') || '—';
    if (document.activeElement !== $('g-advance')) $('g-advance').value = fmt(g.advance);
    $('g-segments').textContent = g.segments;
    const tol = this.app.font?.info.tolerance ?? 0;
    $('g-error').textContent = `${g.worst_error.toFixed(3)} of ${fmt(tol)}`;
    $('g-version').textContent = g.version.slice(0, 8);
    const p = this.sel && this.point(this.sel);
    $('point-panel').classList.toggle('empty', !p);
    $('p-id').textContent = p ? `${this.sel.c}.${this.sel.i}` : '(none selected)';
    for (const [id, k] of [['p-x', 0], ['p-y', 1], ['p-s', 2], ['p-s-range', 2]]) {
      const input = $(id);
      input.disabled = !p;
      if (document.activeElement !== input) input.value = p ? fmt(p[k]) : '';
    }
    $('undo').disabled = !this.history().undo.length;
    $('redo').disabled = !this.history().redo.length;
  }

  // ---- edits -----------------------------------------------------------------------

  /** Sends `ops` (after the edits before it); records `{ops, inverse}` as one undo step. */
  commit(ops, inverse, { record = true, from = 'undo' } = {}) {
    const name = this.name;
    this.pending++;
    this.queue = this.queue.then(async () => {
      let { status, body } = await edit(name, this.glyph.version, ops);
      if (name !== this.name) return;
      if (status === 409) {
        // Saved elsewhere meanwhile: take the file as it is now and, when its points are
        // still the same points (no insert or delete), apply this edit on top of it.
        const now = await getGlyph(name);
        const shape = (g) => g.contours.map((c) => c.points.length).join();
        if (shape(now) === shape(this.glyph)) ({ status, body } = await edit(name, now.version, ops));
        else this.glyph = now;
      }
      if (status === 200) {
        if (record) {
          const h = this.history();
          h.undo.push({ ops, inverse });
          if (h.undo.length > HISTORY) h.undo.shift();
          if (from === 'undo') h.redo.length = 0;
        }
        this.set(body);
        return true;
      }
      if (status === 409) this.app.toast('The file changed on disk meanwhile (points added or removed): showing it as it is now; this edit was not applied.', true);
      else this.app.toast(body?.error ?? `edit refused (${status})`, true);
      this.set(await getGlyph(name));
      return false;
    }).catch((e) => { this.app.toast(String(e), true); return false; })
      .finally(() => { this.pending--; });
    return this.queue;
  }

  undo() {
    const h = this.history();
    const step = h.undo.pop();
    if (!step) return;
    this.commit(step.inverse, step.ops, { record: false }).then((ok) => {
      if (ok) h.redo.push(step); else h.undo.push(step);
      this.panel();
    });
  }

  redo() {
    const h = this.history();
    const step = h.redo.pop();
    if (!step) return;
    this.commit(step.ops, step.inverse, { from: 'redo' }).then((ok) => {
      if (!ok) h.redo.push(step);
      this.panel();
    });
  }

  setShape(s) {
    const p = this.sel && this.point(this.sel);
    if (!p) return;
    s = Math.round(Math.min(1, Math.max(-1, s)) * 1000) / 1000;
    if (s === p[2]) return;
    const { c, i } = this.sel;
    this.commit([{ op: 'shape', contour: c, point: i, s }], [{ op: 'shape', contour: c, point: i, s: p[2] }]);
  }

  moveTo(x, y) {
    const p = this.sel && this.point(this.sel);
    if (!p || (x === p[0] && y === p[1])) return;
    const { c, i } = this.sel;
    this.commit([{ op: 'move', contour: c, point: i, x, y }],
      [{ op: 'move', contour: c, point: i, x: p[0], y: p[1] }]);
  }

  deletePoint() {
    const p = this.sel && this.point(this.sel);
    if (!p) return;
    const { c, i } = this.sel;
    this.sel = null;
    this.commit([{ op: 'delete', contour: c, point: i }],
      [{ op: 'insert', contour: c, index: i, point: [...p] }]);
  }

  insertOnEdge(e, c, i) {
    e.stopPropagation();
    const [px, py] = this.local(e);
    const [x, y] = this.font(px, py).map(Math.round);
    const pts = this.glyph.contours[c].points;
    const a = pts[i], b = pts[(i + 1) % pts.length];
    const s = a[2] === 0 && b[2] === 0 ? 0 : 1;
    this.sel = { c, i: i + 1 };
    this.commit([{ op: 'insert', contour: c, index: i + 1, point: [x, y, s] }],
      [{ op: 'delete', contour: c, point: i + 1 }]);
  }

  setAdvance(value) {
    const old = this.glyph.advance;
    if (!(value >= 0) || value === old) return;
    this.commit([{ op: 'advance', value }], [{ op: 'advance', value: old }]);
  }

  // ---- pointer and keys ------------------------------------------------------------

  startPoint(e, c, i) {
    if (e.button !== 0) return;
    e.stopPropagation();
    e.preventDefault();
    this.svg.focus();
    this.sel = { c, i };
    const p = this.point(this.sel);
    this.drag = { kind: 'point', c, i, start: [p[0], p[1]], last: [p[0], p[1]], sent: [p[0], p[1]], grab: this.local(e), origin: this.screen(p) };
    this.svg.setPointerCapture(e.pointerId);
    this.draw();
    this.panel();
  }

  startAdvance(e) {
    if (e.button !== 0) return;
    e.stopPropagation();
    e.preventDefault();
    const a = this.glyph.advance;
    this.drag = { kind: 'advance', start: a, last: a, sent: a };
    this.svg.setPointerCapture(e.pointerId);
  }

  /** While dragging, the latest position is sent whenever no edit is on its way, so the
   * outline follows the pointer; the drag is one undo step. */
  stream(final) {
    const d = this.drag;
    if (!d || (!final && this.pending)) return;
    if (d.kind === 'point') {
      if (d.last[0] === d.sent[0] && d.last[1] === d.sent[1] && !final) return;
      d.sent = [...d.last];
      const op = { op: 'move', contour: d.c, point: d.i, x: d.last[0], y: d.last[1] };
      if (!final) { this.commit([op], null, { record: false }).then(() => this.stream(false)); return; }
      const moved = d.last[0] !== d.start[0] || d.last[1] !== d.start[1];
      if (moved) {
        this.commit([op], [{ op: 'move', contour: d.c, point: d.i, x: d.start[0], y: d.start[1] }]);
      }
    } else {
      if (d.last === d.sent && !final) return;
      d.sent = d.last;
      const op = { op: 'advance', value: d.last };
      if (!final) { this.commit([op], null, { record: false }).then(() => this.stream(false)); return; }
      if (d.last !== d.start) this.commit([op], [{ op: 'advance', value: d.start }]);
    }
  }

  bind() {
    const svg = this.svg;
    svg.addEventListener('pointerdown', (e) => {
      if (e.button !== 0 && e.button !== 1) return;
      if (!this.view) return;
      // Captured only once it moves, so that a double-click still reaches an edge.
      this.drag = { kind: 'pan', from: this.local(e), view: { ...this.view }, moved: false, id: e.pointerId };
    });
    svg.addEventListener('pointermove', (e) => {
      const [px, py] = this.local(e);
      if (this.view) {
        const [fx, fy] = this.font(px, py);
        this.hud.textContent = `${Math.round(fx)}, ${Math.round(fy)}   ·   ${Math.round(this.view.s * this.app.font.info.units_per_em)} px/em`;
      }
      const d = this.drag;
      if (!d) return;
      if (d.kind === 'pan') {
        const dx = px - d.from[0], dy = py - d.from[1];
        if (!d.moved && Math.abs(dx) + Math.abs(dy) > 2) {
          d.moved = true;
          svg.setPointerCapture(d.id);
        }
        if (!d.moved) return;
        this.view = { s: d.view.s, tx: d.view.tx + dx, ty: d.view.ty + dy };
        this.draw();
      } else if (d.kind === 'point') {
        const sx = d.origin[0] + px - d.grab[0], sy = d.origin[1] + py - d.grab[1];
        const [x, y] = this.font(sx, sy).map(Math.round);
        if (x === d.last[0] && y === d.last[1]) return;
        d.last = [x, y];
        const p = this.glyph.contours[d.c].points[d.i];
        p[0] = x; p[1] = y;
        this.draw();
        this.panel();
        this.stream(false);
      } else if (d.kind === 'advance') {
        const a = Math.max(0, Math.round(this.font(px, py)[0]));
        if (a === d.last) return;
        d.last = a;
        this.glyph.advance = a;
        this.draw();
        this.panel();
        this.stream(false);
      }
    });
    const end = () => {
      const d = this.drag;
      if (!d) return;
      if (d.kind === 'pan') {
        this.drag = null;
        if (!d.moved && this.sel) { this.sel = null; this.draw(); this.panel(); }
        return;
      }
      this.stream(true);
      this.drag = null;
    };
    svg.addEventListener('pointerup', end);
    svg.addEventListener('pointercancel', end);
    svg.addEventListener('wheel', (e) => {
      e.preventDefault();
      const [px, py] = this.local(e);
      this.zoom(Math.pow(1.0015, -e.deltaY), px, py);
    }, { passive: false });

    const $ = (id) => document.getElementById(id);
    $('undo').onclick = () => this.undo();
    $('redo').onclick = () => this.redo();
    $('fit').onclick = () => { this.fit(); this.draw(); };
    $('zoom-in').onclick = () => this.zoom(1.25, svg.clientWidth / 2, svg.clientHeight / 2);
    $('zoom-out').onclick = () => this.zoom(0.8, svg.clientWidth / 2, svg.clientHeight / 2);
    $('g-advance').onchange = (e) => this.setAdvance(Number(e.target.value));
    $('p-s').onchange = (e) => this.setShape(Number(e.target.value));
    $('p-s-range').onchange = (e) => this.setShape(Number(e.target.value));
    $('p-x').onchange = (e) => { const p = this.sel && this.point(this.sel); if (p) this.moveTo(Number(e.target.value), p[1]); };
    $('p-y').onchange = (e) => { const p = this.sel && this.point(this.sel); if (p) this.moveTo(p[0], Number(e.target.value)); };
    $('p-delete').onclick = () => this.deletePoint();
    for (const b of document.querySelectorAll('.kinds button')) b.onclick = () => this.setShape(Number(b.dataset.s));
  }

  /** Keys of the editor; true when the key was used. */
  key(e) {
    const ctrl = e.ctrlKey || e.metaKey;
    const k = e.key;
    if (ctrl && (k === 'z' || k === 'Z')) { e.shiftKey ? this.redo() : this.undo(); return true; }
    if (ctrl && (k === 'y' || k === 'Y')) { this.redo(); return true; }
    if (ctrl) return false;
    if (k === 'f' || k === 'F') { this.fit(); this.draw(); return true; }
    if (k === '+' || k === '=') { this.zoom(1.25, this.svg.clientWidth / 2, this.svg.clientHeight / 2); return true; }
    if (k === '-' || k === '_') { this.zoom(0.8, this.svg.clientWidth / 2, this.svg.clientHeight / 2); return true; }
    if (k === 'Tab' && this.glyph.contours.length) {
      const flat = this.glyph.contours.flatMap((c, ci) => c.points.map((_, i) => ({ c: ci, i })));
      const at = this.sel ? flat.findIndex((q) => q.c === this.sel.c && q.i === this.sel.i) : -1;
      this.sel = flat[(at + (e.shiftKey ? flat.length - 1 : 1) + flat.length) % flat.length];
      this.draw(); this.panel();
      return true;
    }
    const p = this.sel && this.point(this.sel);
    if (!p) return false;
    const step = e.shiftKey ? 10 : 1;
    const moves = { ArrowLeft: [-step, 0], ArrowRight: [step, 0], ArrowUp: [0, step], ArrowDown: [0, -step] };
    if (moves[k]) { this.moveTo(p[0] + moves[k][0], p[1] + moves[k][1]); return true; }
    if (k === '0') { this.setShape(0); return true; }
    if (k === '1') { this.setShape(1); return true; }
    if (k === '9') { this.setShape(-1); return true; }
    if (k === '[') { this.setShape(p[2] - 0.1); return true; }
    if (k === ']') { this.setShape(p[2] + 0.1); return true; }
    if (k === 'Delete' || k === 'Backspace') { this.deletePoint(); return true; }
    if (k === 'Escape') { this.sel = null; this.draw(); this.panel(); return true; }
    return false;
  }
}
