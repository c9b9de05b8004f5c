// Headless Chromium for the tests: the system browser (TOOLCHAIN.md), driven by
// playwright-core. Playwright gives every launch a fresh temporary profile
// (its own --user-data-dir).
import { chromium } from 'playwright-core';

export const CHROMIUM = process.env.CHROMIUM || '/usr/bin/chromium';

export const FLAGS = [
  '--no-sandbox',
  '--disable-gpu',
  '--disable-quic',
  '--no-first-run',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
];

export function launch() {
  return chromium.launch({ executablePath: CHROMIUM, headless: true, args: FLAGS });
}

/**
 * Opens `url` in a fresh browser context (a `touch` phone or tablet if asked; the tour
 * taken unless `tour`) and records console errors, page errors and requests to any host
 * other than the local server; resolves when the page reports ready.
 */
export async function openPage(browser, url, { width = 1400, height = 1000, dpr = 1, downloads = false, touch = false, tour = false } = {}) {
  const context = await browser.newContext({
    viewport: { width, height },
    deviceScaleFactor: dpr,
    acceptDownloads: downloads,
    hasTouch: touch,
    isMobile: touch,
  });
  // A fresh profile shows the tour on the first visit; tests that are not about it
  // start with it taken (a returning visitor).
  if (!tour) await context.addInitScript(() => localStorage.setItem('ridelab.tourDone', '1'));
  const page = await context.newPage();
  const log = { errors: [], foreign: [] };
  page.on('console', (m) => {
    if (m.type() === 'error') log.errors.push(m.text());
  });
  page.on('pageerror', (e) => log.errors.push(`pageerror: ${e.message}`));
  page.on('request', (r) => {
    const u = new URL(r.url());
    if (!['data:', 'blob:'].includes(u.protocol) && u.hostname !== '127.0.0.1') log.foreign.push(r.url());
  });
  await page.goto(url);
  await page.waitForFunction(() => window.__ridelab && window.__ridelab.ready, null, { timeout: 30_000 });
  return { page, context, log };
}

/** Waits until every view shows the current state, then `extraMs` more. */
export async function settled(page, extraMs) {
  await page.waitForFunction(() => window.__ridelab.isSettled(), null, { timeout: 30_000 });
  await page.waitForTimeout(extraMs);
}
