// End-to-end tests of the analysis panels: objective plane (front, pick, design
// marker, NSGA-II, no-feasible message), FRF / PSD plots, time panel, exports and
// sessions. Pixel checks on the canvases; screenshots in tests/e2e/out/.
//
//   trunk build --release --offline && npm run test:e2e

import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { openPage, settled } from './browser.mjs';
import { useSuite, assertClean, countColour, median, p95, OUT } from './harness.mjs';

const TIMEOUT = 120_000;
const suite = useSuite();

function open(hash = '', { width = 1400, height = 1000, dpr = 1 } = {}) {
  return openPage(suite.browser, suite.srv.url + hash, { width, height, dpr, downloads: true }).then(async (r) => {
    await settle(r.page);
    return r;
  });
}

function settle(page) {
  return settled(page, 150);
}

/** RGBA of canvas `id` at CSS px (x, y). */
function pixel(page, id, x, y) {
  return page.evaluate(
    ([id, x, y]) => {
      const c = document.getElementById(id);
      const dpr = c.width / c.clientWidth;
      return Array.from(c.getContext('2d').getImageData(Math.round(x * dpr), Math.round(y * dpr), 1, 1).data);
    },
    [id, x, y],
  );
}

const STM = [194, 65, 12];
const PICK = [250, 204, 21];
const LOFI = [29, 78, 216];
const HIFI = [185, 28, 28];
const NSGA = [21, 128, 61];


test('objective plane: feasible set, STM front, pick with HiFi re-check, datum', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  const fr = await page.evaluate(() => window.__ridelab.front);
  assert.ok(!fr.error, `a front at class B (${fr.error})`);
  assert.ok(fr.study.front.length > 10, `front has ${fr.study.front.length} points`);
  assert.ok(fr.study.hypervolume > 0, 'hypervolume > 0');
  const pk = fr.study.pick;
  assert.ok(pk.criteria.sws <= 0.007 * (1 + 1e-9), 'the pick meets the SWS limit');
  assert.ok(Math.abs(fr.recheck.rechecked.bacc / pk.criteria.bacc - 1) < 0.3, 'HiFi re-check near the LoFi prediction');
  const line = await countColour(page, 'op-base', STM);
  assert.ok(line > 150, `front line drawn (${line} px)`);
  const cloud = await countColour(page, 'op-base', [210, 223, 240], 30);
  assert.ok(cloud > 200, `feasible set drawn (${cloud} px)`);
  const at = await page.evaluate(() => {
    const a = window.__ridelab;
    const c = a.front.study.pick.criteria;
    return a.objPlane.base.px(c.bacc, c.dtl);
  });
  const px = await pixel(page, 'op-base', at[0], at[1]);
  assert.ok(Math.abs(px[0] - PICK[0]) + Math.abs(px[1] - PICK[1]) + Math.abs(px[2] - PICK[2]) < 40, `pick marker drawn at the pick (${px})`);
  const table = await page.locator('#op-pick').textContent();
  assert.match(table, /Min-max pick: Ks = [\d.]+ kN\/m/);
  assert.match(table, /HiFi re-check/);
  // Ratio axes: the datum sits at (1, 1).
  await page.selectOption('#op-scale', 'ratio');
  const d = await page.evaluate(() => window.__ridelab.objPlane.base.px(1, 1));
  const dp = await pixel(page, 'op-base', d[0], d[1]);
  assert.deepEqual(dp.slice(0, 3), [255, 255, 255], `datum marker (white square) at (1, 1): ${dp}`);
  await page.locator('.objective').screenshot({ path: path.join(OUT, 'objective-ratio.png') });
  await page.selectOption('#op-scale', 'abs');
  // NSGA-II for comparison.
  await page.click('#op-nsga');
  await page.waitForFunction(() => window.__ridelab.nsga, null, { timeout: 60_000 });
  await settle(page);
  const ns = await page.evaluate(() => window.__ridelab.nsga);
  assert.ok(!ns.error && ns.study.front.length > 5, 'NSGA-II front');
  const green = await countColour(page, 'op-base', NSGA);
  assert.ok(green > 40, `NSGA-II points drawn (${green} px)`);
  assert.match(await page.locator('#op-status').textContent(), /NSGA-II .*hypervolume/);
  await page.locator('.objective').screenshot({ path: path.join(OUT, 'objective.png') });
  assertClean(log);
  await context.close();
});

