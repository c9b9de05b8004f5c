// The page's line charts as chart specs (the wasm core's `LineChart`, camelCase keys):
// the objective plane, the FRF and PSD plots, the time response and the damper's
// force-velocity line. The same spec is drawn on screen (js/plot.js, `drawLineChart`,
// plotters on the canvas) and exported (js/svgexport.js, `lineChartSvg`, plotters' SVG
// backend), so an export is the chart on screen with a title. Each builder takes plain
// data (the results the page holds) and throws `{message, field}` when there is nothing
// to draw.

import { extent } from './planezoom.js';

/** The chart colours, #rrggbb. */
const COL = {
  cloud: '#78a0d2',
  stm: '#c2410c',
  nsga: '#15803d',
  lofi: '#1d4ed8',
  hifi: '#b91c1c',
  pick: '#facc15',
  linear: '#6b7280',
  adaptive: '#7c3aed',
  hifiFront: '#1f2937',
  adaptiveWas: '#c4b5fd',
};

/** Opacity of the cloud of feasible designs. */
export const CLOUD_OPACITY = 0.35;

/** The outputs of the spectra and time panels: key, name, FRF and PSD axis labels, time unit. */
// The FRF is per metre of road displacement (the charts' key and titles say so); the
// axis labels stay short enough to fit beside the smallest chart's plot.
export const OUTPUTS = [
  { key: 'bacc', name: 'BAcc', frf: '|H| BAcc [1/s²]', psd: 'PSD BAcc [(m/s²)²/Hz]', time: 'BAcc [m/s²]', scale: 1 },
  { key: 'dtl', name: 'DTL', frf: '|H| DTL [N/m]', psd: 'PSD DTL [N²/Hz]', time: 'DTL [N]', scale: 1 },
  { key: 'sws', name: 'SWS', frf: '|H| SWS [m/m]', psd: 'PSD SWS [m²/Hz]', time: 'SWS [mm]', scale: 1000 },
];

/** The output `key` ('bacc', 'dtl' or 'sws'); throws `{message, field: 'key'}` for another. */
export function output(key) {
  const o = OUTPUTS.find((x) => x.key === key);
  if (!o) throw { message: `no output '${key}' (bacc, dtl or sws)`, field: 'key' };
  return o;
}

const line = (name, colour, points, size) => ({ name, colour, points, style: 'line', size });
const marker = (name, colour, stroke, shape, points, size = 6) => ({ name, colour, stroke, points, style: { markers: shape }, size });


/** A linear range widened by 4 % each side (or by 5 % of the value when it is a point). */
function widen([lo, hi]) {
  if (!(hi > lo)) {
    const d = Math.abs(lo) * 0.05 || 1;
    return [lo - d, hi + d];
  }
  const d = (hi - lo) * 0.04;
  return [lo - d, hi + d];
}

/** "Ks 19.96 kN/m, Cs 1.290 kNs/m" of a state. */
export function designText(state) {
  return `Ks ${(state.ks / 1000).toFixed(2)} kN/m, Cs ${(state.cs / 1000).toFixed(3)} kNs/m`;
}

/** Objective-plane coordinates of `front` (a `front` study result): absolute, or over the datum's (`ratio`). */
export function planeXY(front, ratio) {
  const d = front.datum;
  return ratio ? (bacc, dtl) => [bacc / d.bacc, dtl / d.dtl] : (bacc, dtl) => [bacc, dtl];
}

/**
 * The feasible cells of the surrogate's cloud map (every `step`-th cell each way) as
 * `[x, y]` points of the plane.
 */
export function cloudPoints(cloud, front, ratio, step) {
  const xy = planeXY(front, ratio);
  const n = cloud.nx * cloud.ny;
  const out = [];
  for (let j = 0; j < cloud.ny; j += step) {
    for (let i = 0; i < cloud.nx; i += step) {
      const k = j * cloud.nx + i;
      if (cloud.feasible[k]) out.push(xy(cloud.values[k], cloud.values[n + k]));
    }
  }
  return out;
}

