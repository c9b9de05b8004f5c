// RideLab page: state, URL, controls and views. All computing goes through engines
// (js/engine.js) over the wasm core: the LoFi model and the maps run on the main thread
// (well under a millisecond per design), the HiFi full-car report in a Web Worker, so
// the sliders stay smooth while it computes ("?engine=main" runs everything on the
// main thread).
//
// Data flow: a control changes -> the candidate state is computed by the LoFi engine
// (which also validates it) -> on success it becomes the state, the LoFi views are
// redrawn and the HiFi report is requested; when it arrives for the current state the
// HiFi views are redrawn. On failure the message goes next to the field and the last
// good state stays.

import init, * as api from '../ridelab.js';
import { createEngine, deferredEngine, latestOnly } from './engine.js';
import { encodeHash, decodeHash } from './urlstate.js';
import { MapView, CRITERIA } from './mapview.js';
import { renderCriteria, feasibilityText, routeNote, renderProps, renderModes } from './readout.js';
import { fmt, fmtInput, parseNumber } from './format.js';
import { ObjectivePlane, SpectraPanel, TimePanel, download, mapsCsv, frontCsv, canvasPng } from './panels.js';
import { buildPickers, renderMetrics, tuningText } from './surrogatepanel.js';
import { Guide } from './guide.js';
import { CarEditor } from './careditor.js';
import { objectiveSvg, allSvgs } from './svgexport.js';

/** LoFi and surrogate map resolution (cells); the image is scaled smoothly onto the plot. */
const GRID = { nx: 160, ny: 120 };
/** HiFi and surrogate-error map resolutions (worker): a coarse map first, then the LoFi
 * maps' resolution (the residue route makes a 160 x 120 HiFi map cost about 0.1 s). */
const HIFI_GRIDS = [{ nx: 41, ny: 41 }, GRID];
/** The surrogate's feasible set on the objective plane (about 7000 designs). */
const CLOUD_GRID = { nx: 96, ny: 72 };
/** Side of the HiFi grid the surrogate panel validates the fit on. */
const VALIDATION_LEVELS = 20;

/** What each map model is called on the page. */
const MODEL_NAMES = { lofi: 'LoFi', hifi: 'HiFi', surrogate: 'surrogate', error: 'surrogate error' };

/** The objectives of a map mask, by bit (see the wasm `modelMaps`). */
const OBJECTIVE_BITS = [
  [1, 'SWS limit'], [2, 'bounce band'], [4, 'damping band'],
  [8, 'BAcc ≤ datum'], [16, 'DTL ≤ datum'], [32, 'SWS ≤ datum'],
];

/** ISO 8608 wording of the classes. */
const CLASS_WORDS = {
  A: 'very good', B: 'good', C: 'average', D: 'poor', E: 'very poor', F: 'bad', G: 'very bad', H: 'extremely bad',
};

/** The input element of each state field (the engine's error `field`). */
const FIELD_INPUT = {
  ks: 'ks-num', cs: 'cs-num', speed: 'speed', class: 'class', tracks: 'tracks', swsLimit: 'sws-limit', car: 'car',
  tpSeed: 'tp-seed', tpBump: 'tp-bump', tpRebound: 'tp-rebound', session: 'session-load',
  box: 'ks-min', bounceBand: 'bb-lo', dampingBand: 'db-lo', surrogate: 'sur-approach', plan: 'sur-plan',
};

/** Frequencies of the FRF / PSD plots (log spaced, 0.1..100 Hz). */
const NFREQ = 240;

const $ = (id) => document.getElementById(id);

const app = {
  ready: false,
  readyAt: null,
  api,
  engine: null,
  hifiEngine: null,
  heavyEngine: null,
  defaults: null,
  presets: [],
  state: null,
  view: { scale: 'abs', large: false, model: 'lofi', plan: true },
  desc: null,
  /** LoFi reports of the design and the datum, always for the current state. */
  lofi: { design: null, datum: null },
  /** The surrogate's criteria of the design and the datum (`{bacc, dtl, sws, dtl_relative}`). */
  surrogate: { design: null, datum: null },
  /** The surrogate's map at the page's grid (when the maps show it) and its feasible set. */
  surMaps: null,
  cloud: null,
  /** The map shown when it is not the LoFi's: `{model, key, maps, datum, ms}`. */
  modelMaps: null,
  /** The surrogate's fit report (worker) and the key of what it was fitted to. */
  fit: null,
  fitKey: '',
  /** HiFi reports and the state keys they belong to (may lag the state). */
  hifi: { design: null, datum: null, key: '', datumKey: '' },
  maps: null,
  /** The LoFi STM front study of the current scenario (`{error}` when none is feasible). */
  front: null,
  /** The NSGA-II study, when asked for. */
  nsga: null,
  /** FRFs and PSDs of the current design; the time response, when run. */
  spectra: null,
  time: null,
  /** Times (performance.now) the objective plane's front was last drawn, and how often. */
  frontDrawnAt: 0,
  frontDraws: 0,
  views: [],
  bad: new Set(),
  /** The last custom car that was loaded: {json, ks, cs}. */
  custom: null,
  /** ms from an input to the LoFi views (design), to the HiFi views too (full). */
  metrics: { design: [], full: [], scenario: [], scenarioPhases: [], maps: [] },
  pending: 0,
  interactiveAt: null,
  /** True when every view shows the current state and nothing is queued. */
  isSettled: () => app.pending === 0 && pendingDesign === null && hifiCurrent(),
  /** ms of each HiFi or error map computed in the worker, request to data. */
  mapTimes: [],
};
window.__ridelab = app;

// ---------------------------------------------------------------- messages

function banner(text, kind = 'warn') {
  const b = $('banner');
  $('banner-text').textContent = text;
  b.className = kind === 'error' ? 'banner error' : 'banner';
  b.hidden = !text;
}

function fatal(text) {
  banner(text, 'error');
  $('loading').hidden = true;
}

/** A core message shown next to its input, with the display name and unit. */
function explain(failure, field) {
  const msg = failure.message || String(failure);
  if (field === 'ks') return msg.replace(/^front\.spring: /, 'Ks (front spring, N/m): ');
  if (field === 'cs') return msg.replace(/^front\.damper: /, 'Cs (front damper, N s/m): ');
  if (field === 'swsLimit') return msg.replace(/^sws_limit: must be a finite number > 0 \(m\)/, 'SWS limit: must be a number > 0 (mm)');
  if (field === 'bounceBand') return msg.replace(/^bounce_band: /, 'Bounce band (Hz): ');
  if (field === 'dampingBand') return msg.replace(/^damping_band: /, 'Damping band: ');
  if (field === 'surrogate') return msg.replace(/^(approach|scheme): /, 'Surrogate: ');
  if (field === 'box') return msg.replace(/^(ks|cs)-range: /, 'Design box: ');
  return msg;
}

