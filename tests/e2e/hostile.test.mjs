// Nothing a user made is lost, and nothing hostile breaks the page (issue #27, the page's
// half): authored lessons kept in the browser (and said when they cannot be), a lesson
// link kept in the address bar, links and session files with bad keys applying the good
// ones and naming every bad one, kept designs evaluated again on a new scenario, the
// robust editor's edits checked as typed and marked until applied, crashed workers
// replaced, a new build's service worker dropping the old cache only once it booted, and
// every numeric field given hostile numbers.
//
//   trunk build --release --offline && node --test tests/e2e/hostile.test.mjs

import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { openPage, settled } from './browser.mjs';
import { startServer } from './server.mjs';
import { useSuite, ROOT, DIST, OUT } from './harness.mjs';
import { buildId } from '../../www/sw-stamp.mjs';

const TIMEOUT = 180_000;
const suite = useSuite();

const open = async (hash = '', opts = {}) => {
  const r = await openPage(suite.browser, suite.srv.url + hash, { width: 1280, height: 720, ...opts });
  await settled(r.page, 50);
  return r;
};
const banner = (page) => page.evaluate(() => (document.getElementById('banner').hidden ? '' : document.getElementById('banner-text').textContent));
const state = (page) => page.evaluate(() => window.__ridelab.state);
const text = (page, id) => page.evaluate((i) => document.getElementById(i).textContent, id);

/** Every number shown on the page (text of the readout, compare and lesson tables) is finite. */
async function noNaN(page) {
  const bad = await page.evaluate(() => [...document.querySelectorAll('#criteria, #compare, #lesson, #banner, .msg')]
    // What the user typed is quoted back ('NaN' is not a number): not a result.
    .map((e) => e.textContent.replace(/'[^']*'/g, '')).filter((t) => /\bNaN\b|Infinity|undefined/.test(t)));
  assert.deepEqual(bad, [], 'no NaN, Infinity or undefined on screen');
}

test('a link with bad keys applies the good ones (car JSON and kept designs too) and names every bad key', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open('#speed=1e308&sws=abc&class=Z&ks=-5&cs=1400&keep=20000:1500,foo:bar&model=nope&zzz=1');
  const said = await banner(page);
  for (const k of ['speed', 'sws', 'class', 'Ks', "keep: 'foo:bar'", 'model', "'zzz'"]) assert.ok(said.includes(k), `the banner names ${k}: ${said}`);
  assert.match(said, /1e\+308 m\/s is outside 1\.\.100 m\/s/, 'with the reason and the range');
  const s = await state(page);
  assert.equal(s.cs, 1400, 'the good Cs applies');
  assert.equal(s.speed, 20, 'the bad speed keeps its default');
  assert.equal(await page.locator('#compare th[data-saved]').count(), 1, 'the good kept design is kept');
  await noNaN(page);

  // A custom car's JSON applies beside a bad key.
  const json = await page.evaluate(() => window.__ridelab.presets.find((p) => p.name !== 'sedan').json);
  await page.evaluate((h) => (location.hash = h), `#car=custom&carjson=${encodeURIComponent(json)}&speed=fast&plan=zz:1`);
  await page.waitForFunction(() => window.__ridelab.state.car === 'custom', null, { timeout: 30_000 });
  await settled(page, 50);
  const said2 = await banner(page);
  assert.match(said2, /speed: 'fast' is not a number/);
  assert.match(said2, /plan/i, `the bad plan is named too: ${said2}`);
  assert.deepEqual(JSON.parse((await state(page)).carJson), JSON.parse(json), 'the car JSON applies');
  assert.deepEqual(log.errors, []);
  await context.close();
});

test('a session file with bad keys applies the good ones and names every one; one the engine refuses keeps the current state', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open('#speed=25');
  const base = await state(page);
  const file = (obj) => ({ name: 'session.json', mimeType: 'application/json', buffer: Buffer.from(JSON.stringify(obj)) });
  const session = {
    ridelab: 'session', version: 1, extra: 1,
    state: { ...base, cs: 1500, speed: 'fast', swsLimit: 1e308, foo: 1 },
    view: { model: 'hifi', scale: 'weird', bogus: true },
    kept: [[20000, 1500], [-1, 2]],
  };
  await page.setInputFiles('#session-load', file(session));
  await page.waitForFunction(() => window.__ridelab.state.cs === 1500, null, { timeout: 30_000 });
  await settled(page, 50);
  const said = await banner(page);
  for (const k of ["session key 'extra'", "state: 'foo'", 'state.speed', 'SWS limit', 'view: scale', "view key 'bogus'", 'kept[1]']) assert.ok(said.includes(k), `the banner names ${k}: ${said}`);
  const s = await state(page);
  assert.equal(s.speed, 20, 'the bad speed keeps its default');
  assert.equal(s.swsLimit, base.swsLimit, 'the bad SWS limit keeps its default');
  assert.equal((await page.evaluate(() => window.__ridelab.view)).model, 'hifi', 'the good view key applies');
  assert.equal(await page.locator('#compare th[data-saved]').count(), 1, 'the good kept design is kept');

  // Passes its checks, but the engine refuses to compute it: refused, the state stays.
  await page.evaluate(() => {
    const eng = window.__ridelab.engine;
    const call = eng.call.bind(eng);
    eng.call = (m, ...a) => (m === 'analyse' && a[0].speed === 33.5 ? Promise.reject({ message: 'the solver diverged', field: '' }) : call(m, ...a));
  });
  const before = await state(page);
  await page.setInputFiles('#session-load', file({ ridelab: 'session', version: 1, state: { ...before, speed: 33.5 } }));
  await page.waitForFunction(() => /cannot be computed/.test(document.getElementById('banner-text').textContent), null, { timeout: 30_000 });
  assert.match(await banner(page), /the solver diverged/, 'the reason is said');
  assert.match(await text(page, 'msg-session'), /not loaded/);
  await settled(page, 50);
  assert.deepEqual(await state(page), before, 'the current state stays (not the defaults)');
  await noNaN(page);
  assert.deepEqual(log.errors, []);
  await context.close();
});

