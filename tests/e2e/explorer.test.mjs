// End-to-end tests of the RideLab page in headless Chromium.
//
//   trunk build --release --offline      # builds dist/
//   node --test tests/e2e/               # or: npm run test:e2e
//
// Serves dist/ on a free localhost port, drives /usr/bin/chromium with playwright-core,
// checks pixels on the map canvases, the readout against the native code, the URL
// state, every bad-input message, and prints the timing figures. Screenshots go to
// tests/e2e/out/ (gitignored).

import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';
import { execFileSync } from 'node:child_process';
import { openPage, settled } from './browser.mjs';
import { useSuite, assertClean, ROOT, DIST, OUT } from './harness.mjs';

const TIMEOUT = 90_000;
const figures = {};
const suite = useSuite({
  onAfter: () => {
    if (Object.keys(figures).length) {
      fs.writeFileSync(path.join(OUT, 'figures.json'), JSON.stringify(figures, null, 2));
      console.log(`figures: ${JSON.stringify(figures)}`);
    }
  },
});

// ------------------------------------------------------------------ helpers

/** Opens the page at `hash` (and `query`), waits until every view is ready. */
function open(hash = '', { query = '', dpr = 1, width = 1400, height = 1000 } = {}) {
  return openPage(suite.browser, suite.srv.url + query + hash, { width, height, dpr });
}

/** Waits until every view shows the current state and the URL has been written. */
function settle(page) {
  return settled(page, 200); // the URL is written 120 ms after the last change
}

/** The criteria table as `{"bacc.lofi": value, ...}` (full-precision SI values). */
function readout(page) {
  return page.evaluate(() => {
    const out = {};
    for (const tr of document.querySelectorAll('#criteria tbody tr')) {
      for (const td of tr.querySelectorAll('td[data-model]')) {
        out[`${tr.dataset.crit}.${td.dataset.model}`] = td.dataset.value === undefined ? null : Number(td.dataset.value);
      }
    }
    return out;
  });
}

/** Statistics of a canvas (or its plot area): distinct colours, hatch-grey and opaque pixels. */
function canvasStats(page, id, plotOnly = true) {
  return page.evaluate(
    ([id, plotOnly]) => {
      const c = document.getElementById(id);
      const view = window.__ridelab.views.find((v) => v.base === c || v.overlay === c);
      const dpr = view.size.dpr;
      let x0 = 0;
      let y0 = 0;
      let w = c.width;
      let h = c.height;
      if (plotOnly) {
        const { plot } = view.layout();
        x0 = Math.ceil(plot.x * dpr) + 2;
        y0 = Math.ceil(plot.y * dpr) + 2;
        w = Math.floor(plot.w * dpr) - 4;
        h = Math.floor(plot.h * dpr) - 4;
      }
      const d = c.getContext('2d').getImageData(x0, y0, w, h).data;
      const colours = new Set();
      let grey = 0;
      let opaque = 0;
      for (let k = 0; k < d.length; k += 4) {
        colours.add((d[k] << 16) | (d[k + 1] << 8) | d[k + 2]);
        if (d[k + 3] > 0) opaque++;
        // The hatch lines: dark grey (no colour of either colour map is).
        const mx = Math.max(d[k], d[k + 1], d[k + 2]);
        const mn = Math.min(d[k], d[k + 1], d[k + 2]);
        if (d[k + 3] === 255 && mx - mn < 30 && mx < 120) grey++;
      }
      return {
        width: c.width, height: c.height, cssWidth: c.clientWidth, cssHeight: c.clientHeight, dpr,
        colours: colours.size, grey, opaque, pixels: w * h,
      };
    },
    [id, plotOnly],
  );
}

/** Where the design marker of map `k` is (CSS px in the overlay) and what is drawn there. */
function marker(page, k = 0) {
  return page.evaluate((k) => {
    const a = window.__ridelab;
    const v = a.views[k];
    const { plot, fs } = v.layout();
    const [x, y] = v.toPlot(a.state.ks, a.state.cs, plot);
    const r = Math.max(4, fs * 0.45);
    const g = v.overlay.getContext('2d');
    const px = (dx, dy) => Array.from(g.getImageData(Math.round((x + dx) * v.size.dpr), Math.round((y + dy) * v.size.dpr), 1, 1).data);
    return { x, y, centre: px(0, 0), ring: px(r * 0.55, 0) };
  }, k);
}

function relErr(a, b) {
  return Math.abs(a / b - 1);
}

// ------------------------------------------------------------------ tests

