// The robust design in the page (issue #16): a cases file applied through the Car & road
// tab's editor gives robust maps and a robust front whose numbers are `ridelab map --cases`'s
// and `ridelab optimize --cases --json`'s; a bad field is named and the last good state
// stays; the link carries the cases.
//   trunk build --release --offline && RIDELAB_CLI=target/debug/ridelab node --test tests/e2e/robust.test.mjs
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { openPage, settled } from './browser.mjs';
import { useSuite, assertClean, ROOT, OUT } from './harness.mjs';

const suite = useSuite();
const CAR = path.join(ROOT, 'assets/cars/sedan.json');
const CASES = {
  load_cases: [{ name: 'driver only', mass: 0 }, { name: 'fully laden', mass: 350, x: -0.3, y: 0.4, z: 0.1, weight: 2 }],
  operating: [{ class: 'B', speed: 15 }, { class: 'B', speed: 20, weight: 2 }, { class: 'A', speed: 30 }],
  combine: 'worst',
};

function cli(args) {
  const candidates = [process.env.RIDELAB_CLI, path.join(ROOT, 'target/debug/ridelab'), path.join(ROOT, 'target/release/ridelab')];
  const c = candidates.filter(Boolean).find((x) => fs.existsSync(x));
  assert.ok(c, 'the native CLI is built (cargo build -p ridelab)');
  const file = path.join(OUT, 'robust-cases.json');
  fs.writeFileSync(file, JSON.stringify(CASES));
  return JSON.parse(execFileSync(c, [...args, '--cases', file, '--car', CAR, '--class', 'B', '--speed', '20', '--json'], { encoding: 'utf8' }));
}

const rel = (a, b) => Math.abs(a / b - 1);

async function applyCases(page, text) {
  await page.evaluate(() => {
    const tab = document.getElementById('tab-car');
    if (tab.getAttribute('aria-selected') !== 'true') tab.click();
    document.getElementById('robust').open = true;
  });
  await page.fill('#rb-text', text);
  await page.click('#rb-apply');
  await settled(page, 250);
}

