// The compute engine: one asynchronous interface over the wasm API, so the page never
// cares whether the models run on the main thread ("main", the default: a HiFi report
// takes a few milliseconds) or in a Web Worker ("worker": same module, same numbers).
// Errors are always `{message, field}` objects; `field` names the state field at fault.
// A worker that crashes (an uncaught error) or whose core traps (a WebAssembly trap: its
// memory can no longer be trusted, so it closes itself) is replaced by a fresh one, the
// requests it held are run again there (once), and the page is told (`onRestart`).

import { GpuPath } from './gpupath.js';

/** The wasm functions that need no session (with SESSION_METHODS, the worker's whitelist). */
export const FUNCTIONS = [
  'version', 'defaultState', 'presets', 'roadClasses', 'parseCar', 'checkState', 'surrogates',
  'objectives', 'lineChartSvg', 'mapChartSvg', 'describeRoad', 'designOnRoad',
  'roadMap', 'roadFront', 'useRoad',
];

/** Calls a restarted worker is given again before the requests it held: the profiles registered for the road menu. */
const STICKY = ['useRoad'];

/** The methods of the core's `Explorer` session: an engine call is `(method, state, ...args)`. */
const SESSION_METHODS = [
  'describe', 'analyse', 'designReports', 'readout', 'designStep', 'criteria', 'mapCriteria', 'maps', 'front', 'spectra', 'timeResponse', 'surrogateFit',
  'studyReport', 'fitRecord', 'robustFront',
];

/**
 * `offerFit(record)`: a surrogate fit another thread made (`fitRecord`'s value), which this
 * thread's session adopts for a scenario with the same fit inputs instead of fitting again
 * (one fit per scenario change, issue #28). Resolves to null; the workers' module has it.
 */
const FIT_METHODS = ['offerFit'];

/**
 * The adaptive HiFi loop's calls (issue #15), on the thread's one `AdaptiveRun` of the core
 * (crate/src/web/mod.rs): `adaptiveStart(state, options)`, `adaptiveStep(state)`,
 * `adaptiveReport(state)`, `adaptiveUncertainty(state, nx, ny, levels)`. A step or report
 * for another scenario than the run's is refused.
 */
const ADAPTIVE_METHODS = ['adaptiveStart', 'adaptiveStep', 'adaptiveReport', 'adaptiveUncertainty'];

/**
 * The GPU path's calls (issue #13), on a host made with `{gpu: mode}` (the heavy worker):
 * `gpuStatus()` resolves to `{adapter, reason, failure}` once the GPU is open or refused.
 * On such a host `maps(state, 'hifi' | 'error', nx, ny)` resolves (a promise) to the
 * map with the GPU's HiFi values when there is an adapter, else the CPU's; either way
 * with `compute` ("gpu" or "cpu") and `gpu` (the status) set.
 */
const GPU_METHODS = ['gpuStatus'];

/**
 * `hifiFront(state)`: the HiFi's own front and the plane's front judged on it
 * (`Explorer.hifiFront`), with `ms` (this thread's time, the GPU's included). On a host
 * with the GPU path open and the unweighted BAcc, STM's starting grid comes from the GPU
 * (`compute: "gpu"`, and `gpu` the status); a GPU failure leaves it to the CPU.
 */
const FRONT_METHODS = ['hifiFront'];

/** The largest |`100 (predicted / hifi - 1)`| of BAcc, DTL and SWS, %: a pick's HiFi re-check error. */
function recheckError(predicted, hifi) {
  return Math.max(...['bacc', 'dtl', 'sws'].map((k) => Math.abs(100 * (predicted[k] / hifi[k] - 1))));
}

/**
 * One thread's `Explorer` session (crate/src/web/explorer.rs), moved to each call's state
 * by `setState`: the core compares it with its own and re-parses only the fields that
 * changed (a slider move only the design). The page's states are never changed in place
 * (a change makes a new object), so a call with the state object of the last call skips
 * the setter. A setter that throws leaves the session at its last good state. What a
 * result belongs to is the core's `tags` (issue #28): this host keeps no key of its own.
 */