test('moving the Ks slider moves the design marker in the objective plane', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  const before = await page.evaluate(() => window.__ridelab.objPlane.designAt);
  const c0 = await pixel(page, 'op-overlay', before[0], before[1]);
  assert.deepEqual(c0.slice(0, 3), [0, 0, 0], 'black design marker');
  await page.focus('#ks-range');
  for (let i = 0; i < 40; i++) await page.keyboard.press('ArrowRight');
  await settle(page);
  const after = await page.evaluate(() => window.__ridelab.objPlane.designAt);
  assert.ok(Math.hypot(after[0] - before[0], after[1] - before[1]) > 5, `marker moved (${before} -> ${after})`);
  assert.ok(after[0] > before[0], 'stiffer spring: more BAcc, marker to the right');
  const c1 = await pixel(page, 'op-overlay', after[0], after[1]);
  assert.deepEqual(c1.slice(0, 3), [0, 0, 0], 'marker drawn at the new place');
  const old = await pixel(page, 'op-overlay', before[0], before[1]);
  assert.equal(old[3], 0, 'old place cleared');
  assertClean(log);
  await context.close();
});

test('changing the SWS limit changes the front; edit-to-front timing', { timeout: TIMEOUT }, async (t) => {
  const { page, context, log } = await open();
  const f0 = await page.evaluate(() => window.__ridelab.front.study.front.map((p) => [p.bacc, p.dtl]));
  const times = [];
  const limits = [];
  for (let i = 0; i < 16; i++) limits.push(7.5 + 0.25 * i);
  // One edit of field `id` to `value`, back to back with the last: ms to the new front
  // on screen (the frame after it is drawn).
  const edit = (id, value) =>
    page.evaluate(async ([id, value]) => {
      const a = window.__ridelab;
      const n = a.frontDraws;
      const el = document.getElementById(id);
      const t0 = performance.now();
      el.value = String(value);
      el.dispatchEvent(new Event('change'));
      while (a.frontDraws === n) await new Promise((r) => setTimeout(r, 0));
      await new Promise((r) => requestAnimationFrame(() => r()));
      return performance.now() - t0;
    }, [id, value]);
  for (const mm of limits) times.push(await edit('sws-limit', mm));
  await settle(page);
  const f1 = await page.evaluate(() => window.__ridelab.front.study.front.map((p) => [p.bacc, p.dtl]));
  assert.notDeepEqual(f1, f0, 'the front changed');
  const limit = await page.evaluate(() => window.__ridelab.state.swsLimit);
  assert.ok(Math.abs(limit - 0.01125) < 1e-12, 'last limit applied');
  const maxSws = await page.evaluate(() => Math.max(...window.__ridelab.front.study.front.map((p) => p.sws)));
  assert.ok(maxSws > 0.007, `a larger limit lets the front reach SWS ${maxSws * 1000} mm > 7 mm`);
  // The maps caught up with the last limit once the edits stopped.
  const caught = await page.evaluate(() => {
    const a = window.__ridelab;
    return a.maps.key === JSON.stringify({ ...a.state, ks: 0, cs: 0 }) && a.views.every((v) => v.data.feasible === a.maps.feasible);
  });
  assert.ok(caught, 'the maps show the last state');
  const edits = times.slice(1);
  const pct = p95(edits);
  const med = [...edits].sort((a, b) => a - b)[Math.floor(edits.length / 2)];
  t.diagnostic(`SWS limit edit -> new front on screen (surrogate feasible set + STM front on the surrogate + pick + HiFi re-check + redraw; the maps follow): median ${med.toFixed(1)} ms, p95 ${pct.toFixed(1)} ms over ${edits.length} back-to-back edits`);
  // Where an edit's time goes: waiting in the update queue, wasm work (surrogate,
  // feasible set, front, reports), drawing (objective plane, readout, markers); the rest
  // up to the measured time is the browser's frame (paint) and other tasks.
  const phases = await page.evaluate(() => window.__ridelab.metrics.scenarioPhases.slice(-15));
  const mid = (k) => median(phases.map((p) => p[k])).toFixed(1);
  t.diagnostic(`  per edit, medians: queue ${mid('wait')} ms, wasm ${mid('compute')} ms, drawing ${mid('render')} ms`);
  // Road edits refit the surrogate (10 new HiFi runs) before the front.
  const road = [];
  for (let i = 1; i <= 10; i++) road.push(await edit('speed', 20 + 0.5 * i));
  const roadMed = [...road].sort((a, b) => a - b)[Math.floor(road.length / 2)];
  t.diagnostic(`speed edit -> surrogate refitted, new front on screen: median ${roadMed.toFixed(1)} ms, p95 ${p95(road).toFixed(1)} ms over ${road.length} back-to-back edits`);
  // Isolated edits (the page settled in between): edit -> the three maps redrawn.
  await settle(page);
  const mapsMs = [];
  for (const mm of [8, 8.5, 9, 9.5, 10]) {
    mapsMs.push(
      await page.evaluate(async (mm) => {
        const a = window.__ridelab;
        const n = a.metrics.maps.length;
        const el = document.getElementById('sws-limit');
        const t0 = performance.now();
        el.value = String(mm);
        el.dispatchEvent(new Event('change'));
        while (a.metrics.maps.length === n) await new Promise((r) => setTimeout(r, 1));
        return performance.now() - t0;
      }, mm),
    );
    await settle(page);
  }
  const mapsMed = [...mapsMs].sort((a, b) => a - b)[Math.floor(mapsMs.length / 2)];
  t.diagnostic(`SWS limit edit -> the three maps redrawn (a frame after the front): median ${mapsMed.toFixed(1)} ms over ${mapsMs.length} isolated edits`);
  fs.writeFileSync(
    path.join(OUT, 'front-timing.json'),
    JSON.stringify({ p95Ms: pct, medianMs: med, samplesMs: edits, speedEditMs: road, mapsAfterEditMs: mapsMs }, null, 2),
  );
  await edit('sws-limit', 11.25);
  await edit('speed', 20);
  await settle(page);
  // A bad entry: message next to the field, the last good front kept.
  const before = await page.evaluate(() => window.__ridelab.front.study.hypervolume);
  await page.fill('#sws-limit', '-3');
  await page.locator('#sws-limit').dispatchEvent('change');
  await settle(page);
  assert.match(await page.locator('#msg-swsLimit').textContent(), /SWS limit/);
  assert.equal(await page.evaluate(() => window.__ridelab.front.study.hypervolume), before, 'last good front kept');
  assertClean(log);
  await context.close();
});

