// A small canvas chart: linear or log axes with ticks, labels and units, sized in
// device pixels (HiDPI), series drawn as lines or dots. Used by the objective plane,
// the FRF / PSD plots and the time panel.

import { niceTicks, fmtTick } from './format.js';

/** Log ticks: the decades in [lo, hi] (lo, hi > 0). */
function logTicks(lo, hi) {
  const ticks = [];
  for (let e = Math.ceil(Math.log10(lo) - 1e-9); e <= Math.floor(Math.log10(hi) + 1e-9); e++) ticks.push(10 ** e);
  return ticks;
}

function fmtLog(v) {
  const e = Math.round(Math.log10(v));
  if (e >= -2 && e <= 3) return String(Number(v.toPrecision(1)));
  return `1e${e}`.replace('-', '−');
}

export class Plot {
  /** `canvas`: the element; `opts`: {xLabel, yLabel, xLog, yLog, aspect}. */
  constructor(canvas, opts = {}) {
    this.canvas = canvas;
    this.opts = { aspect: 0.62, ...opts };
    this.size = { w: 0, h: 0, dpr: 1 };
  }

  /** Sizes the backing store to the element's CSS width times devicePixelRatio. */
  resize() {
    const dpr = window.devicePixelRatio || 1;
    const w = Math.max(200, this.canvas.clientWidth || this.canvas.parentElement.clientWidth || 400);
    const h = Math.round(w * this.opts.aspect);
    this.canvas.style.height = `${h}px`;
    this.canvas.width = Math.round(w * dpr);
    this.canvas.height = Math.round(h * dpr);
    this.size = { w, h, dpr };
    this.lay = null;
  }

  /** The plot rectangle in CSS px (cached until the next resize or begin). */
  layout() {
    if (!this.lay) this.lay = this.computeLayout();
    return this.lay;
  }

  computeLayout() {
    const fs = parseFloat(getComputedStyle(document.documentElement).fontSize) || 16;
    const f = Math.max(11, fs * 0.75);
    const left = f * (this.opts.yLog ? 5.4 : 4.6);
    const bottom = f * 3.2;
    const top = f * 0.8;
    const right = f * 1.2;
    return { fs: f, plot: { x: left, y: top, w: this.size.w - left - right, h: this.size.h - top - bottom } };
  }

  /** Sets the axis ranges `{x: [lo, hi], y: [lo, hi]}` (widened a little on linear axes). */
  setRange(x, y, pad = 0.04) {
    const widen = ([lo, hi], log) => {
      if (log) return [lo, hi];
      if (!(hi > lo)) {
        const d = Math.abs(lo) * 0.05 || 1;
        return [lo - d, hi + d];
      }
      const d = (hi - lo) * pad;
      return [lo - d, hi + d];
    };
    this.x = widen(x, this.opts.xLog);
    this.y = widen(y, this.opts.yLog);
  }

  /** A function data -> CSS px along one axis. */
  axisMap([lo, hi], log, start, len, flip) {
    if (log) {
      const l0 = Math.log10(lo);
      const k = len / (Math.log10(hi) - l0);
      return flip ? (v) => start + len - (Math.log10(v) - l0) * k : (v) => start + (Math.log10(v) - l0) * k;
    }
    const k = len / (hi - lo);
    return flip ? (v) => start + len - (v - lo) * k : (v) => start + (v - lo) * k;
  }

  /** Data -> CSS px. */
  px(xv, yv) {
    const { plot } = this.layout();
    const t = (v, [lo, hi], log) => (log ? (Math.log10(v) - Math.log10(lo)) / (Math.log10(hi) - Math.log10(lo)) : (v - lo) / (hi - lo));
    return [plot.x + t(xv, this.x, this.opts.xLog) * plot.w, plot.y + (1 - t(yv, this.y, this.opts.yLog)) * plot.h];
  }

  /** Clears and draws frame, grid, ticks and axis labels; returns the 2D context (CSS px units). */
  begin() {
    if (this.size.w === 0 || this.canvas.width !== Math.round(this.size.w * this.size.dpr)) this.resize();
    this.lay = null; // the root font size may have changed (large type)
    const g = this.canvas.getContext('2d');
    g.setTransform(this.size.dpr, 0, 0, this.size.dpr, 0, 0);
    g.clearRect(0, 0, this.size.w, this.size.h);
    g.fillStyle = '#fff';
    g.fillRect(0, 0, this.size.w, this.size.h);
    const { plot, fs } = this.layout();
    g.font = `${fs}px system-ui, sans-serif`;
    g.strokeStyle = '#e3e6ea';
    g.lineWidth = 1;
    g.fillStyle = '#333';
    const xt = this.opts.xLog ? { ticks: logTicks(...this.x), log: true } : niceTicks(this.x[0], this.x[1], Math.max(3, Math.floor(plot.w / (fs * 6))));
    const yt = this.opts.yLog ? { ticks: logTicks(...this.y), log: true } : niceTicks(this.y[0], this.y[1], Math.max(3, Math.floor(plot.h / (fs * 3))));
    g.textAlign = 'center';
    g.textBaseline = 'top';
    for (const v of xt.ticks) {
      const [x] = this.px(v, this.opts.yLog ? this.y[0] : this.y[0]);
      g.beginPath();
      g.moveTo(x, plot.y);
      g.lineTo(x, plot.y + plot.h);
      g.stroke();
      g.fillText(xt.log ? fmtLog(v) : fmtTick(v, xt.step), x, plot.y + plot.h + fs * 0.3);
    }
    g.textAlign = 'right';
    g.textBaseline = 'middle';
    for (const v of yt.ticks) {
      const [, y] = this.px(this.opts.xLog ? this.x[0] : this.x[0], v);
      g.beginPath();
      g.moveTo(plot.x, y);
      g.lineTo(plot.x + plot.w, y);
      g.stroke();
      g.fillText(yt.log ? fmtLog(v) : fmtTick(v, yt.step), plot.x - fs * 0.3, y);
    }
    g.strokeStyle = '#555';
    g.strokeRect(plot.x, plot.y, plot.w, plot.h);
    g.textAlign = 'center';
    g.textBaseline = 'bottom';
    g.fillText(this.opts.xLabel || '', plot.x + plot.w / 2, this.size.h - 2);
    g.save();
    g.translate(fs * 1.0, plot.y + plot.h / 2);
    g.rotate(-Math.PI / 2);
    g.textBaseline = 'middle';
    g.fillText(this.opts.yLabel || '', 0, 0);
    g.restore();
    g.save();
    g.beginPath();
    g.rect(plot.x, plot.y, plot.w, plot.h);
    g.clip();
    this.g = g;
    return g;
  }

