// End-to-end tests of the classroom (issue #30): with a lesson open, at 1920 x 1080,
// 1600 x 1000 and 1280 x 720, plain and in projector mode, the sliders, the three maps,
// the objective plane and the readout are whole, on screen and apart (map tick labels
// 12 px or more in projector mode), the lesson editor fits its panel; the objective
// plane's zoom (wheel, keys, reset) travels in the link; on a phone a tab brings its
// panel into view, and the keyboard goes into the drawer and back to the tab with
// Escape; the lesson reveal marks the class's prediction right or wrong; the chart
// export shows its progress and names its files after the car.
//
//   trunk build --release --offline && node --test tests/e2e/classroom.test.mjs

import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { openPage, settled } from './browser.mjs';
import { useSuite, assertClean, OUT, ROOT } from './harness.mjs';

const TIMEOUT = 300_000;
const suite = useSuite();

async function open(hash = '', opts = {}) {
  const r = await openPage(suite.browser, suite.srv.url + hash, { width: 1280, height: 720, ...opts });
  await settled(r.page, 100);
  return r;
}

/** Waits until the page has settled and the lesson panel shows every number of its step. */
async function lessonReady(page) {
  await page.waitForFunction(() => window.__ridelab.isSettled() && document.getElementById('lesson').dataset.ready === 'true', null, { timeout: 60_000 });
}

/** The workbench's parts whose boxes must be whole, on screen and apart. */
const PARTS = { sliders: '.sliders', bacc: '#map-bacc', dtl: '#map-dtl', sws: '#map-sws', plane: '#op-base', readout: '.readout' };

/**
 * The boxes of PARTS and the lesson panel (CSS px, `[x, y, w, h]`), the map tick labels'
 * size in CSS px (the core's 12 px at the map's type zoom), the readout's table and the
 * lesson editor's overflow, scrollY.
 */
function measure(page) {
  return page.evaluate((parts) => {
    const box = (s) => {
      const r = document.querySelector(s).getBoundingClientRect();
      return [r.x, r.y, r.width, r.height].map((v) => Math.round(v * 10) / 10);
    };
    const boxes = Object.fromEntries(Object.entries(parts).map(([k, s]) => [k, box(s)]));
    const lesson = document.getElementById('lesson');
    const wrap = document.querySelector('.readout .table-wrap');
    const table = document.getElementById('criteria');
    const ro = document.querySelector('.readout').getBoundingClientRect();
    const sws = document.querySelector('#criteria tr[data-crit="sws"]').getBoundingClientRect();
    return {
      boxes,
      lesson: lesson.hidden ? null : box('#lesson'),
      tickPx: window.__ridelab.views.map((v) => v.layout().fs),
      planeTickPx: window.__ridelab.objPlane.base.layout().fs,
      readoutClipped: table.getBoundingClientRect().right > wrap.getBoundingClientRect().right + 0.5 || wrap.scrollWidth > wrap.clientWidth + 0.5,
      swsRowInside: sws.bottom <= ro.bottom + 0.5 && sws.bottom <= innerHeight,
      scrollY: window.scrollY,
      viewport: [innerWidth, innerHeight],
    };
  }, PARTS);
}

/** Do boxes `a` and `b` (`[x, y, w, h]`) overlap by more than half a pixel? */
const overlap = (a, b) => Math.min(a[0] + a[2], b[0] + b[2]) - Math.max(a[0], b[0]) > 0.5 && Math.min(a[1] + a[3], b[1] + b[3]) - Math.max(a[1], b[1]) > 0.5;

/** Asserts the layout rules of issue #30 on measurement `m` (`where` names the case). */
function assertWhole(m, where, projector) {
  const [W, H] = m.viewport;
  const all = { ...m.boxes, ...(m.lesson ? { lesson: m.lesson } : {}) };
  for (const [k, [x, y, w, h]] of Object.entries(all)) {
    assert.ok(w > 0 && h > 0, `${where}: ${k} has a size (${w} x ${h})`);
    assert.ok(x >= -0.5 && y >= -0.5 && x + w <= W + 0.5 && y + h <= H + 0.5, `${where}: ${k} [${x}, ${y}, ${w}, ${h}] inside ${W} x ${H}`);
  }
  const names = Object.keys(all);
  for (let i = 0; i < names.length; i++) {
    for (let j = i + 1; j < names.length; j++) {
      assert.ok(!overlap(all[names[i]], all[names[j]]), `${where}: ${names[i]} ${all[names[i]]} and ${names[j]} ${all[names[j]]} apart`);
    }
  }
  for (const k of ['bacc', 'dtl', 'sws']) assert.ok(m.boxes[k][2] >= 180, `${where}: map ${k} ${m.boxes[k][2]} px wide`);
  assert.ok(m.boxes.plane[2] >= 300 && m.boxes.plane[3] >= 200, `${where}: the plane ${m.boxes.plane[2]} x ${m.boxes.plane[3]}`);
  assert.equal(m.readoutClipped, false, `${where}: the readout's table is not cut`);
  assert.equal(m.swsRowInside, true, `${where}: the readout's SWS row is on screen`);
  assert.equal(m.scrollY, 0, `${where}: no scroll`);
  if (projector) {
    for (const fs of m.tickPx) assert.ok(fs >= 12, `${where}: map tick labels ${fs} px`);
    assert.ok(m.planeTickPx >= 12, `${where}: plane tick labels ${m.planeTickPx} px`);
  }
}

