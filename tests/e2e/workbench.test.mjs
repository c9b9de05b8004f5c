// End-to-end tests of the workbench layout and its classroom features: the sliders, the
// three maps and the objective plane inside the first viewport at laptop and projector
// sizes (with every tab open too), phones and tablets without horizontal overflow and
// with touch on the maps, the keyboard on a focused map, projector mode, the colour-blind
// palette, the tour and the shortcuts, and the defects found on a walk through the page
// (issue #11), each with a test that failed before its fix.
//
//   trunk build --release --offline && npm run test:e2e

import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { openPage, settled } from './browser.mjs';
import { useSuite, assertClean, readZip, OUT } from './harness.mjs';

const TIMEOUT = 120_000;
const suite = useSuite();

async function open(hash = '', opts = {}) {
  const r = await openPage(suite.browser, suite.srv.url + hash, { width: 1280, height: 720, ...opts });
  await settled(r.page, 150);
  return r;
}

const settle = (page) => settled(page, 200);

/** The first set: the two sliders, their numeric fields, the three maps and the plane. */
const FIRST_SET = ['#ks-range', '#ks-num', '#cs-range', '#cs-num', '#map-bacc', '#map-dtl', '#map-sws', '#op-base', '#criteria'];

/** Bounding boxes of `sels` and the scroll position. */
function boxes(page, sels) {
  return page.evaluate((sels) => ({
    scrollX: window.scrollX,
    scrollY: window.scrollY,
    vw: window.innerWidth,
    vh: window.innerHeight,
    boxes: Object.fromEntries(sels.map((s) => {
      const r = document.querySelector(s).getBoundingClientRect();
      return [s, { x: r.x, y: r.y, w: r.width, h: r.height }];
    })),
  }), sels);
}

/** Every element of `sels` fully inside the viewport, with the page not scrolled. */
async function assertInView(page, sels, what) {
  const b = await boxes(page, sels);
  assert.equal(b.scrollY, 0, `${what}: scrollY`);
  assert.equal(b.scrollX, 0, `${what}: scrollX`);
  for (const [s, r] of Object.entries(b.boxes)) {
    assert.ok(r.w > 40 && r.h > 8, `${what}: ${s} has a size (${r.w} x ${r.h})`);
    assert.ok(r.x >= 0 && r.y >= 0 && r.x + r.w <= b.vw + 0.5 && r.y + r.h <= b.vh + 0.5,
      `${what}: ${s} inside the ${b.vw} x ${b.vh} viewport (${JSON.stringify(r)})`);
  }
  return b;
}

/** Distinct colours on canvas `id` (a drawn chart has many; a blank one has one). */
function colours(page, id) {
  return page.evaluate((id) => {
    const c = document.getElementById(id);
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    const set = new Set();
    for (let k = 0; k < d.length; k += 4) if (d[k + 3] > 0) set.add((d[k] << 16) | (d[k + 1] << 8) | d[k + 2]);
    return set.size;
  }, id);
}

/** The element at the centre of each of `sels` (not covered by anything else). */
function uncovered(page, sels) {
  return page.evaluate((sels) => sels.map((s) => {
    const el = document.querySelector(s);
    const r = el.getBoundingClientRect();
    const hit = document.elementFromPoint(r.x + r.width / 2, r.y + r.height / 2);
    return { s, ok: hit === el || el.parentElement.contains(hit) };
  }), sels);
}

test('the first set fills one screen at 1280 x 720, 1600 x 1000 and 1920 x 1080, every canvas drawn', { timeout: TIMEOUT }, async () => {
  for (const [width, height] of [[1280, 720], [1600, 1000], [1920, 1080]]) {
    const { page, context, log } = await open('', { width, height });
    await assertInView(page, FIRST_SET, `${width} x ${height}`);
    for (const id of ['map-bacc', 'map-dtl', 'map-sws', 'op-base']) {
      const n = await colours(page, id);
      assert.ok(n > 200, `${width} x ${height}: ${id} drawn (${n} colours)`);
    }
    // The three maps in one row, the readout's table not cut off.
    const tops = await page.evaluate(() => ['bacc', 'dtl', 'sws'].map((k) => document.getElementById(`map-${k}`).getBoundingClientRect().top));
    assert.ok(Math.max(...tops) - Math.min(...tops) < 1, `${width} x ${height}: maps in one row (${tops})`);
    const wrap = await page.evaluate(() => {
      const w = document.querySelector('.readout .table-wrap');
      return { scroll: w.scrollWidth, client: w.clientWidth };
    });
    assert.ok(wrap.scroll <= wrap.client, `${width} x ${height}: readout table fits (${wrap.scroll} > ${wrap.client})`);
    if (width === 1280) await page.screenshot({ path: path.join(OUT, 'workbench-1280.png') });
    if (width === 1600) await page.screenshot({ path: path.join(OUT, 'workbench-1600.png') });
    assertClean(log);
    await context.close();
  }
});