test('loads clean: no console errors, no other hosts (load timing and wasm size printed)', { timeout: TIMEOUT }, async (t) => {
  const { page, context, log } = await open();
  const timing = await page.evaluate(() => ({
    interactive: window.__ridelab.interactiveAt,
    ready: window.__ridelab.readyAt,
    marks: window.__ridelab.marks,
    nav: performance.getEntriesByType('navigation')[0].toJSON(),
  }));
  t.diagnostic(`script start ${timing.marks.start.toFixed(0)} ms, wasm ready ${timing.marks.wasm.toFixed(0)} ms, DOMContentLoaded ${timing.nav.domContentLoadedEventEnd.toFixed(0)} ms`);
  await page.screenshot({ path: path.join(OUT, 'default.png'), fullPage: true });
  assertClean(log);
  assert.equal(await page.locator('#banner').isHidden(), true, 'no banner on a clean load');
  // The first screen's module (fetched before the first map) and the workers' (after it).
  const first = fs.readFileSync(path.join(DIST, 'ridelab-first_bg.wasm'));
  const firstGz = zlib.gzipSync(first, { level: 9 }).length;
  const wasm = fs.readFileSync(path.join(DIST, 'ridelab_bg.wasm'));
  const gz = zlib.gzipSync(wasm, { level: 9 }).length;
  figures.loadToFirstMapMs = Math.round(await page.evaluate(() => window.__ridelab.firstMapAt));
  figures.loadToInteractiveMs = Math.round(timing.interactive);
  figures.loadToHiFiReadyMs = Math.round(timing.ready);
  figures.wasmBytes = wasm.length;
  figures.wasmGzipBytes = gz;
  figures.firstWasmBytes = first.length;
  figures.firstWasmGzipBytes = firstGz;
  t.diagnostic(`load to the first map drawn: ${figures.loadToFirstMapMs} ms (target 1 s)`);
  t.diagnostic(`load to interactive (LoFi readout + maps drawn): ${timing.interactive.toFixed(0)} ms`);
  t.diagnostic(`load to every view ready (HiFi readout too): ${timing.ready.toFixed(0)} ms`);
  t.diagnostic(`ridelab-first_bg.wasm (before the first map): ${first.length} bytes, ${firstGz} bytes gzipped (zlib level 9); ridelab_bg.wasm (the workers'): ${wasm.length} bytes, ${gz} gzipped`);
  await context.close();
});

test('a link to the HiFi or error maps starts the workers once its first screen is painted, not at the 5 s fallback', { timeout: TIMEOUT }, async () => {
  for (const model of ['hifi', 'error']) {
    const { page, context, log } = await open(`#model=${model}`);
    await page.waitForFunction((m) => window.__ridelab.modelMaps?.model === m, model, { timeout: 30_000 });
    const r = await page.evaluate(() => ({ by: window.__ridelab.firstScreenBy, firstMapAt: window.__ridelab.firstMapAt }));
    assert.equal(r.by, 'page', `${model}: the workers started with the page's first screen`);
    assert.equal(r.firstMapAt, null, `${model}: no LoFi map was drawn first`);
    assertClean(log);
    await context.close();
  }
  // The default view starts them with its first map.
  const { page, context } = await open();
  assert.equal(await page.evaluate(() => window.__ridelab.firstScreenBy), 'page');
  await context.close();
});

test('the three maps draw colour maps, hatching, axes and markers', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  for (const key of ['bacc', 'dtl', 'sws']) {
    const s = await canvasStats(page, `map-${key}`);
    assert.ok(s.colours > 200, `${key}: plot has ${s.colours} distinct colours (a real colour map)`);
    assert.ok(s.grey > 0.01 * s.pixels, `${key}: hatching where SWS > 7 mm (${s.grey} of ${s.pixels} px)`);
    const whole = await canvasStats(page, `map-${key}`, false);
    assert.equal(whole.width, Math.round(whole.cssWidth * whole.dpr), 'canvas sized in device pixels');
    const o = await canvasStats(page, `map-${key}-overlay`, false);
    assert.ok(o.opaque > 50, `${key}: markers drawn on the overlay`);
  }
  const m = await marker(page);
  assert.deepEqual(m.centre.slice(0, 3), [0, 0, 0], 'design marker: black centre');
  assert.ok(m.ring.every((c) => c > 200), `design marker: white ring (${m.ring})`);
  assertClean(log);
  await context.close();
});

test('moving the Ks slider changes the readout and the marker', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  const before = await readout(page);
  const m0 = await marker(page);
  await page.focus('#ks-range');
  for (let i = 0; i < 20; i++) await page.keyboard.press('ArrowRight');
  await settle(page);
  const after = await readout(page);
  const m1 = await marker(page);
  const ks = await page.evaluate(() => window.__ridelab.state.ks);
  assert.equal(ks, 19960 + 20 * 100, 'twenty 0.1 kN/m steps from the datum, 19.96 kN/m');
  assert.equal(await page.inputValue('#ks-num'), String(ks / 1000));
  for (const k of ['bacc.lofi', 'bacc.hifi', 'dtl.lofi', 'dtl.hifi']) {
    assert.notEqual(after[k], before[k], `${k} changed`);
  }
  assert.ok(after['bacc.lofi'] > before['bacc.lofi'], 'a stiffer spring gives more body acceleration');
  assert.ok(after['bacc.lofi-d'] > 0 && after['bacc.hifi-d'] > 0, 'change vs datum is positive');
  assert.ok(m1.x > m0.x + 5, `marker moved right (${m0.x.toFixed(1)} -> ${m1.x.toFixed(1)})`);
  assert.equal(m1.y, m0.y, 'marker kept its Cs');
  assert.ok(m1.ring.every((c) => c > 200), `marker drawn at the new place (${m1.ring})`);
  assert.match(page.url(), /ks=21960/, 'URL follows the design');
  assertClean(log);
  await context.close();
});

