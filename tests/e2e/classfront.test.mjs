// End-to-end tests of the class front (issue #30): students' codes (js/classcode.js) made
// here from designs, pasted into the Pick tab's Class front and applied. 30 codes (some
// malformed, some from another scenario, some from another car) give 23 designs ranked by
// ascending min-max score, each design's HiFi and LoFi criteria equal to the native CLI's
// (`ridelab eval`) within REL_TOL, each score equal to the min-max distance the core's
// pick minimises, and every code left out named with its line, text and reason. The
// designs are marked on the maps and the plane and a Clear takes them off; more than 60
// codes are refused by name; hostile text never throws. Screenshots of the class front at
// 1280 x 720 and 1920 x 1080 (and projector mode) go to docs/screens/.
//
//   trunk build --release --offline && RIDELAB_CLI=target/debug/ridelab node --test tests/e2e/classfront.test.mjs

import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { openPage, settled } from './browser.mjs';
import { useSuite, assertClean, countColour, ROOT } from './harness.mjs';
import { MAX_CODES, decodeCode, encodeCode, readCodes, scenarioHash } from '../../www/js/classcode.js';

const TIMEOUT = 300_000;
/** The page's criteria against the CLI's, relative (the two agree to about 1e-12). */
const REL_TOL = 1e-9;
const suite = useSuite();
const SCREENS = path.join(ROOT, 'docs/screens');
/** The class markers' colour (js/classmarks.js CLASS_COLOUR). */
const MAGENTA = [0xd6, 0x00, 0x8f];

async function open(hash = '', opts = {}) {
  const r = await openPage(suite.browser, suite.srv.url + hash, { width: 1400, height: 1000, ...opts });
  await settled(r.page, 100);
  return r;
}

/** `ridelab eval --json` of design `ks`, `cs` by `model` (quarter or full) on the default road (RIDELAB_CLI, else target/). */
function cliEval(model, car, ks, cs) {
  const candidates = [process.env.RIDELAB_CLI, path.join(ROOT, 'target/debug/ridelab'), path.join(ROOT, 'target/release/ridelab')];
  const c = candidates.filter(Boolean).find((x) => fs.existsSync(x));
  assert.ok(c, 'the native CLI is built (cargo build -p ridelab)');
  const args = ['eval', '--model', model, '--car', car, '--class', 'B', '--speed', '20', '--tracks', 'correlated', '--ks', String(ks), '--cs', String(cs), '--json'];
  return JSON.parse(execFileSync(c, args, { encoding: 'utf8' }));
}

/** The page's scenario key (js/store.js `scenarioKey`) of state `s`. */
const keyOf = (s) => JSON.stringify({ ...s, ks: 0, cs: 0 });

/** The min-max score of `c` on front study `fr`, as crate/src/optimize/minmax.rs computes it. */
function score(fr, c) {
  const ratio = (p) => [p.bacc / fr.datum.bacc, p.dtl / fr.datum.dtl];
  const rs = fr.study.front.map(ratio);
  const r = ratio(c);
  return Math.max(...[0, 1].map((k) => {
    const lo = Math.min(...rs.map((x) => x[k]));
    const hi = Math.max(...rs.map((x) => x[k]));
    return hi > lo ? (r[k] - lo) / (hi - lo) : 0;
  }));
}

/**
 * 30 lines of codes for the page's state `s`: 21 designs on its scenario (a 7 x 3 spread
 * over the box, every other one named), 2 of the same car on class C (ranked with a
 * note), 2 for the compact car, 5 malformed. Returns `{text, expect}` (`expect.ranked`:
 * the designs, `expect.left`: the lines left out, `expect.noted`: the lines ranked with a note).
 */
