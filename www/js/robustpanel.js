// The robust design's cases (issue #16) in the Car & road tab: load cases (extra mass kg at
// x, y, z m from the car's centre of gravity, with a weight) and operating points (road
// class, speed m/s, weight), combined worst case or weighted mean; the state's `cases` is
// the text of a `ridelab map --cases FILE` file, which the core parses and checks (its
// message names the field, `cases.load_cases[1].mass`). The tables and the JSON text are
// two views of one cases file: a table edit rewrites the text, "Apply" sends the text.
// Edits not yet applied are marked ("not applied: press Apply"), and each is checked as
// it is typed by the core's own limits (`checkState` on the candidate cases: the message
// names the case and field and states the range), the cell at fault marked.
// Also the map selector (robust, or one case) and the Pick tab's per-case table, and the
// labels the maps and the plane carry with cases.

import { fmt, fmtPct } from './format.js';
import { plainWords } from './controls.js';

/** The road classes an operating point may take (ISO 8608). */
const CLASSES = ['A', 'B', 'C', 'D', 'E', 'F', 'G', 'H'];
/** Most cases (load cases x operating points), as the core's `robust::MAX_CASES`. */
const MAX_CASES = 16;

/** "worst of 6 cases" / "weighted mean of 6 cases" (`desc`: the core's `describe`). */
function ruleText(desc) {
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
function readCases(text) {
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
function cellValue(raw) {
  const t = raw.trim();
  if (t === '') return undefined;
  const n = Number(t);
  return Number.isFinite(n) ? n : t;
}

/** How long typing rests before the cases are checked, ms. */
const CHECK_AFTER_MS = 150;

/** The table and row key a core field path names (`cases.load_cases[1].mass`), or null. */
function cellOf(message) {
  const m = /cases\.(load_cases|operating)\[(\d+)\]\.(\w+)/.exec(message || '');
  return m ? { table: m[1] === 'load_cases' ? 'load' : 'operating', row: Number(m[2]), key: m[3] } : null;
}

/** The cases file's text (compact JSON) of the tables' `{load, operating, combine}`. */
function casesText({ load, operating, combine }) {
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

/**
 * The editor: `els` = `{load, operating, addLoad, addOp, combine, text, apply, pending,
 * clear, caseSelect, msg, count}`; `apply(text)` sends a cases text (null clears them)
 * and resolves to the core's failure or null; `check(text)` resolves to the core's
 * failure for that cases text on the current state, or null; `pickCase(c)` sets `case`
 * ("robust" or "k").
 */
export class RobustPanel {
  constructor(els, { apply, check, pickCase }) {
    this.els = els;
    this.applyText = apply;
    this.checkText = check;
    this.checkTimer = null;
    /** Checks started (only the latest one's answer is shown). */
    this.checks = 0;
    this.model = { load: [], operating: [], combine: 'worst' };
    this.shownText = undefined;
    els.addLoad.addEventListener('click', () => {
      this.model.load.push({ name: `load ${this.model.load.length + 1}`, mass: 0 });
      this.edited();
    });
    els.addOp.addEventListener('click', () => {
      this.model.operating.push({ class: 'B', speed: 20 });
      this.edited();
    });
    els.combine.addEventListener('change', () => {
      this.model.combine = els.combine.value;
      this.edited(false);
    });
    els.text.addEventListener('input', () => {
      const m = readCases(els.text.value);
      if (m) {
        this.model = m;
        this.drawTables();
      }
      this.count();
      this.changed();
    });
    els.apply.addEventListener('click', () => this.send(els.text.value));
    els.clear.addEventListener('click', () => this.send(null));
    els.caseSelect.addEventListener('change', () => pickCase(els.caseSelect.value));
  }

  /** Sends `text` (null: no cases); the core's message, naming the field, stays under the editor. */
  async send(text) {
    clearTimeout(this.checkTimer);
    this.checks++;
    this.els.msg.textContent = '';
    const failure = await this.applyText(text === null ? null : compactCases(text));
    if (failure) {
      this.els.msg.textContent = `Not applied: ${this.words(failure)}`;
      this.markCell(cellOf(failure.message));
    }
  }

  /** A table edit: the text follows (`redraw`: the tables too, after rows came or went). */
  edited(redraw = true) {
    this.els.text.value = casesText(this.model);
    if (redraw) this.drawTables();
    this.count();
    this.changed();
  }

  /** The editor differs from the state's cases: marked not applied, and checked once typing rests. */
  changed() {
    const text = this.els.text.value.trim();
    const applied = this.shownText ? compactCases(this.shownText) : '';
    const pending = (text === '' ? '' : compactCases(text)) !== applied;
    this.els.pending.hidden = !pending;
    this.els.apply.classList.toggle('primary', pending);
    clearTimeout(this.checkTimer);
    const token = ++this.checks;
    if (!pending || text === '') {
      this.els.msg.textContent = '';
      this.markCell(null);
      return;
    }
    this.checkTimer = setTimeout(async () => {
      const failure = this.typedProblem() || (await this.checkText(compactCases(text)));
      if (token !== this.checks) return;
      this.els.msg.textContent = failure ? `${this.words(failure)}; not applied.` : 'The cases are valid: press Apply to use them.';
      this.markCell(failure ? cellOf(failure.message) || failure.cell : null);
    }, CHECK_AFTER_MS);
  }

  /** The first cell of the tables whose number does not read as one: `{message, cell}`, or null. */
  typedProblem() {
    for (const el of [...this.els.load.querySelectorAll('input'), ...this.els.operating.querySelectorAll('input')]) {
      if (el.dataset.kind === 'num' && typeof cellValue(el.value) === 'string') {
        return { message: `${el.getAttribute('aria-label')}: '${el.value.trim()}' is not a number`, cell: { el } };
      }
    }
    return null;
  }

  /** A core failure in the page's words, the cell's own label before the field's path. */
  words(failure) {
    const c = cellOf(failure.message);
    const el = c && this.cellInput(c);
    const text = plainWords(failure.message);
    return el ? text.replace(/^(cases\.[\w[\].]+): /, (m, p) => `${el.getAttribute('aria-label')} (${p}): `) : text;
  }

  /** The input of table cell `{table, row, key}`, or null. */
  cellInput({ table, row, key }) {
    const tb = this.els[table].tBodies[0];
    return tb.rows[row]?.querySelector(`input[data-key="${key}"]`) || null;
  }

  /** Marks the cell at fault (`{table, row, key}` or `{el}`; null: none). */
  markCell(c) {
    for (const el of this.els.load.querySelectorAll('[aria-invalid]')) el.removeAttribute('aria-invalid');
    for (const el of this.els.operating.querySelectorAll('[aria-invalid]')) el.removeAttribute('aria-invalid');
    const el = c && (c.el || this.cellInput(c));
    if (el) el.setAttribute('aria-invalid', 'true');
  }

  /** The case count the tables make, against the bound. */
  count() {
    const n = Math.max(1, this.model.load.length) * Math.max(1, this.model.operating.length);
    this.els.count.textContent = `${n} case${n === 1 ? '' : 's'} (at most ${MAX_CASES})`;
    this.els.count.classList.toggle('bad', n > MAX_CASES);
  }

  /**
   * Shows the view's cases (`cases`: the state's cases text or null; `mapCase`: the
   * state's `case`, the map shown; `desc`: the core's description, its case names and
   * rule): the tables and text when the cases changed, and the map selector.
   */
  show({ cases, mapCase, desc }) {
    const text = cases || null;
    if (text !== this.shownText) {
      this.shownText = text;
      this.model = (text && readCases(text)) || { load: [], operating: [], combine: 'worst' };
      this.els.text.value = text ? compactCases(text) : '';
      this.drawTables();
      this.count();
      this.els.msg.textContent = '';
      this.changed();
    }
    const sel = this.els.caseSelect;
    const names = (desc && desc.cases) || [];
    const want = ['robust', ...names.map((_, k) => String(k))];
    if (sel.options.length !== want.length || [...sel.options].some((o, i) => o.value !== want[i] || (i > 0 && o.textContent !== `case ${i - 1}: ${names[i - 1]}`))) {
      sel.replaceChildren(...want.map((v, i) => {
        const o = document.createElement('option');
        o.value = v;
        o.textContent = i === 0 ? (names.length ? `Robust (${ruleText(desc)})` : 'Robust (no cases)') : `case ${i - 1}: ${names[i - 1]}`;
        return o;
      }));
    }
    sel.value = mapCase && mapCase !== 'robust' ? mapCase : 'robust';
    sel.disabled = !names.length;
    this.els.clear.disabled = !text;
  }

  /** The two tables from the model, each cell editing the model (and the text). */
  drawTables() {
    const { load, operating, combine } = this.model;
    this.els.combine.value = combine;
    const input = (row, key, type, width, label) => {
      const el = document.createElement('input');
      el.type = 'text';
      el.inputMode = type === 'num' ? 'decimal' : 'text';
      el.size = width;
      el.value = row[key] === undefined ? '' : String(row[key]);
      el.setAttribute('aria-label', label);
      el.dataset.key = key;
      el.dataset.kind = type;
      // Each keystroke: the text follows, and the value is checked once typing rests.
      el.addEventListener('input', () => {
        const v = type === 'num' ? cellValue(el.value) : el.value;
        if (v === undefined) delete row[key];
        else row[key] = v;
        this.edited(false);
      });
      return el;
    };
    const remove = (list, i, what) => {
      const b = document.createElement('button');
      b.type = 'button';
      b.textContent = '×';
      b.className = 'row-remove';
      b.setAttribute('aria-label', `Remove ${what} ${i + 1}`);
      b.addEventListener('click', () => {
        list.splice(i, 1);
        this.edited();
      });
      return b;
    };
    const body = (table, rows) => {
      const tb = table.tBodies[0];
      tb.replaceChildren(...rows.map((cells) => {
        const tr = document.createElement('tr');
        for (const c of cells) {
          const td = document.createElement('td');
          td.append(c);
          tr.append(td);
        }
        return tr;
      }));
    };
    body(this.els.load, load.map((c, i) => [
      input(c, 'name', 'text', 10, `Load case ${i + 1} name`),
      input(c, 'mass', 'num', 4, `Load case ${i + 1} extra mass, kg`),
      input(c, 'x', 'num', 3, `Load case ${i + 1} x ahead of the CG, m`),
      input(c, 'y', 'num', 3, `Load case ${i + 1} y half-spacing, m`),
      input(c, 'z', 'num', 3, `Load case ${i + 1} z above the CG, m`),
      input(c, 'weight', 'num', 2, `Load case ${i + 1} weight`),
      remove(load, i, 'load case'),
    ]));
    body(this.els.operating, operating.map((o, i) => {
      const sel = document.createElement('select');
      sel.setAttribute('aria-label', `Operating point ${i + 1} road class`);
      for (const c of CLASSES) sel.append(new Option(c, c));
      sel.value = CLASSES.includes(o.class) ? o.class : 'B';
      sel.addEventListener('change', () => {
        o.class = sel.value;
        this.edited(false);
      });
      return [sel, input(o, 'speed', 'num', 4, `Operating point ${i + 1} speed, m/s`), input(o, 'weight', 'num', 2, `Operating point ${i + 1} weight`), remove(operating, i, 'operating point')];
    }));
    this.els.load.classList.toggle('empty', !load.length);
    this.els.operating.classList.toggle('empty', !operating.length);
  }
}