const SIZES = [[1920, 1080], [1600, 1000], [1280, 720]];

test('layouts with a lesson open: sliders, maps, plane and readout whole and apart at three sizes, plain and projector', { timeout: TIMEOUT }, async () => {
  const seen = {};
  for (const [width, height] of SIZES) {
    for (const projector of [false, true]) {
      const { page, context, log } = await open('#lesson=choosing', { width, height });
      await lessonReady(page);
      if (projector) await page.click('#projector');
      await page.waitForTimeout(400);
      await settled(page, 200);
      const where = `${width} x ${height}${projector ? ' projector' : ''}, lesson`;
      const m = await measure(page);
      seen[where] = m;
      assertWhole(m, where, projector);
      // The lesson's type is large (as lessons.test.mjs asks).
      const px = await page.evaluate(() => parseFloat(getComputedStyle(document.getElementById('lesson-question')).fontSize));
      assert.ok(px >= (projector ? 22 : 18), `${where}: lesson type ${px} px`);
      // The editor fits its panel.
      await page.click('#lesson-edit-toggle');
      await page.waitForSelector('#lesson-edit', { state: 'visible' });
      const over = await page.evaluate(() => {
        const p = document.getElementById('lesson');
        const worst = [...p.querySelectorAll('#lesson-edit *')].map((e) => e.getBoundingClientRect().right).reduce((a, b) => Math.max(a, b), 0);
        return { scroll: p.scrollWidth - p.clientWidth, right: worst - p.getBoundingClientRect().right };
      });
      assert.ok(over.scroll <= 0 && over.right <= 0.5, `${where}: the lesson editor fits its panel (${JSON.stringify(over)})`);
      assertClean(log);
      await context.close();
    }
  }
  // Without a lesson, projector mode keeps the same rules (and the plane's key whole).
  for (const [width, height] of SIZES) {
    const { page, context, log } = await open('#proj=1', { width, height });
    await page.waitForTimeout(300);
    const where = `${width} x ${height} projector`;
    const m = await measure(page);
    seen[where] = m;
    assertWhole(m, where, true);
    const key = await page.evaluate(() => {
      const k = document.getElementById('op-key');
      return k.scrollWidth <= k.clientWidth + 0.5 && k.getBoundingClientRect().bottom <= document.getElementById('op-base').getBoundingClientRect().top + 0.5;
    });
    assert.ok(key, `${where}: the plane's key is whole`);
    assertClean(log);
    await context.close();
  }
  fs.writeFileSync(path.join(OUT, 'classroom-layout.json'), JSON.stringify(seen, null, 1));
});

/** The plane's axes as drawn: `[x lo, x hi, y lo, y hi]`. */
const planeAxes = (page) => page.evaluate(() => {
  const p = window.__ridelab.objPlane.base.placed;
  return [p.x.lo, p.x.hi, p.y.lo, p.y.hi];
});

const near = (a, b, rel = 1e-9) => a.every((v, i) => Math.abs(v - b[i]) <= rel * Math.max(1, Math.abs(v), Math.abs(b[i])));

