// End-to-end tests of the adaptive HiFi loop in the Surrogate tab (issue #15): after N
// clicks the samples added (in order, with their reasons), the front's hypervolume and
// the pick equal `ridelab surrogate --plan P --adaptive N --json`; the history chart, the
// map markers and the plane's adaptive front are drawn; a scenario change discards the
// run (an answer in flight too); a bad state names the field. Screenshots in
// tests/e2e/out/.
//
//   trunk build --release --offline && RIDELAB_CLI=target/debug/ridelab node --test tests/e2e/adaptive.test.mjs

import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { openPage, settled } from './browser.mjs';
import { useSuite, assertClean, countColour, median, ROOT, OUT } from './harness.mjs';

const TIMEOUT = 240_000;
const suite = useSuite();

/** The page with `hash`, settled, the Surrogate tab open. */
async function open(hash = '', { width = 1280, height = 720 } = {}) {
  const r = await openPage(suite.browser, suite.srv.url + hash, { width, height });
  await settled(r.page, 150);
  await r.page.click('#tab-surrogate');
  return r;
}

/** Clicks `sel` and waits until the loop is idle and every view current. */
async function press(page, sel) {
  await page.click(sel);
  await page.waitForFunction(() => !document.getElementById('ad-next').disabled && window.__ridelab.isSettled(), null, { timeout: 180_000 });
}

/** `ridelab ...args --json` (RIDELAB_CLI, else target/debug or target/release). */
function cli(...args) {
  const candidates = [process.env.RIDELAB_CLI, path.join(ROOT, 'target/debug/ridelab'), path.join(ROOT, 'target/release/ridelab')];
  const c = candidates.filter(Boolean).find((x) => fs.existsSync(x));
  assert.ok(c, 'the native CLI is built (cargo build -p ridelab)');
  return JSON.parse(execFileSync(c, [...args, '--json'], { encoding: 'utf8', maxBuffer: 64 << 20 }));
}

/** Largest relative difference between the numbers of `a` and `b` (same shape; other leaves equal). */
function worstDiff(a, b, at = '') {
  if (typeof a === 'number') {
    assert.equal(typeof b, 'number', `${at}: a number on both sides`);
    return Math.abs(a - b) / Math.max(Math.abs(b), 1e-300);
  }
  if (a === null || typeof a !== 'object') {
    assert.deepEqual(a, b, at);
    return 0;
  }
  assert.deepEqual(Object.keys(a).sort(), Object.keys(b).sort(), `${at}: keys`);
  return Math.max(0, ...Object.keys(a).map((k) => worstDiff(a[k], b[k], `${at}.${k}`)));
}

const CAR = () => path.join(ROOT, 'assets/cars/sedan.json');