test('a slider step crosses into the wasm twice on the main thread (setState, designStep)', { timeout: TIMEOUT }, async () => {
  // It was four (setDesign, the LoFi report, the surrogate's criteria, the HiFi readout)
  // and five with Wk comfort (the plane's model's criteria); issue #28. The setter is now
  // setState (the core keeps the scenario when only Ks and Cs changed).
  for (const hash of ['', '#comfort=wk']) {
    const { page, context, log } = await open(hash);
    const calls = () => page.evaluate(() => window.__ridelab.engine.host.wasmCalls);
    await page.focus('#ks-range');
    for (let i = 0; i < 3; i++) {
      const before = await calls();
      await page.keyboard.press('ArrowRight');
      await settle(page);
      assert.equal((await calls()) - before, 2, `${hash || 'default'}: step ${i + 1}`);
    }
    assert.equal(await page.evaluate(() => window.__ridelab.state.ks), 19960 + 3 * 100);
    const r = await page.evaluate(() => window.__ridelab.hifi.design);
    assert.equal(r.ks, 19960 + 3 * 100, 'the HiFi column follows');
    assertClean(log);
    await context.close();
  }
});

/** Native reference numbers: the `ridelab` CLI (RIDELAB_CLI, else target/debug or target/release). */
function nativeReference() {
  const car = path.join(ROOT, 'assets/cars/sedan.json');
  const candidates = [process.env.RIDELAB_CLI, path.join(ROOT, 'target/debug/ridelab'), path.join(ROOT, 'target/release/ridelab')];
  const cli = candidates.filter(Boolean).find((c) => fs.existsSync(c));
  assert.ok(cli, 'the native CLI is built (cargo build -p ridelab)');
  const run = (model) =>
    JSON.parse(execFileSync(cli, ['eval', '--model', model, '--car', car, '--class', 'B', '--speed', '20', '--json'], { encoding: 'utf8' }));
  return { source: `CLI ${path.relative(ROOT, cli)}`, quarter: run('quarter'), full: run('full') };
}

test('datum readout at class B 20 m/s equals the native code to 1e-9', { timeout: TIMEOUT }, async (t) => {
  const ref = nativeReference();
  t.diagnostic(`reference: ${ref.source}`);
  const { page, context, log } = await open('#car=sedan&class=B&speed=20&tracks=correlated');
  const r = await readout(page);
  let worst = 0;
  for (const [model, col] of [['quarter', 'lofi'], ['full', 'hifi']]) {
    for (const k of ['bacc', 'dtl', 'sws']) {
      const e = relErr(r[`${k}.${col}`], ref[model][k]);
      worst = Math.max(worst, e);
      assert.ok(e <= 1e-9, `${model} ${k}: page ${r[`${k}.${col}`]} vs native ${ref[model][k]} (rel ${e})`);
    }
  }
  t.diagnostic(`largest relative difference page vs native: ${worst.toExponential(2)}`);
  figures.pageVsNativeMaxRelDiff = worst;
  assertClean(log);
  await context.close();
});

test('the worker and the main thread give identical numbers', { timeout: TIMEOUT }, async () => {
  // A car with unequal track widths on independent tracks: the road warp needs the low cut-off.
  const car = JSON.parse(fs.readFileSync(path.join(ROOT, 'assets/cars/sedan.json'), 'utf8'));
  Object.assign(car, { name: 'Sedan, published tracks', track_front: 1.522, track_rear: 1.51 });
  const hash = `#car=custom&carjson=${encodeURIComponent(JSON.stringify(car))}&class=D&speed=27&ks=31000&cs=2100&tracks=independent`;
  const a = await open(hash);
  const b = await open(hash, { query: '?engine=main' });
  assert.deepEqual(await readout(a.page), await readout(b.page));
  assert.match(await a.page.textContent('#version'), /worker thread/);
  assert.match(await b.page.textContent('#version'), /main thread/);
  assert.match(await a.page.textContent('#route-note'), /lowest frequency/, 'independent tracks: the low cut-off is explained');
  assertClean(a.log);
  assertClean(b.log);
  await a.context.close();
  await b.context.close();
});