function classCodes(s, box) {
  const key = keyOf(s);
  const lines = [];
  const ranked = [];
  const left = [];
  const noted = [];
  const names = ['Anna', 'Ben', 'Chloé', 'Dev', 'Ema', 'Finn', 'Gus', 'Hana', 'Ivo', 'Jo', 'Kai'];
  let k = 0;
  for (let i = 0; i < 7; i++) {
    for (let j = 0; j < 3; j++) {
      const ks = Math.round(box.ks_min + ((i + 0.5) / 7) * (box.ks_max - box.ks_min));
      const cs = Math.round(box.cs_min + ((j + 0.5) / 3) * (box.cs_max - box.cs_min));
      const name = k % 2 === 0 ? names[k / 2] : '';
      const code = encodeCode({ car: s.car, key, ks, cs, name });
      // Some lines as a student would send them: inside a sentence.
      lines.push(k % 5 === 3 ? `from ${name || 'me'}: ${code} thanks` : code);
      ranked.push({ line: lines.length, ks, cs, name });
      k++;
    }
    if (i === 2) {
      lines.push('RL1-sedan-zzzzzzz-20000-1500-1x2y'); // bad check
      left.push(lines.length);
      lines.push('hello teacher, my design is the stiff one'); // no code
      left.push(lines.length);
    }
  }
  for (const [ks, cs] of [[22000, 1400], [30000, 2500]]) {
    lines.push(encodeCode({ car: s.car, key: keyOf({ ...s, class: 'C' }), ks, cs, name: 'Other_road' }));
    ranked.push({ line: lines.length, ks, cs, name: 'Other_road' });
    noted.push(lines.length);
  }
  for (const [ks, cs] of [[25000, 1800], [15000, 900]]) {
    lines.push(encodeCode({ car: 'compact', key: keyOf({ ...s, car: 'compact' }), ks, cs }));
    left.push(lines.length);
  }
  const good = encodeCode({ car: s.car, key, ks: 20000, cs: 1500, name: 'Zed' });
  lines.push(good.replace('20000', '20001')); // a changed digit: the check catches it
  left.push(lines.length);
  lines.push(good.replace(/^RL1/, 'RL2')); // a later version
  left.push(lines.length);
  lines.push(good.slice(0, 20)); // cut short
  left.push(lines.length);
  assert.equal(lines.length, 30);
  return { text: lines.join('\n'), expect: { ranked, left, noted } };
}

/** Pastes `text`, applies it and waits until the class front is shown and the page settled. */
async function apply(page, text) {
  await page.evaluate(() => (window.__cfBefore = window.__ridelab.classFront));
  await page.fill('#cf-text', text);
  await page.click('#cf-apply');
  await page.waitForFunction(() => window.__ridelab.classFront !== window.__cfBefore && window.__ridelab.isSettled(), null, { timeout: 60_000 });
  await page.waitForTimeout(100);
}

/** Opens the Pick tab and scrolls the class front into view. */
async function showClassFront(page) {
  if ((await page.getAttribute('#tab-pick', 'aria-selected')) !== 'true') await page.click('#tab-pick');
  await page.waitForTimeout(150);
  await page.evaluate(() => document.getElementById('h-class').scrollIntoView({ block: 'start' }));
}

test('the codes: round trip, check, version, names, bounds', () => {
  const key = keyOf({ car: 'sedan', class: 'B' });
  const code = encodeCode({ car: 'sedan', key, ks: 19960.4, cs: 1290.6, name: 'Zoë M' });
  assert.match(code, /^RL1-sedan-[0-9a-z]{7}-19960-1291-Zoë_M-[0-9a-z]{4}$/);
  assert.deepEqual(decodeCode(code).code, { car: 'sedan', scenario: scenarioHash(key), ks: 19960, cs: 1291, name: 'Zoë_M' });
  assert.match(decodeCode(code.replace('19960', '19970')).error, /check/);
  assert.match(decodeCode(code.replace('RL1', 'RL7')).error, /version 7/);
  const many = Array.from({ length: MAX_CODES + 5 }, (_, i) => encodeCode({ car: 'sedan', key, ks: 10000 + i, cs: 1000 })).join('\n');
  const r = readCodes(many);
  assert.equal(r.codes.length, MAX_CODES);
  assert.deepEqual(r.problems.map((p) => p.line), [61, 62, 63, 64, 65]);
  for (const p of r.problems) assert.match(p.reason, /more than 60 codes/);
  // Whatever the text, no throw and every non-blank line either read or named.
  for (const t of ['', '\n\n', 'RL1-', 'RL1----', 'RL1-a-b-c-d-e-f-g-h', 'RL99999999999999999999-x', '\u0000RL1-sedan', 'x'.repeat(100000), `RL1-sedan-0000000-${'9'.repeat(400)}-1-aaaa`]) {
    const out = readCodes(t);
    const lines = t.split(/\r\n|\r|\n/).filter((l) => l.trim() !== '').length;
    assert.equal(out.codes.length + out.problems.length, lines, JSON.stringify(t.slice(0, 40)));
  }
});