function setMsg(field, text) {
  const m = $(`msg-${field}`);
  if (m) m.textContent = text || '';
  const input = $(FIELD_INPUT[field]);
  if (input) {
    if (text) input.setAttribute('aria-invalid', 'true');
    else input.removeAttribute('aria-invalid');
  }
  if (text) app.bad.add(field);
  else app.bad.delete(field);
}

/** Shows an engine failure next to the field it names (or the field being edited). */
function showFailure(failure, source) {
  const field = failure.field && FIELD_INPUT[failure.field] ? failure.field : source;
  if (field && FIELD_INPUT[field]) setMsg(field, explain(failure, field));
  else banner(failure.message || String(failure));
  if (source && source !== field && FIELD_INPUT[source]) {
    // The edit was refused because of another field; keep the edited one marked too.
    setMsg(source, `not applied: ${explain(failure, field)}`);
  }
}

// ---------------------------------------------------------------- computing

/** The key of everything a report depends on. */
function keyOf(s) {
  return JSON.stringify([s.car, s.carJson, s.ks, s.cs, s.class, s.speed, s.tracks]);
}

function datumStateOf(s, desc) {
  return { ...s, ks: desc.datumKs, cs: desc.datumCs };
}

function hifiCurrent() {
  return app.state !== null && app.hifi.key === keyOf(app.state) && app.hifi.datumKey === keyOf(datumStateOf(app.state, app.desc));
}

/** The surrogate's criteria as a report-like row of the readout. */
function surrogateRow(c, desc) {
  return { ...c, dtl_relative: c.dtl / desc.staticWheelLoad };
}

/**
 * Everything on the main thread that depends on car, road, objectives, box and
 * surrogate, plus the design, except the maps (see `refreshMaps`): LoFi reports, the
 * surrogate (fitted once, then kept by the core), its feasible set and the front on it.
 */
async function computeScenario(s) {
  const desc = await app.engine.call('describe', s);
  const ds = datumStateOf(s, desc);
  const [datum, design, sDatum, sDesign, cloud] = await Promise.all([
    app.engine.call('analyse', ds, 'quarter'),
    app.engine.call('analyse', s, 'quarter'),
    app.engine.call('criteria', ds, 'surrogate'),
    app.engine.call('criteria', s, 'surrogate'),
    app.engine.call('modelMaps', s, 'surrogate', CLOUD_GRID.nx, CLOUD_GRID.ny),
  ]);
  let front;
  try {
    front = await app.engine.call('front', s, 'stm', 'surrogate');
  } catch (e) {
    // Not a bad input (the state passed describe): no feasible design, or a numerical failure.
    front = { error: e.message || String(e) };
  }
  return {
    desc,
    lofi: { datum, design },
    surrogate: { datum: surrogateRow(sDatum, desc), design: surrogateRow(sDesign, desc) },
    cloud,
    front,
    nsga: null,
  };
}

/** All updates run one after another; each reads the state when it starts. */
let chain = Promise.resolve();
let queued = 0;
function enqueue(fn) {
  app.pending++;
  queued++;
  const p = chain.then(fn).finally(() => {
    app.pending--;
    queued--;
  });
  chain = p.catch((e) => banner(`Internal error: ${e && e.message ? e.message : e}`, 'error'));
  return p;
}

/** A change of car, road or objective (`patch` of the state) made in field `source`. */
function changeScenario(patchOrFn, source) {
  const tIn = performance.now();
  return enqueue(async () => {
    const t0 = performance.now();
    // A function is read when the job runs: a drag's latest value (see dragSwsLimit).
    const patch = typeof patchOrFn === 'function' ? patchOrFn() : patchOrFn;
    const s = { ...app.state, ...patch };
    let r;
    try {
      r = await computeScenario(s);
    } catch (e) {
      showFailure(e, source);
      return false;
    }
    if (source) setMsg(source, '');
    for (const f of Object.keys(patch)) if (FIELD_INPUT[f]) setMsg(f, '');
    Object.assign(app, r, { state: s });
    const t1 = performance.now();
    renderScenario();
    app.metrics.scenario.push(performance.now() - t0);
    app.metrics.scenarioPhases.push({ wait: t0 - tIn, compute: t1 - t0, render: performance.now() - t1 });
    if (!hifiCurrent()) requestHifi(t0);
    return true;
  });
}

/** The SWS limit (mm) the slider was dragged to, not yet taken by a queued update. */
let pendingSwsMm = null;

/**
 * The SWS limit slider: the front and pick follow while it is dragged. Input events
 * coalesce: while an update for the slider waits in the queue, a new position only
 * replaces its value, so the front is never more than one update behind the pointer.
 */
function dragSwsLimit(mm) {
  const waiting = pendingSwsMm !== null;
  pendingSwsMm = mm;
  $('sws-limit').value = fmtInput(mm, 4);
  if (waiting) return;
  changeScenario(() => {
    const v = pendingSwsMm;
    pendingSwsMm = null;
    return { swsLimit: v / 1000 };
  }, 'swsLimit');
}

/** The latest design request; bursts of slider or drag input coalesce into it. */
let pendingDesign = null;
function changeDesign(ks, cs, source, t0 = performance.now()) {
  const queued = pendingDesign !== null;
  pendingDesign = { ks, cs, source, t0 };
  if (queued) return chain;
  return enqueue(async () => {
    const { ks: k, cs: c, source: src, t0: start } = pendingDesign;
    pendingDesign = null;
    const s = { ...app.state, ks: k, cs: c };
    let design;
    let sur;
    try {
      design = await app.engine.call('analyse', s, 'quarter');
      sur = await app.engine.call('criteria', s, 'surrogate');
    } catch (e) {
      showFailure(e, src);
      syncInputs();
      return false;
    }
    setMsg('ks', '');
    setMsg('cs', '');
    app.state = s;
    app.lofi.design = design;
    app.surrogate.design = surrogateRow(sur, app.desc);
    // The HiFi readout of the design (about 3 ms) in the same update, so every view
    // follows the slider in one frame; the datum's (once per scenario) and any failure
    // go to the HiFi worker.
    let hifiNow = false;
    if (app.hifi.datumKey === keyOf(datumStateOf(s, app.desc))) {
      try {
        app.hifi.design = await app.engine.call('analyse', s, 'full');
        app.hifi.key = keyOf(s);
        hifiNow = true;
      } catch {
        hifiNow = false;
      }
    }
    renderDesign(); // every column, the HiFi one current when computed above
    app.metrics.design.push(performance.now() - start);
    if (hifiNow) app.metrics.full.push(performance.now() - start);
    else requestHifi(start);
    return true;
  });
}