test('URL state round-trips: a link reproduces the view', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  await page.selectOption('#class', 'D');
  await page.fill('#speed', '25');
  await page.press('#speed', 'Enter');
  await page.fill('#ks-num', '30.5');
  await page.press('#ks-num', 'Enter');
  await page.fill('#cs-num', '2.25');
  await page.press('#cs-num', 'Enter');
  await page.click('#tab-car');
  await page.selectOption('#tracks', 'independent');
  await page.keyboard.press('Escape');
  await page.selectOption('#car', 'suv');
  await page.fill('#ks-num', '33');
  await page.press('#ks-num', 'Enter');
  await page.selectOption('#map-scale', 'rel');
  await page.fill('#sws-limit', '9');
  await page.press('#sws-limit', 'Enter');
  await settle(page);
  const url = page.url();
  assert.match(url, /car=suv/);
  assert.match(url, /ks=33000/);
  assert.match(url, /class=D/);
  assert.match(url, /speed=25/);
  assert.match(url, /tracks=independent/);
  assert.match(url, /sws=9/);
  assert.match(url, /scale=rel/);
  const first = await readout(page);
  const state = await page.evaluate(() => window.__ridelab.state);
  await page.screenshot({ path: path.join(OUT, 'relative-suv-D.png'), fullPage: true });

  const again = await open(new URL(url).hash);
  assert.deepEqual(await readout(again.page), first, 'same readout from the link');
  assert.deepEqual(await again.page.evaluate(() => window.__ridelab.state), state, 'same state from the link');
  assert.equal(await again.page.inputValue('#ks-num'), '33');
  assert.equal(await again.page.inputValue('#class'), 'D');
  assert.equal(await again.page.inputValue('#car'), 'suv');
  assert.equal(await again.page.inputValue('#map-scale'), 'rel');
  await page.reload();
  await page.waitForFunction(() => window.__ridelab && window.__ridelab.ready);
  assert.deepEqual(await readout(page), first, 'same readout after a reload');

  // A link that names only the car shows that car's own (datum) design.
  const suv = await open('#car=suv');
  const st = await suv.page.evaluate(() => window.__ridelab.state);
  const preset = await suv.page.evaluate(() => window.__ridelab.presets.find((p) => p.name === 'suv'));
  assert.equal(st.ks, preset.ks);
  assert.equal(st.cs, preset.cs);
  const r = await readout(suv.page);
  for (const k of ['bacc', 'dtl', 'sws']) assert.equal(r[`${k}.lofi-d`], 0, `${k}: the datum itself`);
  assertClean(suv.log);
  await suv.context.close();
  assertClean(log);
  assertClean(again.log);
  await again.context.close();
  await context.close();
});

test('URL round trip: every key at a non-default value reopens the same state, view, readout and controls', { timeout: TIMEOUT }, async () => {
  const car = { ...JSON.parse(fs.readFileSync(path.join(ROOT, 'assets/cars/sedan.json'), 'utf8')), name: 'Link car', sprung_mass: 1380 };
  const keys = {
    car: 'custom',
    carjson: JSON.stringify(car),
    ks: '31000',
    cs: '2100',
    class: 'A',
    speed: '25',
    tracks: 'independent',
    sws: '9',
    box: '12000,38000,600,3800',
    bb: '0.9,1.6',
    db: '0.15,0.6',
    nw: '0,1,0',
    dm: '14',
    tr: '0.02,3',
    sur: 'vba-qts',
    plan: 'grid:4',
    comfort: 'wk',
    pick: 'asf:0.3',
    model: 'surrogate',
    samples: '0',
    scale: 'rel',
    axes: 'ratio',
    pal: 'cividis',
    proj: '1',
    cases: JSON.stringify({ load_cases: [{ name: 'driver only', mass: 0 }, { name: 'laden', mass: 200, x: -0.4 }], operating: [{ class: 'A', speed: 25 }], combine: 'mean' }),
    case: '1',
  };
  const hash = '#' + new URLSearchParams(keys).toString();
  const a = await open(hash);
  await settle(a.page);
  const read = (page) => page.evaluate(() => {
    const r = window.__ridelab;
    const ids = ['ks-num', 'cs-num', 'class', 'speed', 'tracks', 'sws-limit', 'ks-min', 'ks-max', 'cs-min', 'cs-max', 'bb-lo', 'bb-hi', 'db-lo', 'db-hi',
      'sur-approach', 'sur-plan', 'map-model', 'map-scale', 'map-palette', 'op-scale', 'car', 'comfort', 'pick-rule', 'pick-weight'];
    const controls = Object.fromEntries(ids.map((id) => [id, document.getElementById(id).value]));
    for (const id of ['nw-bacc', 'nw-dtl', 'nw-sws', 'show-plan', 'projector']) controls[id] = document.getElementById(id).checked;
    const { nsga, ...view } = r.view;
    return { state: r.state, view, controls, url: location.hash };
  });
  const first = await read(a.page);
  // The state and view the link asked for, in full.
  assert.deepEqual(first.state, {
    car: 'custom', carJson: keys.carjson, ks: 31000, cs: 2100, class: 'A', speed: 25, tracks: 'independent',
    ksMin: 12000, ksMax: 38000, csMin: 600, csMax: 3800, swsLimit: 0.009, bounceBand: [0.9, 1.6], dampingBand: [0.15, 0.6],
    noWorse: [false, true, false], dtlMargin: 14, travel: [0.02, 3], surrogate: 'vba-qts', plan: 'grid:4',
    comfort: 'wk', pick: 'asf:0.3', cases: keys.cases, case: '1',
  });
  assert.deepEqual(first.view, { scale: 'rel', projector: true, model: 'surrogate', plan: false, ratio: true, palette: 'cividis' });
  assert.equal(first.controls['cs-min'], '0.6');
  assert.equal(first.controls['cs-max'], '3.8');
  assert.equal(first.controls['db-lo'], '0.15');
  assert.equal(first.controls['sur-plan'], 'grid:4');
  assert.deepEqual([first.controls.comfort, first.controls['pick-rule'], first.controls['pick-weight']], ['wk', 'asf', '0.3']);
  assert.equal(first.controls['map-model'], 'surrogate');
  assert.equal(first.controls['show-plan'], false);
  // The page writes every key back, and the written link reopens the same page.
  const written = new URLSearchParams(first.url.slice(1));
  for (const k of Object.keys(keys)) assert.ok(written.has(k), `the page's link has '${k}' (${first.url})`);
  const firstReadout = await readout(a.page);
  const b = await open(first.url);
  await settle(b.page);
  const second = await read(b.page);
  assert.deepEqual(second, first, 'same state, view, controls and link');
  assert.deepEqual(await readout(b.page), firstReadout, 'same readout');
  assertClean(a.log);
  assertClean(b.log);
  await a.context.close();
  await b.context.close();
});

