// End-to-end test of the road menu's measured road (issue #31): a profile read on the
// Car & road tab becomes the road menu's last entry, "Measured: FILE"; chosen, the
// workbench is on it: the LoFi and HiFi maps equal `ridelab map --road FILE` to REL_TOL,
// the readout `ridelab eval --road FILE`, the objective plane's front and pick are found
// on the surrogate fitted there, the HiFi front is `ridelab optimize --road FILE
// --evaluator full`'s, the study report `ridelab report --road FILE`'s byte for byte, the
// time response the first seconds of `ridelab simulate --road FILE`'s playback; a new
// speed reshapes the road; the adaptive loop starts there; load cases need an ISO class
// and say so naming the field; a class chosen again is the ISO road. The main thread's
// first-screen module has no shaped routes: its calls on a measured road go to the
// on-demand module. Screenshots go to tests/e2e/out/.
//
//   trunk build --release --offline && RIDELAB_CLI=target/debug/ridelab node --test tests/e2e/roadmenu.test.mjs

import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { openPage, settled } from './browser.mjs';
import { useSuite, assertClean, assertSameLines, ROOT, OUT } from './harness.mjs';

const TIMEOUT = 300_000;
/** The page's numbers against the CLI's, relative (the same code on both targets). */
const REL_TOL = 1e-9;
const suite = useSuite();
const SLAB = path.join(ROOT, 'assets/roads/concrete-slab-5m.csv');

function cliPath() {
  const candidates = [process.env.RIDELAB_CLI, path.join(ROOT, 'target/debug/ridelab'), path.join(ROOT, 'target/release/ridelab')];
  const c = candidates.filter(Boolean).find((x) => fs.existsSync(x));
  assert.ok(c, 'the native CLI is built (cargo build -p ridelab)');
  return path.resolve(c);
}

function cli(args) {
  return JSON.parse(execFileSync(cliPath(), [...args, '--json'], { encoding: 'utf8', maxBuffer: 256 * 1024 * 1024 }));
}

function close(got, want, what) {
  assert.ok(got === want || Math.abs(got / want - 1) <= REL_TOL, `${what}: page ${got}, CLI ${want}`);
}

/** Waits until the workbench is settled on a measured road at the state's speed (or on a class: `measured` false). */
async function settledOn(page, measured = true) {
  await page.waitForFunction((m) => {
    const r = window.__ridelab;
    const d = r.desc;
    const on = Boolean(r.state.roadProfile) === m && Boolean(d && d.measuredRoad) === m;
    return on && (!m || d.measuredRoad.speed === r.state.speed) && r.isSettled() && r.maps && r.front;
  }, measured, { timeout: 120_000 });
  await settled(page, 100);
}

/** The page's maps of `model` (`maps`: the LoFi's; `modelMaps`: the shown HiFi's) at the cells `cells` ([i, j]). */
function mapCells(page, which, cells) {
  return page.evaluate(([w, cells]) => {
    const m = w === 'maps' ? window.__ridelab.maps : window.__ridelab.modelMaps.maps;
    const n = m.nx * m.ny;
    return {
      nx: m.nx,
      ny: m.ny,
      datum: m.datum,
      cells: cells.map(([i, j]) => ({ v: [0, 1, 2].map((c) => m.values[c * n + j * m.nx + i]), broken: m.broken[j * m.nx + i] })),
    };
  }, [which, cells]);
}