/**
 * The HiFi reports of the current design and datum, from the HiFi engine. At most one
 * runs at a time; while it runs, newer requests replace each other (latestOnly).
 */
const hifiRun = latestOnly(async (req) => {
  const dkey = keyOf(req.datumState);
  if (app.hifi.datumKey !== dkey) {
    const datum = await app.hifiEngine.call('analyse', req.datumState, 'full');
    app.hifi.datum = datum;
    app.hifi.datumKey = dkey;
  }
  const design = await app.hifiEngine.call('analyse', req.s, 'full');
  return { ...req, design };
});

function requestHifi(t0) {
  const s = app.state;
  app.pending++;
  hifiRun({ s, key: keyOf(s), datumState: datumStateOf(s, app.desc), t0 })
    .then((r) => {
      if (!r || r.key !== keyOf(app.state)) return; // superseded
      app.hifi.design = r.design;
      app.hifi.key = r.key;
      renderHifi();
      app.metrics.full.push(performance.now() - r.t0);
    })
    .catch((e) => banner(`The HiFi model failed: ${e.message || e}`, 'error'))
    .finally(() => app.pending--);
}

// ---------------------------------------------------------------- rendering

/** The key of everything but the design point (maps, fronts and fits depend on it). */
function scenarioKey(st) {
  return JSON.stringify({ ...st, ks: 0, cs: 0 });
}

/** The key of everything the surrogate's fit depends on. */
function fitKeyOf(st) {
  return JSON.stringify([st.car, st.carJson, st.class, st.speed, st.tracks, st.ksMin, st.ksMax, st.csMin, st.csMax, st.surrogate, st.plan]);
}

/** The map data the maps show for the chosen model: `{maps, datum, kind}` or null while computing. */
function shownMaps() {
  const m = app.view.model;
  const key = scenarioKey(app.state);
  if (m === 'lofi' && app.maps && app.maps.key === key) return { maps: app.maps, datum: app.lofi.datum, kind: 'value' };
  if (m === 'surrogate' && app.surMaps && app.surMaps.key === key) return { maps: app.surMaps, datum: app.surrogate.datum, kind: 'value' };
  const mm = app.modelMaps;
  if (mm && mm.model === m && mm.key === scenarioKey(app.state)) return { maps: mm.maps, datum: mm.datum, kind: m === 'error' ? 'error' : 'value' };
  return null;
}

/** "x % of the box breaks the SWS limit, y % the bounce band" from a map mask. */
function brokenText(maps) {
  const n = maps.nx * maps.ny;
  const parts = [];
  for (const [bit, name] of OBJECTIVE_BITS) {
    let c = 0;
    for (let k = 0; k < n; k++) if (maps.broken[k] & bit) c++;
    if (c) parts.push(`${fmt((100 * c) / n, 3)} % break the ${name}`);
  }
  return parts.join(', ');
}

function renderMaps() {
  const { state, desc } = app;
  const shown = shownMaps();
  const model = app.view.model;
  $('maps-model').textContent = MODEL_NAMES[model];
  const status = $('map-status');
  const road = `class ${state.class} at ${fmtInput(state.speed, 3)} m/s, ${state.tracks} tracks`;
  if (!shown) {
    status.className = 'status';
    if (model !== 'hifi' && model !== 'error') {
      status.textContent = `Computing the ${MODEL_NAMES[model]} maps…`;
      refreshMaps();
      return;
    }
    status.textContent = `Computing the ${MODEL_NAMES[model]} maps (${HIFI_GRIDS[0].nx} × ${HIFI_GRIDS[0].ny}, then ${GRID.nx} × ${GRID.ny}) in the worker…`;
    requestModelMaps();
    return;
  }
  for (const v of app.views) drawMap(v, shown);
  mapStatus(shown);
  renderMarkers();
}

/** One map view from the shown data (`draw` false: data only, drawn by `v.drawBase()`). */
function drawMap(v, shown, draw = true) {
  const { desc } = app;
  v.setData({ maps: shown.maps, box: desc.designBox, swsLimit: desc.swsLimit, scale: app.view.scale, datum: shown.datum, kind: shown.kind }, draw);
}

/** The line under the maps: how much of the box is feasible, what breaks where. */
function mapStatus(shown) {
  const { state } = app;
  const model = app.view.model;
  const status = $('map-status');
  const road = `class ${state.class} at ${fmtInput(state.speed, 3)} m/s, ${state.tracks} tracks`;
  const maps = shown.maps;
  const n = maps.nx * maps.ny;
  const who = `(${MODEL_NAMES[model === 'error' ? 'hifi' : model]}${maps.nx !== GRID.nx ? `, ${maps.nx} × ${maps.ny} grid` : ''})`;
  const timing = app.modelMaps && shown.maps === app.modelMaps.maps ? ` Computed in ${fmt(app.modelMaps.ms, 3)} ms in the worker.` : '';
  if (maps.feasibleCount === n) {
    status.textContent = `Every design in the box meets the design objectives on ${road} ${who}.${timing}`;
    status.className = 'status good';
  } else if (maps.feasibleCount === 0) {
    status.textContent =
      `No design in the box meets the design objectives on ${road} ${who}: the whole map is hatched (${brokenText(maps)}). ` +
      'Try a smoother road, a lower speed or a looser objective.';
    status.className = 'status bad';
  } else {
    status.textContent =
      `${fmt((100 * maps.feasibleCount) / n, 3)} % of the design box meets the design objectives on ${road} ${who}; ${brokenText(maps)}.${timing}`;
    status.className = 'status good';
  }
}

/** A promise that resolves after the next frame has been painted. */
function afterPaint() {
  return new Promise((r) => requestAnimationFrame(() => setTimeout(r, 0)));
}

/**
 * The LoFi (or surrogate) maps of the current scenario, computed and drawn after the
 * next paint and outside the update queue, one map per task: an edit shows its front
 * and readout first, its maps a frame later, and a newer edit never waits for a map. The
 * refresh steps aside while updates are queued and starts again if the state changes
 * under it; it reads the state when it runs. At most one is scheduled.
 */
