// The maps and the Pareto front on a measured road (issue #31), in the road panel of the
// Car & road tab: the three design-criteria maps of the LoFi or the HiFi on the dropped
// profile (one shown at a time, the maps' own view, js/mapview.js, with the design
// objectives' hatching against the datum on that road), computed as `ridelab map --road
// FILE` computes them, and the front of comfort and road holding on that road with its
// pick as `ridelab optimize --road FILE --grid 61 --levels 2` finds it (the objective
// plane's STM settings; the core's `roadMap` and `roadFront`,
// heavy worker). They are computed again when the car, the speed, the tracks, the design
// box, the objectives, the comfort measure or the pick rule change; a design move only
// moves the markers. A click on the map moves the workbench's design.

import { MapView, CRITERIA, WK_CRITERION } from './mapview.js';
import { Plot } from './plot.js';
import { roadFrontSpec } from './chartspecs.js';
import { plainWords } from './controls.js';
import { fmt } from './format.js';

/** The state fields the maps and the front do not depend on (the design, the ISO road, the surrogate, the robust cases). */
const NOT_USED = ['ks', 'cs', 'class', 'surrogate', 'plan', 'cases', 'case'];

/** The state fields the maps and the front depend on, as a key. */
function studiedOn(s) {
  return JSON.stringify(Object.entries(s).filter(([k]) => !NOT_USED.includes(k)).sort(([a], [b]) => (a < b ? -1 : 1)));
}

export class RoadStudy {
  /**
   * `els`: `{box, model, crit, status, maps, front, caption}` (the block, the model and
   * criterion pickers, the status line, where the map goes, the front's canvas and its
   * caption); `hooks`: MapView's `{onPick, onKey, contours, objectives}`; `compute`
   * (js/compute.js `roadMap`, `roadFront`); `look()`: `{palette, tables}` of the maps.
   */
  constructor(els, hooks, { compute, look }) {
    this.els = els;
    this.compute = compute;
    this.look = look;
    this.views = CRITERIA.map((c) => new MapView(els.maps, { ...c, key: `road-${c.key}` }, hooks));
    this.plot = new Plot(els.front, { aspect: 0.8 });
    /** What is shown: `{key, model, name, map, front}` (`map`, `front`: the core's answers). */
    this.shown = null;
    /** What is being computed: `{key, model, bytes}`, or null. */
    this.pending = null;
    /** The design `{ks, cs}` and its judgement on the road (`designOnRoad`), for the markers. */
    this.design = null;
    this.asked = 0;
    els.model.addEventListener('change', () => this.last && this.study(...this.last));
    els.crit.addEventListener('change', () => this.draw());
  }

  /** Whether the maps and front shown (or being computed) are those of state `s`. */
  isCurrent(s) {
    const key = studiedOn(s);
    return this.pending ? this.pending.key === key : Boolean(this.shown) && this.shown.key === key;
  }

  /** The model picked: 'hifi' or 'lofi'. */
  get model() {
    return this.els.model.value === 'lofi' ? 'lofi' : 'hifi';
  }

  /** The view of the chosen criterion (the others are hidden). */
  get view() {
    const k = CRITERIA.findIndex((c) => c.key === this.els.crit.value);
    return this.views[Math.max(0, k)];
  }

  /** Line widths times `thick` (projector mode). */
  setStyle(style) {
    for (const v of this.views) v.setStyle(style);
  }

  /**
   * The maps and front of `road` (`{name, bytes}`) for state `s`, computed unless they are
   * shown already; a failure (a speed the profile is too short for, no feasible design)
   * is said in the status line and leaves nothing stale shown.
   */
  async study(road, s) {
    this.last = [road, s];
    this.els.box.hidden = false;
    const key = studiedOn(s);
    const model = this.model;
    const sh = this.shown;
    if (sh && sh.key === key && sh.model === model && sh.name === road.name && sh.bytes === road.bytes) return;
    const p = this.pending;
    if (p && p.key === key && p.model === model && p.bytes === road.bytes) return;
    const n = ++this.asked;
    this.pending = { key, model, bytes: road.bytes };
    const who = model === 'hifi' ? 'HiFi (full car)' : 'LoFi (quarter car)';
    this.els.status.textContent = `Computing the ${who} maps and front on ${road.name}…`;
    const t0 = performance.now();
    let map = null;
    let front = null;
    let failure = null;
    try {
      map = await this.compute.roadMap(s, road.bytes, road.name, model);
      const t1 = performance.now();
      try {
        front = await this.compute.roadFront(s, road.bytes, road.name, model);
      } catch (e) {
        failure = e;
      }
      /** How long the heavy worker took, ms (the benchmarks read it). */
      this.timing = { mapMs: t1 - t0, frontMs: performance.now() - t1 };
    } catch (e) {
      failure = e;
    }
    if (n !== this.asked) return;
    this.pending = null;
    this.shown = { key, model, name: road.name, bytes: road.bytes, map, front, s };
    const why = failure && plainWords(failure.message || failure);
    this.els.status.textContent = !failure ? '' : map ? `No front on ${road.name}: ${why}` : `${road.name}: ${why}`;
    this.draw();
  }

