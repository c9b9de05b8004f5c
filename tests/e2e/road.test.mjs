// End-to-end tests of the measured road in the page (issue #31): a shipped profile
// (assets/roads/) chosen on the Car & road tab is described as `ridelab road FILE --json`
// describes it (class, Gd(n0), waviness) and the design and its datum on it equal
// `ridelab eval --road FILE` for both models to REL_TOL, before and after the design and
// the speed change; a one-track file follows the page's tracks choice; bad files are refused
// naming the column and row (or the length the speed needs) and leave the last good road;
// the chart is drawn with its axes. A screenshot goes to tests/e2e/out/.
//
//   trunk build --release --offline && RIDELAB_CLI=target/debug/ridelab node --test tests/e2e/road.test.mjs

import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { openPage, settled } from './browser.mjs';
import { useSuite, assertClean, ROOT, OUT } from './harness.mjs';

const TIMEOUT = 300_000;
/** The page's criteria on the road against the CLI's, relative (the same code on both targets: they agree to about 1e-15). */
const REL_TOL = 1e-9;
const suite = useSuite();
const ROAD = path.join(ROOT, 'assets/roads/class-c-waviness-2.5.csv');

function cli(args) {
  const candidates = [process.env.RIDELAB_CLI, path.join(ROOT, 'target/debug/ridelab'), path.join(ROOT, 'target/release/ridelab')];
  const c = candidates.filter(Boolean).find((x) => fs.existsSync(x));
  assert.ok(c, 'the native CLI is built (cargo build -p ridelab)');
  return JSON.parse(execFileSync(c, [...args, '--json'], { encoding: 'utf8', maxBuffer: 256 * 1024 * 1024 }));
}

/** `ridelab eval --road file` at the page's state `s` (design, speed; one-track tracks as the page's). */
function cliEval(model, file, s, twoTracks = false) {
  const args = ['eval', '--model', model, '--car', s.car, '--road', file, '--speed', String(s.speed), '--ks', String(s.ks), '--cs', String(s.cs)];
  return cli(twoTracks ? args : [...args, '--tracks', s.tracks]);
}

function close(got, want, what) {
  assert.ok(Math.abs(got / want - 1) <= REL_TOL, `${what}: page ${got}, CLI ${want}`);
}

/** Chooses `file` (a path, or `{name, buffer}`) and waits for the panel's answer. */
async function choose(page, file) {
  await page.evaluate(() => {
    window.__roadBefore = window.__ridelab.road;
    window.__msgBefore = document.getElementById('msg-road').textContent;
  });
  const f = typeof file === 'string' ? { name: path.basename(file), mimeType: 'text/csv', buffer: fs.readFileSync(file) } : { mimeType: 'text/csv', ...file };
  await page.setInputFiles('#road-file', f);
  await page.waitForFunction(() => {
    const msg = document.getElementById('msg-road').textContent;
    return (window.__ridelab.road !== window.__roadBefore || msg) && !/^Reading/.test(document.getElementById('road-summary').textContent);
  }, null, { timeout: 60_000 });
}

/** Waits until the road is judged at the page's current state. */
async function judgedNow(page) {
  await page.waitForFunction(() => {
    const r = window.__ridelab.road;
    const s = window.__ridelab.state;
    return r && r.key === JSON.stringify([s.car, s.carJson ?? null, s.ks, s.cs, s.speed, s.tracks]) && window.__ridelab.isSettled();
  }, null, { timeout: 60_000 });
  return page.evaluate(() => ({ road: window.__ridelab.road, state: window.__ridelab.state }));
}

function sameAsCli(road, s, datum, file, twoTracks = false) {
  for (const [model, key] of [['quarter', 'quarter'], ['full', 'full']]) {
    const want = cliEval(model, file, s, twoTracks);
    for (const c of ['bacc', 'dtl', 'sws']) close(road.on[key][c], want[c], `${model} ${c} at Ks ${s.ks}, Cs ${s.cs}, ${s.speed} m/s`);
    close(road.on.bacc_wk[key], want.bacc_wk, `${model} bacc_wk at Ks ${s.ks}, Cs ${s.cs}, ${s.speed} m/s`);
    const atDatum = cliEval(model, file, { ...s, ...datum }, twoTracks);
    for (const c of ['bacc', 'dtl', 'sws']) close(road.on[`datum_${key}`][c], atDatum[c], `${model} datum ${c}`);
    close(road.on.bacc_wk[`datum_${key}`], atDatum.bacc_wk, `${model} datum bacc_wk`);
    if (model === 'full') {
      assert.equal(road.on.bacc_wk.comfort, want.comfort);
      assert.equal(road.on.bacc_wk.datum_comfort, atDatum.comfort);
    }
  }
}