let mapsJob = null;
function refreshMaps() {
  if (mapsJob) return;
  app.pending++;
  mapsJob = (async () => {
    for (;;) {
      await afterPaint();
      if (queued > 0) continue;
      const s = app.state;
      const key = scenarioKey(s);
      const t0 = performance.now();
      if (!app.maps || app.maps.key !== key) {
        app.maps = { ...(await app.engine.call('lofiMaps', s, GRID.nx, GRID.ny)), key };
      }
      if (app.view.model === 'surrogate' && (!app.surMaps || app.surMaps.key !== key)) {
        app.surMaps = { ...(await app.engine.call('modelMaps', s, 'surrogate', GRID.nx, GRID.ny)), key };
      }
      const shown = shownMaps();
      if (app.state !== s) continue;
      // HiFi and error maps come from the worker; their arrival draws them (renderMaps).
      if (!shown) {
        if (app.view.model === 'hifi' || app.view.model === 'error') return;
        continue;
      }
      let current = true;
      for (const v of app.views) {
        if (app.state !== s || shownMaps()?.maps !== shown.maps) {
          current = false;
          break;
        }
        // Two short tasks per map (data, then drawing), so an edit waits at most one.
        drawMap(v, shown, false);
        await new Promise((r) => setTimeout(r, 0));
        v.drawBase();
        await new Promise((r) => setTimeout(r, 0));
      }
      if (!current || app.state !== s) continue;
      mapStatus(shown);
      renderMarkers();
      app.metrics.maps.push(performance.now() - t0);
      return;
    }
  })()
    .catch((e) => banner(`The maps failed: ${e.message || e}`, 'error'))
    .finally(() => {
      mapsJob = null;
      app.pending--;
    });
}

function renderScenario() {
  const { state } = app;
  // The car editor follows the datum car (only a scenario change can change it), but
  // edits in progress survive changes of road, box or objectives.
  if (JSON.stringify(app.carEditor.car) !== JSON.stringify(app.desc.car)) app.carEditor.show(app.desc.car);
  $('speed-kmh').textContent = `= ${fmt(state.speed * 3.6, 3)} km/h`;
  app.objPlane.drawBase();
  app.frontDrawnAt = performance.now();
  app.frontDraws++;
  renderMaps();
  if (app.view.nsga) requestNsga();
  requestFit();
  renderDesign();
}

/** The HiFi or surrogate-error maps of the current scenario on `grid`, from the worker. */
const modelMapsRun = latestOnly(async ({ s, model, grid }) => {
  const t0 = performance.now();
  const [maps, datum] = await Promise.all([
    app.heavyEngine.call('modelMaps', s, model, grid.nx, grid.ny),
    model === 'hifi' ? app.heavyEngine.call('criteria', { ...s, ks: app.desc.datumKs, cs: app.desc.datumCs }, 'full') : null,
  ]);
  return { s, model, maps, datum, ms: performance.now() - t0 };
});
/** Progressively: each grid of `HIFI_GRIDS` in turn, each drawn when it arrives, while
 * the scenario and model stay those asked for. */
function requestModelMaps(level = 0) {
  const s = app.state;
  const model = app.view.model;
  const current = (r) => r.model === app.view.model && scenarioKey(r.s) === scenarioKey(app.state);
  app.pending++;
  modelMapsRun({ s, model, grid: HIFI_GRIDS[level] })
    .then((r) => {
      if (!r) return;
      app.mapTimes.push(r.ms);
      app.modelMaps = { model: r.model, key: scenarioKey(r.s), maps: r.maps, datum: r.datum, ms: r.ms };
      if (!current(r)) return;
      renderMaps();
      if (level + 1 < HIFI_GRIDS.length) requestModelMaps(level + 1);
    })
    .catch((e) => {
      $('map-status').textContent = `The ${MODEL_NAMES[model]} maps failed: ${e.message || e}`;
      $('map-status').className = 'status bad';
    })
    .finally(() => app.pending--);
}

/** The surrogate's fit report (samples, tuning, metrics on the HiFi grid), from the worker. */
const fitRun = latestOnly((s) => app.heavyEngine.call('surrogateFit', s, VALIDATION_LEVELS).then((r) => ({ s, r })));
function requestFit() {
  const s = app.state;
  const key = fitKeyOf(s);
  if (key === app.fitKey) return;
  $('sur-status').textContent = 'Fitting and validating on the HiFi…';
  app.pending++;
  const t0 = performance.now();
  fitRun(s)
    .then((out) => {
      if (!out || fitKeyOf(out.s) !== fitKeyOf(app.state)) return;
      app.fit = out.r;
      app.fitKey = fitKeyOf(out.s);
      renderMetrics($('sur-metrics'), out.r);
      $('sur-tuning').textContent = tuningText(out.r);
      $('sur-status').textContent = `${out.r.surrogate} on ${out.r.plan}: fitted and validated in ${fmt(performance.now() - t0, 3)} ms (worker).`;
      renderMarkers();
    })
    .catch((e) => {
      $('sur-status').textContent = `The surrogate fit failed: ${e.message || e}`;
    })
    .finally(() => app.pending--);
}

/** Design, datum, pick and sample markers on every map. */
function renderMarkers() {
  const { state, desc, lofi } = app;
  const shown = shownMaps();
  const d = { ks: desc.datumKs, cs: desc.datumCs };
  const samples = app.view.plan && app.fit && app.fitKey === fitKeyOf(state) ? app.fit.samples : null;
  const pick = app.front && !app.front.error ? app.front.study.pick : null;
  const design = app.view.model === 'surrogate' ? app.surrogate.design : lofi.design;
  const datum = app.view.model === 'surrogate' ? app.surrogate.datum : lofi.datum;
  for (const v of app.views) {
    const k = v.crit.key;
    const caption = shown && (app.view.model === 'lofi' || app.view.model === 'surrogate')
      ? MapView.caption(v.crit, design[k], datum[k], app.view.scale)
      : '';
    v.setMarkers({ ks: state.ks, cs: state.cs }, d, caption, { samples, pick });
  }
}

/** The NSGA-II front of the current scenario, from the worker. */
function requestNsga() {
  const s = app.state;
  const scen = (st) => JSON.stringify({ ...st, ks: 0, cs: 0 });
  const key = scen(s);
  $('op-status').textContent = 'NSGA-II running…';
  app.pending++;
  app.heavyEngine
    .call('front', s, 'nsga2', 'surrogate')
    .catch((e) => ({ error: e.message || String(e) }))
    .then((r) => {
      if (key !== scen(app.state)) return; // the scenario changed meanwhile
      app.nsga = r;
      $('op-status').textContent = r.error
        ? `NSGA-II: ${r.error}`
        : `NSGA-II (population 60, 60 generations, seed 1): ${r.study.front.length} points, hypervolume ${fmt(r.study.hypervolume, 4)} vs STM ${app.front && !app.front.error ? fmt(app.front.study.hypervolume, 4) : '–'} (each against its own reference point).`;
      app.objPlane.drawBase();
    })
    .finally(() => app.pending--);
}

