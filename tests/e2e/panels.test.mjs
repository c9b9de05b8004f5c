// End-to-end tests of the analysis panels: objective plane (front, pick, design
// marker, NSGA-II, no-feasible message), FRF / PSD plots, time panel, exports and
// sessions. Pixel checks on the canvases; screenshots in tests/e2e/out/.
//
//   trunk build --release --offline && npm run test:e2e

import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { openPage, settled } from './browser.mjs';
import { useSuite, assertClean, assertSameLines, countColour, readZip, ROOT, OUT } from './harness.mjs';

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

/** The area `points` (`{bacc, dtl}`) dominate up to `ref` (`[bacc, dtl]`), both minimised. */
function hypervolume(points, ref) {
  const ps = points.filter((p) => p.bacc < ref[0] && p.dtl < ref[1]).sort((a, b) => a.bacc - b.bacc || a.dtl - b.dtl);
  let area = 0;
  let best = ref[1];
  for (let i = 0; i < ps.length; i++) {
    if (ps[i].dtl >= best) continue;
    const next = ps.slice(i + 1).find((q) => q.dtl < ps[i].dtl);
    const x1 = next ? next.bacc : ref[0];
    area += (x1 - ps[i].bacc) * (ref[1] - ps[i].dtl);
    best = ps[i].dtl;
  }
  return area;
}

/** The native CLI (RIDELAB_CLI, else target/debug or target/release). */
function cli() {
  const candidates = [process.env.RIDELAB_CLI, path.join(ROOT, 'target/debug/ridelab'), path.join(ROOT, 'target/release/ridelab')];
  const c = candidates.filter(Boolean).find((x) => fs.existsSync(x));
  assert.ok(c, 'the native CLI is built (cargo build -p ridelab)');
  return c;
}


