// End-to-end test of the shipped lessons' answers (issue #30): every step with options
// states its right option (`answer`, js/lessonbook.js), and that answer follows from the
// numbers the page computes at the step's view by a rule stated here per step. Each rule
// returns the option (1..) the numbers make true, or null when none is, so a wrong
// `answer` in the lesson book, or a page whose numbers no longer bear it out, fails. At
// the reveal the page marks the right option "✓ right answer" and a wrong prediction
// "✗ wrong", and a right prediction "✓ right".
//
//   trunk build --release --offline && node --test tests/e2e/lessonanswers.test.mjs

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { openPage, settled } from './browser.mjs';
import { useSuite, assertClean } from './harness.mjs';

const TIMEOUT = 300_000;
const suite = useSuite();

/** Waits until the page has settled and the lesson panel shows every number of its step. */
async function lessonReady(page) {
  await page.waitForFunction(() => window.__ridelab.isSettled() && document.getElementById('lesson').dataset.ready === 'true', null, { timeout: 60_000 });
}

/**
 * What the page computed at the step shown: `v`, every placeholder's value (SI, or text;
 * undefined when it has none), as the reveal would fill it in; `text`, the reveal as
 * shown; and what the maps and the objective plane show, boiled down for the rules.
 */
function computed(page) {
  return page.evaluate(async () => {
    const { PLACEHOLDERS, resolve } = await import('./js/lessons.js');
    const R = window.__ridelab;
    const P = R.lessons;
    const d = P.data();
    const v = {};
    for (const name of Object.keys(PLACEHOLDERS)) {
      const [p] = resolve(`{${name}}`, d);
      v[name] = p.pending ? 'pending' : p.value;
    }
    const out = { v, text: document.getElementById('lesson-answer').textContent, model: R.view.model };
    const shown = P.store.shownMaps();
    if (shown) {
      const m = shown.maps;
      const { nx, ny } = m;
      const n = nx * ny;
      // Cells breaking each objective (by its name), counted per Ks column and per Cs row
      // (cell k = j nx + i: i along Ks, j along Cs, both from the box's low end).
      const broken = {};
      for (const { bit, name } of P.store.objectives) {
        const cols = new Array(nx).fill(0);
        const rows = new Array(ny).fill(0);
        for (let j = 0; j < ny; j++) for (let i = 0; i < nx; i++) if (m.broken[j * nx + i] & bit) { cols[i]++; rows[j]++; }
        broken[name] = { cols, rows };
      }
      out.maps = { kind: shown.kind, nx, ny, feasibleCount: m.feasibleCount, broken };
      // The largest |value| of each plane of the error maps (the surrogate's error against the HiFi, %).
      if (shown.kind === 'error') out.maps.errMax = [0, 1, 2].map((c) => Math.max(...Array.from(m.values.subarray(c * n, (c + 1) * n), Math.abs)));
      // HiFi maps shown: how alike their BAcc and DTL planes are to the LoFi maps' (Pearson r).
      // (The LoFi maps of this scenario: the store's when current, else computed here as the page does.)
      if (P.store.view.model === 'hifi') {
        const lofi = P.store.maps && P.store.maps.key === R.modelMaps.key ? P.store.maps : await P.compute.lofiMaps(P.store.state);
        out.maps.r = [0, 1].map((c) => {
          const a = m.values.subarray(c * n, (c + 1) * n);
          const b = lofi.values.subarray(c * n, (c + 1) * n);
          const ma = a.reduce((s, x) => s + x, 0) / n;
          const mb = b.reduce((s, x) => s + x, 0) / n;
          let sab = 0, saa = 0, sbb = 0;
          for (let k = 0; k < n; k++) {
            sab += (a[k] - ma) * (b[k] - mb);
            saa += (a[k] - ma) ** 2;
            sbb += (b[k] - mb) ** 2;
          }
          return sab / Math.sqrt(saa * sbb);
        });
      }
    }
    const st = d.front && !d.front.error ? d.front.study : null;
    if (st) {
      const f = st.front;
      let dominated = 0;
      for (const p of f) if (f.some((q) => q.bacc <= p.bacc && q.dtl <= p.dtl && (q.bacc < p.bacc || q.dtl < p.dtl))) dominated++;
      const b = f.map((p) => p.bacc);
      const t = f.map((p) => p.dtl);
      out.front = {
        points: f.length,
        dominated,
        bacc: [Math.min(...b), Math.max(...b)],
        dtl: [Math.min(...t), Math.max(...t)],
        swsMax: Math.max(...f.map((p) => p.sws)),
        pick: { ...st.pick.criteria, ks: st.pick.ks, cs: st.pick.cs, weights: st.pick.pseudo_weights },
      };
    }
    return out;
  });
}

