// The page's panels beyond the first screen (issue #29), loaded with `import()` once the
// first map is drawn, so the first screen fetches, parses and runs none of their code:
// the drawer's spectra, time, car editor, load cases, road, export and class-front panels, the tour and
// the lesson panel (with their own modules: lessons, the lesson book and author, the class
// code, the SVG and PNG exports). `startPanels` builds them into `ui` and wires their
// controls; js/app.js waits for it before the page says it is ready.

import { SpectraPanel } from './spectra.js';
import { TimePanel, DamperChart } from './timepanel.js';
import { CarEditor, carFieldMessage } from './careditor.js';
import { Guide } from './guide.js';
import { plainWords } from './controls.js';
import { download, mapsCsv, frontCsv, slidePng, slidePngs, zip } from './exports.js';
import { allSvgs, carSlug, exportCharts, objectiveChart } from './svgexport.js';
import { LessonPanel } from './lessonpanel.js';
import { ClassFront } from './classfront.js';
import { RoadPanel } from './roadpanel.js';
import { fromSession } from './restore.js';
import { wireTime } from './timecontrols.js';
import { adaptivePlane } from './chartspecs.js';
import { RobustPanel } from './robustpanel.js';

const $ = (id) => document.getElementById(id);

/** "sedan-B-20ms" ("my-van-B-20ms" for a custom car named "My van"): the stem of export file names. */
function stamp(state) {
  return `${carSlug(state)}-${state.roadProfile ? 'measured' : state.class}-${state.speed}ms`;
}

/**
 * Builds the panels into `ui` (`spectra`, `time`, `damper`, `carEditor`, `robust`, `road`, `guide`,
 * `lessons`, `classFront`) and wires their controls. `hooks` are the maps' pick, key and
 * contour callbacks (the road panel's maps use them too); `exportData()` the data of the
 * chart exports; `redraw()` redraws the charts after a resize of the lesson panel.
 */
export function startPanels({ store, controller, compute, render, controls, ui, hooks, exportData, redraw }) {
  ui.spectra = new SpectraPanel((which, key) => $(`sp-${which}-${key}`), $('panel-spectra'), $('sp-key-route'));
  ui.time = new TimePanel({
    car: $('tp-car'),
    play: $('tp-play'),
    charts: Object.fromEntries(['bacc', 'dtl', 'sws'].map((k) => [k, { base: $(`tp-${k}`), overlay: $(`tp-${k}-cursor`) }])),
  });
  ui.damper = new DamperChart($('tp-fv'));
  ui.carEditor = new CarEditor($('car-fields'));
  ui.robust = new RobustPanel({
    load: $('rb-load'), operating: $('rb-op'), addLoad: $('rb-add-load'), addOp: $('rb-add-op'), combine: $('rb-combine'),
    text: $('rb-text'), apply: $('rb-apply'), pending: $('rb-pending'), clear: $('rb-clear'), caseSelect: $('rb-case'), msg: $('msg-cases'), count: $('rb-count'),
  }, {
    // The core's own limits, on the state as it is with these cases.
    check: (text) => compute.checkState({ ...store.state, cases: text, case: null }).then(() => null, (e) => e),
    // A refused text leaves the last good state; the core's message names the field.
    apply: async (text) => {
      let failure = null;
      await controller.changeScenario({ cases: text, case: null }, 'cases', { onFail: (e) => (failure = e) });
      return failure;
    },
    pickCase: (c) => controller.changeScenario({ case: c === 'robust' ? null : c }, 'case', {
      onFail: (e) => ($('msg-cases').textContent = plainWords(e.message)),
    }),
  });
  ui.robust.show({ cases: store.state.cases, mapCase: store.state.case, desc: store.desc });
  ui.guide = new Guide($('tour-card'));
  ui.lessons = new LessonPanel({ root: $('lesson'), bench: $('app'), store, controller, compute, onResize: redraw });
  const ids = { name: 'cf-name', make: 'cf-make', code: 'cf-code', copy: 'cf-copy', text: 'cf-text', file: 'cf-file', apply: 'cf-apply', clear: 'cf-clear', status: 'cf-status', problems: 'cf-problems', table: 'cf-table', drop: 'cf-drop' };
  ui.classFront = new ClassFront(Object.fromEntries(Object.entries(ids).map(([k, id]) => [k, $(id)])), { store, controller, compute });
  ui.road = new RoadPanel({
    box: $('road-box'), file: $('road-file'), msg: $('msg-road'), summary: $('road-summary'), canvas: $('road-psd'), table: $('road-table'), notes: $('road-notes'),
    study: { box: $('road-study'), model: $('road-model'), crit: $('road-crit'), status: $('road-study-status'), maps: $('road-maps'), front: $('road-front'), caption: $('road-study-caption') },
  }, {
    store,
    compute,
    hooks,
    look: () => ({ palette: store.view.palette, tables: ui.tables }),
    onRoad: (road) => ui.onRoad(road),
  });
  $('tab-car').addEventListener('click', () => requestAnimationFrame(() => ui.road.redraw()));
  $('tour').addEventListener('click', () => ui.guide.open());
  const ctx = { store, controller, controls, render, ui, compute };
  wireTime(ctx);
  wireCarEditor(ctx);
  wireExports({ ...ctx, exportData });
  render.panels();
}