test('30 class codes: ranked by min-max score, criteria equal to the CLI, every code left out named; markers on and off', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open('', { width: 1920, height: 1080 });
  const s = await page.evaluate(() => window.__ridelab.state);
  const box = await page.evaluate(() => window.__ridelab.desc.designBox);
  const { text, expect } = classCodes(s, box);
  await showClassFront(page);
  await apply(page, text);
  const cf = await page.evaluate(() => window.__ridelab.classFront);
  const fr = await page.evaluate(() => window.__ridelab.front);

  // Every design read, ranked by ascending score.
  assert.equal(cf.rows.length, expect.ranked.length, 'designs ranked');
  assert.deepEqual(cf.rows.map((r) => r.line).sort((a, b) => a - b), expect.ranked.map((r) => r.line));
  cf.rows.forEach((r, i) => {
    assert.equal(r.rank, i + 1);
    if (i > 0) assert.ok(r.score >= cf.rows[i - 1].score, `rank ${i + 1} scores no less than rank ${i}`);
    assert.ok(Number.isFinite(r.score));
  });

  // The score is the min-max distance of the core's pick: the pick's own is its score,
  // no front point beats it, and each design's is recomputed from its plane criteria.
  assert.ok(Math.abs(score(fr, fr.study.pick.criteria) - fr.study.pick.score) < 1e-12, 'the pick scores its own score');
  for (const p of fr.study.front) assert.ok(score(fr, p) >= fr.study.pick.score - 1e-12);
  for (const r of cf.rows) assert.ok(Math.abs(score(fr, r.plane) - r.score) < 1e-12, `${r.label}: score`);

  // Each design's criteria against the CLI's.
  let worst = 0;
  for (const r of cf.rows) {
    for (const [model, mine] of [['full', r.hifi], ['quarter', r.lofi]]) {
      const c = cliEval(model, s.car, r.ks, r.cs);
      for (const k of ['bacc', 'dtl', 'sws']) {
        const d = Math.abs(mine[k] - c[k]) / Math.abs(c[k]);
        worst = Math.max(worst, d);
        assert.ok(d < REL_TOL, `${r.label} ${model} ${k}: page ${mine[k]} vs CLI ${c[k]}`);
      }
    }
    const want = expect.ranked.find((e) => e.line === r.line);
    assert.deepEqual([r.ks, r.cs], [want.ks, want.cs]);
    assert.equal(r.label, want.name ? want.name.replace(/_/g, ' ') : `student ${r.n}`);
    assert.equal(r.note !== '', expect.noted.includes(r.line), `${r.label}: a note only for another scenario`);
  }
  console.log(`class front: ${cf.rows.length} designs, largest page-vs-CLI relative difference ${worst.toExponential(2)}`);

  // Every code left out (and every one ranked with a note) named with its line and text.
  const lines = text.split('\n');
  const named = await page.$$eval('#cf-problems li', (lis) => lis.map((li) => li.textContent));
  assert.equal(named.length, expect.left.length + expect.noted.length);
  for (const n of [...expect.left, ...expect.noted]) {
    const item = named.find((t) => t.startsWith(`Line ${n} `));
    assert.ok(item, `line ${n} named`);
    assert.ok(item.includes(lines[n - 1].trim().slice(0, 20)), `line ${n}: its text (${item})`);
  }
  assert.match(named.find((t) => t.startsWith(`Line ${expect.left[0]} `)), /check does not match/);
  assert.match(named.find((t) => t.startsWith(`Line ${expect.left[1]} `)), /no RideLab code/);
  for (const n of expect.left.slice(2, 4)) assert.match(named.find((t) => t.startsWith(`Line ${n} `)), /compact car/);
  assert.match(named.find((t) => t.startsWith(`Line ${expect.left[5]} `)), /version 2/);
  assert.match(await page.textContent('#cf-status'), /23 designs ranked.*7 lines not used/);

  // The table: the pick's reference row, then the ranks in order, a design's note in a
  // row beneath it; finite numbers, units in the headings.
  const table = await page.evaluate(() => {
    const t = document.getElementById('cf-table');
    const cells = (r) => [...r.cells].map((c) => c.textContent);
    return {
      head: cells(t.tHead.rows[0]),
      rows: [...t.tBodies[0].querySelectorAll('tr[data-rank], tr.pick-row')].map(cells),
      notes: [...t.tBodies[0].querySelectorAll('tr.note-row')].map((r) => [r.previousElementSibling.dataset.rank, r.textContent]),
    };
  });
  assert.deepEqual(table.head, ['Rank', 'Student', 'Ks kN/m', 'Cs kNs/m', 'BAcc m/s²', 'DTL N', 'SWS mm', 'Min-max score', 'Feasible']);
  assert.equal(table.rows.length, cf.rows.length + 1);
  assert.match(table.rows[0][1], /pick/);
  assert.deepEqual(table.rows.slice(1).map((r) => r[0]), cf.rows.map((r) => String(r.rank)));
  for (const r of table.rows) for (const c of r.slice(2, 8)) assert.match(c, /^−?[\d.]+$/, `a finite number: ${c}`);
  assert.deepEqual(table.notes.map(([rank]) => Number(rank)).sort((a, b) => a - b), cf.rows.filter((r) => r.note).map((r) => r.rank));
  for (const [, t] of table.notes) assert.match(t, /another road/);

  // The markers: magenta on every map and on the plane, gone after Clear.
  const marks = async () => ({
    maps: await Promise.all(['bacc', 'dtl', 'sws'].map((k) => countColour(page, `map-${k}-overlay`, MAGENTA, 60))),
    plane: await countColour(page, 'op-overlay', MAGENTA, 60),
  });
  const on = await marks();
  for (const n of on.maps) assert.ok(n > 50, `class markers on each map (${on.maps})`);
  assert.ok(on.plane > 50, `class markers on the plane (${on.plane})`);
  assert.equal(await page.isVisible('#op-key-class'), true);

  // A new scenario evaluates the codes again on it.
  await page.selectOption('#class', 'C');
  await page.waitForFunction(() => window.__ridelab.classFront?.key === JSON.stringify({ ...window.__ridelab.state, ks: 0, cs: 0 }) && window.__ridelab.isSettled(), null, { timeout: 60_000 });
  const onC = await page.evaluate(() => window.__ridelab.classFront);
  assert.equal(onC.rows.length, 23);
  assert.equal(onC.rows.filter((r) => r.note.includes('another road')).length, 21, 'on class C the class B codes carry the note');
  await page.selectOption('#class', 'B');
  await page.waitForFunction(() => window.__ridelab.classFront?.key === JSON.stringify({ ...window.__ridelab.state, ks: 0, cs: 0 }) && window.__ridelab.isSettled(), null, { timeout: 60_000 });

  await page.click('#cf-clear');
  await page.waitForTimeout(100);
  const off = await marks();
  assert.deepEqual(off, { maps: [0, 0, 0], plane: 0 }, 'Clear takes the markers off');
  assert.equal(await page.isVisible('#cf-table'), false);
  assert.equal(await page.evaluate(() => window.__ridelab.classFront), null);
  assertClean(log);
  await context.close();
});