/** Which of `rows`'s entries are non-zero: `'none'`, `'all'`, `'low'` (a run from index 0), `'high'` (a run to the end) or `'mixed'`. */
function run(counts) {
  const on = counts.map((c) => c > 0);
  const k = on.indexOf(true);
  if (k < 0) return 'none';
  const last = on.lastIndexOf(true);
  if (on.slice(k, last + 1).includes(false)) return 'mixed';
  if (k === 0 && last === on.length - 1) return 'all';
  if (k === 0) return 'low';
  if (last === on.length - 1) return 'high';
  return 'mixed';
}

/** Every count in `counts` is 0 or `full`. */
const allOrNothing = (counts, full) => counts.every((c) => c === 0 || c === full);

/** One sign for a change, or 0 for none (within `tol`, a fraction). */
const sign = (x, tol = 1e-9) => (Math.abs(x) <= tol ? 0 : Math.sign(x));

/** The option of "What happens to BAcc and DTL?" (both fall, BAcc falls DTL rises, BAcc rises DTL falls, both rise) from the signs of their changes. */
const fallRise = (bacc, dtl) => ({ '-1,-1': 1, '-1,1': 2, '1,-1': 3, '1,1': 4 })[`${sign(bacc)},${sign(dtl)}`] ?? null;

/**
 * The rule of each step with options, by `lesson:step` (1-based): `rule(x, seen)` the
 * option the numbers make true (1..) or null; `x` the step's `computed`, `seen` the
 * lesson's steps so far (0-based). `why` is the rule in words.
 */
