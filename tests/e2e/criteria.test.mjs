// End-to-end tests of the comfort measure and the pick rule (issue #16): ISO 2631-1 Wk
// comfort in the readout (with the standard's Annex C label), the maps and the objective
// plane, the knee and weighted picks with their pseudo-weights, against the native CLI
// (`ridelab eval --json`, `ridelab optimize --pick ... --json`); both fields in the URL.
//
//   trunk build --release --offline && RIDELAB_CLI=target/debug/ridelab node --test tests/e2e/criteria.test.mjs

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

function open(hash = '') {
  return openPage(suite.browser, suite.srv.url + hash, { width: 1400, height: 1000 }).then(async (r) => {
    await settle(r.page);
    return r;
  });
}

function settle(page) {
  return settled(page, 200); // the URL is written 120 ms after the last change
}

/** `ridelab ...args` as JSON (RIDELAB_CLI, else target/debug or target/release). */
function cli(args) {
  const candidates = [process.env.RIDELAB_CLI, path.join(ROOT, 'target/debug/ridelab'), path.join(ROOT, 'target/release/ridelab')];
  const c = candidates.filter(Boolean).find((x) => fs.existsSync(x));
  assert.ok(c, 'the native CLI is built (cargo build -p ridelab)');
  return JSON.parse(execFileSync(c, [...args, '--car', CAR, '--class', 'B', '--speed', '20', '--json'], { encoding: 'utf8' }));
}

/** `ridelab optimize` with the page's objective plane's method: STM on a 61 x 61 grid refined twice. */
function optimize(evaluator, extra) {
  return cli(['optimize', '--evaluator', evaluator, '--plan', 'ae:10', '--method', 'stm', '--grid', '61', '--levels', '2', ...extra]);
}

const rel = (a, b) => Math.abs(a / b - 1);

/** The criteria table's full-precision values, `{"wk.hifi": v, ...}` (null where a cell has none). */
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

/** The page's pick against the CLI's: the same front point, its design and pseudo-weights to 1e-9, and the HiFi re-check. */
function assertSamePick(page, native, what) {
  const p = page.study.pick;
  const q = native.pick;
  assert.equal(p.rule, q.rule, `${what}: rule`);
  assert.equal(p.index, q.index, `${what}: front index`);
  assert.ok(rel(p.ks, q.ks) <= 1e-9 && rel(p.cs, q.cs) <= 1e-9, `${what}: page (${p.ks}, ${p.cs}) vs CLI (${q.ks}, ${q.cs})`);
  for (let i = 0; i < 2; i++) {
    assert.ok(Math.abs(p.pseudo_weights[i] - q.pseudo_weights[i]) <= 1e-9, `${what}: pseudo-weights ${p.pseudo_weights} vs ${q.pseudo_weights}`);
    assert.ok(Math.abs(p.distance[i] - q.distance[i]) <= 1e-9, `${what}: distances ${p.distance} vs ${q.distance}`);
  }
  for (const k of ['bacc', 'dtl', 'sws']) {
    assert.ok(rel(page.recheck.rechecked[k], native.hifi_recheck.rechecked[k]) <= 1e-9, `${what}: HiFi re-check ${k}`);
  }
}

