// The readout: criteria of the design by both models against the datum, ride
// properties and modes. Every value cell carries its full-precision SI number in
// `data-value` (the tests compare those with the native CLI).

import { fmt, fmtInput, fmtPct, fmtSmall } from './format.js';

const ROWS = [
  { crit: 'bacc', get: (r) => r.bacc, show: (v) => fmt(v, 4) },
  // ISO 2631-1 Wk-weighted (the reports' `bacc_wk`); the surrogate has none.
  { crit: 'wk', get: (r) => r.bacc_wk, show: (v) => fmt(v, 4) },
  { crit: 'dtl', get: (r) => r.dtl, show: (v) => fmt(v, 4) },
  { crit: 'dtlrel', get: (r) => r.dtl_relative, show: (v) => fmt(v * 100, 3) },
  { crit: 'sws', get: (r) => r.sws, show: (v) => fmt(v * 1000, 4) },
];

function cell(table, crit, model) {
  return table.querySelector(`tr[data-crit="${crit}"] td[data-model="${model}"]`);
}

/**
 * Fills one model's columns of the criteria table (`model`: "lofi" or "hifi") from the
 * design's and the datum's reports; `pending` greys them while a newer result is
 * being computed (the values shown are then those of an earlier design).
 */
export function renderCriteria(table, model, design, datum, swsLimit, pending = false) {
  for (const row of ROWS) {
    const c = cell(table, row.crit, model);
    const dc = cell(table, row.crit, `${model}-d`);
    for (const x of [c, dc]) x.classList.toggle('pending', pending || !design);
    if (!design || !datum) {
      c.textContent = '…';
      dc.textContent = '';
      delete c.dataset.value;
      delete dc.dataset.value;
      continue;
    }
    const v = row.get(design);
    const d = row.get(datum);
    if (v === undefined) {
      c.textContent = '—';
      dc.textContent = '';
      delete c.dataset.value;
      delete dc.dataset.value;
      continue;
    }
    c.textContent = row.show(v);
    c.dataset.value = String(v);
    c.classList.toggle('over', row.crit === 'sws' && swsLimit != null && v > swsLimit);
    const frac = v / d - 1;
    // The column heading says "%"; the cell holds the signed number.
    dc.textContent = fmtPct(frac).replace(' %', '');
    dc.dataset.value = String(frac);
    const tiny = Math.abs(frac) < 5e-4;
    dc.classList.toggle('better', !tiny && frac < 0);
    dc.classList.toggle('worse', !tiny && frac > 0);
    dc.title = tiny ? 'same as the datum' : frac < 0 ? 'better than the datum (lower)' : 'worse than the datum (higher)';
  }
  table.querySelector(`thead th[data-model="${model}"]`)?.classList.toggle('pending', pending);
}

/**
 * The readout's line on ISO 2631-1 comfort (`lofi`, `hifi`: the design's reports, `hifi`
 * null while computing): each model's Wk-weighted RMS body acceleration and the
 * standard's Annex C label (the reports' `comfort`).
 */
export function comfortNote(el, lofi, hifi) {
  const part = (name, r) => `${name} ${fmt(r.bacc_wk, 3)} m/s², ${r.comfort}`;
  el.textContent = `ISO 2631-1 Annex C: ${[hifi ? part('HiFi', hifi) : null, part('LoFi', lofi)].filter(Boolean).join('; ')}. The surrogate is unweighted.`;
  el.title = el.textContent;
  el.dataset.label = hifi ? hifi.comfort : lofi.comfort;
  el.dataset.model = hifi ? 'hifi' : 'lofi';
}

/** The design's SWS against the limit, in words (`hifi` may be null while computing). */
export function feasibilityText(lofi, hifi, swsLimit) {
  if (swsLimit == null) return { text: 'No SWS limit set.', ok: true };
  const lim = fmtInput(swsLimit * 1000, 4);
  const okL = lofi.sws <= swsLimit;
  if (!hifi) {
    return {
      text: `SWS ${fmt(lofi.sws * 1000, 3)} mm (LoFi): ${okL ? 'meets' : 'exceeds'} SWS ≤ ${lim} mm; HiFi is being computed.`,
      ok: okL,
    };
  }
  const okH = hifi.sws <= swsLimit;
  const both = `SWS ${fmt(lofi.sws * 1000, 3)} mm (LoFi), ${fmt(hifi.sws * 1000, 3)} mm (HiFi)`;
  if (okL && okH) return { text: `${both}: the design meets SWS ≤ ${lim} mm.`, ok: true };
  if (!okL && !okH) return { text: `${both}: the design exceeds SWS ≤ ${lim} mm (infeasible).`, ok: false };
  return {
    text: `${both}: the models disagree: ${okL ? 'LoFi' : 'HiFi'} meets SWS ≤ ${lim} mm, ${okL ? 'HiFi' : 'LoFi'} does not.`,
    ok: false,
  };
}