test('objective plane: feasible set, STM front, pick with HiFi re-check, datum', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  const fr = await page.evaluate(() => window.__ridelab.front);
  assert.ok(!fr.error, `a front at class B (${fr.error})`);
  assert.ok(fr.study.front.length > 10, `front has ${fr.study.front.length} points`);
  assert.ok(fr.study.hypervolume > 0, 'hypervolume > 0');
  const pk = fr.study.pick;
  assert.ok(pk.criteria.sws <= 0.007 * (1 + 1e-9), 'the pick meets the SWS limit');
  for (const e of fr.recheck.error_percent) assert.ok(Math.abs(e) < 1, `the pick's HiFi re-check within 1 % (${fr.recheck.error_percent})`);
  // The hypervolume shown is the area the front dominates up to its reference point.
  const hvStm = hypervolume(fr.study.front, fr.study.reference_point);
  assert.ok(Math.abs(hvStm / fr.study.hypervolume - 1) < 1e-9, `STM hypervolume ${fr.study.hypervolume} = ${hvStm}`);
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
  const { ns, limit, box } = await page.evaluate(() => ({ ns: window.__ridelab.nsga, limit: window.__ridelab.state.swsLimit, box: window.__ridelab.desc.designBox }));
  assert.ok(!ns.error && ns.study.front.length > 5, 'NSGA-II front');
  // Every NSGA-II point is a feasible design of the box, non-dominated within its front.
  for (const p of ns.study.front) {
    assert.ok(p.sws <= limit * (1 + 1e-12), `NSGA-II point meets the SWS limit (${p.sws})`);
    assert.ok(p.ks >= box.ks_min && p.ks <= box.ks_max && p.cs >= box.cs_min && p.cs <= box.cs_max, `NSGA-II point in the box (${p.ks}, ${p.cs})`);
    assert.ok(!ns.study.front.some((q) => q !== p && q.bacc <= p.bacc && q.dtl <= p.dtl && (q.bacc < p.bacc || q.dtl < p.dtl)), 'non-dominated');
  }
  // Against the same reference point (STM's) NSGA-II covers nearly all of STM's area.
  const ratio = hypervolume(ns.study.front, fr.study.reference_point) / hvStm;
  assert.ok(ratio > 0.98 && ratio < 1.005, `NSGA-II hypervolume / STM's on STM's reference point: ${ratio}`);
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

test('changing the SWS limit changes the front; the maps follow the last edit; a bad entry keeps the front', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  const f0 = await page.evaluate(() => window.__ridelab.front.study.front.map((p) => [p.bacc, p.dtl]));
  // Edits back to back, each dispatched as soon as the last front is drawn.
  for (let i = 0; i < 16; i++) {
    await page.evaluate(async (value) => {
      const a = window.__ridelab;
      const n = a.frontDraws;
      const el = document.getElementById('sws-limit');
      el.value = String(value);
      el.dispatchEvent(new Event('change'));
      while (a.frontDraws === n) await new Promise((r) => setTimeout(r, 0));
    }, 7.5 + 0.25 * i);
  }
  await settle(page);
  const f1 = await page.evaluate(() => window.__ridelab.front.study.front.map((p) => [p.bacc, p.dtl]));
  assert.notDeepEqual(f1, f0, 'the front changed');
  const limit = await page.evaluate(() => window.__ridelab.state.swsLimit);
  assert.ok(Math.abs(limit - 0.01125) < 1e-12, 'last limit applied');
  const maxSws = await page.evaluate(() => Math.max(...window.__ridelab.front.study.front.map((p) => p.sws)));
  assert.ok(maxSws > 0.007, `a larger limit lets the front reach SWS ${maxSws * 1000} mm > 7 mm`);
  assert.ok(maxSws <= limit * (1 + 1e-9), 'and keeps it within the limit');
  // The maps caught up with the last limit once the edits stopped.
  const caught = await page.evaluate(() => {
    const a = window.__ridelab;
    // The maps' key is the core's scenario tag (js/store.js `tags`) of the state shown.
    return a.maps.key === a.session(a.state).tags().scenario && a.views.every((v) => v.data.feasible === a.maps.feasible);
  });
  assert.ok(caught, 'the maps show the last state');
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
  // The front moved while the pointer was still down (how often depends on the machine:
  // printed above) ...
  assert.ok(drawsAtRelease > f0.draws, `${drawsAtRelease - f0.draws} fronts during the drag`);
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

/**
 * The quarter car's |H| from road displacement in closed form (`q`: {ms, mu, ks, cs, kt,
 * ct}) at angular frequency `w`: `[BAcc, DTL, SWS]` with BAcc = zs'', DTL = kt (zu - zr),
 * SWS = zs - zu (crate/src/model/quarter.rs).
 */
function quarterFrf(q, w) {
  const c = (re, im = 0) => ({ re, im });
  const add = (a, b) => c(a.re + b.re, a.im + b.im);
  const sub = (a, b) => c(a.re - b.re, a.im - b.im);
  const mul = (a, b) => c(a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re);
  const div = (a, b) => {
    const d = b.re * b.re + b.im * b.im;
    return c((a.re * b.re + a.im * b.im) / d, (a.im * b.re - a.re * b.im) / d);
  };
  const abs = (a) => Math.hypot(a.re, a.im);
  // (ms s² + cs s + ks) Zs = (cs s + ks) Zu; (mu s² + (cs + ct) s + ks + kt) Zu - (cs s + ks) Zs = (ct s + kt) Zr.
  const A = c(q.ks - q.ms * w * w, q.cs * w);
  const B = c(q.ks, q.cs * w);
  const C = c(q.ks + q.kt - q.mu * w * w, (q.cs + q.ct) * w);
  const D = c(q.kt, q.ct * w);
  const det = sub(mul(A, C), mul(B, B));
  const zu = div(mul(D, A), det);
  const zs = div(mul(D, B), det);
  return [w * w * abs(zs), q.kt * abs(sub(zu, c(1))), abs(sub(zs, zu))];
}

test('FRF and PSD: the LoFi equals the quarter car in closed form, the PSD integrates to the readout\'s RMS; both models drawn', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open('#ks=26000&cs=1700');
  const { sp, q, gv, lofi, state } = await page.evaluate(() => {
    const a = window.__ridelab;
    return { sp: a.spectra, q: a.desc.quarter, gv: a.desc.velocityPsd, lofi: a.lofi.design, state: a.state };
  });
  assert.ok(sp && sp.f.length > 100, 'spectra computed');
  assert.ok(Math.abs(sp.f[0] - 0.1) < 1e-12 && Math.abs(sp.f[sp.f.length - 1] - 100) < 1e-9, '0.1..100 Hz');
  const design = { ...q, ks: state.ks, cs: state.cs };
  // |H| of the LoFi at every frequency, and its PSD |H|² Gv / w² (a white road velocity).
  let worst = 0;
  for (let i = 0; i < sp.f.length; i++) {
    const w = 2 * Math.PI * sp.f[i];
    const h = quarterFrf(design, w);
    for (let k = 0; k < 3; k++) {
      worst = Math.max(worst, Math.abs(sp.lofi.frf[k][i] / h[k] - 1), Math.abs(sp.lofi.psd[k][i] / ((h[k] * h[k] * gv) / (w * w)) - 1));
    }
  }
  assert.ok(worst < 1e-9, `LoFi FRF and PSD vs the closed form: largest relative difference ${worst}`);
  // The PSD's area over 0.1..100 Hz (trapezoids in log f on the page's frequencies) plus
  // the closed form's tails below and above equals the readout's RMS squared.
  const psdAt = (f, k) => {
    const w = 2 * Math.PI * f;
    const h = quarterFrf(design, w)[k];
    return (h * h * gv) / (w * w);
  };
  const logTrap = (fs, ys) => {
    let s = 0;
    for (let i = 1; i < fs.length; i++) s += 0.5 * (ys[i] * fs[i] + ys[i - 1] * fs[i - 1]) * Math.log(fs[i] / fs[i - 1]);
    return s;
  };
  const tail = (lo, hi, k) => {
    const n = 4000;
    const fs = Array.from({ length: n + 1 }, (_, i) => lo * (hi / lo) ** (i / n));
    return logTrap(fs, fs.map((f) => psdAt(f, k)));
  };
  for (const [k, key] of [[0, 'bacc'], [1, 'dtl'], [2, 'sws']]) {
    const area = logTrap(sp.f, sp.lofi.psd[k]) + tail(1e-5, 0.1, k) + tail(100, 1e6, k);
    const rms2 = lofi[key] ** 2;
    assert.ok(Math.abs(area / rms2 - 1) < 2e-3, `${key}: PSD area ${area} vs RMS² ${rms2} (${area / rms2 - 1})`);
  }
  // The panel draws when it is shown (and catches up when opened).
  await page.click('#tab-spectra');
  await page.waitForTimeout(200);
  for (const id of ['sp-frf-bacc', 'sp-frf-dtl', 'sp-frf-sws', 'sp-psd-bacc', 'sp-psd-dtl', 'sp-psd-sws']) {
    const blue = await countColour(page, id, LOFI);
    const red = await countColour(page, id, HIFI);
    assert.ok(blue > 100, `${id}: LoFi curve (${blue} px)`);
    assert.ok(red > 50, `${id}: HiFi curve (${red} px)`);
  }
  const s0 = JSON.stringify(sp.lofi.frf[0].slice(0, 5));
  await page.focus('#cs-range');
  for (let i = 0; i < 10; i++) await page.keyboard.press('ArrowRight');
  await settle(page);
  const s1 = await page.evaluate(() => JSON.stringify(window.__ridelab.spectra.lofi.frf[0].slice(0, 5)));
  assert.notEqual(s1, s0, 'spectra follow the design');
  await page.locator('#panel-spectra').screenshot({ path: path.join(OUT, 'spectra.png') });
  assertClean(log);
  await context.close();
});

/** `ridelab simulate` of the default car and road at design (ks, cs): the page's run settings. */
function simulateCli(model, ks, cs, seed, extra = []) {
  const car = path.join(ROOT, 'assets/cars/sedan.json');
  // With --bump and --rebound the CLI takes Cs from them (their mean): `cs` null leaves it out.
  const design = ['--ks', String(ks), ...(cs === null ? [] : ['--cs', String(cs)])];
  const args = ['simulate', '--model', model, '--car', car, '--class', 'B', '--speed', '20', ...design,
    '--duration', '10', '--dt', '0.001', '--seed', String(seed), '--decimate', '10', ...extra, '--json'];
  const v = JSON.parse(execFileSync(cli(), args, { encoding: 'utf8', maxBuffer: 64 << 20 }));
  // The CLI names its series (`series.bacc`, `rms.bacc`); the page's record keeps arrays.
  const crit = ['bacc', 'dtl', 'sws'];
  return { t: v.series.t, outputs: crit.map((k) => v.series[k]), rms: crit.map((k) => v.rms[k]) };
}

/** Largest difference of two records' outputs relative to each output's RMS, and of their RMS values. */
function recordDiff(a, b) {
  let worst = 0;
  for (let k = 0; k < 3; k++) {
    worst = Math.max(worst, Math.abs(a.rms[k] / b.rms[k] - 1));
    for (let i = 0; i < a.t.length; i++) worst = Math.max(worst, Math.abs(a.outputs[k][i] - b.outputs[k][i]) / b.rms[k]);
  }
  return worst;
}

test('time panel: both models equal `ridelab simulate` for the same seed; plots, cursor and slow motion', { timeout: TIMEOUT }, async (t) => {
  const { page, context, log } = await open('#ks=24000&cs=1500');
  await page.click('#tab-time');
  // Bad input: a message next to the field, nothing run.
  await page.fill('#tp-bump', '2');
  await page.click('#tp-run');
  assert.match(await page.locator('#msg-tpRebound').textContent(), /both/);
  await page.fill('#tp-rebound', 'abc');
  await page.click('#tp-run');
  assert.match(await page.locator('#msg-tpRebound').textContent(), /not a number/);
  await page.fill('#tp-bump', '');
  await page.fill('#tp-rebound', '');
  await page.fill('#tp-seed', '7');
  const t0 = Date.now();
  await page.click('#tp-run');
  await page.waitForFunction(() => window.__ridelab.time, null, { timeout: 60_000 });
  t.diagnostic(`time response (10 s, 1 ms, both models) in ${Date.now() - t0} ms`);
  await settle(page);
  const r = await page.evaluate(() => window.__ridelab.time);
  assert.equal(r.hifi.t.length, 1000, '10 s at 1 ms, every 10th sample');
  assert.equal(r.hifi.positions.length, 7, 'full-car coordinates');
  // The same seed, duration, step and decimation in the CLI: the same records.
  for (const [model, rec] of [['quarter', r.lofi], ['full', r.hifi]]) {
    const native = simulateCli(model, 24000, 1500, 7);
    const d = recordDiff(rec, native);
    t.diagnostic(`page vs ridelab simulate --model ${model}: largest difference ${d.toExponential(2)} of the RMS`);
    assert.ok(d < 1e-9, `${model}: page vs CLI ${d}`);
  }
  // Another seed is another road.
  const other = simulateCli('quarter', 24000, 1500, 8);
  assert.ok(recordDiff(r.lofi, other) > 1e-3, 'seed 8 differs from seed 7');
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
  const cursor = await countColour(page, 'tp-bacc-cursor', [17, 24, 39], 60);
  await page.click('#tp-play');
  const k1 = await page.evaluate(() => window.__ridelab.timePanel.k);
  assert.ok(k1 !== k0, `animation advanced (${k0} -> ${k1})`);
  assert.ok(!img1.equals(img2), 'the side view changes while playing');
  assert.ok(cursor > 20, `a time cursor on the traces while playing (${cursor} px)`);
  assert.equal(await page.locator('#tp-play').textContent(), 'Play', 'paused');
  // Slow motion: a tenth of real time advances about a tenth as far.
  await page.selectOption('#tp-rate', '0.1');
  const slow = await page.evaluate(async () => {
    const p = window.__ridelab.timePanel;
    const k = p.k;
    p.toggle();
    const t0 = performance.now();
    await new Promise((r) => setTimeout(r, 1000));
    p.toggle();
    const dt = p.res.hifi.t[1] - p.res.hifi.t[0];
    return { record: ((p.k - k + p.res.hifi.t.length) % p.res.hifi.t.length) * dt, wall: (performance.now() - t0) / 1000 };
  });
  assert.ok(slow.record > 0.03 && slow.record < 0.15, `slow motion x0.1: ${slow.record} s of record in ${slow.wall} s`);
  await page.locator('#panel-time').screenshot({ path: path.join(OUT, 'time.png') });
  // An asymmetric damper: a run with both rates, a different record from the linear one.
  await page.fill('#tp-bump', '1');
  await page.fill('#tp-rebound', '3');
  await page.click('#tp-run');
  await page.waitForFunction(() => /Done .*asymmetric damper 1 \/ 3 kNs\/m/.test(document.getElementById('tp-status').textContent), null, { timeout: 60_000 });
  const asym = await page.evaluate(() => window.__ridelab.time);
  assert.ok(Math.abs(asym.lofi.rms[2] / r.lofi.rms[2] - 1) > 1e-3, 'the asymmetric damper changes the SWS record');
  assert.equal(asym.damperRate, 2000, "the run's Cs is the mean of bump and rebound");
  // The same law in the CLI (Cs left out: the mean), both models: the same records.
  const law = ['--bump', '1000', '--rebound', '3000'];
  for (const [model, rec] of [['quarter', asym.lofi], ['full', asym.hifi]]) {
    const d = recordDiff(rec, simulateCli(model, 24000, null, 7, law));
    t.diagnostic(`asymmetric: page vs ridelab simulate --model ${model} --bump 1000 --rebound 3000: ${d.toExponential(2)} of the RMS`);
    assert.ok(d < 1e-9, `asymmetric ${model}: page vs CLI ${d}`);
  }
  // The force-velocity chart: the law's slopes, drawn, with the linear rate of the maps.
  const fv = await page.evaluate(() => window.__ridelab.damperChart.curve);
  const slope = (v) => {
    const p = fv.points;
    const i = p.findIndex((q) => q[0] >= v) || 1;
    return (p[i][1] - p[i - 1][1]) / (p[i][0] - p[i - 1][0]);
  };
  assert.equal(fv.linearRate, 2000);
  assert.ok(Math.abs(slope(0.5) - 3000) < 1e-9 && Math.abs(slope(-0.5) - 1000) < 1e-9, `F-v slopes ${slope(-0.5)} / ${slope(0.5)}`);
  assert.ok((await countColour(page, 'tp-fv', HIFI)) > 200, 'the F-v line is drawn');
  // A digressive damper: a knee at 0.2 m/s with softer slopes above, page and CLI alike.
  await page.fill('#tp-knee', '0.2');
  await page.fill('#tp-bump-high', '0.5');
  await page.click('#tp-run');
  assert.match(await page.locator('#msg-tpReboundHigh').textContent(), /knee needs/, 'a knee needs every field');
  await page.fill('#tp-rebound-high', '1.5');
  await page.click('#tp-run');
  await page.waitForFunction(() => /Done .*digressive damper 1 \/ 3 kNs\/m to 0\.2 m\/s/.test(document.getElementById('tp-status').textContent), null, { timeout: 60_000 });
  const dig = await page.evaluate(() => window.__ridelab.time);
  const knee = [...law, '--knee', '0.2', '--bump-high', '500', '--rebound-high', '1500'];
  for (const [model, rec] of [['quarter', dig.lofi], ['full', dig.hifi]]) {
    const d = recordDiff(rec, simulateCli(model, 24000, null, 7, knee));
    t.diagnostic(`digressive: page vs CLI --model ${model}: ${d.toExponential(2)} of the RMS`);
    assert.ok(d < 1e-9, `digressive ${model}: page vs CLI ${d}`);
  }
  assert.ok(recordDiff(dig.lofi, asym.lofi) > 1e-4, 'the knee changes the record');
  const fv2 = await page.evaluate(() => window.__ridelab.damperChart.curve.points);
  assert.equal(fv2.length, 5, 'the knees are corners of the F-v line');
  // A rate beyond the core's bound: the message beside the field, in kNs/m.
  await page.fill('#tp-rebound', '5000');
  await page.click('#tp-run');
  assert.match(await page.locator('#msg-tpRebound').textContent(), /at most 1000 kNs\/m \(got 5000 kNs\/m\)/);
  await page.locator('#panel-time').screenshot({ path: path.join(OUT, 'time-damper.png') });
  assertClean(log);
  await context.close();
});

test('exports: the maps and front CSV hold the data on screen; the plane PNG is slide size', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open('#model=surrogate&sws=8');
  await page.click('#tab-export');
  const grab = async (sel) => {
    const [dl] = await Promise.all([page.waitForEvent('download'), page.click(sel)]);
    const file = path.join(OUT, dl.suggestedFilename());
    await dl.saveAs(file);
    return file;
  };
  // The maps CSV of the model shown: each row is a cell centre with the values the map draws.
  const maps = fs.readFileSync(await grab('#maps-csv'), 'utf8').trim().split('\n');
  assert.equal(maps[0], 'ks_N_per_m,cs_Ns_per_m,bacc_m_per_s2,dtl_N,sws_m,feasible');
  assert.equal(maps.length, 1 + 160 * 120, 'one row per map cell');
  const shown = await page.evaluate(() => {
    const a = window.__ridelab;
    const v = a.views;
    return {
      box: a.desc.designBox,
      nx: v[0].data.nx,
      ny: v[0].data.ny,
      shown: v.map((x) => Array.from(x.data.shown)),
      feasible: Array.from(v[0].data.feasible),
      same: a.views[0].data.feasible === a.surMaps.feasible,
    };
  });
  assert.ok(shown.same, 'the maps on screen are the surrogate\'s');
  const factor = [1, 1, 1000];
  for (let r = 1; r < maps.length; r++) {
    const x = maps[r].split(',').map(Number);
    const k = r - 1;
    const i = k % shown.nx;
    const j = Math.floor(k / shown.nx);
    const ks = shown.box.ks_min + ((i + 0.5) * (shown.box.ks_max - shown.box.ks_min)) / shown.nx;
    const cs = shown.box.cs_min + ((j + 0.5) * (shown.box.cs_max - shown.box.cs_min)) / shown.ny;
    assert.ok(x[0] === ks && x[1] === cs, `row ${r}: cell (${i}, ${j}) at its centre (${x[0]}, ${x[1]})`);
    for (let c = 0; c < 3; c++) {
      const want = shown.shown[c][k];
      assert.ok(Math.abs(x[2 + c] * factor[c] - want) <= 1e-12 * Math.abs(want), `row ${r} column ${c}: ${x[2 + c]} vs ${want}`);
    }
    assert.equal(x[5], shown.feasible[k], `row ${r}: feasible`);
  }
  // The front CSV: the STM front on the plane, point for point, the pick marked.
  const front = fs.readFileSync(await grab('#front-csv'), 'utf8').trim().split('\n');
  assert.equal(front[0], 'method,ks_N_per_m,cs_Ns_per_m,bacc_m_per_s2,dtl_N,sws_m,pick');
  const fr = await page.evaluate(() => window.__ridelab.front.study);
  assert.equal(front.length - 1, fr.front.length, 'every front point');
  fr.front.forEach((p, i) => {
    const x = front[i + 1].split(',');
    assert.equal(x[0], 'stm');
    assert.deepEqual(x.slice(1, 6).map(Number), [p.ks, p.cs, p.bacc, p.dtl, p.sws], `front point ${i}`);
    assert.equal(x[6], i === fr.pick.index ? '1' : '0');
  });
  const png = fs.readFileSync(await grab('#op-png'));
  assert.equal(png.subarray(1, 4).toString(), 'PNG');
  assert.ok(png.readUInt32BE(16) >= 1600, `objective plane PNG ${png.readUInt32BE(16)} px wide`);
  assertClean(log);
  await context.close();
});

