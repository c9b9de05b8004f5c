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
import { useSuite, readZip, OUT } from './harness.mjs';

const TIMEOUT = 120_000;
const suite = useSuite();

/** The page, settled, with the time response run. */
async function openWired() {
  const r = await openPage(suite.browser, suite.srv.url, { width: 1400, height: 1000, downloads: true });
  await settled(r.page, 150);
  const wired = await r.page.evaluate(async () => {
    const { FUNCTIONS } = await import('./js/engine.js');
    const app = window.__ridelab;
    // The first screen's module leaves them to the on-demand one, which the main thread's
    // engine loads at the first export (issue #29).
    return typeof app.api.lineChartSvg === 'undefined' && FUNCTIONS.includes('lineChartSvg') && FUNCTIONS.includes('mapChartSvg');
  });
  assert.ok(wired, 'the engine answers lineChartSvg and mapChartSvg from the on-demand module');
  await r.page.click('#tab-time');
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
    const all = await m.allSvgs(app.exportData(), app.svg);
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
    // A value of the wrong type, found at its path after the read (web/charts.rs `locate`).
    const good = { colour: '#000000', points: [[1, 1], [2, 2]] };
    const width = await fail({ width: 'wide', series: [good] });
    const size = await fail({ series: [good, { ...good, size: 'big' }] });
    const point = await fail({ series: [good, { ...good, points: [[1, 'one']] }] });
    const notList = await fail({ series: 'none' });
    const markerAt = await fail({ unit: 'u', nx: 2, ny: 2, values: [1, 2, 3, 4], markers: [{ label: 'a', ks: 2e4, cs: 1e3 }, { label: 'b', ks: 'x', cs: 1e3 }] }, 'mapChartSvg');
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
    return { nan, log, unknown, nested, colour, map, width, size, point, notList, markerAt, worker };
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
  assert.equal(res.width.field, 'width', JSON.stringify(res.width));
  assert.match(res.width.message, /invalid type: string "wide"/);
  assert.equal(res.size.field, 'series[1].size', JSON.stringify(res.size));
  assert.equal(res.point.field, 'series[1].points', JSON.stringify(res.point));
  assert.equal(res.notList.field, 'series', JSON.stringify(res.notList));
  assert.equal(res.markerAt.field, 'markers[1].ks', JSON.stringify(res.markerAt));
  assert.equal(res.worker.first.field, 'chart', JSON.stringify(res.worker));
  assert.match(res.worker.first.message, /main thread/);
  assert.match(String(res.worker.after), /^\d+\.\d+\.\d+/);
  assert.deepEqual(log.errors, [], 'console errors');
  await context.close();
});

test('the SVG buttons download the objective plane, and every chart as one zip', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await openWired();
  await page.click('#tab-export');
  const [one] = await Promise.all([page.waitForEvent('download'), page.click('#op-svg')]);
  assert.match(one.suggestedFilename(), /^ridelab-objective-sedan-B-20ms\.svg$/);
  const text = fs.readFileSync(await one.path(), 'utf8');
  assert.match(text, /^<svg/);
  assert.match(text, /Pareto front, STM/);
  // Every chart: one zip of 13 SVG documents (one download, not a burst of 13).
  const downloads = [];
  page.on('download', (d) => downloads.push(d));
  await page.click('#svg-all');
  await page.waitForFunction(() => /SVGs/.test(document.getElementById('export-status').textContent), null, { timeout: 60_000 });
  await page.waitForTimeout(300);
  assert.equal(downloads.length, 1, 'one download');
  assert.equal(downloads[0].suggestedFilename(), 'ridelab-charts-svg-sedan-B-20ms.zip');
  const entries = readZip(fs.readFileSync(await downloads[0].path()));
  const files = entries.map((e) => e.name);
  assert.equal(files.length, 13, files.join(', '));
  assert.ok(files.includes('ridelab-map-sws-sedan-B-20ms.svg'), files.join(', '));
  for (const e of entries) assert.match(e.data.toString('utf8'), /^<svg/, e.name);
  assert.deepEqual(log.errors, [], 'console errors');
  await context.close();
});