/**
 * Opens the page at `hash` in a `width` x `height` window with the Car & road tab's road
 * section open and `file` chosen; `datum`: the page's car's datum design.
 */
async function openWithRoad(hash, [width, height], file) {
  const { page, context, log } = await openPage(suite.browser, `${suite.srv.url}${hash}`, { width, height });
  await settled(page, 100);
  const datum = await page.evaluate(() => ({ ks: window.__ridelab.desc.datumKs, cs: window.__ridelab.desc.datumCs }));
  await page.click('#tab-car');
  await page.evaluate(() => (document.getElementById('road-box').open = true));
  // The maps and front on a road are code the first screen does not fetch.
  const fetched = () => page.evaluate(() => performance.getEntriesByType('resource').map((e) => e.name).filter((n) => n.endsWith('/js/roadstudy.js')).length);
  assert.equal(await fetched(), 0, 'js/roadstudy.js fetched before a road');
  await choose(page, file);
  await page.waitForFunction(() => window.__ridelab.roadStudy, null, { timeout: 60_000 });
  assert.equal(await fetched(), 1, 'js/roadstudy.js fetched with the first road');
  return { page, context, log, datum };
}

test('a dropped road: described and judged as the CLI does, kept through bad files', { timeout: TIMEOUT }, async () => {
  const { page, context, log, datum } = await openWithRoad('#car=sedan&class=B&speed=20&tracks=correlated', [1600, 1000], ROAD);

  // The description is the CLI's.
  const want = cli(['road', ROAD]);
  let { road, state } = await judgedNow(page);
  assert.equal(road.desc.iso8608.class, want.iso8608.class);
  close(road.desc.iso8608.gd_n0, want.iso8608.gd_n0, 'gd_n0');
  close(road.desc.iso8608.waviness, want.iso8608.waviness, 'waviness');
  assert.equal(road.desc.samples, want.samples);
  const summary = await page.textContent('#road-summary');
  assert.match(summary, new RegExp(`class ${want.iso8608.class}, Gd\\(n0 = 0.1 cycle/m\\) \\S+ m³, waviness ${want.iso8608.waviness.toFixed(2)}`));
  sameAsCli(road, state, datum, ROAD, true);

  // A new design and a new speed: judged again, still the CLI's.
  await page.fill('#ks-num', '30.5');
  await page.press('#ks-num', 'Enter');
  await page.fill('#speed', '27');
  await page.press('#speed', 'Enter');
  ({ road, state } = await judgedNow(page));
  assert.equal(state.ks, 30500);
  assert.equal(road.on.road.speed, 27);
  sameAsCli(road, state, datum, ROAD, true);

  // The table shows the numbers in the page's units with the change against the datum.
  const rows = await page.$$eval('#road-table tbody tr', (trs) => trs.map((tr) => tr.textContent));
  assert.equal(rows.length, 4);
  assert.match(rows[1], /BAcc Wk m\/s²/);
  assert.match(rows[3], /SWS mm/);
  assert.match(await page.textContent('#road-table caption'), /at 27 m\/s, measured tracks/);

  // The chart is drawn, with its axes' units.
  const drawn = await page.evaluate(() => {
    const c = document.getElementById('road-psd');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let ink = 0;
    for (let i = 0; i < d.length; i += 4) if (d[i] < 200 || d[i + 1] < 200 || d[i + 2] < 200) ink++;
    return { ink, w: c.clientWidth, h: c.clientHeight };
  });
  assert.ok(drawn.w > 200 && drawn.h > 120, `the chart's size ${drawn.w} x ${drawn.h}`);
  assert.ok(drawn.ink > 2000, `ink on the chart: ${drawn.ink} pixels`);
  fs.mkdirSync(OUT, { recursive: true });
  await page.screenshot({ path: path.join(OUT, 'road-1600.png') });

  // Bad files: named by column and row (or by what the speed needs); the good road stays.
  const bad = [
    ['text.csv', 'distance_m,elevation_m\n0,0\n0.1,0.001\n0.2,abc\n', /elevation_m.*row 3|row 3.*elevation_m/],
    ['back.csv', 'distance_m,elevation_m\n0,0\n0.1,0.001\n0.05,0.002\n', /distance_m/],
    ['header.csv', 'x,y\n0,0\n', /distance_m/],
    ['empty.csv', '', /\S/],
  ];
  for (const [name, text, re] of bad) {
    await choose(page, { name, buffer: Buffer.from(text) });
    const msg = await page.textContent('#msg-road');
    assert.match(msg, re, `${name}: ${msg}`);
    assert.match(msg, /class-c-waviness-2\.5\.csv stays/, `${name}: ${msg}`);
    const r = await page.evaluate(() => window.__ridelab.road);
    assert.equal(r.name, 'class-c-waviness-2.5.csv', name);
  }
  // A profile too short for the speed says how long it must be.
  const short = ['distance_m,elevation_m', ...Array.from({ length: 400 }, (_, i) => `${(i * 0.1).toFixed(1)},${(0.002 * Math.sin(i / 7)).toFixed(6)}`)].join('\n');
  await choose(page, { name: 'short.csv', buffer: Buffer.from(short) });
  assert.match(await page.textContent('#msg-road'), /road/);
  assert.equal((await page.evaluate(() => window.__ridelab.road)).name, 'class-c-waviness-2.5.csv');
  assertClean(log);
  await context.close();
});

