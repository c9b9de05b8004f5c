// The page's "Download report" against `ridelab report` (issue #28): for ten cars and
// roads (the heavy sedan of the issue first, then nine drawn from a seeded generator
// inside the car editor's ranges), the page's HTML equals the CLI's byte for byte.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { openPage, settled } from './browser.mjs';
import { useSuite, assertClean, assertSameLines, ROOT, OUT } from './harness.mjs';

const suite = useSuite();
const cli = () => process.env.RIDELAB_CLI || path.join(ROOT, 'target/debug/ridelab');
const sedan = JSON.parse(fs.readFileSync(path.join(ROOT, 'assets/cars/sedan.json'), 'utf8'));

/** A seeded uniform generator on [0, 1) (mulberry32). */
function rng(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

/** The ten scenarios: [name, car JSON, class, speed m/s]. */
function scenarios() {
  const heavy = structuredClone(sedan);
  heavy.name = 'Heavy sedan';
  heavy.sprung_mass = 1600;
  heavy.front.unsprung_mass = 45;
  const out = [['heavy', heavy, 'C', 25]];
  const r = rng(28);
  const pick = (lo, hi) => +(lo + (hi - lo) * r()).toPrecision(4);
  for (let k = 1; k < 10; k++) {
    const car = structuredClone(sedan);
    car.name = `Random car ${k}`;
    car.sprung_mass = pick(900, 2200);
    car.front.unsprung_mass = pick(25, 60);
    car.rear.unsprung_mass = pick(25, 60);
    car.front.spring = pick(15000, 35000);
    car.front.damper = pick(800, 3000);
    out.push([`random${k}`, car, 'ABCD'[Math.floor(r() * 4)], pick(10, 30)]);
  }
  return out;
}

for (const [name, car, klass, speed] of scenarios()) {
  test(`report of ${name} (${car.name}, class ${klass} at ${speed} m/s): page = CLI byte for byte`, { timeout: 240_000 }, async () => {
    const carjson = JSON.stringify(car);
    const hash = '#' + new URLSearchParams({ car: 'custom', carjson, ks: car.front.spring, cs: car.front.damper, class: klass, speed }).toString();
    const { page, context, log } = await openPage(suite.browser, suite.srv.url + hash, { downloads: true });
    await settled(page, 100);
    await page.click('#tab-export');
    const [dl] = await Promise.all([page.waitForEvent('download', { timeout: 200_000 }), page.click('#report-html')]);
    const file = path.join(OUT, `report-page-${name}.html`);
    await dl.saveAs(file);
    const html = fs.readFileSync(file, 'utf8');
    const carFile = path.join(OUT, `report-car-${name}.json`);
    fs.writeFileSync(carFile, carjson);
    const dir = path.join(OUT, `report-cli-${name}`);
    execFileSync(cli(), ['report', '--car', carFile, '--class', klass, '--speed', String(speed), '--approach', 'rba-mul-rbf-mq', '--plan', 'ae:10', '--out', dir], { encoding: 'utf8', maxBuffer: 64 << 20, stdio: ['ignore', 'pipe', 'pipe'] });
    const want = fs.readFileSync(path.join(dir, 'report.html'), 'utf8');
    assertSameLines(html, want, 'page and CLI reports');
    assertClean(log);
    await context.close();
  });
}