/** FRFs and PSDs of the current design (both models, worker), debounced. */
let spectraTimer = null;
const spectraRun = latestOnly((s) => app.heavyEngine.call('spectra', s, NFREQ).then((r) => ({ s, r })));
function requestSpectra() {
  // Spectra depend on the car, road and design only, not on objectives or the surrogate.
  const key = keyOf(app.state) + fitKeyOf(app.state);
  if (key === app.spectraKey) return;
  app.spectraKey = key;
  clearTimeout(spectraTimer);
  if (!spectraTimer) app.pending++;
  spectraTimer = setTimeout(() => {
    spectraTimer = null;
    const s = app.state;
    spectraRun(s)
      .then((out) => {
        if (!out || keyOf(out.s) + fitKeyOf(out.s) !== keyOf(app.state) + fitKeyOf(app.state)) return;
        app.spectra = out.r;
        app.spectraPanel.show(out.r);
        $('sp-status').textContent = `Ks ${fmt(s.ks / 1000, 4)} kN/m, Cs ${fmt(s.cs / 1000, 4)} kNs/m`;
      })
      .catch((e) => {
        app.spectraKey = '';
        $('sp-status').textContent = `Spectra failed: ${e.message || e}`;
      })
      .finally(() => app.pending--);
  }, 60);
}

function renderDesign() {
  const { desc, lofi } = app;
  renderCriteria($('criteria'), 'lofi', lofi.design, lofi.datum, desc.swsLimit);
  renderCriteria($('criteria'), 'sur', app.surrogate.design, app.surrogate.datum, desc.swsLimit);
  renderProps($('ride-props'), lofi.design);
  renderModes($('modes-lofi'), lofi.design.modes);
  renderMarkers();
  app.objPlane.drawOverlay();
  requestSpectra();
  renderTimeStale();
  renderHifi();
  syncInputs();
  scheduleUrl();
}

/** The HiFi column and modes; greyed while they belong to an earlier state. */
function renderHifi() {
  const { desc, lofi, hifi } = app;
  const current = hifiCurrent();
  const datumOk = hifi.datumKey === keyOf(datumStateOf(app.state, desc));
  renderCriteria($('criteria'), 'hifi', hifi.design, datumOk ? hifi.datum : null, desc.swsLimit, !current);
  if (hifi.design) renderModes($('modes-hifi'), hifi.design.modes, !current);
  const f = feasibilityText(lofi.design, current ? hifi.design : null, desc.swsLimit);
  const fe = $('feasibility');
  fe.textContent = f.text;
  fe.className = f.ok ? 'status good' : 'status bad';
  $('route-note').textContent = routeNote(lofi.design, current ? hifi.design : null);
}

/** Puts the state into every control that does not hold a refused entry. */
function syncInputs() {
  const s = app.state;
  const put = (field, id, value) => {
    if (!app.bad.has(field)) $(id).value = value;
  };
  put('ks', 'ks-num', fmtInput(s.ks / 1000, 3));
  put('cs', 'cs-num', fmtInput(s.cs / 1000, 3));
  put('speed', 'speed', fmtInput(s.speed, 3));
  put('class', 'class', s.class);
  put('tracks', 'tracks', s.tracks);
  put('swsLimit', 'sws-limit', s.swsLimit == null ? '' : fmtInput(s.swsLimit * 1000, 4));
  // The SWS slider spans 1 to 20 mm (and the limit, if outside); no limit: its top.
  const swsMm = s.swsLimit == null ? null : s.swsLimit * 1000;
  $('sws-range').min = String(Math.min(1, swsMm ?? 1));
  $('sws-range').max = String(Math.max(20, swsMm ?? 20));
  if (pendingSwsMm === null) $('sws-range').value = String(swsMm ?? $('sws-range').max);
  const box = app.desc.designBox;
  if (!app.bad.has('box')) {
    $('ks-min').value = fmtInput(box.ks_min / 1000, 4);
    $('ks-max').value = fmtInput(box.ks_max / 1000, 4);
    $('cs-min').value = fmtInput(box.cs_min / 1000, 4);
    $('cs-max').value = fmtInput(box.cs_max / 1000, 4);
  }
  // The sliders span the design box (and the design, if it lies outside).
  $('ks-range').min = String(Math.min(box.ks_min, s.ks) / 1000);
  $('ks-range').max = String(Math.max(box.ks_max, s.ks) / 1000);
  $('cs-range').min = String(Math.min(box.cs_min, s.cs) / 1000);
  $('cs-range').max = String(Math.max(box.cs_max, s.cs) / 1000);
  $('ks-range').value = String(s.ks / 1000);
  $('cs-range').value = String(s.cs / 1000);
  for (const [field, lo, hi, band] of [['bounceBand', 'bb-lo', 'bb-hi', s.bounceBand], ['dampingBand', 'db-lo', 'db-hi', s.dampingBand]]) {
    put(field, lo, band ? fmtInput(band[0], 4) : '');
    put(field, hi, band ? fmtInput(band[1], 4) : '');
  }
  const nw = s.noWorse || [false, false, false];
  ['nw-bacc', 'nw-dtl', 'nw-sws'].forEach((id, i) => ($(id).checked = !!nw[i]));
  ensureOption($('sur-approach'), s.surrogate);
  ensureOption($('sur-plan'), s.plan);
  put('surrogate', 'sur-approach', s.surrogate);
  put('plan', 'sur-plan', s.plan);
  ensureCustomOption();
  put('car', 'car', s.car);
  $('map-scale').value = app.view.scale;
  $('map-model').value = app.view.model;
  $('show-plan').checked = app.view.plan;
  $('large').checked = app.view.large;
}

/** Adds `value` to a select's options when a link or session names one not listed. */
function ensureOption(select, value) {
  if (value && ![...select.options].some((o) => o.value === value)) {
    const o = document.createElement('option');
    o.value = value;
    o.textContent = value;
    select.append(o);
  }
}

function ensureCustomOption() {
  const sel = $('car');
  let opt = sel.querySelector('option[value="custom"]');
  if (app.state.car === 'custom') {
    if (!opt) {
      opt = document.createElement('option');
      opt.value = 'custom';
      sel.append(opt);
    }
    opt.textContent = `${app.desc ? app.desc.car.name : 'custom car'} (file)`;
  } else if (opt && !app.custom) {
    opt.remove();
  }
}

// ---------------------------------------------------------------- URL

/** The page-only settings of a fresh view. */
const DEFAULT_VIEW = { scale: 'abs', large: false, model: 'lofi', plan: true };

let urlTimer = null;
let lastHash = '';
function scheduleUrl() {
  clearTimeout(urlTimer);
  urlTimer = setTimeout(writeUrl, 120);
}
function writeUrl() {
  urlTimer = null;
  const hash = encodeHash(app.state, app.view);
  if (hash !== location.hash) {
    lastHash = hash;
    history.replaceState(null, '', hash);
  }
}

