// RideLab page: starts the wasm core and the workers, builds the store, the controller and
// the views, and wires the controls to the controller. The parts:
//   js/compute.js     every call to the core (main thread, HiFi worker, heavy worker)
//   js/store.js       state, view, results, URL
//   js/controller.js  the update queue: what to recompute when
//   js/render.js      store -> views (each view takes plain data)
//   js/testhooks.js   window.__ridelab for the browser tests
//   js/restore.js     links and session files: what of them applies
//   js/panels.js      the panels beyond the first screen, loaded after the first map
//   js/offline.js     the service worker
// "?engine=main" runs everything on the main thread.

import init, * as api from '../ridelab-first.js';
import { createEngine, deferredEngine } from './engine.js';
import { Compute } from './compute.js';
import { Store } from './store.js';
import { Controller } from './controller.js';
import { Render } from './render.js';
import { Controls, fieldName, plainWords } from './controls.js';
import { MapView, CRITERIA } from './mapview.js';
import { ObjectivePlane, frontPointText } from './plane.js';
import { Plot } from './plot.js';
import { Workbench, bindShortcuts } from './workbench.js';
import { buildPickers } from './surrogatepanel.js';
import { UncertaintyPanel } from './uncertaintypanel.js';
import { adaptivePlane } from './chartspecs.js';
import { currentHifiFront } from './hififront.js';
import { loadTables } from './colormap.js';
import { keyStep } from './steps.js';
import { fmt, parseNumber } from './format.js';
import { installTestHooks } from './testhooks.js';
import { pathText, computeMode } from './gpupath.js';
import { keepDesign, renderCompare, savedEntry, MAX_SAVED } from './compare.js';
import { isLessonHash } from './urlstate.js';
import { withLoadCases } from './robustcases.js';
import { registerServiceWorker } from './offline.js';

/** ISO 8608 wording of the classes. */
const CLASS_WORDS = {
  A: 'very good', B: 'good', C: 'average', D: 'poor', E: 'very poor', F: 'bad', G: 'very bad', H: 'extremely bad',
};

const $ = (id) => document.getElementById(id);

/** The buttons js/panels.js wires (a click on one before it has is made again after). */
const EARLY_BUTTONS = ['#lessons-open', '#tour', '#car-apply', '#car-export', '#cf-make', '#cf-copy', '#cf-apply', '#cf-clear', '#tp-run', '#tp-play',
  '#panel-export button', '#lesson button', '#road-box button', '#robust button'].join(', ');

/** Start-up milestones (ms since navigation), read by the tests. */
const boot = { marks: { start: performance.now() }, ready: false, interactiveAt: null, readyAt: null, firstScreenBy: null };

function fatal(controls, text) {
  controls.banner(text, 'error');
  $('loading').hidden = true;
}

/** A number field: Enter or leaving it applies `toState(value)`; Escape restores it. */
function numberField(controls, store, id, field, toState) {
  const el = $(id);
  el.addEventListener('change', () => {
    const p = parseNumber(el.value);
    if (p.error) {
      controls.setMsg(field, `${fieldName(el)}: ${p.error}`);
      return;
    }
    toState(p.value);
  });
  el.addEventListener('keydown', (ev) => {
    if (ev.key === 'Escape') {
      controls.setMsg(field, '');
      controls.sync(store.state, store.desc, store.view);
    }
  });
}

function buildSelects(store) {
  buildPickers($('sur-approach'), $('sur-plan'), store.surrogateNames);
  const car = $('car');
  for (const p of store.presets) {
    const o = document.createElement('option');
    o.value = p.name;
    o.textContent = p.label;
    car.append(o);
  }
  const cls = $('class');
  for (const c of store.classes) {
    const o = document.createElement('option');
    o.value = c.name;
    o.textContent = `${c.name}: ${CLASS_WORDS[c.name] || ''}`;
    o.title = `ISO 8608 class ${c.name}: Gd(n0) = ${Math.round(c.gd * 1e6)}e-6 m³`;
    cls.append(o);
  }
}