test('adaptive loop: 2 clicks and "Run 5 more" equal `ridelab surrogate --plan ae:5 --adaptive 7`', { timeout: TIMEOUT }, async (t) => {
  const { page, context, log } = await open('#plan=ae:5');
  assert.match(await page.textContent('#ad-status'), /No adaptive run yet/);
  await press(page, '#ad-next');
  let a = await page.evaluate(() => window.__ridelab.adaptive);
  assert.equal(a.report.added.length, 1, 'one click, one HiFi run');
  await press(page, '#ad-next');
  await press(page, '#ad-more');
  a = await page.evaluate(() => window.__ridelab.adaptive);
  const state = await page.evaluate(() => window.__ridelab.state);
  assert.equal(state.plan, 'ae:5');
  const native = cli('surrogate', '--approach', state.surrogate, '--plan', 'ae:5', '--adaptive', '7', '--car', CAR(), '--class', 'B', '--speed', '20').adaptive;

  // The samples, in order, with their reasons: the same designs and words.
  const r = a.report;
  assert.equal(r.added.length, 7);
  assert.deepEqual(r.added.map((x) => x.run), native.added.map((x) => x.run));
  assert.deepEqual(r.added.map((x) => [x.sample.ks, x.sample.cs]), native.added.map((x) => [x.sample.ks, x.sample.cs]), 'the same designs, exactly');
  assert.deepEqual(r.added.map((x) => x.reason), native.added.map((x) => x.reason), 'the same reasons');
  assert.deepEqual(r.options, { ...native.options, runs: 0 }, 'the CLI\'s options (the page steps instead of `runs`)');
  assert.equal(r.uncertainty, native.uncertainty);
  // Every number (HiFi criteria, scores, hypervolumes, picks) to 1e-9 relative.
  const worst = worstDiff({ ...r, options: null }, { ...native, options: null }, 'adaptive');
  t.diagnostic(`page (wasm) vs native CLI: largest relative difference ${worst.toExponential(2)}`);
  assert.ok(worst < 1e-9, `page vs CLI: ${worst}`);
  assert.deepEqual(r.history.map((h) => h.hifi_runs), [5, 6, 7, 8, 9, 10, 11, 12]);
  assert.deepEqual(r.history.map((h) => [h.pick.ks, h.pick.cs]), native.history.map((h) => [h.pick.ks, h.pick.cs]), 'the same picks');

  // The pick's re-check error: the latest pick on the HiFi (`ridelab eval --model full`).
  const last = r.history[r.history.length - 1].pick;
  const hifi = cli('eval', '--model', 'full', '--car', CAR(), '--class', 'B', '--speed', '20', '--ks', String(last.ks), '--cs', String(last.cs));
  const err = Math.max(...['bacc', 'dtl', 'sws'].map((k) => Math.abs(100 * (last.criteria[k] / hifi[k] - 1))));
  assert.equal(a.errors.length, r.history.length, 'an error for the plan and for each run');
  assert.ok(Math.abs(a.errors[a.errors.length - 1] - err) <= 1e-6 * Math.max(err, 1e-3), `re-check error ${a.errors.at(-1)} % vs ${err} %`);
  t.diagnostic(`pick re-check error, %: ${a.errors.map((e) => e.toPrecision(3)).join(', ')}`);
  t.diagnostic(`hypervolume: ${r.history.map((h) => h.hypervolume.toPrecision(6)).join(', ')}`);
  t.diagnostic(`HiFi step in the worker (run, refit, front, re-check, next proposal): median ${median(a.ms).toFixed(0)} ms over ${a.ms.length} (${a.ms.map((x) => x.toFixed(0)).join(', ')})`);

  // The table: the plan's row, then one per run with its reason and numbers.
  const rows = await page.$$eval('#ad-samples tbody tr[data-kind]', (trs) => trs.map((tr) => ({
    kind: tr.dataset.kind,
    cells: [...tr.cells].map((c) => ({ text: c.textContent, value: c.dataset.value })),
    why: tr.nextElementSibling.textContent,
  })));
  assert.equal(rows.length, 8);
  assert.equal(rows[0].kind, 'plan');
  rows.slice(1).forEach((row, i) => {
    assert.equal(row.kind, 'added');
    assert.equal(Number(row.cells[0].value), r.added[i].run);
    assert.equal(Number(row.cells[1].value), r.added[i].sample.ks);
    assert.equal(Number(row.cells[2].value), r.added[i].sample.cs);
    assert.equal(row.why, r.added[i].reason);
    assert.equal(Number(row.cells[3].value), r.history[i + 1].hypervolume);
    assert.equal(Number(row.cells[4].value), a.errors[i + 1]);
  });
  // The status line: where the next run goes and why.
  const status = await page.textContent('#ad-status');
  const c = a.proposal.candidate;
  assert.ok(status.includes(`Ks ${(c.ks / 1000).toFixed(2)}`), status);
  assert.ok(status.includes(a.proposal.reason), status);
  assert.match(status, /EHVI .* \(m\/s²\)·N, probability feasible .* %/);

  // The history chart: drawn, with both lines.
  assert.equal(await page.locator('#ad-chart-box').isVisible(), true);
  assert.ok(await countColour(page, 'ad-chart', [194, 65, 12]) > 30, 'the hypervolume line is drawn');
  assert.ok(await countColour(page, 'ad-chart', [185, 28, 28]) > 30, 'the re-check error line is drawn');
  // The maps mark the runs added and the next one; the plane draws the loop's front and pick.
  const marks = await page.evaluate(() => window.__ridelab.views.map((v) => v.markers.adaptive));
  for (const m of marks) {
    assert.deepEqual(m.added.map((x) => [x.ks, x.cs]), r.added.map((x) => [x.sample.ks, x.sample.cs]));
    assert.deepEqual([m.next.ks, m.next.cs], [c.ks, c.cs]);
  }
  const plane = await page.evaluate(() => window.__ridelab.objPlane.data.adaptive);
  assert.deepEqual(plane.pick, last);
  assert.deepEqual(plane.was.pick, r.history.at(-2).pick, 'the pick before the latest run, drawn light');
  assert.equal(plane.front.length, r.history.at(-1).front_points);
  assert.ok(await countColour(page, 'op-base', [124, 58, 237], 60) > 20, 'the adaptive front is drawn on the plane');
  assert.equal(await page.locator('#op-key-adaptive').isVisible(), true);
  await page.screenshot({ path: path.join(OUT, 'adaptive-1280.png') });
  assertClean(log);
  await context.close();
});

