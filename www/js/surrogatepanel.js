// The surrogate panel: the approach and plan pickers, the fit report (metrics on the
// HiFi validation grid, tuning parameters) from the wasm export `surrogateFit`, and the
// adaptive HiFi loop's proposal line and table of added samples (issue #15).

import { fmt } from './format.js';

/** Plans offered in the picker: Audze-Eglais and full-factorial grids. */
const PLANS = ['ae:3', 'ae:4', 'ae:5', 'ae:6', 'ae:8', 'ae:10', 'ae:12', 'ae:15', 'ae:20',
  'grid:2', 'grid:3', 'grid:4', 'grid:5', 'grid:7', 'grid:10'];

const PLAN_WORDS = (p) => {
  const [kind, n] = p.split(':');
  return kind === 'ae' ? `Audze-Eglais, ${n} points` : `grid ${n} × ${n} (${n * n} points)`;
};

/** The groups of the approach picker, by a name's first word. */
const GROUPS = [
  ['rba', 'RBA: correct the LoFi\'s outputs (response-based)'],
  ['vba', 'VBA: transform Ks and Cs before the LoFi (variable-based)'],
  ['pba', 'PBA: scale the LoFi\'s masses (parameter-based)'],
  ['data', 'Data fit: the HiFi samples alone, no LoFi'],
];

const WORDS = {
  mul: 'multiplied by', add: 'plus', poly1: 'a linear fit', poly2: 'a quadratic fit',
  rbf: 'radial basis functions', gauss: '(Gaussian)', mq: '(multiquadric)', tps: '(thin-plate)',
  lts: 'linear transform', mts: 'mixed transform', qts: 'quadratic transform',
  smts: 'sprung mass', umts: 'unsprung mass', kt: 'tyre stiffness',
  lin: 'linear fit', quad: 'quadratic fit',
};

/** A plain-language label of a surrogate name (`rba-mul-rbf-mq-per-criterion`, ...), its code name after it. */
function surrogateLabel(name) {
  const per = name.endsWith('-per-criterion');
  const base = per ? name.slice(0, -'-per-criterion'.length) : name;
  const [kind, ...rest] = base.split('-');
  let text;
  if (kind === 'rba') {
    const [form, ...resp] = rest;
    text = `LoFi ${WORDS[form] || form} ${resp.map((w) => WORDS[w] || w).join(' ')}`;
  } else if (kind === 'pba') {
    text = `scale ${rest.map((w) => WORDS[w] || w).join(', ')}`;
  } else {
    text = rest.map((w) => WORDS[w] || w).join(' ');
  }
  return `${text}${per ? ', one tuning per criterion' : ''} (${name})`;
}

/** Fills the approach picker (grouped RBA / VBA / PBA / data fit) and the plan picker. */
export function buildPickers(approachSelect, planSelect, names) {
  for (const [kind, label] of GROUPS) {
    const g = document.createElement('optgroup');
    g.label = label;
    for (const n of names.filter((x) => x.split('-')[0] === kind)) {
      const o = document.createElement('option');
      o.value = n;
      o.textContent = surrogateLabel(n);
      g.append(o);
    }
    if (g.children.length) approachSelect.append(g);
  }
  for (const p of PLANS) {
    const o = document.createElement('option');
    o.value = p;
    o.textContent = PLAN_WORDS(p);
    planSelect.append(o);
  }
}

const CRIT = [
  ['bacc', 'BAcc', 'm/s²', 1],
  ['dtl', 'DTL', 'N', 1],
  ['sws', 'SWS', 'mm', 1000],
];

/**
 * The metrics table of a fit report (`ridelab surrogate` JSON): R², RMSE, largest
 * absolute error and the relative true errors per criterion, on the HiFi grid.
 */
export function renderMetrics(table, report) {
  table.replaceChildren();
  if (!report) return;
  const cap = table.createCaption();
  cap.textContent = `Against the HiFi on a ${report.validation_levels} × ${report.validation_levels} grid over the design box (${report.hifi_evaluations} HiFi runs in all).`;
  const head = table.createTHead().insertRow();
  for (const h of ['Criterion', 'R²', 'RMSE', 'max |error|', 'max RTE %', 'mean RTE %']) {
    const th = document.createElement('th');
    th.scope = 'col';
    th.textContent = h;
    if (h !== 'Criterion') th.className = 'num';
    head.append(th);
  }
  const body = table.createTBody();
  for (const [key, title, unit, f] of CRIT) {
    const m = report.metrics[key];
    const tr = body.insertRow();
    tr.dataset.crit = key;
    const th = document.createElement('th');
    th.scope = 'row';
    th.textContent = `${title} (${unit})`;
    tr.append(th);
    const cells = [
      ['r2', fmt(m.r2, 6)],
      ['rmse', fmt(m.rmse * f, 3)],
      ['max_abs_error', fmt(m.max_abs_error * f, 3)],
      ['rte_max_percent', fmt(m.rte_max_percent, 3)],
      ['rte_mean_percent', fmt(m.rte_mean_percent, 3)],
    ];
    for (const [k, text] of cells) {
      const td = tr.insertCell();
      td.className = 'num';
      td.textContent = text;
      td.dataset.metric = k;
      td.dataset.value = String(m[k]);
    }
  }
}

