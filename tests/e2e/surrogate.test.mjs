// End-to-end tests of the surrogate and the design space controls: the surrogate panel
// (metrics against the native CLI), the map model toggle (HiFi and error maps from the
// worker, checked cell by cell against point evaluations), the sample plan on the maps,
// the design box and design-objective editors, the new URL keys and the car editor.
// Screenshots in tests/e2e/out/.
//
//   trunk build --release --offline && npm run test:e2e

import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { openPage, settled } from './browser.mjs';
import { useSuite, assertClean, countColour, ROOT, OUT } from './harness.mjs';

const TIMEOUT = 120_000;
const suite = useSuite();

async function open(hash = '') {
  const r = await openPage(suite.browser, suite.srv.url + hash, { width: 1400, height: 1000 });
  await settled(r.page, 150);
  return r;
}

const settle = (page) => settled(page, 150);

function cli() {
  const candidates = [process.env.RIDELAB_CLI, path.join(ROOT, 'target/debug/ridelab'), path.join(ROOT, 'target/release/ridelab')];
  const c = candidates.filter(Boolean).find((x) => fs.existsSync(x));
  assert.ok(c, 'the native CLI is built (cargo build -p ridelab)');
  return c;
}

test('surrogate panel: metrics equal `ridelab surrogate` to 1e-9 and meet R² ≥ 0.99, RTE ≤ 2 %', { timeout: TIMEOUT }, async (t) => {
  const { page, context, log } = await open();
  const fit = await page.evaluate(() => window.__ridelab.fit);
  assert.equal(fit.surrogate, 'rba-mul-rbf-mq');
  assert.equal(fit.plan, 'ae:10');
  assert.equal(fit.samples.length, 10);
  const car = path.join(ROOT, 'assets/cars/sedan.json');
  const native = JSON.parse(
    execFileSync(cli(), ['surrogate', '--approach', 'rba-mul-rbf-mq', '--plan', 'ae:10', '--car', car, '--class', 'B', '--speed', '20', '--json'], { encoding: 'utf8' }),
  );
  // Same code, same IEEE arithmetic: the page and the CLI agree to rounding (1e-15 seen).
  // The bound leaves room for libm differences (exp, sqrt are correctly rounded; others
  // may differ in the last bit) amplified by the RBF solve.
  let worst = 0;
  let worstAt = '';
  for (const k of ['bacc', 'dtl', 'sws']) {
    for (const m of ['r2', 'rmse', 'max_abs_error', 'rte_max_percent', 'rte_mean_percent']) {
      const a = fit.metrics[k][m];
      const b = native.metrics[k][m];
      const d = Math.abs(a - b) / Math.max(Math.abs(b), 1e-300);
      if (d > worst) [worst, worstAt] = [d, `${k}.${m}`];
    }
    assert.ok(fit.metrics[k].r2 >= 0.99, `${k} R² ${fit.metrics[k].r2}`);
    assert.ok(fit.metrics[k].rte_max_percent <= 2, `${k} max RTE ${fit.metrics[k].rte_max_percent} %`);
  }
  t.diagnostic(`surrogate metrics, page (wasm) vs native CLI: largest relative difference ${worst.toExponential(2)} (${worstAt})`);
  assert.ok(worst < 1e-9, `page vs native metrics: largest relative difference ${worst} (${worstAt})`);
  // The samples (HiFi runs, no fit involved) agree exactly.
  assert.deepEqual(fit.samples, native.samples);
  // The table shows them.
  const shown = await page.locator('#sur-metrics tr[data-crit="sws"] td[data-metric="rte_max_percent"]').getAttribute('data-value');
  assert.equal(Number(shown), fit.metrics.sws.rte_max_percent);
  // The readout's surrogate column: the surrogate at the design, within 1 % of the HiFi.
  const cells = await page.evaluate(() => {
    const q = (crit, model) => Number(document.querySelector(`#criteria tr[data-crit="${crit}"] td[data-model="${model}"]`).dataset.value);
    return ['bacc', 'dtl', 'sws'].map((k) => [q(k, 'sur'), q(k, 'hifi'), q(k, 'lofi')]);
  });
  for (const [s, h, l] of cells) {
    assert.ok(Math.abs(s / h - 1) < 0.01, `surrogate ${s} vs HiFi ${h}`);
    assert.ok(Math.abs(s / h - 1) < Math.abs(l / h - 1) + 1e-12, `the surrogate is nearer the HiFi than the LoFi (${s}, ${l}, ${h})`);
  }
  // The front is found on the surrogate; its pick holds on the HiFi to 1 %.
  const fr = await page.evaluate(() => window.__ridelab.front);
  assert.equal(fr.study.evaluator, 'rba-mul-rbf-mq');
  for (const e of fr.recheck.error_percent) assert.ok(Math.abs(e) < 1, `pick error vs HiFi ${e} %`);
  await page.click('#tab-surrogate');
  await page.locator('#panel-surrogate').screenshot({ path: path.join(OUT, 'surrogate-panel.png') });
  assertClean(log);
  await context.close();
});