  /** Ends the clipped plot area. */
  end() {
    this.g.restore();
  }

  line(xs, ys, colour, width = 1.5, dash = []) {
    const g = this.g;
    g.strokeStyle = colour;
    g.lineWidth = width;
    g.setLineDash(dash);
    g.beginPath();
    let pen = false;
    for (let i = 0; i < xs.length; i++) {
      if (!(Number.isFinite(xs[i]) && Number.isFinite(ys[i]))) {
        pen = false;
        continue;
      }
      const [x, y] = this.px(xs[i], ys[i]);
      if (pen) g.lineTo(x, y);
      else g.moveTo(x, y);
      pen = true;
    }
    g.stroke();
    g.setLineDash([]);
  }

  dots(xs, ys, colour, r = 1.5) {
    const g = this.g;
    g.fillStyle = colour;
    // One path for all dots (one fill call), with the axis maps hoisted out of the loop.
    const { plot } = this.layout();
    const tx = this.axisMap(this.x, this.opts.xLog, plot.x, plot.w, false);
    const ty = this.axisMap(this.y, this.opts.yLog, plot.y, plot.h, true);
    g.beginPath();
    for (let i = 0; i < xs.length; i++) g.rect(tx(xs[i]) - r, ty(ys[i]) - r, 2 * r, 2 * r);
    g.fill();
  }

  /** A marker: 'circle', 'square', 'diamond' or 'cross'. */
  marker(xv, yv, shape, fill, stroke = '#000', r = 6) {
    const g = this.g;
    const [x, y] = this.px(xv, yv);
    g.beginPath();
    if (shape === 'square') g.rect(x - r, y - r, 2 * r, 2 * r);
    else if (shape === 'diamond') {
      g.moveTo(x, y - r * 1.3);
      g.lineTo(x + r * 1.3, y);
      g.lineTo(x, y + r * 1.3);
      g.lineTo(x - r * 1.3, y);
      g.closePath();
    } else g.arc(x, y, r, 0, 2 * Math.PI);
    g.fillStyle = fill;
    g.fill();
    g.lineWidth = 2;
    g.strokeStyle = stroke;
    g.stroke();
    return [x, y];
  }

  /** A legend in the top-right corner: [{label, colour, kind: 'line'|'dot'|'marker'}]. */
  legend(items) {
    const g = this.g;
    const { plot, fs } = this.layout();
    g.font = `${fs}px system-ui, sans-serif`;
    const w = Math.max(...items.map((i) => g.measureText(i.label).width)) + fs * 2.6;
    const h = items.length * fs * 1.3 + fs * 0.4;
    const x0 = plot.x + plot.w - w - 4;
    const y0 = plot.y + 4;
    g.fillStyle = 'rgba(255,255,255,0.88)';
    g.fillRect(x0, y0, w, h);
    g.strokeStyle = '#bbb';
    g.lineWidth = 1;
    g.strokeRect(x0, y0, w, h);
    items.forEach((it, k) => {
      const y = y0 + fs * 0.2 + fs * 1.3 * (k + 0.5);
      g.strokeStyle = it.colour;
      g.fillStyle = it.colour;
      g.lineWidth = 2;
      g.setLineDash(it.dash || []);
      if (it.kind === 'line') {
        g.beginPath();
        g.moveTo(x0 + fs * 0.4, y);
        g.lineTo(x0 + fs * 1.8, y);
        g.stroke();
      } else {
        const cx = x0 + fs * 1.1;
        const r = it.kind === 'dot' ? 2 : fs * 0.35;
        g.beginPath();
        if (it.shape === 'square') g.rect(cx - r, y - r, 2 * r, 2 * r);
        else if (it.shape === 'diamond') {
          g.moveTo(cx, y - r * 1.3);
          g.lineTo(cx + r * 1.3, y);
          g.lineTo(cx, y + r * 1.3);
          g.lineTo(cx - r * 1.3, y);
          g.closePath();
        } else g.arc(cx, y, r, 0, 2 * Math.PI);
        g.fill();
        if (it.stroke) {
          g.strokeStyle = it.stroke;
          g.stroke();
        }
      }
      g.setLineDash([]);
      g.fillStyle = '#222';
      g.textAlign = 'left';
      g.textBaseline = 'middle';
      g.fillText(it.label, x0 + fs * 2.1, y);
    });
  }
}
