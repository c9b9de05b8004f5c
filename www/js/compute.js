// The one place the page calls the wasm core. Each method is one question the page asks
// ("the reports of this scenario", "the HiFi maps", ...) and routes it to the engine it
// belongs on (js/engine.js): the LoFi work and the maps on the main thread (`main`, well
// under a millisecond a design), the HiFi readout on the HiFi worker (`hifi`, never busy
// with long jobs), long jobs on the heavy worker (`heavy`: HiFi maps, the fit's
// validation, spectra, time responses, NSGA-II). Each engine holds one `Explorer` session
// of the core, which keeps fits and maps; a call passes the view's state and the engine
// moves its session there by the smallest setter (js/engine.js `Host`).


/** LoFi and surrogate map resolution (cells); the image is scaled smoothly onto the plot. */
export const GRID = { nx: 160, ny: 120 };
/** HiFi and surrogate-error map resolution (worker): the LoFi maps' own, since the
 * residue route makes a 160 x 120 HiFi map cost about 0.1 s in the worker. */
export const HIFI_GRID = GRID;
/** The surrogate's feasible set on the objective plane (about 7000 designs). */
const CLOUD_GRID = { nx: 96, ny: 72 };
/** Side of the HiFi grid the surrogate panel validates the fit on. */
export const VALIDATION_LEVELS = 20;
/** The adaptive loop's uncertainty map (cells; heavy worker, about 5000 estimates). */
const UNCERTAINTY_GRID = { nx: 80, ny: 60 };
/** The maps on a measured road (cells; heavy worker, 4 800 runs of the exact route with the road's filters). */
const ROAD_MAP_GRID = { nx: 80, ny: 60 };
/** Frequencies of the FRF / PSD plots (log spaced, 0.1..100 Hz). */
const NFREQ = 240;
/** The time panel's run: 10 s at 1 ms, every 10th sample kept (the seed and damper are the user's). */
const TIME_RUN = { duration: 10, dt: 0.001, f_min: 0.1, f_max: 200, decimate: 10 };

/**
 * The model of the objective plane (its feasible set, front, pick and design marker) for
 * state `s`: the surrogate, or with Wk comfort the LoFi (the surrogates are fitted to the
 * unweighted BAcc; the core refuses a Wk front on them, as `ridelab optimize` does); with
 * robust cases (`s.cases`) the LoFi's robust objective, "robust" (the surrogate is fitted
 * to one case; the core refuses its front naming `cases`, and `ridelab optimize --cases`
 * optimises the quarter car's robust objective).
 */
export function planeModel(s) {
  if (s.cases) return 'robust';
  return s.comfort === 'wk' ? 'lofi' : 'surrogate';
}

/**
 * With robust cases (`s.cases`), the design's criteria as the LoFi maps show them (the
 * robust map's, or with `case` K that case's: the core's `mapCriteria`), for the maps'
 * captions; null without cases (the captions read the LoFi report).
 */
function mapDesignOf(main, s) {
  return s.cases ? main.call('mapCriteria', s, 'lofi') : Promise.resolve(null);
}

export class Compute {
  /**
   * `api`: the wasm module (synchronous calls that need no engine: colour tables);
   * `engines`: `{main, hifi, heavy}` (js/engine.js; the workers may fall back to main).
   */
  constructor(api, { main, hifi, heavy }) {
    this.api = api;
    this.main = main;
    this.hifi = hifi;
    this.heavy = heavy;
  }

  /** What the page needs once: defaults, presets, road classes, surrogate names, the design objectives by mask bit, version. */
  async boot() {
    const call = (m) => this.main.call(m);
    return {
      defaults: await call('defaultState'),
      presets: await call('presets'),
      classes: await call('roadClasses'),
      surrogateNames: await call('surrogates'),
      objectives: await call('objectives'),
      version: await call('version'),
    };
  }

  /** The 256-entry RGB table of a colour map (`Uint8Array` of 768 bytes). */
  colourTable(name) {
    return this.api.colourTable(name);
  }