test('opening every tab at 1600 x 1000 keeps the first set in view and uncovered', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open('', { width: 1600, height: 1000 });
  const tabs = await page.$$eval('.tabs [role="tab"]', (ts) => ts.map((t) => t.id));
  assert.equal(tabs.length, 9);
  for (const id of tabs) {
    await page.click(`#${id}`);
    await page.waitForTimeout(150);
    assert.equal(await page.getAttribute(`#${id}`, 'aria-selected'), 'true');
    const panel = await page.getAttribute(`#${id}`, 'aria-controls');
    assert.equal(await page.isVisible(`#${panel}`), true, `${panel} shown`);
    await assertInView(page, FIRST_SET, `tab ${id}`);
    for (const u of await uncovered(page, ['#ks-range', '#cs-range', '#map-bacc-pick', '#map-dtl-pick', '#map-sws-pick', '#op-overlay'])) {
      assert.ok(u.ok, `tab ${id}: ${u.s} not covered by the drawer`);
    }
    const wrap = await page.evaluate(() => {
      const w = document.querySelector('.readout .table-wrap');
      return { scroll: w.scrollWidth, client: w.clientWidth };
    });
    assert.ok(wrap.scroll <= wrap.client, `tab ${id}: the readout table fits beside the drawer (${wrap.scroll} > ${wrap.client})`);
    if (id === 'tab-spectra') await page.screenshot({ path: path.join(OUT, 'workbench-1600-spectra.png') });
  }
  // The same tab again closes the drawer; Escape closes it too.
  await page.click(`#${tabs[tabs.length - 1]}`);
  assert.equal(await page.isVisible('#drawer'), false, 'clicking the open tab closes the drawer');
  await page.click('#tab-car');
  await page.keyboard.press('Escape');
  assert.equal(await page.isVisible('#drawer'), false, 'Escape closes the drawer');
  // At 1280 x 720 the drawer opens over the right part; the sliders and maps stay in view.
  const small = await open('', { width: 1280, height: 720 });
  await small.page.click('#tab-time');
  await assertInView(small.page, FIRST_SET, '1280 with the time tab');
  for (const u of await uncovered(small.page, ['#ks-range', '#cs-range', '#map-bacc-pick'])) assert.ok(u.ok, `1280: ${u.s} uncovered`);
  await small.page.screenshot({ path: path.join(OUT, 'workbench-1280-time.png') });
  assertClean(small.log);
  await small.context.close();
  assertClean(log);
  await context.close();
});

test('phones and tablets: no horizontal overflow, maps stacked, a touch drag on a map moves the design', { timeout: TIMEOUT }, async () => {
  for (const [width, height] of [[390, 844], [768, 1024]]) {
    const { page, context, log } = await open('', { width, height, touch: true, dpr: 2 });
    const o = await page.evaluate(() => ({ sw: document.documentElement.scrollWidth, iw: window.innerWidth }));
    assert.ok(o.sw <= o.iw, `${width} x ${height}: no horizontal overflow (${o.sw} > ${o.iw})`);
    const lefts = await page.evaluate(() => ['bacc', 'dtl', 'sws'].map((k) => document.getElementById(`map-${k}`).getBoundingClientRect()));
    assert.ok(lefts[1].top >= lefts[0].bottom - 1 && lefts[2].top >= lefts[1].bottom - 1, `${width}: maps stacked`);
    const fonts = await page.evaluate(() => getComputedStyle(document.querySelector('.readout td.num')).fontSize);
    assert.ok(parseFloat(fonts) >= 14, `readable readout text (${fonts})`);
    // Every tab's panel opens in the flow without widening the page.
    for (const id of ['tab-spectra', 'tab-time', 'tab-export', 'tab-car']) {
      await page.click(`#${id}`);
      await page.waitForTimeout(100);
      const w = await page.evaluate(() => document.documentElement.scrollWidth);
      assert.ok(w <= o.iw, `${width}: ${id} open, no overflow (${w})`);
    }
    if (width === 390) await page.screenshot({ path: path.join(OUT, 'phone-390.png'), fullPage: true });
    // A touch drag on the DTL map: touch start at 20 %, 30 % of its plot, end at 80 %, 70 %.
    await page.locator('#map-dtl-pick').scrollIntoViewIfNeeded();
    const r = await page.evaluate(() => {
      const b = document.getElementById('map-dtl-pick').getBoundingClientRect();
      return { x: b.x, y: b.y, w: b.width, h: b.height };
    });
    const at = (u, v) => ({ x: r.x + u * r.w, y: r.y + (1 - v) * r.h });
    const cdp = await context.newCDPSession(page);
    const touch = (type, p) => cdp.send('Input.dispatchTouchEvent', { type, touchPoints: p ? [{ x: p.x, y: p.y }] : [] });
    await touch('touchStart', at(0.2, 0.3));
    for (let i = 1; i <= 6; i++) await touch('touchMove', at(0.2 + 0.1 * i, 0.3 + (0.4 * i) / 6));
    await touch('touchEnd');
    await settle(page);
    const s = await page.evaluate(() => ({ ...window.__ridelab.state, box: window.__ridelab.desc.designBox }));
    const want = { ks: s.box.ks_min + 0.8 * (s.box.ks_max - s.box.ks_min), cs: s.box.cs_min + 0.7 * (s.box.cs_max - s.box.cs_min) };
    assert.ok(Math.abs(s.ks - want.ks) <= (s.box.ks_max - s.box.ks_min) / r.w + 10, `${width}: touch drag ks ${s.ks} (want ${want.ks})`);
    assert.ok(Math.abs(s.cs - want.cs) <= (s.box.cs_max - s.box.cs_min) / r.h + 5, `${width}: touch drag cs ${s.cs} (want ${want.cs})`);
    assertClean(log);
    await context.close();
  }
});