/** The Car & road tab's editor: apply the edited car, or save it as a file. */
function wireCarEditor({ store: st, controller: ctl, controls, render, ui, compute }) {
  $('car-apply').addEventListener('click', async () => {
    const ed = ui.carEditor;
    const r = ed.read();
    if (r.error) {
      ed.mark(r.path, r.error);
      return;
    }
    const json = JSON.stringify(r.car);
    let parsed;
    try {
      parsed = await compute.parseCar(json);
    } catch (e) {
      const path = e.message.split(':')[0];
      if (ed.has(path)) ed.mark(path, carFieldMessage(path, e.message));
      else controls.setMsg('carEditor', plainWords(e.message));
      return;
    }
    ed.mark('', '');
    // The design stays where it is; the datum is the edited car's own front.
    const ok = await ctl.changeScenario({ car: 'custom', carJson: json }, 'carEditor', {
      onFail: (e) => controls.setMsg('carEditor', `The edited car cannot be computed: ${plainWords(e.message)}`),
    });
    if (ok) {
      st.custom = { json, ks: parsed.ks, cs: parsed.cs, origin: 'editor', name: r.car.name };
      controls.setMsg('carEditor', '');
      render.controls();
    }
  });
  $('car-export').addEventListener('click', () => {
    const car = st.desc.car;
    const name = (car.name || 'car').toLowerCase().replace(/[^a-z0-9]+/g, '-').replace(/^-|-$/g, '');
    download(`${name}.json`, new Blob([JSON.stringify(car, null, 2) + '\n'], { type: 'application/json' }));
  });
}

function wireExports({ store: st, controller: ctl, controls, ui, compute, exportData }) {
  const status = (t) => ($('export-status').textContent = t);
  const failed = (what) => (e) => status(`${what} failed: ${e.message || e}`);
  $('front-csv').addEventListener('click', () => download(`ridelab-front-${stamp(st.state)}.csv`, new Blob([frontCsv(st.front, st.nsga, adaptivePlane(st.adaptive))], { type: 'text/csv' })));
  $('maps-csv').addEventListener('click', () => {
    const shown = st.shownMaps();
    if (!shown) return;
    const m = st.view.model;
    download(`ridelab-${m}-maps-${stamp(st.state)}.csv`, new Blob([mapsCsv(st.desc.designBox, m, shown.maps)], { type: 'text/csv' }));
  });
  $('op-png').addEventListener('click', () => {
    const data = exportData();
    Promise.resolve()
      .then(() => slidePng({ kind: 'line', spec: objectiveChart(data) }))
      .then((png) => download(`ridelab-objective-${stamp(st.state)}.png`, png))
      .catch(failed('PNG export'));
  });
  $('op-svg').addEventListener('click', () => {
    Promise.resolve()
      .then(() => compute.svg('line', objectiveChart(exportData())))
      .then((svg) => download(`ridelab-objective-${stamp(st.state)}.svg`, new Blob([svg], { type: 'image/svg+xml' })))
      .catch(failed('SVG export'));
  });
  // Every chart in one download: a burst of downloads trips the browser's guard.
  $('png-all').addEventListener('click', async () => {
    try {
      const charts = exportCharts(exportData());
      const files = await slidePngs(charts, (c) => `ridelab-${c.name}-${stamp(st.state)}.png`, (n, total) => status(`Drawing the charts at slide size: ${n} of ${total}…`));
      download(`ridelab-charts-png-${stamp(st.state)}.zip`, await zip(files));
      status(`${files.length} PNGs (1600 px wide) in one zip.`);
    } catch (e) {
      failed('PNG export')(e);
    }
  });
  $('svg-all').addEventListener('click', async () => {
    try {
      const list = await allSvgs(exportData(), (kind, spec) => compute.svg(kind, spec));
      const files = list.map(({ name, svg }) => ({ name: `ridelab-${name}-${stamp(st.state)}.svg`, data: svg }));
      download(`ridelab-charts-svg-${stamp(st.state)}.zip`, await zip(files));
      status(`${files.length} SVGs in one zip.`);
    } catch (e) {
      failed('SVG export')(e);
    }
  });
  // The study report: built by the core in the heavy worker (seconds), saved as one HTML file.
  $('report-html').addEventListener('click', async () => {
    const button = $('report-html');
    button.disabled = true;
    status('Building the study report in the worker (maps, fidelity study, fronts)…');
    try {
      const t0 = performance.now();
      const r = await compute.report(st.state);
      download(`ridelab-report-${stamp(st.state)}.html`, new Blob([r.html], { type: 'text/html' }));
      status(`Study report: ${r.title} (${((performance.now() - t0) / 1000).toFixed(1)} s).`);
    } catch (e) {
      failed('The report')(e);
    } finally {
      button.disabled = false;
    }
  });
  $('session-save').addEventListener('click', () => {
    download(`ridelab-session-${stamp(st.state)}.json`, new Blob([JSON.stringify(st.session(), null, 2)], { type: 'application/json' }));
  });
  $('session-load').addEventListener('change', async (ev) => {
    const input = ev.target;
    const file = input.files && input.files[0];
    if (!file) return;
    input.value = '';
    let session;
    try {
      session = await fromSession(compute, st.defaults, await file.text());
    } catch (e) {
      controls.setMsg('session', `${file.name}: ${plainWords(e.message || e)}`);
      return;
    }
    controls.setMsg('session', '');
    const shown = await ctl.enqueue(async () => ctl.load(session, 'session'));
    if (!shown) controls.setMsg('session', `${file.name}: not loaded, it cannot be computed (the banner says why); the current view stays.`);
    else if (session.problems.length) controls.setMsg('session', `${file.name}: ${session.problems.join('; ')}; the rest is loaded.`);
  });
}
