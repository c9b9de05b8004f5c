// SVG export of the page's charts. Each function builds a chart spec from `app`
// (js/app.js, `window.__ridelab`) and resolves to an SVG document (a string) drawn by the
// wasm core's chart module (plotters' SVG backend) through the engine methods
// `lineChartSvg` and `mapChartSvg`. They go to `app.engine`, the main-thread engine,
// never to the worker: plotters measures text in the page's document. A failure rejects
// with `{message, field}` like every engine call (`field` names the spec field).

/** Colours of js/panels.js, as #rrggbb (plus an opacity for the cloud). */
const COL = {
  cloud: '#78a0d2',
  stm: '#c2410c',
  nsga: '#15803d',
  lofi: '#1d4ed8',
  hifi: '#b91c1c',
  pick: '#facc15',
};

/** The outputs of the spectra and time panels: key, name, FRF and PSD axis labels, time unit. */
const OUTPUTS = [
  { key: 'bacc', name: 'BAcc', frf: '|H| BAcc / road displacement [1/s²]', psd: 'PSD BAcc [(m/s²)²/Hz]', time: 'BAcc [m/s²]', scale: 1 },
  { key: 'dtl', name: 'DTL', frf: '|H| DTL / road displacement [N/m]', psd: 'PSD DTL [N²/Hz]', time: 'DTL [N]', scale: 1 },
  { key: 'sws', name: 'SWS', frf: '|H| SWS / road displacement [m/m]', psd: 'PSD SWS [m²/Hz]', time: 'SWS [mm]', scale: 1000 },
];

function output(key) {
  const o = OUTPUTS.find((x) => x.key === key);
  if (!o) throw { message: `no output '${key}' (bacc, dtl or sws)`, field: 'key' };
  return o;
}

const line = (name, colour, points, size) => ({ name, colour, points, style: 'line', size });
const marker = (name, colour, stroke, shape, x, y, size = 6) =>
  ({ name, colour, stroke, points: [[x, y]], style: { markers: shape }, size });

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

/** The page's linear range widening (js/plot.js setRange, 4 % each side). */
function widen([lo, hi]) {
  if (!(hi > lo)) {
    const d = Math.abs(lo) * 0.05 || 1;
    return [lo - d, hi + d];
  }
  const d = (hi - lo) * 0.04;
  return [lo - d, hi + d];
}

function designText(app) {
  return `Ks ${(app.state.ks / 1000).toFixed(2)} kN/m, Cs ${(app.state.cs / 1000).toFixed(3)} kNs/m`;
}

/**
 * The objective plane (BAcc against DTL, on the surrogate): its feasible designs (every
 * other cell of the page's 96 x 72 set each way), the STM Pareto front, the NSGA-II front when computed,
 * the min-max pick and its HiFi re-check, the datum and the current design; on the
 * datum-ratio axes when the panel shows them (`ratio`, default the panel's choice).
 */