test('choosing Wk: the readout gives `ridelab eval` bacc_wk and its Annex C label; maps, plane and front follow', { timeout: TIMEOUT }, async (t) => {
  const { page, context, log } = await open();
  assert.equal(await page.isHidden('tr[data-crit="wk"]'), true, 'no Wk row with the unweighted BAcc');
  await page.click('#tab-objectives');
  await page.selectOption('#comfort', 'wk');
  await settle(page);
  assert.equal(await page.evaluate(() => window.__ridelab.state.comfort), 'wk');
  assert.match(await page.evaluate(() => location.hash), /comfort=wk/);
  // Readout: the LoFi's and HiFi's Wk at the datum design equal the CLI's to 1e-9.
  const r = await readout(page);
  const quarter = cli(['eval', '--model', 'quarter']);
  const full = cli(['eval', '--model', 'full']);
  for (const [col, ref] of [['lofi', quarter], ['hifi', full]]) {
    const e = rel(r[`wk.${col}`], ref.bacc_wk);
    assert.ok(e <= 1e-9, `${col}: page ${r[`wk.${col}`]} vs CLI ${ref.bacc_wk} (rel ${e})`);
    assert.ok(rel(r[`bacc.${col}`], ref.bacc) <= 1e-9, `${col}: the unweighted BAcc stays beside it`);
  }
  assert.equal(r['wk.sur'], null, 'the surrogate has no Wk');
  const note = page.locator('#comfort-note');
  assert.equal(await note.isVisible(), true);
  assert.equal(await note.getAttribute('data-label'), full.comfort, "the HiFi's Annex C label");
  assert.match(await note.textContent(), new RegExp(`HiFi [\\d.]+ m/s², ${full.comfort}`));
  t.diagnostic(`Wk at the datum: LoFi ${quarter.bacc_wk}, HiFi ${full.bacc_wk} m/s^2 (${full.comfort})`);
  // The LoFi BAcc map is the Wk one, and says so.
  assert.match(await page.textContent('figure[data-crit="bacc"] .map-title'), /BAcc \(Wk\): Wk-weighted RMS body acceleration/);
  const maps = await page.evaluate(() => {
    const a = window.__ridelab;
    return { nx: a.maps.nx, ny: a.maps.ny, values: Array.from(a.maps.values.slice(0, 3)), box: a.desc.designBox };
  });
  // Its first cell, at the cell centre, is `ridelab eval`'s Wk there (spectral route) to 1e-8.
  const ks = maps.box.ks_min + (0.5 * (maps.box.ks_max - maps.box.ks_min)) / maps.nx;
  const cs = maps.box.cs_min + (0.5 * (maps.box.cs_max - maps.box.cs_min)) / maps.ny;
  const cell = cli(['eval', '--model', 'quarter', '--ks', String(ks), '--cs', String(cs)]);
  assert.ok(rel(maps.values[0], cell.bacc_wk) <= 1e-8, `LoFi Wk map cell ${maps.values[0]} vs CLI ${cell.bacc_wk}`);
  // The plane: the LoFi's Wk front, as `ridelab optimize --evaluator quarter --comfort wk`.
  assert.match(await page.textContent('#h-objective'), /LoFi, Wk comfort/);
  const fr = await page.evaluate(() => window.__ridelab.front);
  assert.equal(fr.comfort, 'wk');
  const native = optimize('quarter', ['--comfort', 'wk']);
  assert.equal(fr.study.front.length, native.front.length, 'front points');
  let worst = 0;
  fr.study.front.forEach((p, k) => {
    for (const key of ['ks', 'cs', 'bacc', 'dtl', 'sws']) worst = Math.max(worst, rel(p[key], native.front[k][key]));
  });
  assert.ok(worst <= 1e-9, `Wk front page vs CLI: ${worst}`);
  assertSamePick(fr, native, 'Wk min-max');
  assert.match(await page.textContent('#op-pick'), /BAcc \(Wk\)/);
  await page.locator('.objective').screenshot({ path: path.join(OUT, 'objective-wk.png') });
  // Back to the unweighted BAcc: the Wk row goes, the plane is the surrogate's again.
  await page.selectOption('#comfort', 'bacc');
  await settle(page);
  assert.equal(await page.isHidden('tr[data-crit="wk"]'), true);
  assert.equal(await page.evaluate(() => window.__ridelab.front.comfort), 'bacc');
  assert.doesNotMatch(await page.evaluate(() => location.hash), /comfort=/);
  assertClean(log);
  await context.close();
});

