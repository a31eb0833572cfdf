// xglyph studio: the page's entry. Loads the font, follows the event stream, and switches
// between the overview (#/) and the glyph editor (#/glyph/NAME).

import { getFont, listen } from './api.js';
import { renderOverview, renderLine } from './overview.js';
import { Editor } from './editor.js';

const $ = (id) => document.getElementById(id);

const app = {
  font: null,
  errors: [],
  editor: null,
  current: null,
  toastTimer: 0,

  toast(message, bad = false) {
    const t = $('toast');
    t.textContent = message;
    t.classList.toggle('bad', bad);
    t.hidden = false;
    clearTimeout(this.toastTimer);
    this.toastTimer = setTimeout(() => { t.hidden = true; }, bad ? 6000 : 3000);
  },

  async loadFont() {
    this.font = await getFont();
    const info = this.font.info;
    $('family').textContent = `${info.family} ${info.style}`;
    document.title = `${info.family} — xglyph studio`;
    if (!this.current) renderOverview($('overview'), this.font, (n) => this.go(n));
    this.drawLine();
  },

  drawLine() {
    if (this.font) renderLine($('line'), this.font, $('sample').value, (n) => this.go(n), this.current);
  },

  go(name) {
    location.hash = name ? `#/glyph/${encodeURIComponent(name)}` : '#/';
  },

  async route() {
    const m = location.hash.match(/^#\/glyph\/(.+)$/);
    const name = m ? decodeURIComponent(m[1]) : null;
    this.current = name;
    $('overview').hidden = !!name;
    $('editor').hidden = !name;
    const crumbs = $('crumbs');
    crumbs.textContent = '';
    if (name) {
      const b = document.createElement('b');
      b.textContent = name;
      crumbs.append('›', b);
      await this.editor.open(name);
      $('canvas').focus();
    } else if (this.font) {
      renderOverview($('overview'), this.font, (n) => this.go(n));
    }
    this.drawLine();
  },

  showErrors(errors) {
    this.errors = errors;
    const box = $('errors');
    box.hidden = !errors.length;
    document.body.classList.toggle('broken', errors.length > 0);
    box.replaceChildren();
    if (!errors.length) return;
    const h = document.createElement('h2');
    h.textContent = `The sources have ${errors.length} error${errors.length > 1 ? 's' : ''}; showing the last good outlines`;
    box.appendChild(h);
    for (const e of errors) {
      const pre = document.createElement('pre');
      pre.className = 'diagnostic';
      pre.textContent = e.text ?? `${e.file}:${e.line}:${e.column}: error: ${e.message}`;
      box.appendChild(pre);
    }
  },

  /** Loads the font again, at most one request at a time (a drag streams many edits). */
  async refreshFont() {
    if (this.fontLoading) { this.fontStale = true; return this.fontLoading; }
    this.fontLoading = (async () => {
      do { this.fontStale = false; await this.loadFont(); } while (this.fontStale);
    })().finally(() => { this.fontLoading = null; });
    return this.fontLoading;
  },

  async onEvent(msg) {
    if (msg.errors) { this.showErrors(msg.errors); return; }
    if (msg.changed) {
      this.showErrors([]);
      await this.refreshFont();
      if (this.current) {
        const g = this.font.glyphs.find((x) => x.name === this.current);
        if (!g) { this.toast(`${this.current} is gone from the font`, true); this.go(null); return; }
        if (msg.changed.includes(this.current)) await this.editor.refresh();
      }
    }
  },
};

async function main() {
  app.editor = new Editor(app);
  listen((m) => app.onEvent(m), (up) => {
    const s = $('status');
    s.textContent = up ? 'live' : 'reconnecting…';
    s.classList.toggle('up', up);
    if (up) app.refreshFont().catch((e) => app.toast(String(e), true));
  });
  await app.loadFont();
  window.addEventListener('hashchange', () => app.route());
  $('sample').addEventListener('input', () => app.drawLine());
  document.addEventListener('keydown', (e) => {
    const t = e.target;
    const typing = t instanceof HTMLInputElement || t instanceof HTMLTextAreaElement;
    if (typing) { if (e.key === 'Escape') t.blur(); return; }
    if (app.current && app.editor.key(e)) { e.preventDefault(); return; }
    if (e.key === 'Escape' && app.current) app.go(null);
  });
  await app.route();
  document.body.dataset.ready = '1';
}

window.studio = app;
main().catch((e) => app.toast(String(e), true));