test('keyboard: arrow keys on a focused map step Ks and Cs with a visible focus ring; the URL follows', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  // "m" focuses the first map from the keyboard: the focus ring shows.
  await page.keyboard.press('m');
  const ring = await page.evaluate(() => {
    const el = document.activeElement;
    const cs = getComputedStyle(el);
    return { id: el.id, visible: el.matches(':focus-visible'), style: cs.outlineStyle, width: parseFloat(cs.outlineWidth) };
  });
  assert.equal(ring.id, 'map-bacc-pick');
  assert.ok(ring.visible && ring.style === 'solid' && ring.width >= 2, `focus ring ${JSON.stringify(ring)}`);
  const s0 = await page.evaluate(() => window.__ridelab.state);
  assert.deepEqual([s0.ks, s0.cs], [19960, 1290], 'the datum');
  const press = async (key, n = 1) => {
    for (let i = 0; i < n; i++) await page.keyboard.press(key);
    await settle(page);
    return page.evaluate(() => [window.__ridelab.state.ks, window.__ridelab.state.cs]);
  };
  assert.deepEqual(await press('ArrowRight'), [20060, 1290], 'Right: Ks + 0.1 kN/m');
  assert.match(page.url(), /ks=20060&cs=1290/, 'the URL follows');
  assert.deepEqual(await press('ArrowUp', 2), [20060, 1310], 'Up twice: Cs + 2 x 0.01 kNs/m');
  // Coarse steps (0.1 kNs/m, 1 kN/m) keep to their own grid through the datum.
  assert.deepEqual(await press('PageDown'), [20060, 1290], 'Page Down: down to the coarse grid, the datum\'s Cs');
  assert.deepEqual(await press('PageDown'), [20060, 1190], 'Page Down: Cs - 0.1 kNs/m');
  assert.deepEqual(await press('Shift+ArrowLeft'), [19960, 1190], 'Shift + Left: to the coarse grid, the datum\'s Ks');
  assert.deepEqual(await press('ArrowLeft', 9), [19060, 1190], 'nine fine steps left');
  assert.match(page.url(), /ks=19060&cs=1190/);
  // The slider steps the same grid and can sit exactly at the datum.
  await page.focus('#ks-range');
  await press('ArrowRight', 9);
  assert.equal(await page.evaluate(() => window.__ridelab.state.ks), 19960, 'the Ks slider lands on the datum');
  assert.equal(await page.inputValue('#ks-range'), '19.96', 'the slider sits exactly at 19.96 kN/m');
  await page.keyboard.press('d');
  await settle(page);
  assert.deepEqual(await page.evaluate(() => [window.__ridelab.state.ks, window.__ridelab.state.cs]), [19960, 1290], '"d": the datum');
  // "?" lists the shortcuts; Escape closes the list.
  await page.keyboard.press('?');
  assert.equal(await page.isVisible('#shortcuts'), true, 'the shortcut list');
  assert.match(await page.textContent('#shortcuts'), /Page Up/);
  await page.keyboard.press('Escape');
  assert.equal(await page.isVisible('#shortcuts'), false);
  assertClean(log);
  await context.close();
});

