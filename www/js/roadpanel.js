// The measured road of the Car & road tab (issue #31). A profile file (CSV
// `distance_m,elevation_m[,elevation_right_m]`), chosen or dropped, is described by the
// core as `ridelab road FILE --json` does (Welch PSD, ISO 8608 class and waviness) and
// drawn against ISO 8608's class boundaries; the design and its datum are judged on it by
// both models (`designOnRoad`, each number as `ridelab eval --road FILE`) at the road's
// speed, again whenever the design, the car, the speed or the tracks change; the maps and
// the front on it (js/roadstudy.js, as `ridelab map` and `ridelab optimize --road FILE`).
// A refused file names its column and row and leaves the last good road. The file is not
// kept in the link or a saved session; the panel says so.

import { Plot } from './plot.js';
import { roadPsdSpec } from './chartspecs.js';
import { plainWords } from './controls.js';
import { fmt } from './format.js';

/** The core's limit on a profile file, 128 MiB (crate/src/road_profile/profile.rs MAX_BYTES is the check; this only spares reading a larger file). */
const MAX_FILE_BYTES = 128 * 1024 * 1024;
/** Quiet time after a design change before the road is judged again, ms. */
const SETTLE_MS = 150;

/** The rows of the judgement table: key, name, unit, scale from SI. */
const ROWS = [
  ['bacc', 'BAcc', 'm/s²', 1],
  ['bacc_wk', 'BAcc Wk', 'm/s²', 1],
  ['dtl', 'DTL', 'N', 1],
  ['sws', 'SWS', 'mm', 1000],
];

/**
 * Row `k` of the judgement `on` for `model` ('quarter', 'full', 'datum_quarter' or
 * 'datum_full'): the criteria, or the ISO 2631-1 Wk-weighted BAcc (`bacc_wk`).
 */
const valueOf = (on, model, k) => (k === 'bacc_wk' ? on.bacc_wk[model] : on[model][k]);

/** The state fields the judgement depends on. */
const judgedOn = (s) => JSON.stringify([s.car, s.carJson ?? null, s.ks, s.cs, s.speed, s.tracks]);

export class RoadPanel {
  /**
   * `els`: `{box, file, msg, summary, canvas, table, notes, study}` (`study`: RoadStudy's
   * elements); `store` (the state), `compute` (js/compute.js: `describeRoad`,
   * `designOnRoad`, `roadMap`, `roadFront` in the heavy worker), `hooks` (the maps'
   * `{onPick, onKey, contours, objectives}`), `look()` (the maps' `{palette, tables}`) and
   * `onRoad(road)`, told of each road read (`{name, bytes, desc}`).
   */
  constructor(els, { store, compute, hooks, look, onRoad = () => {} }) {
    this.els = els;
    /** Called with the road after each file read well (the road menu offers it). */
    this.onRoad = onRoad;
    this.store = store;
    this.compute = compute;
    this.plot = new Plot(els.canvas, { aspect: 0.6 });
    /** The maps and front on the road (js/roadstudy.js, loaded with the first road: not on the first screen's path). */
    this.study = null;
    this.studyArgs = [els.study, hooks, { compute, look }];
    this.style = null;
    /** The road shown: `{name, bytes, desc}`; its judgement `{key, on}` (`on`: the core's DesignOnRoad). */
    this.road = null;
    this.judged = null;
    this.timing = null;
    this.timer = null;
    /** Requests started (only the latest one's answer is shown). */
    this.asked = 0;
    els.file.addEventListener('change', () => {
      const f = els.file.files && els.file.files[0];
      els.file.value = '';
      if (f) this.load(f);
    });
    els.box.addEventListener('dragover', (ev) => {
      ev.preventDefault();
      els.box.classList.add('dropping');
    });
    els.box.addEventListener('dragleave', () => els.box.classList.remove('dropping'));
    els.box.addEventListener('drop', (ev) => {
      ev.preventDefault();
      els.box.classList.remove('dropping');
      const f = ev.dataTransfer && ev.dataTransfer.files[0];
      if (f) this.load(f);
    });
    els.box.addEventListener('toggle', () => this.redraw());
  }

  /** The maps and front on the road, made on first use (their module loaded then). */
  async studyView() {
    if (!this.study) {
      const { RoadStudy } = await import('./roadstudy.js');
      this.study ??= new RoadStudy(...this.studyArgs);
      if (this.style) this.study.setStyle(this.style);
    }
    return this.study;
  }

  /** Line widths times `thick` (projector mode), for the maps on the road. */
  setStyle(style) {
    this.style = style;
    if (this.study) this.study.setStyle(style);
  }

  /** Reads, describes and judges `file` (a File or Blob with a `name`); a refused file keeps the last good road. */
  async load(file) {
    const name = file.name || 'road.csv';
    const n = ++this.asked;
    this.els.msg.textContent = '';
    if (file.size > MAX_FILE_BYTES) {
      this.els.msg.textContent = `${name}: ${(file.size / 2 ** 20).toFixed(0)} MiB is larger than a profile file may be (128 MiB); ${this.keeps()}`;
      return;
    }
    this.els.summary.textContent = `Reading ${name}…`;
    try {
      const bytes = new Uint8Array(await file.arrayBuffer());
      const t0 = performance.now();
      const desc = await this.compute.describeRoad(bytes);
      const t1 = performance.now();
      const on = await this.compute.designOnRoad(this.store.state, bytes, name);
      if (n !== this.asked) return;
      /** How long the heavy worker took, ms (the benchmarks read it). */
      this.timing = { describeMs: t1 - t0, judgeMs: performance.now() - t1 };
      this.road = { name, bytes, desc };
      this.judged = { key: judgedOn(this.store.state), on };
      this.show();
      this.onRoad(this.road);
      const view = await this.studyView();
      const st = this.store.state;
      view.moveDesign({ ks: st.ks, cs: st.cs }, this.judged.key === judgedOn(st) ? this.judged.on : null);
      view.study(this.road, st);
    } catch (e) {
      if (n !== this.asked) return;
      this.els.msg.textContent = `${name}: ${plainWords(e.message || e)}; ${this.keeps()}`;
      if (this.road) this.show();
      else this.els.summary.textContent = '';
    }
  }