test('a corrupt or invalid URL shows a message and falls back to the defaults', { timeout: TIMEOUT }, async () => {
  const clean = await open();
  const defaults = await readout(clean.page);
  await clean.context.close();
  // One malformed value per key of the link.
  const cases = [
    ['#ks=abc&class=B', /ks: 'abc' is not a number/],
    ['#cs=0', /Cs \(front damper\): must be > 0/],
    ['#class=Z', /class: 'Z' is not an ISO 8608 class/],
    ['#speed=-5', /speed: must be a finite number > 0/],
    ['#tracks=diagonal', /tracks: 'diagonal' is not/],
    ['#car=hovercraft', /no preset named 'hovercraft'/],
    ['#car=custom&carjson=%7Bnot%20json', /not a valid car file: key must be a string \(line 1, column 2\)/],
    ['#sws=seven', /sws: 'seven' is not a number/],
    ['#box=10000,40000,500', /box: '10000,40000,500' is not 4 numbers/],
    ['#box=10000,40000,4000,500', /Design box: Cs from 4 must be below 0\.5 kNs\/m/],
    ['#bb=1.2', /bb: '1.2' is not 2 numbers/],
    ['#db=0.5,0.2', /Damping band: needs finite 0 <= lo < hi/],
    ['#nw=1,2,0', /nw: '1,2,0' is not three 0\/1 flags/],
    ['#sur=kriging', /kriging/],
    ['#plan=ae%3A500', /at most 100/],
    ['#model=best', /model: 'best' is not/],
    ['#samples=2', /samples: '2' is not 0 or 1/],
    ['#scale=big', /scale: 'big' is not/],
    ['#axes=log', /axes: 'log' is not/],
    ['#pal=rainbow', /pal: 'rainbow' is not/],
    ['#proj=yes', /proj: 'yes' is not 0 or 1/],
    ['#cases=%7B%22combine%22%3A%22median%22%7D', /cases\.combine/],
    ['#case=2', /case/],
    ['#zoom=3', /unknown key 'zoom'/],
    ['#%E0%A4%A', /./],
  ];
  // The first case opens the page with the link; the others arrive as hash changes on a
  // page showing a good view (the same reading and checking of the link).
  const good = '#class=A&speed=30';
  const { page, context, log } = await open(cases[0][0]);
  const banner = page.locator('#banner');
  for (const [i, [hash, message]] of cases.entries()) {
    if (i > 0) {
      await page.evaluate((h) => (location.hash = h), good);
      await page.waitForFunction(() => window.__ridelab.state.class === 'A');
      await settle(page);
      await page.click('#banner-close');
      await page.evaluate((h) => (location.hash = h), hash);
      await page.waitForFunction(() => !document.getElementById('banner').hidden);
      await settle(page);
    }
    assert.equal(await banner.isVisible(), true, `${hash}: message shown`);
    // Undecodable percent escapes are read leniently by URLSearchParams: an unknown key.
    assert.match(await banner.textContent(), message, `${hash}: message names the problem`);
    // The key named keeps its default (the rest of a link applies: none here).
    assert.match(await banner.textContent(), /kept the default|default view/);
    assert.deepEqual(await readout(page), defaults, `${hash}: default readout`);
    if (hash === '#ks=abc&class=B') await page.screenshot({ path: path.join(OUT, 'corrupt-url.png') });
  }
  await page.click('#banner-close');
  assert.equal(await banner.isHidden(), true, 'the message can be dismissed');
  assertClean(log);
  await context.close();
});