test('session round trip: the whole state, view and readout; bad files are refused with a message', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open('#class=A&speed=25&ks=27000&cs=1900&sws=8.5&bb=0.9,1.6&model=surrogate&scale=rel&axes=ratio&pal=cividis&samples=0');
  await page.click('#tab-export');
  const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#session-save')]);
  const sessionFile = path.join(OUT, dl.suggestedFilename());
  await dl.saveAs(sessionFile);
  const session = JSON.parse(fs.readFileSync(sessionFile, 'utf8'));
  const snap = (p) => p.evaluate(() => {
    const r = window.__ridelab;
    const { nsga, ...view } = r.view;
    const cells = {};
    for (const td of document.querySelectorAll('#criteria td[data-model]')) cells[`${td.closest('tr').dataset.crit}.${td.dataset.model}`] = td.dataset.value;
    return { state: r.state, view, cells, hash: location.hash };
  });
  const a = await snap(page);
  assert.deepEqual(session.state, a.state, 'the file holds the state');
  const b = await open();
  await b.page.click('#tab-export');
  await b.page.setInputFiles('#session-load', sessionFile);
  await b.page.waitForFunction(() => window.__ridelab.state.class === 'A', null, { timeout: 30_000 });
  await settle(b.page);
  assert.deepEqual(await snap(b.page), a, 'the loaded session: same state, view, readout and link');
  // Bad files: a message next to the button, the state kept.
  const cases = [
    ['not-json.json', 'this is not JSON', /not a RideLab session file \(not JSON\)/],
    ['wrong-tag.json', JSON.stringify({ ...session, ridelab: 'car' }), /not a RideLab session file/],
    ['unknown-key.json', JSON.stringify({ ...session, colour: 'red' }), /unknown session key 'colour'/],
    ['unknown-view.json', JSON.stringify({ ...session, view: { ...session.view, zoom: 2 } }), /unknown view key 'zoom'/],
    ['bad-view.json', JSON.stringify({ ...session, view: { ...session.view, model: 'best' } }), /view: model cannot be "best"/],
    ['unknown-state.json', JSON.stringify({ ...session, state: { ...session.state, colour: 'red' } }), /'colour' is not a known field/],
    ['bad-speed.json', JSON.stringify({ ...session, state: { ...session.state, speed: -1 } }), /speed: must be a finite number > 0/],
  ];
  for (const [name, text, re] of cases) {
    const f = path.join(OUT, name);
    fs.writeFileSync(f, text);
    await b.page.setInputFiles('#session-load', f);
    await b.page.waitForFunction((n) => document.getElementById('msg-session').textContent.startsWith(n), name);
    assert.match(await b.page.textContent('#msg-session'), re, name);
    // A bad key keeps its default (or is left out); the rest of the file applies (#27).
    if (name === 'bad-speed.json') assert.deepEqual((await snap(b.page)).state, { ...a.state, speed: 20 }, `${name}: the rest applies`);
    else if (name === 'bad-view.json') assert.deepEqual((await snap(b.page)).view, { ...a.view, model: 'lofi' }, `${name}: the rest applies`);
    else assert.deepEqual(await snap(b.page), a, `${name}: the state stays`);
  }
  assertClean(b.log);
  await b.context.close();
  assertClean(log);
  await context.close();
});