  /**
   * Contour segments of one map plane (`field`, `nx x ny` cell centres) at each finite
   * level: `Float64Array`s `[x0, y0, x1, y1, ...]` in grid coordinates, by the core's
   * marching squares, so the screen's lines are the exported charts' (main thread).
   */
  contours(field, nx, ny, levels) {
    return this.api.contourSegments(field, nx, ny, Float64Array.from(levels.filter(Number.isFinite)));
  }

  /** The damper law's force-velocity line to `vMax` m/s: `{points: [[v m/s, f N]], linearRate N s/m}` (main thread: a few points). */
  damperCurve(law, vMax) {
    return this.api.damperCurve(law, vMax);
  }

  describe(s) {
    return this.main.call('describe', s);
  }

  checkState(s) {
    return this.main.call('checkState', s);
  }

  parseCar(json) {
    return this.main.call('parseCar', json);
  }

  /**
   * Everything on the main thread that depends on car, road, objectives, box and
   * surrogate, plus the design, except the maps: LoFi reports, the surrogate (fitted
   * once, then kept by the core), the objective plane's feasible set, STM front (`{error}`
   * when none is feasible) and the design's criteria (`plane: {model, design}`), on the
   * plane's model (`planeModel`). With `plane` false the feasible set and the front are
   * left out (`cloud` and `front` null: `planeParts` computes them). Rejects with
   * `{message, field}` on a bad state.
   */
  async scenario(s, { plane: withPlane = true } = {}) {
    const main = this.main;
    const desc = await main.call('describe', s);
    const ds = { ...s, ks: desc.datumKs, cs: desc.datumCs };
    const plane = planeModel(s);
    const [datum, design, sDatum, sDesign, pDesign, mapDesign] = await Promise.all([
      main.call('analyse', ds, 'lofi'),
      main.call('analyse', s, 'lofi'),
      main.call('criteria', ds, 'surrogate'),
      main.call('criteria', s, 'surrogate'),
      plane === 'surrogate' ? null : main.call('criteria', s, plane),
      mapDesignOf(main, s),
    ]);
    const { cloud, front } = withPlane ? await this.planeParts(s) : { cloud: null, front: null };
    const row = (c) => ({ ...c, dtl_relative: c.dtl / desc.staticWheelLoad });
    return {
      desc,
      lofi: { datum, design },
      surrogate: { datum: row(sDatum), design: row(sDesign) },
      cloud,
      front,
      plane: { model: plane, design: pDesign || sDesign },
      mapDesign,
    };
  }

  /**
   * The objective plane's feasible set (`cloud`: the criteria on CLOUD_GRID by the
   * plane's model) and STM front (`{error}` when none is feasible) of scenario `s`.
   */
  async planeParts(s) {
    const cloud = await this.main.call('maps', s, planeModel(s), CLOUD_GRID.nx, CLOUD_GRID.ny);
    let front;
    try {
      front = await this.front(s, 'stm');
    } catch (e) {
      // Not a bad input (the state passed describe): no feasible design, or a numerical failure.
      front = { error: e.message || String(e) };
    }
    return { cloud, front };
  }

  /**
   * A new design point of the same scenario: its LoFi report, surrogate criteria and
   * criteria by the objective plane's model (`plane`), and with `withHifi` its HiFi
   * readout too (the report without its frequency-route check, about 0.1 ms, on the main
   * thread so every view follows the slider in one frame; null when it fails), the LoFi's
   * a readout too (the report's numbers without its frequency-route check), all in one
   * wasm call (`designStep`, after the session's `setState`; with robust cases one more
   * for the maps' criteria), with the session's `tags` there. Both full reports follow
   * from the HiFi worker once the design rests (`designReports`).
   */
  async design(s, desc, withHifi) {
    const r = await this.main.call('designStep', s, planeModel(s), withHifi);
    const mapDesign = await mapDesignOf(this.main, s);
    const sur = r.surrogate;
    return { lofi: r.lofi, surrogate: { ...sur, dtl_relative: sur.dtl / desc.staticWheelLoad }, plane: r.plane ?? sur, hifi: r.hifi, mapDesign, tags: r.tags };
  }