test('the road menu\'s measured road: the workbench\'s maps, readout and front on it, as ridelab --road', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await openPage(suite.browser, `${suite.srv.url}#car=sedan&class=B&speed=20&tracks=correlated`, { width: 1600, height: 1000, downloads: true });
  await settled(page, 100);
  assert.equal(await page.$('#class option[value="measured"]'), null, 'no measured entry before a road is read');
  await page.click('#tab-car');
  await page.evaluate(() => (document.getElementById('road-box').open = true));
  await page.setInputFiles('#road-file', { name: 'concrete-slab-5m.csv', mimeType: 'text/csv', buffer: fs.readFileSync(SLAB) });
  await page.waitForSelector('#class option[value="measured"]', { state: 'attached', timeout: 60_000 });
  assert.equal(await page.textContent('#class option[value="measured"]'), 'Measured: concrete-slab-5m.csv');
  await page.selectOption('#class', 'measured');
  await settledOn(page);
  const { state, desc } = await page.evaluate(() => ({ state: window.__ridelab.state, desc: window.__ridelab.desc }));
  assert.match(state.roadProfile, /^concrete-slab-5m\.csv#[0-9a-f]{16}$/);
  assert.equal(desc.measuredRoad.file, 'concrete-slab-5m.csv');
  assert.equal(await page.inputValue('#class'), 'measured');
  assert.match(await page.textContent('#map-status'), /the measured road concrete-slab-5m\.csv at 20 m\/s/);

  // The LoFi maps (main thread, on its on-demand module) and the HiFi maps (worker): cells
  // against `ridelab map --road` on a 2 x 2 grid through them (the page's cell centres).
  const road = ['--car', 'sedan', '--road', SLAB, '--speed', '20', '--tracks', 'correlated'];
  const ks = (k) => 10000 + ((k + 0.5) * 30000) / 160;
  const cs = (k) => 500 + ((k + 0.5) * 3500) / 120;
  const [i, j] = [50, 70];
  const cells = [[i, j], [i + 1, j], [i, j + 1], [i + 1, j + 1]];
  for (const [which, model, mapModel] of [['maps', 'quarter', 'lofi'], ['modelMaps', 'full', 'hifi']]) {
    if (mapModel === 'hifi') {
      await page.selectOption('#map-model', 'hifi');
      await page.waitForFunction(() => window.__ridelab.modelMaps && window.__ridelab.modelMaps.model === 'hifi' && window.__ridelab.isSettled(), null, { timeout: 120_000 });
    }
    const got = await mapCells(page, which, cells);
    assert.equal(got.nx * got.ny, 160 * 120);
    const want = cli(['map', '--model', model, ...road, '--ks-range', `${ks(i)}:${ks(i + 1)}:2`, '--cs-range', `${cs(j)}:${cs(j + 1)}:2`]);
    assert.equal(want.road.file, SLAB);
    got.cells.forEach((g, k) => {
      ['bacc', 'dtl', 'sws'].forEach((c, ci) => close(g.v[ci], want[c][k], `${model} map ${c} cell ${k}`));
      assert.equal(g.broken, want.feasibility.mask[k], `${model} mask cell ${k}`);
    });
    for (const c of ['bacc', 'dtl', 'sws']) close(got.datum[c], want.datum.criteria[c], `${model} datum ${c}`);
  }

  // The readout: `ridelab eval --road` for both models at the design.
  const rd = await page.evaluate(() => ({ lofi: window.__ridelab.lofi, hifi: window.__ridelab.hifi, state: window.__ridelab.state }));
  for (const [model, r] of [['quarter', rd.lofi.design], ['full', rd.hifi.design]]) {
    const want = cli(['eval', '--model', model, ...road, '--ks', String(rd.state.ks), '--cs', String(rd.state.cs)]);
    for (const c of ['bacc', 'dtl', 'sws', 'bacc_wk']) close(r[c], want[c], `${model} readout ${c}`);
  }

  // The objective plane: a front on the surrogate fitted on the road, its pick re-checked
  // on the full car there (`ridelab eval --road` at the pick).
  const fr = await page.evaluate(() => window.__ridelab.front);
  assert.ok(!fr.error, fr.error);
  assert.ok(fr.study.front.length > 5, `front points: ${fr.study.front.length}`);
  const pick = fr.study.pick;
  const atPick = cli(['eval', '--model', 'full', ...road, '--ks', String(pick.ks), '--cs', String(pick.cs)]);
  for (const c of ['bacc', 'dtl', 'sws']) close(fr.recheck.rechecked[c], atPick[c], `pick's HiFi ${c}`);
  // The HiFi front (heavy worker): `ridelab optimize --road --evaluator full` with the
  // objective plane's STM settings.
  await page.waitForFunction(() => {
    const h = window.__ridelab.hifiFront;
    return window.__ridelab.isSettled() && h && (h.error || h.front);
  }, null, { timeout: 120_000 });
  const hf = await page.evaluate(() => window.__ridelab.hifiFront);
  assert.ok(!hf.error, hf.error && hf.error.message);
  const hopt = cli(['optimize', '--evaluator', 'full', ...road, '--grid', '61', '--levels', '2']);
  assert.equal(hf.front.study.front.length, hopt.front.length, 'HiFi front points');
  hf.front.study.front.forEach((p, k) => ['ks', 'cs', 'bacc', 'dtl'].forEach((c) => close(p[c], hopt.front[k][c], `HiFi front point ${k} ${c}`)));
  close(hf.front.study.hypervolume, hopt.hypervolume, 'HiFi hypervolume');
  for (const c of ['ks', 'cs']) close(hf.front.study.pick[c], hopt.pick[c], `HiFi pick ${c}`);
  fs.mkdirSync(OUT, { recursive: true });
  await page.screenshot({ path: path.join(OUT, 'roadmenu-1600.png') });

  // The study report on the road: `ridelab report --road FILE` byte for byte (the CLI run
  // where the file is, so that both name it alike).
  await page.click('#tab-export');
  const [dl] = await Promise.all([page.waitForEvent('download', { timeout: 200_000 }), page.click('#report-html')]);
  const pageReport = path.join(OUT, 'report-page-slab.html');
  await dl.saveAs(pageReport);
  const dir = path.join(OUT, 'report-cli-slab');
  execFileSync(cliPath(), ['report', '--road', path.basename(SLAB), '--car', 'sedan', '--speed', '20', '--approach', 'rba-mul-rbf-mq', '--plan', 'ae:10', '--out', dir], { cwd: path.dirname(SLAB), stdio: ['ignore', 'pipe', 'pipe'] });
  assertSameLines(fs.readFileSync(pageReport, 'utf8'), fs.readFileSync(path.join(dir, 'report.html'), 'utf8'), 'page and CLI reports on the measured road');
  await page.click('#tab-car');

  // A new speed: the road shaped again at it, the maps the CLI's there.
  await page.fill('#speed', '27');
  await page.press('#speed', 'Enter');
  await settledOn(page);
  await page.selectOption('#map-model', 'lofi');
  await settledOn(page);
  const at27 = await mapCells(page, 'maps', cells);
  const want27 = cli(['map', '--model', 'quarter', ...road.map((a) => (a === '20' ? '27' : a)), '--ks-range', `${ks(i)}:${ks(i + 1)}:2`, '--cs-range', `${cs(j)}:${cs(j + 1)}:2`]);
  at27.cells.forEach((g, k) => ['bacc', 'dtl', 'sws'].forEach((c, ci) => close(g.v[ci], want27[c][k], `27 m/s quarter ${c} cell ${k}`)));

  // The time response: the profile played back from rest, the first 10 s of `ridelab
  // simulate --road FILE` (both models, every kept sample to REL_TOL).
  const tr = await page.evaluate(() => window.__ridelab.heavyEngine.call('timeResponse', window.__ridelab.state, { duration: 10, dt: 0.001, f_min: 0.1, f_max: 200, decimate: 10, seed: 1 }));
  for (const [model, r] of [['quarter', tr.lofi], ['full', tr.hifi]]) {
    const want = cli(['simulate', '--model', model, '--car', 'sedan', '--road', SLAB, '--speed', '27', '--decimate', '10']);
    const n = r.t.length;
    assert.ok(n > 1000 && Math.abs(r.t[n - 1] - 10) < 0.01, `${model}: ${n} samples to ${r.t[n - 1]} s`);
    for (let i = 0; i < n; i += 7) {
      assert.equal(r.t[i], want.series.t[i], `${model} t[${i}]`);
      ['bacc', 'dtl', 'sws'].forEach((c, o) => close(r.outputs[o][i], want.series[c][i], `${model} ${c} at ${r.t[i]} s`));
    }
  }
  // The spectra: drawn on the road's PSD (the Rust tests check their area).
  const sp = await page.evaluate(() => window.__ridelab.heavyEngine.call('spectra', window.__ridelab.state, 60));
  assert.equal(sp.f.length, 60);
  assert.ok(sp.hifi.psd[0].every((p) => Number.isFinite(p) && p > 0), 'HiFi BAcc PSD');

  // The adaptive loop starts on the road (the Rust tests compare it with `ridelab
  // surrogate --road FILE --adaptive K`); robust cases need an ISO class, and say so.
  const started = await page.evaluate(() => window.__ridelab.heavyEngine.call('adaptiveStart', window.__ridelab.state, {}).then(() => ({ ok: true }), (e) => ({ ok: false, e })));
  assert.ok(started.ok, JSON.stringify(started.e));
  const cases = await page.evaluate(() => window.__ridelab.engine.call('checkState', { ...window.__ridelab.state, cases: '{"operating": [{"class": "C", "speed": 25}]}' }).then(() => null, (e) => e));
  assert.equal(cases.field, 'cases');
  assert.match(cases.message, /measured road is one scenario/);

  // A class again: the ISO road, the menu shows it.
  await page.selectOption('#class', 'C');
  await settledOn(page, false);
  assert.equal((await page.evaluate(() => window.__ridelab.state)).roadProfile, undefined);
  assert.match(await page.textContent('#map-status'), /class C at 27 m\/s/);
  assertClean(log);
  await context.close();
});