const RULES = {
  'comfort:1': {
    why: 'a definition, read from the reveal the page shows: BAcc (body acceleration) is comfort, DTL (tyre load) road holding',
    rule: (x) => (/BAcc[^.]*is comfort/.test(x.text) && /DTL[^.]*is road holding/.test(x.text) ? 1
      : /DTL[^.]*is comfort/.test(x.text) && /BAcc[^.]*is road holding/.test(x.text) ? 2
        : /SWS[^.]*both/.test(x.text) ? 3 : null),
  },
  'comfort:2': {
    why: 'softer spring: the signs of {lofi,hifi}.{bacc,dtl}.pct, the same on LoFi and HiFi',
    rule: ({ v }) => {
      const lo = fallRise(v['lofi.bacc.pct'], v['lofi.dtl.pct']);
      return lo === fallRise(v['hifi.bacc.pct'], v['hifi.dtl.pct']) ? lo : null;
    },
  },
  'comfort:3': {
    why: 'more damping: the signs of {lofi,hifi}.{bacc,dtl}.pct, the same on LoFi and HiFi',
    rule: ({ v }) => {
      const lo = fallRise(v['lofi.bacc.pct'], v['lofi.dtl.pct']);
      return lo === fallRise(v['hifi.bacc.pct'], v['hifi.dtl.pct']) ? lo : null;
    },
  },
  'comfort:4': {
    why: '{cs_opt} against {datum.cs} (below or above), and {cs_dtl} against {cs_opt} (agrees within 10 %, wants more or less)',
    rule: ({ v }) => {
      const below = v.cs_opt < v['datum.cs'];
      const dtl = Math.abs(v.cs_dtl / v.cs_opt - 1) <= 0.1 ? 'agrees' : v.cs_dtl > v.cs_opt ? 'more' : 'less';
      if (below && dtl === 'agrees') return 1;
      if (below && dtl === 'more') return 2;
      if (!below && dtl === 'less') return 3;
      return null;
    },
  },
  'fidelity:1': {
    why: 'the largest |{gap.*}| of BAcc, DTL, SWS (by more than 0.1 point)',
    rule: ({ v }) => {
      const g = ['gap.bacc', 'gap.dtl', 'gap.sws'].map((n) => Math.abs(v[n]));
      const top = Math.max(...g);
      const i = g.indexOf(top);
      return g.every((x, j) => j === i || top - x > 0.001) ? i + 1 : null;
    },
  },
  'fidelity:2': {
    why: '|{gap.bacc}| at 10 m/s against step 1\'s at 20 m/s (the same within 0.1 point)',
    rule: ({ v }, seen) => {
      const d = Math.abs(v['gap.bacc']) - Math.abs(seen[0].v['gap.bacc']);
      return Math.abs(d) <= 0.001 ? 3 : d > 0 ? 1 : 2;
    },
  },
  'fidelity:3': {
    why: '|{gap.bacc}| at 40 m/s against both earlier speeds (20 and 10 m/s); the same within 0.1 point',
    rule: ({ v }, seen) => {
      const ds = [seen[0], seen[1]].map((s) => Math.abs(v['gap.bacc']) - Math.abs(s.v['gap.bacc']));
      if (ds.every((d) => Math.abs(d) <= 0.001)) return 3;
      if (ds.every((d) => d > 0.001)) return 1;
      if (ds.every((d) => d < -0.001)) return 2;
      return null;
    },
  },
  'fidelity:4': {
    why: 'the HiFi maps shown against the LoFi maps of the same box: Pearson r of the BAcc planes and of the DTL planes both over 0.98 (alike), else not',
    rule: (x) => {
      const r = x.maps?.r;
      if (!r) return null;
      return r.every((c) => c > 0.98) ? 1 : 2;
    },
  },
  'objectives:1': {
    why: 'the cells breaking the SWS limit: every Cs row all or nothing (whatever the spring), a run from the lowest Cs (light damping); or every Ks column all or nothing from the lowest Ks (soft springs); or only the stiff, heavily damped quarter',
    rule: ({ maps }) => {
      const { cols, rows } = maps.broken.sws_limit;
      if (allOrNothing(rows, maps.nx) && run(rows) === 'low') return 1;
      if (allOrNothing(cols, maps.ny) && run(cols) === 'low') return 2;
      if (run(cols) === 'high' && run(rows) === 'high') return 3;
      return null;
    },
  },
  'objectives:2': {
    why: 'the Ks columns with cells breaking the body-bounce band: a run from the softest (1), to the stiffest (2), or none (3)',
    rule: ({ maps }) => ({ low: 1, high: 2, none: 3 })[run(maps.broken.bounce_band.cols)] ?? null,
  },
  'objectives:3': {
    why: 'the share of the box meeting the SWS limit: over 65 % most, 35..65 % about half, 0 none',
    rule: ({ maps }) => {
      const n = maps.nx * maps.ny;
      const ok = 1 - maps.broken.sws_limit.rows.reduce((s, c) => s + c, 0) / n;
      return ok > 0.65 ? 1 : ok >= 0.35 && ok <= 0.65 ? 2 : ok === 0 ? 3 : null;
    },
  },
  'surrogate:1': {
    why: '{samples}: 5..20 about ten, 300..3000 about a thousand, {grid.cells} all of them',
    rule: ({ v }) => (v.samples === v['grid.cells'] ? 3 : v.samples >= 5 && v.samples <= 20 ? 1 : v.samples >= 300 && v.samples <= 3000 ? 2 : null),
  },
  'surrogate:2': {
    why: 'the worst error, the largest of {fit.rte.*} (20 × 20 HiFi grid) and of the error maps shown: under 1 %, 1..10 % a few per cent, over 10 %',
    rule: ({ v, maps }) => {
      const w = Math.max(v['fit.rte.bacc'], v['fit.rte.dtl'], v['fit.rte.sws'], ...maps.errMax.map((e) => e / 100));
      return w < 0.01 ? 1 : w <= 0.1 ? 2 : 3;
    },
  },
  'surrogate:3': {
    why: 'the pick with ae:3 against step 2\'s with ae:10: the same Ks and Cs and {recheck.err} within 0.05 point (1), or another Ks or Cs and a larger {recheck.err} (2)',
    rule: ({ v }, seen) => {
      const p = seen[1].v;
      const same = v['pick.ks'] === p['pick.ks'] && v['pick.cs'] === p['pick.cs'];
      const d = v['recheck.err'] - p['recheck.err'];
      if (same && Math.abs(d) <= 0.0005) return 1;
      if (!same && d > 0) return 2;
      return null;
    },
  },
  'choosing:1': {
    why: 'on the front the page drew: no point dominated by another in BAcc and DTL (1); every point the least BAcc (2); every point\'s SWS at most 99 % of {sws_limit} (3); the one true',
    rule: ({ v, front }) => {
      const holds = [
        front.dominated === 0,
        front.bacc[0] === front.bacc[1],
        front.swsMax <= 0.99 * v.sws_limit,
      ];
      return holds.filter(Boolean).length === 1 ? holds.indexOf(true) + 1 : null;
    },
  },
  'choosing:2': {
    why: 'the pick on the front: the least-BAcc point is the comfort end, the least-DTL point the road-holding end; the middle when it is neither and lies 20..80 % of the way along in both BAcc and DTL',
    rule: ({ front }) => {
      const { pick, bacc, dtl } = front;
      if (pick.bacc === bacc[0]) return 1;
      if (pick.dtl === dtl[0]) return 3;
      const tb = (pick.bacc - bacc[0]) / (bacc[1] - bacc[0]);
      const td = (pick.dtl - dtl[0]) / (dtl[1] - dtl[0]);
      return [tb, td].every((t) => t >= 0.2 && t <= 0.8) ? 2 : null;
    },
  },
  'choosing:3': {
    why: '{recheck.err}: at most 1 % (1), at most 10 % (2), more (3)',
    rule: ({ v }) => (v['recheck.err'] <= 0.01 ? 1 : v['recheck.err'] <= 0.1 ? 2 : 3),
  },
  'choosing:4': {
    why: '{pick.cs} with SWS ≤ 6 mm against step 2\'s with 7 mm: up (1), down (2), the same pick (3)',
    rule: ({ v }, seen) => {
      const p = seen[1].v;
      if (v['pick.cs'] === p['pick.cs'] && v['pick.ks'] === p['pick.ks']) return 3;
      return v['pick.cs'] > p['pick.cs'] ? 1 : v['pick.cs'] < p['pick.cs'] ? 2 : null;
    },
  },
};

