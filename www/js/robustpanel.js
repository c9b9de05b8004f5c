// The robust design's cases editor (issue #16) in the Car & road tab: load cases and
// operating points as tables beside the cases file's JSON text (js/robustcases.js reads
// and writes it), two views of one file: a table edit rewrites the text, "Apply" sends
// the text. Edits not yet applied are marked ("not applied: press Apply"), and each is
// checked as it is typed by the core's own limits (`checkState` on the candidate cases:
// the message names the case and field and states the range), the cell at fault marked.
// Also the maps' case selector (robust, or one case). Built with the panels beyond the
// first screen (js/panels.js).

import { plainWords } from './controls.js';
import { CHECK_AFTER_MS, CLASSES, MAX_CASES, casesText, cellOf, cellValue, compactCases, readCases, ruleText } from './robustcases.js';

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