/**
 * What the objective plane draws of the adaptive loop `a` (js/store.js `adaptive`, or
 * null): `{front, pick, was}` (its surrogate's front, its latest pick, the front and pick
 * before its latest run or null), or null when no loop runs.
 */
export function adaptivePlane(a) {
  return a && a.report.history.length ? { front: a.front, pick: a.report.history[a.report.history.length - 1].pick, was: a.was } : null;
}

/**
 * The objective plane (BAcc against DTL, on the surrogate; with Wk comfort, `front.comfort`
 * "wk", the Wk-weighted BAcc on the LoFi) of `{front, nsga, cloud,
 * design, adaptive}` (`design`: the surrogate's criteria of the current design, or null;
 * `adaptive`: the adaptive loop's `{front, pick, was}` when one runs, `was` the front and
 * pick before its latest run or null): the feasible designs, the STM Pareto front, the
 * NSGA-II front when computed, the adaptive loop's front and pick (the earlier ones light),
 * the min-max pick and its HiFi re-check, the datum and the current design; on the
 * datum-ratio axes when `ratio`. On screen (`live`) there is no legend (the page's key
 * above the chart says it, and nothing in the plot hides under it), the cloud is drawn by the page
 * (thousands of dots) and the design on a layer of its own (it moves with the sliders).
 * An export has every other cloud cell each way, the legend and a `title`.
 */
