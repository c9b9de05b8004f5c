// The page's line charts as chart specs (the wasm core's `LineChart`, camelCase keys):
// the objective plane, the FRF and PSD plots and the time response. The same spec is
// drawn on screen (js/plot.js, `drawLineChart`, plotters on the canvas) and exported
// (js/svgexport.js, `lineChartSvg`, plotters' SVG backend), so an export is the chart
// on screen with a title. Each builder reads `app` (js/app.js) and throws
// `{message, field}` when there is nothing to draw.

/** The chart colours, #rrggbb. */
const COL = {
  cloud: '#78a0d2',
  stm: '#c2410c',
  nsga: '#15803d',
  lofi: '#1d4ed8',
  hifi: '#b91c1c',
  pick: '#facc15',
};

/** Opacity of the cloud of feasible designs. */
export const CLOUD_OPACITY = 0.35;

/** The outputs of the spectra and time panels: key, name, FRF and PSD axis labels, time unit. */
export const OUTPUTS = [
  { key: 'bacc', name: 'BAcc', frf: '|H| BAcc / road displacement [1/s²]', psd: 'PSD BAcc [(m/s²)²/Hz]', time: 'BAcc [m/s²]', scale: 1 },
  { key: 'dtl', name: 'DTL', frf: '|H| DTL / road displacement [N/m]', psd: 'PSD DTL [N²/Hz]', time: 'DTL [N]', scale: 1 },
  { key: 'sws', name: 'SWS', frf: '|H| SWS / road displacement [m/m]', psd: 'PSD SWS [m²/Hz]', time: 'SWS [mm]', scale: 1000 },
];

/** The output `key` ('bacc', 'dtl' or 'sws'); throws `{message, field: 'key'}` for another. */
export function output(key) {
  const o = OUTPUTS.find((x) => x.key === key);
  if (!o) throw { message: `no output '${key}' (bacc, dtl or sws)`, field: 'key' };
  return o;
}

const line = (name, colour, points, size) => ({ name, colour, points, style: 'line', size });
const marker = (name, colour, stroke, shape, points, size = 6) => ({ name, colour, stroke, points, style: { markers: shape }, size });

/** `[lo, hi]` of finite `vs`. */
function extent(vs) {
  let lo = Infinity;
  let hi = -Infinity;
  for (const v of vs) {
    if (!Number.isFinite(v)) continue;
    if (v < lo) lo = v;
    if (v > hi) hi = v;
  }
  return [lo, hi];
}

/** A linear range widened by 4 % each side (or by 5 % of the value when it is a point). */
function widen([lo, hi]) {
  if (!(hi > lo)) {
    const d = Math.abs(lo) * 0.05 || 1;
    return [lo - d, hi + d];
  }
  const d = (hi - lo) * 0.04;
  return [lo - d, hi + d];
}

export function designText(app) {
  return `Ks ${(app.state.ks / 1000).toFixed(2)} kN/m, Cs ${(app.state.cs / 1000).toFixed(3)} kNs/m`;
}

/** Objective-plane coordinates: absolute, or divided by the datum's (`ratio`). */
export function planeXY(app, ratio) {
  const d = app.front.datum;
  return ratio ? (bacc, dtl) => [bacc / d.bacc, dtl / d.dtl] : (bacc, dtl) => [bacc, dtl];
}

/**
 * The feasible cells of the surrogate's cloud map (every `step`-th cell each way) as
 * `[x, y]` points of the plane.
 */
export function cloudPoints(app, ratio, step) {
  const xy = planeXY(app, ratio);
  const m = app.cloud;
  const n = m.nx * m.ny;
  const out = [];
  for (let j = 0; j < m.ny; j += step) {
    for (let i = 0; i < m.nx; i += step) {
      const k = j * m.nx + i;
      if (m.feasible[k]) out.push(xy(m.values[k], m.values[n + k]));
    }
  }
  return out;
}

/**
 * The objective plane (BAcc against DTL, on the surrogate): its feasible designs, the STM
 * Pareto front, the NSGA-II front when computed, the min-max pick and its HiFi re-check,
 * the datum and the current design; on the datum-ratio axes when `ratio`. On screen
 * (`live`) the cloud and the current design are legend entries only: the page draws the
 * cloud itself (thousands of dots) and the design on a layer of its own (it moves with
 * the sliders). An export has every other cloud cell each way and a `title`.
 */
