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

/** Records every frame the objective plane draws: the adaptive pick's BAcc, DTL and the front's length. */
function recordPlane(page) {
  return page.evaluate(() => {
    const plane = window.__ridelab.objPlane;
    const draw = plane.draw;
    window.__planeFrames = [];
    plane.draw = function (data, frame) {
      const a = data.adaptive;
      if (frame && a) window.__planeFrames.push({ bacc: a.pick.criteria.bacc, dtl: a.pick.criteria.dtl, n: a.front.length, final: !this.animating });
      return draw.call(this, data, frame);
    };
  });
}

test('adaptive loop: 2 clicks and "Run 5 more" equal `ridelab surrogate --plan ae:5 --adaptive 7`', { timeout: TIMEOUT }, async (t) => {
  const { page, context, log } = await open('#plan=ae:5');
  assert.match(await page.textContent('#ad-status'), /No adaptive run yet/);
  await press(page, '#ad-next');
  let a = await page.evaluate(() => window.__ridelab.adaptive);
  assert.equal(a.report.added.length, 1, 'one click, one HiFi run');

  // The second run moves the loop's front and pick on the plane: frames between the old
  // and the new place (monotone, eased), then exactly the computed ones.
  await recordPlane(page);
  await press(page, '#ad-next');
  const moved = await page.evaluate(() => ({
    frames: window.__planeFrames,
    moved: window.__ridelab.objPlane.moved,
    drawn: window.__ridelab.objPlane.data.adaptive,
    a: window.__ridelab.adaptive,
  }));
  const [p0, p1] = [moved.a.was.pick.criteria, moved.a.report.history.at(-1).pick.criteria];
  const between = moved.frames.slice(0, -1);
  t.diagnostic(`move: ${moved.moved.frames} frames in ${moved.moved.ms.toFixed(0)} ms; pick BAcc ${p0.bacc} -> ${p1.bacc}, DTL ${p0.dtl} -> ${p1.dtl}`);
  assert.ok(moved.moved.frames >= 3, `the move is animated (${moved.moved.frames} frames)`);
  assert.ok(moved.moved.ms >= 400 && moved.moved.ms < 1300, `about 400 ms (${moved.moved.ms} ms)`);
  assert.equal(between.length, moved.moved.frames, 'every frame recorded');
  for (const key of ['bacc', 'dtl']) {
    const [lo, hi] = [Math.min(p0[key], p1[key]), Math.max(p0[key], p1[key])];
    const tol = 1e-12 * hi;
    const seq = between.map((f) => f[key]);
    assert.ok(seq.every((v) => v >= lo - tol && v <= hi + tol), `${key}: every frame between the old and the new pick`);
    const dir = Math.sign(p1[key] - p0[key]);
    assert.ok(seq.every((v, i) => i === 0 || dir * (v - seq[i - 1]) >= -tol), `${key}: the pick moves one way`);
  }
  assert.ok(between.every((f) => f.n === Math.max(moved.a.was.front.length, moved.a.front.length)), 'the fronts resampled to a common length');
  assert.deepEqual(moved.drawn.front, moved.a.front, 'after the move the plane draws the computed front, exactly');
  assert.deepEqual(moved.drawn.pick, moved.a.report.history.at(-1).pick, 'and the computed pick');
  assert.deepEqual(moved.drawn.was, moved.a.was);

  // With reduced motion the five runs jump: no frames in between.
  await page.emulateMedia({ reducedMotion: 'reduce' });
  await page.evaluate(() => (window.__planeFrames = []));
  await press(page, '#ad-more');
  const jumped = await page.evaluate(() => ({ moved: window.__ridelab.objPlane.moved, frames: window.__planeFrames.length }));
  assert.deepEqual(jumped, { moved: { frames: 0, ms: 0 }, frames: 0 }, 'reduced motion: no animation');
  await page.emulateMedia({ reducedMotion: 'no-preference' });

  a = await page.evaluate(() => window.__ridelab.adaptive);
  const state = await page.evaluate(() => window.__ridelab.state);
  assert.equal(state.plan, 'ae:5');
  const out = cli('surrogate', '--approach', state.surrogate, '--plan', 'ae:5', '--adaptive', '7', '--car', CAR(), '--class', 'B', '--speed', '20');
  const native = out.adaptive;

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

  // The uncertainty map: the loop's sigma, %, at the 80 x 60 cells; its check against the
  // HiFi is the CLI's estimate of the same kind for the same 12 samples (`uncertainty`).
  const u = a.uncertainty;
  const est = out.uncertainty.find((x) => x.method === r.uncertainty);
  assert.equal(est.status, 'estimated', JSON.stringify(est));
  assert.equal(u.levels, 20);
  assert.equal(u.check.method, r.uncertainty);
  // Correlations and means to 1e-9 relative; the estimate on the grid to 1e-9 of its
  // largest value (at a sample it is at its floor, ~1e-4 %, where wasm and native
  // arithmetic differ in the 7th digit).
  const wu = worstDiff(
    { pearson: u.check.pearson, spearman: u.check.spearman, e: u.check.estimated_mean_percent, t: u.check.true_mean_percent },
    { pearson: est.pearson, spearman: est.spearman, e: est.estimated_mean_percent, t: est.true_mean_percent },
    'uncertainty',
  );
  for (const key of ['bacc', 'dtl', 'sws']) {
    const [x, y] = [u.check.map_percent[key], est.map_percent[key]];
    assert.equal(x.length, 400);
    const top = Math.max(...y);
    const d = Math.max(...x.map((v, i) => Math.abs(v - y[i]))) / top;
    assert.ok(d < 1e-9, `${key}: the estimate on the grid, page vs CLI, ${d} of its largest`);
  }
  t.diagnostic(`uncertainty (${r.uncertainty}): page vs CLI largest relative difference ${wu.toExponential(2)}; Pearson ${JSON.stringify(u.check.pearson)}, Spearman ${JSON.stringify(u.check.spearman)}; at the samples ${JSON.stringify(u.atSamples)} %; ${u.ms.toFixed(0)} ms in the worker`);
  assert.ok(wu < 1e-9, `uncertainty page vs CLI: ${wu}`);
  await page.locator('#ad-unc-box').scrollIntoViewIfNeeded();
  assert.equal(await page.locator('#ad-unc-box').isVisible(), true);
  const box = await page.evaluate(() => window.__ridelab.desc.designBox);
  const samples = [...r.initial, ...r.added.map((x) => x.sample)];
  for (const [k, key] of ['bacc', 'dtl', 'sws'].entries()) {
    await page.selectOption('#ad-unc-crit', key);
    const shown = await page.evaluate(() => {
      const v = window.__ridelab.uncertaintyPanel.view;
      const stat = (name) => document.querySelector(`#ad-unc-caption [data-stat="${name}"]`);
      return {
        id: v.base.id, nx: v.data.nx, ny: v.data.ny, shown: [...v.data.shown], unit: v.data.unit, lo: v.data.lo, visible: !v.fig.hidden,
        markers: v.markers.samples.length + v.markers.adaptive.added.length,
        caption: document.getElementById('ad-unc-caption').textContent,
        pearson: { value: stat('pearson').dataset.value, text: stat('pearson').textContent },
        spearman: { value: stat('spearman').dataset.value, text: stat('spearman').textContent },
      };
    });
    assert.equal(shown.id, `map-sigma-${key}`);
    assert.ok(shown.visible);
    assert.equal(shown.unit, '% estimated 1σ');
    assert.equal(shown.lo, 0, 'the colour scale starts at 0 %');
    assert.equal(shown.markers, 12, 'the 12 HiFi samples marked');
    const n = u.nx * u.ny;
    assert.deepEqual(shown.shown, [...u.map.slice(k * n, (k + 1) * n)], `${key}: the map is the core's`);
    // The caption: the kind in words, the core's correlations (exact in data-value, to 3 digits in the text).
    assert.match(shown.caption, r.uncertainty === 'loo' ? /leave-one-out cross-validation/ : /predictive standard deviation/);
    assert.match(shown.caption, /20 × 20 HiFi grid/);
    for (const stat of ['pearson', 'spearman']) {
      const want = u.check[stat][key];
      assert.equal(Number(shown[stat].value), want, `${key} ${stat}: the caption's is the core's`);
      assert.ok(Math.abs(Number(shown[stat].text.replace('−', '-')) - want) <= 5e-4 + 1e-12, `${key} ${stat}: ${shown[stat].text} vs ${want}`);
    }
    // At the samples sigma is at its floor (the core's value at the samples is below 1e-4
    // of the map's largest for an interpolating surrogate); the cells holding a sample lie
    // below the map's median, and the tenth of the cells farthest from every sample
    // average more than those cells.
    const peak = Math.max(...shown.shown);
    assert.ok(u.atSamples[key] <= 1e-4 * peak, `${key}: ${u.atSamples[key]} % at the samples vs ${peak} % peak`);
    const cell = (ks, cs) => {
      const i = Math.min(u.nx - 1, Math.floor(((ks - box.ks_min) / (box.ks_max - box.ks_min)) * u.nx));
      const j = Math.min(u.ny - 1, Math.floor(((cs - box.cs_min) / (box.cs_max - box.cs_min)) * u.ny));
      return j * u.nx + i;
    };
    const sorted = [...shown.shown].sort((x, y) => x - y);
    const med = sorted[Math.floor(n / 2)];
    const atCells = samples.map((p) => shown.shown[cell(p.ks, p.cs)]);
    assert.ok(atCells.every((v) => v < med), `${key}: sample cells ${atCells.map((v) => v.toPrecision(2))} below the median ${med}`);
    const dist = [];
    for (let j = 0; j < u.ny; j++) {
      for (let i = 0; i < u.nx; i++) {
        const [x, y] = [(i + 0.5) / u.nx, (j + 0.5) / u.ny];
        const d = Math.min(...samples.map((p) => Math.hypot(x - (p.ks - box.ks_min) / (box.ks_max - box.ks_min), y - (p.cs - box.cs_min) / (box.cs_max - box.cs_min))));
        dist.push([d, shown.shown[j * u.nx + i]]);
      }
    }
    dist.sort((x, y) => y[0] - x[0]);
    const far = dist.slice(0, n / 10).reduce((acc, x) => acc + x[1], 0) / (n / 10);
    const near = atCells.reduce((acc, v) => acc + v, 0) / atCells.length;
    t.diagnostic(`${key}: sigma at the sample cells ${near.toPrecision(3)} %, median ${med.toPrecision(3)} %, farthest tenth ${far.toPrecision(3)} %, peak ${peak.toPrecision(3)} %`);
    assert.ok(far > near, `${key}: far ${far} vs near ${near}`);
  }
  assert.ok(await countColour(page, 'map-sigma-sws', [68, 1, 84], 50) > 20, 'the map is painted (viridis from 0)');
  await page.locator('#ad-unc-box').screenshot({ path: path.join(OUT, 'adaptive-uncertainty.png') });

  // The plane's exports carry the loop's front and pick with their legend entries.
  const ex = await page.evaluate(async () => {
    const { objectiveChart } = await import('./js/svgexport.js');
    const { frontCsv } = await import('./js/exports.js');
    const app = window.__ridelab;
    const data = app.exportData();
    const spec = objectiveChart(data);
    const svg = await app.svg('line', spec);
    const doc = new DOMParser().parseFromString(svg, 'image/svg+xml');
    return {
      series: spec.series.map((x) => ({ name: x.name, points: x.points })),
      texts: [...doc.querySelectorAll('text')].map((e) => e.textContent.trim()),
      purple: [...doc.querySelectorAll('polyline')].filter((e) => e.getAttribute('stroke') === '#7C3AED').map((e) => e.getAttribute('points').trim().split(/\s+/).length),
      csv: frontCsv(app.front, app.nsga, data.adaptive).trim().split('\n').filter((l) => l.startsWith('adaptive,')),
    };
  });
  const name = `adaptive loop's front (${a.front.length} pts)`;
  const series = ex.series.find((x) => x.name === name);
  assert.ok(series, `the export has the loop's front: ${ex.series.map((x) => x.name).join('; ')}`);
  assert.deepEqual(series.points, a.front.map((p) => [p.bacc, p.dtl]), 'every point of the loop\'s front');
  const pickSeries = ex.series.find((x) => x.name === 'adaptive loop\'s pick');
  assert.deepEqual(pickSeries.points, [[last.criteria.bacc, last.criteria.dtl]]);
  assert.ok(ex.texts.includes(name), 'the legend names the loop\'s front');
  assert.ok(ex.texts.includes('adaptive loop\'s pick'), 'and its pick');
  assert.ok(ex.purple.length >= 1 && ex.purple.every((m) => m >= 2 && m <= a.front.length), `the front's polyline in the SVG (${ex.purple})`);
  assert.equal(ex.csv.length, a.front.length, 'the CSV lists the loop\'s front');
  assert.deepEqual(ex.csv.map((l) => l.split(',').slice(1, 3).map(Number)), a.front.map((p) => [p.ks, p.cs]));
  assert.equal(ex.csv.filter((l) => l.endsWith(',1')).length, 1, 'its pick marked once');

  // Convergence (#30): "Run 5 more" stops at the first proposal below the core's stop
  // threshold, as `ridelab surrogate --adaptive 12` does, and says so; "Run anyway" adds
  // that run, as the CLI with `--stop-below 0` does.
  const args = ['surrogate', '--approach', state.surrogate, '--plan', 'ae:5', '--car', CAR(), '--class', 'B', '--speed', '20'];
  const stops = cli(...args, '--adaptive', '12').adaptive;
  assert.ok(stops.stopped && stops.added.length < 12, `the CLI's loop converges within 12 runs (${stops.added.length}, ${stops.stopped})`);
  const more = Math.ceil((stops.added.length - 7) / 5);
  for (let k = 0; k < more; k++) await press(page, '#ad-more');
  const conv = await page.evaluate(() => ({
    a: window.__ridelab.adaptive,
    status: document.getElementById('ad-status').textContent,
    next: document.getElementById('ad-next').textContent,
    more: document.getElementById('ad-more').disabled,
  }));
  assert.deepEqual(conv.a.report.added.map((x) => [x.sample.ks, x.sample.cs]), stops.added.map((x) => [x.sample.ks, x.sample.cs]), 'the page stops where the CLI stops');
  assert.equal(conv.a.proposal.converged, true);
  assert.ok(stops.stopped.endsWith(conv.a.proposal.reason), 'the same reason as the CLI\'s');
  assert.match(conv.status, /^Converged: .* below the stop threshold, so the loop stops here; "Run anyway" adds it/);
  assert.equal(conv.next, 'Run anyway');
  assert.equal(conv.more, true, '"Run 5 more" is off once converged');
  t.diagnostic(`converged after ${stops.added.length} adaptive runs: ${stops.stopped}`);
  await press(page, '#ad-next');
  const anyway = await page.evaluate(() => window.__ridelab.adaptive.report.added.map((x) => [x.sample.ks, x.sample.cs]));
  const all = cli(...args, '--adaptive', String(stops.added.length + 1), '--stop-below', '0').adaptive;
  assert.deepEqual(anyway, all.added.map((x) => [x.sample.ks, x.sample.cs]), '"Run anyway" adds the converged proposal');
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