test('car file import: non-JSON, empty and uncomputable files are refused beside the field; the same file loads again', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  const good = await page.evaluate(() => window.__ridelab.state);
  const sedan = JSON.parse(fs.readFileSync(path.join(ROOT, 'assets/cars/sedan.json'), 'utf8'));
  const load = async (name, text) => {
    await page.evaluate(() => (document.getElementById('msg-carFile').textContent = ''));
    await page.setInputFiles('#car-file', { name, mimeType: 'application/json', buffer: Buffer.from(text) });
    await page.waitForFunction(() => document.getElementById('msg-carFile').textContent !== '' || window.__ridelab.state.car === 'custom');
    await settle(page);
    return page.textContent('#msg-carFile');
  };
  assert.match(await load('notes.json', 'my car is blue'), /^notes\.json: not a valid car file: /);
  assert.match(await load('empty.json', ''), /^empty\.json: the file is empty/);
  // Valid car-file values that no model can compute: a wheel with no mass to speak of.
  const stiff = { ...sedan, name: 'Featherweight', front: { ...sedan.front, unsprung_mass: 1e-300 } };
  const msg = await load('feather.json', JSON.stringify(stiff));
  assert.match(msg, /^feather\.json: /, msg);
  assert.deepEqual(await page.evaluate(() => window.__ridelab.state), good, 'the state stays after each refusal');
  assert.equal(await page.inputValue('#car-file'), '', 'the input is cleared after an error');
  // The same bad file again: the message comes back (the second choice is a change).
  assert.match(await load('notes.json', 'my car is blue'), /^notes\.json: not a valid car file/);
  assertClean(log);
  await context.close();
});