test('dragging the SWS limit slider moves the front while it is dragged', { timeout: TIMEOUT }, async (t) => {
  const { page, context, log } = await open();
  await page.locator('#sws-range').scrollIntoViewIfNeeded();
  const box = await page.locator('#sws-range').boundingBox();
  const f0 = await page.evaluate(() => ({ draws: window.__ridelab.frontDraws, hv: window.__ridelab.front.study.hypervolume }));
  // A pointer drag across the slider at about 60 moves a second, from 30 % to 70 % of
  // its track (1..20 mm: about 6.7 to 14.3 mm).
  const y = box.y + box.height / 2;
  await page.mouse.move(box.x + 0.3 * box.width, y);
  await page.mouse.down();
  const during = [];
  for (let i = 1; i <= 40; i++) {
    await page.mouse.move(box.x + (0.3 + (0.4 * i) / 40) * box.width, y);
    await page.waitForTimeout(16);
    if (i % 10 === 0) during.push(await page.evaluate(() => window.__ridelab.frontDraws));
  }
  const dragged = await page.evaluate(() => Number(document.getElementById('sws-range').value));
  await page.mouse.up();
  const drawsAtRelease = await page.evaluate(() => window.__ridelab.frontDraws);
  await settle(page);
  const end = await page.evaluate(() => ({
    draws: window.__ridelab.frontDraws,
    limit: window.__ridelab.state.swsLimit,
    text: document.getElementById('sws-limit').value,
    hv: window.__ridelab.front.study.hypervolume,
    maxSws: Math.max(...window.__ridelab.front.study.front.map((p) => p.sws)),
  }));
  t.diagnostic(`SWS slider drag (40 moves, ~0.9 s): ${drawsAtRelease - f0.draws} fronts drawn during the drag, ` +
    `${end.draws - f0.draws} in all; front draws after every 10 moves: ${during.map((d) => d - f0.draws).join(', ')}`);
  // The front moved while the pointer was still down, more than once ...
  assert.ok(during[0] > f0.draws, 'a new front within the first 10 moves');
  assert.ok(drawsAtRelease - f0.draws >= 4, `${drawsAtRelease - f0.draws} fronts during the drag`);
  // ... and it ends on the slider's last value, shown in the text field too.
  assert.ok(dragged > 12 && dragged < 16, `slider at ${dragged} mm`);
  assert.ok(Math.abs(end.limit * 1000 - dragged) < 1e-9, `limit ${end.limit * 1000} mm = slider ${dragged} mm`);
  assert.equal(Number(end.text), dragged);
  assert.notEqual(end.hv, f0.hv, 'a different front');
  assert.ok(end.maxSws <= end.limit * (1 + 1e-9), 'the front keeps to the new limit');
  // Faster input than the page can follow coalesces: 20 input events in one task make
  // at most two updates (the one taken first, then the latest value), not 20.
  const burst = await page.evaluate(async () => {
    const a = window.__ridelab;
    const n = a.frontDraws;
    const el = document.getElementById('sws-range');
    for (let i = 0; i < 20; i++) {
      el.value = String(9 + 0.1 * i);
      el.dispatchEvent(new Event('input'));
    }
    while (!a.isSettled()) await new Promise((r) => setTimeout(r, 5));
    return { fronts: a.frontDraws - n, limit: a.state.swsLimit };
  });
  assert.ok(burst.fronts >= 1 && burst.fronts <= 2, `${burst.fronts} fronts for a burst of 20 inputs`);
  assert.ok(Math.abs(burst.limit - 0.0109) < 1e-12, `the burst ends on its last value (${burst.limit})`);
  assertClean(log);
  await context.close();
});

