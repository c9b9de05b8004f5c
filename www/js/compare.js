// Saved designs side by side: up to three designs kept from the sliders, each with its
// LoFi and HiFi criteria and their change against the datum, beside the datum itself
// (the Pick tab). Plain data in, a table out; the page keeps the list, the link its Ks, Cs.
// Each entry carries the scenario it was evaluated for: when the car or road changes the
// entries are shown pending ("…", never the old car's numbers) and evaluated again on the
// new scenario (`evaluateKept`), or dropped with the reason said.

import { fmt, fmtPct } from './format.js';
import { explain } from './controls.js';

/** How many designs are kept; keeping a fourth drops the oldest. */
export const MAX_SAVED = 3;

/** The criteria rows: key, label with unit, and the shown number from SI. */
const ROWS = [
  { key: 'bacc', label: 'BAcc m/s²', show: (v) => fmt(v, 4) },
  { key: 'dtl', label: 'DTL N', show: (v) => fmt(v, 4) },
  { key: 'sws', label: 'SWS mm', show: (v) => fmt(v * 1000, 4) },
];

/**
 * `saved` with `entry` (`{ks, cs, lofi, hifi, datum: {lofi, hifi}}`, reports in SI) added
 * at the end: the same design replaces its older copy, and the oldest goes beyond MAX_SAVED.
 */
export function keepDesign(saved, entry) {
  const rest = saved.filter((s) => !(s.ks === entry.ks && s.cs === entry.cs));
  return [...rest, entry].slice(-MAX_SAVED);
}

/** `{bacc, dtl, sws}` of a report (SI), or null. */
const crit = (r) => (r ? { bacc: r.bacc, dtl: r.dtl, sws: r.sws } : null);

/**
 * A kept design's entry from its reports and its datum's (`lofi`, `hifi`: reports with
 * `bacc`, `dtl`, `sws` in SI, or null where not computed; `datum`: `{ks, cs, lofi, hifi}`),
 * evaluated for the scenario `key` (its scenario tag, js/store.js `tags`).
 */
export function savedEntry(ks, cs, lofi, hifi, datum, key) {
  return {
    ks,
    cs,
    key,
    lofi: crit(lofi),
    hifi: crit(hifi),
    datum: { design: { ks: datum.ks, cs: datum.cs }, lofi: crit(datum.lofi), hifi: crit(datum.hifi) },
  };
}

/** The entry while it is evaluated again on a new scenario: its Ks and Cs, no numbers. */
export function pendingEntry(e) {
  return { ks: e.ks, cs: e.cs, key: null, lofi: null, hifi: null, datum: { design: null, lofi: null, hifi: null } };
}

/** "Ks 20 kN/m, Cs 1.5 kNs/m" of a kept design. */
const designWords = (ks, cs) => `Ks ${fmt(ks / 1000, 4)} kN/m, Cs ${fmt(cs / 1000, 4)} kNs/m`;

/**
 * The designs `pairs` (`[[ks N/m, cs N s/m], ...]`) evaluated on state `s`'s scenario
 * (`desc`: its `describe`; `compute`: js/compute.js, LoFi and HiFi reports and the
 * datum's; `key`: the scenario's tag): `{entries, failed}`, `failed` naming each design
 * that cannot be evaluated there, with the reason.
 */
export async function evaluateKept(compute, s, desc, pairs, key) {
  const evaluate = (ks, cs) => compute.design({ ...s, ks, cs }, desc, true).catch((e) => ({ error: e }));
  const datum = await evaluate(desc.datumKs, desc.datumCs);
  const entries = [];
  const failed = [];
  for (const [ks, cs] of pairs) {
    const r = datum.error ? datum : await evaluate(ks, cs);
    if (r.error || !r.hifi) failed.push(`${designWords(ks, cs)} (${r.error ? explain(r.error, 'ks') : 'the HiFi model has no answer there'})`);
    else entries.push(savedEntry(ks, cs, r.lofi, r.hifi, { ks: desc.datumKs, cs: desc.datumCs, lofi: datum.lofi, hifi: datum.hifi }, key));
  }
  return { entries, failed };
}

const el = (tag, text, cls) => {
  const e = document.createElement(tag);
  if (text !== undefined) e.textContent = text;
  if (cls) e.className = cls;
  return e;
};

/**
 * Fills `table` with the datum (of the last design kept) and the `saved` designs as
 * columns: Ks, Cs, then each criterion by the LoFi and the HiFi with % against the
 * design's own datum (`data-value` holds SI).
 * `onSet(i)` and `onRemove(i)` are called from each column's buttons.
 */
export function renderCompare(table, saved, { onSet, onRemove }) {
  table.replaceChildren();
  if (!saved.length) {
    table.hidden = true;
    return;
  }
  table.hidden = false;
  const head = el('tr');
  head.append(el('th', ''), el('th', 'Datum'));
  saved.forEach((s, i) => {
    const th = el('th', `Design ${i + 1} `);
    th.dataset.saved = String(i);
    const set = el('button', 'Set', 'small');
    set.type = 'button';
    set.title = `Set the sliders to design ${i + 1}`;
    set.addEventListener('click', () => onSet(i));
    const rm = el('button', '×', 'small');
    rm.type = 'button';
    rm.title = `Remove design ${i + 1}`;
    rm.setAttribute('aria-label', `Remove design ${i + 1}`);
    rm.addEventListener('click', () => onRemove(i));
    th.append(set, rm);
    head.append(th);
  });
  table.append(el('thead'));
  table.tHead.append(head);
  const body = el('tbody');
  const datum = saved[saved.length - 1].datum;
  const design = (label, get) => {
    const tr = el('tr');
    tr.append(el('th', label));
    tr.lastChild.scope = 'row';
    tr.append(el('td', get(datum.design), 'num'));
    for (const s of saved) tr.append(el('td', get(s), 'num'));
    body.append(tr);
  };
  design('Ks kN/m', (d) => (d ? fmt(d.ks / 1000, 4) : '…'));
  design('Cs kNs/m', (d) => (d ? fmt(d.cs / 1000, 4) : '…'));
  for (const model of ['lofi', 'hifi']) {
    for (const row of ROWS) {
      const tr = el('tr');
      tr.dataset.crit = row.key;
      tr.dataset.model = model;
      tr.append(el('th', `${row.label} (${model === 'lofi' ? 'LoFi' : 'HiFi'})`));
      tr.lastChild.scope = 'row';
      const d = datum[model]?.[row.key];
      const c = el('td', d == null ? '…' : row.show(d), 'num');
      if (d != null) c.dataset.value = String(d);
      tr.append(c);
      for (const s of saved) {
        const v = s[model]?.[row.key];
        const own = s.datum[model]?.[row.key];
        const td = el('td', v == null ? '…' : row.show(v), 'num');
        if (v != null) {
          td.dataset.value = String(v);
          if (own != null) {
            // Against the datum of the design's own scenario.
            const frac = v / own - 1;
            const pct = el('span', ` ${fmtPct(frac)}`, frac < -5e-4 ? 'better' : frac > 5e-4 ? 'worse' : '');
            td.append(pct);
          }
        }
        tr.append(td);
      }
      body.append(tr);
    }
  }
  table.append(body);
}
