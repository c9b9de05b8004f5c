// End-to-end tests of the lessons (issue #20): every shipped lesson's steps load and
// every placeholder resolves to a number with no NaN, one number per lesson equal to the
// native CLI's for the same state; a lesson authored in the page survives export and
// import (file and link) in a fresh page; a malformed lesson is refused with the step
// and field named while the page keeps its state; the keyboard steps through a lesson
// without taking the arrow keys from a focused map; the panel leaves the sliders, maps
// and objective plane whole at 1280 x 720 and on a phone.
//
//   trunk build --release --offline && RIDELAB_CLI=target/debug/ridelab node --test tests/e2e/lessons.test.mjs

import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { openPage, settled } from './browser.mjs';
import { useSuite, assertClean, ROOT, OUT } from './harness.mjs';

const TIMEOUT = 240_000;
const suite = useSuite();
const CAR = path.join(ROOT, 'assets/cars/sedan.json');

async function open(hash = '', opts = {}) {
  const r = await openPage(suite.browser, suite.srv.url + hash, { width: 1280, height: 720, ...opts });
  await settled(r.page, 100);
  return r;
}

/** The native CLI (RIDELAB_CLI, else target/debug or target/release). */
function cli(args) {
  const candidates = [process.env.RIDELAB_CLI, path.join(ROOT, 'target/debug/ridelab'), path.join(ROOT, 'target/release/ridelab')];
  const c = candidates.filter(Boolean).find((x) => fs.existsSync(x));
  assert.ok(c, 'the native CLI is built (cargo build -p ridelab)');
  return JSON.parse(execFileSync(c, [...args, '--json'], { encoding: 'utf8', maxBuffer: 64 << 20 }));
}

/** `ridelab eval` of the sedan (`model`: quarter or full) with extra options. */
const evalCli = (model, extra = []) => cli(['eval', '--model', model, '--car', CAR, ...extra]);

/** Waits until the page has settled and the lesson panel shows every number of its step. */
async function lessonReady(page) {
  await page.waitForFunction(() => window.__ridelab.isSettled() && document.getElementById('lesson').dataset.ready === 'true', null, { timeout: 60_000 });
}

/** The step shown: question and answer text, and each placeholder's `{name: value}` (SI, as in data-value). */
function shown(page) {
  return page.evaluate(() => {
    const values = {};
    for (const el of document.querySelectorAll('#lesson-question .live, #lesson-answer .live')) values[el.dataset.ph] = el.dataset.value;
    return {
      question: document.getElementById('lesson-question').textContent,
      answer: document.getElementById('lesson-answer').textContent,
      count: document.getElementById('lesson-count').textContent,
      values,
    };
  });
}

/** Answers (option 1 when there are options) and reveals step `k` of the running lesson; its text once every number is in. */
async function revealStep(page, k) {
  await page.evaluate((k) => window.__ridelab.lessons.go(k), k);
  await lessonReady(page);
  if (await page.locator('#lesson-options button').count()) await page.click('#lesson-options button >> nth=0');
  await page.click('#lesson-reveal');
  await lessonReady(page);
  return shown(page);
}

const close = (a, b, rel = 1e-9) => Math.abs(a - b) <= rel * Math.max(Math.abs(a), Math.abs(b));