test('hover on a map reads Ks, Cs and the value; the pick button and a click on the front set the design', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  const r = await page.evaluate(() => {
    const b = document.getElementById('map-bacc-pick').getBoundingClientRect();
    return { x: b.x, y: b.y, w: b.width, h: b.height };
  });
  await page.mouse.move(r.x + 0.5 * r.w, r.y + 0.5 * r.h);
  const tip = await page.textContent('#map-bacc ~ .map-tip');
  const cell = await page.evaluate(() => {
    const v = window.__ridelab.views[0];
    const d = v.data;
    return d.shown[Math.floor(d.ny / 2) * d.nx + Math.floor(d.nx / 2)];
  });
  assert.match(tip, /Ks 25(\.0+)? kN\/m, Cs 2\.25 kNs\/m: BAcc [\d.]+ m\/s²/, tip);
  assert.ok(Math.abs(Number(/BAcc ([\d.]+)/.exec(tip)[1]) / cell - 1) < 1e-3, `hover value ${tip} = cell ${cell}`);
  // The pick button.
  await page.click('#to-pick');
  await settle(page);
  const pick = await page.evaluate(() => [window.__ridelab.front.study.pick.ks, window.__ridelab.front.study.pick.cs, window.__ridelab.state.ks, window.__ridelab.state.cs]);
  assert.deepEqual(pick.slice(2), pick.slice(0, 2), 'the design is the pick');
  // A click by the front selects the front point nearest the click (in screen px).
  const p0 = await page.evaluate(() => {
    const a = window.__ridelab;
    const front = a.front.study.front;
    const p = front[Math.floor(front.length / 3)];
    const [x, y] = a.objPlane.base.px(p.bacc, p.dtl);
    const b = document.getElementById('op-overlay').getBoundingClientRect();
    const cx = Math.round(b.x + x + 3);
    const cy = Math.round(b.y + y - 4);
    let best = null;
    let bestD = Infinity;
    for (const q of front) {
      const [qx, qy] = a.objPlane.base.px(q.bacc, q.dtl);
      const d = Math.hypot(b.x + qx - cx, b.y + qy - cy);
      if (d < bestD) [best, bestD] = [q, d];
    }
    return { x: cx, y: cy, ks: best.ks, cs: best.cs, d: bestD };
  });
  assert.ok(p0.d < 8, `the click is by the front (${p0.d} px)`);
  await page.mouse.click(p0.x, p0.y);
  await settle(page);
  assert.deepEqual(await page.evaluate(() => [window.__ridelab.state.ks, window.__ridelab.state.cs]), [p0.ks, p0.cs], 'a click selects the nearest front point');
  assertClean(log);
  await context.close();
});

test('projector mode at 1280 x 720: large type and the same layout, nothing cut off', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  await page.check('#projector');
  await page.waitForTimeout(300);
  await settle(page);
  assert.equal(await page.evaluate(() => getComputedStyle(document.documentElement).fontSize), '19px');
  assert.match(page.url(), /proj=1/);
  await assertInView(page, FIRST_SET, 'projector');
  const tops = await page.evaluate(() => ['bacc', 'dtl', 'sws'].map((k) => document.getElementById(`map-${k}`).getBoundingClientRect().top));
  assert.ok(Math.max(...tops) - Math.min(...tops) < 1, `projector: the SWS map stays in the row (${tops})`);
  const wrap = await page.evaluate(() => {
    const w = document.querySelector('.readout .table-wrap');
    return { scroll: w.scrollWidth, client: w.clientWidth };
  });
  assert.ok(wrap.scroll <= wrap.client, `projector: the criteria table fits (${wrap.scroll} > ${wrap.client})`);
  await page.screenshot({ path: path.join(OUT, 'projector-1280.png') });
  // The FRF charts' labels are not cut at the canvas edges.
  await page.click('#tab-spectra');
  await page.waitForTimeout(300);
  for (const id of ['sp-frf-bacc', 'sp-frf-dtl', 'sp-frf-sws', 'sp-psd-bacc', 'sp-psd-dtl', 'sp-psd-sws']) {
    const edge = await page.evaluate((id) => {
      const c = document.getElementById(id);
      const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      const dark = (x, y) => {
        const k = 4 * (y * c.width + x);
        return d[k + 3] > 0 && d[k] + d[k + 1] + d[k + 2] < 300;
      };
      let n = 0;
      for (let y = 0; y < c.height; y++) for (const x of [0, 1]) if (dark(x, y)) n++;
      for (let x = 0; x < c.width * 0.25; x++) for (const y of [0, 1, c.height - 2, c.height - 1]) if (dark(x, y)) n++;
      return n;
    }, id);
    assert.equal(edge, 0, `${id}: no text cut at the canvas's left, top or bottom edge`);
  }
  await page.screenshot({ path: path.join(OUT, 'projector-1280-spectra.png') });
  // Projector mode travels in the link, and an old link's large=1 means it too.
  const again = await open('#large=1');
  assert.equal(await again.page.evaluate(() => document.documentElement.classList.contains('projector')), true);
  await again.context.close();
  assertClean(log);
  await context.close();
});