test('map model toggle: HiFi and error maps from the worker equal point evaluations', { timeout: TIMEOUT }, async (t) => {
  const { page, context, log } = await open();
  const lofiPixels = await page.evaluate(() => {
    const c = document.getElementById('map-bacc');
    return Array.from(c.getContext('2d').getImageData(0, 0, c.width, c.height).data.filter((_, k) => k % 997 === 0));
  });
  await page.selectOption('#map-model', 'hifi');
  await settle(page);
  assert.match(await page.locator('#maps-model').textContent(), /HiFi/);
  const check = await page.evaluate(() => {
    const a = window.__ridelab;
    const m = a.modelMaps.maps;
    const box = a.desc.designBox;
    const n = m.nx * m.ny;
    let worst = 0;
    for (const [i, j] of [[0, 0], [159, 0], [53, 77], [159, 119], [80, 60]]) {
      const ks = box.ks_min + ((i + 0.5) * (box.ks_max - box.ks_min)) / m.nx;
      const cs = box.cs_min + ((j + 0.5) * (box.cs_max - box.cs_min)) / m.ny;
      const c = a.session({ ...a.state, ks, cs }).criteria('hifi');
      const k = j * m.nx + i;
      for (const [p, v] of [[0, c.bacc], [1, c.dtl], [2, c.sws]]) worst = Math.max(worst, Math.abs(m.values[p * n + k] / v - 1));
    }
    return { worst, nx: m.nx, ny: m.ny, model: a.modelMaps.model };
  });
  assert.equal(check.model, 'hifi');
  assert.deepEqual([check.nx, check.ny], [160, 120]);
  assert.ok(check.worst < 1e-12, `HiFi map cells vs point evaluations: ${check.worst}`);
  const hifiPixels = await page.evaluate(() => {
    const c = document.getElementById('map-bacc');
    return Array.from(c.getContext('2d').getImageData(0, 0, c.width, c.height).data.filter((_, k) => k % 997 === 0));
  });
  const changed = lofiPixels.filter((v, k) => v !== hifiPixels[k]).length;
  assert.ok(changed > 50, `the HiFi map redrew the canvas (${changed} sampled bytes changed)`);
  await page.locator('.maps').screenshot({ path: path.join(OUT, 'maps-hifi.png') });

  // Error map: the planes are 100 (S/HiFi - 1) %, small, both signs, diverging colours.
  await page.selectOption('#map-model', 'error');
  await settle(page);
  const err = await page.evaluate(() => {
    const m = window.__ridelab.modelMaps.maps;
    const v = Array.from(m.values);
    return { min: Math.min(...v), max: Math.max(...v), model: window.__ridelab.modelMaps.model };
  });
  assert.equal(err.model, 'error');
  assert.ok(err.min < 0 && err.max > 0, `errors of both signs (${err.min}, ${err.max})`);
  assert.ok(Math.max(-err.min, err.max) < 2, `surrogate within 2 % of the HiFi everywhere (${err.min} .. ${err.max} %)`);
  const red = await countColour(page, 'map-dtl', [178, 24, 43], 120);
  const blue = await countColour(page, 'map-dtl', [33, 102, 172], 120);
  assert.ok(red > 100 && blue > 100, `diverging colours drawn (red ${red}, blue ${blue} px)`);
  await page.locator('.maps').screenshot({ path: path.join(OUT, 'maps-error.png') });

  assertClean(log);
  await context.close();
});