test('kept designs are evaluated again on a new car and road, or dropped with a note', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open('#keep=20000:1500,39000:1500');
  const cell = () => page.evaluate(() => [...document.querySelectorAll('#compare tr[data-crit="bacc"][data-model="lofi"] td')].map((td) => td.dataset.value ?? td.textContent));
  const b1 = await cell();
  await page.selectOption('#class', 'C');
  await page.waitForFunction(() => window.__ridelab.state.class === 'C', null, { timeout: 30_000 });
  await settled(page, 100);
  const b2 = await cell();
  const want = await page.evaluate(async () => {
    const s = window.__ridelab.state;
    const eng = window.__ridelab.engine;
    return Promise.all([[20000, 1500], [39000, 1500]].map(([ks, cs]) => eng.call('analyse', { ...s, ks, cs }, 'lofi').then((r) => r.bacc)));
  });
  assert.notDeepEqual(b2.slice(1), b1.slice(1), 'the kept designs no longer show the old road\'s numbers');
  assert.deepEqual(b2.slice(1).map(Number), want, 'they show the new road\'s');
  assert.match(await text(page, 'compare-hint'), /evaluated again on the new car and road/);

  // A design box that no longer holds one: it is dropped, and the note says why.
  await page.evaluate(() => {
    const el = document.getElementById('ks-max');
    el.value = '30';
    el.dispatchEvent(new Event('change'));
  });
  await page.waitForFunction(() => window.__ridelab.state.ksMax === 30000, null, { timeout: 30_000 });
  await settled(page, 100);
  // The core refuses a design outside the box its surrogate was fitted over.
  assert.equal(await page.locator('#compare th[data-saved]').count(), 1, 'the design outside the new box is dropped');
  const hint = await text(page, 'compare-hint');
  assert.match(hint, /Dropped, as they cannot be evaluated on it: Ks 39(\.0+)? kN\/m, Cs 1\.50* kNs\/m \(/, `the dropped design is named with the reason: ${hint}`);
  assert.match(await banner(page), /Dropped/, 'and the banner says so');
  await noNaN(page);
  assert.deepEqual(log.errors, []);
  await context.close();
});

