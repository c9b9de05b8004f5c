// End-to-end tests of the HiFi front on the objective plane (issue #13): the heavy worker
// runs STM on the full car with the plane's settings, and the page shows that front and its
// pick beside the surrogate's, with both hypervolumes and the HiFi runs each took. The
// front is `ridelab optimize --evaluator full --method stm --grid 61 --levels 2`'s; the
// Pick tab's table shows the core's numbers; a scenario change brings the new scenario's.
//
//   trunk build --release --offline && RIDELAB_CLI=target/debug/ridelab node --test tests/e2e/hififront.test.mjs

import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { openPage, settled } from './browser.mjs';
import { useSuite, assertClean, ROOT, OUT } from './harness.mjs';

const TIMEOUT = 120_000;
const suite = useSuite();
const CAR = path.join(ROOT, 'assets/cars/sedan.json');
const rel = (a, b) => Math.abs(a / b - 1);

/** `ridelab optimize --evaluator full` with the plane's STM (61 x 61, 2 levels) on class `cls` at `speed` m/s. */
function hifiOptimize(cls, speed) {
  const candidates = [process.env.RIDELAB_CLI, path.join(ROOT, 'target/debug/ridelab'), path.join(ROOT, 'target/release/ridelab')];
  const c = candidates.filter(Boolean).find((x) => fs.existsSync(x));
  assert.ok(c, 'the native CLI is built (cargo build -p ridelab)');
  return JSON.parse(execFileSync(c, ['optimize', '--evaluator', 'full', '--method', 'stm', '--grid', '61', '--levels', '2',
    '--car', CAR, '--class', cls, '--speed', String(speed), '--json'], { encoding: 'utf8' }));
}

/** The page's HiFi front against the CLI's: every point to 1e-9, hypervolume, reference point and pick. */
function assertSameFront(h, native, what) {
  const f = h.front.study;
  assert.equal(f.front.length, native.front.length, `${what}: points`);
  f.front.forEach((p, i) => {
    const q = native.front[i];
    for (const k of ['ks', 'cs', 'bacc', 'dtl', 'sws']) assert.ok(rel(p[k], q[k]) <= 1e-9, `${what}: point ${i} ${k} ${p[k]} vs ${q[k]}`);
  });
  assert.ok(rel(f.hypervolume, native.hypervolume) <= 1e-9, `${what}: hypervolume ${f.hypervolume} vs ${native.hypervolume}`);
  for (let k = 0; k < 2; k++) assert.ok(rel(f.reference_point[k], native.reference_point[k]) <= 1e-9, `${what}: reference point`);
  assert.ok(rel(f.pick.ks, native.pick.ks) <= 1e-9 && rel(f.pick.cs, native.pick.cs) <= 1e-9, `${what}: pick`);
  // The HiFi runs: STM's evaluations and the datum's.
  assert.equal(h.hifiRuns, native.evaluations + 1, `${what}: HiFi runs`);
}

test('the plane shows the HiFi front of `ridelab optimize --evaluator full`, its pick, both hypervolumes and the runs each took', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await openPage(suite.browser, suite.srv.url, { width: 1280, height: 720 });
  await settled(page, 200);
  const h = await page.evaluate(() => window.__ridelab.hifiFront);
  assert.ok(h && !h.error, `a HiFi front (${h && h.error})`);
  assert.equal(h.compute, 'cpu', 'no WebGPU in this browser: STM on the CPU HiFi');
  assertSameFront(h, hifiOptimize('B', 20), 'class B at 20 m/s');
  // The plane's front judged on it: the surrogate's, its runs its samples and one re-check.
  const fit = await page.evaluate(() => window.__ridelab.fit);
  assert.equal(h.plane.model, 'surrogate');
  assert.equal(h.plane.hifiRuns, fit.samples.length + 1);
  assert.ok(h.plane.hypervolumeRatio > 0.95 && h.plane.hypervolumeRatio < 1.0001, `hypervolume ratio ${h.plane.hypervolumeRatio}`);
  assert.ok(Math.abs(h.plane.hypervolumeOnHifi / h.front.study.hypervolume - h.plane.hypervolumeRatio) <= 1e-12);
  // The pick gap is the surrogate pick's HiFi re-check against the HiFi pick.
  const fr = await page.evaluate(() => window.__ridelab.front);
  ['bacc', 'dtl', 'sws'].forEach((k, i) => {
    const want = 100 * (fr.recheck.rechecked[k] / h.front.study.pick.criteria[k] - 1);
    assert.ok(Math.abs(h.plane.pickGapPercent[i] - want) <= 1e-9, `pick gap ${k}`);
  });
  // What the user sees: the key, the line under the plane, the Pick tab's table.
  assert.equal(await page.isVisible('#op-key-hifi'), true, 'the plane\'s key names the HiFi front');
  const line = await page.locator('#op-hifi-status').textContent();
  const runs = String(h.hifiRuns).replace(/\B(?=(\d{3})+(?!\d))/g, '\u2009');
  assert.match(line, new RegExp(`^${runs} HiFi runs\\. Surrogate's front \\(${h.plane.hifiRuns} runs\\): `));
  assert.match(await page.getAttribute('#op-hifi-status', 'title'), /STM on the full car, 61 × 61 grid refined twice \(CPU/);
  await page.click('#tab-pick');
  const cells = await page.evaluate(() => [...document.querySelectorAll('#op-hifi td[data-value]')].map((td) => Number(td.dataset.value)));
  for (const v of [h.plane.hifiRuns, h.hifiRuns, h.plane.hypervolume, h.plane.hypervolumeOnHifi, h.front.study.hypervolume, h.plane.hypervolumeRatio, h.front.study.pick.ks, h.front.study.pick.cs]) {
    assert.ok(cells.some((c) => c === v), `the table shows ${v}`);
  }
  await page.screenshot({ path: path.join(OUT, 'hifi-front-1280.png') });
  assertClean(log);
  await context.close();
});

test('a road change brings that road\'s HiFi front; the ratio axes put it against the HiFi datum', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await openPage(suite.browser, suite.srv.url, { width: 1400, height: 1000 });
  await settled(page, 200);
  const before = await page.evaluate(() => window.__ridelab.hifiFront);
  await page.fill('#speed', '30');
  await page.press('#speed', 'Enter');
  await settled(page, 200);
  const h = await page.evaluate(() => window.__ridelab.hifiFront);
  assert.notEqual(h.front.study.hypervolume, before.front.study.hypervolume);
  assertSameFront(h, hifiOptimize('B', 30), 'class B at 30 m/s');
  // Ratio axes: the HiFi front's points over the HiFi datum, the pick's re-check too.
  await page.selectOption('#op-scale', 'ratio');
  await settled(page, 100);
  const spec = await page.evaluate(async () => {
    const { objectiveSpec } = await import('./js/chartspecs.js');
    const a = window.__ridelab;
    return objectiveSpec({ front: a.front, cloud: a.cloud, hifi: a.hifiFront }, { ratio: true });
  });
  const s = spec.series.find((x) => x.name.startsWith('HiFi front'));
  const d = h.front.datum;
  assert.ok(Math.abs(s.points[0][0] - h.front.study.front[0].bacc / d.bacc) <= 1e-12);
  assert.ok(spec.series.some((x) => x.name.startsWith('HiFi min-max pick')));
  assertClean(log);
  await context.close();
});
