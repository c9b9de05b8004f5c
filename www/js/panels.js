// The analysis panels below the maps: the objective plane (surrogate feasible set, Pareto
// fronts, min-max pick, datum and design), the FRF and PSD plots, the time panel with
// its animated side view, and the exports. Each panel draws from `app` (js/app.js);
// computing goes through the engines over the wasm exports `front`, `spectra` and
// `timeResponse`.

import { Plot } from './plot.js';
import { fmt, fmtPct } from './format.js';

const $ = (id) => document.getElementById(id);

const COL = {
  cloud: 'rgba(120, 160, 210, 0.35)',
  stm: '#c2410c',
  nsga: '#15803d',
  lofi: '#1d4ed8',
  hifi: '#b91c1c',
  datum: '#fff',
  pick: '#facc15',
};

// ------------------------------------------------------------------ objective plane

export class ObjectivePlane {
  constructor(app) {
    this.app = app;
    this.base = new Plot($('op-base'), { aspect: 0.62 });
    this.over = new Plot($('op-overlay'), { aspect: 0.62 });
    this.ratio = false;
  }

  /** Axis values of criteria `c` ({bacc, dtl}) in the current scale. */
  xy(bacc, dtl) {
    const d = this.app.front?.datum;
    return this.ratio && d ? [bacc / d.bacc, dtl / d.dtl] : [bacc, dtl];
  }

  labels() {
    return this.ratio
      ? ['BAcc / datum BAcc (surrogate)  [–]', 'DTL / datum DTL  [–]']
      : ['BAcc RMS  [m/s²]', 'DTL RMS  [N]'];
  }