test('the robust editor checks values as they are typed and marks edits not applied', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  await page.evaluate(() => {
    document.querySelector('.tabs [aria-controls="panel-car"], .tabs [role="tab"]')?.click();
    document.getElementById('robust').open = true;
  });
  await page.click('#rb-add-load');
  assert.equal(await page.isVisible('#rb-pending'), true, 'an edit not applied is marked');
  assert.match(await text(page, 'rb-pending'), /not applied: press Apply/);
  const mass = page.locator('#rb-load input[data-key="mass"]').first();
  for (const [typed, want] of [['1e308', /Load case 1 extra mass, kg \(cases\.load_cases\[0\]\.mass\): 1e\+308 kg is outside -20000\.\.20000 kg/], ['NaN', /extra mass, kg: 'NaN' is not a number/], ['-1e9', /outside -20000\.\.20000 kg/]]) {
    await mass.fill(typed);
    await page.waitForFunction((w) => new RegExp(w).test(document.getElementById('msg-cases').textContent), want.source, { timeout: 10_000 });
    assert.equal(await mass.getAttribute('aria-invalid'), 'true', `${typed}: the cell is marked`);
    if (typed === '1e308') await page.screenshot({ path: path.join(OUT, 'hostile-robust-typed.png') });
    assert.equal((await state(page)).cases, null, 'nothing applied');
  }
  await mass.fill('300');
  await page.waitForFunction(() => /valid: press Apply/.test(document.getElementById('msg-cases').textContent), null, { timeout: 10_000 });
  assert.equal(await mass.getAttribute('aria-invalid'), null);
  await page.click('#rb-apply');
  await page.waitForFunction(() => window.__ridelab.state.cases !== null, null, { timeout: 30_000 });
  await settled(page, 50);
  assert.equal(await page.isVisible('#rb-pending'), false, 'applied: the mark goes');
  assert.match((await state(page)).cases, /"mass":300/);
  await page.screenshot({ path: path.join(OUT, 'hostile-robust.png') });
  assert.deepEqual(log.errors, []);
  await context.close();
});

test('a worker that traps or crashes is restarted, the page says so, and the request is run again', { timeout: TIMEOUT }, async () => {
  const { page, context } = await open();
  // The HiFi worker (the other one has ?gpu=); after a restart the newest.
  const hifiWorker = () => page.workers().filter((w) => /worker\.js$/.test(w.url())).at(-1);
  // A trap of the core (a WebAssembly.RuntimeError) on the next HiFi report (the
  // design's reports by both models, `designReports`, or a datum's, `analyse`).
  await hifiWorker().evaluate(() => {
    const h = self.ridelabHost;
    const run = h.run.bind(h);
    h.run = (m, a) => {
      if (m !== 'analyse' && m !== 'designReports') return run(m, a);
      h.run = run;
      throw new WebAssembly.RuntimeError('unreachable');
    };
  });
  await page.fill('#ks-num', '21');
  await page.dispatchEvent('#ks-num', 'change');
  await settled(page, 50);
  assert.match(await banner(page), /HiFi worker stopped \(its core stopped: unreachable\) and was restarted\. 1 request was run again/);
  assert.equal(await page.evaluate(() => window.__ridelab.state.ks), 21000);
  const hifi = await page.evaluate(() => document.querySelector('#criteria tr[data-crit="bacc"] td[data-model="hifi"]').dataset.value);
  assert.ok(Number.isFinite(Number(hifi)), 'the HiFi column is current');
  await page.screenshot({ path: path.join(OUT, 'hostile-worker.png') });

  // An error the worker does not catch: the same.
  await hifiWorker().evaluate(() => {
    const on = self.onmessage;
    self.onmessage = (ev) => {
      if (ev.data.method !== 'analyse' && ev.data.method !== 'designReports') return on(ev);
      self.onmessage = on;
      throw new Error('boom');
    };
  });
  await page.fill('#ks-num', '22');
  await page.dispatchEvent('#ks-num', 'change');
  await settled(page, 50);
  assert.match(await banner(page), /HiFi worker stopped \(.*boom\) and was restarted/);
  assert.equal(await page.evaluate(() => window.__ridelab.state.ks), 22000);
  await context.close();
});