test('robust maps, front and per-case pick are the CLI\'s; a bad field is named; the link carries the cases', async () => {
  const { page, context, log } = await openPage(suite.browser, suite.srv.url, { width: 1280, height: 720 });
  await settled(page, 200);
  await applyCases(page, JSON.stringify(CASES, null, 1));
  const st = await page.evaluate(() => ({ state: window.__ridelab.state, desc: window.__ridelab.desc }));
  assert.equal(st.desc.cases.length, 6);
  assert.equal(JSON.parse(st.state.cases).operating.length, 3);
  assert.match(await page.textContent('#maps-model'), /LoFi, robust \(worst of 6 cases\)/);
  assert.match(await page.textContent('#h-objective'), /LoFi, robust: worst of 6 cases/);
  assert.match(await page.textContent('#map-status'), /every case, robust \(worst of 6 cases\)/);
  // The HiFi front (issue #13) with cases is the robust one: `ridelab optimize --cases
  // --evaluator full` with the plane's STM, every point to 1e-9; the line under the plane
  // judges the LoFi's robust front against it.
  const hopt = cli(['optimize', '--evaluator', 'full', '--method', 'stm', '--grid', '61', '--levels', '2']);
  const hf = await page.evaluate(() => window.__ridelab.objPlane.data.hifi);
  assert.ok(hf && !hf.error, hf && hf.error);
  assert.equal(hf.front.study.front.length, hopt.front.length);
  hf.front.study.front.forEach((p, k) => ['ks', 'cs', 'bacc', 'dtl'].forEach((c) => assert.ok(rel(p[c], hopt.front[k][c]) < 1e-9, `HiFi front point ${k} ${c}`)));
  assert.ok(rel(hf.front.study.hypervolume, hopt.hypervolume) < 1e-9, 'HiFi robust hypervolume');
  assert.ok(rel(hf.front.study.pick.ks, hopt.pick.ks) < 1e-9 && rel(hf.front.study.pick.cs, hopt.pick.cs) < 1e-9, 'HiFi robust pick');
  assert.equal(hf.hifiRuns, hopt.evaluations + 6);
  assert.equal(hf.plane.model, 'robust');
  assert.match(await page.textContent('#op-hifi-status'), /HiFi runs\. LoFi's robust front \(12 runs\): [\d.]+ % of its hypervolume/);

  // A map cell against `ridelab map --cases` on a 2 x 2 grid through that cell's centre
  // and its neighbour's (the page's cells: ks_i = 10000 + (i + 1/2) 30000 / 160 N/m).
  const [i, j] = [40, 30];
  const ks = (k) => 10000 + ((k + 0.5) * 30000) / 160;
  const cs = (k) => 500 + ((k + 0.5) * 3500) / 120;
  const want = cli(['map', '--model', 'quarter', '--ks-range', `${ks(i)}:${ks(i + 1)}:2`, '--cs-range', `${cs(j)}:${cs(j + 1)}:2`]);
  const got = await page.evaluate(([i, j]) => {
    const m = window.__ridelab.maps;
    const n = m.nx * m.ny;
    const at = (ii, jj) => jj * m.nx + ii;
    return [[i, j], [i + 1, j], [i, j + 1], [i + 1, j + 1]].map(([a, b]) => ({
      v: [0, 1, 2].map((c) => m.values[c * n + at(a, b)]), broken: m.broken[at(a, b)],
    }));
  }, [i, j]);
  got.forEach((g, k) => {
    ['bacc', 'dtl', 'sws'].forEach((c, ci) => assert.ok(rel(g.v[ci], want[c][k]) < 1e-9, `${c} cell ${k}: ${g.v[ci]} vs ${want[c][k]}`));
    assert.equal(g.broken, want.feasibility.mask[k], `mask cell ${k}`);
  });

  // The maps' captions give the robust map's value at the design: near that cell's centre,
  // the CLI's robust map through the design (the caption to its 4 digits, the value
  // behind it to 1e-9).
  for (const [id, v] of [['#ks-num', ks(i) / 1000], ['#cs-num', cs(j) / 1000]]) {
    await page.fill(id, String(v));
    await page.press(id, 'Enter');
  }
  await settled(page, 200);
  const at = await page.evaluate(() => ({
    design: window.__ridelab.state.ks, csAt: window.__ridelab.state.cs, md: window.__ridelab.mapDesign,
    captions: [...document.querySelectorAll('.map-panel .at')].map((e) => e.textContent),
  }));
  assert.equal(at.design, ks(i));
  // The Cs box keeps 7 digits: the CLI's map through the design as the page holds it.
  const here = cli(['map', '--model', 'quarter', '--ks-range', `${at.design}:${at.design + 1}:2`, '--cs-range', `${at.csAt}:${at.csAt + 1}:2`]);
  ['bacc', 'dtl', 'sws'].forEach((c) => assert.ok(rel(at.md[c], here[c][0]) < 1e-9, `design's ${c} on the robust map: ${at.md[c]} vs ${here[c][0]}`));
  assert.match(at.captions[0], new RegExp(`${here.bacc[0].toPrecision(4)} m/s²`), at.captions[0]);
  assert.match(at.captions[2], new RegExp(`${(1000 * here.sws[0]).toPrecision(4)} mm`), at.captions[2]);

  // The front and the per-case pick against `ridelab optimize --cases --json`.
  const opt = cli(['optimize', '--evaluator', 'quarter', '--method', 'stm', '--grid', '61', '--levels', '2']);
  const fr = await page.evaluate(() => window.__ridelab.front);
  assert.ok(!fr.error, fr.error);
  assert.ok(rel(fr.study.pick.ks, opt.pick.ks) < 1e-9 && rel(fr.study.pick.cs, opt.pick.cs) < 1e-9, 'pick design');
  assert.ok(rel(fr.study.hypervolume, opt.hypervolume) < 1e-9, 'hypervolume');
  const rows = await page.evaluate(() => [...document.querySelectorAll('#op-cases tr[data-model]')].map((tr) => ({
    k: Number(tr.dataset.case), model: tr.dataset.model,
    v: [...tr.querySelectorAll('td[data-value]')].map((td) => Number(td.dataset.value)),
    pct: [...tr.querySelectorAll('td[data-pct]')].map((td) => Number(td.dataset.pct)),
  })));
  assert.equal(rows.length, 12, 'two rows (LoFi, HiFi) per case');
  for (const r of rows) {
    const h = opt.cases[r.k].hifi_recheck;
    const c = r.model === 'lofi' ? h.predicted : h.rechecked;
    const p = r.model === 'lofi' ? h.predicted_change_percent : h.rechecked_change_percent;
    ['bacc', 'dtl', 'sws'].forEach((key, ci) => {
      assert.ok(rel(r.v[ci], c[key]) < 1e-9, `case ${r.k} ${r.model} ${key}`);
      assert.ok(Math.abs(r.pct[ci] - p[ci]) <= 1e-9 * Math.max(1, Math.abs(p[ci])), `case ${r.k} ${r.model} ${key} %`);
    });
  }
  const broken = await page.evaluate(() => [...document.querySelectorAll('#op-cases .case-broken')].map((e) => e.dataset.broken));
  assert.deepEqual(broken, opt.cases.map((c) => c.broken.join(',')));
  await page.screenshot({ path: path.join(OUT, 'robust-drawer-1280.png') });

  // A bad field: the message names it and the state stays.
  const bad = JSON.stringify({ ...CASES, load_cases: [CASES.load_cases[0], { ...CASES.load_cases[1], mass: -5000 }] });
  await applyCases(page, bad);
  assert.match(await page.textContent('#msg-cases'), /cases\.load_cases\[1\]\.mass/);
  assert.equal(await page.evaluate(() => window.__ridelab.state.cases), st.state.cases, 'last good state kept');

  // One case on the maps: case 4's name in the heading.
  await page.selectOption('#rb-case', '4');
  await settled(page, 250);
  assert.match(await page.textContent('#maps-model'), /case 4: fully laden \/ B at 20 m\/s/);
  const hash = await page.evaluate(() => location.hash);
  assert.match(hash, /cases=/);
  assert.match(hash, /case=4/);
  await page.evaluate(() => document.getElementById('drawer-close').click());
  await page.screenshot({ path: path.join(OUT, 'robust-maps-1280.png') });
  assertClean(log);
  await context.close();

  // The link reproduces them.
  const again = await openPage(suite.browser, suite.srv.url + hash, { width: 390, height: 844 });
  await settled(again.page, 200);
  const s2 = await again.page.evaluate(() => window.__ridelab.state);
  assert.equal(s2.cases, st.state.cases);
  assert.equal(s2.case, '4');
  assert.match(await again.page.textContent('#maps-model'), /case 4: fully laden/);
  await again.page.screenshot({ path: path.join(OUT, 'robust-390.png'), fullPage: false });
  assertClean(again.log);
  await again.context.close();
});

test('a car file with load cases (as `ridelab --car FILE`) makes the design robust over them; its maps are `ridelab map --car FILE`\'s', async () => {
  const { page, context, log } = await openPage(suite.browser, suite.srv.url, { width: 1280, height: 720 });
  await settled(page, 200);
  const car = JSON.parse(fs.readFileSync(CAR, 'utf8'));
  const file = { ...car, name: 'Sedan with a roof box', load_cases: [{ name: 'driver only', mass: 0 }, { name: 'roof box', mass: 60, x: -0.2, z: 0.9 }] };
  const carPath = path.join(OUT, 'robust-car.json');
  fs.writeFileSync(carPath, JSON.stringify(file));
  await page.evaluate(() => document.getElementById('tab-car').click());
  await page.setInputFiles('#car-file', { name: 'roofbox.json', mimeType: 'application/json', buffer: Buffer.from(JSON.stringify(file)) });
  await settled(page, 250);
  const st = await page.evaluate(() => ({ state: window.__ridelab.state, desc: window.__ridelab.desc, maps: window.__ridelab.maps }));
  assert.deepEqual(JSON.parse(st.state.cases).load_cases, file.load_cases.map((c) => ({ x: 0, y: 0, z: 0, weight: 1, ...c })), 'the file\'s load cases in the cases file');
  assert.equal(st.desc.cases.length, 2);
  assert.match(await page.textContent('#maps-model'), /LoFi, robust \(worst of 2 cases\)/);
  assert.match(await page.textContent('#note-car'), /Robust over its 2 load cases/);
  // The CLI reads the same file with no cases file: the robust map over its load cases.
  const c = [process.env.RIDELAB_CLI, path.join(ROOT, 'target/debug/ridelab')].filter(Boolean).find((x) => fs.existsSync(x));
  const [i, j] = [100, 70];
  const ks = 10000 + ((i + 0.5) * 30000) / 160;
  const cs = 500 + ((j + 0.5) * 3500) / 120;
  const want = JSON.parse(execFileSync(c, ['map', '--model', 'quarter', '--car', carPath, '--class', 'B', '--speed', '20', '--json',
    '--ks-range', `${ks}:${ks + 1}:2`, '--cs-range', `${cs}:${cs + 1}:2`], { encoding: 'utf8' }));
  const n = st.maps.nx * st.maps.ny;
  const k = j * st.maps.nx + i;
  ['bacc', 'dtl', 'sws'].forEach((name, ci) => assert.ok(rel(st.maps.values[ci * n + k], want[name][0]) < 1e-9, `${name}: ${st.maps.values[ci * n + k]} vs ${want[name][0]}`));
  assertClean(log);
  await context.close();
});