/** The state and view a hash asks for, validated; the defaults (and a message) if not. */
async function loadFromHash(hash) {
  const d = decodeHash(hash);
  const fallback = (why) => {
    banner(`This link's view could not be restored (${why}); showing the default view instead.`);
    return { state: { ...app.defaults }, view: { ...DEFAULT_VIEW } };
  };
  if (d.problems.length) return fallback(d.problems.join('; '));
  const s = { ...app.defaults, ...d.state };
  if (s.car !== 'custom') s.carJson = null;
  try {
    // A link without ks or cs means the car's own (datum) front spring or damper.
    if (d.state.ks === undefined || d.state.cs === undefined) {
      const desc = await app.engine.call('describe', { ...s, ks: app.defaults.ks, cs: app.defaults.cs });
      if (d.state.ks === undefined) s.ks = desc.datumKs;
      if (d.state.cs === undefined) s.cs = desc.datumCs;
    }
    await app.engine.call('describe', s);
  } catch (e) {
    return fallback(e.message);
  }
  return { state: s, view: { ...DEFAULT_VIEW, ...d.view } };
}

async function applyLoaded({ state, view }) {
  let r;
  view = { ...app.view, ...view };
  try {
    r = await computeScenario(state);
  } catch (e) {
    // Valid but not computable (a numerical failure): the defaults always are.
    banner(`This view could not be computed (${e.message}); showing the default view instead.`);
    state = { ...app.defaults };
    r = await computeScenario(state);
  }
  if (state.car === 'custom') app.custom = { json: state.carJson, ks: r.desc.datumKs, cs: r.desc.datumCs };
  Object.assign(app, r, { state });
  app.view = view;
  for (const f of Object.keys(FIELD_INPUT)) setMsg(f, '');
  applyLarge();
  renderScenario();
  requestHifi(performance.now());
}

// ---------------------------------------------------------------- controls

function numberField(id, field, toState) {
  const el = $(id);
  el.addEventListener('change', () => {
    const p = parseNumber(el.value);
    if (p.error) {
      setMsg(field, p.error);
      return;
    }
    toState(p.value);
  });
  el.addEventListener('keydown', (ev) => {
    if (ev.key === 'Escape') {
      setMsg(field, '');
      syncInputs();
    }
  });
}

function applyLarge() {
  document.documentElement.classList.toggle('large', app.view.large);
  requestAnimationFrame(() => {
    for (const v of app.views) {
      v.resize();
      v.drawBase();
      v.drawOverlay();
    }
    redrawPanels();
  });
}

function redrawPanels() {
  if (!app.state) return;
  app.objPlane.drawBase();
  if (app.spectra) app.spectraPanel.draw(app.spectra);
  if (app.time) app.timePanel.draw(app.time);
}

function wire() {
  for (const [kind, id] of [['ks', 'ks-range'], ['cs', 'cs-range']]) {
    $(id).addEventListener('input', (ev) => {
      const t0 = performance.now();
      const v = Math.round(Number(ev.target.value) * 1e6) / 1e3;
      const s = app.state;
      if (kind === 'ks') changeDesign(v, s.cs, 'ks', t0);
      else changeDesign(s.ks, v, 'cs', t0);
    });
  }
  numberField('ks-num', 'ks', (v) => changeDesign(Math.round(v * 1e6) / 1e3, app.state.cs, 'ks'));
  numberField('cs-num', 'cs', (v) => changeDesign(app.state.ks, Math.round(v * 1e6) / 1e3, 'cs'));
  numberField('speed', 'speed', (v) => changeScenario({ speed: v }, 'speed'));
  numberField('sws-limit', 'swsLimit', (v) => changeScenario({ swsLimit: v / 1000 }, 'swsLimit'));
  $('sws-range').addEventListener('input', (ev) => dragSwsLimit(Number(ev.target.value)));
  $('class').addEventListener('change', (ev) => changeScenario({ class: ev.target.value }, 'class'));
  $('tracks').addEventListener('change', (ev) => changeScenario({ tracks: ev.target.value }, 'tracks'));
  $('car').addEventListener('change', (ev) => {
    const name = ev.target.value;
    if (name === 'custom') {
      const c = app.custom;
      if (c) changeScenario({ car: 'custom', carJson: c.json, ks: c.ks, cs: c.cs }, 'car');
    } else {
      const p = app.presets.find((x) => x.name === name);
      changeScenario({ car: name, carJson: null, ks: p.ks, cs: p.cs }, 'car');
    }
  });
  $('car-file').addEventListener('change', async (ev) => {
    const file = ev.target.files && ev.target.files[0];
    if (!file) return;
    const text = await file.text();
    let parsed;
    try {
      parsed = await app.engine.call('parseCar', text);
    } catch (e) {
      setMsg('car', `${file.name}: ${e.message}`);
      return;
    }
    const json = JSON.stringify(JSON.parse(text));
    const ok = await changeScenario({ car: 'custom', carJson: json, ks: parsed.ks, cs: parsed.cs }, 'car');
    if (ok) app.custom = { json, ks: parsed.ks, cs: parsed.cs };
    ev.target.value = ''; // the same file can be loaded again after an edit
  });
  $('reset-datum').addEventListener('click', () => changeDesign(app.desc.datumKs, app.desc.datumCs, 'ks'));
  $('map-scale').addEventListener('change', (ev) => {
    app.view.scale = ev.target.value;
    renderMaps();
    scheduleUrl();
  });
  $('map-model').addEventListener('change', (ev) => {
    app.view.model = ev.target.value;
    scheduleUrl();
    renderMaps();
  });
  $('show-plan').addEventListener('change', (ev) => {
    app.view.plan = ev.target.checked;
    renderMarkers();
    scheduleUrl();
  });
  $('sur-approach').addEventListener('change', (ev) => changeScenario({ surrogate: ev.target.value }, 'surrogate'));
  $('sur-plan').addEventListener('change', (ev) => changeScenario({ plan: ev.target.value }, 'plan'));
  const boxEdit = () => {
    const v = {};
    for (const [id, key] of [['ks-min', 'ksMin'], ['ks-max', 'ksMax'], ['cs-min', 'csMin'], ['cs-max', 'csMax']]) {
      const p = parseNumber($(id).value);
      if (p.error) {
        setMsg('box', `${$(id).getAttribute('aria-label')}: ${p.error}`);
        return;
      }
      v[key] = Math.round(p.value * 1e6) / 1e3;
    }
    changeScenario(v, 'box');
  };
  for (const id of ['ks-min', 'ks-max', 'cs-min', 'cs-max']) $(id).addEventListener('change', boxEdit);
  for (const [field, lo, hi] of [['bounceBand', 'bb-lo', 'bb-hi'], ['dampingBand', 'db-lo', 'db-hi']]) {
    const edit = () => {
      const a = $(lo).value.trim();
      const b = $(hi).value.trim();
      if (a === '' && b === '') {
        changeScenario({ [field]: null }, field);
        return;
      }
      if (a === '' || b === '') {
        setMsg(field, 'give both ends of the band, or leave both empty to switch it off');
        return;
      }
      const pa = parseNumber(a);
      const pb = parseNumber(b);
      if (pa.error || pb.error) {
        setMsg(field, pa.error || pb.error);
        return;
      }
      changeScenario({ [field]: [pa.value, pb.value] }, field);
    };
    $(lo).addEventListener('change', edit);
    $(hi).addEventListener('change', edit);
  }
  for (const id of ['nw-bacc', 'nw-dtl', 'nw-sws']) {
    $(id).addEventListener('change', () => {
      const nw = ['nw-bacc', 'nw-dtl', 'nw-sws'].map((x) => $(x).checked);
      changeScenario({ noWorse: nw.some((x) => x) ? nw : null }, 'noWorse');
    });
  }
  $('tour').addEventListener('click', () => app.guide.open());
  $('car-apply').addEventListener('click', async () => {
    const r = app.carEditor.read();
    if (r.error) {
      app.carEditor.mark(r.path);
      setMsg('car', r.error);
      return;
    }
    const json = JSON.stringify(r.car);
    let parsed;
    try {
      parsed = await app.engine.call('parseCar', json);
    } catch (e) {
      app.carEditor.mark(e.message.split(':')[0]);
      setMsg('car', `Car editor: ${e.message}`);
      return;
    }
    app.carEditor.mark('');
    // The design stays where it is; the datum is the edited car's own front.
    const ok = await changeScenario({ car: 'custom', carJson: json }, 'car');
    if (ok) app.custom = { json, ks: parsed.ks, cs: parsed.cs };
  });
  $('car-export').addEventListener('click', () => {
    const car = app.desc.car;
    const name = (car.name || 'car').toLowerCase().replace(/[^a-z0-9]+/g, '-').replace(/^-|-$/g, '');
    download(`${name}.json`, new Blob([JSON.stringify(car, null, 2) + '\n'], { type: 'application/json' }));
  });
  $('large').addEventListener('change', (ev) => {
    app.view.large = ev.target.checked;
    applyLarge();
    scheduleUrl();
  });
  $('copy-link').addEventListener('click', async () => {
    writeUrl();
    const btn = $('copy-link');
    try {
      await navigator.clipboard.writeText(location.href);
      btn.textContent = 'Link copied';
    } catch {
      btn.textContent = 'Copy the address bar';
    }
    setTimeout(() => (btn.textContent = 'Copy link'), 2000);
  });
  $('banner-close').addEventListener('click', () => banner(''));
  wirePanels();
  window.addEventListener('hashchange', () => {
    if (location.hash === lastHash) return;
    enqueue(async () => applyLoaded(await loadFromHash(location.hash)));
  });
  matchMedia(`(resolution: ${window.devicePixelRatio}dppx)`).addEventListener('change', () => {
    for (const v of app.views) v.resize();
    redrawPanels();
  });
  let resizeTimer = null;
  window.addEventListener('resize', () => {
    clearTimeout(resizeTimer);
    resizeTimer = setTimeout(redrawPanels, 150);
  });
}

