// The HiFi's own Pareto front beside the objective plane's (issue #13): the heavy
// worker runs STM on the full car (crate/src/explorer/hifi_front.rs, its starting grid on
// the GPU when there is one) and judges the plane's front on the HiFi against it. Here:
// which answer is current, the plane's line about it, and the Pick tab's table. Handed
// plain data.

import { fmt, fmtPct } from './format.js';

/** The store's HiFi front when it is for the current scenario and has no error, else null. */
export function currentHifiFront(st) {
  const h = st.hifiFront;
  return h && !h.error && h.key === st.tags?.scenario ? h : null;
}

/** Whose front the plane shows (the core's `plane.model`): in a sentence, at its start, in the table. */
const WHOSE = { surrogate: "the surrogate's", lofi: "the LoFi's", robust: "the LoFi's robust" };
const LINE_NAMES = { surrogate: "Surrogate's", lofi: "LoFi's", robust: "LoFi's robust" };
const TABLE_NAMES = { surrogate: 'Surrogate front', lofi: 'LoFi front', robust: 'LoFi robust front' };

function whose(h) {
  return WHOSE[h.plane.model];
}

/** A count with thin-space thousands ("4 620"). */
function count(n) {
  return String(n).replace(/\B(?=(\d{3})+(?!\d))/g, '\u2009');
}

/** The plane's line on the HiFi front `h` (js/compute.js `hifiFront`), after its key ("HiFi front, its pick:"). */
export function hifiFrontLine(h) {
  if (!h) return '';
  if (h.error) return `HiFi front: ${h.error.replace(/^sws_limit: /, 'SWS limit: ')}`;
  const p = h.plane;
  return `${count(h.hifiRuns)} HiFi runs. ${LINE_NAMES[h.plane.model]} front (${count(p.hifiRuns)} runs): ` +
    `${fmt(100 * p.hypervolumeRatio, 4)} % of its hypervolume, pick ${fmtPct(p.pickGapPercent[0] / 100, 2)} BAcc, ${fmtPct(p.pickGapPercent[1] / 100, 2)} DTL.`;
}

/** The line's tooltip: how the figures were made. */
export function hifiFrontTitle(h) {
  const p = h.plane;
  const on = h.plane.model === 'robust' ? "every case's full car, the robust objective" : 'the full car';
  return `STM on ${on}, 61 × 61 grid refined twice (${h.compute === 'gpu' ? 'starting grid on the GPU' : 'CPU'}, ${fmt(h.ms, 3)} ms in the worker). ` +
    `Hypervolumes against the HiFi front's reference point (${fmt(h.front.study.reference_point[0], 4)} m/s², ${fmt(h.front.study.reference_point[1], 4)} N): ` +
    `HiFi front ${fmt(h.front.study.hypervolume, 5)}, ${whose(h)} front ${fmt(p.hypervolume, 5)} as predicted and ${fmt(p.hypervolumeOnHifi, 5)} on the HiFi ` +
    `(${p.hifiFeasiblePoints} of its ${p.frontPoints} designs meet the objectives there), (m/s²)·N.`;
}

/**
 * The Pick tab's table: the plane's front and pick (`fr`, the store's `front`) against the
 * HiFi's (`h`): HiFi runs, points, both hypervolumes, both picks on the HiFi and how far
 * apart they are. Empty without a current answer.
 */
export function renderHifiFront(table, h, fr) {
  if (!h || h.error || !fr || fr.error) {
    table.replaceChildren();
    if (h && h.error) table.innerHTML = `<caption>No HiFi front: ${h.error}</caption>`;
    return;
  }
  const p = h.plane;
  const hp = h.front.study.pick;
  const rc = fr.recheck;
  const on = TABLE_NAMES[p.model];
  const cell = (v, text) => `<td class="num" data-value="${v}">${text}</td>`;
  const row = (name, unit, a, b, extra = '<td></td>') =>
    `<tr><th scope="row">${name}${unit ? ` <span class="unit">${unit}</span>` : ''}</th>${a}${b}${extra}</tr>`;
  const crit = (name, unit, k, scale, i) => row(name, unit,
    cell(rc.rechecked[k], fmt(rc.rechecked[k] * scale, 4)),
    cell(hp.criteria[k], fmt(hp.criteria[k] * scale, 4)),
    `<td class="num delta" data-value="${p.pickGapPercent[i]}">${fmtPct(p.pickGapPercent[i] / 100, 2)}</td>`);
  const pct = (v) => `<td class="num delta" data-value="${v}">${fmtPct(v / 100)}</td>`;
  const change = (name, i) => row(`${name} vs datum`, '%', pct(rc.rechecked_change_percent[i]), pct(hp.change_percent[i]));
  // The pick rows are both picks' HiFi criteria, then their changes against the HiFi datum.
  table.innerHTML = `
    <caption>${on} and its pick against the HiFi's (${h.compute === 'gpu' ? 'starting grid on the GPU' : 'on the CPU'},
      ${fmt(h.ms, 3)} ms in the worker); each pick by the same rule, on the HiFi</caption>
    <thead><tr><th scope="col"></th><th scope="col" class="num">${on.split(' ')[0]}</th><th scope="col" class="num">HiFi</th>
      <th scope="col" class="num" title="Hypervolume: the plane front's share of the HiFi front's on the HiFi; picks: 100 (plane / HiFi - 1)">Diff.</th></tr></thead>
    <tbody>
      ${row('HiFi runs', '', cell(p.hifiRuns, count(p.hifiRuns)), cell(h.hifiRuns, count(h.hifiRuns)))}
      ${row('Front points', '', cell(p.frontPoints, p.frontPoints), cell(h.front.study.front.length, h.front.study.front.length))}
      ${row('feasible on the HiFi', '', cell(p.hifiFeasiblePoints, p.hifiFeasiblePoints), cell(h.front.study.front.length, h.front.study.front.length))}
      ${row('Hypervolume, predicted', '(m/s²)·N', cell(p.hypervolume, fmt(p.hypervolume, 5)), cell(h.front.study.hypervolume, fmt(h.front.study.hypervolume, 5)))}
      ${row('on the HiFi', '(m/s²)·N', cell(p.hypervolumeOnHifi, fmt(p.hypervolumeOnHifi, 5)), cell(h.front.study.hypervolume, fmt(h.front.study.hypervolume, 5)),
        `<td class="num" data-value="${p.hypervolumeRatio}">${fmt(100 * p.hypervolumeRatio, 4)} %</td>`)}
      ${row('Pick Ks', 'kN/m', cell(fr.study.pick.ks, fmt(fr.study.pick.ks / 1000, 4)), cell(hp.ks, fmt(hp.ks / 1000, 4)))}
      ${row('Pick Cs', 'kNs/m', cell(fr.study.pick.cs, fmt(fr.study.pick.cs / 1000, 4)), cell(hp.cs, fmt(hp.cs / 1000, 4)))}
      ${crit(fr.comfort === 'wk' ? 'Pick BAcc (Wk)' : 'Pick BAcc', 'm/s²', 'bacc', 1, 0)}
      ${crit('Pick DTL', 'N', 'dtl', 1, 1)}
      ${crit('Pick SWS', 'mm', 'sws', 1000, 2)}
      ${change('BAcc', 0)}
      ${change('DTL', 1)}
    </tbody>`;
}
