// The time panel: the time response of both models as three charts (plotters), an
// animated side view of the full car on the road, and a time cursor on the charts while
// it plays (at real speed or in slow motion). Handed the run's result and the speed.
// Beside it the front damper's force-velocity chart (DamperChart), handed the core's curve.

import { Plot } from './plot.js';
import { OUTPUTS, damperSpec, timeSpec } from './chartspecs.js';
import { fmt } from './format.js';

export class TimePanel {
  /** `els`: `{car, play, charts: {bacc, dtl, sws}: {base, overlay}}`. */
  constructor({ car, play, charts }) {
    this.plots = OUTPUTS.map((o) => ({ key: o.key, plot: new Plot(charts[o.key].base, { aspect: 0.45 }), overlay: charts[o.key].overlay }));
    this.car = car;
    this.playButton = play;
    this.res = null;
    this.speed = 20;
    this.playing = false;
    /** The sample shown, and how fast the animation runs (1 = real time). */
    this.k = 0;
    this.rate = 1;
    this.raf = null;
    this.thick = 1;
  }

  setStyle({ thick }) {
    this.thick = thick;
  }

  /**
   * Draws the run `res` (`timeResponse` result) at vehicle speed `speed` (m/s), with
   * `linear` (the linear damper's run on the same road) underneath when given.
   */
  draw(res, speed, linear = null) {
    this.res = res;
    this.speed = speed;
    this.linear = linear;
    if (!res) return;
    for (const { key, plot } of this.plots) {
      const spec = timeSpec(res, key, { linear });
      if (this.thick !== 1) for (const s of spec.series) s.size *= this.thick;
      plot.draw(spec);
    }
    this.k = Math.min(this.k, res.hifi.t.length - 1);
    this.drawFrame();
  }

  /** The side view and the cursors at sample `this.k`. */
  drawFrame() {
    this.drawCar();
    this.drawCursors();
  }

  /** A vertical line at the time shown, on each chart's overlay. */
  drawCursors() {
    const res = this.res;
    if (!res) return;
    const t = res.hifi.t[this.k];
    for (const { plot, overlay } of this.plots) {
      if (!plot.placed || plot.error) continue;
      const { w, h, dpr } = plot.size;
      if (overlay.width !== plot.canvas.width || overlay.height !== plot.canvas.height) {
        overlay.width = plot.canvas.width;
        overlay.height = plot.canvas.height;
      }
      overlay.style.height = plot.canvas.style.height;
      const g = overlay.getContext('2d');
      g.setTransform(dpr, 0, 0, dpr, 0, 0);
      g.clearRect(0, 0, w, h);
      if (!this.playing && this.k === 0) continue;
      const { plot: box } = plot.layout();
      const [x] = plot.px(t, plot.placed.y.lo);
      g.strokeStyle = '#111827';
      g.lineWidth = 2 * this.thick;
      g.beginPath();
      g.moveTo(x, box.y);
      g.lineTo(x, box.y + box.h);
      g.stroke();
    }
  }