test('colour-blind palette: the maps take cividis from the core and the link keeps it', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  await page.selectOption('#map-palette', 'cividis');
  await settle(page);
  const px = await page.evaluate(() => {
    const a = window.__ridelab;
    const v = a.views[0];
    const table = a.api.colourTable('cividis');
    const { plot } = v.layout();
    const g = v.base.getContext('2d');
    // The colour bar's ends on screen vs the core's table ends.
    return { lo: Array.from(table.slice(0, 3)), hi: Array.from(table.slice(765, 768)), map: v.data.colourMap, url: location.hash, plot };
  });
  assert.equal(px.map, 'cividis');
  assert.deepEqual(px.lo, [0, 34, 78]);
  assert.deepEqual(px.hi, [254, 232, 56]);
  await settle(page);
  assert.match(page.url(), /pal=cividis/);
  // The map's pixels are cividis colours (its low third, dark blue to grey), none viridis purple.
  const hits = await page.evaluate(() => {
    const a = window.__ridelab;
    const t = a.api.colourTable('cividis');
    const c = document.getElementById('map-dtl');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let cividis = 0;
    let purple = 0;
    for (let k = 0; k < d.length; k += 4) {
      if (Math.abs(d[k] - 68) + Math.abs(d[k + 1] - 1) + Math.abs(d[k + 2] - 84) < 20) purple++;
      for (let e = 0; e < 85; e += 4) {
        if (Math.abs(d[k] - t[3 * e]) + Math.abs(d[k + 1] - t[3 * e + 1]) + Math.abs(d[k + 2] - t[3 * e + 2]) < 12) {
          cividis++;
          break;
        }
      }
    }
    return { cividis, purple };
  });
  assert.ok(hits.cividis > 1000, `cividis colours on the DTL map (${hits.cividis} px)`);
  assert.equal(hits.purple, 0, 'no viridis purple left');
  const again = await open(new URL(page.url()).hash);
  assert.equal(await again.page.inputValue('#map-palette'), 'cividis');
  await again.context.close();
  assertClean(log);
  await context.close();
});

test('tour: a card beside each real control, focus moves to it, Escape closes it, remembered', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open('', { tour: true });
  assert.equal(await page.isVisible('#tour-card'), true, 'the tour shows on a first visit');
  assert.equal(await page.evaluate(() => document.activeElement.id), 'tour-card', 'focus moves to the card');
  const steps = [];
  for (let i = 0; i < 6; i++) {
    const s = await page.evaluate(() => {
      const card = document.getElementById('tour-card').getBoundingClientRect();
      const lit = document.querySelector('.spotlight');
      const r = lit.getBoundingClientRect();
      const overlap = !(card.right <= r.left || card.left >= r.right || card.bottom <= r.top || card.top >= r.bottom);
      const gap = Math.max(r.left - card.right, card.left - r.right, r.top - card.bottom, card.top - r.bottom);
      return { id: lit.id, overlap, gap, inView: card.left >= 0 && card.top >= 0 && card.right <= innerWidth && card.bottom <= innerHeight, count: document.getElementById('tour-count').textContent };
    });
    steps.push(s);
    assert.equal(s.count, `${i + 1} of 6`);
    assert.ok(!s.overlap, `step ${i + 1}: the card does not cover ${s.id}`);
    assert.ok(s.gap < 40, `step ${i + 1}: the card sits beside ${s.id} (${s.gap} px away)`);
    assert.ok(s.inView, `step ${i + 1}: the card is in view`);
    if (i === 1) await page.screenshot({ path: path.join(OUT, 'tour-step-2.png') });
    if (i < 5) await page.click('#tour-next');
  }
  assert.deepEqual(steps.map((s) => s.id), ['ks-range', 'map-grid', 'sws-range', 'map-model', 'op-wrap', 'tab-spectra']);
  await page.keyboard.press('Escape');
  assert.equal(await page.isVisible('#tour-card'), false, 'Escape closes the tour');
  assert.equal(await page.evaluate(() => document.querySelectorAll('.spotlight').length), 0);
  await page.reload();
  await page.waitForFunction(() => window.__ridelab && window.__ridelab.ready);
  assert.equal(await page.isVisible('#tour-card'), false, 'closed tours stay closed');
  await page.click('#tour');
  assert.equal(await page.isVisible('#tour-card'), true, 'the Tour button opens it again');
  assertClean(log);
  await context.close();
});