export function objectiveSvg(app, { ratio = app.objPlane ? app.objPlane.ratio : false, width = 720, height = 460 } = {}) {
  const fr = app.front;
  if (!fr || fr.error) return Promise.reject({ message: `no front to draw${fr ? `: ${fr.error}` : ''}`, field: 'front' });
  const d = fr.datum;
  const xy = (bacc, dtl) => (ratio ? [bacc / d.bacc, dtl / d.dtl] : [bacc, dtl]);
  const m = app.cloud;
  const n = m.nx * m.ny;
  const cloud = [];
  for (let j = 0; j < m.ny; j += 2) {
    for (let i = 0; i < m.nx; i += 2) {
      const k = j * m.nx + i;
      if (m.feasible[k]) cloud.push(xy(m.values[k], m.values[n + k]));
    }
  }
  const front = fr.study.front.map((p) => xy(p.bacc, p.dtl));
  const datum = xy(d.bacc, d.dtl);
  // The page's range: the front and the datum, room to the upper right for the cloud.
  const [x0, x1] = extent([...front.map((p) => p[0]), datum[0]]);
  const [y0, y1] = extent([...front.map((p) => p[1]), datum[1]]);
  const xRange = widen([x0 - 0.05 * (x1 - x0), x1 + 0.6 * (x1 - x0)]);
  const yRange = widen([y0 - 0.05 * (y1 - y0), y1 + 0.6 * (y1 - y0)]);
  const series = [];
  if (cloud.length) {
    series.push({ name: 'feasible designs (surrogate)', colour: COL.cloud, points: cloud, style: 'dots', size: 1.4, opacity: 0.35 });
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
  // The re-check larger and underneath, as on the page: a close one rings the pick.
  series.push(marker('pick re-checked (HiFi)', '#ffffff', COL.hifi, 'diamond', hp[0], hp[1], 9));
  series.push(marker(`min-max pick (${fr.study.evaluator})`, COL.pick, '#000000', 'diamond', pk[0], pk[1]));
  series.push(marker('datum', '#ffffff', '#000000', 'square', datum[0], datum[1], 6));
  if (app.surrogate && app.surrogate.design) {
    const p = xy(app.surrogate.design.bacc, app.surrogate.design.dtl);
    series.push(marker('current design', '#000000', '#ffffff', 'circle', p[0], p[1], 4.5));
  }
  const spec = {
    title: `Objective plane (surrogate ${fr.study.evaluator}): ${app.state.car}, class ${app.state.class} at ${app.state.speed} m/s`,
    xLabel: ratio ? 'BAcc / datum BAcc (surrogate) [–]' : 'BAcc [m/s²]',
    yLabel: ratio ? 'DTL / datum DTL [–]' : 'DTL [N]',
    xRange,
    yRange,
    width,
    height,
    series,
  };
  return app.engine.call('lineChartSvg', spec);
}

/**
 * One FRF (`which` = 'frf') or PSD ('psd') plot of the current design, log-log over
 * 0.1..100 Hz: HiFi and LoFi for output `key` ('bacc', 'dtl' or 'sws').
 */
export async function spectraSvg(app, which = 'frf', key = 'bacc', { width = 640, height = 440 } = {}) {
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
  // The page's y range: whole decades, at most 8 of them below the peak.
  const [low, top] = extent([...a, ...b, ...c].map((p) => p[1]));
  const hi = 10 ** Math.ceil(Math.log10(top));
  const lo = 10 ** Math.floor(Math.log10(Math.max(low, top * 1e-8)));
  const spec = {
    title: `${o.name} ${which === 'frf' ? 'frequency response' : 'PSD'}: ${designText(app)}`,
    xLabel: 'frequency [Hz]',
    yLabel: o[which],
    xLog: true,
    yLog: true,
    xRange: [0.1, 100],
    yRange: [lo, hi],
    width,
    height,
    legend: 'lowerLeft',
    // HiFi wide underneath, LoFi narrow on top: both stay visible where they agree.
    series: [
      line('HiFi (full car)', COL.hifi, b, 4),
      line('LoFi (quarter car)', COL.lofi, a, 1.6),
      line(`tuned LoFi (${sp.surrogateRoute})`, COL.nsga, c, 1.6),
    ],
  };
  return app.engine.call('lineChartSvg', spec);
}

/** One output (`key`) of the time response, when it has been run: HiFi and LoFi with their RMS. */
export async function timeSvg(app, key = 'bacc', { width = 720, height = 340 } = {}) {
  const res = app.time;
  if (!res) throw { message: 'no time response yet: run it first', field: 'time' };
  const o = output(key);
  const k = OUTPUTS.indexOf(o);
  const pts = (r) => r.t.map((t, i) => [t, r.outputs[k][i] * o.scale]);
  const rms = (r) => (r.rms[k] * o.scale).toPrecision(3);
  const spec = {
    title: `${o.name} time response: ${designText(app)}`,
    xLabel: 'time [s]',
    yLabel: o.time,
    width,
    height,
    series: [
      line(`HiFi (RMS ${rms(res.hifi)})`, COL.hifi, pts(res.hifi), 2.6),
      line(`LoFi (RMS ${rms(res.lofi)})`, COL.lofi, pts(res.lofi), 1),
    ],
  };
  return app.engine.call('lineChartSvg', spec);
}

/** The map models' names in titles. */
const MAP_MODELS = { lofi: 'LoFi', hifi: 'HiFi', surrogate: 'surrogate', error: 'surrogate error vs HiFi' };

/**
 * A design map as the MapView `view` shows it: its values (absolute, or % against the
 * datum), colour range, contour levels, the infeasible area, the datum and the design.
 */
export function mapSvg(app, view, { width = 640, height = 480 } = {}) {
  const d = view && view.data;
  if (!d) return Promise.reject({ message: 'no map to draw yet', field: 'map' });
  const span = d.hi - d.lo;
  const levels = d.ticks.filter((t) => t > d.lo + 1e-9 * span && t < d.hi - 1e-9 * span);
  const markers = [];
  if (view.markers) {
    const { design, datum, samples, pick } = view.markers;
    for (const [i, smp] of (samples || []).entries()) {
      markers.push({ label: i === 0 ? 'HiFi samples' : '', ks: smp.ks, cs: smp.cs, shape: 'cross', colour: '#7c2d12', size: 4 });
    }
    if (pick) markers.push({ label: 'min-max pick', ks: pick.ks, cs: pick.cs, shape: 'square', colour: '#facc15', size: 5 });
    markers.push({ label: 'datum', ks: datum.ks, cs: datum.cs, shape: 'diamond' });
    markers.push({ label: 'design', ks: design.ks, cs: design.cs, shape: 'circle', colour: '#ffffff', size: 5 });
  }
  const spec = {
    title: `${view.crit.title}: ${view.crit.long} (${MAP_MODELS[app.view.model] || 'LoFi'})`,
    unit: `${view.crit.title} [${d.unit}]`,
    nx: d.nx,
    ny: d.ny,
    values: d.shown,
    designBox: d.box,
    colourMap: d.scale === 'rel' ? 'diverging' : 'viridis',
    range: [d.lo, d.hi],
    contours: { levels },
    markers,
    width,
    height,
  };
  if (d.infeasible) spec.feasible = d.feasible;
  return app.engine.call('mapChartSvg', spec);
}

/**
 * Every chart there is data for, as `[{name, svg}]`: the objective plane, the FRF and
 * PSD plots, the time response (once run) and the three maps.
 */
export async function allSvgs(app) {
  const jobs = [];
  if (app.front && !app.front.error) jobs.push(['objective', () => objectiveSvg(app)]);
  if (app.spectra) {
    for (const which of ['frf', 'psd']) {
      for (const o of OUTPUTS) jobs.push([`${which}-${o.key}`, () => spectraSvg(app, which, o.key)]);
    }
  }
  if (app.time) for (const o of OUTPUTS) jobs.push([`time-${o.key}`, () => timeSvg(app, o.key)]);
  for (const v of app.views) jobs.push([`map-${v.crit.key}`, () => mapSvg(app, v)]);
  const out = [];
  for (const [name, make] of jobs) out.push({ name, svg: await make() });
  return out;
}
