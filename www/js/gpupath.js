// The GPU path of the HiFi maps (issue #13): the wasm's `GpuMaps` (crate/src/web/gpu.rs,
// built with the crate's `gpu` feature: wgpu on the browser's WebGPU) computes the HiFi
// criteria of every cell; the thread's `Explorer` session keeps them (`keepHifiMap`) and
// makes the HiFi and surrogate-error maps of them as of its own. Without WebGPU, without
// an adapter (by default a hardware one: `computeMode`), or when the GPU fails, the
// session's CPU HiFi draws the maps (the reference, never removed) and `status()` says why. Nothing here waits for ever: the adapter
// request and each map have a time limit, past which the CPU path takes over.

/** ms the adapter and device request may take before the page stays on the CPU. */
const GPU_REQUEST_MS = 15_000;
/** ms one GPU map may take before the CPU draws it instead (a software adapter is slow). */
const GPU_MAP_MS = 120_000;

/** `promise`, or a rejection naming `what` after `ms`. */
function within(promise, ms, what) {
  let timer;
  const late = new Promise((_, reject) => {
    timer = setTimeout(() => reject(new Error(`${what}: no answer within ${ms / 1000} s`)), ms);
  });
  return Promise.race([promise, late]).finally(() => clearTimeout(timer));
}

const messageOf = (e) => (e && typeof e === 'object' && 'message' in e ? String(e.message) : String(e));

/**
 * The page's `?compute=` (as `ridelab map --compute`): "auto" (the default) takes a
 * hardware adapter only, since a software one (SwiftShader) is far slower than the CPU
 * path; "gpu" takes any adapter; "cpu" never asks for one.
 */
export function computeMode(search) {
  const m = new URLSearchParams(search).get('compute');
  return ['gpu', 'cpu'].includes(m) ? m : 'auto';
}

/** The adapter's name from its `GPUAdapterInfo` (wgpu gives none on the web). */
function adapterName(adapter) {
  const i = adapter.info || {};
  return [i.vendor, i.architecture, i.description].filter(Boolean).join(' ') || 'WebGPU adapter';
}

export class GpuPath {
  /** `api`: the wasm module (its `GpuMaps` class is there only in a `gpu` build); `mode`: see `computeMode`. */
  constructor(api, mode = 'auto') {
    this.api = api;
    this.mode = mode;
    this.opening = null;
    /** The adapter's name once the GPU is open. */
    this.adapter = null;
    /** Why the CPU draws the HiFi maps: no GPU, or the last GPU failure (null: none). */
    this.reason = null;
    /** The last GPU error (the CPU then drew that scenario's maps). */
    this.failure = null;
  }

  /** The `GpuMaps`, requested once, or null (then `reason` says why). */
  open() {
    if (!this.opening) this.opening = this.request();
    return this.opening;
  }

  async request() {
    const gpu = globalThis.navigator && navigator.gpu;
    if (this.mode === 'cpu') return this.none('asked for by ?compute=cpu');
    if (typeof this.api.GpuMaps !== 'function') return this.none('no WebGPU adapter: this build has no GPU path');
    if (!gpu) return this.none('no WebGPU adapter');
    try {
      // Asked here first, so the wasm is only called with an adapter there.
      const adapter = await within(gpu.requestAdapter({ powerPreference: 'high-performance' }), GPU_REQUEST_MS, 'WebGPU adapter');
      if (!adapter) return this.none('no WebGPU adapter');
      const name = adapterName(adapter);
      const software = adapter.info?.isFallbackAdapter ?? adapter.isFallbackAdapter;
      if (software && this.mode === 'auto') return this.none(`software WebGPU adapter ${name}, slower than the CPU; ?compute=gpu takes it`);
      const maps = await within(this.api.GpuMaps.request(), GPU_REQUEST_MS, 'WebGPU device');
      this.adapter = maps.adapter || name;
      return maps;
    } catch (e) {
      return this.none(`GPU failed: ${messageOf(e)}`);
    }
  }

  none(reason) {
    this.reason = reason;
    return null;
  }

  /** The HiFi criteria planes of `state` on `nx` x `ny` cells from the GPU (rejects on a GPU error or past GPU_MAP_MS). */
  async map(maps, state, nx, ny) {
    try {
      const m = await within(maps.hifiMap(state, nx, ny), GPU_MAP_MS, 'GPU map');
      this.failure = null;
      return m.values;
    } catch (e) {
      this.failure = messageOf(e);
      throw e;
    }
  }

  /** The HiFi criteria of the objective plane's STM starting grid of `state` from the GPU (`GpuMaps.stmGrid`'s values; rejects as `map`). */
  async stmGrid(maps, state) {
    try {
      const m = await within(maps.stmGrid(state), GPU_MAP_MS, 'GPU grid');
      this.failure = null;
      return m.values;
    } catch (e) {
      this.failure = messageOf(e);
      throw e;
    }
  }

  /** `{adapter, reason, failure}`: what the footer and the map status say. */
  status() {
    return { adapter: this.adapter, reason: this.reason, failure: this.failure };
  }
}

/**
 * The footer's words for the path that drew the HiFi maps: `compute` the maps' own
 * (`"gpu"` or `"cpu"`), `gpu` the status above.
 */
export function pathText(compute, gpu) {
  if (compute === 'gpu') return `GPU: ${gpu.adapter || 'WebGPU adapter'}`;
  if (gpu && gpu.failure) return `CPU (the GPU failed: ${gpu.failure})`;
  if (gpu && gpu.adapter) return 'CPU';
  return `CPU (${gpu && gpu.reason ? gpu.reason : 'no WebGPU adapter'})`;
}
