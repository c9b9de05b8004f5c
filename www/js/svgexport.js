// SVG export of the page's charts. Each function builds a chart spec from `app`
// (js/app.js, `window.__ridelab`) and resolves to an SVG document (a string) drawn by the
// wasm core's chart module (plotters' SVG backend) through the engine methods
// `lineChartSvg` and `mapChartSvg`. They go to `app.engine`, the main-thread engine,
// never to the worker: plotters measures text in the page's document. A failure rejects
// with `{message, field}` like every engine call (`field` names the spec field).

import { OUTPUTS, designText, objectiveSpec, output, spectraSpec, timeSpec } from './chartspecs.js';

/** A spec builder's result as a promise (its `{message, field}` throw as a rejection). */
function specOf(build) {
  try {
    return Promise.resolve(build());
  } catch (e) {
    return Promise.reject(e);
  }
}

/** The objective plane as on screen (`ratio`: the panel's datum-ratio axes), with a title. */
export function objectiveSvg(app, { ratio = app.objPlane ? app.objPlane.ratio : false, width = 720, height = 460 } = {}) {
  return specOf(() => {
    const fr = app.front;
    const title = fr && !fr.error
      ? `Objective plane (surrogate ${fr.study.evaluator}): ${app.state.car}, class ${app.state.class} at ${app.state.speed} m/s`
      : '';
    return objectiveSpec(app, { ratio, width, height, title });
  }).then((spec) => app.engine.call('lineChartSvg', spec));
}

/** One FRF (`which` = 'frf') or PSD ('psd') plot of output `key` ('bacc', 'dtl', 'sws'). */
export function spectraSvg(app, which = 'frf', key = 'bacc', { width = 640, height = 440 } = {}) {
  return specOf(() => {
    const title = `${output(key).name} ${which === 'frf' ? 'frequency response' : 'PSD'}: ${designText(app)}`;
    return spectraSpec(app, which, key, { width, height, title });
  }).then((spec) => app.engine.call('lineChartSvg', spec));
}

/** One output (`key`) of the time response, once it has been run. */
export function timeSvg(app, key = 'bacc', { width = 720, height = 340 } = {}) {
  return specOf(() => {
    return timeSpec(app, key, { width, height, title: `${output(key).name} time response: ${designText(app)}` });
  }).then((spec) => app.engine.call('lineChartSvg', spec));
}

/** The map models' names in titles. */
const MAP_MODELS = { lofi: 'LoFi', hifi: 'HiFi', surrogate: 'surrogate', error: 'surrogate error vs HiFi' };

/**
 * A design map as the MapView `view` shows it: its values (absolute, or % against the
 * datum), colour range, contour levels (the screen's colour bar ticks), the infeasible
 * area, the datum and the design.
 */
export function mapSvg(app, view, { width = 640, height = 480 } = {}) {
  const d = view && view.data;
  if (!d) return Promise.reject({ message: 'no map to draw yet', field: 'map' });
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
  // The map on screen (values, colours, range) with its contour levels, a title, the
  // markers and their legend.
  const spec = {
    ...view.chartSpec(width, height),
    title: `${view.crit.title}: ${view.crit.long} (${MAP_MODELS[app.view.model] || 'LoFi'})`,
    contours: { levels: d.levels },
    markers,
  };
  delete spec.legend;
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