test('send my design: the code carries the design and scenario and ranks on the teacher page', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  await page.click('#tab-pick');
  await page.fill('#ks-num', '23.45');
  await page.press('#ks-num', 'Enter');
  await settled(page, 100);
  await page.fill('#cf-name', 'Rosa Parks!');
  await page.click('#cf-make');
  const code = (await page.textContent('#cf-code')).trim();
  const s = await page.evaluate(() => window.__ridelab.state);
  const d = decodeCode(code);
  assert.deepEqual(d.code, { car: s.car, scenario: scenarioHash(keyOf(s)), ks: 23450, cs: Math.round(s.cs), name: 'Rosa_Parks' });
  // The code follows the design.
  await page.fill('#ks-num', '25');
  await page.press('#ks-num', 'Enter');
  await settled(page, 100);
  assert.equal(decodeCode((await page.textContent('#cf-code')).trim()).code.ks, 25000);
  await apply(page, code);
  const cf = await page.evaluate(() => window.__ridelab.classFront);
  assert.equal(cf.rows.length, 1);
  assert.equal(cf.rows[0].label, 'Rosa Parks');
  assert.equal(cf.rows[0].note, '');
  assert.deepEqual(cf.problems, []);
  assertClean(log);
  await context.close();
});

test('hostile text and more than 60 codes: named, never thrown', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  await page.click('#tab-pick');
  const s = await page.evaluate(() => window.__ridelab.state);
  const key = keyOf(s);
  const hostile = [
    encodeCode({ car: s.car, key, ks: 9_999_999, cs: 1 }),
    encodeCode({ car: s.car, key, ks: 1, cs: 9_999_999 }),
    encodeCode({ car: s.car, key, ks: 1, cs: 1 }),
    'RL1-sedan-0000000-NaN-Infinity-aaaa',
    '<img src=x onerror=alert(1)> RL1-<b>',
    '\u202eRL1-sedan',
    'RL1-' + 'a'.repeat(5000),
  ].join('\n');
  await apply(page, hostile);
  const cf = await page.evaluate(() => window.__ridelab.classFront);
  assert.equal(cf.rows.length + cf.problems.length, 7, 'every line ranked or named');
  for (const r of cf.rows) for (const v of [r.score, r.hifi.bacc, r.hifi.dtl, r.hifi.sws]) assert.ok(Number.isFinite(v));
  const cells = await page.$$eval('#cf-table td', (tds) => tds.map((t) => t.textContent));
  for (const c of cells) assert.doesNotMatch(c, /NaN|Infinity|undefined/);
  assert.equal(await page.evaluate(() => document.querySelector('#cf-problems img')), null, 'text is text');

  const many = Array.from({ length: 65 }, (_, i) => encodeCode({ car: s.car, key, ks: 12000 + 300 * i, cs: 800 + 40 * i })).join('\n');
  await apply(page, many);
  const m = await page.evaluate(() => window.__ridelab.classFront);
  assert.equal(m.rows.length, 60);
  assert.deepEqual(m.problems.map((p) => p.line), [61, 62, 63, 64, 65]);
  assert.match(await page.textContent('#cf-problems'), /Line 61 .*more than 60 codes/);
  // The page still works: a design change goes through.
  await page.fill('#ks-num', '21');
  await page.press('#ks-num', 'Enter');
  await settled(page, 100);
  assert.equal(await page.evaluate(() => window.__ridelab.state.ks), 21000);
  assertClean(log);
  await context.close();
});