test('the objective plane: axes fitted to the fronts, wheel and keys zoom, the link carries pz=, a reload restores it, Fit goes back', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open('', { width: 1600, height: 1000 });
  const fitted = await planeAxes(page);
  // The fitted axes hold every point of the front and the pick.
  const inside = await page.evaluate(([x0, x1, y0, y1]) => {
    const fr = window.__ridelab.front;
    return [...fr.study.front, fr.study.pick.criteria].every((p) => p.bacc >= x0 && p.bacc <= x1 && p.dtl >= y0 && p.dtl <= y1);
  }, fitted);
  assert.ok(inside, `the front inside the fitted axes ${fitted}`);
  assert.equal(await page.isDisabled('#op-reset'), true, 'Fit is off on the fitted axes');
  // The wheel over the plane zooms in about the pointer.
  const box = await page.locator('#op-overlay').boundingBox();
  await page.mouse.move(box.x + box.width * 0.5, box.y + box.height * 0.5);
  await page.mouse.wheel(0, -400);
  await page.waitForFunction(() => /[#&]pz=/.test(location.hash), null, { timeout: 10_000 });
  const zoomed = await planeAxes(page);
  assert.ok(zoomed[1] - zoomed[0] < 0.8 * (fitted[1] - fitted[0]), `x range ${zoomed.slice(0, 2)} narrower than ${fitted.slice(0, 2)}`);
  assert.ok(zoomed[3] - zoomed[2] < 0.8 * (fitted[3] - fitted[2]), `y range ${zoomed.slice(2)} narrower than ${fitted.slice(2)}`);
  assert.equal(await page.isDisabled('#op-reset'), false);
  // Keys on the focused plane: + zooms in, an arrow pans right, - zooms out.
  await page.focus('#op-overlay');
  await page.keyboard.press('+');
  const plus = await planeAxes(page);
  assert.ok(plus[1] - plus[0] < zoomed[1] - zoomed[0], '+ zooms in');
  await page.keyboard.press('ArrowRight');
  const right = await planeAxes(page);
  assert.ok(right[0] > plus[0] && Math.abs((right[1] - right[0]) - (plus[1] - plus[0])) < 1e-9 * (plus[1] - plus[0]) + 1e-12, 'an arrow pans');
  await page.keyboard.press('-');
  const shown = await planeAxes(page);
  await page.waitForTimeout(600);
  const hash = await page.evaluate(() => location.hash);
  assert.match(decodeURIComponent(hash), /[#&]pz=[-\d.]+,[-\d.]+,[-\d.]+,[-\d.]+/);
  // The link in a fresh page: the same axes.
  const again = await open(hash, { width: 1600, height: 1000 });
  const restored = await planeAxes(again.page);
  assert.ok(near(restored, shown, 1e-3), `the link restores the axes: ${restored} vs ${shown}`);
  // Fit: back to the fitted axes, and pz= leaves the link.
  await again.page.click('#op-reset');
  assert.ok(near(await planeAxes(again.page), fitted), 'Fit restores the fitted axes');
  await again.page.waitForFunction(() => !/[#&]pz=/.test(location.hash), null, { timeout: 10_000 });
  assertClean(again.log);
  await again.context.close();
  assertClean(log);
  await context.close();
});

test('tabs: on a phone a tap brings the panel into view; from the keyboard the focus goes into it and Escape, even in a field, gives it back to the tab', { timeout: TIMEOUT }, async () => {
  const phone = await open('', { width: 390, height: 844, touch: true });
  const { page } = phone;
  await page.tap('#tab-objectives');
  await page.waitForTimeout(300);
  const seen = await page.evaluate(() => {
    const r = document.getElementById('panel-objectives').getBoundingClientRect();
    return { top: r.top, inView: r.top >= -1 && r.top < innerHeight - 100, scrollY: window.scrollY };
  });
  assert.ok(seen.inView && seen.scrollY > 500, `the panel is in view after the tap (${JSON.stringify(seen)})`);
  await page.screenshot({ path: path.join(OUT, 'classroom-phone-tab.png') });
  assertClean(phone.log);
  await phone.context.close();

  for (const [width, height] of [[1280, 720], [390, 844]]) {
    const { page: p, context, log } = await open('', { width, height });
    await p.focus('#tab-objectives');
    await p.keyboard.press('Enter');
    const first = await p.evaluate(() => ({ id: document.activeElement.id, inDrawer: document.getElementById('drawer').contains(document.activeElement) }));
    assert.ok(first.inDrawer, `${width}: the focus is in the drawer (${first.id})`);
    assert.equal(first.id, 'ks-min', `${width}: on the panel's first control`);
    // Typing in the field, then Escape: the drawer closes, the focus goes back to the tab.
    await p.keyboard.type('12');
    await p.keyboard.press('Escape');
    assert.equal(await p.isHidden('#drawer'), true, `${width}: Escape in a field closes the drawer`);
    assert.equal(await p.evaluate(() => document.activeElement.id), 'tab-objectives', `${width}: the focus is back on the tab`);
    assert.equal((await p.evaluate(() => window.__ridelab.state)).ksMin, 10000, `${width}: the half-typed value was not applied`);
    // A select in the drawer too.
    await p.keyboard.press('Enter');
    await p.focus('#nw-bacc');
    await p.keyboard.press('Escape');
    assert.equal(await p.isHidden('#drawer'), true);
    assert.equal(await p.evaluate(() => document.activeElement.id), 'tab-objectives');
    // A digit shortcut opens a tab from the keyboard too: the focus goes into it.
    await p.focus('#ks-range');
    await p.keyboard.press('1');
    assert.equal(await p.evaluate(() => document.getElementById('drawer').contains(document.activeElement)), true, `${width}: 1 opens Car & road with the focus in it`);
    assertClean(log);
    await context.close();
  }
});

/** A lesson file of two steps, each with three options and the second the right one. */
function answerLesson(extra = {}) {
  const step = { view: 'ks=19960&cs=1290', question: 'Which is comfort?', options: ['DTL', 'BAcc', 'SWS'], answer: 2, reveal: 'BAcc is comfort: {hifi.bacc} on the full car.', ...extra };
  return JSON.stringify({ ridelab: 'lesson', version: 1, title: 'Answers', steps: [step, { ...step }] });
}

test('the lesson reveal: every option stays, the right one marked, the class\'s prediction marked right or wrong', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  await page.click('#lessons-open');
  // An answer that is no option is refused, naming the step and field.
  await page.setInputFiles('#lesson-file', { name: 'bad.json', mimeType: 'application/json', buffer: Buffer.from(answerLesson({ answer: 4 })) });
  await page.waitForFunction(() => document.getElementById('lesson-msg').textContent.startsWith('bad.json: '));
  assert.equal(await page.textContent('#lesson-msg'), 'bad.json: steps[0].answer: must be the number of one of its options (1 to 3)');
  await page.setInputFiles('#lesson-file', { name: 'answers.json', mimeType: 'application/json', buffer: Buffer.from(answerLesson()) });
  await lessonReady(page);
  const options = () => page.$$eval('#lesson-options button', (bs) => bs.map((b) => ({ visible: b.offsetParent !== null, verdict: b.dataset.verdict || '', text: b.textContent })));
  // Step 1: the class picks 1, which is wrong.
  await page.click('#lesson-options button >> nth=0');
  assert.deepEqual((await options()).map((o) => o.verdict), ['', '', ''], 'nothing marked before the reveal');
  await page.click('#lesson-reveal');
  await lessonReady(page);
  let o = await options();
  assert.deepEqual(o.map((x) => x.visible), [true, true, true], 'every option stays');
  assert.deepEqual(o.map((x) => x.verdict), ['wrong', 'answer', '']);
  assert.match(o[0].text, /✗/);
  assert.match(o[1].text, /right answer/);
  assert.match(await page.textContent('#lesson-hint'), /The class chose 1; the right answer is 2\./);
  await page.screenshot({ path: path.join(OUT, 'classroom-reveal-wrong.png') });
  // Step 2: the class picks 2, which is right.
  await page.click('#lesson-next');
  await lessonReady(page);
  await page.focus('#lesson');
  await page.keyboard.press('2');
  await page.keyboard.press('Space');
  await lessonReady(page);
  o = await options();
  assert.deepEqual(o.map((x) => x.verdict), ['', 'right', '']);
  assert.match(await page.textContent('#lesson-hint'), /The class was right\./);
  assertClean(log);
  await context.close();
});

test('exports: "PNG of every chart" shows its progress, files and the PNG title name the custom car; the line under the plane wraps', { timeout: TIMEOUT }, async () => {
  const car = JSON.parse(fs.readFileSync(path.join(ROOT, 'assets/cars/sedan.json'), 'utf8'));
  car.name = 'Teaching van';
  const hash = `#car=custom&carjson=${encodeURIComponent(JSON.stringify(car))}`;
  const { page, context, log } = await open(hash, { width: 1600, height: 1000, downloads: true });
  assert.equal((await page.evaluate(() => window.__ridelab.state)).car, 'custom');
  const title = await page.evaluate(() => import('./js/svgexport.js').then((m) => m.objectiveChart(window.__ridelab.exportData()).title));
  assert.match(title, /Teaching van, class B at 20 m\/s/);
  await page.click('#tab-export');
  await page.evaluate(() => {
    window.__said = [];
    const el = document.getElementById('export-status');
    new MutationObserver(() => window.__said.push(el.textContent)).observe(el, { childList: true, characterData: true, subtree: true });
  });
  const [dl] = await Promise.all([page.waitForEvent('download', { timeout: 120_000 }), page.click('#png-all')]);
  assert.match(dl.suggestedFilename(), /^ridelab-charts-png-teaching-van-B-20ms\.zip$/);
  const said = await page.evaluate(() => window.__said);
  const steps = said.map((t) => /: (\d+) of (\d+)/.exec(t)).filter(Boolean);
  assert.ok(steps.length >= 3, `progress shown: ${said.join(' | ')}`);
  assert.equal(steps[0][1], '0');
  assert.equal(steps.at(-1)[1], steps.at(-1)[2], 'the last says all of them');
  // The line under the plane: wrapped, never cut with an ellipsis.
  const line = await page.evaluate(() => {
    const el = document.querySelector('.hifi-line');
    const cs = getComputedStyle(el);
    return { ws: cs.whiteSpace, cut: el.scrollWidth > el.clientWidth + 0.5 };
  });
  assert.deepEqual(line, { ws: 'normal', cut: false });
  assertClean(log);
  await context.close();
});