const pc = (x) => `${(x * 100).toFixed(2)} %`;

/** The numbers each rule decides on, in words (for the table the test prints). */
const NUMBERS = {
  'comfort:1': (x) => x.text.slice(0, 60),
  'comfort:2': ({ v }) => `BAcc ${pc(v['lofi.bacc.pct'])} / ${pc(v['hifi.bacc.pct'])}, DTL ${pc(v['lofi.dtl.pct'])} / ${pc(v['hifi.dtl.pct'])} (LoFi / HiFi)`,
  'comfort:3': ({ v }) => `BAcc ${pc(v['lofi.bacc.pct'])} / ${pc(v['hifi.bacc.pct'])}, DTL ${pc(v['lofi.dtl.pct'])} / ${pc(v['hifi.dtl.pct'])} (LoFi / HiFi)`,
  'comfort:4': ({ v }) => `cs_opt ${v.cs_opt.toFixed(0)}, datum.cs ${v['datum.cs']}, cs_dtl ${v.cs_dtl.toFixed(0)} N s/m`,
  'fidelity:1': ({ v }) => `gap BAcc ${pc(v['gap.bacc'])}, DTL ${pc(v['gap.dtl'])}, SWS ${pc(v['gap.sws'])}`,
  'fidelity:2': ({ v }, seen) => `gap.bacc ${pc(v['gap.bacc'])} at 10 m/s, ${pc(seen[0].v['gap.bacc'])} at 20`,
  'fidelity:3': ({ v }, seen) => `gap.bacc ${pc(v['gap.bacc'])} at 40 m/s, ${pc(seen[0].v['gap.bacc'])} at 20, ${pc(seen[1].v['gap.bacc'])} at 10`,
  'fidelity:4': ({ maps }) => `r(HiFi, LoFi) BAcc ${maps.r[0].toFixed(4)}, DTL ${maps.r[1].toFixed(4)}`,
  'objectives:1': ({ v, maps }) => `SWS breakers: rows ${run(maps.broken.sws_limit.rows)} (${maps.broken.sws_limit.rows.filter((c) => c).length} of ${maps.ny}, each ${Math.max(...maps.broken.sws_limit.rows)} of ${maps.nx}), cols ${run(maps.broken.sws_limit.cols)}; cs_sws ${v.cs_sws.toFixed(0)} N s/m`,
  'objectives:2': ({ v, maps }) => `band breakers: Ks cols ${run(maps.broken.bounce_band.cols)} (${maps.broken.bounce_band.cols.filter((c) => c).length} of ${maps.nx}); feasible ${pc(v.feasible)}`,
  'objectives:3': ({ v }) => `feasible ${pc(v.feasible)}, lofi.sws ${(v['lofi.sws'] * 1000).toFixed(2)} mm, cs_sws ${v.cs_sws.toFixed(0)} > box ${v['box.cs_max']} N s/m`,
  'surrogate:1': ({ v }) => `samples ${v.samples}, grid.cells ${v['grid.cells']}`,
  'surrogate:2': ({ v, maps }) => `fit.rte ${pc(v['fit.rte.bacc'])} / ${pc(v['fit.rte.dtl'])} / ${pc(v['fit.rte.sws'])}, error maps max ${maps.errMax.map((e) => `${e.toFixed(2)} %`).join(' / ')}`,
  'surrogate:3': ({ v }, seen) => `pick (${v['pick.ks']}, ${v['pick.cs'].toFixed(1)}) vs (${seen[1].v['pick.ks']}, ${seen[1].v['pick.cs'].toFixed(1)}); recheck.err ${pc(v['recheck.err'])} vs ${pc(seen[1].v['recheck.err'])}`,
  'choosing:1': ({ v, front }) => `${front.points} points, ${front.dominated} dominated, SWS max ${(front.swsMax * 1000).toFixed(4)} of ${(v.sws_limit * 1000).toFixed(1)} mm`,
  'choosing:2': ({ front: { pick, bacc, dtl } }) => `pick BAcc ${((pick.bacc - bacc[0]) / (bacc[1] - bacc[0])).toFixed(2)}, DTL ${((pick.dtl - dtl[0]) / (dtl[1] - dtl[0])).toFixed(2)} of the front's span; weights ${pick.weights.map((w) => w.toFixed(2)).join(' / ')}`,
  'choosing:3': ({ v }) => `recheck.err ${pc(v['recheck.err'])}`,
  'choosing:4': ({ v }, seen) => `pick.cs ${v['pick.cs'].toFixed(1)} vs ${seen[1].v['pick.cs'].toFixed(1)} N s/m (Ks ${v['pick.ks']} vs ${seen[1].v['pick.ks']})`,
};

