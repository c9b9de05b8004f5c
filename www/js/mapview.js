// One design-criteria-space map: a criterion over Ks x Cs as a dense colour image (an
// RGBA ImageData put on an offscreen canvas, then scaled onto the plot), contour lines,
// the infeasible area hatched with the values showing through, axes with units and a
// colour bar drawn by the core, and the design, datum, pick and sample markers on an
// overlay canvas (so moving the design redraws only the markers). A pick surface over
// the plot takes the pointer (click, drag, touch: set the design; hover: read a value)
// and the keyboard (arrows move the design a step). The view is handed plain data
// (`setData`, `setMarkers`); it never reads the page's state.

import { colourIndex, pixels } from './colormap.js';
import { fmt, fmtPct } from './format.js';
import { drawMapFrame } from '../ridelab-first.js';
import { paintClass } from './classmarks.js';

/** The criteria drawn as maps: plane index in the wasm map, display unit and factor. */
export const CRITERIA = [
  {
    key: 'bacc', plane: 0, title: 'BAcc', long: 'RMS body acceleration', unit: 'm/s²', factor: 1,
    teach: 'Comfort: grows with a stiffer spring and a harder damper.',
  },
  {
    key: 'dtl', plane: 1, title: 'DTL', long: 'RMS dynamic tyre load', unit: 'N', factor: 1,
    teach: 'Road holding: has a best damper rate; too soft or too hard lets the wheel hop.',
  },
  {
    key: 'sws', plane: 2, title: 'SWS', long: 'RMS suspension working space', short: 'working space', unit: 'mm', factor: 1000,
    teach: 'Working space: a softer damper lets the suspension travel further.',
  },
];

/** The BAcc map with ISO 2631-1 Wk comfort (the LoFi's and HiFi's maps then carry it). */
export const WK_CRITERION = {
  ...CRITERIA[0], title: 'BAcc (Wk)', long: 'Wk-weighted RMS body acceleration',
  teach: 'Comfort by ISO 2631-1: the body acceleration weighted by the Wk curve (most felt from 4 to 12.5 Hz), m/s²; grows with a stiffer spring and a harder damper.',
};

/** The caption of an error map. */
const ERROR_TEACH = 'Surrogate minus HiFi in % of the HiFi: blue where the surrogate is lower, red where higher.';
/** The caption of an uncertainty map. */
const SIGMA_TEACH = 'Estimated 1σ relative error of the surrogate in %: zero at its HiFi samples, larger away from them.';

/** The hatch of each family of objectives (the core's `objectives()`): lines, dots, lines. */
const HATCH_OF_FAMILY = { limit: '/', band: 'dots', datum: '-' };

/** `[{bits, kind}]`: one hatch per family, `bits` the family's bits of a map's `broken` mask. */
function hatchGroups(objectives) {
  return Object.entries(HATCH_OF_FAMILY).map(([family, kind]) => ({
    kind,
    bits: objectives.filter((o) => o.family === family).reduce((b, o) => b | o.bit, 0),
  }));
}

/** The SWS limit's line by map set (`MapView.limitLine`). */
const LIMIT_LINES = new WeakMap();

/** The core's smallest map chart, logical px. */
const MIN_W = 360;
const MIN_H = 240;

const KS_UNIT = 1000; // N/m per kN/m
const CS_UNIT = 1000; // N s/m per kN s/m

function rootFontPx() {
  return parseFloat(getComputedStyle(document.documentElement).fontSize) || 15;
}