test('each bad input shows its message next to the field and keeps the last good state', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  const good = await readout(page);
  const goodUrl = page.url();
  const cases = [
    ['#speed', 'speed', '-5', /speed: must be a finite number > 0 \(m\/s\)/],
    ['#speed', 'speed', '', /enter a number/],
    ['#speed', 'speed', 'NaN', /'NaN' is not a number/],
    ['#speed', 'speed', '1e999', /not a finite number/],
    ['#speed', 'speed', '150', /150 m\/s is outside 1\.\.100 m\/s/],
    ['#ks-num', 'ks', '-5', /Ks \(front spring\): must be > 0 \(got −5 kN\/m\)/],
    ['#ks-num', 'ks', 'abc', /'abc' is not a number/],
    ['#ks-num', 'ks', '0', /must be > 0/],
    ['#cs-num', 'cs', '0', /unbounded/],
    ['#cs-num', 'cs', '-1', /must not be negative/],
    ['#cs-num', 'cs', '', /enter a number/],
    ['#sws-limit', 'swsLimit', '0', /SWS limit: must be a number > 0 \(mm\)/],
    ['#sws-limit', 'swsLimit', 'seven', /not a number/],
  ];
  for (const [sel, field, text, message] of cases) {
    await page.fill(sel, text);
    await page.press(sel, 'Enter');
    await settle(page);
    const msg = page.locator(`#msg-${field}`);
    assert.equal(await msg.isVisible(), true, `${sel} '${text}': message visible`);
    assert.match(await msg.textContent(), message, `${sel} '${text}'`);
    assert.equal(await page.getAttribute(sel, 'aria-invalid'), 'true');
    assert.deepEqual(await readout(page), good, `${sel} '${text}': last good state kept`);
    assert.equal(page.url(), goodUrl, `${sel} '${text}': URL unchanged`);
    if (sel === '#speed' && text === '-5') {
      await page.fill('#cs-num', '0');
      await page.press('#cs-num', 'Enter');
      await settle(page);
      await page.screenshot({ path: path.join(OUT, 'bad-inputs.png') });
      await page.fill('#cs-num', '1.29');
      await page.press('#cs-num', 'Enter');
      await settle(page);
    }
    // Escape restores the field; the message goes.
    await page.press(sel, 'Escape');
    assert.equal(await msg.isVisible(), false, `${sel}: message cleared by Escape`);
  }
  // A bad car file names the field; a good one becomes the datum and travels in the URL.
  const bad = JSON.parse(fs.readFileSync(path.join(ROOT, 'assets/cars/sedan.json'), 'utf8'));
  bad.sprung_mass = -3;
  await page.setInputFiles('#car-file', { name: 'bad.json', mimeType: 'application/json', buffer: Buffer.from(JSON.stringify(bad)) });
  await page.waitForFunction(() => document.getElementById('msg-carFile').textContent !== '');
  assert.match(await page.textContent('#msg-carFile'), /bad\.json: sprung_mass: must be > 0/);
  const misspelt = fs.readFileSync(path.join(ROOT, 'assets/cars/sedan.json'), 'utf8').replace('"pitch_inertia"', '"pitch_inertai"');
  await page.setInputFiles('#car-file', { name: 'typo.json', mimeType: 'application/json', buffer: Buffer.from(misspelt) });
  await page.waitForFunction(() => /typo/.test(document.getElementById('msg-carFile').textContent));
  assert.match(await page.textContent('#msg-carFile'), /'pitch_inertai' is not a known field/);
  assert.deepEqual(await readout(page), good, 'bad car files change nothing');
  const mine = { ...JSON.parse(fs.readFileSync(path.join(ROOT, 'assets/cars/sedan.json'), 'utf8')), name: 'Test hatchback', sprung_mass: 1100 };
  await page.setInputFiles('#car-file', { name: 'mine.json', mimeType: 'application/json', buffer: Buffer.from(JSON.stringify(mine)) });
  await settle(page);
  assert.equal(await page.textContent('#msg-carFile'), '');
  assert.match(await page.textContent('#note-car'), /The design moved to Test hatchback's own front/, 'the page says the design moved');
  assert.match(await page.locator('#car option:checked').textContent(), /Test hatchback/);
  const custom = await readout(page);
  assert.notDeepEqual(custom, good);
  assert.match(page.url(), /car=custom&carjson=/);
  const again = await open(new URL(page.url()).hash);
  assert.deepEqual(await readout(again.page), custom, 'a custom car travels in the link');
  await again.context.close();
  assertClean(log);
  await context.close();
});

test('class C: no feasible design, and the page says so', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  await page.selectOption('#class', 'C');
  await settle(page);
  const status = page.locator('#map-status');
  assert.match(await status.textContent(), /No design in the box meets the design objectives on class C .*100 % break the SWS limit/);
  assert.match((await status.getAttribute('class')) || '', /bad/);
  const s = await canvasStats(page, 'map-bacc');
  assert.ok(s.grey > 0.08 * s.pixels, `the whole map is hatched (${s.grey} of ${s.pixels} px)`);
  const b = await open();
  const sb = await canvasStats(b.page, 'map-bacc');
  assert.ok(s.grey > 3 * sb.grey, 'far more hatching than at class B');
  await b.context.close();
  await page.screenshot({ path: path.join(OUT, 'class-c.png'), fullPage: true });
  assertClean(log);
  await context.close();
});