test('every shipped lesson: its steps load, every placeholder resolves, one number per lesson equals the CLI', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  await page.click('#lessons-open');
  const ids = await page.$$eval('#lesson-shipped button', (bs) => bs.map((b) => b.dataset.lesson));
  assert.deepEqual(ids, ['comfort', 'fidelity', 'objectives', 'surrogate', 'choosing']);
  const seen = {};
  for (const id of ids) {
    if (await page.isVisible('#lesson-menu')) await page.click('#lesson-menu');
    await page.click(`#lesson-shipped button[data-lesson="${id}"]`);
    await lessonReady(page);
    const n = await page.evaluate(() => window.__ridelab.lessons.lesson.steps.length);
    seen[id] = [];
    for (let k = 0; k < n; k++) {
      const s = await revealStep(page, k);
      const where = `${id} step ${k + 1}`;
      assert.equal(s.count, `Step ${k + 1} of ${n}`, where);
      for (const text of [s.question, s.answer]) {
        assert.doesNotMatch(text, /\{[a-z_][\w.]*\}/i, `${where}: a placeholder left in "${text}"`);
        assert.doesNotMatch(text, /NaN|undefined|…|Infinity/, `${where}: "${text}"`);
      }
      assert.ok(s.answer.length > 40, `${where}: a reveal is shown`);
      for (const [name, v] of Object.entries(s.values)) {
        if (v !== undefined && /^-?[\d.e+-]+$/.test(v)) assert.ok(Number.isFinite(Number(v)), `${where}: {${name}} = ${v}`);
      }
      seen[id].push({ ...s, state: await page.evaluate(() => window.__ridelab.state), pick: await page.evaluate(() => window.__ridelab.front.study?.pick ?? null) });
    }
  }

  // 1. Comfort: the HiFi SWS of the softer spring (step 2), and the comfort-optimal damping of
  //    step 4 from the car file's own masses (ms = M b / (2 L)).
  const c2 = seen.comfort[1];
  assert.equal(c2.state.ks, 14000);
  assert.ok(close(Number(c2.values['hifi.sws']), evalCli('full', ['--ks', '14000', '--cs', '1290']).sws), `comfort: {hifi.sws} ${c2.values['hifi.sws']}`);
  const car = JSON.parse(fs.readFileSync(CAR, 'utf8'));
  const ms = (car.sprung_mass * car.b) / (2 * (car.a + car.b));
  const csOpt = 19960 * Math.sqrt((ms + car.front.unsprung_mass) / car.front.tire_stiffness);
  assert.ok(close(Number(seen.comfort[3].values.cs_opt), csOpt, 1e-12), `{cs_opt} ${seen.comfort[3].values.cs_opt} vs ${csOpt}`);

  // 2. What the quarter car cannot see: the BAcc gap at 10 m/s.
  const f2 = seen.fidelity[1];
  assert.equal(f2.state.speed, 10);
  const gap = evalCli('full', ['--speed', '10']).bacc / evalCli('quarter', ['--speed', '10']).bacc - 1;
  assert.ok(close(Number(f2.values['gap.bacc']), gap, 1e-7), `fidelity: {gap.bacc} ${f2.values['gap.bacc']} vs ${gap}`);

  // 3. The design objective space: class C, the LoFi SWS and no feasible design.
  const o3 = seen.objectives[2];
  assert.equal(o3.state.class, 'C');
  assert.ok(close(Number(o3.values['lofi.sws']), evalCli('quarter', ['--class', 'C']).sws), `objectives: {lofi.sws} ${o3.values['lofi.sws']}`);
  assert.equal(Number(o3.values.feasible), 0, 'no design in the box meets SWS ≤ 7 mm on class C');
  assert.match(o3.answer, /no design meets the objectives: SWS limit 7(\.0)? mm is exceeded everywhere/);

  // 4. Why a surrogate: its largest BAcc error on the HiFi grid, as `ridelab surrogate` says.
  const s2 = seen.surrogate[1];
  const fit = cli(['surrogate', '--approach', 'rba-mul-rbf-mq', '--plan', 'ae:10', '--car', CAR, '--class', 'B', '--speed', '20']);
  assert.ok(close(Number(s2.values['fit.rte.bacc']), fit.metrics.bacc.rte_max_percent / 100, 1e-7), `surrogate: {fit.rte.bacc} ${s2.values['fit.rte.bacc']} vs ${fit.metrics.bacc.rte_max_percent} %`);
  assert.equal(Number(seen.surrogate[0].values.samples), fit.samples.length);

  // 5. Choosing one design: the pick's HiFi re-check equals `ridelab eval --model full` at the pick.
  const p3 = seen.choosing[2];
  const hifiAtPick = evalCli('full', ['--ks', String(p3.pick.ks), '--cs', String(p3.pick.cs)]);
  assert.ok(close(Number(p3.values['recheck.bacc']), hifiAtPick.bacc), `choosing: {recheck.bacc} ${p3.values['recheck.bacc']} vs ${hifiAtPick.bacc}`);
  assertClean(log);
  await context.close();
});