export class MapView {
  /**
   * @param {HTMLElement} parent where the figure goes
   * @param {object} crit one of CRITERIA
   * @param {object} hooks
   *   - `onPick(ks, cs)`: a click or drag on the map, N/m and N s/m;
   *   - `onKey(ev)`: a key on the focused map (true when it moved the design);
   *   - `contours(field, nx, ny, levels)`: the core's marching squares (js/compute.js
   *     `contours`), segments per level in grid coordinates: the SWS limit's line (the
   *     contour lines at the colour bar's ticks come with the frame, `drawMapFrame`);
   *   - `objectives`: the core's design objectives by mask bit (`{bit, label, family}[]`),
   *     read when a map is drawn or hovered: the page builds its map views before the core
   *     is up, so their figures are laid out while the wasm downloads.
   */
  constructor(parent, crit, hooks) {
    const { onPick, onKey, contours } = hooks;
    this.crit = crit;
    this.contours = contours;
    this.hooks = hooks;
    this.onPick = onPick;
    this.onKey = onKey;
    this.data = null;
    this.markers = null;
    this.thick = 1;

    const fig = document.createElement('figure');
    fig.className = 'map-panel';
    fig.dataset.crit = crit.key;
    const cap = document.createElement('figcaption');
    const title = document.createElement('span');
    title.className = 'map-title';
    this.titleEl = title;
    this.captionTitle();
    this.atEl = document.createElement('span');
    this.atEl.className = 'at';
    cap.append(title, this.atEl);
    this.teachEl = document.createElement('p');
    this.teachEl.className = 'teach';
    this.teachEl.textContent = crit.teach;
    cap.title = crit.teach;
    this.capEl = cap;
    const stack = document.createElement('div');
    stack.className = 'map-stack';
    this.base = document.createElement('canvas');
    this.base.className = 'base';
    this.base.setAttribute('role', 'img');
    this.base.id = `map-${crit.key}`;
    this.overlay = document.createElement('canvas');
    this.overlay.className = 'overlay';
    this.overlay.id = `map-${crit.key}-overlay`;
    this.overlay.setAttribute('aria-hidden', 'true');
    // The plot's pick surface: pointer and keyboard.
    this.surface = document.createElement('div');
    this.surface.className = 'pick-surface';
    this.surface.id = `map-${crit.key}-pick`;
    this.surface.tabIndex = 0;
    this.surface.setAttribute('role', 'group');
    this.surface.setAttribute('aria-roledescription', 'design picker');
    this.surface.setAttribute('aria-label', `${crit.title} map: click or drag to set Ks and Cs; arrow keys move Ks (left, right) and Cs (up, down) by a step, Page Up and Down by ten`);
    this.tip = document.createElement('div');
    this.tip.className = 'map-tip';
    this.tip.hidden = true;
    stack.append(this.base, this.overlay, this.surface, this.tip);
    fig.append(cap, this.teachEl, stack);
    parent.append(fig);
    this.fig = fig;
    this.stack = stack;

    this.size = { w: 0, h: 0, dpr: 1 };
    this.ro = new ResizeObserver(() => this.resize());
    this.ro.observe(stack);
    this.bindPointer();
    this.surface.addEventListener('keydown', (ev) => {
      if (this.onKey(ev)) ev.preventDefault();
    });
  }

  /**
   * The plot and colour bar in CSS px (`{fs, plot: {x, y, w, h}, bar}`) as the core's map
   * chart laid them out at the last `drawBase` (null before the first).
   */
  layout() {
    const pl = this.placed;
    if (!pl) return null;
    return layoutOf(pl);
  }

  /** Sizes the canvases to the stack; redraws and returns true when the size changed. */
  resize() {
    const r = this.stack.getBoundingClientRect();
    const dpr = window.devicePixelRatio || 1;
    const w = Math.round(r.width);
    const h = Math.round(r.height);
    if (w === this.size.w && h === this.size.h && dpr === this.size.dpr) return false;
    this.size = { w, h, dpr };
    for (const c of [this.base, this.overlay]) {
      c.width = Math.max(1, Math.round(w * dpr));
      c.height = Math.max(1, Math.round(h * dpr));
    }
    this.drawBase();
    this.drawOverlay();
    return true;
  }

  /** Line widths times `thick` (projector mode: thicker lines), from the next redraw. */
  setStyle({ thick }) {
    this.thick = thick;
  }