export function objectiveSpec({ front: fr, nsga, cloud, design, adaptive = null, hifi = null }, { ratio = false, width = 720, height = 460, title = '', live = false } = {}) {
  if (!fr || fr.error) throw { message: `no front to draw${fr ? `: ${fr.error}` : ''}`, field: 'front' };
  const xy = planeXY(fr, ratio);
  const cloudPts = live || !cloud ? [] : cloudPoints(cloud, fr, ratio, 2);
  const frontPts = fr.study.front.map((p) => xy(p.bacc, p.dtl));
  const datum = xy(fr.datum.bacc, fr.datum.dtl);
  // The HiFi's own front (issue #13), each point by the HiFi (ratios to the HiFi datum).
  const hf = hifi && hifi.front && !hifi.error ? hifi.front : null;
  const hxy = hf ? planeXY(hf, ratio) : null;
  const hfPts = hf ? hf.study.front.map((p) => hxy(p.bacc, p.dtl)) : [];
  // The range: the fronts and the datum, room to the upper right for the cloud.
  const [x0, x1] = extent([...frontPts.map((p) => p[0]), ...hfPts.map((p) => p[0]), datum[0]]);
  const [y0, y1] = extent([...frontPts.map((p) => p[1]), ...hfPts.map((p) => p[1]), datum[1]]);
  const xRange = widen([x0 - 0.05 * (x1 - x0), x1 + 0.6 * (x1 - x0)]);
  const yRange = widen([y0 - 0.05 * (y1 - y0), y1 + 0.6 * (y1 - y0)]);
  const series = [];
  if (cloudPts.length) {
    series.push({ name: 'feasible designs (surrogate)', colour: COL.cloud, points: cloudPts, style: 'dots', size: 1.4, opacity: CLOUD_OPACITY });
  }
  // The HiFi's own front wide and dark underneath: where the plane's front is on it, it
  // shows as a dark edge around the plane's line.
  const on = hifi && hifi.plane && hifi.plane.model === 'robust' ? "HiFi robust front, STM on every case's full car" : 'HiFi front, STM on the full car';
  if (hf) series.push(line(`${on} (${hf.study.front.length} pts, ${hifi.hifiRuns} HiFi runs)`, COL.hifiFront, hfPts, 5));
  series.push(line(`Pareto front, STM (${frontPts.length} pts)`, COL.stm, frontPts, 2.5));
  if (nsga && !nsga.error) {
    const nf = nsga.study.front.map((p) => xy(p.bacc, p.dtl));
    series.push({ name: `NSGA-II front (${nf.length} pts)`, colour: COL.nsga, points: nf, style: 'dots', size: 2.6 });
  }
  const was = adaptive && adaptive.was;
  if (was) series.push(line('adaptive loop\'s front before its latest run', COL.adaptiveWas, was.front.map((p) => xy(p.bacc, p.dtl)), 2));
  if (adaptive) {
    const af = adaptive.front.map((p) => xy(p.bacc, p.dtl));
    series.push(line(`adaptive loop's front (${af.length} pts)`, COL.adaptive, af, 2));
  }
  const pk = xy(fr.study.pick.criteria.bacc, fr.study.pick.criteria.dtl);
  const rc = fr.recheck.rechecked;
  const dh = fr.datumHifi;
  const hp = ratio ? [rc.bacc / dh.bacc, rc.dtl / dh.dtl] : [rc.bacc, rc.dtl];
  // The HiFi's own pick, a large cross under the plane's pick and its re-check: where
  // they coincide its arms stick out around them.
  if (hf) {
    const r = hf.study.pick.rule === 'minmax' ? 'min-max' : hf.study.pick.rule;
    series.push(marker(`HiFi ${r} pick`, COL.hifiFront, COL.hifiFront, 'cross', [hxy(hf.study.pick.criteria.bacc, hf.study.pick.criteria.dtl)], 11));
  }
  // The re-check larger and underneath: a close one rings the pick.
  series.push(marker('pick re-checked (HiFi)', '#ffffff', COL.hifi, 'diamond', [hp], 9));
  const rule = fr.study.pick.rule === 'minmax' ? 'min-max' : fr.study.pick.rule;
  const w = fr.study.pick.pseudo_weights;
  series.push(marker(`${rule} pick (${fr.study.evaluator}; pseudo-weights ${w[0].toFixed(2)} / ${w[1].toFixed(2)})`, COL.pick, '#000000', 'diamond', [pk]));
  series.push(marker('datum', '#ffffff', '#000000', 'square', [datum], 6));
  // The adaptive loop's picks over the min-max pick, so they show where they move.
  if (was) series.push(marker('adaptive loop\'s pick before its latest run', COL.adaptiveWas, '#ffffff', 'triangle', [xy(was.pick.criteria.bacc, was.pick.criteria.dtl)], 6));
  if (adaptive) series.push(marker('adaptive loop\'s pick', COL.adaptive, '#ffffff', 'triangle', [xy(adaptive.pick.criteria.bacc, adaptive.pick.criteria.dtl)], 7));
  if (!live && design) series.push(marker('current design', '#000000', '#ffffff', 'circle', [xy(design.bacc, design.dtl)], 4.5));
  return {
    title,
    xLabel: fr.comfort === 'wk'
      ? (ratio ? 'Wk-weighted BAcc / datum (LoFi) [–]' : 'Wk-weighted RMS body acceleration [m/s²]')
      : (ratio ? 'BAcc / datum BAcc (surrogate) [–]' : 'BAcc [m/s²]'),
    yLabel: ratio ? 'DTL / datum DTL [–]' : 'DTL [N]',
    xRange,
    yRange,
    width,
    height,
    legend: live ? 'none' : 'upperRight',
    series,
  };
}

/**
 * One FRF (`which` = 'frf') or PSD ('psd') plot of `sp` (the `spectra` result), log-log
 * over 0.1..100 Hz: HiFi, LoFi and the surrogate's tuned LoFi for output `key`. The page
 * draws six of them small under one key of its own (`legend: 'none'`).
 */