test('class C: the objective plane names the binding objective', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  await page.selectOption('#class', 'C');
  await settle(page);
  const msg = page.locator('#op-msg');
  assert.equal(await msg.isVisible(), true, 'message shown');
  const text = await msg.textContent();
  assert.match(text, /no feasible design/i);
  assert.match(text, /sws|SWS/i, `names the SWS objective: ${text}`);
  assert.equal(await page.locator('#op-wrap').isHidden(), true, 'no empty plot');
  await page.locator('.objective').screenshot({ path: path.join(OUT, 'objective-class-c.png') });
  await page.selectOption('#class', 'B');
  await settle(page);
  assert.equal(await page.locator('#op-wrap').isVisible(), true, 'the plot comes back');
  assertClean(log);
  await context.close();
});

test('FRF and PSD plots draw both models', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  const sp = await page.evaluate(() => window.__ridelab.spectra);
  assert.ok(sp && sp.f.length > 100, 'spectra computed');
  assert.ok(Math.abs(sp.f[0] - 0.1) < 1e-12 && Math.abs(sp.f[sp.f.length - 1] - 100) < 1e-9, '0.1..100 Hz');
  // The panel draws when it is on screen (and catches up when scrolled to).
  await page.locator('.spectra').scrollIntoViewIfNeeded();
  await page.waitForTimeout(150);
  for (const id of ['sp-frf-bacc', 'sp-frf-dtl', 'sp-frf-sws', 'sp-psd-bacc', 'sp-psd-dtl', 'sp-psd-sws']) {
    const blue = await countColour(page, id, LOFI);
    const red = await countColour(page, id, HIFI);
    assert.ok(blue > 100, `${id}: LoFi curve (${blue} px)`);
    assert.ok(red > 50, `${id}: HiFi curve (${red} px)`);
  }
  // Body bounce peak of BAcc/road gain between 0.8 and 2 Hz... the LoFi has a local max there.
  const k = sp.lofi.frf[0].findIndex((_, i, a) => i > 0 && i < a.length - 1 && a[i] > a[i - 1] && a[i] > a[i + 1]);
  assert.ok(sp.f[k] > 0.7 && sp.f[k] < 2.5, `first BAcc FRF peak at ${sp.f[k]} Hz (body bounce)`);
  const s0 = JSON.stringify(sp.lofi.frf[0].slice(0, 5));
  await page.focus('#cs-range');
  for (let i = 0; i < 10; i++) await page.keyboard.press('ArrowRight');
  await settle(page);
  const s1 = await page.evaluate(() => JSON.stringify(window.__ridelab.spectra.lofi.frf[0].slice(0, 5)));
  assert.notEqual(s1, s0, 'spectra follow the design');
  await page.locator('.spectra').screenshot({ path: path.join(OUT, 'spectra.png') });
  assertClean(log);
  await context.close();
});