  /**
   * New map data. `maps`: {nx, ny, values, feasible, broken, feasibleCount} from the
   * engine; `box`: design box (N/m, N s/m); `swsLimit`: m or null; `scale`: "abs" or
   * "rel"; `datum`: the datum's criteria {bacc, dtl, sws} by the map's model (for "rel");
   * `kind`: "value" (criteria), "error" (the planes hold the surrogate's signed error
   * against the HiFi, %, and `scale` is ignored) or "sigma" (the estimated 1σ relative
   * error, %, on the absolute palette from 0); `palette`: the colour map of absolute
   * values ("viridis" or "cividis") and `tables` the colour tables by name. `draw` false
   * leaves the drawing to a later `drawBase()` (the page splits a map's update over two
   * tasks).
   */
  setData({ maps, box, swsLimit, scale, datum, kind = 'value', palette = 'viridis', tables }, draw = true) {
    const { nx, ny, values } = maps;
    const n = nx * ny;
    const off = this.crit.plane * n;
    const f = this.crit.factor;
    const error = kind === 'error';
    const sigma = kind === 'sigma';
    if (error) scale = 'rel';
    if (sigma) scale = 'abs';
    const ref = datum ? datum[this.crit.key] : 1;
    // The shown values and their range in one pass. The colour range spans every design
    // in the box, the infeasible ones too: their values show through the hatching.
    const shown = new Float64Array(n);
    let lo = Infinity;
    let hi = -Infinity;
    for (let k = 0; k < n; k++) {
      const v = values[off + k];
      const x = error || sigma ? v : scale === 'rel' ? (v / ref - 1) * 100 : v * f;
      shown[k] = x;
      if (x < lo) lo = x;
      if (x > hi) hi = x;
    }
    if (sigma) lo = 0;
    if (scale === 'rel') {
      const m = Math.max(Math.abs(lo), Math.abs(hi), 1e-9);
      lo = -m;
      hi = m;
    } else if (!(hi > lo)) {
      const pad = Math.max(1e-9, Math.abs(lo) * 1e-3);
      lo -= pad;
      hi += pad;
    }
    const colourMap = scale === 'rel' ? 'diverging' : palette;
    const table = tables[colourMap];

    // The dense colour image and the infeasible masks (one per hatch: opaque where a
    // design breaks an objective of that group, bits of `maps.broken`) in one pass over
    // the grid: one pixel per cell, row 0 at the top (highest Cs).
    const img = new ImageData(nx, ny);
    const cells = new Uint32Array(img.data.buffer);
    const colours = pixels(table);
    const groups = hatchGroups(this.hooks.objectives).filter((g) => g.bits);
    const masks = groups.map((g) => ({ ...g, image: new ImageData(nx, ny), any: false }));
    for (let j = 0; j < ny; j++) {
      const row = (ny - 1 - j) * nx;
      for (let i = 0; i < nx; i++) {
        const k = j * nx + i;
        cells[row + i] = colours[colourIndex((shown[k] - lo) / (hi - lo))];
        const b = maps.broken[k];
        if (!b) continue;
        for (const m of masks) {
          if (b & m.bits) {
            m.image.data[4 * (row + i) + 3] = 255;
            m.any = true;
          }
        }
      }
    }
    const colour = new OffscreenCanvas(nx, ny);
    colour.getContext('2d').putImageData(img, 0, 0);
    const drawn = masks.filter((m) => m.any).map(({ kind, bits, image }) => {
      const canvas = new OffscreenCanvas(nx, ny);
      canvas.getContext('2d').putImageData(image, 0, 0);
      return { kind, bits, canvas };
    });

    const limitLine = swsLimit && !error ? this.limitLine(maps, swsLimit) : [];

    this.data = {
      nx, ny, box, lo, hi, colourMap, colour, masks: drawn, limitLine, scale,
      // Contour levels and lines: at the colour bar's ticks, set when it is drawn.
      levels: [], contours: [],
      infeasible: maps.feasibleCount < n,
      unit: error ? '% error vs HiFi' : sigma ? '% estimated 1σ' : scale === 'rel' ? '% vs datum' : this.crit.unit,
      shown, kind, feasible: maps.feasible, broken: maps.broken,
    };
    const teach = error ? ERROR_TEACH : sigma ? SIGMA_TEACH : this.crit.teach;
    // Set only when it changes: a text change lays the page out again.
    if (this.teachEl.textContent !== teach) this.teachEl.textContent = teach;
    this.capEl.title = teach;
    this.base.setAttribute(
      'aria-label',
      `${error ? `Surrogate error in ${this.crit.long}` : sigma ? `Estimated uncertainty of the surrogate's ${this.crit.long}` : this.crit.long} map over spring rate Ks ${box.ks_min / KS_UNIT} to ${box.ks_max / KS_UNIT} kN/m ` +
        `and damper rate Cs ${box.cs_min / CS_UNIT} to ${box.cs_max / CS_UNIT} kNs/m; ` +
        `values ${fmt(lo)} to ${fmt(hi)} ${this.data.unit}.`,
    );
    if (draw) this.drawAtSize();
  }