// ---------------------------------------------------------------- defects of issue #11

test('defect: the current-design dot stays visible on the plane (beyond the axes, by the legend, at 6 mm)', { timeout: TIMEOUT }, async () => {
  for (const [hash, clamped] of [['#ks=40000&cs=4000', true], ['#ks=30000&cs=1290', null], ['#sws=6', null]]) {
    const { page, context, log } = await open(hash);
    const d = await page.evaluate(() => {
      const p = window.__ridelab.objPlane;
      const { plot } = p.base.layout();
      const c = document.getElementById('op-overlay');
      const dpr = c.width / c.clientWidth;
      const px = Array.from(c.getContext('2d').getImageData(Math.round(p.designAt[0] * dpr), Math.round(p.designAt[1] * dpr), 1, 1).data);
      return { at: p.designAt, clamped: p.designClamped, plot, px };
    });
    assert.ok(d.at[0] >= d.plot.x && d.at[0] <= d.plot.x + d.plot.w && d.at[1] >= d.plot.y && d.at[1] <= d.plot.y + d.plot.h, `${hash}: the dot inside the plot (${d.at})`);
    assert.deepEqual(d.px.slice(0, 3), [0, 0, 0], `${hash}: the dot drawn (${d.px})`);
    if (clamped !== null) assert.equal(d.clamped, clamped, `${hash}: pinned to the edge with an arrow`);
    // No legend inside the plot on screen: the key above the chart says what is what.
    const legendText = await page.evaluate(() => {
      const p = window.__ridelab.objPlane;
      const { plot } = p.base.layout();
      const c = document.getElementById('op-base');
      const dpr = c.width / c.clientWidth;
      const x0 = Math.round((plot.x + 0.55 * plot.w) * dpr);
      const y0 = Math.round((plot.y + 2) * dpr);
      const w = Math.round(0.44 * plot.w * dpr);
      const h = Math.round(0.3 * plot.h * dpr);
      const d = c.getContext('2d').getImageData(x0, y0, w, h).data;
      let n = 0;
      for (let k = 0; k < d.length; k += 4) if (d[k] + d[k + 1] + d[k + 2] < 150) n++;
      return n;
    });
    assert.ok(legendText < 120, `${hash}: no legend text in the plot's upper right (${legendText} dark px)`);
    assert.match(await page.textContent('#op-key'), /design/);
    assertClean(log);
    await context.close();
  }
});

test('defect: the link keeps the objective plane\'s ratio axes', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  await page.selectOption('#op-scale', 'ratio');
  await settle(page);
  assert.match(page.url(), /axes=ratio/);
  const again = await open(new URL(page.url()).hash);
  assert.equal(await again.page.inputValue('#op-scale'), 'ratio');
  const d = await again.page.evaluate(() => {
    const p = window.__ridelab.objPlane;
    const [x, y] = p.base.px(1, 1);
    const c = document.getElementById('op-base');
    const dpr = c.width / c.clientWidth;
    return Array.from(c.getContext('2d').getImageData(Math.round(x * dpr), Math.round(y * dpr), 1, 1).data);
  });
  assert.deepEqual(d.slice(0, 3), [255, 255, 255], `the datum's white square at (1, 1) on the reopened ratio axes: ${d}`);
  await again.context.close();
  assertClean(log);
  await context.close();
});

test('defect: after a refused plan the plan menu shows the plan in use', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  await page.click('#tab-surrogate');
  await page.selectOption('#sur-approach', 'data-quad');
  await settle(page);
  assert.equal(await page.evaluate(() => window.__ridelab.state.surrogate), 'data-quad');
  await page.selectOption('#sur-plan', 'ae:3');
  await settle(page);
  assert.match(await page.textContent('#msg-plan'), /needs at least 6 samples/);
  const st = await page.evaluate(() => window.__ridelab.state.plan);
  assert.equal(st, 'ae:10', 'the state keeps its plan');
  assert.equal(await page.inputValue('#sur-plan'), st, 'the menu shows the plan the fit uses');
  assert.equal(await page.evaluate(() => window.__ridelab.fit.samples.length), 10);
  assertClean(log);
  await context.close();
});