test('one scenario change, one surrogate fit in the page: the main thread fits, the worker adopts its fit', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  // [main thread, background worker, HiFi worker]: fits made so far.
  const fits = () => page.evaluate(() => {
    const r = window.__ridelab;
    return Promise.all([r.engine, r.heavyEngine, r.hifiEngine].map((e) => e.call('fitCount')));
  });
  // On load the main thread fits for the readout, the plane and the surrogate maps; the
  // background worker adopts that fit for its fit report, error map and NSGA-II front
  // (it fitted its own copy before; before that, two); the HiFi worker never fits.
  assert.deepEqual(await fits(), [1, 0, 0], 'fits after the first load');
  await page.click('#tab-surrogate');
  for (const [i, plan] of ['grid:4', 'ae:12'].entries()) {
    await page.selectOption('#sur-plan', plan);
    await settle(page);
    assert.equal((await page.evaluate(() => window.__ridelab.fit)).plan, plan, 'the fit report follows');
    assert.deepEqual(await fits(), [2 + i, 0, 0], `fits after change ${i + 1} (to ${plan})`);
  }
  // A design move refits nothing.
  await page.focus('#ks-range');
  await page.keyboard.press('ArrowRight');
  await settle(page);
  assert.deepEqual(await fits(), [3, 0, 0], 'a design move refits nothing');
  assertClean(log);
  await context.close();
});

test('sample plan: the HiFi samples are marked on the maps and follow the plan picker', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  const SAMPLE = [124, 45, 18];
  const on = await countColour(page, 'map-sws-overlay', SAMPLE, 60);
  assert.ok(on > 40, `sample crosses drawn (${on} px)`);
  await page.uncheck('#show-plan');
  const off = await countColour(page, 'map-sws-overlay', SAMPLE, 60);
  assert.equal(off, 0, 'no crosses with the plan hidden');
  await page.check('#show-plan');
  await page.click('#tab-surrogate');
  await page.selectOption('#sur-plan', 'grid:4');
  await settle(page);
  const fit = await page.evaluate(() => window.__ridelab.fit);
  assert.equal(fit.plan, 'grid:4');
  assert.equal(fit.samples.length, 16);
  // A 4 x 4 grid puts samples on the box corners.
  const box = await page.evaluate(() => window.__ridelab.desc.designBox);
  assert.ok(fit.samples.some((s) => s.ks === box.ks_min && s.cs === box.cs_min), 'a sample at the lowest corner');
  const more = await countColour(page, 'map-sws-overlay', SAMPLE, 60);
  assert.ok(more > on, `more crosses for 16 samples than for 10 (${more} vs ${on} px)`);
  // Another approach: the front follows it.
  await page.selectOption('#sur-approach', 'vba-qts');
  await settle(page);
  assert.equal(await page.evaluate(() => window.__ridelab.front.study.evaluator), 'vba-qts');
  assert.match(await page.locator('#sur-status').textContent(), /vba-qts on grid:4/);
  assert.match(page.url(), /sur=vba-qts/);
  assert.match(page.url(), /plan=grid%3A4/);
  assertClean(log);
  await context.close();
});

test('design box and objectives: edits apply, bad ones name the field and keep the last good state', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  await page.click('#tab-objectives');
  const set = async (id, v) => {
    await page.fill(`#${id}`, v);
    await page.dispatchEvent(`#${id}`, 'change');
    await settle(page);
  };
  await set('ks-min', '15');
  await set('ks-max', '30');
  let s = await page.evaluate(() => window.__ridelab.state);
  assert.equal(s.ksMin, 15000);
  assert.equal(s.ksMax, 30000);
  assert.equal(await page.getAttribute('#ks-range', 'min'), '15');
  assert.equal(await page.getAttribute('#ks-range', 'max'), '30');
  // The plan follows the box: every sample inside 15..30 kN/m.
  const ks = await page.evaluate(() => window.__ridelab.fit.samples.map((x) => x.ks));
  assert.ok(ks.every((k) => k >= 15000 && k <= 30000), `samples inside the box (${ks})`);
  // A reversed box is refused next to the box fields; the state keeps 15..30.
  await set('ks-min', '35');
  assert.match(await page.locator('#msg-box').textContent(), /Design box|ks/i);
  s = await page.evaluate(() => window.__ridelab.state);
  assert.equal(s.ksMin, 15000);
  await set('ks-min', '15');
  assert.equal(await page.locator('#msg-box').textContent(), '');

  // Bounce band 1.0 .. 1.2 Hz: part of the box breaks it; the status names it.
  await set('bb-lo', '1.0');
  assert.match(await page.locator('#msg-bounceBand').textContent(), /both ends/);
  await set('bb-hi', '1.2');
  s = await page.evaluate(() => window.__ridelab.state);
  assert.deepEqual(s.bounceBand, [1, 1.2]);
  assert.match(await page.locator('#map-status').textContent(), /break the body-bounce frequency band/);
  const bits = await page.evaluate(() => {
    const m = window.__ridelab.maps;
    let b = 0;
    for (const x of m.broken) if (x & 2) b++;
    return b / m.broken.length;
  });
  assert.ok(bits > 0.05 && bits < 0.95, `bounce band broken on part of the box (${bits})`);
  // A reversed band is refused and the last good band stays.
  await set('bb-lo', '1.5');
  assert.match(await page.locator('#msg-bounceBand').textContent(), /Bounce band/);
  s = await page.evaluate(() => window.__ridelab.state);
  assert.deepEqual(s.bounceBand, [1, 1.2]);
  await set('bb-lo', '1.0');
  // No worse than the datum in DTL.
  await page.check('#nw-dtl');
  await settle(page);
  s = await page.evaluate(() => window.__ridelab.state);
  assert.deepEqual(s.noWorse, [false, true, false]);
  assert.match(await page.locator('#map-status').textContent(), /DTL no worse than datum/);
  await page.locator('.maps').screenshot({ path: path.join(OUT, 'maps-objectives.png') });
  await page.locator('#panel-objectives').screenshot({ path: path.join(OUT, 'objectives-panel.png') });
  // The link carries all of it.
  const url = page.url();
  assert.match(url, /box=15000%2C30000%2C500%2C4000/);
  assert.match(url, /bb=1%2C1.2/);
  assert.match(url, /nw=0%2C1%2C0/);
  const again = await open(new URL(url).hash);
  const s2 = await again.page.evaluate(() => window.__ridelab.state);
  assert.deepEqual([s2.ksMin, s2.ksMax, s2.bounceBand, s2.noWorse], [15000, 30000, [1, 1.2], [false, true, false]]);
  assertClean(again.log);
  await again.context.close();
  assertClean(log);
  await context.close();
});