test('a one-track road drives the wheels as the page\'s tracks say, as the CLI with --tracks', { timeout: TIMEOUT }, async () => {
  // The shipped two-track profile's left track alone.
  const lines = fs.readFileSync(ROAD, 'utf8').trim().split('\n').slice(1).map((l) => l.split(','));
  const text = ['distance_m,elevation_m', ...lines.map(([x, z]) => `${x},${z}`)].join('\n');
  const file = path.join(OUT, 'one-track.csv');
  fs.mkdirSync(OUT, { recursive: true });
  fs.writeFileSync(file, text);
  const { page, context, log, datum } = await openWithRoad('#car=suv&class=C&speed=15&tracks=independent', [1280, 720], file);
  let { road, state } = await judgedNow(page);
  assert.equal(road.desc.tracks, 1);
  assert.equal(road.on.road.tracks, 'independent');
  sameAsCli(road, state, datum, file);
  // The page's tracks choice follows to the road.
  await page.selectOption('#tracks', 'correlated');
  ({ road, state } = await judgedNow(page));
  assert.equal(road.on.road.tracks, 'correlated');
  sameAsCli(road, state, datum, file);
  assertClean(log);
  await context.close();
});

/** Waits until the road's maps and front are shown for the page's current state and `model`. */
async function studiedNow(page, model) {
  await page.waitForFunction((m) => {
    const r = window.__ridelab.roadStudy;
    const s = window.__ridelab.state;
    return r && r.model === m && r.map && r.map.road.speed === s.speed && (r.front || r.status) && window.__ridelab.isSettled();
  }, model, { timeout: 120_000 });
  return page.evaluate(() => {
    const r = window.__ridelab.roadStudy;
    const plain = (m) => ({ ...m, values: Array.from(m.values), broken: Array.from(m.broken), ksValues: Array.from(m.ksValues), csValues: Array.from(m.csValues) });
    return { study: { ...r, map: plain(r.map) }, state: window.__ridelab.state };
  });
}