test('defect: an edited car is named "(edited)", not "(file)", and its errors sit beside the field', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  await page.click('#tab-car');
  await page.click('#car-editor summary');
  assert.equal(await page.inputValue('#car-front-spring'), '19.96', 'springs in kN/m, as the sliders');
  await page.fill('#car-sprung_mass', '1600');
  await page.click('#car-apply');
  await settle(page);
  const label = await page.locator('#car option:checked').textContent();
  assert.match(label, /\(edited\)$/, label);
  assert.doesNotMatch(label, /file/, label);
  await page.fill('#car-front-tire_stiffness', '-5');
  await page.click('#car-apply');
  await page.waitForFunction(() => document.getElementById('msg-car-front-tire_stiffness').textContent !== '');
  assert.match(await page.textContent('#msg-car-front-tire_stiffness'), /tyre stiffness: must be > 0 \(got −5 kN\/m\)/);
  assert.equal(await page.textContent('#msg-car'), '', 'nothing beside the car menu');
  assertClean(log);
  await context.close();
});

test('defect: the same car file can be loaded again after an error (the input is cleared)', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open();
  const file = { name: 'broken.json', mimeType: 'application/json', buffer: Buffer.from('{"name": "x"') };
  await page.setInputFiles('#car-file', file);
  await page.waitForFunction(() => document.getElementById('msg-carFile').textContent !== '');
  assert.equal(await page.inputValue('#car-file'), '', 'the file input is empty again');
  assertClean(log);
  await context.close();
});

test('defect: "PNG of every chart" is one zip of slide-size PNGs', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open('', { downloads: true });
  await page.click('#tab-export');
  const files = [];
  page.on('download', (d) => files.push(d));
  await page.click('#png-all');
  await page.waitForFunction(() => /PNGs/.test(document.getElementById('export-status').textContent), null, { timeout: 60_000 });
  await page.waitForTimeout(300);
  assert.equal(files.length, 1, 'one download');
  assert.match(files[0].suggestedFilename(), /^ridelab-charts-png-sedan-B-20ms\.zip$/);
  const zipPath = path.join(OUT, files[0].suggestedFilename());
  await files[0].saveAs(zipPath);
  const entries = readZip(fs.readFileSync(zipPath));
  assert.deepEqual(entries.map((e) => e.name.replace(/^ridelab-|-sedan-B-20ms\.png$/g, '')), [
    'objective', 'frf-bacc', 'frf-dtl', 'frf-sws', 'psd-bacc', 'psd-dtl', 'psd-sws', 'map-bacc', 'map-dtl', 'map-sws',
  ]);
  for (const e of entries) {
    assert.equal(e.data.subarray(1, 4).toString(), 'PNG', `${e.name} is a PNG`);
    const width = e.data.readUInt32BE(16);
    assert.ok(width >= 1600, `${e.name}: ${width} px wide`);
  }
  assertClean(log);
  await context.close();
});

test('defect: the HiFi modes at Ks 40, Cs 4 are labelled once each, one of them pitch', { timeout: TIMEOUT }, async () => {
  const { page, context } = await open('#ks=40000&cs=4000');
  const labels = await page.evaluate(() => window.__ridelab.hifi.design.modes.map((m) => m.label));
  await context.close();
  assert.equal(new Set(labels).size, labels.length, `distinct labels: ${labels.join(', ')}`);
  assert.ok(labels.some((l) => /pitch/.test(l)), `a pitch mode: ${labels.join(', ')}`);
});

