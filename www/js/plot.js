// A line chart on a canvas, drawn by the wasm core with plotters (`drawLineChart`: axes,
// ticks, labels, series and legend from a chart spec, see js/chartspecs.js). The chart is
// laid out in logical pixels: the canvas's CSS size divided by the type zoom (the root
// font size over its normal 15 px), so "large type" enlarges text and lines alike; the
// context is scaled by devicePixelRatio times that zoom, so it is sharp on HiDPI screens
// and projectors. `px` maps data to CSS px on the drawn axes, for what the page draws on
// top (the objective plane's cloud and its live design marker).

import { drawLineChart } from '../ridelab-first.js';

/** The root font size the charts' fixed type sizes are made for, px. */
const NORMAL_TYPE_PX = 15;
/** The chart module's smallest chart, logical px. */
const MIN_W = 240;
const MIN_H = 200;

export class Plot {
  /**
   * `canvas`: the element; `opts`: `{aspect}` (height over width) or `{fill: true}` (the
   * height of the canvas's parent, for a chart that fills a cell of the workbench).
   */
  constructor(canvas, opts = {}) {
    this.canvas = canvas;
    this.opts = { aspect: 0.62, fill: false, ...opts };
    this.size = { w: 0, h: 0, dpr: 1, zoom: 1 };
    this.placed = null;
    this.error = null;
  }

  /** The chart's CSS size in its box now: `{w, h}` (px). */
  measure() {
    const w = Math.max(MIN_W, this.canvas.clientWidth || this.canvas.parentElement.clientWidth || 400);
    const h = this.opts.fill
      ? Math.max(MIN_H * 0.8, Math.floor(this.canvas.parentElement.clientHeight))
      : Math.max(MIN_H * 0.8, Math.round(w * this.opts.aspect));
    return { w, h };
  }

  /** True when the chart's box still has the size it was last drawn at: a redraw would change nothing. */
  fitsBox() {
    const { w, h } = this.measure();
    return w === this.size.w && h === this.size.h && (window.devicePixelRatio || 1) === this.size.dpr;
  }

  /** Sizes the backing store to the element's CSS width times devicePixelRatio. */
  resize() {
    const dpr = window.devicePixelRatio || 1;
    const { w, h } = this.measure();
    const type = (parseFloat(getComputedStyle(document.documentElement).fontSize) || NORMAL_TYPE_PX) / NORMAL_TYPE_PX;
    // Never lay a chart out below the chart module's minimum: shrink the zoom instead.
    const zoom = Math.min(type, w / MIN_W, h / MIN_H);
    if (this.canvas.style.height !== `${h}px`) this.canvas.style.height = `${h}px`;
    if (this.canvas.width !== Math.round(w * dpr)) this.canvas.width = Math.round(w * dpr);
    if (this.canvas.height !== Math.round(h * dpr)) this.canvas.height = Math.round(h * dpr);
    this.size = { w, h, dpr, zoom };
  }

  /**
   * Draws `spec` (its width and height set here) with plotters: `layer` 'all', 'axes'
   * or 'series'. On a bad spec the canvas shows the message (kept in `this.error`) and
   * the previous axes stay in `this.placed`. Returns true when drawn.
   */
  draw(spec, layer = 'all') {
    if (layer !== 'series') this.resize();
    const { w, h, dpr, zoom } = this.size;
    spec.width = Math.max(MIN_W, Math.floor(w / zoom));
    spec.height = Math.max(MIN_H, Math.floor(h / zoom));
    try {
      this.placed = drawLineChart(this.canvas, spec, dpr * zoom, layer);
      this.error = null;
      return true;
    } catch (e) {
      this.error = { message: String(e.message || e), field: e.field || '' };
      const g = this.canvas.getContext('2d');
      g.setTransform(dpr, 0, 0, dpr, 0, 0);
      g.fillStyle = '#fff';
      g.fillRect(0, 0, w, h);
      g.fillStyle = '#a3281d';
      g.font = '13px system-ui, sans-serif';
      g.fillText(`Cannot draw this chart: ${this.error.message}`, 8, 20, w - 16);
      return false;
    }
  }

  /** The plot rectangle in CSS px and the tick label size (`{plot: {x, y, w, h}, fs}`). */
  layout() {
    const z = this.size.zoom;
    const f = this.placed ? this.placed.frame : { left: 0, right: 1, top: 0, bottom: 1 };
    return { fs: 12 * z, plot: { x: f.left * z, y: f.top * z, w: (f.right - f.left) * z, h: (f.bottom - f.top) * z } };
  }

  /** Data -> CSS px on the drawn axes (as plotters places them, before rounding). */
  px(xv, yv) {
    return this.mapper()(xv, yv);
  }

  /** The function data -> CSS px of the drawn axes. */
  mapper() {
    const { plot } = this.layout();
    const { x, y } = this.placed;
    const t = (a) => (a.log ? (v) => Math.log10(v / a.lo) / Math.log10(a.hi / a.lo) : (v) => (v - a.lo) / (a.hi - a.lo));
    const tx = t(x);
    const ty = t(y);
    return (xv, yv) => [plot.x + tx(xv) * plot.w, plot.y + (1 - ty(yv)) * plot.h];
  }

  /**
   * Dots of half side `r` CSS px at `points` (`[[x, y], ...]`) over the drawn axes: one
   * path and one fill for thousands of them, clipped to the plot.
   */
  dots(points, colour, r = 1.5) {
    if (!this.placed) return;
    const g = this.canvas.getContext('2d');
    const { plot } = this.layout();
    const at = this.mapper();
    g.setTransform(this.size.dpr, 0, 0, this.size.dpr, 0, 0);
    g.save();
    g.beginPath();
    g.rect(plot.x, plot.y, plot.w, plot.h);
    g.clip();
    g.fillStyle = colour;
    g.beginPath();
    for (const [x, y] of points) {
      const [px, py] = at(x, y);
      g.rect(px - r, py - r, 2 * r, 2 * r);
    }
    g.fill();
    g.restore();
  }
}
