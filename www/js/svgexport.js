// The page's charts for export: every chart there is data for as a chart spec at export
// size with a title (the screen's specs, js/chartspecs.js), drawn as SVG by the wasm core
// (plotters' SVG backend: `lineChartSvg`, `mapChartSvg`, main thread only: plotters
// measures text in the page's document) or as a slide-size PNG (js/exports.js). Takes
// plain data; a failure rejects with `{message, field}` like every engine call.

import { OUTPUTS, designText, objectiveSpec, output, spectraSpec, timeSpec } from './chartspecs.js';
import { roadWords } from './format.js';

/** The map models' names in titles. */
const MAP_MODELS = { lofi: 'LoFi', hifi: 'HiFi', surrogate: 'surrogate', error: 'surrogate error vs HiFi' };

/**
 * The car's name for titles: a custom car's own `name` (its JSON), else the preset's id (`sedan`).
 */
function carName(state) {
  if (state.car === 'custom' && state.carJson) {
    try {
      const n = JSON.parse(state.carJson).name;
      if (typeof n === 'string' && n.trim()) return n.trim();
    } catch {
      // A car the core refused is never the state's; its id names it then.
    }
  }
  return state.car;
}

/** The car's name for file names: lower case, letters and digits joined by '-', at most 40 characters. */
export function carSlug(state) {
  return carName(state).toLowerCase().replace(/[^a-z0-9]+/g, '-').replace(/^-+|-+$/g, '').slice(0, 40).replace(/-+$/, '') || state.car;
}

/**
 * The objective plane as on screen (`ratio`: its datum-ratio axes; `adaptive`: the
 * adaptive loop's front and picks, js/chartspecs.js `adaptivePlane`, when one runs), with
 * a title.
 */
export function objectiveChart({ state, front, nsga, cloud, design, ratio, adaptive = null, hifi = null }, { width = 720, height = 460 } = {}) {
  const title = front && !front.error
    ? `Objective plane (surrogate ${front.study.evaluator}): ${carName(state)}, ${roadWords(state)}`
    : '';
  return objectiveSpec({ front, nsga, cloud, design, adaptive, hifi }, { ratio, width, height, title });
}

/** One FRF (`which` = 'frf') or PSD ('psd') chart of output `key`, with a title. */
function spectraChart({ state, spectra }, which = 'frf', key = 'bacc', { width = 640, height = 440 } = {}) {
  const title = `${output(key).name} ${which === 'frf' ? 'frequency response per metre of road displacement' : 'PSD'}: ${designText(state)}`;
  return spectraSpec(spectra, which, key, { width, height, title });
}

/** One output (`key`) of the time response, once it has been run, with a title. */
function timeChart({ state, time, timeLinear }, key = 'bacc', { width = 720, height = 340 } = {}) {
  return timeSpec(time, key, { width, height, linear: timeLinear, title: `${output(key).name} time response: ${designText(state)}` });
}

/**
 * The map chart spec of a MapView `view` as shown: its values (absolute, or % against
 * the datum), colour range, contour levels (the screen's colour bar ticks), the
 * infeasible area, the markers with a legend, and a title naming the map's `model`.
 */
function mapChart(view, model, { width = 640, height = 480 } = {}) {
  const d = view && view.data;
  if (!d) throw { message: 'no map to draw yet', field: 'map' };
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
    ...view.chartSpec(width, height),
    title: `${view.crit.title}: ${view.crit.long} (${MAP_MODELS[model] || 'LoFi'})`,
    contours: { levels: d.levels },
    markers,
  };
  delete spec.legend;
  if (d.infeasible) spec.feasible = d.feasible;
  return spec;
}

/**
 * Every chart there is data for, as `[{name, kind, spec, view?}]` (`kind`: 'line' or
 * 'map'; a map also names its `view`): the objective plane, the FRF and PSD plots, the
 * time response (once run) and the three maps. `data`: `{state, front, nsga, cloud,
 * design, ratio, adaptive, spectra, time, views, model}`.
 */
export function exportCharts(data) {
  const out = [];
  if (data.front && !data.front.error) out.push({ name: 'objective', kind: 'line', spec: objectiveChart(data) });
  if (data.spectra) {
    for (const which of ['frf', 'psd']) {
      for (const o of OUTPUTS) out.push({ name: `${which}-${o.key}`, kind: 'line', spec: spectraChart(data, which, o.key) });
    }
  }
  if (data.time) for (const o of OUTPUTS) out.push({ name: `time-${o.key}`, kind: 'line', spec: timeChart(data, o.key) });
  for (const v of data.views) if (v.data) out.push({ name: `map-${v.crit.key}`, kind: 'map', spec: mapChart(v, data.model), view: v });
  return out;
}

/** Every chart as `[{name, svg}]`; `svg(kind, spec)` draws one (js/compute.js `svg`). */
export async function allSvgs(data, svg) {
  const out = [];
  for (const c of exportCharts(data)) out.push({ name: c.name, svg: await svg(c.kind, c.spec) });
  return out;
}