export function spectraSpec(sp, which = 'frf', key = 'bacc', { width = 640, height = 440, title = '', legend = 'lowerLeft' } = {}) {
  if (!sp) throw { message: 'no spectra to draw yet', field: 'spectra' };
  if (which !== 'frf' && which !== 'psd') throw { message: `'${which}' is not 'frf' or 'psd'`, field: 'which' };
  const o = output(key);
  const k = OUTPUTS.indexOf(o);
  // Log axes: only positive values can be drawn.
  const pts = (vs) => sp.f.map((f, i) => [f, vs[i]]).filter(([f, v]) => f > 0 && v > 0 && Number.isFinite(v));
  const a = pts(sp.lofi[which][k]);
  const b = pts(sp.hifi[which][k]);
  const c = pts(sp.surrogate[which][k]);
  // The y range: whole decades, at most 8 of them below the peak.
  const [low, top] = extent([...a, ...b, ...c].map((p) => p[1]));
  const hi = 10 ** Math.ceil(Math.log10(top));
  const lo = 10 ** Math.floor(Math.log10(Math.max(low, top * 1e-8)));
  return {
    title,
    xLabel: 'frequency [Hz]',
    yLabel: o[which],
    xLog: true,
    yLog: true,
    xRange: [0.1, 100],
    yRange: [lo, hi],
    width,
    height,
    legend,
    // HiFi wide underneath, LoFi narrow on top: both stay visible where they agree.
    series: [
      line('HiFi (full car)', COL.hifi, b, 5),
      line(`tuned LoFi (${sp.surrogateRoute})`, COL.nsga, c, 3),
      line('LoFi (quarter car)', COL.lofi, a, 2),
    ],
  };
}

/**
 * One output (`key`) of a time response `time` (the panel's run): HiFi and LoFi with
 * their RMS; with `linear` (the same road with the linear damper, when the run had a
 * nonlinear one), its HiFi trace underneath in grey.
 */
export function timeSpec(time, key = 'bacc', { width = 720, height = 340, title = '', linear = null } = {}) {
  if (!time) throw { message: 'no time response yet: run it first', field: 'time' };
  const o = output(key);
  const k = OUTPUTS.indexOf(o);
  const pts = (r) => r.t.map((t, i) => [t, r.outputs[k][i] * o.scale]);
  const rms = (r) => (r.rms[k] * o.scale).toPrecision(3);
  const a = pts(time.hifi);
  const b = pts(time.lofi);
  const c = linear ? pts(linear.hifi) : [];
  // Room above the signals for the legend (a third of their span), none taken below.
  const [lo, hi] = extent([...a, ...b, ...c].map((p) => p[1]));
  const span = hi > lo ? hi - lo : Math.abs(hi) || 1;
  const series = [];
  if (linear) series.push(line(`HiFi, linear damper (RMS ${rms(linear.hifi)})`, COL.linear, c, 3.5));
  series.push(line(`HiFi (RMS ${rms(time.hifi)})`, COL.hifi, a, 2.6));
  series.push(line(`LoFi (RMS ${rms(time.lofi)})`, COL.lofi, b, 1));
  return {
    title,
    xLabel: 'time [s]',
    yLabel: o.time,
    xRange: [time.hifi.t[0], time.hifi.t[time.hifi.t.length - 1]],
    yRange: [lo - 0.04 * span, hi + 0.34 * span],
    width,
    height,
    series,
  };
}

/**
 * The front damper's force-velocity line (`curve`: the core's `damperCurve`, v in m/s,
 * f in N; v > 0 is rebound) in kN, with the equivalent linear rate the maps use as a
 * grey line underneath; `linear`: the law is the design's own linear damper.
 */
export function damperSpec(curve, { width = 360, height = 240, title = '', linear = false } = {}) {
  if (!curve || !curve.points.length) throw { message: 'no damper law', field: 'damper' };
  const pts = curve.points.map(([v, f]) => [v, f / 1000]);
  const [v0, v1] = [pts[0][0], pts[pts.length - 1][0]];
  const rate = curve.linearRate / 1000;
  const [lo, hi] = extent(pts.map((p) => p[1]).concat([rate * v0, rate * v1]));
  const span = hi - lo || 1;
  const series = [];
  const kns = (x) => (x / 1000).toPrecision(3);
  if (!linear) series.push(line(`linear rate of the maps, Cs ${kns(curve.linearRate)} kNs/m`, COL.linear, [[v0, rate * v0], [v1, rate * v1]], 2));
  series.push(line(linear ? `linear damper, Cs ${kns(curve.linearRate)} kNs/m` : 'bump / rebound law', COL.hifi, pts, 3));
  return {
    title,
    xLabel: 'damper speed [m/s] (bump < 0 < rebound)',
    yLabel: 'force [kN]',
    xRange: [v0, v1],
    yRange: [lo - 0.04 * span, hi + 0.3 * span],
    width,
    height,
    legend: 'upperLeft',
    series,
  };
}