  /**
   * The SWS limit's line on `maps` (the SWS plane of its `values`): traced once for the
   * three views that show one map set, not once per view.
   */
  limitLine(maps, swsLimit) {
    const kept = LIMIT_LINES.get(maps);
    if (kept && kept.swsLimit === swsLimit) return kept.line;
    const n = maps.nx * maps.ny;
    const line = this.contours(maps.values.subarray(2 * n, 3 * n), maps.nx, maps.ny, [swsLimit])[0];
    LIMIT_LINES.set(maps, { swsLimit, line });
    return line;
  }

  /**
   * Draws the base at the box's size now: the box may have changed since the
   * ResizeObserver last reported (the page's first state fills the readout in the same
   * task), and a resize redraws base and overlay, so the map is drawn once, not twice.
   */
  drawAtSize() {
    if (!this.resize()) this.drawBase();
  }

  /** The caption's title of `this.crit`: "BAcc: RMS body acceleration". */
  captionTitle() {
    const crit = this.crit;
    // "RMS ", "design: " and then the long name give way when the panel is narrow
    // (style.css, container queries on .map-panel), so the caption is never cut.
    const span = (cls, text) => {
      const el = document.createElement('span');
      el.className = cls;
      el.textContent = text;
      return el;
    };
    const rms = crit.long.startsWith('RMS ');
    const name = rms ? crit.long.slice(4) : crit.long;
    const named = span('named', ': ');
    named.append(span('rms', rms ? 'RMS ' : ''), span('name-long', name), span('name-short', crit.short || name));
    this.titleEl.replaceChildren(crit.title, named);
  }

  /**
   * The BAcc map's comfort measure: ISO 2631-1 Wk-weighted (`wk` true) or unweighted;
   * its caption, teaching line and colour-bar label follow (the next `setData` draws them).
   */
  setComfort(wk) {
    if (this.crit.key !== 'bacc') return;
    const crit = wk ? WK_CRITERION : CRITERIA[0];
    if (crit === this.crit) return;
    this.crit = crit;
    this.captionTitle();
    this.teachEl.textContent = crit.teach;
    this.capEl.title = crit.teach;
  }

  /**
   * The design and datum points (N/m, N s/m), optionally the surrogate's sample points,
   * the min-max pick ({ks, cs}) and the adaptive loop's `{added, next}` (the samples it
   * added, its next proposal or null), the class front's designs (`klass`: `[{rank, ks,
   * cs}]` or null, js/classmarks.js), and the caption's text (the design's value).
   */
  setMarkers({ design, datum, samples = null, pick = null, adaptive = null, klass = null }, caption) {
    this.markers = { design, datum, samples, pick, adaptive, klass };
    const label = caption.startsWith('design: ') ? 'design: ' : '';
    const labelEl = document.createElement('span');
    labelEl.className = 'at-label';
    labelEl.textContent = label;
    this.atEl.replaceChildren(labelEl, caption.slice(label.length));
    this.drawOverlay();
  }

  /** The map chart spec of the current data for the core (`drawMapFrame`, `mapChartSvg`). */
  chartSpec(width, height) {
    const d = this.data;
    return {
      unit: `${this.crit.title} [${d.unit}]`,
      nx: d.nx,
      ny: d.ny,
      values: d.shown,
      designBox: d.box,
      colourMap: d.colourMap,
      range: [d.lo, d.hi],
      legend: 'none',
      width,
      height,
    };
  }

  /**
   * The map on screen: plotters draws the frame (axes, ticks, labels, colour bar with
   * its unit) at the core's layout; the page puts the dense colour image in it, then the
   * contour lines at the colour bar's ticks, the hatching and the SWS limit.
   */
  drawBase() {
    if (!this.size.w) return;
    const { w, h, dpr } = this.size;
    if (!this.data) {
      const g = this.base.getContext('2d');
      g.setTransform(dpr, 0, 0, dpr, 0, 0);
      g.clearRect(0, 0, w, h);
      return;
    }
    // Logical px: the CSS size over the type zoom, never below the chart's minimum.
    const zoom = Math.min(rootFontPx() / 15, w / MIN_W, h / MIN_H);
    this.placed = this.paint(this.base, w, h, dpr, zoom);
    const l = this.layout();
    if (l) {
      const st = this.surface.style;
      st.left = `${l.plot.x}px`;
      st.top = `${l.plot.y}px`;
      st.width = `${l.plot.w}px`;
      st.height = `${l.plot.h}px`;
    }
  }