test('adaptive loop: a scenario change discards the run, an answer in flight too', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open('#plan=ae:4');
  await press(page, '#ad-next');
  const key = await page.evaluate(() => window.__ridelab.adaptive.key);
  // A design change keeps it.
  await page.fill('#ks-num', '25');
  await page.press('#ks-num', 'Enter');
  await settled(page, 100);
  assert.equal(await page.evaluate(() => window.__ridelab.adaptive?.key), key, 'a new design keeps the run');
  // A new speed drops it: the panel, the markers and the plane forget it.
  await page.fill('#speed', '25');
  await page.press('#speed', 'Enter');
  await settled(page, 100);
  const after = await page.evaluate(() => ({
    a: window.__ridelab.adaptive,
    marks: window.__ridelab.views.map((v) => v.markers.adaptive),
    plane: window.__ridelab.objPlane.data.adaptive,
    dropped: window.__ridelab.counters.adaptiveDropped,
  }));
  assert.equal(after.a, null);
  assert.deepEqual(after.marks, [null, null, null]);
  assert.equal(after.plane, null);
  assert.equal(after.dropped, 1);
  assert.equal(await page.locator('#ad-samples').isVisible(), false);
  assert.equal(await page.locator('#ad-chart-box').isVisible(), false);
  assert.match(await page.textContent('#ad-status'), /No adaptive run yet/);
  // A step in flight when the scenario changes is dropped: nothing of it is shown.
  await press(page, '#ad-next');
  assert.equal(await page.evaluate(() => window.__ridelab.adaptive.report.added.length), 1);
  await page.click('#ad-more');
  await page.selectOption('#sur-plan', 'ae:6');
  await page.waitForFunction(() => !document.getElementById('ad-next').disabled && window.__ridelab.isSettled(), null, { timeout: 180_000 });
  assert.equal(await page.evaluate(() => window.__ridelab.adaptive), null, 'the run for ae:4 is gone');
  // The next click starts a run on the new scenario.
  await press(page, '#ad-next');
  const fresh = await page.evaluate(() => window.__ridelab.adaptive);
  assert.equal(fresh.report.plan, 'ae:6');
  assert.equal(fresh.report.added.length, 1);
  assert.equal(fresh.state.speed, 25);
  assertClean(log);
  await context.close();
});

test('adaptive loop: a bad state or option names the field; a step for another scenario is refused', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  const fails = await page.evaluate(async () => {
    const h = window.__ridelab.heavyEngine;
    const s = window.__ridelab.state;
    const fail = (p) => p.then(() => null, (e) => e);
    return {
      speed: await fail(h.call('adaptiveStart', { ...s, speed: -5 }, null)),
      plan: await fail(h.call('adaptiveStart', { ...s, plan: 'ae:1' }, null)),
      unknown: await fail(h.call('adaptiveStart', { ...s, sped: 20 }, null)),
      option: await fail(h.call('adaptiveStart', s, { candidates: 1 })),
      noRun: await fail(h.call('adaptiveStep', { ...s, speed: 21 })),
    };
  });
  assert.equal(fails.speed.field, 'speed', JSON.stringify(fails.speed));
  assert.match(fails.speed.message, /speed/);
  assert.equal(fails.plan.field, 'plan', JSON.stringify(fails.plan));
  assert.equal(fails.unknown.field, 'state', JSON.stringify(fails.unknown));
  assert.ok(fails.option.field, `a bad option names a field: ${JSON.stringify(fails.option)}`);
  assert.match(fails.option.message, /candidates/);
  assert.equal(fails.noRun.field, 'adaptive');
  assertClean(log);
  await context.close();
});

test('adaptive loop at 390 x 844: the panel fits the phone, buttons and chart usable', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open('#plan=ae:5', { width: 390, height: 844 });
  await page.locator('#ad-next').scrollIntoViewIfNeeded();
  await press(page, '#ad-next');
  await press(page, '#ad-next');
  const fit = await page.evaluate(() => {
    const r = (id) => document.getElementById(id).getBoundingClientRect();
    return {
      overflow: document.documentElement.scrollWidth - window.innerWidth,
      next: r('ad-next'),
      more: r('ad-more'),
      chart: r('ad-chart'),
      vw: window.innerWidth,
    };
  });
  assert.ok(fit.overflow <= 0, `no horizontal overflow (${fit.overflow} px)`);
  for (const k of ['next', 'more', 'chart']) {
    assert.ok(fit[k].x >= 0 && fit[k].x + fit[k].width <= fit.vw + 0.5, `${k} inside the width (${JSON.stringify(fit[k])})`);
  }
  assert.ok(fit.next.height >= 24, 'a button to tap');
  await page.locator('#ad-chart').scrollIntoViewIfNeeded();
  await page.screenshot({ path: path.join(OUT, 'adaptive-390.png') });
  assertClean(log);
  await context.close();
});