export class Host {
  constructor(api, { gpu = null } = {}) {
    this.api = api;
    /** The GPU path of the HiFi maps (js/gpupath.js; `gpu` its mode), on the heavy worker only. */
    this.gpu = gpu ? new GpuPath(api, gpu) : null;
    /** The scenario and grid whose GPU map failed (the CPU drew it; not asked again). */
    this.gpuFailedKey = null;
    this.explorer = null;
    /** The state object the session was last moved to (see the class comment). */
    this.state = null;
    /** The adaptive loop (`AdaptiveRun`) and the scenario tag it was started for. */
    this.adaptive = null;
    this.adaptiveKey = null;
    /** Calls into the wasm module so far (setters and session methods; tests read it). */
    this.wasmCalls = 0;
    /** The latest fit offered (`offerFit`), kept for a session made later. */
    this.offered = null;
  }

  /**
   * Offers the session `record` (see FIT_METHODS), kept for a session made later; a module
   * without `offerFit` (the first screen's) keeps it only to pass on, and fits for itself.
   */
  offerFit(record) {
    this.offered = record;
    if (this.explorer && typeof this.explorer.offerFit === 'function') {
      this.wasmCalls++;
      this.explorer.offerFit(record);
    }
    return null;
  }

  /** The session moved to `state` (throws the core's error naming the field). */
  at(state) {
    if (!this.explorer) {
      this.wasmCalls++;
      this.explorer = new this.api.Explorer(state);
      if (this.offered) this.offerFit(this.offered);
    } else if (state !== this.state) {
      this.wasmCalls++;
      // On a refusal the session stays where it was, and so does `this.state`.
      this.explorer.setState(state);
    }
    this.state = state;
    return this.explorer;
  }

  /** The core's tags of `state` (`{design, datum, fit, scenario}`, js/store.js `tags`). */
  tagsOf(state) {
    const explorer = this.at(state);
    this.wasmCalls++;
    return explorer.tags();
  }

  /** Runs one engine call: synchronously, or a promise for the GPU path's calls. */
  run(method, args) {
    this.wasmCalls++;
    if (FUNCTIONS.includes(method)) return this.api[method](...args);
    // The robust maps' cases are evaluated on the CPU (as `ridelab map --cases`).
    // So is a measured road's (the GPU kernel is the ISO road's).
    if (this.gpu && method === 'maps' && ['hifi', 'error'].includes(args[1]) && !args[0].cases && !args[0].roadProfile) return this.gpuMaps(...args);
    if (this.gpu && method === 'gpuStatus') return this.gpu.open().then(() => this.gpu.status());
    // The session's surrogate fits so far (tests read it; 0 before the first state).
    if (method === 'fitCount') return this.explorer ? this.explorer.fitCount() : 0;
    if (SESSION_METHODS.includes(method)) {
      const [state, ...rest] = args;
      return this.at(state)[method](...rest);
    }
    if (ADAPTIVE_METHODS.includes(method) || FRONT_METHODS.includes(method) || FIT_METHODS.includes(method)) {
      return this[method](...args);
    }
    throw { message: `no method ${method}`, field: '' };
  }

  /**
   * The HiFi or error map of `state` on `nx` x `ny` cells, its HiFi values from the GPU
   * when it is open (computed once per scenario and grid, then kept by the session like
   * its own), else the session's CPU values. A GPU failure leaves that scenario to the
   * CPU and says so in the result's `gpu.failure`.
   */
  async gpuMaps(state, model, nx, ny) {
    const key = `${this.tagsOf(state).scenario}|${nx}x${ny}`;
    if (this.at(state).hifiPath(nx, ny) !== 'gpu' && this.gpuFailedKey !== key) {
      const maps = await this.gpu.open();
      if (maps) {
        try {
          const values = await this.gpu.map(maps, state, nx, ny);
          // Other calls may have moved the session while the GPU ran: back to `state`.
          this.at(state).keepHifiMap(nx, ny, values);
        } catch {
          this.gpuFailedKey = key;
        }
      }
    }
    const out = this.at(state).maps(model, nx, ny);
    out.gpu = { ...this.gpu.status(), failure: this.gpuFailedKey === key ? this.gpu.failure : null };
    return out;
  }

