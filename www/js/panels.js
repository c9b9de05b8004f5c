// The analysis panels below the maps: the objective plane (surrogate feasible set, Pareto
// fronts, min-max pick, datum and design), the FRF and PSD plots, the time panel with
// its animated side view, and the exports. Each panel draws from `app` (js/app.js);
// computing goes through the engines over the wasm exports `front`, `spectra` and
// `timeResponse`.

import { Plot } from './plot.js';
import { fmt, fmtPct } from './format.js';
import { CLOUD_OPACITY, OUTPUTS, cloudPoints, objectiveSpec, planeXY, spectraSpec, timeSpec } from './chartspecs.js';

const $ = (id) => document.getElementById(id);

/** The live layer's colours (the charts' own are in js/chartspecs.js). */
const CLOUD_FILL = `rgba(120, 160, 210, ${CLOUD_OPACITY})`;

// ------------------------------------------------------------------ objective plane

export class ObjectivePlane {
  constructor(app) {
    this.app = app;
    this.base = new Plot($('op-base'), { aspect: 0.62 });
    this.over = $('op-overlay');
    this.ratio = false;
  }

  /**
   * The plane in three layers on the base canvas: plotters' axes, the cloud of feasible
   * designs (the page's own dots: thousands of them in one path), then plotters' fronts,
   * markers and legend. The current design goes on the overlay canvas.
   */
  drawBase() {
    const { app } = this;
    const fr = app.front;
    const msg = $('op-msg');
    const wrap = $('op-wrap');
    if (!fr || fr.error) {
      msg.textContent = fr ? `No front to draw: ${fr.error.replace(/^sws_limit: /, 'SWS limit: ')}` : '';
      msg.className = 'status bad';
      msg.hidden = !fr;
      wrap.hidden = true;
      $('op-pick').hidden = true;
      return;
    }
    msg.hidden = true;
    wrap.hidden = false;
    $('op-pick').hidden = false;
    const spec = objectiveSpec(app, { ratio: this.ratio, live: true });
    if (this.base.draw(spec, 'axes')) {
      // Every cell of a cloud up to 120 wide, every other one of a larger one.
      this.base.dots(cloudPoints(app, this.ratio, app.cloud.nx > 120 ? 2 : 1), CLOUD_FILL, 1.4);
      this.base.draw(spec, 'series');
    }
    this.renderPick();
    this.drawOverlay();
  }

  /** The current design's marker (moves with the sliders). */
  drawOverlay() {
    const { app } = this;
    const b = this.base;
    if (!app.front || app.front.error || !b.placed || b.error) return;
    const c = this.over;
    const { w, h, dpr } = b.size;
    if (c.width !== b.canvas.width || c.height !== b.canvas.height) {
      c.width = b.canvas.width;
      c.height = b.canvas.height;
    }
    if (c.style.height !== b.canvas.style.height) c.style.height = b.canvas.style.height;
    const g = c.getContext('2d');
    g.setTransform(dpr, 0, 0, dpr, 0, 0);
    g.clearRect(0, 0, w, h);
    const { plot } = b.layout();
    const [x, y] = planeXY(app, this.ratio)(app.surrogate.design.bacc, app.surrogate.design.dtl);
    const [px, py] = b.px(x, y);
    this.designAt = [px, py];
    if (px < plot.x || px > plot.x + plot.w || py < plot.y || py > plot.y + plot.h) return;
    const r = 4.5 * b.size.zoom;
    g.beginPath();
    g.arc(px, py, r, 0, 2 * Math.PI);
    g.fillStyle = '#000';
    g.fill();
    g.lineWidth = 2;
    g.strokeStyle = '#fff';
    g.stroke();
  }

  renderPick() {
    const fr = this.app.front;
    const p = fr.study.pick;
    const r = fr.recheck;
    const row = (name, unit, k, scale, dec) => {
      const lo = p.criteria[k] * scale;
      const hi = r.rechecked[k] * scale;
      const i = { bacc: 0, dtl: 1, sws: 2 }[k];
      return `<tr><th scope="row">${name} <span class="unit">${unit}</span></th>
        <td class="num" data-value="${p.criteria[k]}">${fmt(lo, dec)}</td>
        <td class="num delta">${fmtPct(p.change_percent[i] / 100)}</td>
        <td class="num" data-value="${r.rechecked[k]}">${fmt(hi, dec)}</td>
        <td class="num delta">${fmtPct(r.rechecked_change_percent[i] / 100)}</td>
        <td class="num">${fmtPct(r.error_percent[i] / 100, 2)}</td></tr>`;
    };
    $('op-pick').innerHTML = `
      <caption>Min-max pick: Ks = <b data-value="${p.ks}">${fmt(p.ks / 1000, 4)} kN/m</b>,
        Cs = <b data-value="${p.cs}">${fmt(p.cs / 1000, 4)} kNs/m</b>;
        hypervolume ${fmt(fr.study.hypervolume, 4)} (m/s²)·N, ${fr.study.evaluations} runs of ${fr.study.evaluator}</caption>
      <thead><tr><th scope="col">Criterion</th><th scope="col" class="num">Surrogate</th><th scope="col" class="num">vs datum</th>
        <th scope="col" class="num">HiFi re-check</th><th scope="col" class="num">vs datum</th>
        <th scope="col" class="num">Surrogate − HiFi</th></tr></thead>
      <tbody>${row('BAcc', 'm/s²', 'bacc', 1, 4)}${row('DTL', 'N', 'dtl', 1, 4)}${row('SWS', 'mm', 'sws', 1000, 4)}</tbody>`;
  }
}