  /** The side view at sample `this.k`: road, wheels, springs and the pitching body. */
  drawCar() {
    const res = this.res;
    if (!res) return;
    const c = this.car;
    const dpr = window.devicePixelRatio || 1;
    const w = Math.max(300, c.clientWidth || 600);
    const h = Math.round(w * 0.4);
    if (c.width !== Math.round(w * dpr)) {
      c.width = Math.round(w * dpr);
      c.height = Math.round(h * dpr);
      c.style.height = `${h}px`;
    }
    const g = c.getContext('2d');
    g.setTransform(dpr, 0, 0, dpr, 0, 0);
    g.fillStyle = '#f8fafc';
    g.fillRect(0, 0, w, h);
    const hf = res.hifi;
    const n = hf.t.length;
    const k = Math.min(this.k, n - 1);
    const dtS = hf.t[1] - hf.t[0];
    const v = this.speed;
    const { a, b } = res;
    const span = a + b + 3.2; // m of road shown
    const m2px = w / span;
    const EX = 10; // vertical exaggeration of the motions
    const ground = h * 0.86;
    const xOf = (x) => w / 2 + x * m2px; // x: m forward of the CG (car faces right)
    // Road height at x metres forward of the front axle: the front-right profile
    // `delta = x / v` seconds ahead (the record is periodic).
    const roadAt = (x) => {
      const idx = k + ((x - a) / v) / dtS;
      const i0 = Math.floor(idx);
      const fr = idx - i0;
      const r0 = hf.road[((i0 % n) + n) % n];
      const r1 = hf.road[(((i0 + 1) % n) + n) % n];
      return r0 + fr * (r1 - r0);
    };
    const yOf = (z) => ground - z * EX * m2px;
    g.beginPath();
    for (let px = 0; px <= w; px += 2) {
      const x = (px - w / 2) / m2px;
      const y = yOf(roadAt(x));
      if (px === 0) g.moveTo(px, y);
      else g.lineTo(px, y);
    }
    g.lineTo(w, h);
    g.lineTo(0, h);
    g.closePath();
    g.fillStyle = '#9ca3af';
    g.fill();
    const pos = hf.positions;
    const z = pos[0][k];
    const th = pos[1][k];
    const wheelR = 0.3 * m2px;
    const bodyH = 0.42 * m2px;
    const rideH = 0.22 * m2px; // static spring length on screen
    const corners = [
      { x: a, zu: pos[3][k] },
      { x: -b, zu: pos[5][k] },
    ];
    const bodyY = (x) => yOf(z - x * th) - 2 * wheelR - rideH + (ground - yOf(0));
    // Wheels and springs.
    for (const cn of corners) {
      const cx = xOf(cn.x);
      const cy = yOf(cn.zu) - wheelR;
      const top = bodyY(cn.x);
      g.strokeStyle = '#374151';
      g.lineWidth = 2;
      g.beginPath();
      const coils = 7;
      for (let s = 0; s <= coils * 2; s++) {
        const y = cy + (top - cy) * (s / (coils * 2));
        const x = cx + (s === 0 || s === coils * 2 ? 0 : s % 2 ? 6 : -6);
        if (s === 0) g.moveTo(x, y);
        else g.lineTo(x, y);
      }
      g.stroke();
      g.beginPath();
      g.arc(cx, cy, wheelR, 0, 2 * Math.PI);
      g.fillStyle = '#111827';
      g.fill();
      g.beginPath();
      g.arc(cx, cy, wheelR * 0.45, 0, 2 * Math.PI);
      g.fillStyle = '#d1d5db';
      g.fill();
    }
    // Body: a rectangle through the two corner points, pitching with theta (x EX).
    const x0 = -b - 0.7;
    const x1 = a + 0.7;
    g.beginPath();
    g.moveTo(xOf(x0), bodyY(x0));
    g.lineTo(xOf(x1), bodyY(x1));
    g.lineTo(xOf(x1), bodyY(x1) - bodyH);
    g.lineTo(xOf(x0), bodyY(x0) - bodyH);
    g.closePath();
    g.fillStyle = 'rgba(29, 78, 216, 0.8)';
    g.fill();
    g.strokeStyle = '#1e3a8a';
    g.stroke();
    g.fillStyle = '#111';
    g.font = '12px system-ui, sans-serif';
    g.textAlign = 'left';
    g.textBaseline = 'top';
    const slow = this.rate === 1 ? '' : `, slow motion ×${this.rate}`;
    g.fillText(`t = ${hf.t[k].toFixed(2)} s, HiFi (full car), motions ×${EX}, ${fmt(v * 3.6, 3)} km/h${slow}`, 6, 6);
  }

  /** Plays or pauses the side view. */
  toggle() {
    if (!this.res) return;
    this.playing = !this.playing;
    this.playButton.textContent = this.playing ? 'Pause' : 'Play';
    if (this.playing) {
      let last = performance.now();
      let carry = 0;
      const step = (now) => {
        if (!this.playing) return;
        const hf = this.res.hifi;
        const dt = hf.t[1] - hf.t[0];
        // Whole samples of record time elapsed at this rate; the rest carries over (a
        // frame's time stamp may precede the press that started the animation).
        carry += (Math.max(0, now - last) / 1000) * this.rate;
        last = Math.max(last, now);
        const adv = Math.floor(carry / dt);
        carry -= adv * dt;
        this.k = (this.k + adv) % hf.t.length;
        this.drawFrame();
        this.raf = requestAnimationFrame(step);
      };
      this.raf = requestAnimationFrame(step);
    } else cancelAnimationFrame(this.raf);
  }
}

/** Largest damper speed on the force-velocity chart, m/s (road damper speeds stay under about 1 m/s). */
export const DAMPER_V_MAX = 1;

/** The front damper's force against its speed (the core's `damperCurve`), with the linear rate the maps use. */
export class DamperChart {
  constructor(canvas) {
    this.plot = new Plot(canvas, { aspect: 0.5 });
    this.curve = null;
    this.linear = true;
    this.thick = 1;
    /** Set by the page: reads the panel's fields and draws their law. */
    this.refresh = () => {};
  }

  setStyle({ thick }) {
    this.thick = thick;
  }

  /** Draws `curve` (`{points, linearRate}`); `linear`: the design's own linear damper. */
  draw(curve, linear) {
    this.curve = curve;
    this.linear = linear;
    this.redraw();
  }

  /**
   * Is the chart on screen (its panel open)? Read from the `hidden` attributes above it,
   * not from the layout: `offsetParent` after the readout's DOM writes forced a layout on
   * every slider move (about 2.5 ms of each, profiled).
   */
  visible() {
    return this.plot.canvas.isConnected && this.plot.canvas.closest('[hidden]') === null;
  }

  /** Draws again at the canvas's current size (nothing while its panel is hidden). */
  redraw() {
    if (!this.curve || !this.visible()) return;
    const spec = damperSpec(this.curve, { linear: this.linear });
    if (this.thick !== 1) for (const s of spec.series) s.size *= this.thick;
    this.plot.draw(spec);
  }
}