test('NSGA-II: an answer for an earlier scenario is dropped and the new scenario\'s is computed', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  // The heavy worker busy first (a HiFi map), so NSGA-II for class B answers after the
  // page has moved to class A; then the page asks again for class A.
  await page.evaluate(() => {
    const a = window.__ridelab;
    a.heavyEngine.call('maps', { ...a.state, speed: 21 }, 'hifi', 41, 41);
    document.getElementById('op-nsga').click();
    const cls = document.getElementById('class');
    cls.value = 'A';
    cls.dispatchEvent(new Event('change'));
  });
  await page.waitForFunction(() => window.__ridelab.nsga && window.__ridelab.state.class === 'A', null, { timeout: 60_000 });
  await settle(page);
  const r = await page.evaluate(() => {
    const a = window.__ridelab;
    const direct = a.session(a.state).front('nsga2', 'surrogate');
    return { counters: a.counters, shown: a.nsga.study.front, direct: direct.study.front, key: a.nsga.key, now: a.session(a.state).tags().scenario };
  });
  assert.ok(r.counters.nsgaDropped >= 1, `the class B answer was dropped (${r.counters.nsgaDropped})`);
  assert.ok(r.counters.nsgaRuns >= 2, `and NSGA-II ran again (${r.counters.nsgaRuns} runs)`);
  assert.equal(r.key, r.now, 'the front shown is for the scenario shown');
  for (const e of r.counters.nsgaLog) assert.equal(e.key, e.shown, 'no answer was ever shown for another scenario');
  assert.deepEqual(r.shown, r.direct, 'the NSGA-II front of class A');
  assertClean(log);
  await context.close();
});