/** Wires every control to the controller. */
function wire({ store, controller: ctl, controls, render, ui, bench, compute, panels }) {
  const st = store;
  // Design sliders: pointer and keyboard; keys move on the grid through the datum.
  for (const [axis, id] of [['ks', 'ks-range'], ['cs', 'cs-range']]) {
    const el = $(id);
    el.addEventListener('input', (ev) => {
      // The event's time stamp: when the input happened, before any queueing.
      const t0 = Math.min(performance.now(), ev.timeStamp || performance.now());
      const v = Math.round(Number(el.value) * 1e6) / 1e3;
      const d = ctl.targetDesign();
      if (axis === 'ks') ctl.changeDesign(Math.round(v / 10) * 10, d.cs, 'ks', t0);
      else ctl.changeDesign(d.ks, Math.round(v), 'cs', t0);
    });
    el.addEventListener('keydown', (ev) => {
      const next = keyStep(ev, ctl.targetDesign(), { ks: st.desc.datumKs, cs: st.desc.datumCs }, st.desc.designBox, axis);
      if (!next) return;
      ev.preventDefault();
      ctl.changeDesign(next.ks, next.cs, axis, ev.timeStamp);
    });
  }
  numberField(controls, st, 'ks-num', 'ks', (v) => ctl.changeDesign(Math.round(v * 1e6) / 1e3, st.state.cs, 'ks'));
  numberField(controls, st, 'cs-num', 'cs', (v) => ctl.changeDesign(st.state.ks, Math.round(v * 1e6) / 1e3, 'cs'));
  numberField(controls, st, 'speed', 'speed', (v) => ctl.changeScenario({ speed: v }, 'speed'));
  numberField(controls, st, 'sws-limit', 'swsLimit', (v) => ctl.changeScenario({ swsLimit: v / 1000 }, 'swsLimit'));
  $('sws-range').addEventListener('input', (ev) => ctl.dragSwsLimit(Number(ev.target.value)));
  $('class').addEventListener('change', (ev) => {
    const v = ev.target.value;
    if (v === 'measured') measuredRoad(ui.road.road);
    else ctl.changeScenario({ class: v, roadProfile: null }, 'class');
  });
  /**
   * The road menu on the road panel's `road` (`{name, bytes}`): registered on every thread,
   * then the workbench's state on it; a road the threads refuse keeps the last good state.
   */
  const measuredRoad = async (road) => {
    let key;
    try {
      key = await compute.useRoad(road.bytes, road.name);
    } catch (e) {
      controls.setMsg('class', `${road.name}: ${plainWords(e.message || e)}`);
      controls.sync(st.state, st.desc, st.view);
      return;
    }
    await ctl.changeScenario({ roadProfile: key, cases: null, case: null }, 'class', {
      note: `The workbench is on the measured road ${road.name} at ${fmt(st.state.speed, 3)} m/s: its maps, surrogate, fronts, readout, spectra, time response (the profile played back), adaptive loop and report; load cases need an ISO class.`,
    });
  };
  /** A road read by the road panel: the road menu's last entry; the workbench follows a new file when it is on the last one. */
  ui.onRoad = (road) => {
    const cls = $('class');
    let opt = cls.querySelector('option[value="measured"]');
    if (!opt) {
      opt = document.createElement('option');
      opt.value = 'measured';
      cls.append(opt);
    }
    opt.textContent = `Measured: ${road.name}`;
    opt.title = `The road profile ${road.name} (Car & road tab), shaped at the road speed`;
    if (st.state.roadProfile) measuredRoad(road);
  };
  $('tracks').addEventListener('change', (ev) => ctl.changeScenario({ tracks: ev.target.value }, 'tracks'));
  const moved = (label, ks, cs) => `The design moved to ${label}'s own front (its datum): Ks ${fmt(ks / 1000, 4)} kN/m, Cs ${fmt(cs / 1000, 4)} kNs/m.`;
  $('car').addEventListener('change', (ev) => {
    const name = ev.target.value;
    if (name === 'custom') {
      const c = st.custom;
      if (c) ctl.changeScenario({ car: 'custom', carJson: c.json, ks: c.ks, cs: c.cs }, 'car', { note: moved('the custom car', c.ks, c.cs) });
    } else {
      const p = st.presets.find((x) => x.name === name);
      ctl.changeScenario({ car: name, carJson: null, ks: p.ks, cs: p.cs }, 'car', { note: moved(p.label, p.ks, p.cs) });
    }
  });
  $('car-file').addEventListener('change', async (ev) => {
    const input = ev.target;
    const file = input.files && input.files[0];
    if (!file) return;
    // Cleared first: choosing the same file again (after an error or an edit) is a change.
    input.value = '';
    const text = await file.text();
    let parsed;
    try {
      parsed = await compute.parseCar(text);
    } catch (e) {
      controls.setMsg('carFile', `${file.name}: ${plainWords(e.message)}`);
      return;
    }
    const json = JSON.stringify(JSON.parse(text));
    const change = { car: 'custom', carJson: json, ks: parsed.ks, cs: parsed.cs };
    let note = moved(parsed.car.name, parsed.ks, parsed.cs);
    if (parsed.loadCases.length) {
      // As `ridelab --car FILE`: the file's load cases make the design robust over them.
      // They go into the cases file (the Car & road tab's editor), replacing its own.
      change.cases = withLoadCases(st.state.cases, parsed.loadCases);
      change.case = null;
      note += ` Robust over its ${parsed.loadCases.length} load cases (Car & road tab).`;
    }
    const ok = await ctl.changeScenario(change, 'carFile', {
      note,
      onFail: (e) => controls.setMsg('carFile', `${file.name}: cannot be computed: ${plainWords(e.message)}`),
    });
    if (ok) {
      st.custom = { json, ks: parsed.ks, cs: parsed.cs, origin: 'file', name: parsed.car.name };
      controls.setMsg('carFile', '');
      render.controls();
    }
  });
  const toDatum = () => ctl.changeDesign(st.desc.datumKs, st.desc.datumCs, 'ks');
  const toPick = () => {
    if (st.front && !st.front.error) ctl.changeDesign(st.front.study.pick.ks, st.front.study.pick.cs, 'ks');
  };
  $('reset-datum').addEventListener('click', toDatum);
  $('to-pick').addEventListener('click', toPick);
  const showSaved = () => renderCompare($('compare'), st.saved, {
    onSet: (i) => ctl.changeDesign(st.saved[i].ks, st.saved[i].cs, 'ks'),
    onRemove: (i) => {
      st.saved = st.saved.filter((_, j) => j !== i);
      showSaved();
      st.scheduleUrl();
    },
  });
  /** Keeps the design once its HiFi column is current (js/compare.js). */
  const keep = async () => {
    while (!ctl.isSettled()) await new Promise((r) => setTimeout(r, 20));
    st.saved = keepDesign(st.saved, savedEntry(st.state.ks, st.state.cs, st.lofi.design, st.hifiCurrent() ? st.hifi.design : null, {
      ks: st.desc.datumKs,
      cs: st.desc.datumCs,
      lofi: st.lofi.datum,
      hifi: st.hifiDatumCurrent() ? st.hifi.datum : null,
    }, st.tags.scenario));
    showSaved();
    st.scheduleUrl();
    $('compare-hint').textContent = `${st.saved.length} of ${MAX_SAVED} designs kept; "Keep" again adds the current one (the oldest goes).`;
    $('compare-hint').classList.remove('bad');
  };
  ctl.onSavedChanged = (note, bad = false) => {
    showSaved();
    $('compare-hint').textContent = `${note} "Keep" adds the current design (the oldest goes).`;
    $('compare-hint').classList.toggle('bad', bad);
    if (bad) controls.banner(note);
  };
  $('keep').addEventListener('click', keep);
  $('map-scale').addEventListener('change', (ev) => ctl.setView({ scale: ev.target.value }));
  $('map-model').addEventListener('change', (ev) => ctl.setView({ model: ev.target.value }));
  $('map-palette').addEventListener('change', (ev) => ctl.setView({ palette: ev.target.value }));
  $('show-plan').addEventListener('change', (ev) => ctl.setView({ plan: ev.target.checked }));
  $('op-scale').addEventListener('change', (ev) => ctl.setView({ ratio: ev.target.value === 'ratio' }));
  // The plane's zoom (wheel, drag, keys, reset; js/plane.js) goes into the link as pz=.
  $('op-overlay').addEventListener('planezoom', (ev) => ctl.setView({ planeZoom: ev.detail }));
  $('projector').addEventListener('change', (ev) => ctl.setView({ projector: ev.target.checked }));
  $('op-nsga').addEventListener('click', () => ctl.requestNsga());
  $('ad-next').addEventListener('click', () => ctl.runAdaptive(1));
  $('ad-more').addEventListener('click', () => ctl.runAdaptive(5));
  $('sur-approach').addEventListener('change', (ev) => ctl.changeScenario({ surrogate: ev.target.value }, 'surrogate'));
  $('sur-plan').addEventListener('change', (ev) => ctl.changeScenario({ plan: ev.target.value }, 'plan'));
  const boxEdit = () => {
    const v = {};
    for (const [id, key] of [['ks-min', 'ksMin'], ['ks-max', 'ksMax'], ['cs-min', 'csMin'], ['cs-max', 'csMax']]) {
      const p = parseNumber($(id).value);
      if (p.error) {
        controls.setMsg('box', `${$(id).getAttribute('aria-label')}: ${p.error}`);
        return;
      }
      v[key] = Math.round(p.value * 1e6) / 1e3;
    }
    ctl.changeScenario(v, 'box');
  };
  for (const id of ['ks-min', 'ks-max', 'cs-min', 'cs-max']) $(id).addEventListener('change', boxEdit);
  for (const [field, lo, hi] of [['bounceBand', 'bb-lo', 'bb-hi'], ['dampingBand', 'db-lo', 'db-hi']]) {
    const edit = () => {
      const a = $(lo).value.trim();
      const b = $(hi).value.trim();
      if (a === '' && b === '') {
        ctl.changeScenario({ [field]: null }, field);
        return;
      }
      if (a === '' || b === '') {
        controls.setMsg(field, `${field === 'bounceBand' ? 'Body-bounce band (Hz)' : 'Damping-ratio band'}: give both ends, or leave both empty to switch it off`);
        return;
      }
      const pa = parseNumber(a);
      const pb = parseNumber(b);
      if (pa.error || pb.error) {
        controls.setMsg(field, `${fieldName($(pa.error ? lo : hi))}: ${pa.error || pb.error}`);
        return;
      }
      ctl.changeScenario({ [field]: [pa.value, pb.value] }, field);
    };
    $(lo).addEventListener('change', edit);
    $(hi).addEventListener('change', edit);
  }
  // The comfort measure and the pick rule (issue #16): the core validates both.
  $('comfort').addEventListener('change', (ev) => ctl.changeScenario({ comfort: ev.target.value }, 'comfort'));
  const pickEdit = () => {
    const rule = $('pick-rule').value;
    $('pick-weight').disabled = rule !== 'asf';
    $('pick-weight-out').textContent = `W = ${Number($('pick-weight').value).toFixed(2)}`;
    ctl.changeScenario({ pick: rule === 'asf' ? `asf:${Number($('pick-weight').value)}` : rule }, 'pick');
  };
  $('pick-rule').addEventListener('change', pickEdit);
  $('pick-weight').addEventListener('change', pickEdit);
  $('pick-weight').addEventListener('input', () => ($('pick-weight-out').textContent = `W = ${Number($('pick-weight').value).toFixed(2)}`));
  for (const id of ['nw-bacc', 'nw-dtl', 'nw-sws']) {
    $(id).addEventListener('change', () => {
      const nw = ['nw-bacc', 'nw-dtl', 'nw-sws'].map((x) => $(x).checked);
      ctl.changeScenario({ noWorse: nw.some((x) => x) ? nw : null }, 'noWorse');
    });
  }
  $('copy-link').addEventListener('click', async () => {
    st.writeUrl();
    const btn = $('copy-link');
    try {
      await navigator.clipboard.writeText(location.href);
      btn.textContent = 'Copied';
    } catch {
      btn.textContent = 'Copy the address bar';
    }
    setTimeout(() => (btn.textContent = 'Link'), 2000);
  });
  $('banner-close').addEventListener('click', () => controls.banner(''));
  $('keys').addEventListener('click', () => $('shortcuts').showModal());
  bindShortcuts({
    help: () => $('shortcuts').showModal(),
    tab: (i) => bench.tabs[i]?.click(),
    datum: toDatum,
    pick: toPick,
    keep,
    map: () => ui.maps[0].surface.focus(),
    projector: () => ctl.setView({ projector: !st.view.projector }),
    lesson: () => panels.then(() => ui.lessons.open()),
    escape: () => (ui.guide?.isOpen ? ui.guide.close() : bench.close()),
  });
  window.addEventListener('hashchange', () => {
    if (location.hash === st.lastHash) return;
    if (isLessonHash(location.hash)) panels.then(() => ui.lessons.openLink(location.hash));
    else ctl.loadHash(location.hash);
  });
  matchMedia(`(resolution: ${window.devicePixelRatio}dppx)`).addEventListener('change', () => render.redrawAll());
  // The plane and the panels follow the size of their boxes (window, drawer, type). The
  // observer's first report, of the size the plane was just drawn at, redraws nothing.
  let resizeTimer = null;
  const later = () => {
    clearTimeout(resizeTimer);
    resizeTimer = setTimeout(() => render.redrawAll(), 100);
  };
  new ResizeObserver(() => {
    if (!ui.plane.base.fitsBox()) later();
  }).observe($('op-wrap'));
  window.addEventListener('resize', later);
}