/** The options as shown: `{verdict, text}` each. */
const options = (page) => page.$$eval('#lesson-options button', (bs) => bs.map((b) => ({ verdict: b.dataset.verdict ?? '', text: b.textContent })));

/** Goes to step `k`, the class predicting option `i` (0-based), and reveals; resolves once every number is in. */
async function predictAndReveal(page, k, i) {
  await page.evaluate((k) => window.__ridelab.lessons.go(k), k);
  await lessonReady(page);
  await page.click(`#lesson-options button >> nth=${i}`);
  await page.click('#lesson-reveal');
  await lessonReady(page);
}

test('every shipped step with options states its answer; the page\'s numbers bear it out; the reveal marks it and the prediction', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await openPage(suite.browser, suite.srv.url, { width: 1280, height: 720 });
  await settled(page, 100);
  await page.click('#lessons-open');
  const shipped = await page.evaluate(() => import('./js/lessonbook.js').then((m) => m.SHIPPED));
  const table = [];
  for (const { id, lesson } of shipped) {
    if (await page.isVisible('#lesson-menu')) await page.click('#lesson-menu');
    await page.click(`#lesson-shipped button[data-lesson="${id}"]`);
    await lessonReady(page);
    const seen = [];
    for (const [k, step] of lesson.steps.entries()) {
      const where = `${id}:${k + 1}`;
      if (!step.options?.length) {
        seen.push(null);
        continue;
      }
      const r = RULES[where];
      assert.ok(r, `${where}: a rule for the step's answer`);
      assert.ok(Number.isInteger(step.answer), `${where}: the step states its answer`);
      const n = step.options.length;
      const right = step.answer - 1;
      const wrong = (right + 1) % n;

      // A wrong prediction: the right option "✓ right answer", the prediction "✗ wrong".
      await predictAndReveal(page, k, wrong);
      const x = await computed(page);
      assert.ok(!Object.values(x.v).includes('pending'), `${where}: every number is in`);
      let shown = await options(page);
      assert.equal(shown.length, n);
      shown.forEach((o, i) => {
        const want = i === right ? 'answer' : i === wrong ? 'wrong' : '';
        assert.equal(o.verdict, want, `${where}: option ${i + 1} "${o.text}"`);
      });
      assert.match(shown[right].text, /✓ right answer$/, `${where}: the right option is marked`);
      assert.match(shown[wrong].text, /✗ wrong/, `${where}: the wrong prediction is marked`);
      assert.match(await page.textContent('#lesson-hint'), new RegExp(`^The class chose ${wrong + 1}; the right answer is ${right + 1}\\. `));

      // The numbers make the stated answer, and only it, true.
      const made = r.rule(x, seen);
      table.push({ step: where, answer: `${step.answer}. ${step.options[right]}`, rule: made, numbers: NUMBERS[where](x, seen) });
      assert.equal(made, step.answer, `${where}: the numbers make option ${made} true (${r.why}), the lesson says ${step.answer}`);
      seen.push(x);

      // A right prediction: "✓ right", no other option marked.
      await predictAndReveal(page, k, right);
      shown = await options(page);
      shown.forEach((o, i) => assert.equal(o.verdict, i === right ? 'right' : '', `${where}: option ${i + 1} "${o.text}"`));
      assert.match(shown[right].text, /✓ right: the class's prediction$/);
      assert.match(await page.textContent('#lesson-hint'), /^The class was right\. /);
    }
  }
  assert.deepEqual(table.map((t) => t.step).sort(), Object.keys(RULES).sort(), 'a rule for each shipped step with options, and no other');
  console.table(table);
  assertClean(log);
  await context.close();
});

test('the rules decide: other numbers make another option, or none, true', () => {
  // The rules are functions of the numbers alone: fed other numbers they give another option, or none.
  const x = { v: { 'lofi.bacc.pct': -0.11, 'lofi.dtl.pct': -0.01, 'hifi.bacc.pct': -0.10, 'hifi.dtl.pct': -0.008 } };
  assert.equal(RULES['comfort:2'].rule(x), 1);
  assert.equal(RULES['comfort:2'].rule({ v: { ...x.v, 'hifi.dtl.pct': 0.01 } }), null, 'LoFi and HiFi disagree: no option');
  assert.equal(RULES['comfort:3'].rule({ v: { 'lofi.bacc.pct': 0.16, 'lofi.dtl.pct': -0.08, 'hifi.bacc.pct': 0.17, 'hifi.dtl.pct': -0.08 } }), 3);
  assert.equal(RULES['surrogate:1'].rule({ v: { samples: 3, 'grid.cells': 19200 } }), null);
  assert.equal(RULES['choosing:3'].rule({ v: { 'recheck.err': 0.05 } }), 2);
  assert.equal(run([0, 0, 3, 3]), 'high');
  assert.equal(run([3, 0, 3, 0]), 'mixed');
});