test('saved designs: Keep (and S) keeps up to three, side by side with the readout\'s values; Set restores one', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await open('#ks=15000&cs=1000');
  /** The readout's LoFi and HiFi criteria (SI, from data-value). */
  const readout = () => page.evaluate(() => Object.fromEntries(['lofi', 'hifi'].flatMap((m) => ['bacc', 'dtl', 'sws'].map((c) =>
    [`${m}-${c}`, Number(document.querySelector(`#criteria tr[data-crit="${c}"] td[data-model="${m}"]`).dataset.value)]))));
  const kept = [];
  for (const [ks, cs] of [[15000, 1000], [30000, 2500], [20000, 1500], [25000, 3000]]) {
    await page.evaluate(([ks, cs]) => { location.hash = `#ks=${ks}&cs=${cs}`; }, [ks, cs]);
    await page.waitForFunction(([ks, cs]) => window.__ridelab.state.ks === ks && window.__ridelab.state.cs === cs, [ks, cs]);
    await settle(page);
    kept.push({ ks, cs, values: await readout() });
    if (ks === 20000) await page.keyboard.press('s');
    else await page.click('#keep');
    await page.waitForFunction((n) => window.__ridelab.saved.length === n, Math.min(kept.length, 3));
  }
  await page.click('#tab-pick');
  const cols = await page.$$eval('#compare thead th[data-saved]', (ths) => ths.length);
  assert.equal(cols, 3, 'three designs kept: the oldest dropped');
  const table = await page.evaluate(() => [...document.querySelectorAll('#compare tbody tr[data-crit]')].map((tr) => ({
    key: `${tr.dataset.model}-${tr.dataset.crit}`,
    values: [...tr.querySelectorAll('td')].slice(1).map((td) => Number(td.dataset.value)),
  })));
  for (const row of table) {
    kept.slice(1).forEach((k, i) => assert.equal(row.values[i], k.values[row.key], `${row.key} of design ${i + 1}`));
  }
  await page.locator('#compare thead th[data-saved="0"] button', { hasText: 'Set' }).click();
  await page.waitForFunction(() => window.__ridelab.state.ks === 30000 && window.__ridelab.state.cs === 2500);
  await page.locator('#compare thead th[data-saved="2"] button[aria-label^="Remove"]').click();
  assert.equal(await page.$$eval('#compare thead th[data-saved]', (ths) => ths.length), 2, 'one removed');
  // The link carries the kept designs; a fresh page evaluates them again to the same numbers.
  await page.waitForFunction(() => /[#&]ks=30000&.*&keep=30000%3A2500%2C20000%3A1500$/.test(location.hash));
  const link = await page.evaluate(() => location.hash);
  const savedOf = (p) => p.evaluate(() => window.__ridelab.saved.map((s) => ({ ks: s.ks, cs: s.cs, lofi: s.lofi, hifi: s.hifi })));
  const before = await savedOf(page);
  assertClean(log);
  await context.close();
  const again = await open(link);
  await again.page.waitForFunction(() => window.__ridelab.saved.length === 2);
  const after = await savedOf(again.page);
  assert.deepEqual(after.map((s) => [s.ks, s.cs]), [[30000, 2500], [20000, 1500]], 'the link\'s designs, in order');
  for (const [i, s] of after.entries()) {
    for (const m of ['lofi', 'hifi']) {
      for (const c of ['bacc', 'dtl', 'sws']) {
        const rel = Math.abs(s[m][c] / before[i][m][c] - 1);
        assert.ok(rel <= 1e-12, `design ${i + 1} ${m} ${c}: ${s[m][c]} vs ${before[i][m][c]} (1e-12)`);
      }
    }
  }
  assert.equal(await again.page.$$eval('#compare thead th[data-saved]', (ths) => ths.length), 2, 'both in the table');
  assertClean(again.log);
  await again.context.close();
  // A bad list is refused with the field named, and the default view shown.
  const bad = await open('#ks=15000&cs=1000&keep=1:2:3');
  assert.match(await bad.page.locator('#banner').innerText(), /keep: '1:2:3' is not Ks:Cs pairs/);
  assert.equal(await bad.page.evaluate(() => window.__ridelab.saved.length), 0);
  await bad.context.close();
});

test('defect: the readout, pick, metrics and compare tables fit their column (no sideways scroll) at 390 x 844 and in the drawer at 1600 x 1000', { timeout: TIMEOUT }, async () => {
  for (const [width, height] of [[390, 844], [1600, 1000]]) {
    const { page, context, log } = await open('#ks=15000&cs=1000', { width, height });
    await page.click('#keep');
    await page.waitForFunction(() => window.__ridelab.saved.length === 1);
    for (const tab of ['pick', 'surrogate']) {
      await page.click(`#tab-${tab}`);
      await page.waitForFunction(() => document.querySelector('#sur-metrics tbody tr'));
      const tables = await page.evaluate(() => [...document.querySelectorAll('.table-wrap > table')]
        .filter((t) => t.offsetParent !== null)
        .map((t) => ({ id: t.id, scroll: t.parentElement.scrollWidth, width: t.parentElement.clientWidth })));
      assert.ok(tables.length >= 2, `${width}: ${tab} tab shows its tables (${tables.map((t) => t.id)})`);
      for (const t of tables) assert.ok(t.scroll <= t.width + 1, `${width} x ${height}, ${tab} tab: #${t.id} is ${t.scroll} px in ${t.width} px`);
    }
    assertClean(log);
    await context.close();
  }
});