/** The data of the chart exports (js/svgexport.js `exportCharts`). */
function exportDataOf(store, ui) {
  const st = store;
  return {
    state: st.state,
    front: st.front,
    nsga: st.nsga,
    cloud: st.cloud,
    design: st.plane.design,
    ratio: st.view.ratio,
    adaptive: adaptivePlane(st.adaptive),
    hifi: currentHifiFront(st),
    spectra: st.spectra,
    time: st.time ? st.time.result : null,
    timeLinear: st.time ? st.time.linear : null,
    views: ui.maps,
    model: st.view.model,
  };
}

// ---------------------------------------------------------------- start

async function main() {
  const controls = new Controls();
  const kind = new URLSearchParams(location.search).get('engine') === 'main' ? 'main' : 'worker';
  // Two modules of the core (issue #29): this thread's first screen runs on the small
  // ridelab-first.js; the workers, and this thread's on-demand calls (an SVG export, or
  // everything when a worker cannot start), on ridelab.js, which has every part.
  const loadOnDemand = () => import('../ridelab.js').then(async (full) => {
    await full.default({ module_or_path: new URL('../ridelab_bg.wasm', import.meta.url) });
    return full;
  });
  // Two workers: one answers the HiFi readout of each design (a few ms) and is never busy
  // with long jobs; the other runs those, so a slider move never waits behind them. They
  // start once the first screen is painted (the first map drawn, or the maps fail; with
  // HiFi or error maps, which only they draw, the plane and readout), or 5 s after the
  // module is up, so this thread's module loads and compiles alone; their calls wait until
  // then. `boot.firstScreenBy` says which came first ('page' or 'timeout').

  // A crashed worker is replaced and its requests run again (js/engine.js); the page says so.
  let firstScreenDone;
  const firstScreen = new Promise((resolve) => {
    firstScreenDone = (by) => {
      boot.firstScreenBy ??= by;
      resolve();
    };
  });
  const onRestart = (name) => ({ reason, retried, failed }) => controls.banner(
    `The ${name} worker stopped (${reason}) and was restarted.` +
    `${retried ? ` ${retried} request${retried === 1 ? ' was' : 's were'} run again.` : ''}` +
    `${failed ? ` ${failed} request${failed === 1 ? '' : 's'} crashed it twice and ${failed === 1 ? 'was' : 'were'} given up (its panel says so).` : ''}`,
    failed ? 'error' : 'warn');
  const afterFirstScreen = (options) => firstScreen.then(() => createEngine(api, 'worker', options));
  const worker = kind === 'worker' ? afterFirstScreen({ onRestart: onRestart('HiFi') }) : null;
  const heavy = kind === 'worker' ? afterFirstScreen({ gpu: computeMode(location.search), onRestart: onRestart('background') }) : null;
  worker?.catch(() => {}); // handled by deferredEngine (falls back to the main thread)
  heavy?.catch(() => {});
  // The page's objects that need no core are built while the wasm downloads, the three map
  // views among them: their figures are laid out then, not in the task that draws the first
  // maps (on a slow link the wasm is the last file to arrive).
  const store = new Store();
  let compute;
  let controller = null;
  const datumOf = () => ({ ks: store.desc.datumKs, cs: store.desc.datumCs });
  const onMapKey = (ev) => {
    const next = keyStep(ev, controller.targetDesign(), datumOf(), store.desc.designBox);
    if (!next) return false;
    controller.changeDesign(next.ks, next.cs, 'ks', ev.timeStamp);
    return true;
  };
  // The callbacks of every map view (the three maps, the uncertainty map, the road panel's).
  const mapHooks = {
    onPick: (ks, cs) => controller.changeDesign(Math.round(ks / 10) * 10, Math.round(cs / 5) * 5, 'ks'),
    onKey: onMapKey,
    contours: (field, nx, ny, levels) => compute.contours(field, nx, ny, levels),
    get objectives() {
      return store.objectives;
    },
  };
  const maps = CRITERIA.map((c) => new MapView($('map-grid'), c, mapHooks));
  try {
    await init({ module_or_path: new URL('../ridelab-first_bg.wasm', import.meta.url) });
  } catch (e) {
    fatal(controls, `The ride models (WebAssembly) failed to load: ${e && e.message ? e.message : e}`);
    return;
  }
  setTimeout(() => firstScreenDone('timeout'), 5000);
  boot.marks.wasm = performance.now();
  try {
    const main = await createEngine(api, 'main', { loadOnDemand });
    const hifi = worker ? deferredEngine(worker, main) : main;
    compute = new Compute(api, { main, hifi, heavy: heavy ? deferredEngine(heavy, main) : main });
    Object.assign(store, await compute.boot());
    compute.gpuStatus().then((g) => {
      // Until a HiFi map says otherwise (a GPU failure), the path the GPU status gives.
      if (!$('compute-path').textContent) $('compute-path').textContent = `HiFi maps: ${pathText(g.adapter ? 'gpu' : 'cpu', g)}.`;
    });
    Promise.resolve(hifi.ready).then(() => {
      $('version').textContent = `RideLab ${store.version}; HiFi model on the ${hifi.kind === 'worker' ? 'worker' : 'main'} thread.`;
    });
  } catch (e) {
    fatal(controls, `The ride models could not start: ${e.message || e}`);
    return;
  }
  buildSelects(store);
  const ui = {
    controls,
    tables: loadTables((name) => compute.colourTable(name)),
    maps,
    plane: new ObjectivePlane({ base: $('op-base'), overlay: $('op-overlay'), wrap: $('op-wrap'), msg: $('op-msg') }, (p, sel) => {
      controller.changeDesign(p.ks, p.cs, 'ks');
      $('op-status').textContent = frontPointText(store.front, sel.index);
    }),
    adaptiveChart: new Plot($('ad-chart'), { aspect: 0.5 }),
    uncertainty: new UncertaintyPanel({ box: $('ad-unc-box'), select: $('ad-unc-crit'), maps: $('ad-unc-map'), caption: $('ad-unc-caption') }, mapHooks),
  };
  const render = new Render(store, ui);
  const redraw = () => requestAnimationFrame(() => render.redrawAll());
  controller = new Controller(store, compute, render, controls);
  controller.onFirstMap = () => firstScreenDone('page');
  const bench = new Workbench({
    bench: $('app'),
    drawer: $('drawer'),
    tabs: [...document.querySelectorAll('.tabs [role="tab"]')],
    close: $('drawer-close'),
    onResize: () => redraw(),
  });
  // The panels beyond the first screen (js/panels.js: the drawer's spectra, time, car, road,
  // export and class-front panels, the tour and the lessons) load once the first map is
  // drawn; until then their charts are not drawn, and a click on one of their buttons is
  // held and made again once they are (EARLY_BUTTONS).
  const panels = firstScreen
    .then(() => import('./panels.js'))
    .then(({ startPanels }) => startPanels({ store, controller, compute, render, controls, ui, hooks: mapHooks, exportData: () => exportDataOf(store, ui), redraw }));
  panels.catch((e) => controls.banner(`Some panels failed to load (${e.message || e}); reload the page to use them.`, 'error'));
  const early = (ev) => {
    const button = ev.target.closest(EARLY_BUTTONS);
    if (!button) return;
    ev.preventDefault();
    ev.stopPropagation();
    panels.then(() => button.click(), () => {});
  };
  document.addEventListener('click', early, true);
  panels.finally(() => document.removeEventListener('click', early, true)).catch(() => {});
  controller.onViewsChanged = () => {
    ui.lessons?.viewsChanged();
    ui.classFront?.viewsChanged();
    ui.road?.viewsChanged();
  };
  installTestHooks({ store, controller, compute, ui, boot, exportData: () => exportDataOf(store, ui) });
  wire({ store, controller, controls, render, ui, bench, compute, panels });
  $('loading').hidden = true;
  $('app').removeAttribute('aria-busy');
  // A lesson link opens on the default view; the lesson's first step sets its own.
  const lessonLink = isLessonHash(location.hash) ? location.hash : null;
  await controller.enqueue(async () => controller.load(await controller.fromHash(lessonLink ? '' : location.hash)));
  for (const v of ui.maps) v.resize();
  boot.interactiveAt = performance.now();
  // Ready when the HiFi column has arrived too, and the panels beyond the first screen.
  while (!controller.isSettled()) await new Promise((r) => setTimeout(r, 5));
  try {
    await panels;
  } catch {
    return; // the banner says so
  }
  boot.ready = true;
  boot.readyAt = performance.now();
  if (lessonLink) ui.lessons.openLink(lessonLink);
  // A new visitor's tour, unless a lesson is already open (Lessons clicked during the load).
  else if (!ui.lessons.isOpen) ui.guide.showIfNew();
  document.documentElement.dataset.ready = '1';
  registerServiceWorker(controls, (what) => ui.lessons.own.mayLeave(what));
}

main();
