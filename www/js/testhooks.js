// What the browser tests read: `window.__ridelab`, a window onto the store, the views,
// the controller's counters and the engines. Nothing in the page reads it.

/** Installs `window.__ridelab` over the page's parts (`parts`: see js/app.js). */
export function installTestHooks({ store, controller, compute, ui, boot, exportData }) {
  const hooks = {
    /** Milestones, ms since navigation: script start, wasm ready; interactive (maps drawn) and ready (HiFi too). */
    marks: boot.marks,
    get ready() {
      return boot.ready;
    },
    get interactiveAt() {
      return boot.interactiveAt;
    },
    get readyAt() {
      return boot.readyAt;
    },
    /** What started the workers: 'page' (its first screen painted) or 'timeout' (the 5 s fallback). */
    get firstScreenBy() {
      return boot.firstScreenBy;
    },
    /** When the first map was drawn, ms since navigation. */
    get firstMapAt() {
      return controller.counters.firstMapAt;
    },
    /** True when every view shows the current state and nothing is queued. */
    isSettled: () => controller.isSettled(),
    // The store's data.
    get state() {
      return store.state;
    },
    /** The core's tags of the state (js/store.js `tags`): what every result is keyed by. */
    get tags() {
      return store.tags;
    },
    get view() {
      return store.view;
    },
    get desc() {
      return store.desc;
    },
    get presets() {
      return store.presets;
    },
    /** The measured road (js/roadpanel.js): `{name, desc, on, key, timing}` (`on`: the design and datum on it; `timing`: the file's description and judgement, ms), or null. */
    get road() {
      const r = ui.road && ui.road.road;
      return r ? { name: r.name, desc: r.desc, on: ui.road.judged && ui.road.judged.on, key: ui.road.judged && ui.road.judged.key, timing: ui.road.timing } : null;
    },
    /** The maps and front on the measured road (js/roadstudy.js): `{key, model, name, map, front, timing}` (`map`, `front`: the core's `roadMap`, `roadFront`), or null. */
    get roadStudy() {
      const sh = ui.road && ui.road.study && ui.road.study.shown;
      return sh ? { key: sh.key, model: sh.model, name: sh.name, map: sh.map, front: sh.front, status: document.getElementById('road-study-status').textContent, timing: ui.road.study.timing } : null;
    },
    /** The class front (js/classfront.js): `{key, rows, problems}` or null. */
    get classFront() {
      return store.classFront;
    },
    get lofi() {
      return store.lofi;
    },
    /** With robust cases, the design's criteria as the LoFi maps show them. */
    get mapDesign() {
      return store.mapDesign;
    },
    get hifi() {
      return store.hifi;
    },
    get surrogate() {
      return store.surrogate;
    },
    get maps() {
      return store.maps;
    },
    get surMaps() {
      return store.surMaps;
    },
    get modelMaps() {
      return store.modelMaps;
    },
    get cloud() {
      return store.cloud;
    },
    get front() {
      return store.front;
    },
    get nsga() {
      return store.nsga;
    },
    /** The HiFi's own front and the plane's judged on it (js/store.js `hifiFront`) or null. */
    get hifiFront() {
      return store.hifiFront;
    },
    get fit() {
      return store.fit;
    },
    /** The adaptive HiFi loop of the Surrogate tab (js/store.js `adaptive`) or null. */
    get adaptive() {
      return store.adaptive;
    },
    get spectra() {
      return store.spectra;
    },
    /** The time response shown (`timeResponse` result) or null. */
    /** The designs kept to compare (js/compare.js). */
    get saved() {
      return store.saved;
    },
    get time() {
      return store.time ? store.time.result : null;
    },
    // The views.
    views: ui.maps,
    /** The objective plane (js/plane.js): `data` is what it drew last, `animating` and `moved` its adaptive move. */
    objPlane: ui.plane,
    /** The adaptive loop's uncertainty map (js/uncertaintypanel.js). */
    uncertaintyPanel: ui.uncertainty,
    // The panels loaded after the first map (js/panels.js): undefined until then.
    get spectraPanel() {
      return ui.spectra;
    },
    get timePanel() {
      return ui.time;
    },
    get damperChart() {
      return ui.damper;
    },
    /** The lesson panel (js/lessonpanel.js). */
    get lessons() {
      return ui.lessons;
    },
    // The controller's measurements.
    metrics: controller.metrics,
    counters: controller.counters,
    get frontDraws() {
      return controller.counters.frontDraws;
    },
    // The engines and the raw wasm module.
    api: compute.api,
    /** The main thread's `Explorer` session moved to `state` (the engine's own: see js/engine.js `Host`). */
    session: (state) => compute.main.host.at(state),
    /** The same on the main thread's on-demand module (ridelab.js: loaded at the first call), a promise. */
    onDemandSession: (state) => compute.main.full().then((host) => host.at(state)),
    /** The on-demand module itself, a promise (the first screen's is `api`). */
    onDemandApi: () => compute.main.full().then((host) => host.api),
    engine: compute.main,
    heavyEngine: compute.heavy,
    hifiEngine: compute.hifi,
    /** The data the chart exports are made of (js/svgexport.js `exportCharts`). */
    exportData,
    /** SVG of a chart spec (`kind`: 'line' or 'map'), as the export buttons make it. */
    svg: (kind, spec) => compute.svg(kind, spec),
  };
  window.__ridelab = hooks;
}