  /** See FRONT_METHODS. */
  async hifiFront(state) {
    const t0 = performance.now();
    let values;
    const key = `${this.tagsOf(state).scenario}|stm`;
    // The GPU grid is one case's unweighted BAcc on an ISO road: Wk comfort, robust cases
    // and a measured road run on the CPU.
    if (this.gpu && (state.comfort || 'bacc') === 'bacc' && !state.cases && !state.roadProfile && this.gpuFailedKey !== key) {
      const maps = await this.gpu.open();
      if (maps) {
        try {
          values = await this.gpu.stmGrid(maps, state);
        } catch {
          this.gpuFailedKey = key;
        }
      }
    }
    const out = this.at(state).hifiFront(values);
    out.ms = performance.now() - t0;
    if (this.gpu) out.gpu = { ...this.gpu.status(), failure: this.gpuFailedKey === key ? this.gpu.failure : null };
    return out;
  }

  /**
   * Starts the adaptive loop on `state`'s scenario (its plan run on the HiFi, its
   * surrogate fitted), replacing any earlier one: `{key, report, proposal, front, ms,
   * recheck}` (`recheck`: the plan's pick re-run on the HiFi, `{rechecked, error}` with
   * `error` the largest |error|, %). Throws the core's error naming the field.
   */
  adaptiveStart(state, options) {
    const t0 = performance.now();
    const run = new this.api.AdaptiveRun(state, options);
    if (this.adaptive) this.adaptive.free();
    this.adaptive = run;
    this.adaptiveKey = this.tagsOf(state).scenario;
    const report = run.report();
    const { pick } = report.history[0];
    const rechecked = this.at({ ...state, ks: pick.ks, cs: pick.cs }).criteria('hifi');
    return {
      key: this.adaptiveKey,
      report,
      proposal: this.proposal(),
      front: run.front(),
      recheck: { rechecked, error: recheckError(pick.criteria, rechecked) },
      ms: performance.now() - t0,
    };
  }

  /**
   * One HiFi run at the proposal, the refit and the new front: `{added, step, recheck,
   * proposal, front, ms}` (`recheck` as the core's, with `error` added; `ms`: the step's
   * time in this thread, the next proposal and the front included).
   */
  adaptiveStep(state) {
    const run = this.adaptiveFor(state);
    const t0 = performance.now();
    const r = run.step();
    r.recheck.error = recheckError(r.recheck.predicted, r.recheck.rechecked);
    const out = { ...r, proposal: this.proposal(), front: run.front() };
    return { ...out, ms: performance.now() - t0 };
  }

  /** The loop so far (`ridelab surrogate ... --adaptive K`'s `adaptive`). */
  adaptiveReport(state) {
    return this.adaptiveFor(state).report();
  }

  /**
   * The loop's uncertainty estimate: `{nx, ny, map, levels, check, atSamples, ms}`
   * (`map`: sigma, %, at the `nx` x `ny` cell centres, three planes as the maps';
   * `check`, `atSamples`: the core's `uncertaintyCheck(levels)`, how well sigma predicts
   * the true error on the `levels` x `levels` HiFi grid, and its largest value at the
   * samples, %).
   */
  adaptiveUncertainty(state, nx, ny, levels) {
    const run = this.adaptiveFor(state);
    const t0 = performance.now();
    const map = run.uncertaintyMap(nx, ny);
    const c = run.uncertaintyCheck(levels);
    return { nx, ny, map, levels: c.levels, check: c.check, atSamples: c.at_samples_percent, ms: performance.now() - t0 };
  }

  /** The run of `state`'s scenario; throws `{field: 'adaptive'}` when there is none. */
  adaptiveFor(state) {
    if (!this.adaptive || this.tagsOf(state).scenario !== this.adaptiveKey) {
      throw { message: 'adaptive: no adaptive run for this scenario (start one first)', field: 'adaptive' };
    }
    return this.adaptive;
  }

  /** The run's next proposal, or `{error}` when there is none (the box is full of samples). */
  proposal() {
    try {
      return this.adaptive.propose();
    } catch (e) {
      return { error: toFailure(e).message };
    }
  }
}

/** Turns anything thrown into `{message, field}`. */
export function toFailure(e) {
  if (e && typeof e === 'object' && 'message' in e) {
    return { message: String(e.message), field: typeof e.field === 'string' ? e.field : '' };
  }
  return { message: String(e), field: '' };
}