  /** A HiFi report on the HiFi worker (`s`: the datum's state; a design's come with `designReports`). */
  hifiReport(s) {
    return this.hifi.call('analyse', s, 'hifi');
  }

  /**
   * The design's full reports by both models, `{lofi, hifi}`, in one call on the HiFi
   * worker: a slider step shows their readouts (`design`), and the reports' frequency-
   * route checks follow once the design rests.
   */
  designReports(s) {
    return this.hifi.call('designReports', s);
  }

  /** The LoFi maps of the scenario at the page's grid (main thread). */
  lofiMaps(s) {
    return this.main.call('maps', s, 'lofi', GRID.nx, GRID.ny);
  }

  /** The surrogate's maps of the scenario at the page's grid (main thread, fit kept). */
  surrogateMaps(s) {
    return this.main.call('maps', s, 'surrogate', GRID.nx, GRID.ny);
  }

  /**
   * Offers the heavy engine the main thread's surrogate fit of `s` (whose fit tag, the
   * core's, is `fitTag`), before a call that needs the surrogate, once per fit: the worker
   * adopts it instead of fitting again, so a scenario change costs the page one fit
   * (issue #28). The main thread fits for its plane anyway; a state it cannot fit is left
   * to the call's own error.
   */
  shareFit(s, fitTag) {
    const key = fitTag;
    if (this.sharedFit?.key !== key) {
      const done = this.main.call('fitRecord', s).then(
        (record) => record && this.heavy.call('offerFit', record).catch(() => {}),
        () => {},
      );
      this.sharedFit = { key, done };
    }
    return this.sharedFit.done;
  }

  /** The HiFi or surrogate-error maps (`model`) at the HiFi grid, with the HiFi datum's criteria (heavy worker; `fitTag`: see `shareFit`). */
  async modelMaps(s, fitTag, model, datumState) {
    if (model === 'error') await this.shareFit(s, fitTag);
    const [maps, datum] = await Promise.all([
      this.heavy.call('maps', s, model, HIFI_GRID.nx, HIFI_GRID.ny),
      model === 'hifi' ? this.heavy.call('criteria', datumState, 'hifi') : null,
    ]);
    return { maps, datum };
  }

  /**
   * The GPU path of the HiFi maps (heavy worker, js/gpupath.js): `{adapter, reason,
   * failure}` once the GPU is open (`adapter` its name) or refused (`reason`). Without
   * the worker the CPU draws them.
   */
  gpuStatus() {
    return this.heavy.call('gpuStatus').catch(() => ({ adapter: null, reason: 'no WebGPU adapter: the HiFi maps are drawn on the main thread', failure: null }));
  }

  /**
   * The HiFi's own front (STM on the full car, the plane's grid and levels; STM's
   * starting grid on the GPU when the worker has one) and the plane's front judged on it:
   * both hypervolumes against the HiFi front's reference point and the HiFi runs each
   * took (heavy worker; `{error}` when none is feasible).
   */
  async hifiFront(s, fitTag) {
    await this.shareFit(s, fitTag);
    return this.heavy.call('hifiFront', s).catch((e) => ({ error: e.message || String(e) }));
  }

  /** The surrogate's fit report, validated on the HiFi grid (heavy worker). */
  async fit(s, fitTag) {
    await this.shareFit(s, fitTag);
    return this.heavy.call('surrogateFit', s, VALIDATION_LEVELS);
  }

  /**
   * The plane's front by `method` ("stm": main thread, "nsga2": heavy worker); with robust
   * cases the robust front (`robustFront`) in a worker, whose module has the robust
   * optimiser (the first-screen wasm leaves it out, issue #29): STM on the HiFi worker,
   * which no long job holds up, NSGA-II on the heavy one.
   */
  front(s, method) {
    const plane = planeModel(s);
    const stm = method === 'stm';
    if (plane === 'robust') return (stm ? this.hifi : this.heavy).call('robustFront', s, method, plane);
    return (stm ? this.main : this.heavy).call('front', s, method, plane);
  }