test('authoring: a lesson built in the page survives export and import, as a file and as a link, in a fresh page', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open('', { downloads: true });
  await page.click('#lessons-open');
  await page.click('#lesson-new');
  await lessonReady(page);
  assert.equal(await page.isVisible('#lesson-edit'), true, 'a new lesson opens the editor');
  await page.fill('#le-title', 'Springs, my way');
  await page.fill('#le-question', 'Datum first: how hard does the body shake?');
  await page.fill('#le-options', 'Hard\nSoftly');
  await page.fill('#le-reveal', 'BAcc is {hifi.bacc} on the full car.');
  // A second view: a softer spring on a rougher road, added as a step and edited.
  await page.fill('#ks-num', '15');
  await page.press('#ks-num', 'Enter');
  await page.selectOption('#class', 'C');
  await settled(page, 100);
  await page.click('#le-add');
  await lessonReady(page);
  await page.fill('#le-question', 'Softer, on class {class}: and now?');
  await page.fill('#le-reveal', 'BAcc {hifi.bacc.pct} against the datum; SWS {lofi.sws}.');
  await page.fill('#le-highlight', 'map-grid, op-wrap');
  // A typo is named at once, with the step and field.
  await page.fill('#le-hide', 'critera');
  assert.equal(await page.textContent('#lesson-msg'), "steps[1].hide[0]: no element 'critera' on the page");
  await page.fill('#le-hide', 'criteria');
  assert.equal(await page.textContent('#lesson-msg'), '');
  // Reordered: the second step first.
  await page.click('#le-up');
  const built = await page.evaluate(() => window.__ridelab.lessons.lesson);
  assert.equal(built.steps.length, 2);
  assert.match(built.steps[0].view, /ks=15000/);
  assert.match(built.steps[0].view, /class=C/);
  assert.deepEqual(built.steps[0].highlight, ['map-grid', 'op-wrap']);
  assert.deepEqual(built.steps[1].options, ['Hard', 'Softly']);
  const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#lesson-export')]);
  const file = fs.readFileSync(await dl.path(), 'utf8');
  fs.writeFileSync(path.join(OUT, 'lesson-authored.json'), file);
  const exported = JSON.parse(file);
  assert.equal(exported.ridelab, 'lesson');
  assert.equal(exported.title, 'Springs, my way');
  await page.click('#lesson-copy');
  const link = await page.inputValue('#lesson-link');
  assert.match(link, /#lesson=[\w-]+$/);
  assertClean(log);
  await context.close();

  // The file in a fresh page.
  const fresh = await open();
  await fresh.page.click('#lessons-open');
  await fresh.page.setInputFiles('#lesson-file', { name: 'mine.json', mimeType: 'application/json', buffer: Buffer.from(file) });
  await lessonReady(fresh.page);
  const imported = await fresh.page.evaluate(() => window.__ridelab.lessons.lesson);
  assert.deepEqual(imported, built, 'the same lesson after the file round trip');
  assert.equal((await fresh.page.evaluate(() => window.__ridelab.state)).class, 'C', 'its first step set its view');
  assertClean(fresh.log);
  await fresh.context.close();

  // The link in a fresh page.
  const byLink = await open(link.slice(link.indexOf('#')));
  await lessonReady(byLink.page);
  assert.deepEqual(await byLink.page.evaluate(() => window.__ridelab.lessons.lesson), built, 'the same lesson from its link');
  const st = await byLink.page.evaluate(() => window.__ridelab.state);
  assert.equal(st.ks, 15000);
  assertClean(byLink.log);
  await byLink.context.close();
});

