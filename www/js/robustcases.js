// The robust design's cases (issue #16), as text and labels: the state's `cases` is the
// text of a `ridelab map --cases FILE` file (load cases: extra mass kg at x, y, z m from
// the car's centre of gravity, with a weight; operating points: road class, speed m/s,
// weight; combined worst case or weighted mean), which the core parses and checks. Here:
// that text read into tables and written back, a car file's load cases put in, its compact
// form for links, the labels the maps and the plane carry with cases, and the Pick tab's
// per-case table. The editor of the cases is js/robustpanel.js (loaded with the panels).

import { fmt, fmtPct } from './format.js';

/** The road classes an operating point may take (ISO 8608). */
export const CLASSES = ['A', 'B', 'C', 'D', 'E', 'F', 'G', 'H'];
/** Most cases (load cases x operating points), as the core's `robust::MAX_CASES`. */
export const MAX_CASES = 16;

/** "worst of 6 cases" / "weighted mean of 6 cases" (`desc`: the core's `describe`). */
export function ruleText(desc) {
  const n = desc.cases.length;
  return `${desc.combine === 'mean' ? 'weighted mean' : 'worst'} of ${n} case${n === 1 ? '' : 's'}`;
}

/**
 * What the maps show with cases, for their heading: "robust (worst of 6 cases)" or
 * "case 3: fully laden / B at 30 m/s"; '' without cases or for a model the cases do not
 * reach (`model`: the view's; the surrogate and its error stay on the car as given).
 */
export function robustMapLabel(state, desc, model) {
  if (!state.cases || !desc || !desc.cases || !(model === 'lofi' || model === 'hifi')) return '';
  const k = state.case && state.case !== 'robust' ? Number(state.case) : null;
  return k === null ? `robust (${ruleText(desc)})` : `case ${k}: ${desc.cases[k]}`;
}

/** The objective plane's model with cases: "(LoFi, robust: worst of 6 cases)", else null. */
export function robustPlaneLabel(state, desc) {
  return state.cases && desc && desc.cases ? `(LoFi, robust: ${ruleText(desc)})` : null;
}

/** The cases file of `text` as `{load, operating, combine}` for the tables, or null when it is not a JSON object. */
export function readCases(text) {
  try {
    const v = JSON.parse(text);
    if (!v || typeof v !== 'object' || Array.isArray(v)) return null;
    return {
      load: Array.isArray(v.load_cases) ? v.load_cases.map((c) => ({ ...c })) : [],
      operating: Array.isArray(v.operating) ? v.operating.map((o) => ({ ...o })) : [],
      combine: v.combine === 'mean' ? 'mean' : 'worst',
    };
  } catch {
    return null;
  }
}

/** A number typed in a cell: the number, or the text itself so that the core names the field. */
export function cellValue(raw) {
  const t = raw.trim();
  if (t === '') return undefined;
  const n = Number(t);
  return Number.isFinite(n) ? n : t;
}

/** How long typing rests before the cases are checked, ms. */
export const CHECK_AFTER_MS = 150;

/** The table and row key a core field path names (`cases.load_cases[1].mass`), or null. */
export function cellOf(message) {
  const m = /cases\.(load_cases|operating)\[(\d+)\]\.(\w+)/.exec(message || '');
  return m ? { table: m[1] === 'load_cases' ? 'load' : 'operating', row: Number(m[2]), key: m[3] } : null;
}

/** The cases file's text (compact JSON) of the tables' `{load, operating, combine}`. */
export function casesText({ load, operating, combine }) {
  const out = {};
  if (load.length) out.load_cases = load;
  if (operating.length) out.operating = operating;
  out.combine = combine;
  return JSON.stringify(out);
}

/**
 * The cases text `text` (or none) with its load cases replaced by `loadCases` (a car
 * file's, as the core's `parseCar` gives them); its operating points and rule kept.
 */
export function withLoadCases(text, loadCases) {
  const c = (text && readCases(text)) || { load: [], operating: [], combine: 'worst' };
  return casesText({ ...c, load: loadCases });
}

/** The cases text in its compact form (one line, no spaces), or the text itself when it is not JSON. */
export function compactCases(text) {
  try {
    return JSON.stringify(JSON.parse(text));
  } catch {
    return text;
  }
}

const esc = (s) => String(s).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c]);

/**
 * The Pick tab's per-case table of a robust front `fr` (the core's `front` with `robust`):
 * per case its name and weight, then the pick's BAcc (m/s^2), DTL (N) and SWS (mm)
 * predicted by the LoFi and re-checked on that case's HiFi, each with its % change
 * against that case's datum, and the objectives the HiFi re-check breaks (as `ridelab
 * optimize --cases --json`'s `cases`). Hidden without cases.
 */
export function renderCasePicks(table, fr) {
  if (!fr || fr.error || !fr.robust) {
    table.hidden = true;
    table.replaceChildren();
    return;
  }
  const r = fr.robust;
  const crit = [['bacc', 1, 4], ['dtl', 1, 4], ['sws', 1000, 4]];
  const cells = (c, pct) => crit.map(([k, scale, dec], i) =>
    `<td class="num" data-crit="${k}" data-value="${c[k]}">${fmt(c[k] * scale, dec)}</td>` +
    `<td class="num delta" data-crit="${k}" data-pct="${pct[i]}">${fmtPct(pct[i] / 100)}</td>`).join('');
  const rows = r.cases.map((c, k) => {
    const h = c.hifi_recheck;
    const broken = c.broken.length ? `breaks ${c.broken.map((o) => esc(o)).join(', ')} on the HiFi` : 'meets every objective on the HiFi';
    return `<tr class="case-name" data-case="${k}"><th scope="rowgroup" colspan="7">${k}: ${esc(c.case.name)}
        <span class="unit">weight ${fmt(c.case.probability, 3)}; ${c.case.sprung_mass.toFixed(0)} kg sprung</span>
        <span class="case-broken${c.broken.length ? ' bad' : ''}" data-broken="${c.broken.join(',')}">${broken}</span></th></tr>
      <tr data-case="${k}" data-model="lofi"><th scope="row">LoFi</th>${cells(h.predicted, h.predicted_change_percent)}</tr>
      <tr data-case="${k}" data-model="hifi"><th scope="row">HiFi</th>${cells(h.rechecked, h.rechecked_change_percent)}</tr>`;
  }).join('');
  table.innerHTML = `
    <caption>The pick in each case (${r.combine === 'mean' ? 'weighted mean' : 'worst case'} over ${r.cases.length}):
      the LoFi's prediction and the case's HiFi re-check, % against that case's own datum</caption>
    <thead><tr><th scope="col">Case</th><th scope="col" class="num">BAcc <span class="unit">m/s²</span></th><th scope="col" class="num">vs datum</th>
      <th scope="col" class="num">DTL <span class="unit">N</span></th><th scope="col" class="num">vs datum</th>
      <th scope="col" class="num">SWS <span class="unit">mm</span></th><th scope="col" class="num">vs datum</th></tr></thead>
    <tbody>${rows}</tbody>`;
  table.hidden = false;
}