export function objectiveSpec(app, { ratio = false, width = 720, height = 460, title = '', live = false } = {}) {
  const fr = app.front;
  if (!fr || fr.error) throw { message: `no front to draw${fr ? `: ${fr.error}` : ''}`, field: 'front' };
  const xy = planeXY(app, ratio);
  const cloud = live ? [] : cloudPoints(app, ratio, 2);
  const front = fr.study.front.map((p) => xy(p.bacc, p.dtl));
  const datum = xy(fr.datum.bacc, fr.datum.dtl);
  // The range: the front and the datum, room to the upper right for the cloud.
  const [x0, x1] = extent([...front.map((p) => p[0]), datum[0]]);
  const [y0, y1] = extent([...front.map((p) => p[1]), datum[1]]);
  const xRange = widen([x0 - 0.05 * (x1 - x0), x1 + 0.6 * (x1 - x0)]);
  const yRange = widen([y0 - 0.05 * (y1 - y0), y1 + 0.6 * (y1 - y0)]);
  const series = [];
  if (live || cloud.length) {
    series.push({ name: 'feasible designs (surrogate)', colour: COL.cloud, points: cloud, style: 'dots', size: 1.4, opacity: CLOUD_OPACITY });
  }
  series.push(line(`Pareto front, STM (${front.length} pts)`, COL.stm, front, 2.5));
  if (app.nsga && !app.nsga.error) {
    const nf = app.nsga.study.front.map((p) => xy(p.bacc, p.dtl));
    series.push({ name: `NSGA-II front (${nf.length} pts)`, colour: COL.nsga, points: nf, style: 'dots', size: 2.6 });
  }
  const pk = xy(fr.study.pick.criteria.bacc, fr.study.pick.criteria.dtl);
  const rc = fr.recheck.rechecked;
  const dh = fr.datumHifi;
  const hp = ratio ? [rc.bacc / dh.bacc, rc.dtl / dh.dtl] : [rc.bacc, rc.dtl];
  // The re-check larger and underneath: a close one rings the pick.
  series.push(marker('pick re-checked (HiFi)', '#ffffff', COL.hifi, 'diamond', [hp], 9));
  series.push(marker(`min-max pick (${fr.study.evaluator})`, COL.pick, '#000000', 'diamond', [pk]));
  series.push(marker('datum', '#ffffff', '#000000', 'square', [datum], 6));
  const design = app.surrogate && app.surrogate.design;
  if (live || design) {
    series.push(marker('current design', '#000000', '#ffffff', 'circle', live ? [] : [xy(design.bacc, design.dtl)], 4.5));
  }
  return {
    title,
    xLabel: ratio ? 'BAcc / datum BAcc (surrogate) [–]' : 'BAcc [m/s²]',
    yLabel: ratio ? 'DTL / datum DTL [–]' : 'DTL [N]',
    xRange,
    yRange,
    width,
    height,
    series,
  };
}

/**
 * One FRF (`which` = 'frf') or PSD ('psd') plot of the current design, log-log over
 * 0.1..100 Hz: HiFi, LoFi and the surrogate's tuned LoFi for output `key`. The page
 * draws six of them small under one key of its own (`legend: 'none'`).
 */
export function spectraSpec(app, which = 'frf', key = 'bacc', { width = 640, height = 440, title = '', legend = 'lowerLeft' } = {}) {
  const sp = app.spectra;
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

/** One output (`key`) of the time response, when it has been run: HiFi and LoFi with their RMS. */
export function timeSpec(app, key = 'bacc', { width = 720, height = 340, title = '' } = {}) {
  const res = app.time;
  if (!res) throw { message: 'no time response yet: run it first', field: 'time' };
  const o = output(key);
  const k = OUTPUTS.indexOf(o);
  const pts = (r) => r.t.map((t, i) => [t, r.outputs[k][i] * o.scale]);
  const rms = (r) => (r.rms[k] * o.scale).toPrecision(3);
  const a = pts(res.hifi);
  const b = pts(res.lofi);
  // Room above the signals for the legend (a third of their span), none taken below.
  const [lo, hi] = extent([...a, ...b].map((p) => p[1]));
  const span = hi > lo ? hi - lo : Math.abs(hi) || 1;
  return {
    title,
    xLabel: 'time [s]',
    yLabel: o.time,
    xRange: [res.hifi.t[0], res.hifi.t[res.hifi.t.length - 1]],
    yRange: [lo - 0.04 * span, hi + 0.34 * span],
    width,
    height,
    series: [
      line(`HiFi (RMS ${rms(res.hifi)})`, COL.hifi, a, 2.6),
      line(`LoFi (RMS ${rms(res.lofi)})`, COL.lofi, b, 1),
    ],
  };
}