test('clicking and dragging on a map sets Ks and Cs', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  await page.locator('#map-dtl-overlay').scrollIntoViewIfNeeded();
  const geo = await page.evaluate(() => {
    const v = window.__ridelab.views[1];
    const r = v.overlay.getBoundingClientRect();
    const { plot } = v.layout();
    return { left: r.left + plot.x, top: r.top + plot.y, w: plot.w, h: plot.h };
  });
  const at = (u, v) => [geo.left + u * geo.w, geo.top + (1 - v) * geo.h];
  await page.mouse.click(...at(0.5, 0.75));
  await settle(page);
  let s = await page.evaluate(() => window.__ridelab.state);
  assert.ok(Math.abs(s.ks - 25000) <= 30000 / geo.w + 10, `click: ks ${s.ks}`);
  assert.ok(Math.abs(s.cs - (500 + 0.75 * 3500)) <= 3500 / geo.h + 5, `click: cs ${s.cs}`);
  assert.equal(await page.inputValue('#cs-num'), String(s.cs / 1000));
  await page.mouse.move(...at(0.2, 0.3));
  await page.mouse.down();
  await page.mouse.move(...at(0.5, 0.5), { steps: 5 });
  await page.mouse.move(...at(0.9, 0.6), { steps: 5 });
  await page.mouse.up();
  await settle(page);
  s = await page.evaluate(() => window.__ridelab.state);
  assert.ok(Math.abs(s.ks - (10000 + 0.9 * 30000)) <= 30000 / geo.w + 10, `drag: ks ${s.ks}`);
  assert.ok(Math.abs(s.cs - (500 + 0.6 * 3500)) <= 3500 / geo.h + 5, `drag: cs ${s.cs}`);
  const m = await marker(page, 1);
  const plot = await page.evaluate(() => window.__ridelab.views[1].layout().plot);
  assert.ok(Math.abs(m.x - (plot.x + 0.9 * plot.w)) < 2, `marker under the pointer (${m.x} vs ${plot.x + 0.9 * plot.w})`);
  assert.ok(Math.abs(m.y - (plot.y + 0.4 * plot.h)) < 2, 'marker under the pointer (y)');
  assertClean(log);
  await context.close();
});

test('HiDPI canvases and projector mode', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open('', { dpr: 2 });
  const s = await canvasStats(page, 'map-dtl', false);
  assert.equal(s.dpr, 2);
  assert.equal(s.width, Math.round(s.cssWidth * 2), 'backing store at 2x');
  assert.equal(s.height, Math.round(s.cssHeight * 2));
  await page.screenshot({ path: path.join(OUT, 'hidpi.png'), fullPage: true });
  await page.locator('.maps').screenshot({ path: path.join(OUT, 'hidpi-maps.png') });

  const font0 = await page.evaluate(() => getComputedStyle(document.documentElement).fontSize);
  await page.check('#projector');
  await page.waitForTimeout(300);
  const font1 = await page.evaluate(() => getComputedStyle(document.documentElement).fontSize);
  assert.equal(font0, '15px');
  assert.equal(font1, '19px');
  await settle(page);
  assert.match(page.url(), /proj=1/);
  const s2 = await canvasStats(page, 'map-dtl', false);
  assert.equal(s2.width, Math.round(s2.cssWidth * 2), 'backing store at 2x in projector mode');
  await page.screenshot({ path: path.join(OUT, 'large.png'), fullPage: true });
  const again = await open(new URL(page.url()).hash);
  assert.equal(await again.page.evaluate(() => getComputedStyle(document.documentElement).fontSize), '19px');
  await again.context.close();
  assertClean(log);
  await context.close();
});

test('keyboard: every control is a native, focusable input', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  const tabOrder = async (n) => {
    const order = [];
    for (let i = 0; i < n; i++) {
      await page.keyboard.press('Tab');
      order.push(await page.evaluate(() => document.activeElement.id || document.activeElement.tagName));
    }
    return order;
  };
  // The workbench: the tabs, the design, the scenario, the map options, the maps themselves.
  let order = await tabOrder(36);
  for (const id of ['tab-car', 'tab-help', 'projector', 'ks-range', 'ks-num', 'cs-range', 'cs-num', 'reset-datum', 'to-pick', 'car', 'class', 'speed',
    'sws-range', 'sws-limit', 'map-model', 'map-scale', 'map-palette', 'show-plan', 'map-bacc-pick', 'map-dtl-pick', 'map-sws-pick', 'op-scale', 'op-nsga']) {
    assert.ok(order.includes(id), `${id} reachable with Tab (${order.join(', ')})`);
  }
  // A tab's panel: its controls come next in the order.
  await page.click('#tab-objectives');
  await page.focus('#drawer-close');
  order = await tabOrder(10);
  for (const id of ['ks-min', 'ks-max', 'cs-min', 'cs-max', 'bb-lo', 'bb-hi', 'db-lo', 'db-hi', 'nw-bacc']) {
    assert.ok(order.includes(id), `${id} reachable with Tab in its panel (${order.join(', ')})`);
  }
  await page.keyboard.press('Escape');
  await page.focus('#cs-range');
  await page.keyboard.press('ArrowLeft');
  await settle(page);
  assert.equal(await page.evaluate(() => window.__ridelab.state.cs), 1280);
  await page.focus('#class');
  await page.keyboard.press('ArrowDown');
  await settle(page);
  assert.equal(await page.evaluate(() => window.__ridelab.state.class), 'C');
  assertClean(log);
  await context.close();
});