/** One line on how the surrogate was tuned. */
export function tuningText(report) {
  if (!report) return '';
  const d = report.diagnostics.map((x) => `${x.criteria}: ${x.method}${x.iterations ? `, ${x.iterations} iterations` : ''}`).join('; ');
  const shown = report.tuning.slice(0, 12).map((p) => `${p.name} = ${fmt(p.value, 4)}`).join(', ');
  const more = report.tuning.length > 12 ? ` and ${report.tuning.length - 12} more` : '';
  return `${report.samples.length} HiFi samples (${report.plan_method}). Fit: ${d}. Tuning: ${shown || 'none'}${more}.`;
}

/**
 * The adaptive loop's next run in words: where (Ks kN/m, Cs kNs/m), why (the core's
 * reason), its expected hypervolume improvement and probability of meeting the
 * objectives; or why there is none.
 */
export function proposalText(proposal) {
  if (proposal.error) return `No further HiFi run: ${proposal.error.replace(/^adaptive: /, '')}.`;
  const c = proposal.candidate;
  if (proposal.converged) {
    return `Converged: the best next run (Ks ${fmt(c.ks / 1000, 4)} kN/m, Cs ${fmt(c.cs / 1000, 4)} kNs/m) is expected to improve the front's ` +
      `hypervolume by ${fmt(c.value, 3)} (m/s²)·N, below the stop threshold, so the loop stops here; "Run anyway" adds it. Why: ${proposal.reason}.`;
  }
  return `Next HiFi run: Ks ${fmt(c.ks / 1000, 4)} kN/m, Cs ${fmt(c.cs / 1000, 4)} kNs/m, ${c.on_front ? 'on' : 'off'} the predicted front; ` +
    `EHVI ${fmt(c.ehvi, 3)} (m/s²)·N, probability feasible ${fmt(100 * c.probability_feasible, 3)} %. Why: ${proposal.reason}.`;
}

/**
 * The table of the samples the adaptive loop added (`a`: js/store.js `adaptive`, or null),
 * in order: run number, Ks, Cs, and the front's hypervolume and the pick's HiFi re-check
 * error after it, with the reason on a row of its own below (it is long; a phone keeps
 * the numbers in view); the plan's row first.
 */
export function renderAdaptive(table, a) {
  table.replaceChildren();
  table.hidden = !a;
  if (!a) return;
  const h = a.report.history;
  const cap = table.createCaption();
  cap.textContent = `${a.report.surrogate} on ${a.report.plan} + ${a.report.added.length} adaptive runs (${a.report.uncertainty} uncertainty); hypervolume against the fixed reference point (${fmt(a.report.reference_point[0], 4)} m/s², ${fmt(a.report.reference_point[1], 4)} N).`;
  const head = table.createTHead().insertRow();
  for (const t of ['HiFi run', 'Ks kN/m', 'Cs kNs/m', 'Hypervolume (m/s²)·N', 'Pick error %']) {
    const th = document.createElement('th');
    th.scope = 'col';
    th.textContent = t;
    th.className = 'num';
    head.append(th);
  }
  const body = table.createTBody();
  const row = (kind, run, ks, cs, why, k) => {
    const tr = body.insertRow();
    tr.dataset.kind = kind;
    const cells = [
      [String(run), run],
      [ks === null ? '–' : fmt(ks / 1000, 4), ks],
      [cs === null ? '–' : fmt(cs / 1000, 4), cs],
      [fmt(h[k].hypervolume, 5), h[k].hypervolume],
      [fmt(a.errors[k], 3), a.errors[k]],
    ];
    for (const [text, v] of cells) {
      const td = tr.insertCell();
      td.textContent = text;
      td.className = 'num';
      if (v !== null) td.dataset.value = String(v);
    }
    const note = body.insertRow();
    note.className = 'why';
    const td = note.insertCell();
    td.colSpan = cells.length;
    td.textContent = why;
  };
  row('plan', `1–${h[0].hifi_runs}`, null, null, `The ${a.report.plan} plan.`, 0);
  a.report.added.forEach((x, i) => row('added', x.run, x.sample.ks, x.sample.cs, x.reason, i + 1));
}
