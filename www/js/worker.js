// Web Worker entry: the same wasm module as the page, answering engine calls
// `{id, method, args}` with `{id, ok, value}` or `{id, ok: false, error: {message, field}}`.
import init, * as api from '../ridelab.js';
import { METHODS, toFailure } from './engine.js';

const ready = init({ module_or_path: new URL('../ridelab_bg.wasm', import.meta.url) });

self.onmessage = async ({ data }) => {
  const { id, method, args } = data;
  try {
    await ready;
    if (!METHODS.includes(method)) throw { message: `no method ${method}`, field: '' };
    const value = api[method](...args);
    const transfer = [];
    if (value && typeof value === 'object') {
      for (const v of Object.values(value)) if (ArrayBuffer.isView(v)) transfer.push(v.buffer);
      if (ArrayBuffer.isView(value)) transfer.push(value.buffer);
    }
    self.postMessage({ id, ok: true, value }, transfer);
  } catch (e) {
    self.postMessage({ id, ok: false, error: toFailure(e) });
  }
};