/**
 * Whether `api` (a wasm module's exports) answers `method`: the page's first-screen module
 * (ridelab-first.js) leaves out the on-demand parts that the workers' module has.
 */
export function answers(api, method) {
  // The GPU path is the heavy worker's (a main-thread host refuses it either way).
  if (GPU_METHODS.includes(method)) return true;
  if (FUNCTIONS.includes(method)) return typeof api[method] === 'function';
  if (SESSION_METHODS.includes(method)) return typeof api.Explorer.prototype[method] === 'function';
  if (ADAPTIVE_METHODS.includes(method)) return typeof api.AdaptiveRun === 'function';
  return typeof api.Explorer.prototype[method] === 'function';
}

/**
 * The main thread's engine: its `Host` on the first-screen module, and on a call that
 * module does not answer (an SVG export, or every call when a worker could not start),
 * a second `Host` on the on-demand module, which `loadOnDemand()` loads at that first
 * call (issue #29). Each host keeps its own session.
 */
class MainEngine {
  constructor(api, loadOnDemand) {
    this.host = new Host(api);
    this.loadOnDemand = loadOnDemand;
    this.onDemand = null;
    this.kind = 'main';
  }

  /**
   * The host on the on-demand module (loaded once; a failed load is tried again at the
   * next call), offered the first-screen host's fits so that it does not fit again.
   */
  full() {
    if (!this.onDemand) {
      this.onDemand = this.loadOnDemand().then((api) => {
        const host = new Host(api);
        if (this.host.offered) host.offerFit(this.host.offered);
        return host;
      });
      this.onDemand.catch(() => (this.onDemand = null));
    }
    return this.onDemand;
  }

  call(method, ...args) {
    // A fit offered here (the heavy worker fell back to this thread): the first-screen
    // host made it; kept for the on-demand host, which is given it when it loads.
    if (FIT_METHODS.includes(method)) {
      this.host.offerFit(args[0]);
      return this.onDemand ? this.onDemand.then((host) => host.run(method, args)) : Promise.resolve(null);
    }
    // A state on a measured road (`roadProfile`): the first-screen module has no shaped
    // routes, so the on-demand host answers it (with the profiles registered there).
    const measured = args[0] !== null && typeof args[0] === 'object' && Boolean(args[0].roadProfile);
    if ((measured || !answers(this.host.api, method)) && this.loadOnDemand) {
      return this.full().then((host) => host.run(method, args)).catch((e) => Promise.reject(toFailure(e)));
    }
    try {
      const value = this.host.run(method, args);
      return value instanceof Promise ? value.catch((e) => Promise.reject(toFailure(e))) : Promise.resolve(value);
    } catch (e) {
      return Promise.reject(toFailure(e));
    }
  }
}

/** How many times a request is sent to a worker before a crash while it waits is reported instead. */
const MAX_SENDS = 2;
/** How many crashed workers are replaced; after that (a worker that cannot even start) every call is refused. */
const MAX_RESTARTS = 5;

class WorkerEngine {
  /**
   * `make()`: a new Worker of this engine's module and URL; `onRestart({reason, retried,
   * failed})`: called after a crashed worker was replaced (`retried`: the requests sent
   * again, `failed`: those rejected after crashing it twice).
   */
  constructor(make, onRestart) {
    this.make = make;
    this.onRestart = onRestart;
    this.kind = 'worker';
    this.next = 1;
    /** Requests in flight: id -> `{resolve, reject, msg, sends}`. */
    this.pending = new Map();
    /** Workers replaced after a crash. */
    this.restarts = 0;
    /** Why the worker is given up (after MAX_RESTARTS), or null. */
    this.dead = null;
    /** The STICKY calls sent so far (their messages), by their arguments' identity. */
    this.sticky = [];
    this.attach(make());
  }