test('a malformed lesson is refused with the step and field named; the page keeps its state', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open('#ks=15000&cs=1500&class=A&speed=25');
  const before = await page.evaluate(() => JSON.stringify(window.__ridelab.state));
  await page.click('#lessons-open');
  const good = await page.evaluate(() => import('./js/lessonbook.js').then((m) => m.SHIPPED[0].lesson));
  const cases = [
    [(l) => (l.steps[2].question = ''), 'steps[2].question: must be a non-empty string'],
    [(l) => (l.steps[1].reveal = 'BAcc {hifi.bac}'), 'steps[1].reveal: unknown placeholder {hifi.bac}'],
    [(l) => (l.steps[0].options = ['only one']), 'steps[0].options: must be a list of 2 to 6 answers'],
    [(l) => (l.steps[3].view = 'speed=fast'), "steps[3].view: speed: 'fast' is not a number"],
    [(l) => (l.steps[1].view = 'speed=-5'), 'steps[1].view: '],
    [(l) => (l.steps[2].highlight = ['no-such-thing']), "steps[2].highlight[0]: no element 'no-such-thing' on the page"],
    [(l) => (l.steps[0].colour = 'red'), "steps[0]: unknown key 'colour'"],
    [(l) => (l.version = 2), 'version: must be 1'],
  ];
  for (const [spoil, message] of cases) {
    const bad = JSON.parse(JSON.stringify(good));
    spoil(bad);
    await page.setInputFiles('#lesson-file', { name: 'bad.json', mimeType: 'application/json', buffer: Buffer.from(JSON.stringify(bad)) });
    await page.waitForFunction(() => document.getElementById('lesson-msg').textContent.startsWith('bad.json: '));
    const msg = await page.textContent('#lesson-msg');
    assert.ok(msg.startsWith(`bad.json: ${message}`), `"${msg}" names ${message}`);
    assert.equal(await page.evaluate(() => window.__ridelab.lessons.lesson), null, 'no lesson started');
    assert.equal(await page.evaluate(() => JSON.stringify(window.__ridelab.state)), before, 'the state stays');
    await page.evaluate(() => (document.getElementById('lesson-msg').textContent = ''));
  }
  await page.setInputFiles('#lesson-file', { name: 'notes.txt', mimeType: 'text/plain', buffer: Buffer.from('not json') });
  await page.waitForFunction(() => document.getElementById('lesson-msg').textContent !== '');
  assert.equal(await page.textContent('#lesson-msg'), 'notes.txt: not a RideLab lesson file (not JSON)');
  assert.equal(await page.evaluate(() => JSON.stringify(window.__ridelab.state)), before, 'the state stays');
  // A broken lesson link pasted into the address bar: refused the same way.
  const bad = JSON.parse(JSON.stringify(good));
  bad.steps[1].question = 42;
  const hash = await page.evaluate((l) => import('./js/lessons.js').then((m) => m.lessonHash({ ...l, steps: l.steps.map((s) => ({ options: [], highlight: [], hide: [], ...s })) })), bad);
  await page.evaluate((h) => (location.hash = h), hash);
  await page.waitForFunction(() => document.getElementById('lesson-msg').textContent.startsWith('The lesson link: '));
  assert.equal(await page.textContent('#lesson-msg'), 'The lesson link: steps[1].question: must be a non-empty string');
  assert.equal(await page.evaluate(() => JSON.stringify(window.__ridelab.state)), before, 'the state stays');
  await page.screenshot({ path: path.join(OUT, 'lesson-refused.png') });
  assertClean(log);
  await context.close();
});

test('keyboard: with the panel focused Space reveals and goes on, the arrows step, digits pick; a focused map keeps its arrows', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open('#lesson=comfort');
  await lessonReady(page);
  const at = () => page.evaluate(() => ({ k: window.__ridelab.lessons.k, revealed: window.__ridelab.lessons.revealed, picked: window.__ridelab.lessons.picked }));
  assert.equal(await page.evaluate(() => document.activeElement.id), 'lesson', 'the panel has the focus');
  assert.deepEqual(await at(), { k: 0, revealed: false, picked: null });
  await page.keyboard.press('Space');
  assert.equal((await at()).revealed, false, 'no reveal before the class has answered');
  await page.keyboard.press('2');
  assert.equal(await page.isHidden('#drawer'), true, 'a digit in the panel picks, it opens no tab');
  assert.deepEqual(await at(), { k: 0, revealed: false, picked: 1 });
  await page.keyboard.press('Space');
  assert.deepEqual(await at(), { k: 0, revealed: true, picked: 1 });
  await lessonReady(page);
  assert.ok(await page.evaluate(() => document.getElementById('criteria').classList.contains('spotlight')), 'the reveal outlines what to look at');
  await page.keyboard.press('Space');
  await lessonReady(page);
  assert.equal((await at()).k, 1, 'Space after the reveal: the next step');
  assert.equal((await page.evaluate(() => window.__ridelab.state)).ks, 14000, 'the step set its view');
  assert.ok(await page.evaluate(() => document.getElementById('criteria').classList.contains('lesson-veil')), 'the step hides the readout until the class has answered');
  await page.keyboard.press('ArrowRight');
  await lessonReady(page);
  assert.equal((await at()).k, 2);
  await page.keyboard.press('ArrowLeft');
  await lessonReady(page);
  assert.equal((await at()).k, 1);
  await page.keyboard.press('PageDown');
  await lessonReady(page);
  assert.equal((await at()).k, 2);
  await page.keyboard.press('1');
  await page.keyboard.press('Space');
  await lessonReady(page);
  /** The reveal's {lofi.bacc.pct} and the readout's LoFi % cell of BAcc (both SI fractions). */
  const pct = () => page.evaluate(() => [
    document.querySelector('#lesson-answer .live[data-ph="lofi.bacc.pct"]').dataset.value,
    document.querySelector('#criteria tr[data-crit="bacc"] td[data-model="lofi-d"]').dataset.value,
  ]);
  const [before, readout] = await pct();
  assert.equal(before, readout, 'the reveal shows the readout\'s number');
  // A focused map: the arrows move the design, not the lesson; the reveal follows.
  const ks = (await page.evaluate(() => window.__ridelab.state)).ks;
  await page.focus('#map-bacc-pick');
  await page.keyboard.press('ArrowRight');
  await settled(page, 100);
  await lessonReady(page);
  assert.equal((await page.evaluate(() => window.__ridelab.state)).ks, ks + 100, 'Ks one step up');
  assert.equal((await at()).k, 2, 'the lesson stayed');
  const [after, readoutAfter] = await pct();
  assert.notEqual(after, before, 'the reveal follows the design');
  assert.equal(after, readoutAfter, 'and still shows the readout\'s number');
  // L gives the keyboard back to the panel.
  await page.keyboard.press('l');
  assert.equal(await page.evaluate(() => document.activeElement.id), 'lesson');
  await page.keyboard.press('ArrowLeft');
  await lessonReady(page);
  assert.equal((await at()).k, 1);
  assertClean(log);
  await context.close();
});