/** A number field of the time panel: `{value}` (undefined when empty and `optional`) or null after a message. */
function readField(id, field, { optional = false, integer = false, min = 0 } = {}) {
  const text = $(id).value.trim();
  if (optional && text === '') {
    setMsg(field, '');
    return { value: undefined };
  }
  const p = parseNumber(text);
  if (p.error) {
    setMsg(field, p.error);
    return null;
  }
  if (integer && !(Number.isInteger(p.value) && p.value >= 0 && p.value <= 2 ** 32)) {
    setMsg(field, 'must be a whole number ≥ 0');
    return null;
  }
  if (!integer && !(p.value > min)) {
    setMsg(field, `must be > ${min}`);
    return null;
  }
  setMsg(field, '');
  return p;
}

async function runTime() {
  const seed = readField('tp-seed', 'tpSeed', { integer: true });
  const bump = readField('tp-bump', 'tpBump', { optional: true });
  const rebound = readField('tp-rebound', 'tpRebound', { optional: true });
  if (!seed || !bump || !rebound) return;
  if ((bump.value === undefined) !== (rebound.value === undefined)) {
    setMsg(bump.value === undefined ? 'tpBump' : 'tpRebound', 'give both bump and rebound, or neither');
    return;
  }
  const opts = { duration: 10, dt: 0.001, seed: seed.value, f_min: 0.1, f_max: 200, decimate: 10 };
  // With a bump / rebound law the run's Cs is their mean (the core's rule, as in `ridelab simulate`).
  if (bump.value !== undefined) opts.damper = { bump: bump.value * 1000, rebound: rebound.value * 1000 };
  const status = $('tp-status');
  status.textContent = 'Simulating…';
  $('tp-run').disabled = true;
  app.pending++;
  const t0 = performance.now();
  try {
    const s = app.state;
    const r = await app.heavyEngine.call('timeResponse', s, opts);
    app.time = r;
    app.timeKey = JSON.stringify(s);
    $('tp-charts').hidden = false;
    app.timePanel.draw(r);
    renderTimeStale();
    $('tp-play').disabled = false;
    status.textContent = `Done in ${fmt(performance.now() - t0, 3)} ms (${opts.damper ? `asymmetric damper ${fmt(bump.value, 3)} / ${fmt(rebound.value, 3)} kNs/m, so Cs = their mean ${fmt(r.damperRate / 1000, 3)} kNs/m` : 'linear damper'}, seed ${seed.value}).`;
  } catch (e) {
    status.textContent = `The time response failed: ${e.message || e}`;
  } finally {
    $('tp-run').disabled = false;
    app.pending--;
  }
}

/** Says when the time response shown belongs to an earlier design or scenario. */
function renderTimeStale() {
  const el = $('tp-stale');
  if (!app.time) {
    el.textContent = 'Press "Run time response" to simulate the current design.';
    return;
  }
  el.textContent = app.timeKey === JSON.stringify(app.state)
    ? ''
    : 'The time response shown is for an earlier design or road; run it again for the current one.';
}

function stamp() {
  return `${app.state.car}-${app.state.class}-${app.state.speed}ms`;
}