test('the JS API refuses bad input with messages naming the field, and keeps working', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  const r = await page.evaluate(() => {
    const api = window.__ridelab.api;
    const s = api.defaultState();
    const fail = (f) => {
      try {
        f();
        return null;
      } catch (e) {
        return { message: e.message, field: e.field, isError: e instanceof Error };
      }
    };
    // One session, as the page keeps one per thread: every refused setter leaves it at
    // its last good state, and the constructor refuses a bad state outright.
    const ex = new api.Explorer(s);
    const map = ex.maps('lofi', 4, 3);
    return {
      presets: api.presets().map((p) => p.name),
      mapLength: map.values.length,
      mapIsF64: map.values instanceof Float64Array,
      evaluate: ['lofi', 'hifi'].filter((m) => ex.analyse(m).bacc > 0).sort(),
      empty: fail(() => new api.Explorer({})),
      unknown: fail(() => ex.setState({ ...s, colour: 'red' })),
      speed: fail(() => ex.setState({ ...s, speed: -5 })),
      nan: fail(() => ex.setState({ ...s, speed: NaN })),
      ks: fail(() => ex.setState({ ...s, ks: 0 })),
      cs: fail(() => ex.setState({ ...s, cs: -1 })),
      model: fail(() => ex.analyse('bicycle')),
      grid: fail(() => ex.maps('lofi', 0, 10)),
      hugeGrid: fail(() => ex.maps('lofi', 100000, 10)),
      car: fail(() => api.parseCar('{"name": "x"}')),
      json: fail(() => api.parseCar('{oops')),
      box: fail(() => ex.setState({ ...s, ksMin: 50000 })),
      sws: fail(() => new api.Explorer({ ...s, swsLimit: 0 })),
      after: ex.criteria('lofi').bacc,
      kept: ex.state().speed === s.speed && ex.state().ks === s.ks,
      // The core's marching squares in grid coordinates: f = i on a 3 x 2 grid crosses
      // 0.5 on the vertical x = 0.5 and 1 on the column of nodes x = 1.
      contour: ['0.5', '1'].map((l) => Array.from(api.contourSegments(new Float64Array([0, 1, 2, 0, 1, 2]), 3, 2, new Float64Array([+l]))[0])),
      level: fail(() => api.contourSegments(new Float64Array(6), 3, 2, new Float64Array([NaN]))),
      objectives: api.objectives().map((o) => [o.bit, o.family]),
    };
  });
  assert.deepEqual(r.presets, ['sedan', 'compact', 'suv']);
  assert.equal(r.mapLength, 3 * 4 * 3);
  assert.ok(r.mapIsF64);
  assert.deepEqual(r.evaluate, ['hifi', 'lofi']);
  const expect = {
    empty: ['state', /missing field/],
    unknown: ['state', /unknown field `colour`/],
    speed: ['speed', /^speed: must be a finite number > 0/],
    nan: ['speed', /^speed:/],
    ks: ['ks', /^front\.spring: must be > 0/],
    cs: ['cs', /^front\.damper: must not be negative/],
    model: ['model', /^model: 'bicycle' is not 'quarter' or 'full'/],
    grid: ['nx', /^nx: grid size must be 2\.\.=1001/],
    hugeGrid: ['nx', /^nx:/],
    car: ['car', /missing field/],
    json: ['car', /./],
    box: ['box', /^ks-range: minimum 50000 must be below maximum 40000/],
    sws: ['swsLimit', /^sws_limit:/],
  };
  for (const [k, [field, re]] of Object.entries(expect)) {
    assert.ok(r[k], `${k}: refused`);
    assert.ok(r[k].isError, `${k}: a JS Error`);
    assert.equal(r[k].field, field, `${k}: field (${r[k].message})`);
    assert.match(r[k].message, re, k);
  }
  assert.ok(r.after > 0, 'the module still works after every refusal');
  assert.ok(r.kept, 'the session kept its last good state');
  const seg = (a) => [Math.min(a[1], a[3]), Math.max(a[1], a[3]), a[0], a[2]];
  assert.deepEqual(seg(r.contour[0]), [0, 1, 0.5, 0.5], 'the 0.5 contour of f = i');
  assert.deepEqual(seg(r.contour[1]), [0, 1, 1, 1], 'the contour through a column of nodes');
  assert.equal(r.level.field, 'level');
  assert.deepEqual(r.objectives, [[1, 'limit'], [2, 'band'], [4, 'band'], [8, 'datum'], [16, 'datum'], [32, 'datum'], [64, 'limit'], [128, 'limit']]);
  assertClean(log);
  await context.close();
});
