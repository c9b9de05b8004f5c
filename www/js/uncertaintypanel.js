// The adaptive loop's uncertainty map in the Surrogate tab (issue #15): the core's
// estimate sigma of the loop's surrogate, %, for the chosen criterion, as a map (the
// maps' own view, js/mapview.js, kind "sigma") with the loop's HiFi samples marked, and a
// caption that says how the estimate is computed and how well it predicts the true error
// of the surrogate on the HiFi validation grid (Pearson and Spearman correlation, by the
// core's `uncertaintyCheck`). Handed plain data (js/render.js).

import { MapView, CRITERIA } from './mapview.js';
import { fmt, fmtSmall } from './format.js';

/** The estimate's two kinds, in words (the core's `uncertainty`: "model" or "loo"). */
const KIND_WORDS = {
  model: 'model: the Gaussian-process correction\'s own predictive standard deviation',
  loo: 'loo: leave-one-out cross-validation errors spread over the box',
};

/** A criterion of CRITERIA as a sigma map's: its own element ids, the values in %. */
function sigmaCrit(c) {
  return { ...c, key: `sigma-${c.key}`, title: `σ ${c.title}`, short: c.short, unit: '%', factor: 1, teach: '' };
}

export class UncertaintyPanel {
  /**
   * `els`: `{box, select, maps, caption}` elements (the block, the criterion picker, where
   * the maps go, the caption); `hooks`: MapView's `{onPick, onKey, contours, objectives}`.
   */
  constructor({ box, select, maps, caption }, hooks) {
    this.box = box;
    this.select = select;
    this.caption = caption;
    this.views = CRITERIA.map((c) => new MapView(maps, sigmaCrit(c), hooks));
    this.last = null;
    select.addEventListener('change', () => this.last && this.show(...this.last));
  }

  /** The view of the chosen criterion (the others are hidden). */
  get view() {
    return this.views[Math.max(0, CRITERIA.findIndex((c) => c.key === this.select.value))];
  }

  /** Line widths times `thick` (projector mode). */
  setStyle(style) {
    for (const v of this.views) v.setStyle(style);
  }

  /**
   * The map and caption of the loop `a` (js/store.js `adaptive`, or null: hidden) over
   * design box `box` (N/m, N s/m); `design`, `datum`: `{ks, cs}` markers; `palette` and
   * `tables` as the maps'.
   */
  show(a, { box, design, datum, palette, tables }) {
    this.last = [a, { box, design, datum, palette, tables }];
    const u = a && a.uncertainty;
    this.box.hidden = !u;
    if (!u) return;
    const k = CRITERIA.findIndex((c) => c.key === this.select.value);
    const crit = CRITERIA[Math.max(0, k)];
    const n = u.nx * u.ny;
    const maps = { nx: u.nx, ny: u.ny, values: u.map, feasible: new Uint8Array(n).fill(1), broken: new Uint8Array(n), feasibleCount: n };
    const samples = a.report.initial;
    const adaptive = { added: a.report.added.map((x) => x.sample), next: a.proposal.error ? null : a.proposal.candidate };
    for (const v of this.views) {
      const on = v === this.view;
      v.fig.hidden = !on;
      if (!on) continue;
      v.setData({ maps, box, swsLimit: null, scale: 'abs', datum: null, kind: 'sigma', palette, tables });
      v.resize();
      v.setMarkers({ design, datum, samples, adaptive }, '');
    }
    this.caption.replaceChildren(...captionParts(a, crit));
  }

  /** Moves the design marker (`{ks, cs}`) on the shown map. */
  moveDesign(design) {
    const v = this.view;
    if (this.box.hidden || !v.markers) return;
    v.setMarkers({ ...v.markers, design }, '');
  }

  /** Redraws the shown map at its size (after the drawer opened, a resize). */
  redraw() {
    const v = this.view;
    if (this.box.hidden || !v.data) return;
    if (!v.resize()) {
      v.drawBase();
      v.drawOverlay();
    }
  }
}

/**
 * The caption of criterion `crit`'s sigma map: how the estimate is computed (the run's
 * kind and the core's words), its noise floor at the samples, and its Pearson and
 * Spearman correlation with the true |error| on the HiFi grid, each number in an element
 * (`data-stat`) with its exact value in `data-value`.
 */
function captionParts(a, crit) {
  const u = a.uncertainty;
  const c = u.check;
  const k = crit.key;
  const num = (name, v, text) => {
    const b = document.createElement('b');
    b.dataset.stat = name;
    b.dataset.value = String(v);
    b.textContent = v === null ? 'none (no spread)' : text(v);
    return b;
  };
  const three = (v) => fmt(v, 3);
  const samples = a.report.initial.length + a.report.added.length;
  return [
    `σ: the estimated 1σ relative error of ${crit.long} of ${a.report.surrogate} fitted to ${samples} HiFi samples (× on the map), %. `,
    `Uncertainty kind ${KIND_WORDS[c.method] || c.method} (${c.description}). `,
    'At the samples σ is at most ', num('floor', u.atSamples[k], fmtSmall), ' % (its noise floor). ',
    `Against the surrogate's true |error| on the ${u.levels} × ${u.levels} HiFi grid: Pearson r = `, num('pearson', c.pearson[k], three),
    ', Spearman ρ = ', num('spearman', c.spearman[k], three),
    '; mean σ ', num('estimated', c.estimated_mean_percent[k], three), ' %, mean true |error| ', num('true', c.true_mean_percent[k], three), ' %.',
  ];
}