  /** The seeded NSGA-II front on the plane's model (heavy worker; `{error}` when none is feasible). */
  async nsga(s, fitTag) {
    await this.shareFit(s, fitTag);
    return this.front(s, 'nsga2').catch((e) => ({ error: e.message || String(e) }));
  }

  /** The study report of the view, `{title, html, markdown}`, as `ridelab report` writes it (heavy worker; seconds). */
  report(s) {
    return this.heavy.call('studyReport', s);
  }

  /**
   * Starts the adaptive HiFi loop on the scenario of `s` (its plan on the HiFi, the fit,
   * the front, the first proposal; heavy worker, where the run stays): see js/engine.js
   * `Host.adaptiveStart`. The options are the core's defaults, as `ridelab surrogate
   * --adaptive K` without further flags.
   */
  adaptiveStart(s) {
    return this.heavy.call('adaptiveStart', s, null);
  }

  /** One more HiFi run of the loop started for the scenario of `s`, the refit and the new proposal (heavy worker). */
  adaptiveStep(s) {
    return this.heavy.call('adaptiveStep', s);
  }

  /** The loop so far: samples with reasons and the history of fronts (heavy worker). */
  adaptiveReport(s) {
    return this.heavy.call('adaptiveReport', s);
  }

  /**
   * The adaptive loop's uncertainty map at UNCERTAINTY_GRID and how well it predicts the
   * true error on the VALIDATION_LEVELS HiFi grid (heavy worker; the first call runs that
   * grid on the HiFi): js/engine.js `Host.adaptiveUncertainty`.
   */
  adaptiveUncertainty(s) {
    return this.heavy.call('adaptiveUncertainty', s, UNCERTAINTY_GRID.nx, UNCERTAINTY_GRID.ny, VALIDATION_LEVELS);
  }

  /**
   * Registers the road profile `bytes` (named `file`) on every thread for the road menu;
   * resolves to its key, the state's `roadProfile` that puts the workbench on it (the
   * core shapes it at the state's speed and tracks). Rejects with `{message, field: 'road'}`.
   */
  async useRoad(bytes, file) {
    const engines = [...new Set([this.main, this.hifi, this.heavy])];
    const keys = await Promise.all(engines.map((e) => e.call('useRoad', bytes, file)));
    return keys[0];
  }

  /** A road profile file's bytes described (`ridelab road FILE --json`; heavy worker). */
  describeRoad(bytes) {
    return this.heavy.call('describeRoad', bytes);
  }

  /** The design of `s` and its datum on the road profile `bytes` (named `file`), both models (`ridelab eval --road FILE`; heavy worker). */
  designOnRoad(s, bytes, file) {
    return this.heavy.call('designOnRoad', s, bytes, file);
  }

  /**
   * The maps of `model` ('lofi' or 'hifi') on the road profile `bytes` (named `file`) over
   * ROAD_MAP_GRID cells of the design box of `s` (`ridelab map --road FILE`; heavy worker).
   */
  roadMap(s, bytes, file, model) {
    return this.heavy.call('roadMap', s, bytes, file, model, ROAD_MAP_GRID.nx, ROAD_MAP_GRID.ny);
  }

  /** The Pareto front of `model` on the road profile `bytes` (named `file`) and its pick (`ridelab optimize --road FILE`; heavy worker). */
  roadFront(s, bytes, file, model) {
    return this.heavy.call('roadFront', s, bytes, file, model);
  }

  /** FRFs and PSDs of the design (heavy worker). */
  async spectra(s) {
    await this.shareFit(s);
    return this.heavy.call('spectra', s, NFREQ);
  }

  /** The time response of the design on a seeded road: `opts` adds `seed` and the damper to TIME_RUN. */
  time(s, opts) {
    return this.heavy.call('timeResponse', s, { ...TIME_RUN, ...opts });
  }

  /** An SVG document of a line chart or map chart spec (`kind`: 'line' or 'map'; main thread only). */
  svg(kind, spec) {
    return this.main.call(kind === 'map' ? 'mapChartSvg' : 'lineChartSvg', spec);
  }
}