  /** What a refused file leaves shown, in words. */
  keeps() {
    return this.road ? `${this.road.name} stays.` : 'no road is loaded.';
  }

  /**
   * After the views changed: the design marker moved; the road judged again at the new
   * design, car, speed or tracks, and the maps and front computed again when what they
   * depend on changed (once the sliders rest).
   */
  viewsChanged() {
    if (!this.road) return;
    const s = this.store.state;
    if (this.study) this.study.moveDesign({ ks: s.ks, cs: s.cs }, this.judged && this.judged.key === judgedOn(s) ? this.judged.on : null);
    if (this.judged && this.judged.key === judgedOn(s) && this.study && this.study.isCurrent(s)) return;
    clearTimeout(this.timer);
    this.timer = setTimeout(() => {
      const now = this.store.state;
      if (!(this.judged && this.judged.key === judgedOn(now))) this.judge();
      this.studyView().then((v) => v.study(this.road, this.store.state));
    }, SETTLE_MS);
  }

  async judge() {
    const road = this.road;
    const s = this.store.state;
    const n = ++this.asked;
    try {
      const on = await this.compute.designOnRoad(s, road.bytes, road.name);
      if (n !== this.asked) return;
      this.els.msg.textContent = '';
      this.judged = { key: judgedOn(s), on };
    } catch (e) {
      if (n !== this.asked) return;
      // A speed the profile is too short for: the message says how long it must be.
      this.els.msg.textContent = `${road.name}: ${plainWords(e.message || e)}`;
      this.judged = { key: judgedOn(s), on: null };
    }
    this.show();
  }

  show() {
    const { desc, name } = this.road;
    const f = desc.iso8608;
    this.els.summary.textContent =
      `${name}: ${desc.samples} samples every ${fmt(desc.spacing_m, 3)} m (${fmt(desc.length_m / 1000, 3)} km), ` +
      `${desc.tracks} track${desc.tracks === 2 ? 's' : ''}. ISO 8608 class ${f.class}, ` +
      `Gd(n0 = 0.1 cycle/m) ${f.gd_n0.toExponential(2)} m³, waviness ${f.waviness.toFixed(2)} ` +
      `(fit over ${fmt(f.band[0], 2)}–${fmt(f.band[1], 3)} cycle/m, residual ${f.residual.toFixed(3)} in log10).`;
    this.els.box.dataset.roadClass = f.class;
    this.drawTable();
    this.redraw();
    const st = this.store.state;
    if (this.study) this.study.moveDesign({ ks: st.ks, cs: st.cs }, this.judged && this.judged.on);
  }

  drawTable() {
    const t = this.els.table;
    const on = this.judged && this.judged.on;
    t.hidden = !on;
    const notes = [...(this.road.desc.notes || []), ...(on ? on.notes : [])];
    this.els.notes.textContent = notes.length ? `Notes: ${notes.join('; ')}.` : '';
    if (!on) return;
    const r = on.road;
    t.querySelector('caption').textContent =
      `The design and the datum on ${r.file} at ${Number(r.speed.toPrecision(4))} m/s, ${r.tracks} tracks ` +
      `(exact route; the shaping filter's PSD error ${(100 * r.fit_error).toFixed(1)} % over ${fmt(r.band_hz[0], 2)}–${fmt(r.band_hz[1], 3)} Hz; ` +
      `BAcc unweighted, BAcc Wk weighted by ISO 2631-1: the full car ${on.bacc_wk.comfort}, at the datum ${on.bacc_wk.datum_comfort})`;
    const pct = (a, b) => `${a >= b ? '+' : '−'}${Math.abs(100 * (a / b - 1)).toFixed(1)} %`;
    const body = t.querySelector('tbody');
    body.replaceChildren(...ROWS.map(([k, label, unit, scale]) => {
      const tr = document.createElement('tr');
      const [q, f, q0, f0] = ['quarter', 'full', 'datum_quarter', 'datum_full'].map((m) => valueOf(on, m, k));
      const cells = [
        `${label} <span class="unit">${unit}</span>`,
        fmt(q * scale, 4), pct(q, q0),
        fmt(f * scale, 4), pct(f, f0),
      ];
      cells.forEach((html, i) => {
        const td = document.createElement(i === 0 ? 'th' : 'td');
        if (i === 0) td.scope = 'row';
        td.innerHTML = html;
        tr.append(td);
      });
      return tr;
    }));
  }

  /** The PSD chart, when the panel is open and a road is loaded. */
  redraw() {
    const shown = Boolean(this.road);
    this.els.canvas.hidden = !shown;
    if (!shown || !this.els.box.open || !this.els.canvas.clientWidth) return;
    this.plot.draw(roadPsdSpec(this.road.desc));
    if (this.study) this.study.redraw();
  }
}
