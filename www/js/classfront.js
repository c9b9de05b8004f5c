// The class front (issue #30): each student sends the teacher their chosen design as a
// short code (js/classcode.js), and the teacher's page shows every student's design on
// the three maps and on the objective plane against the front and the pick, ranked by
// the min-max score. Student side: "Send my design" shows the current design's code and
// copies it. Teacher side: paste the codes (or drop / open a text file), Apply; Clear
// takes them off. Up to MAX_CODES codes; every line that is not used is named with its
// line number, text and the reason.
//
// Each design is evaluated by the engine on the teacher's scenario (js/compute.js
// `design`: the LoFi, the HiFi readout and the criteria of the plane's model); the
// table shows the HiFi full car's BAcc (m/s²), DTL (N) and SWS (mm on the page, m in
// the data), Ks in kN/m and Cs in kNs/m (N/m and N s/m in the data). The min-max score
// is the one the page's pick minimises (crate/src/optimize/minmax.rs): the design's
// criteria on the plane's model as ratios to the front's datum, `r_i = f_i / f_i(datum)`,
// normalised over the front, `d_i = (r_i - r_i,min) / (r_i,max - r_i,min)` (0 where the
// front has no spread), score `max(d_BAcc, d_DTL)`: 0 is the ideal point, a front point
// scores 0..1, a design off the front can score above 1 (or below 0 when it beats the
// front's best in both, which only an infeasible design can).

import { MAX_CODES, cleanName, encodeCode, readCodes, scenarioHash } from './classcode.js';
import { scenarioKey } from './store.js';
import { explain } from './controls.js';
import { fmt, fmtInput } from './format.js';

/**
 * The min-max score of criteria `c` (`{bacc, dtl}` on the plane's model) against front
 * study `fr` (js/compute.js `scenario().front`): `{distance: [d_bacc, d_dtl], score}`,
 * or null when `fr` has no front or a number is not finite.
 */
function minMaxScore(fr, c) {
  if (!fr || fr.error || !fr.study || !fr.study.front.length) return null;
  const datum = fr.datum;
  const ratio = (p) => [p.bacc / datum.bacc, p.dtl / datum.dtl];
  const rs = fr.study.front.map(ratio);
  const r = ratio(c);
  const distance = [0, 1].map((k) => {
    const lo = Math.min(...rs.map((x) => x[k]));
    const hi = Math.max(...rs.map((x) => x[k]));
    return hi - lo > 0 ? (r[k] - lo) / (hi - lo) : 0;
  });
  const score = Math.max(...distance);
  return Number.isFinite(score) ? { distance, score } : null;
}

const finite = (c) => !!c && ['bacc', 'dtl', 'sws'].every((k) => Number.isFinite(c[k]));

/**
 * The codes read from the text (js/classcode.js `readCodes`) evaluated on state `s`'s
 * scenario (`desc` its `describe`, `fr` its front, `compute` js/compute.js): `{rows,
 * problems}`. `rows` ranked by ascending min-max score (ties and designs with no score
 * keep the order of the text): `{rank, n, line, label, ks, cs, hifi, lofi, plane, score,
 * distance, feasible, note}` (criteria in SI); `problems`: the lines not ranked or
 * ranked with a warning, `{line, text, reason, ranked}` (`ranked`: true for a design
 * ranked with a note). Never throws.
 */
async function evaluateClass(compute, s, desc, fr, { codes, problems: unread }) {
  const here = scenarioHash(scenarioKey(s));
  const problems = [...unread];
  const rows = [];
  const box = desc.designBox;
  for (const c of codes) {
    const named = (reason) => problems.push({ line: c.line, text: c.text, reason });
    if (c.car !== s.car) {
      named(`made for the ${c.car} car; this page shows the ${s.car} car (left out)`);
      continue;
    }
    const other = c.scenario !== here;
    if (other && s.car === 'custom') {
      named('made for another custom car or scenario (left out)');
      continue;
    }
    let r;
    try {
      r = await compute.design({ ...s, ks: c.ks, cs: c.cs }, desc, true);
    } catch (e) {
      named(`cannot be evaluated here: ${explain(e || { message: 'no reason given' }, 'ks')} (left out)`);
      continue;
    }
    if (!finite(r.hifi) || !finite(r.lofi) || !finite(r.plane)) {
      named('the models have no finite answer for this design (left out)');
      continue;
    }
    const notes = [];
    if (other) {
      notes.push('made on another road, speed or objective: scored on this one');
      problems.push({ line: c.line, text: c.text, reason: 'made on another scenario of this car (road, speed, objectives or box differ): ranked on this one, see its note', ranked: true });
    }
    if (c.ks < box.ks_min || c.ks > box.ks_max || c.cs < box.cs_min || c.cs > box.cs_max) notes.push('outside the design box');
    const m = minMaxScore(fr, r.plane);
    rows.push({
      n: c.n, line: c.line, label: c.name ? c.name.replace(/_/g, ' ') : `student ${c.n}`, ks: c.ks, cs: c.cs,
      hifi: pick3(r.hifi), lofi: pick3(r.lofi), plane: pick3(r.plane),
      score: m ? m.score : null, distance: m ? m.distance : null,
      feasible: desc.swsLimit == null || r.hifi.sws <= desc.swsLimit,
      note: notes.join('; '),
    });
  }
  // Ascending score, stable; designs without a score (no front) last, in text order.
  rows.sort((a, b) => (a.score ?? Infinity) - (b.score ?? Infinity) || a.n - b.n);
  rows.forEach((row, i) => (row.rank = row.score === null ? null : i + 1));
  problems.sort((a, b) => a.line - b.line);
  return { rows, problems };
}