  /**
   * Paints the map on `canvas` (`w` x `h` CSS px at `dpr` device px each, laid out at
   * `zoom`); returns where the core placed frame and bar (with `zoom`), or null with the
   * message drawn when the core refused.
   */
  paint(canvas, w, h, dpr, zoom) {
    const d = this.data;
    let placed;
    try {
      placed = { ...drawMapFrame(canvas, this.chartSpec(Math.max(MIN_W, Math.floor(w / zoom)), Math.max(MIN_H, Math.floor(h / zoom))), dpr * zoom), zoom };
      this.error = null;
    } catch (e) {
      this.error = { message: String(e.message || e), field: e.field || '' };
      const g = canvas.getContext('2d');
      g.setTransform(dpr, 0, 0, dpr, 0, 0);
      g.clearRect(0, 0, w, h);
      g.fillStyle = '#a3281d';
      g.font = '13px system-ui, sans-serif';
      g.fillText(`Cannot draw this map: ${this.error.message}`, 8, 20, w - 16);
      return null;
    }
    const g = canvas.getContext('2d');
    g.setTransform(dpr, 0, 0, dpr, 0, 0);
    const { plot } = layoutOf(placed);
    const gx = (x) => plot.x + ((x + 0.5) / d.nx) * plot.w; // grid -> CSS px
    const gy = (y) => plot.y + plot.h - ((y + 0.5) / d.ny) * plot.h;
    const lw = this.thick;

    // Colour image, smoothly scaled from one pixel per cell.
    g.imageSmoothingEnabled = true;
    g.imageSmoothingQuality = 'high';
    g.drawImage(d.colour, plot.x, plot.y, plot.w, plot.h);

    // Contour lines at the colour bar's ticks, which the core drew the frame with and
    // traced on the spec's values in the same call: a dark halo under a light line reads
    // on both ends of the colour map.
    d.levels = placed.levels;
    d.contours = placed.contours;
    const strokeSegs = (segs) => {
      g.beginPath();
      for (let k = 0; k < segs.length; k += 4) {
        g.moveTo(gx(segs[k]), gy(segs[k + 1]));
        g.lineTo(gx(segs[k + 2]), gy(segs[k + 3]));
      }
      g.stroke();
    };
    g.save();
    g.beginPath();
    g.rect(plot.x, plot.y, plot.w, plot.h);
    g.clip();
    g.lineCap = 'round';
    for (const segs of d.contours) {
      g.strokeStyle = 'rgba(0,0,0,0.35)';
      g.lineWidth = 2 * lw;
      strokeSegs(segs);
      g.strokeStyle = 'rgba(255,255,255,0.85)';
      g.lineWidth = 0.8 * lw;
      strokeSegs(segs);
    }

    // Infeasible area: a pattern per objective group ('/' SWS limit, dots the frequency
    // bands, '-' worse than the datum), each cut to its mask, over a light wash: the
    // colours (the values) stay readable underneath.
    const W = Math.ceil(plot.w * dpr);
    const H = Math.ceil(plot.h * dpr);
    for (const m of d.masks) {
      const scratch = this.scratchCanvas(W, H);
      const sg = scratch.getContext('2d');
      sg.globalCompositeOperation = 'copy';
      sg.drawImage(this.hatchPattern(m.kind, W, H, dpr), 0, 0);
      sg.globalCompositeOperation = 'destination-in';
      sg.imageSmoothingEnabled = false;
      sg.drawImage(m.canvas, 0, 0, W, H);
      g.drawImage(scratch, 0, 0, W, H, plot.x, plot.y, plot.w, plot.h);
    }
    // The SWS limit itself.
    if (d.limitLine.length) {
      g.strokeStyle = '#fff';
      g.lineWidth = 3.5 * lw;
      strokeSegs(d.limitLine);
      g.strokeStyle = '#000';
      g.lineWidth = 1.6 * lw;
      strokeSegs(d.limitLine);
    }
    g.restore();
    g.strokeStyle = '#333';
    g.lineWidth = 1;
    g.strokeRect(plot.x, plot.y, plot.w, plot.h);
    return placed;
  }