test('authored lessons are saved as they are edited, listed under "Your lessons", and survive a reload', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  await page.keyboard.press('l');
  await page.click('#lesson-new');
  await page.waitForSelector('#lesson-edit:not([hidden])');
  await page.fill('#le-title', 'Damping for year 2');
  await page.fill('#le-question', 'What does more damping do?');
  assert.equal(await page.evaluate(() => { const e = new Event('beforeunload', { cancelable: true }); window.dispatchEvent(e); return e.defaultPrevented; }), false,
    'saved: leaving asks nothing');
  await page.reload();
  await page.waitForFunction(() => window.__ridelab && window.__ridelab.ready, null, { timeout: 30_000 });
  await page.keyboard.press('l');
  const own = page.locator('#lesson-own button[data-own]');
  await own.first().waitFor();
  assert.match(await own.first().textContent(), /Damping for year 2 \(1 step/);
  await page.screenshot({ path: path.join(OUT, 'hostile-lesson-list.png') });
  await own.first().click();
  await page.waitForFunction(() => document.getElementById('lesson-title').textContent === 'Damping for year 2');
  assert.match(await text(page, 'lesson-question'), /What does more damping do\?/);

  // Storage fails: said on screen, leaving asks first, another lesson asks before it replaces it.
  await page.evaluate(() => {
    Storage.prototype.setItem = () => {
      throw new DOMException('full', 'QuotaExceededError');
    };
  });
  await page.click('#lesson-edit-toggle');
  await page.fill('#le-question', 'What does much more damping do?');
  assert.match(await text(page, 'lesson-msg'), /Not saved in this browser: this browser's storage for the page is full\. "Download \(JSON\)" keeps it/);
  await page.screenshot({ path: path.join(OUT, 'hostile-lesson-unsaved.png') });
  assert.equal(await page.evaluate(() => { const e = new Event('beforeunload', { cancelable: true }); window.dispatchEvent(e); return e.defaultPrevented; }), true,
    'unsaved: leaving asks first');
  let asked = '';
  page.once('dialog', (d) => {
    asked = d.message();
    d.dismiss();
  });
  await page.click('#lesson-menu');
  await page.click('#lesson-shipped button[data-lesson="comfort"]');
  await page.waitForTimeout(200);
  assert.match(asked, /Damping for year 2" is not saved in this browser/);
  assert.equal(await text(page, 'lesson-title'), 'Lessons', 'the list stays; the unsaved lesson was not replaced');
  // Downloaded as a file: nothing is lost by leaving any more.
  page.once('dialog', (d) => d.accept());
  await page.click('#lesson-own button[data-own]');
  await page.waitForFunction(() => document.getElementById('lesson-title').textContent === 'Damping for year 2');
  await page.click('#lesson-edit-toggle');
  await page.fill('#le-question', 'What does much more damping do?');
  assert.equal(await page.evaluate(() => { const e = new Event('beforeunload', { cancelable: true }); window.dispatchEvent(e); return e.defaultPrevented; }), true);
  await page.click('#lesson-export');
  assert.match(await text(page, 'lesson-msg'), /Downloaded as ridelab-lesson-damping-for-year-2\.json; this browser still could not store it/);
  assert.equal(await page.evaluate(() => { const e = new Event('beforeunload', { cancelable: true }); window.dispatchEvent(e); return e.defaultPrevented; }), false,
    'downloaded: leaving asks nothing');
  assert.deepEqual(log.errors, []);
  await context.close();
});

test('a lesson link stays in the address bar while its lesson is open, so a reload opens it again', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open('#lesson=comfort');
  await page.waitForFunction(() => document.getElementById('lesson').dataset.ready === 'true', null, { timeout: 30_000 });
  await settled(page, 300);
  assert.equal(await page.evaluate(() => location.hash), '#lesson=comfort');
  await page.click('#lesson-next');
  await page.waitForFunction(() => document.getElementById('lesson').dataset.ready === 'true', null, { timeout: 30_000 });
  await settled(page, 300);
  assert.equal(await page.evaluate(() => location.hash), '#lesson=comfort', 'a step keeps it');
  await page.reload();
  await page.waitForFunction(() => document.getElementById('lesson-title').textContent === 'Comfort against road holding', null, { timeout: 30_000 });
  await page.click('#lesson-close');
  await page.waitForFunction(() => location.hash.startsWith('#car='), null, { timeout: 5_000 });
  assert.deepEqual(log.errors, []);
  await context.close();
});

test('a new build takes over only after its page booted: the old cache stays until then, and authored lessons survive', { timeout: TIMEOUT }, async (t) => {
  const root = fs.mkdtempSync(path.join(os.tmpdir(), 'ridelab-hostile-'));
  fs.cpSync(DIST, root, { recursive: true });
  let srv = await startServer(root);
  const port = new URL(srv.url).port;
  const { page, context } = await openPage(suite.browser, srv.url, { width: 1280, height: 720 });
  t.after(async () => {
    await context.close().catch(() => {});
    await srv.close().catch(() => {});
    fs.rmSync(root, { recursive: true, force: true });
  });
  await settled(page, 50);
  await page.waitForFunction(() => navigator.serviceWorker && navigator.serviceWorker.controller, null, { timeout: 30_000 });
  await page.keyboard.press('l');
  await page.click('#lesson-new');
  await page.fill('#le-title', 'Kept across builds');
  const id1 = buildId(root);
  // (A statement, not a comment: the stamp minifies the scripts first, www/minify.mjs.)
  fs.appendFileSync(path.join(root, 'js/format.js'), "\nexport const NEXT_BUILD = 'the next build';\n");
  fs.copyFileSync(path.join(ROOT, 'www/sw.js'), path.join(root, 'sw.js'));
  execFileSync(process.execPath, [path.join(ROOT, 'www/sw-stamp.mjs'), root]);
  const id2 = buildId(root);
  await srv.close();
  srv = await startServer(root, Number(port));
  await page.reload();
  await page.waitForFunction(() => /new version/.test(document.getElementById('banner-text').textContent), null, { timeout: 30_000 });
  await Promise.all([page.waitForEvent('load'), page.click('#banner-action')]);
  const atLoad = await page.evaluate(async () => (await caches.keys()).filter((k) => k.startsWith('ridelab-')).sort());
  assert.deepEqual(atLoad, [`ridelab-${id1}`, `ridelab-${id2}`].sort(), 'the old build\'s cache stays until the new page has booted');
  await page.waitForFunction(() => window.__ridelab && window.__ridelab.ready, null, { timeout: 30_000 });
  // (An async predicate's promise is truthy at once: poll in the page instead.)
  await page.evaluate(async () => {
    const t0 = performance.now();
    while ((await caches.keys()).filter((k) => k.startsWith('ridelab-')).length !== 1 && performance.now() - t0 < 10_000) {
      await new Promise((r) => setTimeout(r, 50));
    }
  });
  assert.deepEqual(await page.evaluate(async () => (await caches.keys()).filter((k) => k.startsWith('ridelab-'))), [`ridelab-${id2}`]);
  await page.keyboard.press('l');
  assert.match(await page.locator('#lesson-own button[data-own]').first().textContent(), /Kept across builds/);
});

/**
 * The page's numeric fields: id, the message beside it, what names it in the message, and
 * the field set first (the other end of a band).
 */
const FIELDS = [
  ['ks-num', 'msg-ks', /^(Spring )?Ks\b/], ['cs-num', 'msg-cs', /^(Damper )?Cs\b/], ['speed', 'msg-speed', /^speed\b/i],
  ['sws-limit', 'msg-swsLimit', /^SWS limit\b/],
  ['ks-min', 'msg-box', /Design box|Lowest Ks of the design box/], ['ks-max', 'msg-box', /Design box|Highest Ks of the design box/],
  ['cs-min', 'msg-box', /Design box|Lowest Cs of the design box/], ['cs-max', 'msg-box', /Design box|Highest Cs of the design box/],
  ['bb-lo', 'msg-bounceBand', /Bounce band|body-bounce/i, ['bb-hi', '1.5']], ['db-lo', 'msg-dampingBand', /Damping band|damping ratio|Damping-ratio band/i, ['db-hi', '0.5']],
];

test('every numeric field given 0, a negative, 1e308, NaN or a far value: a finite result or a message naming the field, the last good state kept', { timeout: 600_000 }, async () => {
  const { page, context, log } = await open();
  const set = (id, v) => page.evaluate(([i, x]) => {
    const el = document.getElementById(i);
    el.value = x;
    el.dispatchEvent(new Event('change', { bubbles: true }));
  }, [id, v]);
  const seen = [];
  for (const [id, msgId, names, first] of FIELDS) {
    if (first) await set(...first);
    for (const v of ['0', '-5', '1e308', 'NaN', '123456789']) {
      const before = await state(page);
      await set(id, v);
      await settled(page, 20);
      const after = await state(page);
      const r = await page.evaluate(([m]) => ({
        msg: document.getElementById(m).textContent,
        ks: document.getElementById('ks-range').value,
        cs: document.getElementById('cs-range').value,
      }), [msgId]);
      const changed = JSON.stringify(after) !== JSON.stringify(before);
      if (changed) {
        assert.ok(Object.values(after).flat().every((x) => typeof x !== 'number' || Number.isFinite(x)), `${id}=${v}: a finite state`);
        assert.equal(r.msg, '', `${id}=${v}: applied, no message`);
      } else {
        assert.match(r.msg, names, `${id}=${v}: refused with a message naming the field: ${r.msg}`);
        assert.deepEqual(after, before, `${id}=${v}: the last good state kept`);
      }
      assert.equal(Number(r.ks), after.ks / 1000, `${id}=${v}: the Ks slider agrees with the state`);
      assert.equal(Number(r.cs), after.cs / 1000, `${id}=${v}: the Cs slider agrees with the state`);
      seen.push(`${id}=${v}: ${changed ? 'applied' : r.msg}`);
      fs.writeFileSync(path.join(OUT, 'hostile-fields.txt'), seen.join('\n') + '\n');
      await noNaN(page);
    }
    // Back to the defaults for the next field.
    await page.evaluate(() => (location.hash = '#ks=19960'));
    await page.waitForFunction(() => window.__ridelab.state.ks === 19960 && window.__ridelab.state.speed === 20);
    await settled(page, 20);
  }
  assert.deepEqual(log.errors, []);
  await context.close();
});

test('the Time tab\'s fields given hostile numbers: a run with a finite result, or a message naming the field', { timeout: 600_000 }, async () => {
  const { page, context, log } = await open();
  await page.click('#tab-time');
  const run = async (fields) => {
    const r = await page.evaluate(async (fs) => {
      for (const id of ['tp-seed', 'tp-bump', 'tp-rebound', 'tp-knee', 'tp-bump-high', 'tp-rebound-high']) document.getElementById(id).value = id === 'tp-seed' ? '1' : '';
      for (const [id, v] of Object.entries(fs)) document.getElementById(id).value = v;
      for (const m of document.querySelectorAll('#panel-time .msg')) m.textContent = '';
      document.getElementById('tp-status').textContent = '';
      document.getElementById('tp-run').click();
      for (let k = 0; k < 400 && /Simulating/.test(document.getElementById('tp-status').textContent); k++) await new Promise((res) => setTimeout(res, 25));
      return {
        msgs: [...document.querySelectorAll('#panel-time .msg')].map((m) => m.textContent).filter(Boolean),
        status: document.getElementById('tp-status').textContent,
      };
    }, fields);
    return r;
  };
  const seen = [];
  const cases = [
    ['tp-seed', {}, /^Seed\b/], ['tp-bump', { 'tp-rebound': '2' }, /^Bump\b|bump/], ['tp-rebound', { 'tp-bump': '2' }, /^Rebound\b|rebound/],
    ['tp-knee', { 'tp-bump': '2', 'tp-rebound': '2', 'tp-bump-high': '1', 'tp-rebound-high': '1' }, /^Knee\b|knee/],
    ['tp-bump-high', { 'tp-bump': '2', 'tp-rebound': '2', 'tp-knee': '0.1', 'tp-rebound-high': '1' }, /^Bump above\b|bump/],
  ];
  for (const [id, others, names] of cases) {
    for (const v of ['0', '-5', '1e308', 'NaN', '123456789']) {
      const r = await run({ ...others, [id]: v });
      seen.push(`${id}=${v}: ${r.msgs.join(' | ') || r.status}`);
      if (r.msgs.length) assert.ok(r.msgs.some((m) => names.test(m)), `${id}=${v}: the message names the field: ${r.msgs}`);
      else assert.match(r.status, /^Done in/, `${id}=${v}: ran: ${r.status}`);
      await noNaN(page);
    }
  }
  fs.writeFileSync(path.join(OUT, 'hostile-time-fields.txt'), seen.join('\n') + '\n');
  assert.deepEqual(log.errors, []);
  await context.close();
});

test('the car editor\'s fields given hostile numbers: applied with finite results, or a message beside the field', { timeout: 600_000 }, async () => {
  const { page, context, log } = await open();
  await page.click('#tab-car');
  const ids = await page.evaluate(() => [...document.querySelectorAll('#car-fields input[data-path]')].map((i) => i.id));
  assert.ok(ids.length >= 10, `${ids.length} car fields`);
  const seen = [];
  for (const id of ids) {
    for (const v of ['0', '-5', '1e308', 'NaN', '123456789']) {
      const before = await state(page);
      const r = await page.evaluate(async ([i, x]) => {
        const el = document.getElementById(i);
        const was = el.value;
        el.value = x;
        document.getElementById('car-apply').click();
        await new Promise((res) => setTimeout(res, 60));
        const out = { was, msg: document.getElementById(`msg-${i}`).textContent, other: document.getElementById('msg-carEditor')?.textContent || '' };
        el.value = was;
        return out;
      }, [id, v]);
      await settled(page, 20);
      const after = await state(page);
      const changed = JSON.stringify(after) !== JSON.stringify(before);
      seen.push(`${id}=${v}: ${changed ? 'applied' : r.msg || r.other}`);
      if (changed) assert.ok(Object.values(after).flat().every((x) => typeof x !== 'number' || Number.isFinite(x)), `${id}=${v}: finite`);
      else if (Number(r.was) !== Number(v)) {
        assert.ok(r.msg !== '', `${id}=${v}: a message beside the field (${r.other})`);
        assert.doesNotMatch(r.msg.replace(/'[^']*'/g, ''), /null|undefined|NaN|Infinity|line \d+ column/, `${id}=${v}: in plain words: ${r.msg}`);
      }
      await noNaN(page);
    }
    fs.writeFileSync(path.join(OUT, 'hostile-car-fields.txt'), seen.join('\n') + '\n');
  }
  assert.deepEqual(log.errors, []);
  await context.close();
});
