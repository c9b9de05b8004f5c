// Web Worker entry: the same wasm module as the page, answering engine calls
// `{id, method, args}` with `{id, ok, value}` or `{id, ok: false, error: {message, field}}`.
// A trap of the core (a WebAssembly.RuntimeError: its memory can no longer be trusted)
// is answered `{id, ok: false, trap: true, error}` and the worker closes; the page's
// engine starts a fresh one (js/engine.js).
import init, * as api from '../ridelab.js';
import { Host, toFailure } from './engine.js';

// This thread's session: the worker's maps, fits and fronts are kept between calls. The
// GPU path (js/gpupath.js) is asked for on the worker that draws the HiFi maps only: the
// page starts that one with `?gpu=MODE` in its URL (the page's `?compute=`).
const host = new Host(api, { gpu: new URL(self.location.href).searchParams.get('gpu') });
const ready = init({ module_or_path: new URL('../ridelab_bg.wasm', import.meta.url) });
/** This thread's session, where the browser tests reach it (tests/e2e/hostile.test.mjs). */
self.ridelabHost = host;

self.onmessage = async ({ data }) => {
  const { id, method, args } = data;
  try {
    await ready;
    const value = await host.run(method, args);
    const transfer = [];
    if (value && typeof value === 'object') {
      for (const v of Object.values(value)) if (ArrayBuffer.isView(v)) transfer.push(v.buffer);
      if (ArrayBuffer.isView(value)) transfer.push(value.buffer);
    }
    self.postMessage({ id, ok: true, value }, transfer);
  } catch (e) {
    const trap = e instanceof WebAssembly.RuntimeError;
    self.postMessage({ id, ok: false, trap, error: toFailure(e) });
    if (trap) self.close();
  }
};