test('HiDPI and projector mode: the charts are sized in device pixels and redraw', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open('', { dpr: 2 });
  await page.click('#tab-spectra');
  await page.waitForTimeout(200);
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
  await page.check('#projector');
  await page.waitForTimeout(400);
  for (const s of await sizes()) assert.equal(s.w, Math.round(s.css * 2), `${s.id} after projector mode`);
  assert.ok((await countColour(page, 'sp-frf-bacc', LOFI)) > 100, 'FRF redrawn in projector mode');
  await page.locator('.objective').screenshot({ path: path.join(OUT, 'objective-hidpi-large.png') });
  assertClean(log);
  await context.close();
});

test('front, spectra, timeResponse, damperCurve: bad arguments name the field', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  const r = await page.evaluate(async () => {
    const a = window.__ridelab;
    const s = a.state;
    // Spectra and time responses are the on-demand module's (issue #29).
    const od = await a.onDemandSession(s);
    const err = (f) => {
      try {
        f();
        return null;
      } catch (e) {
        return { message: e.message, field: e.field };
      }
    };
    return {
      method: err(() => a.session(s).front('simplex')),
      nfreq: err(() => od.spectra(1)),
      dt: err(() => od.timeResponse({ dt: 0.5 })),
      asym: err(() => od.timeResponse({ damper: { bump: -1, rebound: 2 } })),
      unknown: err(() => a.session({ ...s, bogus: 1 }).front('stm')),
      classC: err(() => a.session({ ...s, class: 'C' }).front('stm')),
      colour: err(() => a.api.colourTable('rainbow')),
      lawBump: err(() => a.api.damperCurve({ bump: 0, rebound: 2000, knee: null }, 1)),
      lawKnee: err(() => a.api.damperCurve({ bump: 1000, rebound: 2000, knee: { velocity: 0.1, bump: -1, rebound: 0 } }, 1)),
      lawKey: err(() => a.api.damperCurve({ bump: 1000, rebound: 2000, soft: 1 }, 1)),
      vMax: err(() => a.api.damperCurve({ bump: 1000, rebound: 2000, knee: null }, NaN)),
    };
  });
  assert.equal(r.method.field, 'method');
  assert.equal(r.nfreq.field, 'nfreq');
  assert.equal(r.dt.field, 'dt');
  assert.equal(r.asym.field, 'damper');
  assert.equal(r.unknown.field, 'state');
  assert.equal(r.classC.field, 'swsLimit', `class C: ${r.classC.message}`);
  assert.equal(r.colour.field, 'colourMap');
  assert.equal(r.lawBump.field, 'bump', r.lawBump.message);
  assert.equal(r.lawKnee.field, 'knee.bump', r.lawKnee.message);
  assert.equal(r.lawKey.field, 'damper', r.lawKey.message);
  assert.equal(r.vMax.field, 'vMax', r.vMax.message);
  assertClean(log);
  await context.close();
});