  /** A `w` x `h` scratch canvas of this view (device px), kept between redraws. */
  scratchCanvas(w, h) {
    if (!this.scratch || this.scratch.width !== w || this.scratch.height !== h) this.scratch = new OffscreenCanvas(w, h);
    return this.scratch;
  }

  /**
   * The hatch of kind `kind` ('/', '-' or 'dots') on a `w` x `h` canvas (device px, `dpr`
   * a CSS px): a light wash with dark marks haloed in white, drawn once per size and kind.
   */
  hatchPattern(kind, w, h, dpr) {
    this.patterns = this.patterns || new Map();
    const key = `${kind} ${w} ${h} ${dpr} ${this.thick}`;
    let c = this.patterns.get(key);
    if (c) return c;
    if (this.patterns.size > 6) this.patterns.clear();
    c = new OffscreenCanvas(w, h);
    const hg = c.getContext('2d');
    hg.fillStyle = 'rgba(255,255,255,0.28)';
    hg.fillRect(0, 0, w, h);
    const gap = 8 * dpr * this.thick;
    const path = () => {
      hg.beginPath();
      if (kind === '-') {
        for (let y = gap / 2; y < h; y += gap) {
          hg.moveTo(0, y);
          hg.lineTo(w, y);
        }
      } else if (kind === '/') {
        for (let x = -h; x < w; x += gap) {
          hg.moveTo(x, h);
          hg.lineTo(x + h, 0);
        }
      } else {
        const r = 1.3 * dpr * this.thick;
        for (let y = gap / 2; y < h; y += gap) {
          for (let x = ((y / gap) % 2) * (gap / 2) + gap / 4; x < w; x += gap) {
            hg.moveTo(x + r, y);
            hg.arc(x, y, r, 0, 2 * Math.PI);
          }
        }
      }
    };
    path();
    if (kind === 'dots') {
      hg.fillStyle = 'rgba(255,255,255,0.9)';
      hg.lineWidth = 1.2 * dpr;
      hg.strokeStyle = 'rgba(255,255,255,0.9)';
      hg.stroke();
      hg.fillStyle = 'rgb(30,30,30)';
      hg.fill();
    } else {
      hg.strokeStyle = 'rgba(255,255,255,0.75)';
      hg.lineWidth = 2.6 * dpr * this.thick;
      hg.stroke();
      hg.strokeStyle = 'rgb(30,30,30)';
      hg.lineWidth = 1.1 * dpr * this.thick;
      hg.stroke();
    }
    this.patterns.set(key, c);
    return c;
  }

  toPlot(ks, cs, plot) {
    const b = this.data.box;
    return [
      plot.x + ((ks - b.ks_min) / (b.ks_max - b.ks_min)) * plot.w,
      plot.y + plot.h - ((cs - b.cs_min) / (b.cs_max - b.cs_min)) * plot.h,
    ];
  }

  drawOverlay() {
    if (!this.size.w) return;
    const { w, h, dpr } = this.size;
    const g = this.overlay.getContext('2d');
    g.setTransform(dpr, 0, 0, dpr, 0, 0);
    g.clearRect(0, 0, w, h);
    if (!this.data || !this.markers || !this.placed) return;
    this.paintMarkers(g, this.layout());
  }