test('time panel: runs both models in the worker, plots and animates', { timeout: TIMEOUT }, async (t) => {
  const { page, context, log } = await open();
  // Bad input: a message next to the field, nothing run.
  await page.fill('#tp-bump', '2');
  await page.click('#tp-run');
  assert.match(await page.locator('#msg-tpRebound').textContent(), /both/);
  await page.fill('#tp-rebound', 'abc');
  await page.click('#tp-run');
  assert.match(await page.locator('#msg-tpRebound').textContent(), /not a number/);
  await page.fill('#tp-bump', '');
  await page.fill('#tp-rebound', '');
  const t0 = Date.now();
  await page.click('#tp-run');
  await page.waitForFunction(() => window.__ridelab.time, null, { timeout: 60_000 });
  t.diagnostic(`time response (10 s, 1 ms, both models) in ${Date.now() - t0} ms`);
  await settle(page);
  const r = await page.evaluate(() => {
    const x = window.__ridelab.time;
    return { n: x.hifi.t.length, rmsL: x.lofi.rms, rmsH: x.hifi.rms, pos: x.hifi.positions.length };
  });
  assert.equal(r.n, 1000, '10 s at 1 ms, every 10th sample');
  assert.equal(r.pos, 7, 'full-car coordinates');
  for (const id of ['tp-bacc', 'tp-dtl', 'tp-sws']) {
    assert.ok((await countColour(page, id, LOFI)) > 200, `${id}: LoFi trace`);
    assert.ok((await countColour(page, id, HIFI)) > 200, `${id}: HiFi trace`);
  }
  const body = await countColour(page, 'tp-car', [57, 98, 217], 60);
  assert.ok(body > 500, `car body drawn (${body} px)`);
  const wheels = await countColour(page, 'tp-car', [17, 24, 39], 20);
  assert.ok(wheels > 200, `wheels drawn (${wheels} px)`);
  const k0 = await page.evaluate(() => window.__ridelab.timePanel.k);
  await page.click('#tp-play');
  await page.waitForTimeout(500);
  const img1 = await page.locator('#tp-car').screenshot();
  await page.waitForTimeout(300);
  const img2 = await page.locator('#tp-car').screenshot();
  await page.click('#tp-play');
  const k1 = await page.evaluate(() => window.__ridelab.timePanel.k);
  assert.ok(k1 !== k0, `animation advanced (${k0} -> ${k1})`);
  assert.ok(!img1.equals(img2), 'the side view changes while playing');
  assert.equal(await page.locator('#tp-play').textContent(), 'Play', 'paused');
  await page.locator('.timep').screenshot({ path: path.join(OUT, 'time.png') });
  // Asymmetric damper.
  await page.fill('#tp-bump', '1');
  await page.fill('#tp-rebound', '3');
  await page.click('#tp-run');
  await page.waitForFunction(() => /asymmetric/.test(document.getElementById('tp-status').textContent), null, { timeout: 60_000 });
  assertClean(log);
  await context.close();
});

test('exports: maps CSV, front CSV, PNG, session round trip', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  const grab = async (sel) => {
    const [dl] = await Promise.all([page.waitForEvent('download'), page.click(sel)]);
    const file = path.join(OUT, dl.suggestedFilename());
    await dl.saveAs(file);
    return file;
  };
  const maps = fs.readFileSync(await grab('#maps-csv'), 'utf8').trim().split('\n');
  assert.equal(maps[0], 'ks_N_per_m,cs_Ns_per_m,bacc_m_per_s2,dtl_N,sws_m,feasible');
  assert.equal(maps.length, 1 + 160 * 120, 'one row per map cell');
  const front = fs.readFileSync(await grab('#front-csv'), 'utf8').trim().split('\n');
  assert.equal(front[0], 'method,ks_N_per_m,cs_Ns_per_m,bacc_m_per_s2,dtl_N,sws_m,pick');
  assert.equal(front.filter((l) => l.endsWith(',1')).length, 1, 'one pick row');
  const png = fs.readFileSync(await grab('#op-png'));
  assert.deepEqual([...png.subarray(1, 4)].map((c) => String.fromCharCode(c)).join(''), 'PNG');
  // Session: save at class A, 25 m/s; load it into a fresh page.
  await page.selectOption('#class', 'A');
  await settle(page);
  await page.fill('#speed', '25');
  await page.locator('#speed').dispatchEvent('change');
  await settle(page);
  const sessionFile = await grab('#session-save');
  const session = JSON.parse(fs.readFileSync(sessionFile, 'utf8'));
  assert.equal(session.state.class, 'A');
  const b = await open();
  await b.page.setInputFiles('#session-load', sessionFile);
  await b.page.waitForFunction(() => window.__ridelab.state.class === 'A', null, { timeout: 30_000 });
  await settle(b.page);
  assert.equal(await b.page.evaluate(() => window.__ridelab.state.speed), 25);
  // A bad session file: message, state kept.
  const bad = path.join(OUT, 'bad-session.json');
  fs.writeFileSync(bad, JSON.stringify({ ridelab: 'session', state: { ...session.state, speed: -1 } }));
  await b.page.setInputFiles('#session-load', bad);
  await b.page.waitForFunction(() => document.getElementById('msg-session').textContent.length > 0);
  assert.match(await b.page.locator('#msg-session').textContent(), /speed/);
  assert.equal(await b.page.evaluate(() => window.__ridelab.state.speed), 25);
  assertClean(b.log);
  await b.context.close();
  await page.screenshot({ path: path.join(OUT, 'panels-full.png'), fullPage: true });
  assertClean(log);
  await context.close();
});