test('Download report: the page builds the study report of the view, byte for byte the one ridelab report writes', { timeout: TIMEOUT }, async () => {
  // The SUV on a class C road: no design meets the 7 mm limit, so the report says why
  // instead of computing fronts (a few seconds in the worker).
  const { page, context, log } = await open('#car=suv&class=C');
  await page.click('#tab-export');
  const [dl] = await Promise.all([page.waitForEvent('download', { timeout: 60_000 }), page.click('#report-html')]);
  assert.match(dl.suggestedFilename(), /^ridelab-report-.*\.html$/);
  const file = path.join(OUT, dl.suggestedFilename());
  await dl.saveAs(file);
  const html = fs.readFileSync(file, 'utf8');
  assert.match(await page.locator('#export-status').textContent(), /Study report: RideLab study report: Mid-size SUV, class C at 20 m\/s/);
  const dir = path.join(OUT, 'report-cli');
  execFileSync(cli(), ['report', '--car', 'suv', '--class', 'C', '--approach', 'rba-mul-rbf-mq', '--plan', 'ae:10', '--out', dir], { encoding: 'utf8', maxBuffer: 64 << 20 });
  const want = fs.readFileSync(path.join(dir, 'report.html'), 'utf8');
  assertSameLines(html, want, 'page and CLI reports');
  assert.match(html, /No design in the box meets the design objectives/);
  assertClean(log);
  await context.close();
});