  /** The markers on context `g` (CSS px) over the plot of layout `{fs, plot}`. */
  paintMarkers(g, { fs, plot }) {
    const { design, datum, samples, pick, adaptive, klass } = this.markers;
    const lw = this.thick;
    const inside = (p) => p[0] >= plot.x - 0.5 && p[0] <= plot.x + plot.w + 0.5 && p[1] >= plot.y - 0.5 && p[1] <= plot.y + plot.h + 0.5;
    const r = Math.max(4, fs * 0.45) * Math.sqrt(lw);

    // The surrogate's HiFi sample points: small white-ringed crosses.
    if (samples) {
      for (const smp of samples) {
        const q = this.toPlot(smp.ks, smp.cs, plot);
        if (inside(q)) cross(g, q, r, lw, '#7c2d12');
      }
    }
    // The adaptive loop's samples: purple white-ringed crosses; its next run: a purple ring.
    if (adaptive) {
      for (const smp of adaptive.added) {
        const q = this.toPlot(smp.ks, smp.cs, plot);
        if (inside(q)) cross(g, q, r, lw, ADAPTIVE);
      }
      const nx = adaptive.next && this.toPlot(adaptive.next.ks, adaptive.next.cs, plot);
      if (nx && inside(nx)) {
        g.beginPath();
        g.arc(nx[0], nx[1], 1.6 * r, 0, 2 * Math.PI);
        g.strokeStyle = '#fff';
        g.lineWidth = 4.5 * lw;
        g.stroke();
        g.strokeStyle = ADAPTIVE;
        g.lineWidth = 2.2 * lw;
        g.stroke();
      }
    }
    // The min-max pick: a yellow square.
    if (pick) {
      const q = this.toPlot(pick.ks, pick.cs, plot);
      if (inside(q)) {
        g.fillStyle = '#facc15';
        g.strokeStyle = '#000';
        g.lineWidth = 1.6 * lw;
        g.beginPath();
        g.rect(q[0] - r, q[1] - r, 2 * r, 2 * r);
        g.fill();
        g.stroke();
      }
    }
    // The class front's designs (issue #30), under the datum and the design.
    paintClass(g, klass, (row) => {
      const q = this.toPlot(row.ks, row.cs, plot);
      return inside(q) ? q : null;
    }, { r: r * 0.9, lw, fs: fs * 1.05 });

    const pd = this.toPlot(datum.ks, datum.cs, plot);
    if (inside(pd)) {
      g.lineWidth = 3.5 * lw;
      g.strokeStyle = '#fff';
      diamond(g, pd, r * 1.35);
      g.stroke();
      g.lineWidth = 1.6 * lw;
      g.strokeStyle = '#000';
      diamond(g, pd, r * 1.35);
      g.stroke();
    }
    const p = this.toPlot(design.ks, design.cs, plot);
    if (inside(p)) {
      g.save();
      g.beginPath();
      g.rect(plot.x, plot.y, plot.w, plot.h);
      g.clip();
      g.setLineDash([4, 3]);
      g.strokeStyle = 'rgba(255,255,255,0.9)';
      g.lineWidth = lw;
      g.beginPath();
      g.moveTo(plot.x, p[1]);
      g.lineTo(plot.x + plot.w, p[1]);
      g.moveTo(p[0], plot.y);
      g.lineTo(p[0], plot.y + plot.h);
      g.stroke();
      g.restore();
      g.beginPath();
      g.arc(p[0], p[1], r, 0, 2 * Math.PI);
      g.fillStyle = '#fff';
      g.fill();
      g.lineWidth = 2 * lw;
      g.strokeStyle = '#000';
      g.stroke();
      g.beginPath();
      g.arc(p[0], p[1], r * 0.3, 0, 2 * Math.PI);
      g.fillStyle = '#000';
      g.fill();
    }
  }

  /**
   * The map with its markers on a new canvas of `width` x `height` CSS px at `scale`
   * device px each (a slide-size PNG), laid out as on screen at zoom `zoom`.
   */
  snapshot(width, height, scale, zoom) {
    const c = document.createElement('canvas');
    c.width = Math.round(width * scale);
    c.height = Math.round(height * scale);
    if (!this.data) return c;
    const placed = this.paint(c, width, height, scale, zoom);
    if (placed && this.markers) {
      const g = c.getContext('2d');
      g.setTransform(scale, 0, 0, scale, 0, 0);
      this.paintMarkers(g, layoutOf(placed));
    }
    return c;
  }

  /** The design (N/m, N s/m) under a pointer event, clamped into the box when `clamp`; null outside. */
  designAt(ev, clamp) {
    if (!this.data || !this.placed) return null;
    const rect = this.surface.getBoundingClientRect();
    let u = (ev.clientX - rect.left) / rect.width;
    let v = 1 - (ev.clientY - rect.top) / rect.height;
    if (!clamp && (u < 0 || u > 1 || v < 0 || v > 1)) return null;
    u = Math.min(1, Math.max(0, u));
    v = Math.min(1, Math.max(0, v));
    const b = this.data.box;
    return { u, v, ks: b.ks_min + u * (b.ks_max - b.ks_min), cs: b.cs_min + v * (b.cs_max - b.cs_min) };
  }