  /** The feasible cells of the surrogate's map as [bacc[], dtl[]] (at most 120 x 90 of them). */
  cloud() {
    const m = this.app.cloud;
    const n = m.nx * m.ny;
    const step = m.nx > 120 ? 2 : 1;
    const xs = [];
    const ys = [];
    for (let j = 0; j < m.ny; j += step) {
      for (let i = 0; i < m.nx; i += step) {
        const k = j * m.nx + i;
        if (!m.feasible[k]) continue;
        const [x, y] = this.xy(m.values[k], m.values[n + k]);
        xs.push(x);
        ys.push(y);
      }
    }
    return [xs, ys];
  }

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
    const [xl, yl] = this.labels();
    this.base.opts.xLabel = xl;
    this.base.opts.yLabel = yl;
    const [cx, cy] = this.cloud();
    const front = fr.study.front.map((p) => this.xy(p.bacc, p.dtl));
    const d = this.xy(fr.datum.bacc, fr.datum.dtl);
    // The range: the front, the datum and the bulk of the feasible set near the front.
    const fx = front.map((p) => p[0]);
    const fy = front.map((p) => p[1]);
    const xs = [...fx, d[0]];
    const ys = [...fy, d[1]];
    const xmin = Math.min(...xs);
    const ymin = Math.min(...ys);
    const xmax = Math.max(...xs);
    const ymax = Math.max(...ys);
    const xr = [xmin - 0.05 * (xmax - xmin), xmax + 0.6 * (xmax - xmin)];
    const yr = [ymin - 0.05 * (ymax - ymin), ymax + 0.6 * (ymax - ymin)];
    this.base.resize();
    this.over.resize();
    this.base.setRange(xr, yr);
    this.over.setRange(xr, yr);
    this.over.opts = this.base.opts;
    this.base.begin();
    this.base.dots(cx, cy, COL.cloud, 1.4);
    this.base.line(fx, fy, COL.stm, 2.5);
    const legend = [
      { label: 'feasible designs (surrogate)', colour: 'rgb(120,160,210)', kind: 'dot' },
      { label: `Pareto front, STM (${fr.study.front.length} pts)`, colour: COL.stm, kind: 'line' },
    ];
    if (app.nsga && !app.nsga.error) {
      const nf = app.nsga.study.front.map((p) => this.xy(p.bacc, p.dtl));
      this.base.dots(nf.map((p) => p[0]), nf.map((p) => p[1]), COL.nsga, 2.6);
      legend.push({ label: `NSGA-II front (${nf.length} pts)`, colour: COL.nsga, kind: 'dot' });
    }
    const pk = fr.study.pick.criteria;
    const pp = this.xy(pk.bacc, pk.dtl);
    const rc = fr.recheck.rechecked;
    const dh = fr.datumHifi;
    // The HiFi re-check of the pick, on the same datum-relative scale as its model: a
    // larger diamond underneath, so a close re-check rings the pick instead of hiding it.
    const hp = this.ratio ? [rc.bacc / dh.bacc, rc.dtl / dh.dtl] : [rc.bacc, rc.dtl];
    this.base.marker(hp[0], hp[1], 'diamond', '#fff', COL.hifi, 9);
    this.base.marker(pp[0], pp[1], 'diamond', COL.pick, '#000', 6);
    this.base.marker(d[0], d[1], 'square', COL.datum, '#000', 8);
    legend.push({ label: 'min-max pick (surrogate)', colour: COL.pick, kind: 'marker', shape: 'diamond', stroke: '#000' });
    legend.push({ label: 'pick re-checked (HiFi)', colour: '#fff', kind: 'marker', shape: 'diamond', stroke: COL.hifi });
    legend.push({ label: 'datum', colour: '#fff', kind: 'marker', shape: 'square', stroke: '#000' });
    legend.push({ label: 'current design', colour: '#000', kind: 'marker', stroke: '#fff' });
    this.base.end();
    this.base.legend(legend);
    this.renderPick();
    this.drawOverlay();
  }

  /** The current design's marker (moves with the sliders). */
  drawOverlay() {
    const { app } = this;
    if (!app.front || app.front.error || !this.over.x) return;
    const c = this.over.canvas;
    const g = c.getContext('2d');
    g.setTransform(this.over.size.dpr, 0, 0, this.over.size.dpr, 0, 0);
    g.clearRect(0, 0, this.over.size.w, this.over.size.h);
    const { plot } = this.over.layout();
    g.save();
    g.beginPath();
    g.rect(plot.x, plot.y, plot.w, plot.h);
    g.clip();
    this.over.g = g;
    const [x, y] = this.xy(app.surrogate.design.bacc, app.surrogate.design.dtl);
    this.designAt = this.over.marker(x, y, 'circle', '#000', '#fff', 4.5);
    g.restore();
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

const OUT_NAMES = [
  { key: 'bacc', name: 'BAcc', frf: '|H| BAcc / road displacement  [1/s²]', psd: 'PSD BAcc  [(m/s²)²/Hz]' },
  { key: 'dtl', name: 'DTL', frf: '|H| DTL / road displacement  [N/m]', psd: 'PSD DTL  [N²/Hz]' },
  { key: 'sws', name: 'SWS', frf: '|H| SWS / road displacement  [m/m]', psd: 'PSD SWS  [m²/Hz]' },
];

export class SpectraPanel {
  constructor() {
    this.plots = [];
    for (const kind of ['frf', 'psd']) {
      for (const o of OUT_NAMES) {
        const c = $(`sp-${kind}-${o.key}`);
        this.plots.push({ kind, o, plot: new Plot(c, { xLog: true, yLog: true, aspect: 0.7, xLabel: 'frequency  [Hz]', yLabel: o[kind] }) });
      }
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

  draw(sp) {
    this.data = sp;
    this.dirty = false;
    if (!sp) return;
    const i = { bacc: 0, dtl: 1, sws: 2 };
    for (const { kind, o, plot } of this.plots) {
      const a = sp.lofi[kind][i[o.key]];
      const b = sp.hifi[kind][i[o.key]];
      const c = sp.surrogate[kind][i[o.key]];
      const pos = [...a, ...b, ...c].filter((v) => v > 0 && Number.isFinite(v));
      let hi = Math.max(...pos);
      let lo = Math.max(Math.min(...pos), hi * 1e-8);
      lo = 10 ** Math.floor(Math.log10(lo));
      hi = 10 ** Math.ceil(Math.log10(hi));
      plot.resize();
      plot.setRange([0.1, 100], [lo, hi]);
      plot.begin();
      // HiFi widest, then the surrogate's tuned LoFi dashed, the LoFi narrow on top.
      plot.line(sp.f, b.map((v) => (v > 0 ? v : NaN)), COL.hifi, 5);
      plot.line(sp.f, c.map((v) => (v > 0 ? v : NaN)), COL.nsga, 3, [6, 4]);
      plot.line(sp.f, a.map((v) => (v > 0 ? v : NaN)), COL.lofi, 1.4);
      plot.end();
      plot.legend([
        { label: 'LoFi (quarter car)', colour: COL.lofi, kind: 'line' },
        { label: 'HiFi (full car)', colour: COL.hifi, kind: 'line' },
        { label: `tuned LoFi (${sp.surrogateRoute})`, colour: COL.nsga, kind: 'line' },
      ]);
    }
  }
}

// ------------------------------------------------------------------ time panel

export class TimePanel {
  constructor(app) {
    this.app = app;
    this.plots = OUT_NAMES.map((o) => ({
      o,
      plot: new Plot($(`tp-${o.key}`), { aspect: 0.45, xLabel: 'time  [s]', yLabel: { bacc: 'BAcc  [m/s²]', dtl: 'DTL  [N]', sws: 'SWS  [mm]' }[o.key] }),
    }));
    this.car = $('tp-car');
    this.res = null;
    this.playing = false;
    this.k = 0;
    this.raf = null;
  }

  draw(res) {
    this.res = res;
    if (!res) return;
    const scale = { bacc: 1, dtl: 1, sws: 1000 };
    this.plots.forEach(({ o, plot }, i) => {
      const a = res.lofi.outputs[i].map((v) => v * scale[o.key]);
      const b = res.hifi.outputs[i].map((v) => v * scale[o.key]);
      const all = [...a, ...b];
      plot.resize();
      plot.setRange([res.lofi.t[0], res.lofi.t[res.lofi.t.length - 1]], [Math.min(...all), Math.max(...all)]);
      plot.begin();
      plot.line(res.hifi.t, b, COL.hifi, 2.6);
      plot.line(res.lofi.t, a, COL.lofi, 1);
      plot.end();
      plot.legend([
        { label: `LoFi (RMS ${fmt(res.lofi.rms[i] * scale[o.key], 3)})`, colour: COL.lofi, kind: 'line' },
        { label: `HiFi (RMS ${fmt(res.hifi.rms[i] * scale[o.key], 3)})`, colour: COL.hifi, kind: 'line' },
      ]);
    });
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