  /** Takes `worker` as this engine's thread. */
  attach(worker) {
    this.worker = worker;
    worker.onmessage = ({ data }) => {
      if (worker !== this.worker) return;
      if (data.trap) {
        this.crashed(`its core stopped: ${data.error.message}`);
        return;
      }
      const p = this.pending.get(data.id);
      if (!p) return;
      this.pending.delete(data.id);
      if (data.ok) p.resolve(data.value);
      else p.reject(data.error);
    };
    worker.onerror = (ev) => {
      ev.preventDefault();
      if (worker === this.worker) this.crashed(ev.message || 'an error it did not catch');
    };
    worker.onmessageerror = () => {
      if (worker === this.worker) this.crashed('an answer that could not be read');
    };
  }

  /** The worker crashed: a fresh one takes its place and gets the requests it held (each sent at most MAX_SENDS times). */
  crashed(reason) {
    this.worker.terminate();
    if (this.restarts >= MAX_RESTARTS) {
      this.dead = `the worker crashed ${this.restarts + 1} times and is not started again (${reason})`;
      for (const p of this.pending.values()) p.reject({ message: this.dead, field: '' });
      this.pending.clear();
      return;
    }
    this.restarts++;
    this.attach(this.make());
    // Its fresh core has no profiles: they are registered again first (answers ignored).
    for (const msg of this.sticky) this.worker.postMessage({ ...msg, id: 0 });
    let retried = 0;
    let failed = 0;
    for (const [id, p] of [...this.pending]) {
      if (p.sends >= MAX_SENDS) {
        this.pending.delete(id);
        p.reject({ message: `the worker crashed twice on this request (${reason})`, field: '' });
        failed++;
      } else {
        p.sends++;
        this.worker.postMessage(p.msg);
        retried++;
      }
    }
    this.onRestart({ reason, retried, failed });
  }

  call(method, ...args) {
    if (this.dead) return Promise.reject({ message: this.dead, field: '' });
    const id = this.next++;
    const msg = { id, method, args };
    if (STICKY.includes(method)) this.sticky = [...this.sticky.filter((m) => m.args[1] !== args[1]), msg].slice(-4);
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject, msg, sends: 1 });
      this.worker.postMessage(msg);
    });
  }
}

/**
 * An engine of the given kind ("main" or "worker"); the worker answers a ping first.
 * `gpu` ("auto", "gpu" or "cpu", js/gpupath.js `computeMode`): the worker draws the HiFi
 * maps on the GPU path where its mode finds an adapter (`GPU_METHODS`). `onRestart`: see
 * WorkerEngine (a crashed worker replaced). `loadOnDemand()` (main thread): resolves to the
 * on-demand module's API, initialised (see MainEngine).
 */
export async function createEngine(api, kind = 'main', { gpu = null, onRestart = () => {}, loadOnDemand = null } = {}) {
  if (kind !== 'worker') return new MainEngine(api, loadOnDemand);
  const url = new URL(gpu ? `./worker.js?gpu=${gpu}` : './worker.js', import.meta.url);
  const engine = new WorkerEngine(() => new Worker(url, { type: 'module' }), onRestart);
  await engine.call('version');
  return engine;
}

/**
 * An engine usable at once: calls wait for `starting` (a promise of an engine) and go
 * to `fallback` if it fails to start, so a worker's start-up is off the critical path.
 */
export function deferredEngine(starting, fallback) {
  const ready = starting.catch((e) => {
    console.warn(`RideLab: no worker (${e && e.message ? e.message : e}); running on the main thread`);
    return fallback;
  });
  const engine = {
    kind: 'starting',
    ready,
    call: (method, ...args) => ready.then((e) => e.call(method, ...args)),
  };
  ready.then((e) => (engine.kind = e.kind));
  return engine;
}

/**
 * Runs `task(arg)` so that at most one is in flight and only the latest request waits:
 * while one runs, newer requests replace each other, and the last one runs next.
 * Resolves each request with the task's result, or `undefined` if it was superseded.
 */
export function latestOnly(task) {
  let running = null;
  let queued = null;
  const run = (item) => {
    running = task(item.arg).then(item.resolve, item.reject).finally(() => {
      running = null;
      if (queued) {
        const q = queued;
        queued = null;
        run(q);
      }
    });
  };
  return (arg) => new Promise((resolve, reject) => {
    const item = { arg, resolve, reject };
    if (!running) run(item);
    else {
      if (queued) queued.resolve(undefined);
      queued = item;
    }
  });
}