// ------------------------------------------------------------------ spectra

export class SpectraPanel {
  constructor(app) {
    this.app = app;
    this.plots = [];
    for (const which of ['frf', 'psd']) {
      for (const o of OUTPUTS) this.plots.push({ which, key: o.key, plot: new Plot($(`sp-${which}-${o.key}`), { aspect: 0.7 }) });
    }
  }

  /**
   * Draws `sp` now if the panel is on screen, else when it scrolls into view: six log-log
   * charts are the largest redraw after a design change, and nobody sees them off screen.
   */
  show(sp) {
    this.data = sp;
    if (!this.observer) {
      this.visible = true;
      this.observer = new IntersectionObserver((entries) => {
        this.visible = entries.some((e) => e.isIntersecting);
        if (this.visible && this.dirty) this.draw(this.data);
      });
      this.observer.observe($('sp-frf-bacc').closest('section'));
    }
    this.dirty = !this.visible;
    if (this.visible) this.draw(sp);
  }

  /** The six charts of `sp` (the app's current spectra) through plotters. */
  draw(sp) {
    this.data = sp;
    this.dirty = false;
    if (!sp) return;
    $('sp-key-route').textContent = sp.surrogateRoute;
    for (const { which, key, plot } of this.plots) plot.draw(spectraSpec(this.app, which, key, { legend: 'none' }));
  }
}

// ------------------------------------------------------------------ time panel

export class TimePanel {
  constructor(app) {
    this.app = app;
    this.plots = OUTPUTS.map((o) => ({ key: o.key, plot: new Plot($(`tp-${o.key}`), { aspect: 0.45 }) }));
    this.car = $('tp-car');
    this.res = null;
    this.playing = false;
    this.k = 0;
    this.raf = null;
  }

  draw(res) {
    this.res = res;
    if (!res) return;
    for (const { key, plot } of this.plots) plot.draw(timeSpec(this.app, key));
    this.k = 0;
    this.drawCar();
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
    const v = this.app.state.speed;
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
    g.fillText(`t = ${hf.t[k].toFixed(2)} s, HiFi (full car), motions ×${EX}, ${fmt(v * 3.6, 3)} km/h`, 6, 6);
  }

  toggle() {
    if (!this.res) return;
    this.playing = !this.playing;
    $('tp-play').textContent = this.playing ? 'Pause' : 'Play';
    if (this.playing) {
      let last = performance.now();
      const step = (now) => {
        if (!this.playing) return;
        const hf = this.res.hifi;
        const dt = hf.t[1] - hf.t[0];
        this.k = (this.k + Math.max(1, Math.round((now - last) / 1000 / dt))) % hf.t.length;
        last = now;
        this.drawCar();
        this.raf = requestAnimationFrame(step);
      };
      this.raf = requestAnimationFrame(step);
    } else cancelAnimationFrame(this.raf);
  }
}

// ------------------------------------------------------------------ exports

/** Saves `blob` as `name` through a temporary link (no request leaves the page). */
export function download(name, blob) {
  const url = URL.createObjectURL(blob);
  const link = document.createElement('a');
  link.href = url;
  link.download = name;
  document.body.append(link);
  link.click();
  link.remove();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
}

/**
 * CSV of the maps shown (`model`: lofi, hifi, surrogate; or error, whose columns are the
 * surrogate's signed error against the HiFi in %): one row per cell.
 */
export function mapsCsv(app, model, m) {
  const box = app.desc.designBox;
  const n = m.nx * m.ny;
  const lines = [
    model === 'error'
      ? 'ks_N_per_m,cs_Ns_per_m,bacc_error_percent,dtl_error_percent,sws_error_percent,feasible'
      : 'ks_N_per_m,cs_Ns_per_m,bacc_m_per_s2,dtl_N,sws_m,feasible',
  ];
  for (let j = 0; j < m.ny; j++) {
    const cs = box.cs_min + ((j + 0.5) * (box.cs_max - box.cs_min)) / m.ny;
    for (let i = 0; i < m.nx; i++) {
      const ks = box.ks_min + ((i + 0.5) * (box.ks_max - box.ks_min)) / m.nx;
      const k = j * m.nx + i;
      lines.push(`${ks},${cs},${m.values[k]},${m.values[n + k]},${m.values[2 * n + k]},${m.feasible[k]}`);
    }
  }
  return lines.join('\n') + '\n';
}

/** CSV of the STM front (and the NSGA-II one when computed). */
export function frontCsv(app) {
  const lines = ['method,ks_N_per_m,cs_Ns_per_m,bacc_m_per_s2,dtl_N,sws_m,pick'];
  for (const [name, r] of [['stm', app.front], ['nsga2', app.nsga]]) {
    if (!r || r.error) continue;
    r.study.front.forEach((p, i) => {
      lines.push(`${name},${p.ks},${p.cs},${p.bacc},${p.dtl},${p.sws},${i === r.study.pick.index ? 1 : 0}`);
    });
  }
  return lines.join('\n') + '\n';
}

/** Downloads a canvas as PNG; an overlay canvas is composited over its base. */
export function canvasPng(name, base, overlay) {
  let c = base;
  if (overlay) {
    c = document.createElement('canvas');
    c.width = base.width;
    c.height = base.height;
    const g = c.getContext('2d');
    g.drawImage(base, 0, 0);
    g.drawImage(overlay, 0, 0);
  }
  c.toBlob((blob) => download(name, blob), 'image/png');
}