test('HiDPI and large type: the new charts are sized in device pixels and redraw', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open('', { dpr: 2 });
  await page.locator('.spectra').scrollIntoViewIfNeeded();
  await page.waitForTimeout(150);
  const sizes = () =>
    page.evaluate(() =>
      ['op-base', 'op-overlay', 'sp-frf-bacc', 'sp-psd-sws'].map((id) => {
        const c = document.getElementById(id);
        return { id, w: c.width, css: c.clientWidth };
      }),
    );
  for (const s of await sizes()) assert.equal(s.w, Math.round(s.css * 2), `${s.id}: ${s.w} px for ${s.css} CSS px at dpr 2`);
  const line = await countColour(page, 'op-base', STM);
  assert.ok(line > 300, `front drawn at dpr 2 (${line} px)`);
  await page.check('#large');
  await page.waitForTimeout(400);
  for (const s of await sizes()) assert.equal(s.w, Math.round(s.css * 2), `${s.id} after large type`);
  assert.ok((await countColour(page, 'sp-frf-bacc', LOFI)) > 100, 'FRF redrawn after large type');
  await page.locator('.objective').screenshot({ path: path.join(OUT, 'objective-hidpi-large.png') });
  assertClean(log);
  await context.close();
});

test('front, spectra, timeResponse: bad arguments name the field; front timing', { timeout: TIMEOUT }, async (t) => {
  const { page, context, log } = await open();
  const r = await page.evaluate(() => {
    const a = window.__ridelab;
    const s = a.state;
    const err = (f) => {
      try {
        f();
        return null;
      } catch (e) {
        return { message: e.message, field: e.field };
      }
    };
    const times = [];
    for (let i = 0; i < 15; i++) {
      const t0 = performance.now();
      a.api.front({ ...s, swsLimit: 0.007 + 0.0002 * i }, 'stm');
      times.push(performance.now() - t0);
    }
    return {
      method: err(() => a.api.front(s, 'simplex')),
      nfreq: err(() => a.api.spectra(s, 1)),
      dt: err(() => a.api.timeResponse(s, { dt: 0.5 })),
      asym: err(() => a.api.timeResponse(s, { damper: { bump: -1, rebound: 2 } })),
      unknown: err(() => a.api.front({ ...s, bogus: 1 }, 'stm')),
      classC: err(() => a.api.front({ ...s, class: 'C' }, 'stm')),
      times,
    };
  });
  assert.equal(r.method.field, 'method');
  assert.equal(r.nfreq.field, 'nfreq');
  assert.equal(r.dt.field, 'dt');
  assert.equal(r.asym.field, 'damper');
  assert.equal(r.unknown.field, 'state');
  assert.equal(r.classC.field, 'swsLimit', `class C: ${r.classC.message}`);
  const pct = p95(r.times);
  t.diagnostic(`wasm front(state, "stm") on the LoFi (61 x 61, 2 levels, + pick + HiFi re-check): p95 ${pct.toFixed(1)} ms over 15 SWS limits`);
  console.log(`front(stm) wasm call p95 ${pct.toFixed(1)} ms`);
  assert.ok(pct < 200, 'the LoFi front stays fast');
  assertClean(log);
  await context.close();
});
