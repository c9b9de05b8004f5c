// End-to-end tests of the SVG export (js/svgexport.js over the wasm `lineChartSvg` and
// `mapChartSvg`): every chart of the page as an SVG document that the browser parses,
// with its labels and data; bad specs rejected with the field named; and the charts
// refused, not crashed, in a Web Worker (plotters measures text in the page's document);
// the SVG buttons download them.
//
//   trunk build --release --offline && npm run test:e2e

import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { openPage, settled } from './browser.mjs';
import { useSuite, OUT } from './harness.mjs';

const TIMEOUT = 120_000;
const suite = useSuite();

/** The page, settled, with the time response run. */
async function openWired() {
  const r = await openPage(suite.browser, suite.srv.url, { width: 1400, height: 1000, downloads: true });
  await settled(r.page, 150);
  const wired = await r.page.evaluate(async () => {
    const { METHODS } = await import('./js/engine.js');
    const app = window.__ridelab;
    return typeof app.api.lineChartSvg === 'function' && METHODS.includes('lineChartSvg') && METHODS.includes('mapChartSvg');
  });
  assert.ok(wired, 'the page exports lineChartSvg and mapChartSvg');
  await r.page.click('#tp-run');
  await r.page.waitForFunction(() => window.__ridelab.time !== null, null, { timeout: 60_000 });
  await settled(r.page, 50);
  return r;
}

test('every chart exports as a parseable SVG with its labels and data', { timeout: TIMEOUT }, async (t) => {
  const r = await openWired();
  const { page, context, log } = r;
  const out = await page.evaluate(async () => {
    const m = await import('./js/svgexport.js');
    const app = window.__ridelab;
    const t0 = performance.now();
    const all = await m.allSvgs(app);
    const ms = performance.now() - t0;
    const parser = new DOMParser();
    const charts = all.map(({ name, svg }) => {
      const doc = parser.parseFromString(svg, 'image/svg+xml');
      const root = doc.documentElement;
      const texts = [...doc.querySelectorAll('text')].map((e) => e.textContent.trim());
      const lines = [...doc.querySelectorAll('polyline')].map((e) => ({
        stroke: e.getAttribute('stroke'),
        n: e.getAttribute('points').trim().split(/\s+/).length,
      }));
      return {
        name,
        bytes: svg.length,
        ok: root.nodeName === 'svg' && doc.querySelector('parsererror') === null,
        texts,
        lines,
        rects: doc.querySelectorAll('rect').length,
      };
    });
    return {
      ms,
      charts,
      nfreq: app.spectra.f.length,
      ntime: app.time.lofi.t.length,
      save: all.find((c) => c.name === 'map-bacc').svg,
    };
  });
  fs.writeFileSync(path.join(OUT, 'svgexport-map-bacc.svg'), out.save);
  const names = out.charts.map((c) => c.name);
  assert.deepEqual(names, [
    'objective',
    'frf-bacc', 'frf-dtl', 'frf-sws', 'psd-bacc', 'psd-dtl', 'psd-sws',
    'time-bacc', 'time-dtl', 'time-sws',
    'map-bacc', 'map-dtl', 'map-sws',
  ]);
  for (const c of out.charts) {
    assert.ok(c.ok, `${c.name} does not parse`);
    assert.ok(c.bytes < 1_000_000, `${c.name}: ${c.bytes} bytes`);
  }
  const chart = (name) => out.charts.find((c) => c.name === name);
  assert.ok(chart('objective').texts.includes('BAcc [m/s²]'));
  assert.ok(chart('objective').texts.includes('DTL [N]'));
  assert.ok(chart('frf-dtl').texts.includes('frequency [Hz]'));
  assert.ok(chart('psd-sws').texts.includes('PSD SWS [m²/Hz]'));
  assert.ok(chart('map-sws').texts.includes('Ks front spring [kN/m]'));
  assert.ok(chart('map-sws').texts.includes('Cs front damper [kNs/m]'));
  assert.ok(chart('map-bacc').texts.includes('BAcc [m/s²]'));
  // The lines are simplified to within half a pixel (the core's chart tests bound it):
  // a smooth FRF keeps a fraction of its frequencies, a noisy time response most samples.
  const vertices = (name, stroke) => Math.max(0, ...chart(name).lines.filter((l) => l.stroke === stroke).map((l) => l.n));
  for (const stroke of ['#1D4ED8', '#B91C1C']) {
    const f = vertices('frf-bacc', stroke);
    assert.ok(f > 20 && f < out.nfreq, `FRF ${stroke}: ${f} of ${out.nfreq} vertices`);
    const t = vertices('time-dtl', stroke);
    assert.ok(t > out.ntime / 2 && t <= out.ntime, `time ${stroke}: ${t} of ${out.ntime} vertices`);
  }
  // The surrogate's tuned LoFi is drawn too (green).
  assert.ok(vertices('psd-bacc', '#15803D') > 20, 'surrogate PSD');
  // The 160 x 120 page map drawn as at most 80 x 60 blocks.
  assert.ok(chart('map-dtl').rects <= 80 * 60 + 80, `${chart('map-dtl').rects} rects`);
  t.diagnostic(`svg export: ${names.length} charts in ${out.ms.toFixed(0)} ms; ` +
    out.charts.map((c) => `${c.name} ${(c.bytes / 1024).toFixed(0)} KB`).join(', '));
  assert.deepEqual(log.errors, [], 'console errors');
  await context.close();
});