test('a link with a bad surrogate or plan falls back to the defaults with a message', { timeout: TIMEOUT }, async () => {
  for (const [hash, word] of [['#sur=kriging', /kriging/], ['#plan=ae%3A500', /at most 100/], ['#model=best', /model/]]) {
    const { page, context, log } = await open(hash);
    assert.match(await page.locator('#banner-text').textContent(), word);
    assert.equal(await page.evaluate(() => window.__ridelab.state.surrogate), 'rba-mul-rbf-mq');
    assertClean(log);
    await context.close();
  }
});

test('car editor: an edited car applies as a custom car, bad values name the field, JSON exports', { timeout: TIMEOUT }, async () => {
  const r = await openPage(suite.browser, suite.srv.url, { width: 1400, height: 1000, downloads: true });
  const { page, context, log } = r;
  await settle(page);
  await page.click('#tab-car');
  await page.click('#car-editor summary');
  assert.equal(await page.inputValue('#car-sprung_mass'), '1460');
  // A heavier body: the datum's LoFi BAcc falls (a heavier body shakes less on the same spring).
  const before = await page.evaluate(() => window.__ridelab.lofi.datum.bacc);
  await page.fill('#car-sprung_mass', '1700');
  await page.click('#car-apply');
  await settle(page);
  const s = await page.evaluate(() => ({ car: window.__ridelab.state.car, json: JSON.parse(window.__ridelab.state.carJson), bacc: window.__ridelab.lofi.datum.bacc, name: window.__ridelab.desc.car.name }));
  assert.equal(s.car, 'custom');
  assert.equal(s.json.sprung_mass, 1700);
  assert.match(s.name, /\(edited\)$/);
  assert.ok(s.bacc < before, `datum BAcc ${s.bacc} < ${before}`);
  // A negative tyre stiffness: the core's message names the field; the state keeps 1700 kg.
  await page.fill('#car-front-tire_stiffness', '-5');
  await page.click('#car-apply');
  await page.waitForFunction(() => document.getElementById('msg-car-front-tire_stiffness').textContent !== '');
  assert.match(await page.locator('#msg-car-front-tire_stiffness').textContent(), /tyre stiffness: must be > 0/);
  assert.equal(await page.getAttribute('#car-front-tire_stiffness', 'aria-invalid'), 'true');
  assert.equal(await page.evaluate(() => JSON.parse(window.__ridelab.state.carJson).sprung_mass), 1700);
  await page.fill('#car-front-tire_stiffness', 'abc');
  await page.click('#car-apply');
  assert.match(await page.locator('#msg-car-front-tire_stiffness').textContent(), /not a number/);
  // Export: the file parses back to the applied car.
  const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#car-export')]);
  const exported = JSON.parse(fs.readFileSync(await dl.path(), 'utf8'));
  assert.equal(exported.sprung_mass, 1700);
  assert.equal(exported.front.spring, 19960);
  assertClean(log);
  await context.close();
});