const pick3 = (c) => ({ bacc: c.bacc, dtl: c.dtl, sws: c.sws });

const el = (tag, text, cls) => {
  const e = document.createElement(tag);
  if (text !== undefined) e.textContent = text;
  if (cls) e.className = cls;
  return e;
};

/** A score as the table shows it: 3 decimals (the ranking's resolution), '–' for none. */
const scoreText = (v) => (v == null || !Number.isFinite(v) ? '–' : v.toFixed(3).replace('-', '−'));

/**
 * The table's columns: heading, unit, the cell's text and its SI value. Three significant
 * digits, so nine columns fit the drawer in type large enough to read across a room.
 */
const COLUMNS = [
  ['Rank', '', (r) => (r.rank == null ? '–' : String(r.rank))],
  ['Student', '', (r) => r.label],
  ['Ks', 'kN/m', (r) => fmt(r.ks / 1000, 3), (r) => r.ks],
  ['Cs', 'kNs/m', (r) => fmt(r.cs / 1000, 3), (r) => r.cs],
  ['BAcc', 'm/s²', (r) => fmt(r.hifi.bacc, 3), (r) => r.hifi.bacc],
  ['DTL', 'N', (r) => fmt(r.hifi.dtl, 3), (r) => r.hifi.dtl],
  ['SWS', 'mm', (r) => fmt(r.hifi.sws * 1000, 3), (r) => r.hifi.sws],
  ['Min-max score', '', (r) => scoreText(r.score), (r) => r.score],
  ['Feasible', '', (r) => (r.feasible ? 'yes' : 'no')],
];

/**
 * Fills `table` with the ranked `rows` (js `evaluateClass`) and, first, the page's own
 * pick as a reference row (`pick`: `{ks, cs, hifi, score, feasible}` or null); `swsLimit`
 * (m, or null) is what "feasible" checks. A row with a note has it in a row of its own
 * beneath. Numeric cells carry SI in `data-value`; the criteria are the HiFi full car's.
 */
function renderClassTable(table, rows, pick, swsLimit) {
  table.replaceChildren();
  table.hidden = rows.length === 0;
  if (!rows.length) return;
  const lim = swsLimit == null ? '' : `SWS ≤ ${fmtInput(swsLimit * 1000, 4)} mm on the HiFi`;
  table.append(el('caption', `Ranked by the min-max score (0 is the ideal point, the front scores 0 to 1); BAcc, DTL and SWS by the HiFi full car${lim ? `; feasible: ${lim}` : ''}.`));
  const head = el('tr');
  for (const [h, unit, , value] of COLUMNS) {
    const th = el('th', unit ? `${h} ` : h, value ? 'num' : '');
    if (unit) th.append(el('span', unit, 'unit'));
    th.scope = 'col';
    head.append(th);
  }
  table.append(el('thead'));
  table.tHead.append(head);
  const body = el('tbody');
  const line = (r, cls) => {
    const tr = el('tr', undefined, cls || undefined);
    if (r.rank != null) tr.dataset.rank = String(r.rank);
    for (const [, , show, value] of COLUMNS) {
      const td = el('td', show(r), value ? 'num' : '');
      if (value && Number.isFinite(value(r))) td.dataset.value = String(value(r));
      tr.append(td);
    }
    body.append(tr);
    if (r.note) {
      const nt = el('tr', undefined, `note-row ${cls || ''}`.trim());
      const td = el('td', `↳ ${r.note}`, 'note');
      td.colSpan = COLUMNS.length;
      nt.append(td);
      body.append(nt);
    }
  };
  if (pick) line({ ...pick, rank: null, label: 'the pick', note: '' }, 'pick-row');
  // Every other design shaded, its note row with it.
  rows.forEach((r, i) => line(r, i % 2 ? 'stripe' : ''));
  table.append(body);
}

/** "Line 3 ‘text’: reason" items of `problems` in list `ul`. */
function renderProblems(ul, problems) {
  ul.replaceChildren(...problems.map((p) => el('li', `Line ${p.line} ‘${p.text}’: ${p.reason}.`)));
  ul.hidden = problems.length === 0;
}