test('on-screen charts: plotters draws them on the canvas at the core layout; bad arguments name the field', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await openWired();
  const res = await page.evaluate(() => {
    const { api } = window.__ridelab;
    // A known chart at twice the resolution: a red diagonal over 0..10 x 0..10.
    const c = document.createElement('canvas');
    c.width = 800;
    c.height = 600;
    const spec = {
      xLabel: 'x [m]',
      yLabel: 'y [m]',
      xRange: [0, 10],
      yRange: [0, 10],
      width: 400,
      height: 300,
      legend: 'none',
      series: [{ colour: '#ff0000', points: [[0, 0], [10, 10]], size: 3 }],
    };
    const placed = api.drawLineChart(c, spec, 2, 'all');
    const d = c.getContext('2d').getImageData(0, 0, 800, 600).data;
    const rgb = (x, y) => Array.from(d.slice(4 * (y * 800 + x), 4 * (y * 800 + x) + 3));
    const f = placed.frame;
    // The data point (5, 5) lands mid-frame (device px = 2 x logical).
    const mid = rgb(Math.round(f.left + f.right), Math.round(f.top + f.bottom));
    // Tick labels and the axis description: dark pixels left of the frame, below it.
    let left = 0;
    let below = 0;
    for (let y = 0; y < 600; y++) {
      for (let x = 0; x < 800; x++) {
        const k = 4 * (y * 800 + x);
        const dark = d[k] + d[k + 1] + d[k + 2] < 300;
        if (dark && x < 2 * f.left - 4 && y < 2 * f.bottom) left++;
        if (dark && y > 2 * f.bottom + 4) below++;
      }
    }
    const fail = (fn) => {
      try {
        fn();
        return null;
      } catch (e) {
        return { field: e.field, message: e.message };
      }
    };
    const map = { unit: 'u [m]', nx: 2, ny: 2, values: [1, 2, 3, 4], designBox: { ks_min: 1e4, ks_max: 4e4, cs_min: 500, cs_max: 4000 }, width: 400, height: 300 };
    const mapPlaced = api.drawMapFrame(c, map, 1);
    // The frame's contour lines are contourSegments' on the spec's values at its levels.
    const lines = (xs) => Array.from(xs, (a) => Array.from(a));
    mapPlaced.contours = lines(mapPlaced.contours);
    const segments = lines(api.contourSegments(new Float64Array(map.values), 2, 2, new Float64Array(mapPlaced.levels)));
    return {
      segments,
      placed,
      corner: rgb(2, 2),
      mid,
      left,
      below,
      mapPlaced,
      layer: fail(() => api.drawLineChart(c, spec, 1, 'bogus')),
      scale: fail(() => api.drawLineChart(c, spec, 0, 'all')),
      colour: fail(() => api.drawLineChart(c, { ...spec, series: [{ colour: 'red', points: [[1, 1]] }] }, 1, 'all')),
      values: fail(() => api.drawMapFrame(c, { ...map, values: [1, 2, 3] }, 1)),
      box: fail(() => api.drawMapFrame(c, { ...map, designBox: { ...map.designBox, ks_max: 1 } }, 1)),
    };
  });
  // The core's line chart layout (crate/src/chart/line): left 80, right width - 21,
  // top 12 without a title, bottom height - 53.
  assert.deepEqual(res.placed.frame, { left: 80, right: 379, top: 12, bottom: 247 });
  assert.deepEqual([res.placed.x.lo, res.placed.x.hi, res.placed.y.lo, res.placed.y.hi], [0, 10, 0, 10]);
  assert.deepEqual(res.corner, [255, 255, 255], 'white background');
  assert.ok(res.mid[0] > 200 && res.mid[1] < 60 && res.mid[2] < 60, `the line at mid-frame: ${res.mid}`);
  assert.ok(res.left > 300, `y tick labels and description drawn (${res.left} dark px)`);
  assert.ok(res.below > 300, `x tick labels and description drawn (${res.below} dark px)`);
  // The map layout (crate/src/chart/map): left 62, right width - 95; the bar 8 px inside.
  assert.deepEqual(res.mapPlaced.frame, { left: 62, right: 305, top: 12, bottom: 247 });
  assert.deepEqual([res.mapPlaced.bar.top, res.mapPlaced.bar.bottom], [20, 239]);
  // At most one tick per 36 px of bar: 219 px, 6 ticks at most, so a step of 1 over 1..4.
  assert.deepEqual(res.mapPlaced.barTicks, [1, 2, 3, 4]);
  // The contour levels: the ticks strictly inside the colour range 1..4; a line each, the
  // one contourSegments traces on the same values (one way: the values went once).
  assert.deepEqual(res.mapPlaced.levels, [2, 3]);
  assert.deepEqual(res.mapPlaced.contours, res.segments);
  assert.ok(res.segments.every((s) => s.length >= 4), `a segment per level: ${JSON.stringify(res.segments)}`);
  assert.equal(res.layer.field, 'layer');
  assert.equal(res.scale.field, 'scale');
  assert.equal(res.colour.field, 'series[0].colour');
  assert.equal(res.values.field, 'values');
  assert.equal(res.box.field, 'designBox');

  assert.deepEqual(log.errors, [], 'console errors');
  await context.close();
});