function wirePanels() {
  $('op-scale').addEventListener('change', (ev) => {
    app.objPlane.ratio = ev.target.value === 'ratio';
    app.objPlane.drawBase();
  });
  $('op-nsga').addEventListener('click', () => {
    app.view.nsga = true;
    requestNsga();
  });
  $('op-png').addEventListener('click', () => canvasPng(`ridelab-objective-${stamp()}.png`, $('op-base'), $('op-overlay')));
  // SVG charts are drawn by the core's plotters module on the main thread (it measures
  // text through the page's DOM, which a worker has not).
  const saveSvg = (name, svg) => download(name, new Blob([svg], { type: 'image/svg+xml' }));
  const svgFailed = (e) => banner(`SVG export failed: ${e.message || e}`);
  $('op-svg').addEventListener('click', () =>
    objectiveSvg(app).then((svg) => saveSvg(`ridelab-objective-${stamp()}.svg`, svg)).catch(svgFailed));
  $('svg-all').addEventListener('click', () =>
    allSvgs(app)
      .then(async (list) => {
        // One at a time: a burst of downloads trips the browser's multiple-download guard.
        for (const { name, svg } of list) {
          saveSvg(`ridelab-${name}-${stamp()}.svg`, svg);
          await new Promise((r) => setTimeout(r, 150));
        }
      })
      .catch(svgFailed));
  const fcsv = () => download(`ridelab-front-${stamp()}.csv`, new Blob([frontCsv(app)], { type: 'text/csv' }));
  $('front-csv').addEventListener('click', fcsv);
  $('front-csv2').addEventListener('click', fcsv);
  $('maps-csv').addEventListener('click', () => {
    const shown = shownMaps();
    if (!shown) return;
    const m = app.view.model;
    download(`ridelab-${m}-maps-${stamp()}.csv`, new Blob([mapsCsv(app, m, shown.maps)], { type: 'text/csv' }));
  });
  $('png-all').addEventListener('click', () => {
    canvasPng(`ridelab-objective-${stamp()}.png`, $('op-base'), $('op-overlay'));
    for (const c of document.querySelectorAll('.spectra canvas, .timep canvas')) canvasPng(`ridelab-${c.id}-${stamp()}.png`, c);
    for (const v of app.views) canvasPng(`ridelab-map-${v.crit.key}-${stamp()}.png`, v.base, v.overlay);
  });
  $('session-save').addEventListener('click', () => {
    const session = { ridelab: 'session', version: 1, state: app.state, view: { scale: app.view.scale, large: app.view.large, model: app.view.model, plan: app.view.plan } };
    download(`ridelab-session-${stamp()}.json`, new Blob([JSON.stringify(session, null, 2)], { type: 'application/json' }));
  });
  $('session-load').addEventListener('change', async (ev) => {
    const file = ev.target.files && ev.target.files[0];
    if (!file) return;
    ev.target.value = '';
    let session;
    try {
      session = JSON.parse(await file.text());
      if (!session || session.ridelab !== 'session' || typeof session.state !== 'object') throw new Error('not a RideLab session file');
      await app.engine.call('checkState', session.state);
    } catch (e) {
      setMsg('session', `${file.name}: ${e.message || e}`);
      return;
    }
    setMsg('session', '');
    const view = {
      ...DEFAULT_VIEW,
      scale: session.view?.scale === 'rel' ? 'rel' : 'abs',
      large: !!session.view?.large,
      model: MODEL_NAMES[session.view?.model] ? session.view.model : 'lofi',
      plan: session.view?.plan !== false,
    };
    await enqueue(async () => applyLoaded({ state: { ...session.state }, view }));
  });
  $('tp-run').addEventListener('click', runTime);
  $('tp-play').addEventListener('click', () => app.timePanel.toggle());
}

function buildSelects() {
  buildPickers($('sur-approach'), $('sur-plan'), app.surrogateNames);
  const car = $('car');
  for (const p of app.presets) {
    const o = document.createElement('option');
    o.value = p.name;
    o.textContent = p.label;
    car.append(o);
  }
  const cls = $('class');
  for (const c of app.classes) {
    const o = document.createElement('option');
    o.value = c.name;
    o.textContent = `${c.name}: ${CLASS_WORDS[c.name] || ''} (Gd = ${Math.round(c.gd * 1e6)}e-6 m³)`;
    cls.append(o);
  }
}

// ---------------------------------------------------------------- start

async function main() {
  app.marks = { start: performance.now() };
  // The worker loads its own copy of the module: start it first, in parallel.
  const kind = new URLSearchParams(location.search).get('engine') === 'main' ? 'main' : 'worker';
  // Two workers: one answers the HiFi readout of each design (a few ms) and is never
  // busy with long jobs; the other runs those (HiFi maps, the fit's validation, spectra,
  // time responses, NSGA-II), so a slider move never waits behind them.
  const worker = kind === 'worker' ? createEngine(api, 'worker') : null;
  const heavy = kind === 'worker' ? createEngine(api, 'worker') : null;
  worker?.catch(() => {}); // handled by deferredEngine (falls back to the main thread)
  heavy?.catch(() => {});
  try {
    await init({ module_or_path: new URL('../ridelab_bg.wasm', import.meta.url) });
  } catch (e) {
    fatal(`The ride models (WebAssembly) failed to load: ${e && e.message ? e.message : e}`);
    return;
  }
  app.marks.wasm = performance.now();
  try {
    app.engine = await createEngine(api, 'main');
    app.hifiEngine = worker ? deferredEngine(worker, app.engine) : app.engine;
    app.heavyEngine = heavy ? deferredEngine(heavy, app.engine) : app.engine;
    app.defaults = await app.engine.call('defaultState');
    app.presets = await app.engine.call('presets');
    app.classes = await app.engine.call('roadClasses');
    app.surrogateNames = await app.engine.call('surrogates');
    const version = await app.engine.call('version');
    Promise.resolve(app.hifiEngine.ready).then(() => {
      $('version').textContent = `RideLab ${version}; HiFi model on the ${app.hifiEngine.kind === 'worker' ? 'worker' : 'main'} thread.`;
    });
  } catch (e) {
    fatal(`The ride models could not start: ${e.message || e}`);
    return;
  }
  buildSelects();
  app.objPlane = new ObjectivePlane(app);
  app.spectraPanel = new SpectraPanel(app);
  app.timePanel = new TimePanel(app);
  const grid = $('map-grid');
  app.views = CRITERIA.map((c) => new MapView(grid, c, (ks, cs) => {
    changeDesign(Math.round(ks / 10) * 10, Math.round(cs / 5) * 5, 'ks');
  }));
  app.guide = new Guide($('guide'));
  app.carEditor = new CarEditor($('car-fields'));
  wire();
  $('loading').hidden = true;
  $('app').removeAttribute('aria-busy');
  await enqueue(async () => applyLoaded(await loadFromHash(location.hash)));
  for (const v of app.views) v.resize();
  app.interactiveAt = performance.now();
  // Ready when the HiFi column has arrived too.
  while (!app.isSettled()) await new Promise((r) => setTimeout(r, 5));
  app.ready = true;
  app.readyAt = performance.now();
  app.guide.showIfNew();
  document.documentElement.dataset.ready = '1';
}

main();