/**
 * The adaptive loop's history (`a`: js/store.js `adaptive`) against the number of HiFi
 * runs: the front's hypervolume on the surrogate as a change against the plan's front,
 * and the pick's HiFi re-check error (largest of BAcc, DTL, SWS), both in %. The page
 * draws its key above the chart (`legend: 'none'`).
 */
export function adaptiveSpec(a, { width = 420, height = 220, title = '', legend = 'none' } = {}) {
  if (!a || !a.report.history.length) throw { message: 'no adaptive run yet', field: 'adaptive' };
  const h = a.report.history;
  const hv0 = h[0].hypervolume;
  const gain = h.map((x) => [x.hifi_runs, 100 * (x.hypervolume / hv0 - 1)]);
  const err = h.map((x, i) => [x.hifi_runs, a.errors[i]]);
  const n0 = h[0].hifi_runs;
  const n1 = Math.max(h[h.length - 1].hifi_runs, n0 + 1);
  const [lo, hi] = extent([0, ...gain.map((p) => p[1]), ...err.map((p) => p[1])]);
  const span = hi - lo || 1;
  return {
    title,
    xLabel: 'HiFi runs [–]',
    yLabel: 'change, error [%]',
    xRange: [n0 - 0.3, n1 + 0.3],
    yRange: [lo - 0.08 * span, hi + 0.12 * span],
    width,
    height,
    legend,
    series: [
      line('front hypervolume vs the plan\'s [%]', COL.stm, gain, 2.5),
      marker('front hypervolume vs the plan\'s [%]', COL.stm, COL.stm, 'circle', gain, 3.5),
      line('pick\'s HiFi re-check error [%]', COL.hifi, err, 2.5),
      marker('pick\'s HiFi re-check error [%]', '#ffffff', COL.hifi, 'square', err, 3.5),
    ],
  };
}

/** ISO 8608's reference spatial frequency n0, cycle/m, and its classification band. */
const ISO_N0 = 0.1;
const ISO_BAND = [0.011, 2.83];
/** ISO 8608's class boundaries Gd(n0), m³: the geometric means of the class centres 16e-6 4^k (A|B .. G|H). */
const ISO_BOUNDARIES = [1, 2, 3, 4, 5, 6, 7].map((k) => 16e-6 * 2 * 4 ** (k - 1));

/**
 * A measured road's displacement PSD (`d`: the core's `describeRoad`, as `ridelab road
 * FILE --json`), log-log over spatial frequency: every Welch bin faint and the 1/12-octave
 * band means over the band the profile resolves, the ISO 8608 fit over its band and the
 * class boundaries (waviness 2, clipped to the chart) in grey.
 */