  /** Moves the design marker: `design` `{ks, cs}`, `on` its judgement on the road (or null while it is computed). */
  moveDesign(design, on) {
    const was = this.design && this.design.on;
    this.design = { ...design, on };
    if (!this.shown || this.els.box.hidden) return;
    this.markers();
    // The front shows the design's judgement: redrawn when that changes, not on every
    // slider step (the judgement comes once the slider rests).
    if (on !== was) this.drawFront();
  }

  /** The shown map and front at their size (after the panel opened, a resize). */
  redraw() {
    if (!this.shown || this.els.box.hidden) return;
    const v = this.view;
    if (v.data && !v.resize()) {
      v.drawBase();
      v.drawOverlay();
    }
    this.drawFront();
  }

  draw() {
    const sh = this.shown;
    if (!sh) return;
    const { map, s } = sh;
    const wk = s.comfort === 'wk';
    for (const v of this.views) {
      const on = Boolean(map) && v === this.view;
      v.fig.hidden = !on;
      if (!on) continue;
      if (v.crit.plane === 0) v.crit = { ...(wk ? WK_CRITERION : CRITERIA[0]), key: 'road-bacc' };
      v.captionTitle();
      const { palette, tables } = this.look();
      v.setData({ maps: map, box: map.designBox, swsLimit: map.swsLimit, scale: 'abs', datum: map.datum, palette, tables });
      v.resize();
    }
    this.markers();
    this.drawFront();
    this.caption();
  }

  /** The design and datum markers and the pick on the shown map, its caption the design's value. */
  markers() {
    const sh = this.shown;
    if (!sh || !sh.map) return;
    const v = this.view;
    const datum = { ks: sh.map.datumKs, cs: sh.map.datumCs };
    const design = this.design ? { ks: this.design.ks, cs: this.design.cs } : datum;
    const pick = sh.front ? { ks: sh.front.pick.ks, cs: sh.front.pick.cs } : null;
    const on = this.design && this.design.on;
    const m = sh.model === 'hifi' ? 'full' : 'quarter';
    let caption = '';
    if (on) {
      const key = v.crit.plane === 0 && sh.s.comfort === 'wk' ? 'wk' : ['bacc', 'dtl', 'sws'][v.crit.plane];
      const val = key === 'wk' ? on.bacc_wk[m] : on[m][key];
      caption = `design: ${fmt(val * v.crit.factor, 4)} ${v.crit.unit}`;
    }
    v.setMarkers({ design, datum, pick }, caption);
  }

  drawFront() {
    const sh = this.shown;
    const c = this.els.front;
    c.hidden = !(sh && sh.front);
    if (c.hidden || !c.clientWidth) return;
    const on = this.design && this.design.on;
    const m = sh.model === 'hifi' ? 'full' : 'quarter';
    const design = on ? { bacc: sh.s.comfort === 'wk' ? on.bacc_wk[m] : on[m].bacc, dtl: on[m].dtl } : null;
    this.plot.draw(roadFrontSpec(sh.front, { design, wk: sh.s.comfort === 'wk', model: sh.model }));
  }

  caption() {
    const sh = this.shown;
    const { map, front } = sh;
    if (!map) {
      this.els.caption.textContent = '';
      return;
    }
    const r = map.road;
    const who = sh.model === 'hifi' ? 'HiFi (full car)' : 'LoFi (quarter car)';
    const n = map.nx * map.ny;
    let text = `${who} on ${r.file} at ${Number(r.speed.toPrecision(4))} m/s, ${r.tracks} tracks, over ${map.nx} × ${map.ny} designs of the box ` +
      `(exact route with the road's shaping filter, as ridelab map --road): ${(100 * map.feasibleCount / n).toFixed(1)} % meet the design objectives ` +
      `against the datum on this road. The car as given: load cases and operating points are ISO-class scenarios.`;
    if (front) {
      const p = front.pick;
      const ch = p.change_percent;
      text += ` Front: ${front.front.length} designs by STM with the objective plane's settings (${front.evaluations} runs, as ridelab optimize --road --grid 61 --levels 2); ` +
        `${p.rule === 'minmax' ? 'min-max' : p.rule} pick Ks ${fmt(p.ks / 1000, 4)} kN/m, Cs ${fmt(p.cs / 1000, 4)} kNs/m: ` +
        `${sh.s.comfort === 'wk' ? 'BAcc Wk' : 'BAcc'} ${ch[0] >= 0 ? '+' : '−'}${Math.abs(ch[0]).toFixed(1)} %, DTL ${ch[1] >= 0 ? '+' : '−'}${Math.abs(ch[1]).toFixed(1)} % against the datum on the HiFi.`;
    }
    this.els.caption.textContent = text;
  }
}
