// What every end-to-end suite shares: paths, the server and browser started once per
// file (node:test `before` / `after`), and the checks on logs and canvas pixels.
import { before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { startServer } from './server.mjs';
import { launch } from './browser.mjs';

export const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
export const DIST = process.env.RIDELAB_DIST || path.join(ROOT, 'dist');
export const OUT = path.join(ROOT, 'tests/e2e/out');

/**
 * Serves dist/ and launches Chromium before the file's tests, closes both after them
 * (then runs `onAfter`). Returns `{srv, browser}`, filled in once `before` has run.
 */
export function useSuite({ onAfter } = {}) {
  const suite = { srv: null, browser: null };
  before(async () => {
    if (!fs.existsSync(path.join(DIST, 'index.html'))) {
      throw new Error(`${DIST}/index.html is missing: build the page first (trunk build --release --offline)`);
    }
    fs.mkdirSync(OUT, { recursive: true });
    suite.srv = await startServer(DIST);
    suite.browser = await launch();
  });
  after(async () => {
    if (suite.browser) await suite.browser.close();
    if (suite.srv) await suite.srv.close();
    if (onAfter) onAfter();
  });
  return suite;
}

/** No console errors and no request to another host. */
export function assertClean(log) {
  assert.deepEqual(log.errors, [], 'console errors');
  assert.deepEqual(log.foreign, [], 'requests to other hosts');
}

/** Texts `got` and `want` equal line by line; a failure names the first differing line. */
export function assertSameLines(got, want, what) {
  const a = got.split('\n');
  const b = want.split('\n');
  const first = a.findIndex((line, k) => line !== b[k]);
  assert.equal(first, -1, `${what} differ from line ${first + 1}: ${a[first]?.slice(0, 300)} | ${b[first]?.slice(0, 300)}`);
  assert.equal(a.length, b.length);
}

/** Pixels of canvas `id` within `tol` (sum of |channel differences|) of colour `rgb`. */
export function countColour(page, id, rgb, tol = 40) {
  return page.evaluate(
    ([id, rgb, tol]) => {
      const c = document.getElementById(id);
      const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      let n = 0;
      for (let k = 0; k < d.length; k += 4) {
        if (d[k + 3] > 200 && Math.abs(d[k] - rgb[0]) + Math.abs(d[k + 1] - rgb[1]) + Math.abs(d[k + 2] - rgb[2]) < tol) n++;
      }
      return n;
    },
    [id, rgb, tol],
  );
}

/** The median of `xs`. */
export const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];

/** The 95th percentile of `xs` (nearest rank). */
export const p95 = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  return s[Math.min(s.length - 1, Math.ceil(0.95 * s.length) - 1)];
};

/** CRC-32 (IEEE) of a Buffer. */
function crc32(buf) {
  let c = 0xffffffff;
  for (const b of buf) {
    c ^= b;
    for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
  }
  return (c ^ 0xffffffff) >>> 0;
}

/** The entries of a stored (uncompressed) zip as `[{name, data}]`; each entry's CRC is checked. */
export function readZip(buf) {
  const out = [];
  let p = 0;
  while (p + 4 <= buf.length && buf.readUInt32LE(p) === 0x04034b50) {
    const method = buf.readUInt16LE(p + 8);
    const crc = buf.readUInt32LE(p + 14);
    const size = buf.readUInt32LE(p + 18);
    const nameLen = buf.readUInt16LE(p + 26);
    const extra = buf.readUInt16LE(p + 28);
    assert.equal(method, 0, 'zip entries are stored');
    const name = buf.subarray(p + 30, p + 30 + nameLen).toString('utf8');
    const data = buf.subarray(p + 30 + nameLen + extra, p + 30 + nameLen + extra + size);
    assert.equal(crc32(data), crc, `${name}: CRC`);
    out.push({ name, data });
    p += 30 + nameLen + extra + size;
  }
  assert.equal(buf.readUInt32LE(buf.length - 22), 0x06054b50, 'the zip ends with its directory');
  assert.equal(buf.readUInt16LE(buf.length - 12), out.length, 'the directory lists every entry');
  return out;
}