export function roadPsdSpec(d, { width = 640, height = 400, title = '' } = {}) {
  if (!d) throw { message: 'no road profile yet: drop a CSV file', field: 'road' };
  // Only what the profile resolves (below it the detrend's and the window's leakage).
  const [rl, rh] = d.resolved_band;
  const pos = (ns, gs) => ns.map((n, i) => [n, gs[i]]).filter(([n, g]) => n >= rl && n <= rh && g > 0 && Number.isFinite(g));
  const bins = pos(d.psd.n, d.psd.gd);
  const bands = pos(d.psd_bands.n, d.psd_bands.gd);
  const f = d.iso8608;
  const fitAt = (n) => f.gd_n0 * (n / ISO_N0) ** -f.waviness;
  const [xl, xh] = extent(bands.map((p) => p[0]));
  const xRange = [10 ** Math.floor(Math.log10(Math.min(xl, ISO_BAND[0]))), 10 ** Math.ceil(Math.log10(Math.max(xh, ISO_BAND[1])))];
  const [yl, yh] = extent(bands.map((p) => p[1]));
  const yRange = [10 ** Math.floor(Math.log10(yl) - 0.5), 10 ** Math.ceil(Math.log10(yh) + 0.5)];
  // A boundary Gd = b (n / n0)^-2 is straight on log-log: its ends clipped to the chart.
  const boundary = (b, k) => {
    const lo = Math.max(xRange[0], ISO_N0 * Math.sqrt(b / yRange[1]));
    const hi = Math.min(xRange[1], ISO_N0 * Math.sqrt(b / yRange[0]));
    if (!(hi > lo)) return null;
    return line(k === 0 ? 'ISO 8608 class boundaries (A|B lowest)' : '', COL.linear, [[lo, b * (lo / ISO_N0) ** -2], [hi, b * (hi / ISO_N0) ** -2]], 1);
  };
  return {
    title,
    xLabel: 'spatial frequency n [cycle/m]',
    yLabel: 'displacement PSD Gd [m³]',
    xLog: true,
    yLog: true,
    xRange,
    yRange,
    width,
    height,
    // The PSD falls with n: the lower left is free for the key.
    legend: 'lowerLeft',
    series: [
      ...ISO_BOUNDARIES.map(boundary).filter(Boolean),
      { ...line('Welch bins', COL.cloud, bins, 1), opacity: 0.5 },
      line('1/12-octave band means', COL.lofi, bands, 2.5),
      line(`ISO fit: class ${f.class}, w = ${f.waviness.toFixed(2)}`, COL.stm, [f.band[0], f.band[1]].map((n) => [n, fitAt(n)]), 2.5),
    ],
  };
}

/**
 * The Pareto front on a measured road (`f`: the core's `roadFront`, as `ridelab optimize
 * --road FILE --json`) in the comfort-DTL plane, absolute: the front of `model` ('lofi' or
 * 'hifi'), its pick and the pick re-checked on the full car, the datum on the full car and
 * the current `design` (`{bacc, dtl}` on `model`, or null) on that road; `wk` when the
 * comfort axis is the Wk-weighted BAcc.
 */
export function roadFrontSpec(f, { design = null, wk = false, model = 'hifi', width = 640, height = 400, title = '' } = {}) {
  if (!f || !f.front.length) throw { message: 'no front on this road', field: 'road' };
  const pts = f.front.map((p) => [p.bacc, p.dtl]);
  const datum = [f.datum.bacc, f.datum.dtl];
  const others = [datum, ...(design ? [[design.bacc, design.dtl]] : [])];
  const [x0, x1] = extent([...pts, ...others].map((p) => p[0]));
  const [y0, y1] = extent([...pts, ...others].map((p) => p[1]));
  const pk = f.pick.criteria;
  const rc = f.hifi_recheck.rechecked;
  const rule = f.pick.rule === 'minmax' ? 'min-max' : f.pick.rule;
  const who = model === 'hifi' ? 'HiFi' : 'LoFi';
  const series = [
    line(`front, STM on the ${who} (${pts.length} pts)`, COL.stm, pts, 2.5),
    // On the HiFi the re-check is the pick itself.
    ...(model === 'hifi' ? [] : [marker('pick re-checked (HiFi)', '#ffffff', COL.hifi, 'diamond', [[rc.bacc, rc.dtl]], 9)]),
    marker(`${rule} pick`, COL.pick, '#000000', 'diamond', [[pk.bacc, pk.dtl]]),
    marker('datum (HiFi)', '#ffffff', '#000000', 'square', [datum], 6),
  ];
  if (design) series.push(marker(`current design (${who})`, '#000000', '#ffffff', 'circle', [[design.bacc, design.dtl]], 4.5));
  return {
    title,
    xLabel: wk ? 'Wk-weighted RMS body acceleration [m/s²]' : 'BAcc [m/s²]',
    yLabel: 'DTL [N]',
    // The front falls to the right: room below it on the left for the key.
    xRange: widen([x0, x1]),
    yRange: widen([y0 - 1.2 * (y1 - y0), y1]),
    width,
    height,
    legend: 'lowerLeft',
    series,
  };
}