/** The page's maps and front on `file` equal `ridelab map` and `ridelab optimize --road FILE --grid 61 --levels 2` (`model` 'quarter' or 'full') at the page's state `s`. */
function studySameAsCli({ map, front }, s, file, model) {
  const { nx, ny, ksValues: ks, csValues: cs } = map;
  const road = ['--car', s.car, '--road', file, '--speed', String(s.speed), '--tracks', s.tracks];
  const want = cli(['map', '--model', model, ...road, '--ks-range', `${ks[0]}:${ks[nx - 1]}:${nx}`, '--cs-range', `${cs[0]}:${cs[ny - 1]}:${ny}`]);
  assert.equal(want.bacc.length, nx * ny);
  const n = nx * ny;
  ['bacc', 'dtl', 'sws'].forEach((c, k) => {
    for (let i = 0; i < n; i++) close(map.values[k * n + i], want[c][i], `${model} map ${c} at point ${i}`);
  });
  assert.deepEqual(map.broken, want.feasibility.mask, 'the objectives\' mask');
  for (const c of ['bacc', 'dtl', 'sws']) close(map.datum[c], want.datum.criteria[c], `${model} map's datum ${c}`);
  // The objective plane's STM settings, as the page's road front uses them.
  const opt = cli(['optimize', '--evaluator', model, ...road, '--grid', '61', '--levels', '2']);
  assert.equal(front.front.length, opt.front.length, 'front points');
  front.front.forEach((p, i) => {
    for (const c of ['ks', 'cs', 'bacc', 'dtl']) close(p[c], opt.front[i][c], `${model} front point ${i} ${c}`);
  });
  for (const c of ['ks', 'cs']) close(front.pick[c], opt.pick[c], `${model} pick ${c}`);
  for (const c of ['bacc', 'dtl', 'sws']) close(front.hifi_recheck.rechecked[c], opt.hifi_recheck.rechecked[c], `${model} pick's HiFi ${c}`);
  close(front.hypervolume, opt.hypervolume, `${model} hypervolume`);
  assert.deepEqual(front.road, { ...opt.road, file: path.basename(file) });
  assert.deepEqual(map.road, front.road);
}

test('the maps and front on a dropped road: ridelab map and optimize --road, redone for a new speed, not for a new design', { timeout: TIMEOUT }, async () => {
  const SLAB = path.join(ROOT, 'assets/roads/concrete-slab-5m.csv');
  const { page, context, log } = await openWithRoad('#car=sedan&class=B&speed=20&tracks=correlated', [1600, 1000], SLAB);
  let { study, state } = await studiedNow(page, 'hifi');
  assert.equal(study.status, '');
  assert.equal(study.map.nx * study.map.ny, 4800);
  studySameAsCli(study, state, SLAB, 'full');
  const drawn = await page.evaluate(() => {
    const ink = (c) => {
      const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      let n = 0;
      for (let i = 0; i < d.length; i += 4) if (d[i] < 200 || d[i + 1] < 200 || d[i + 2] < 200) n++;
      return { n, w: c.clientWidth, h: c.clientHeight };
    };
    return { map: ink(document.getElementById('map-road-bacc')), front: ink(document.getElementById('road-front')) };
  });
  for (const [k, d] of Object.entries(drawn)) {
    assert.ok(d.w > 250 && d.h > 150 && d.n > 5000, `${k}: ${d.w} x ${d.h}, ${d.n} pixels of ink`);
  }
  assert.match(await page.textContent('#road-study-caption'), /Front: \d+ designs by STM/);
  await page.evaluate(() => document.getElementById('road-study').scrollIntoView());
  await page.screenshot({ path: path.join(OUT, 'road-study-1600.png') });

  // A design move moves the markers only; the maps and front stay.
  const key = study.key;
  const timing = study.timing;
  await page.fill('#ks-num', '30.5');
  await page.press('#ks-num', 'Enter');
  await judgedNow(page);
  ({ study } = await studiedNow(page, 'hifi'));
  assert.equal(study.key, key);
  assert.deepEqual(study.timing, timing, 'not computed again for a design move');
  assert.match(await page.textContent('#road-maps'), /design: [\d.]+ m\/s²/);

  // The LoFi, then a new speed: computed again, still the CLI's.
  await page.selectOption('#road-model', 'lofi');
  await page.fill('#speed', '27');
  await page.press('#speed', 'Enter');
  ({ study, state } = await studiedNow(page, 'lofi'));
  assert.equal(study.map.road.speed, 27);
  studySameAsCli(study, state, SLAB, 'quarter');
  assertClean(log);
  await context.close();
});