export class ClassFront {
  /**
   * `els`: `{name, make, code, copy, text, file, apply, clear, status, problems, table,
   * drop}`; `store`, `controller` (js/controller.js: its queue, its `render`), `compute`.
   */
  constructor(els, { store, controller, compute }) {
    Object.assign(this, { els, store, ctl: controller, compute });
    /** The text last applied (evaluated again when the scenario changes), or null. */
    this.text = null;
    els.make.addEventListener('click', () => this.showCode());
    els.name.addEventListener('input', () => !els.code.hidden && this.showCode());
    els.copy.addEventListener('click', () => this.copy());
    els.apply.addEventListener('click', () => this.apply(els.text.value));
    els.clear.addEventListener('click', () => this.clear());
    els.file.addEventListener('change', async () => {
      const f = els.file.files && els.file.files[0];
      els.file.value = '';
      if (f) await this.readFile(f);
    });
    els.drop.addEventListener('dragover', (ev) => {
      ev.preventDefault();
      els.drop.classList.add('dropping');
    });
    els.drop.addEventListener('dragleave', () => els.drop.classList.remove('dropping'));
    els.drop.addEventListener('drop', async (ev) => {
      ev.preventDefault();
      els.drop.classList.remove('dropping');
      const f = ev.dataTransfer && ev.dataTransfer.files[0];
      if (f) await this.readFile(f);
    });
  }

  /** The current design's code, shown and ready to copy. */
  showCode() {
    const st = this.store;
    const s = st.state;
    const code = encodeCode({ car: s.car, key: scenarioKey(s), ks: s.ks, cs: s.cs, name: cleanName(this.els.name.value) });
    this.els.code.textContent = code;
    this.els.code.hidden = false;
    this.els.copy.disabled = false;
    this.els.code.title = `Ks ${fmt(s.ks / 1000, 4)} kN/m, Cs ${fmt(s.cs / 1000, 4)} kNs/m on this car and road`;
    return code;
  }

  async copy() {
    const code = this.showCode();
    try {
      await navigator.clipboard.writeText(code);
      this.els.copy.textContent = 'Copied';
    } catch {
      this.els.copy.textContent = 'Select and copy it';
    }
    setTimeout(() => (this.els.copy.textContent = 'Copy'), 2000);
  }

  /** A text file of codes (at most 1 MB) into the text box, then applied. */
  async readFile(f) {
    if (f.size > 1 << 20) {
      this.status(`${f.name} is ${fmt(f.size / 1048576, 3)} MB; a file of codes is a few kB (at most 1 MB read).`, true);
      return;
    }
    let text;
    try {
      text = await f.text();
    } catch (e) {
      this.status(`${f.name} cannot be read: ${e.message || e}`, true);
      return;
    }
    this.els.text.value = text;
    await this.apply(text);
  }

  status(text, bad = false) {
    this.els.status.textContent = text;
    this.els.status.classList.toggle('bad', bad);
  }

  /** Reads and evaluates `text` (in the controller's queue); resolves when shown. Never throws. */
  apply(text) {
    const read = readCodes(text);
    if (!read.codes.length && !read.problems.length) {
      this.clear();
      this.status('No codes to apply: paste the students’ codes, one a line.');
      return Promise.resolve();
    }
    this.text = text;
    this.status(`Evaluating ${read.codes.length} designs…`);
    return this.ctl.enqueue(async () => {
      const st = this.store;
      const s = st.state;
      const out = await evaluateClass(this.compute, s, st.desc, st.front, read);
      // For the scenario it was evaluated on; a newer one evaluates it again (`viewsChanged`).
      st.classFront = { key: scenarioKey(s), ...out };
      this.show();
    }).catch((e) => this.status(`The class front failed: ${e.message || e}`, true));
  }

  /** The table, the named lines and the markers from the store. */
  show() {
    const st = this.store;
    const cf = st.classFront;
    const fr = st.front;
    const ok = fr && !fr.error;
    const pick = ok ? { ks: fr.study.pick.ks, cs: fr.study.pick.cs, hifi: fr.recheck.rechecked, score: minMaxScore(fr, fr.study.pick.criteria)?.score ?? null, feasible: st.desc.swsLimit == null || fr.recheck.rechecked.sws <= st.desc.swsLimit } : null;
    renderClassTable(this.els.table, cf ? cf.rows : [], pick, st.desc.swsLimit);
    renderProblems(this.els.problems, cf ? cf.problems : []);
    if (cf) {
      const left = cf.problems.filter((p) => !p.ranked).length;
      const noFront = ok ? '' : ' No front on this scenario: the designs are shown but not scored.';
      this.status(`${cf.rows.length} designs ranked by min-max score${left ? `; ${left} lines not used, named under the table` : ''}. At most ${MAX_CODES} codes.${noFront}`, left > 0);
    }
    this.ctl.render.markers();
    this.ctl.render.plane();
  }

  /** Takes the class's designs off the table, maps and plane. */
  clear() {
    this.text = null;
    this.store.classFront = null;
    this.status('');
    this.show();
  }

  /** After the views changed: a new scenario evaluates the codes again; the shown code follows the design. */
  viewsChanged() {
    const st = this.store;
    if (!this.els.code.hidden) this.showCode();
    if (st.classFront && this.text !== null && st.classFront.key !== scenarioKey(st.state) && !this.refreshing) {
      this.refreshing = true;
      this.apply(this.text).finally(() => (this.refreshing = false));
    }
  }
}
