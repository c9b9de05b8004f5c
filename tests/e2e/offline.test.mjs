// Offline after the first visit: the service worker (www/sw.js, stamped at build time by
// www/sw-stamp.mjs) caches the build; with the server gone a reload still shows and
// computes the page, and a new build replaces the cached one.
//
//   trunk build --release --offline && node --test tests/e2e/offline.test.mjs

import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { openPage, settled } from './browser.mjs';
import { startServer } from './server.mjs';
import { useSuite, assertClean, ROOT, DIST, OUT } from './harness.mjs';
import { buildFiles, buildId } from '../../www/sw-stamp.mjs';

const TIMEOUT = 180_000;
const suite = useSuite();

/** The page's offline state: the worker in control, and the RideLab caches with their sizes. */
function offlineState(page) {
  return page.evaluate(async () => {
    await navigator.serviceWorker.ready;
    const names = (await caches.keys()).filter((k) => k.startsWith('ridelab-'));
    const sizes = {};
    for (const n of names) sizes[n] = (await (await caches.open(n)).keys()).length;
    return { controlled: !!navigator.serviceWorker.controller, names, sizes };
  });
}

test('the build id is a hash of the build, and sw.js lists every file', () => {
  const sw = fs.readFileSync(path.join(DIST, 'sw.js'), 'utf8');
  const id = /const BUILD = '([0-9a-f]{16})';/.exec(sw);
  assert.ok(id, 'sw.js is stamped with a build id');
  assert.equal(id[1], buildId(DIST), 'the id is the hash of the files of this build');
  const files = JSON.parse(/const FILES = (\[.*\]);/.exec(sw)[1]);
  assert.deepEqual(files, ['./', ...buildFiles(DIST)]);
  for (const f of ['index.html', 'ridelab-first_bg.wasm', 'ridelab-first.js', 'ridelab_bg.wasm', 'ridelab.js', 'js/app.js', 'js/worker.js', 'style.css']) assert.ok(files.includes(f), f);
});

test('offline: load once, stop the server, reload: the page works and computes; a new build replaces the cache', { timeout: TIMEOUT }, async (t) => {
  // A copy of the build, so that a "new build" can be made from it below.
  const root = fs.mkdtempSync(path.join(os.tmpdir(), 'ridelab-offline-'));
  fs.cpSync(DIST, root, { recursive: true });
  let srv = await startServer(root);
  const port = new URL(srv.url).port;
  const { page, context, log } = await openPage(suite.browser, srv.url, { width: 1280, height: 720 });
  // Closed whatever happens below (an open server would keep the test process alive).
  t.after(async () => {
    await context.close().catch(() => {});
    await srv.close().catch(() => {});
    fs.rmSync(root, { recursive: true, force: true });
  });
  await settled(page, 100);
  await page.waitForFunction(() => navigator.serviceWorker && navigator.serviceWorker.controller, null, { timeout: 30_000 });
  const first = await offlineState(page);
  const id1 = /const BUILD = '([0-9a-f]{16})';/.exec(fs.readFileSync(path.join(root, 'sw.js'), 'utf8'))[1];
  assert.deepEqual(first.names, [`ridelab-${id1}`], 'one cache, named by the build');
  assert.equal(first.sizes[`ridelab-${id1}`], buildFiles(root).length + 1, 'every file of the build cached (and ./)');
  const online = await page.evaluate(() => window.__ridelab.state);

  // The server goes away: a reload comes from the cache, and everything computes.
  await srv.close();
  await page.reload();
  await page.waitForFunction(() => window.__ridelab && window.__ridelab.ready, null, { timeout: 30_000 });
  await settled(page, 150);
  assert.deepEqual(await page.evaluate(() => window.__ridelab.state), online, 'the same page offline');
  const before = await page.evaluate(() => document.querySelector('#criteria tr[data-crit="bacc"] td[data-model="hifi"]').dataset.value);
  await page.focus('#ks-range');
  for (let i = 0; i < 5; i++) await page.keyboard.press('ArrowRight');
  await settled(page, 150);
  const after = await page.evaluate(() => ({
    ks: window.__ridelab.state.ks,
    hifi: document.querySelector('#criteria tr[data-crit="bacc"] td[data-model="hifi"]').dataset.value,
    maps: window.__ridelab.views.every((v) => v.data !== null),
    worker: document.getElementById('version').textContent,
  }));
  assert.equal(after.ks, 19960 + 500, 'the slider works offline');
  assert.notEqual(after.hifi, before, 'the HiFi readout follows offline');
  assert.ok(after.maps, 'the maps are drawn offline');
  assert.match(after.worker, /worker thread/, 'the workers started from the cache');
  await page.screenshot({ path: path.join(OUT, 'offline.png') });

  // A new build (one file changed, sw.js stamped again) served on the same origin. The
  // file is a module of js/ (style.css carries Trunk's integrity hash in index.html).
  // (A statement, not a comment: the stamp minifies the scripts first, www/minify.mjs.)
  fs.appendFileSync(path.join(root, 'js/format.js'), "\nexport const NEXT_BUILD = 'the next build';\n");
  fs.copyFileSync(path.join(ROOT, 'www/sw.js'), path.join(root, 'sw.js'));
  execFileSync(process.execPath, [path.join(ROOT, 'www/sw-stamp.mjs'), root]);
  const id2 = buildId(root);
  assert.notEqual(id2, id1, 'a changed file makes a new build id');
  srv = await startServer(root, Number(port));
  await page.reload();
  await page.waitForFunction(() => window.__ridelab && window.__ridelab.ready, null, { timeout: 30_000 });
  // The browser finds the new sw.js; it installs beside the old one and waits, and the
  // page (still the old build) offers to switch.
  await page.waitForFunction(() => /new version/.test(document.getElementById('banner-text').textContent), null, { timeout: 30_000 });
  const both = await page.evaluate(async () => (await caches.keys()).filter((k) => k.startsWith('ridelab-')).sort());
  assert.deepEqual(both, [`ridelab-${id1}`, `ridelab-${id2}`].sort(), 'the new build cached beside the old one');
  await Promise.all([page.waitForEvent('load'), page.click('#banner-action')]);
  await page.waitForFunction(() => window.__ridelab && window.__ridelab.ready, null, { timeout: 30_000 });
  // The old build's cache goes once the new page has booted (it tells its worker).
  await page.waitForFunction(async () => (await caches.keys()).filter((k) => k.startsWith('ridelab-')).length === 1, null, { timeout: 10_000 });
  const names = await page.evaluate(async () => (await caches.keys()).filter((k) => k.startsWith('ridelab-')));
  assert.deepEqual(names, [`ridelab-${id2}`], 'the new build\'s cache replaced the old one');
  const js = await page.evaluate(() => fetch('js/format.js').then((r) => r.text()));
  assert.match(js, /the next build/, 'the new build is served');
  assertClean(log);
});