/** Notes on the calculation: route, low cut-off, fidelity gap (`h` may be null). */
export function routeNote(l, h) {
  if (!h) return `LoFi computed by the ${l.route} route; the HiFi full car is being computed.`;
  const gap = (k) => fmtPct(h[k] / l[k] - 1);
  const check = h.route === 'spectral'
    ? `no exact route with road warp to check it against (its own error estimate ${fmtSmall(h.spectral_error_estimate)}).`
    : h.route_difference === undefined
      ? 'checking it against the frequency-domain route…'
      : `the frequency-domain route agrees to ${fmtSmall(Math.max(h.route_difference, l.route_difference ?? 0))} (relative).`;
  const parts = [
    `Fidelity gap HiFi vs LoFi: BAcc ${gap('bacc')}, DTL ${gap('dtl')}, SWS ${gap('sws')}.`,
    `Computed by the ${h.route} route; ${check}`,
  ];
  if (h.low_cutoff_hz != null) {
    parts.push(
      `With independent tracks the road warp makes the HiFi variances grow without bound at low frequency: ` +
        `the band starts at ISO 8608's lowest frequency, ${fmt(h.low_cutoff_hz, 3)} Hz.`,
    );
  }
  return parts.join(' ');
}

/** Ride properties of the design (from the LoFi report: they are the front corner's). */
export function renderProps(dl, report) {
  const items = [
    ['Body bounce frequency', `${fmt(report.body_bounce_hz, 3)} Hz`, 'body_bounce_hz', report.body_bounce_hz],
    ['Damping ratio ζ', fmt(report.damping_ratio, 3), 'damping_ratio', report.damping_ratio],
    ['Wheel (ride) rate', `${fmt(report.wheel_rate / 1000, 4)} kN/m`, 'wheel_rate', report.wheel_rate],
    ['Critical damping', `${fmt(report.critical_damping / 1000, 4)} kNs/m`, 'critical_damping', report.critical_damping],
    ['Static wheel load', `${fmt(report.static_wheel_load, 4)} N`, 'static_wheel_load', report.static_wheel_load],
  ];
  dl.replaceChildren(
    ...items.map(([label, text, key, value]) => {
      const div = document.createElement('div');
      const dt = document.createElement('dt');
      dt.textContent = label;
      const dd = document.createElement('dd');
      dd.textContent = text;
      dd.dataset.key = key;
      dd.dataset.value = String(value);
      div.append(dt, dd);
      return div;
    }),
  );
}

/** One modes table body (`pending` greys it while a newer result is computed). */
export function renderModes(table, modes, pending = false) {
  const body = table.tBodies[0];
  table.classList.toggle('pending', pending);
  body.replaceChildren(
    ...modes.map((m) => {
      const tr = document.createElement('tr');
      const name = document.createElement('td');
      name.textContent = modeLabel(m.label);
      const f = document.createElement('td');
      f.className = 'num';
      f.textContent = fmt(m.frequency, 4);
      f.dataset.value = String(m.frequency);
      const z = document.createElement('td');
      z.className = 'num';
      z.textContent = fmt(m.damping_ratio, 3);
      z.dataset.value = String(m.damping_ratio);
      tr.append(name, f, z);
      return tr;
    }),
  );
}

const SYMBOLS = { z: 'z', zs: 'zs', zu: 'zu', theta: 'θ', phi: 'φ' };

/** "body pitch theta" -> "body pitch (θ)"; other labels unchanged. */
function modeLabel(label) {
  const m = /^(.*) (z|zs|zu|theta|phi)$/.exec(label);
  return m ? `${m[1]} (${SYMBOLS[m[2]]})` : label;
}