  /** The hover readout at a pointer: Ks, Cs and the map's value in its cell. */
  hover(ev) {
    const at = this.designAt(ev, false);
    if (!at) {
      this.tip.hidden = true;
      return;
    }
    const d = this.data;
    const i = Math.min(d.nx - 1, Math.floor(at.u * d.nx));
    const j = Math.min(d.ny - 1, Math.floor(at.v * d.ny));
    const v = d.shown[j * d.nx + i];
    const value = d.unit.startsWith('%') ? `${fmt(v, 3)} ${d.unit}` : `${fmt(v, 4)} ${d.unit}`;
    const broken = this.hooks.objectives.filter((o) => d.broken[j * d.nx + i] & o.bit).map((o) => o.label);
    this.tip.textContent = `Ks ${fmt(at.ks / KS_UNIT, 4)} kN/m, Cs ${fmt(at.cs / CS_UNIT, 3)} kNs/m: ${this.crit.title} ${value}${broken.length ? ` (breaks the ${broken.join(', ')})` : ''}`;
    this.tip.hidden = false;
    const l = this.layout();
    const x = l.plot.x + at.u * l.plot.w;
    const y = l.plot.y + (1 - at.v) * l.plot.h;
    const left = x > this.size.w / 2;
    this.tip.style.left = left ? '' : `${x + 12}px`;
    this.tip.style.right = left ? `${this.size.w - x + 12}px` : '';
    this.tip.style.top = `${Math.max(0, y - 34)}px`;
  }

  bindPointer() {
    const s = this.surface;
    let dragging = false;
    const pick = (ev, clamp) => {
      const at = this.designAt(ev, clamp);
      if (at) this.onPick(at.ks, at.cs);
      return at !== null;
    };
    s.addEventListener('pointerdown', (ev) => {
      if (ev.button !== 0) return;
      if (pick(ev, false)) {
        dragging = true;
        s.setPointerCapture(ev.pointerId);
        ev.preventDefault();
        s.focus({ preventScroll: true });
      }
    });
    s.addEventListener('pointermove', (ev) => {
      if (dragging) pick(ev, true);
      if (ev.pointerType === 'mouse') this.hover(ev);
    });
    const end = (ev) => {
      dragging = false;
      if (s.hasPointerCapture(ev.pointerId)) s.releasePointerCapture(ev.pointerId);
    };
    s.addEventListener('pointerup', end);
    s.addEventListener('pointercancel', end);
    s.addEventListener('pointerleave', () => (this.tip.hidden = true));
  }

  /** The value under a design point, for captions: absolute or relative. */
  static caption(crit, value, datumValue, scale) {
    if (value == null) return '';
    if (scale === 'rel') return `design: ${fmtPct(value / datumValue - 1)}`;
    return `design: ${fmt(value * crit.factor)} ${crit.unit}`;
  }
}

/** The plot and colour bar in CSS px of a `drawMapFrame` placement (with its `zoom`). */
function layoutOf(pl) {
  const z = pl.zoom;
  const rect = (f) => ({ x: f.left * z, y: f.top * z, w: (f.right - f.left) * z, h: (f.bottom - f.top) * z });
  return { fs: 12 * z, plot: rect(pl.frame), bar: rect(pl.bar) };
}

function diamond(g, [x, y], r) {
  g.beginPath();
  g.moveTo(x, y - r);
  g.lineTo(x + r, y);
  g.lineTo(x, y + r);
  g.lineTo(x - r, y);
  g.closePath();
}

/** The adaptive loop's colour on the maps (its samples and next run; the plane's too). */
const ADAPTIVE = '#7c3aed';

/** A white-ringed diagonal cross of half size `0.75 r` at `[x, y]` in `colour` (a HiFi sample). */
function cross(g, [x, y], r, lw, colour) {
  const a = r * 0.75;
  g.strokeStyle = '#fff';
  g.lineWidth = 3.5 * lw;
  g.beginPath();
  g.moveTo(x - a, y - a);
  g.lineTo(x + a, y + a);
  g.moveTo(x - a, y + a);
  g.lineTo(x + a, y - a);
  g.stroke();
  g.strokeStyle = colour;
  g.lineWidth = 1.6 * lw;
  g.stroke();
}
