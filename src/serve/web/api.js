// The studio's HTTP API (docs/serve.md) and SVG path data helpers.

export async function getFont() {
  const r = await fetch('/api/font', { cache: 'no-store' });
  if (!r.ok) throw new Error(`GET /api/font: ${r.status}`);
  return r.json();
}

export async function getGlyph(name) {
  const r = await fetch(`/api/glyph/${encodeURIComponent(name)}`, { cache: 'no-store' });
  if (!r.ok) throw new Error(`GET glyph ${name}: ${r.status}`);
  return r.json();
}

/** POSTs ops against `version`; resolves to {status, body} whatever the status. */
export async function edit(name, version, ops) {
  const r = await fetch(`/api/glyph/${encodeURIComponent(name)}/edit`, {
    method: 'POST',
    headers: { 'Content-Type': 'application/json' },
    body: JSON.stringify({ version, ops }),
  });
  let body = null;
  try { body = await r.json(); } catch { body = { error: `HTTP ${r.status}` }; }
  return { status: r.status, body };
}

/** Listens to the event stream; `onState(true|false)` on (re)connection and loss. */
export function listen(onMessage, onState) {
  const es = new EventSource('/api/events');
  es.onopen = () => onState(true);
  es.onerror = () => onState(false);
  es.onmessage = (e) => {
    try { onMessage(JSON.parse(e.data)); } catch (err) { console.error(err); }
  };
  return es;
}

/** The on-curve points of path data made of absolute M L C Z (as the server writes). */
export function onCurvePoints(d) {
  const out = [];
  const re = /([MLCZ])([^MLCZ]*)/g;
  let m;
  while ((m = re.exec(d))) {
    const nums = m[2].trim().split(/[\s,]+/).filter(Boolean).map(Number);
    if (m[1] === 'M' || m[1] === 'L') out.push([nums[0], nums[1]]);
    if (m[1] === 'C') out.push([nums[4], nums[5]]);
  }
  return out;
}

export const svgNS = 'http://www.w3.org/2000/svg';

export function el(name, attrs = {}, parent = null) {
  const e = document.createElementNS(svgNS, name);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (parent) parent.appendChild(e);
  return e;
}

/** Formats a number as the sources do: shortest form, at most 2 decimals shown here. */
export function fmt(x) {
  return Number.isInteger(x) ? String(x) : String(Math.round(x * 1000) / 1000);
}
