// One design-criteria-space map: a criterion over Ks x Cs as a dense colour image
// (an RGBA ImageData put on an offscreen canvas, then scaled onto the plot), contour
// lines, the infeasible area hatched, axes with units, a colour bar, and the design
// and datum markers on a separate overlay canvas (so moving the design redraws only
// the markers). Click or drag on the plot picks a design.

import { VIRIDIS, DIVERGING, paint } from './colormap.js';
import { contourSegments } from './contour.js';
import { fmt, fmtPct } from './format.js';
import { drawMapFrame } from '../ridelab.js';

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
    key: 'sws', plane: 2, title: 'SWS', long: 'RMS suspension working space', unit: 'mm', factor: 1000,
    teach: 'Working space: a softer damper lets the suspension travel further.',
  },
];

/** Hatch per group of objectives (bits of a map's `broken` mask). */
const HATCHES = [
  { bits: 1, dir: '/', name: 'SWS limit' },
  { bits: 2 | 4, dir: '\\', name: 'bounce or damping band' },
  { bits: 8 | 16 | 32, dir: '-', name: 'worse than the datum' },
];

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
   * @param {(ks: number, cs: number) => void} onPick called with N/m and N s/m
   */
  constructor(parent, crit, onPick) {
    this.crit = crit;
    this.onPick = onPick;
    this.data = null;
    this.markers = null;

    const fig = document.createElement('figure');
    fig.className = 'map-panel';
    fig.dataset.crit = crit.key;
    const cap = document.createElement('figcaption');
    const title = document.createElement('span');
    title.textContent = `${crit.title}: ${crit.long}`;
    this.atEl = document.createElement('span');
    this.atEl.className = 'at';
    cap.append(title, this.atEl);
    const teach = document.createElement('p');
    teach.className = 'teach';
    teach.textContent = crit.teach;
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
    stack.append(this.base, this.overlay);
    fig.append(cap, teach, stack);
    parent.append(fig);
    this.fig = fig;
    this.stack = stack;

    this.size = { w: 0, h: 0, dpr: 1 };
    this.ro = new ResizeObserver(() => this.resize());
    this.ro.observe(stack);
    this.bindPointer();
  }

  /**
   * The plot and colour bar in CSS px (`{fs, plot: {x, y, w, h}, bar}`) as the core's map
   * chart laid them out at the last `drawBase` (null before the first).
   */
  layout() {
    const pl = this.placed;
    if (!pl) return null;
    const z = pl.zoom;
    const rect = (f) => ({ x: f.left * z, y: f.top * z, w: (f.right - f.left) * z, h: (f.bottom - f.top) * z });
    return { fs: 12 * z, plot: rect(pl.frame), bar: rect(pl.bar) };
  }

  resize() {
    const r = this.stack.getBoundingClientRect();
    const dpr = window.devicePixelRatio || 1;
    const w = Math.round(r.width);
    const h = Math.round(r.height);
    if (w === this.size.w && h === this.size.h && dpr === this.size.dpr) return;
    this.size = { w, h, dpr };
    for (const c of [this.base, this.overlay]) {
      c.width = Math.max(1, Math.round(w * dpr));
      c.height = Math.max(1, Math.round(h * dpr));
    }
    this.drawBase();
    this.drawOverlay();
  }

  /**
   * New map data. `maps`: {nx, ny, values, feasible, feasibleCount} from the engine;
   * `box`: design box (N/m, N s/m); `swsLimit`: m or null; `scale`: "abs" or "rel";
   * `datum`: the datum's criteria {bacc, dtl, sws} by the map's model (for "rel");
   * `kind`: "value" (criteria) or "error" (the planes hold the surrogate's signed error
   * against the HiFi, %, and `scale` is ignored). `draw` false leaves the drawing to a
   * later `drawBase()` (the page splits a map's update over two tasks).
   */
  setData({ maps, box, swsLimit, scale, datum, kind = 'value' }, draw = true) {
    const { nx, ny, values } = maps;
    const n = nx * ny;
    const off = this.crit.plane * n;
    const f = this.crit.factor;
    const error = kind === 'error';
    if (error) scale = 'rel';
    const ref = datum ? datum[this.crit.key] : 1;
    const shown = new Float64Array(n);
    for (let k = 0; k < n; k++) {
      const v = values[off + k];
      shown[k] = error ? v : scale === 'rel' ? (v / ref - 1) * 100 : v * f;
    }
    // The colour range spans the feasible designs (those the designer can choose), so
    // their differences show; values beyond it (in the hatched area) take the end
    // colours and the bar gets an "and above" / "and below" triangle.
    const feasible = maps.feasibleCount > 0 ? maps.feasible : null;
    let lo = Infinity;
    let hi = -Infinity;
    let allLo = Infinity;
    let allHi = -Infinity;
    for (let k = 0; k < n; k++) {
      const v = shown[k];
      if (v < allLo) allLo = v;
      if (v > allHi) allHi = v;
      if (feasible && !feasible[k]) continue;
      if (v < lo) lo = v;
      if (v > hi) hi = v;
    }
    if (scale === 'rel') {
      const m = Math.max(Math.abs(lo), Math.abs(hi), 1e-9);
      lo = -m;
      hi = m;
    } else if (!(hi > lo)) {
      const pad = Math.max(1e-9, Math.abs(lo) * 1e-3);
      lo -= pad;
      hi += pad;
    }
    const tol = 1e-9 * (hi - lo);
    const over = allHi > hi + tol;
    const under = allLo < lo - tol;
    const table = scale === 'rel' ? DIVERGING : VIRIDIS;

    // The dense colour image: one pixel per grid cell, row 0 at the top (highest Cs).
    const img = new ImageData(nx, ny);
    for (let j = 0; j < ny; j++) {
      const row = (ny - 1 - j) * nx;
      for (let i = 0; i < nx; i++) {
        paint(table, (shown[j * nx + i] - lo) / (hi - lo), img.data, 4 * (row + i));
      }
    }
    const colour = new OffscreenCanvas(nx, ny);
    colour.getContext('2d').putImageData(img, 0, 0);

    // The infeasible masks, one per hatch: opaque where a design breaks an objective of
    // that group (bits of `maps.broken`; without it, every infeasible cell is SWS's).
    const masks = [];
    for (const group of HATCHES) {
      const mask = new ImageData(nx, ny);
      let any = false;
      for (let j = 0; j < ny; j++) {
        const row = (ny - 1 - j) * nx;
        for (let i = 0; i < nx; i++) {
          const k = j * nx + i;
          const hit = maps.broken ? maps.broken[k] & group.bits : group.bits & 1 && !maps.feasible[k];
          if (hit) {
            mask.data[4 * (row + i) + 3] = 255;
            any = true;
          }
        }
      }
      if (!any) continue;
      const canvas = new OffscreenCanvas(nx, ny);
      canvas.getContext('2d').putImageData(mask, 0, 0);
      masks.push({ ...group, canvas });
    }

    const limitLine = swsLimit && !error ? contourSegments(values, 2 * n, nx, ny, swsLimit) : [];

    this.data = {
      nx, ny, box, lo, hi, table, colour, masks, limitLine, scale, over, under,
      // Contour levels and lines: at the colour bar's ticks, set when it is drawn.
      levels: [], levelsKey: null, contours: [],
      infeasible: maps.feasibleCount < n,
      unit: error ? '% error vs HiFi' : scale === 'rel' ? '% vs datum' : this.crit.unit,
      shown, kind, feasible: maps.feasible,
    };
    this.base.setAttribute(
      'aria-label',
      `${this.crit.long} map over spring rate Ks ${box.ks_min / KS_UNIT} to ${box.ks_max / KS_UNIT} kN/m ` +
        `and damper rate Cs ${box.cs_min / CS_UNIT} to ${box.cs_max / CS_UNIT} kNs/m; ` +
        `values ${fmt(lo)} to ${fmt(hi)} ${this.data.unit}.`,
    );
    if (draw) this.drawBase();
  }

  /**
   * The design and datum points (N/m, N s/m), the design's value for the caption, and
   * optionally the surrogate's sample points and the min-max pick ({ks, cs}).
   */
  setMarkers(design, datum, valueText, { samples = null, pick = null } = {}) {
    this.markers = { design, datum, samples, pick };
    this.atEl.textContent = valueText;
    this.drawOverlay();
  }

  /** A `w` x `h` scratch canvas of this view (device px), kept between redraws. */
  scratchCanvas(w, h) {
    if (!this.scratch || this.scratch.width !== w || this.scratch.height !== h) this.scratch = new OffscreenCanvas(w, h);
    return this.scratch;
  }

  /**
   * The grey wash with hatch lines in direction `dir` ('/', '\\' or '-') on a `w` x `h`
   * canvas (device px), drawn once per size and direction.
   */
  hatchPattern(dir, w, h) {
    this.patterns = this.patterns || new Map();
    const key = `${dir} ${w} ${h}`;
    let c = this.patterns.get(key);
    if (c) return c;
    if (this.patterns.size > 6) this.patterns.clear();
    c = new OffscreenCanvas(w, h);
    const hg = c.getContext('2d');
    const dpr = this.size.dpr;
    hg.fillStyle = 'rgba(150,150,150,0.62)';
    hg.fillRect(0, 0, w, h);
    hg.strokeStyle = 'rgb(58,58,58)';
    hg.lineWidth = 1.1 * dpr;
    const gap = 7 * dpr;
    hg.beginPath();
    if (dir === '-') {
      for (let y = gap / 2; y < h; y += gap) {
        hg.moveTo(0, y);
        hg.lineTo(w, y);
      }
    } else {
      for (let x = -h; x < w; x += gap) {
        if (dir === '/') {
          hg.moveTo(x, h);
          hg.lineTo(x + h, 0);
        } else {
          hg.moveTo(x, 0);
          hg.lineTo(x + h, h);
        }
      }
    }
    hg.stroke();
    this.patterns.set(key, c);
    return c;
  }

  ctx(canvas) {
    const g = canvas.getContext('2d');
    g.setTransform(this.size.dpr, 0, 0, this.size.dpr, 0, 0);
    return g;
  }

  toPlot(ks, cs, plot) {
    const b = this.data.box;
    return [
      plot.x + ((ks - b.ks_min) / (b.ks_max - b.ks_min)) * plot.w,
      plot.y + plot.h - ((cs - b.cs_min) / (b.cs_max - b.cs_min)) * plot.h,
    ];
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
      colourMap: d.scale === 'rel' ? 'diverging' : 'viridis',
      range: [d.lo, d.hi],
      legend: 'none',
      width,
      height,
    };
  }

  /**
   * The map: plotters draws the frame (axes, ticks, labels, colour bar with its unit) at
   * the core's layout; the page puts the dense colour image in it, then the contour lines
   * at the colour bar's ticks, the hatching and the SWS limit.
   */
  drawBase() {
    if (!this.size.w) return;
    const { w, h, dpr } = this.size;
    if (!this.data) {
      this.ctx(this.base).clearRect(0, 0, w, h);
      return;
    }
    const d = this.data;
    // Logical px: the CSS size over the type zoom, never below the chart's minimum.
    const zoom = Math.min(rootFontPx() / 15, w / MIN_W, h / MIN_H);
    try {
      const placed = drawMapFrame(this.base, this.chartSpec(Math.max(MIN_W, Math.floor(w / zoom)), Math.max(MIN_H, Math.floor(h / zoom))), dpr * zoom);
      this.placed = { ...placed, zoom };
      this.error = null;
    } catch (e) {
      this.placed = null;
      this.error = { message: String(e.message || e), field: e.field || '' };
      const g = this.ctx(this.base);
      g.clearRect(0, 0, w, h);
      g.fillStyle = '#a3281d';
      g.font = '13px system-ui, sans-serif';
      g.fillText(`Cannot draw this map: ${this.error.message}`, 8, 20, w - 16);
      return;
    }
    const g = this.ctx(this.base);
    const { plot, bar } = this.layout();
    const gx = (x) => plot.x + ((x + 0.5) / d.nx) * plot.w; // grid -> CSS px
    const gy = (y) => plot.y + plot.h - ((y + 0.5) / d.ny) * plot.h;

    // Colour image, smoothly scaled from one pixel per cell.
    g.imageSmoothingEnabled = true;
    g.imageSmoothingQuality = 'high';
    g.drawImage(d.colour, plot.x, plot.y, plot.w, plot.h);

    // Contour lines at the colour bar's ticks (kept until the levels change): a dark
    // halo under a light line reads on both ends of the colour map.
    const span = d.hi - d.lo;
    const levels = this.placed.barTicks.filter((t) => t > d.lo + 1e-9 * span && t < d.hi - 1e-9 * span);
    const key = levels.join(' ');
    if (d.levelsKey !== key) {
      d.levelsKey = key;
      d.levels = levels;
      d.contours = levels.map((lv) => contourSegments(d.shown, 0, d.nx, d.ny, lv));
    }
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
      g.lineWidth = 2;
      strokeSegs(segs);
      g.strokeStyle = 'rgba(255,255,255,0.85)';
      g.lineWidth = 0.8;
      strokeSegs(segs);
    }

    // Infeasible area: a grey wash plus hatching per objective group ('/' SWS limit,
    // '\' frequency bands, '-' worse than the datum), each cut to its mask; an area that
    // breaks two groups is darker and cross-hatched.
    const W = Math.ceil(plot.w * dpr);
    const H = Math.ceil(plot.h * dpr);
    for (const m of d.masks) {
      // One scratch canvas per view, reused: the hatch pattern is copied in, cut to the
      // mask, and drawn (no new plot-sized canvas per map per redraw).
      const scratch = this.scratchCanvas(W, H);
      const sg = scratch.getContext('2d');
      sg.globalCompositeOperation = 'copy';
      sg.drawImage(this.hatchPattern(m.dir, W, H), 0, 0);
      sg.globalCompositeOperation = 'destination-in';
      sg.imageSmoothingEnabled = false;
      sg.drawImage(m.canvas, 0, 0, W, H);
      g.drawImage(scratch, 0, 0, W, H, plot.x, plot.y, plot.w, plot.h);
    }
    // The SWS limit itself.
    if (d.limitLine.length) {
      g.strokeStyle = '#fff';
      g.lineWidth = 3.5;
      strokeSegs(d.limitLine);
      g.strokeStyle = '#000';
      g.lineWidth = 1.6;
      strokeSegs(d.limitLine);
    }
    g.restore();
    g.strokeStyle = '#333';
    g.lineWidth = 1;
    g.strokeRect(plot.x, plot.y, plot.w, plot.h);

    // "and above" / "and below" triangles on the colour bar for values beyond its range.
    const tri = (y, dir, t) => {
      const c = new Uint8ClampedArray(4);
      paint(d.table, t, c, 0);
      g.beginPath();
      g.moveTo(bar.x, y);
      g.lineTo(bar.x + bar.w / 2, y - dir * bar.w * 0.9);
      g.lineTo(bar.x + bar.w, y);
      g.closePath();
      g.fillStyle = `rgb(${c[0]},${c[1]},${c[2]})`;
      g.fill();
      g.stroke();
    };
    if (d.over) tri(bar.y, 1, 1);
    if (d.under) tri(bar.y + bar.h, -1, 0);
  }

  drawOverlay() {
    if (!this.size.w) return;
    const g = this.ctx(this.overlay);
    g.clearRect(0, 0, this.size.w, this.size.h);
    if (!this.data || !this.markers || !this.placed) return;
    const { fs, plot } = this.layout();
    const { design, datum, samples, pick } = this.markers;
    const inside = (p) => p[0] >= plot.x - 0.5 && p[0] <= plot.x + plot.w + 0.5 && p[1] >= plot.y - 0.5 && p[1] <= plot.y + plot.h + 0.5;
    const r = Math.max(4, fs * 0.45);

    // The surrogate's HiFi sample points: small white-ringed crosses.
    if (samples) {
      g.lineWidth = 1.5;
      for (const smp of samples) {
        const q = this.toPlot(smp.ks, smp.cs, plot);
        if (!inside(q)) continue;
        const a = r * 0.75;
        g.strokeStyle = '#fff';
        g.lineWidth = 3.5;
        g.beginPath();
        g.moveTo(q[0] - a, q[1] - a);
        g.lineTo(q[0] + a, q[1] + a);
        g.moveTo(q[0] - a, q[1] + a);
        g.lineTo(q[0] + a, q[1] - a);
        g.stroke();
        g.strokeStyle = '#7c2d12';
        g.lineWidth = 1.6;
        g.stroke();
      }
    }
    // The min-max pick: a yellow square.
    if (pick) {
      const q = this.toPlot(pick.ks, pick.cs, plot);
      if (inside(q)) {
        g.fillStyle = '#facc15';
        g.strokeStyle = '#000';
        g.lineWidth = 1.6;
        g.beginPath();
        g.rect(q[0] - r, q[1] - r, 2 * r, 2 * r);
        g.fill();
        g.stroke();
      }
    }

    const pd = this.toPlot(datum.ks, datum.cs, plot);
    if (inside(pd)) {
      g.lineWidth = 3.5;
      g.strokeStyle = '#fff';
      diamond(g, pd, r * 1.35);
      g.stroke();
      g.lineWidth = 1.6;
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
      g.lineWidth = 1;
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
      g.lineWidth = 2;
      g.strokeStyle = '#000';
      g.stroke();
      g.beginPath();
      g.arc(p[0], p[1], r * 0.3, 0, 2 * Math.PI);
      g.fillStyle = '#000';
      g.fill();
    }
  }

  bindPointer() {
    let dragging = false;
    const pick = (ev, clamp) => {
      if (!this.data || !this.placed) return false;
      const rect = this.overlay.getBoundingClientRect();
      const { plot } = this.layout();
      let u = (ev.clientX - rect.left - plot.x) / plot.w;
      let v = 1 - (ev.clientY - rect.top - plot.y) / plot.h;
      if (!clamp && (u < 0 || u > 1 || v < 0 || v > 1)) return false;
      u = Math.min(1, Math.max(0, u));
      v = Math.min(1, Math.max(0, v));
      const b = this.data.box;
      this.onPick(b.ks_min + u * (b.ks_max - b.ks_min), b.cs_min + v * (b.cs_max - b.cs_min));
      return true;
    };
    this.overlay.addEventListener('pointerdown', (ev) => {
      if (ev.button !== 0) return;
      if (pick(ev, false)) {
        dragging = true;
        this.overlay.setPointerCapture(ev.pointerId);
        ev.preventDefault();
      }
    });
    this.overlay.addEventListener('pointermove', (ev) => {
      if (dragging) pick(ev, true);
    });
    const end = (ev) => {
      dragging = false;
      if (this.overlay.hasPointerCapture(ev.pointerId)) this.overlay.releasePointerCapture(ev.pointerId);
    };
    this.overlay.addEventListener('pointerup', end);
    this.overlay.addEventListener('pointercancel', end);
  }

  /** The value under a design point, for captions: absolute or relative. */
  static caption(crit, value, datumValue, scale) {
    if (value == null) return '';
    if (scale === 'rel') return `design: ${fmtPct(value / datumValue - 1)}`;
    return `design: ${fmt(value * crit.factor)} ${crit.unit}`;
  }
}

function diamond(g, [x, y], r) {
  g.beginPath();
  g.moveTo(x, y - r);
  g.lineTo(x + r, y);
  g.lineTo(x, y + r);
  g.lineTo(x - r, y);
  g.closePath();
}
