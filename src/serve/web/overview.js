// The overview: one cell per glyph (name, worst error, segments) and the text line set
// in the live font with kerning.

import { el, fmt } from './api.js';

/** Draws every glyph into `root`; `open(name)` is called on a click. */
export function renderOverview(root, font, open) {
  const info = font.info;
  const top = info.ascender, bottom = info.descender;
  const height = top - bottom;
  const frag = document.createDocumentFragment();
  // Code-point order, as the sheet; unencoded glyphs (accents, .notdef) last.
  const key = (g) => (g.unicodes.length ? g.unicodes[0] : 0x110000);
  const glyphs = [...font.glyphs].sort((a, b) => key(a) - key(b));
  for (const g of glyphs) {
    const cell = document.createElement('a');
    cell.className = 'cell';
    cell.href = `#/glyph/${encodeURIComponent(g.name)}`;
    cell.dataset.glyph = g.name;
    const ink = inkWidth(g);
    const pad = height * 0.08;
    const x0 = Math.min(0, ink[0]) - pad, x1 = Math.max(g.advance, ink[1]) + pad;
    const w = Math.max(x1 - x0, height * 0.5);
    const cx = (x0 + x1) / 2;
    const svg = el('svg', { viewBox: `${cx - w / 2} ${-top - pad} ${w} ${height + 2 * pad}`,
      preserveAspectRatio: 'xMidYMid meet', class: 'cell-glyph' });
    const guides = el('g', { class: 'cell-guides' }, svg);
    el('line', { x1: cx - w, x2: cx + w, y1: 0, y2: 0 }, guides);
    el('rect', { x: 0, y: -top, width: Math.max(g.advance, 0.001), height, class: 'cell-advance' }, guides);
    if (g.path) el('path', { d: g.path, transform: 'scale(1,-1)', class: 'cell-ink' }, svg);
    cell.appendChild(svg);
    const label = document.createElement('div');
    label.className = 'cell-label';
    const uni = g.unicodes.length ? 'U+' + g.unicodes[0].toString(16).toUpperCase().padStart(4, '0') : '';
    label.innerHTML = `<b></b><span class="uni">${uni}</span>`;
    label.querySelector('b').textContent = g.name;
    const stats = document.createElement('div');
    stats.className = 'cell-stats';
    const err = g.worst_error ?? 0;
    const near = err > info.tolerance * 0.9 ? ' near' : '';
    stats.innerHTML = `<span class="err${near}" title="worst fit error, font units">ε ${err.toFixed(3)}</span>` +
      `<span title="Bézier segments">${g.segments ?? 0} seg</span>`;
    cell.append(label, stats);
    cell.addEventListener('click', (e) => { e.preventDefault(); open(g.name); });
    frag.appendChild(cell);
  }
  root.replaceChildren(frag);
}

function inkWidth(g) {
  if (!g.path) return [0, g.advance];
  const xs = g.path.match(/-?\d+(\.\d+)?/g)?.map(Number).filter((_, i) => i % 2 === 0) ?? [];
  return xs.length ? [Math.min(...xs), Math.max(...xs)] : [0, g.advance];
}

/** Sets `text` in the font into the SVG `svg`, kerning applied; `open(name)` on a click. */
export function renderLine(svg, font, text, open, highlight) {
  const info = font.info;
  const byChar = new Map();
  for (const g of font.glyphs) for (const u of g.unicodes) if (!byChar.has(u)) byChar.set(u, g);
  const notdef = font.glyphs.find((g) => g.name === '.notdef');
  const kern = new Map(font.kerning.map((k) => [`${k.left}\u0000${k.right}`, k.value]));
  svg.replaceChildren();
  const group = el('g', {}, svg);
  let x = 0, prev = null;
  for (const ch of text) {
    const g = byChar.get(ch.codePointAt(0)) ?? notdef;
    if (!g) { x += info.units_per_em / 2; prev = null; continue; }
    if (prev) x += kern.get(`${prev.name}\u0000${g.name}`) ?? 0;
    const a = el('g', { transform: `translate(${x} 0)`, class: 'line-glyph' }, group);
    a.dataset.glyph = g.name;
    if (g.name === highlight) a.classList.add('current');
    el('rect', { x: 0, y: -info.ascender, width: Math.max(g.advance, 1), height: info.ascender - info.descender, class: 'hit' }, a);
    if (g.path) el('path', { d: g.path, transform: 'scale(1 -1)' }, a);
    a.addEventListener('click', () => open(g.name));
    x += g.advance;
    prev = g;
  }
  const pad = info.units_per_em * 0.15;
  const width = Math.max(x, info.units_per_em) + 2 * pad;
  svg.setAttribute('viewBox', `${-pad} ${-info.ascender - pad / 2} ${width} ${info.ascender - info.descender + pad}`);
  svg.dataset.width = fmt(x);
}