test('the knee and asf:0.3 picks equal `ridelab optimize --pick` on the same surrogate front; pseudo-weights of a clicked point', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open('#pick=knee');
  assert.equal(await page.evaluate(() => window.__ridelab.state.pick), 'knee');
  const knee = await page.evaluate(() => window.__ridelab.front);
  assertSamePick(knee, optimize('rba-mul-rbf-mq', ['--pick', 'knee']), 'knee');
  assert.match(await page.textContent('#op-pick'), /Knee pick: Ks = [\d.]+ kN\/m/);
  // The weighted pick at W = 0.3 from the Objectives tab.
  await page.click('#tab-objectives');
  await page.selectOption('#pick-rule', 'asf');
  await page.evaluate(() => {
    const el = document.getElementById('pick-weight');
    el.value = '0.3';
    el.dispatchEvent(new Event('change'));
  });
  await settle(page);
  assert.equal(await page.evaluate(() => window.__ridelab.state.pick), 'asf:0.3');
  assert.match(await page.evaluate(() => location.hash), /pick=asf%3A0\.3/);
  const asf = await page.evaluate(() => window.__ridelab.front);
  assertSamePick(asf, optimize('rba-mul-rbf-mq', ['--pick', 'asf:0.3']), 'asf:0.3');
  assert.notEqual(asf.study.pick.index, knee.study.pick.index, 'W = 0.3 picks another design than the knee');
  const table = await page.textContent('#op-pick');
  assert.match(table, /Weighted pick \(W = 0\.3\): Ks = /);
  const w = asf.study.pick.pseudo_weights;
  assert.ok(table.includes(`pseudo-weights comfort ${w[0].toFixed(2)}, road holding ${w[1].toFixed(2)}`), table);
  // Every point's pseudo-weights, from its datum ratios: w_i = (1 - d_i) / sum (1 - d_j).
  const pts = asf.study.front;
  const r = pts.map((p) => [p.bacc / asf.datum.bacc, p.dtl / asf.datum.dtl]);
  const lo = [0, 1].map((i) => Math.min(...r.map((x) => x[i])));
  const hi = [0, 1].map((i) => Math.max(...r.map((x) => x[i])));
  r.forEach((x, k) => {
    const d = [0, 1].map((i) => (x[i] - lo[i]) / (hi[i] - lo[i]));
    const s = 2 - d[0] - d[1];
    const want = [(1 - d[0]) / s, (1 - d[1]) / s];
    for (let i = 0; i < 2; i++) assert.ok(Math.abs(asf.pseudoWeights[k][i] - want[i]) <= 1e-12, `point ${k}: ${asf.pseudoWeights[k]} vs ${want}`);
  });
  // A click on a front point sets the design there and says its pseudo-weights.
  await page.click('#drawer-close', { timeout: 2000 }).catch(() => {});
  // The plane widens when the drawer closes and redraws 100 ms after its box settles.
  await page.waitForTimeout(400);
  await settle(page);
  const k = Math.floor(pts.length / 4);
  const at = await page.evaluate((k) => {
    const a = window.__ridelab;
    const p = a.front.study.front[k];
    return a.objPlane.base.px(p.bacc, p.dtl);
  }, k);
  // Where every front point was drawn before the click (the design's move may rescale the axes).
  const allAt = await page.evaluate(() => {
    const a = window.__ridelab;
    return a.front.study.front.map((p) => a.objPlane.base.px(p.bacc, p.dtl));
  });
  await page.locator('#op-overlay').click({ position: { x: at[0], y: at[1] } });
  await settle(page);
  const sel = await page.evaluate(() => window.__ridelab.objPlane.selected);
  // Neighbouring front points can lie within a pixel of each other: the click selects
  // the point nearest the clicked pixel, which is the aimed one or one on top of it. The
  // click lands on a whole pixel and the plane's overlay maps it back through its own
  // rounded box: within 2 px of the aim.
  const off = Math.hypot(allAt[sel.index][0] - at[0], allAt[sel.index][1] - at[1]);
  assert.ok(off <= 2, `the clicked front point ${sel.index} lay ${off.toFixed(2)} px from the aimed ${k} (2 px)`);
  const j = sel.index;
  const status = await page.textContent('#op-status');
  const pw = asf.pseudoWeights[j];
  assert.deepEqual(sel.weights, pw, 'the selection holds its own pseudo-weights');
  assert.ok(status.includes(`Front point ${j + 1} of ${pts.length}`) && status.includes(`pseudo-weights comfort ${pw[0].toFixed(2)}, road holding ${pw[1].toFixed(2)}`), status);
  const s = await page.evaluate(() => window.__ridelab.state);
  assert.deepEqual([s.ks, s.cs], [pts[j].ks, pts[j].cs], 'the design moved to the point');
  assertClean(log);
  await context.close();
});

test('the URL carries comfort and pick when not the default; a bad value keeps the default and says so', { timeout: TIMEOUT }, async () => {
  let { page, context, log } = await open('#comfort=wk&pick=asf:0.3&speed=25');
  let s = await page.evaluate(() => window.__ridelab.state);
  assert.deepEqual([s.comfort, s.pick, s.speed], ['wk', 'asf:0.3', 25]);
  assert.equal(await page.inputValue('#comfort'), 'wk');
  assert.equal(await page.inputValue('#pick-rule'), 'asf');
  assert.equal(await page.inputValue('#pick-weight'), '0.3');
  const hash = await page.evaluate(() => location.hash);
  assert.match(hash, /comfort=wk/);
  assert.match(hash, /pick=asf%3A0\.3/);
  assert.equal(await page.locator('#banner').isHidden(), true, 'no banner');
  assertClean(log);
  await context.close();
  // The defaults stay out of the URL.
  ({ page, context, log } = await open());
  assert.doesNotMatch(await page.evaluate(() => location.hash), /comfort|pick/);
  await context.close();
  // Bad values: the default kept, the rest of the link applied, a message naming the field.
  for (const [hash, field, want, said] of [
    ['#comfort=iso&pick=knee&speed=25', 'comfort', 'bacc', /Comfort objective: 'iso' is not 'bacc' or 'wk'.*kept the default/],
    ['#pick=asf:2&speed=25', 'pick', 'minmax', /Pick: 'asf:2': the comfort weight W of asf:W must be in \[0, 1\].*kept the default/],
    ['#pick=best&comfort=wk&speed=25', 'pick', 'minmax', /Pick: 'best' is not minmax, knee or asf:W/],
  ]) {
    ({ page, context, log } = await open(hash));
    s = await page.evaluate(() => window.__ridelab.state);
    assert.equal(s[field], want, `${hash}: ${field} keeps its default`);
    assert.equal(s.speed, 25, `${hash}: the rest of the link applies`);
    if (hash.includes('pick=knee')) assert.equal(s.pick, 'knee');
    if (hash.includes('comfort=wk')) assert.equal(s.comfort, 'wk');
    assert.equal(await page.locator('#banner').isVisible(), true, `${hash}: message shown`);
    assert.match(await page.textContent('#banner-text'), said);
    assertClean(log);
    await context.close();
  }
});