/** The element at the centre of each of `sels` is itself (nothing covers it), and it lies inside the viewport. */
function whole(page, sels) {
  return page.evaluate((sels) => sels.map((s) => {
    const el = document.querySelector(s);
    const r = el.getBoundingClientRect();
    const hit = document.elementFromPoint(r.x + r.width / 2, r.y + r.height / 2);
    const inside = r.width > 40 && r.height > 8 && r.x >= 0 && r.y >= 0 && r.right <= innerWidth + 0.5 && r.bottom <= innerHeight + 0.5;
    return { s, ok: inside && (hit === el || el.parentElement.contains(hit)), r: [r.x, r.y, r.width, r.height].map(Math.round) };
  }), sels);
}

test('the lesson panel beside the workbench: sliders, maps and plane whole at 1280 x 720, in large type; a sheet on a phone', { timeout: TIMEOUT }, async () => {
  for (const projector of [false, true]) {
    const { page, context, log } = await open('#lesson=choosing');
    // The checkbox takes the focus; the keys below are the panel's once it has it back.
    if (projector) await page.click('#projector');
    await page.focus('#lesson');
    await lessonReady(page);
    await page.keyboard.press('1');
    await page.keyboard.press('Space');
    await lessonReady(page);
    await page.waitForTimeout(300);
    const res = await whole(page, ['#ks-range', '#ks-num', '#cs-range', '#cs-num', '#map-bacc', '#map-dtl', '#map-sws', '#op-base', '#lesson']);
    for (const r of res) assert.ok(r.ok, `${projector ? 'projector' : 'plain'}: ${r.s} whole and uncovered (${r.r})`);
    // The reveal is scrolled into the panel's view (the panel scrolls when it is long).
    const seen = await page.evaluate(() => {
      const p = document.getElementById('lesson').getBoundingClientRect();
      const a = document.getElementById('lesson-answer').getBoundingClientRect();
      return a.top >= p.top - 0.5 && a.top + 40 <= p.bottom;
    });
    assert.ok(seen, `${projector ? 'projector' : 'plain'}: the reveal's start is in view`);
    assert.equal(await page.evaluate(() => window.scrollY), 0);
    const px = await page.evaluate(() => parseFloat(getComputedStyle(document.getElementById('lesson-question')).fontSize));
    assert.ok(px >= (projector ? 22 : 18), `lesson type ${px} px`);
    await page.screenshot({ path: path.join(OUT, `lesson-1280${projector ? '-projector' : ''}.png`) });
    assertClean(log);
    await context.close();
  }
  const phone = await open('#lesson=comfort', { width: 390, height: 844, touch: true });
  await lessonReady(phone.page);
  const res = await whole(phone.page, ['#ks-range', '#cs-range', '#lesson-question']);
  for (const r of res) assert.ok(r.ok, `phone: ${r.s} whole and uncovered (${r.r})`);
  assert.equal(await phone.page.evaluate(() => document.documentElement.scrollWidth <= innerWidth), true, 'no sideways scroll');
  await phone.page.screenshot({ path: path.join(OUT, 'lesson-390.png') });
  assertClean(phone.log);
  await phone.context.close();
});