test('screenshots of the class front with the 30 codes at 1280 x 720 and 1920 x 1080 (plain and projector): the table whole, 16 px type', { timeout: TIMEOUT }, async () => {
  fs.mkdirSync(SCREENS, { recursive: true });
  const shots = [[1280, 720, 'class-front-1280x720.png', ''], [1920, 1080, 'class-front.png', ''], [1920, 1080, 'class-front-projector.png', '#proj=1']];
  for (const [width, height, file, hash] of shots) {
    const { page, context, log } = await open(hash, { width, height });
    const s = await page.evaluate(() => window.__ridelab.state);
    const box = await page.evaluate(() => window.__ridelab.desc.designBox);
    await showClassFront(page);
    await apply(page, classCodes(s, box).text);
    // The teacher's view: the status line, the table and the named lines.
    await page.evaluate(() => document.getElementById('cf-status').scrollIntoView({ block: 'start' }));
    await page.waitForTimeout(200);
    await page.screenshot({ path: path.join(SCREENS, file) });
    // Readable across a room: the table whole in its box (no sideways scroll), its type 16 px or more.
    const fit = await page.evaluate(() => {
      const t = document.getElementById('cf-table');
      const w = t.parentElement;
      return { scroll: w.scrollWidth, client: w.clientWidth, px: parseFloat(getComputedStyle(t.tBodies[0].rows[1].cells[1]).fontSize) };
    });
    console.log(`${width} x ${height}${hash ? ' projector' : ''}: class table ${fit.scroll} px in ${fit.client} px, type ${fit.px} px`);
    assert.ok(fit.scroll <= fit.client, `${width} x ${height}: the class table fits its box (${fit.scroll} > ${fit.client})`);
    assert.ok(fit.px >= 16, `${width} x ${height}: type ${fit.px} px`);
    assertClean(log);
    await context.close();
  }
});