test('bad specs are refused naming the field; a worker gets an error, not a crash', { timeout: TIMEOUT }, async (t) => {
  const r = await openWired();
  const { page, context, log } = r;
  const res = await page.evaluate(async () => {
    const app = window.__ridelab;
    const fail = (spec, method = 'lineChartSvg') => app.engine.call(method, spec).then(() => null, (e) => e);
    const series = [{ colour: '#000000', points: [[1, 1], [2, NaN]] }];
    const nan = await fail({ series });
    const log = await fail({ yLog: true, series: [{ colour: '#000000', points: [[1, 1], [2, -3]] }] });
    const unknown = await fail({ xlabel: 'x', series: [] });
    const nested = await fail({ series: [{ colour: '#000000', points: [[1, 1]], stroek: '#ffffff' }] });
    const colour = await fail({ series: [{ colour: 'red', points: [[1, 1]] }] });
    const map = await fail({ unit: 'u', nx: 2, ny: 2, values: [1, 2, 3] }, 'mapChartSvg');
    // The worker: the same module, no window; the call must throw, and the worker live on.
    const worker = await new Promise((resolve) => {
      const src = `import init, * as api from '${new URL('./ridelab.js', location.href)}';
        self.onmessage = async () => {
          await init({ module_or_path: new URL('${new URL('./ridelab_bg.wasm', location.href)}') });
          let first;
          try { api.lineChartSvg({ series: [{ colour: '#000000', points: [[1, 1], [2, 2]] }] }); first = 'no error'; }
          catch (e) { first = { message: e.message, field: e.field }; }
          let after;
          try { after = api.version(); } catch (e) { after = 'dead: ' + e.message; }
          self.postMessage({ first, after });
        };`;
      const w = new Worker(URL.createObjectURL(new Blob([src], { type: 'text/javascript' })), { type: 'module' });
      w.onmessage = ({ data }) => resolve(data);
      w.onerror = (e) => resolve({ first: 'worker error: ' + e.message });
      w.postMessage(0);
    });
    return { nan, log, unknown, nested, colour, map, worker };
  });
  assert.equal(res.nan.field, 'series[0].points[1]');
  assert.match(res.nan.message, /y is NaN/);
  assert.equal(res.log.field, 'series[0].points[1]');
  assert.match(res.log.message, /log axis/);
  assert.equal(res.unknown.field, 'xlabel');
  assert.match(res.unknown.message, /unknown field `xlabel`/);
  assert.equal(res.nested.field, 'series[0].stroek');
  assert.equal(res.colour.field, 'series[0].colour');
  assert.equal(res.map.field, 'values');
  assert.equal(res.worker.first.field, 'chart', JSON.stringify(res.worker));
  assert.match(res.worker.first.message, /main thread/);
  assert.match(String(res.worker.after), /^\d+\.\d+\.\d+/);
  assert.deepEqual(log.errors, [], 'console errors');
  await context.close();
});

test('the SVG buttons download the objective plane and every chart', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await openWired();
  const [one] = await Promise.all([page.waitForEvent('download'), page.click('#op-svg')]);
  assert.match(one.suggestedFilename(), /^ridelab-objective-sedan-B-20ms\.svg$/);
  const text = fs.readFileSync(await one.path(), 'utf8');
  assert.match(text, /^<svg/);
  assert.match(text, /Pareto front, STM/);
  const files = [];
  page.on('download', (d) => files.push(d.suggestedFilename()));
  await page.click('#svg-all');
  for (let i = 0; i < 200 && files.length < 13; i++) await page.waitForTimeout(50);
  assert.equal(files.length, 13, files.join(', '));
  assert.ok(files.includes('ridelab-map-sws-sedan-B-20ms.svg'), files.join(', '));
  assert.deepEqual(log.errors, [], 'console errors');
  await context.close();
});
