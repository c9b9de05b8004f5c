// End-to-end tests of the page's GPU path (issue #13): with `--enable-unsafe-webgpu`
// headless Chromium has a SwiftShader WebGPU adapter (../shared/TOOLCHAIN.md), and the
// heavy worker draws the HiFi and surrogate-error maps from the GPU at the LoFi maps'
// resolution, equal to the CPU path's (the main thread's `Explorer`) within 1e-4 on every
// cell; the footer (the Glossary panel's last line) names the adapter. SwiftShader is a
// software adapter, which the page's default (`?compute=auto`, as `ridelab map`) leaves for
// the CPU, saying so; `?compute=gpu` takes it. Without the flag the page falls back to the
// CPU and says so. Also a benchmark: the 160 x 120 HiFi map on
// the GPU path against the CPU path, median of 5 each, in the same page.
//
//   trunk build --release --offline && node --test tests/e2e/gpu.test.mjs

import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { chromium } from 'playwright-core';
import { CHROMIUM, FLAGS, openPage } from './browser.mjs';
import { useSuite, assertClean, median, OUT } from './harness.mjs';

const TIMEOUT = 600_000;
/** Largest relative difference of a GPU cell from the CPU's, -. */
const TOL = 1e-4;
/** The SwiftShader WebGPU adapter (TOOLCHAIN.md): the suite's flags plus WebGPU. */
const GPU_FLAGS = [...FLAGS, '--enable-unsafe-webgpu', '--use-webgpu-adapter=swiftshader'];

const suite = useSuite();

/** Waits until the maps show `model`'s maps of the current scenario (a software GPU is slow: up to `ms`). */
async function mapsShown(page, model, ms) {
  await page.selectOption('#map-model', model);
  await page.waitForFunction(
    (model) => {
      const a = window.__ridelab;
      const mm = a.modelMaps;
      return a.isSettled() && mm && mm.model === model && mm.maps.compute !== undefined;
    },
    model,
    { timeout: ms, polling: 250 },
  );
}

/**
 * The shown HiFi or error map against the CPU path's (the main thread's own session,
 * `maps(model, nx, ny)`): the largest relative difference of the HiFi values (`hifi`), or
 * the largest difference of the error values in percentage points (`error`).
 */
function compareWithCpu(page) {
  return page.evaluate(() => {
    const a = window.__ridelab;
    const mm = a.modelMaps;
    const m = mm.maps;
    const cpu = new a.api.Explorer(a.state);
    const want = cpu.maps(mm.model, m.nx, m.ny);
    cpu.free();
    let worst = 0;
    for (let k = 0; k < want.values.length; k++) {
      const d = mm.model === 'hifi' ? Math.abs(m.values[k] / want.values[k] - 1) : Math.abs(m.values[k] - want.values[k]);
      worst = Math.max(worst, d);
    }
    return { worst, n: want.values.length, nx: m.nx, ny: m.ny, compute: m.compute, cpuCompute: want.compute, gpu: m.gpu };
  });
}

test('without WebGPU the HiFi maps fall back to the CPU and the footer says so', { timeout: TIMEOUT }, async () => {
  const { page, context, log } = await openPage(suite.browser, suite.srv.url);
  await page.waitForFunction(() => document.getElementById('compute-path').textContent !== '', null, { timeout: 30_000 });
  await mapsShown(page, 'hifi', 60_000);
  const r = await compareWithCpu(page);
  assert.equal(r.compute, 'cpu');
  assert.equal(r.worst, 0, 'the CPU path is the session\'s own CPU map');
  assert.match(await page.locator('#compute-path').textContent(), /^HiFi maps: CPU \(no WebGPU adapter.*\)\.$/);
  assert.match(await page.locator('#map-status').textContent(), /on the CPU \(no WebGPU adapter/);
  assertClean(log);
  await context.close();
});

test('with a SwiftShader WebGPU adapter the HiFi and error maps come from the GPU, equal to the CPU within 1e-4', { timeout: TIMEOUT }, async (t) => {
  const browser = await chromium.launch({ executablePath: CHROMIUM, headless: true, args: GPU_FLAGS });
  try {
    let probe;
    {
      const { page, context, log } = await openPage(browser, suite.srv.url);
      probe = await page.evaluate(async () => {
        if (!navigator.gpu) return { adapter: false, why: 'navigator.gpu is undefined' };
        const a = await navigator.gpu.requestAdapter();
        return a ? { adapter: true, info: `${a.info?.vendor} ${a.info?.architecture} ${a.info?.description}`, fallback: a.info?.isFallbackAdapter } : { adapter: false, why: 'requestAdapter() gave null' };
      });
      t.diagnostic(`WebGPU probe: ${JSON.stringify(probe)}`);
      await page.waitForFunction(() => document.getElementById('compute-path').textContent !== '', null, { timeout: 60_000 });
      const footer = await page.locator('#compute-path').textContent();
      t.diagnostic(`footer: ${footer}`);
      if (!probe.adapter) {
        // No adapter in this Chromium: the fallback must still be right, then the skip says why.
        await mapsShown(page, 'hifi', 60_000);
        const r = await compareWithCpu(page);
        assert.equal(r.compute, 'cpu');
        assert.equal(r.worst, 0);
        assert.match(footer, /^HiFi maps: CPU \(/);
        t.skip(`no SwiftShader WebGPU adapter in this Chromium (${probe.why}); the CPU fallback was checked`);
        await context.close();
        return;
      }
      assertClean(log);
      // The default (auto) leaves a software adapter for the CPU, and says so.
      assert.equal(probe.fallback, true, 'SwiftShader reports itself as a fallback adapter');
      assert.match(footer, /^HiFi maps: CPU \(software WebGPU adapter .+, slower than the CPU; \?compute=gpu takes it\)\.$/);
      await mapsShown(page, 'hifi', 60_000);
      assert.equal((await compareWithCpu(page)).compute, 'cpu');
      await context.close();
    }
    {
      const { page, context, log } = await openPage(browser, `${suite.srv.url}?compute=gpu`);
      await page.waitForFunction(() => document.getElementById('compute-path').textContent !== '', null, { timeout: 60_000 });
      const footer = await page.locator('#compute-path').textContent();
      t.diagnostic(`footer with ?compute=gpu: ${footer}`);
      assert.match(footer, /^HiFi maps: GPU: .+\.$/);
      const t0 = Date.now();
      await mapsShown(page, 'hifi', 300_000);
      t.diagnostic(`first HiFi map shown after ${((Date.now() - t0) / 1000).toFixed(1)} s`);
      const hifi = await compareWithCpu(page);
      t.diagnostic(`HiFi map ${hifi.nx} x ${hifi.ny} on ${hifi.gpu.adapter}: worst relative difference from the CPU ${hifi.worst.toExponential(2)} over ${hifi.n} values`);
      assert.equal(hifi.compute, 'gpu', `drawn on the GPU path (${JSON.stringify(hifi.gpu)})`);
      assert.deepEqual([hifi.nx, hifi.ny], [160, 120], 'at the LoFi maps\' resolution');
      assert.ok(hifi.worst <= TOL, `GPU vs CPU HiFi: ${hifi.worst}`);
      assert.match(await page.locator('#map-status').textContent(), /on the GPU: /);
      // The error map is made of the same kept GPU values: 100 (S / HiFi - 1) % within
      // 100 (1 + |e| / 100) 1e-4 percentage points of the CPU's; 0.012 bounds it for |e| < 20 %.
      await mapsShown(page, 'error', 300_000);
      const err = await compareWithCpu(page);
      assert.equal(err.compute, 'gpu');
      assert.ok(err.worst <= 0.012, `GPU vs CPU error map: ${err.worst} percentage points`);
      await page.locator('.maps').screenshot({ path: path.join(OUT, 'maps-hifi-gpu.png') });

      // The HiFi front's STM starting grid (61 x 61) also comes from the GPU: its front,
      // hypervolume and pick equal the CPU's (the main thread's own session) within 1e-4.
      await page.waitForFunction(() => {
        const h = window.__ridelab.hifiFront;
        return window.__ridelab.isSettled() && h && !h.error;
      }, null, { timeout: 300_000, polling: 250 });
      const fronts = await page.evaluate(async () => {
        const a = window.__ridelab;
        const api = await a.onDemandApi();
        const cpu = new api.Explorer(a.state);
        const want = cpu.hifiFront();
        cpu.free();
        return { gpu: a.hifiFront, cpu: want };
      });
      const [gf, cf] = [fronts.gpu.front.study, fronts.cpu.front.study];
      t.diagnostic(`HiFi front: GPU grid ${fronts.gpu.compute}, ${gf.front.length} points (CPU ${cf.front.length}), hypervolume ${gf.hypervolume} vs ${cf.hypervolume}, ${fronts.gpu.ms.toFixed(0)} ms`);
      assert.equal(fronts.gpu.compute, 'gpu', `STM's grid on the GPU (${JSON.stringify(fronts.gpu.gpu)})`);
      assert.equal(fronts.cpu.compute, 'cpu');
      assert.ok(Math.abs(gf.hypervolume / cf.hypervolume - 1) <= TOL, 'hypervolume');
      for (const k of ['bacc', 'dtl', 'sws']) assert.ok(Math.abs(gf.pick.criteria[k] / cf.pick.criteria[k] - 1) <= TOL, `pick ${k}`);
      assert.equal(fronts.gpu.hifiRuns, fronts.cpu.hifiRuns);

      // Benchmark: the 160 x 120 HiFi map, GPU path (a GpuMaps of this thread, the kernel
      // compiled once) against the CPU path (a fresh session each time), 5 runs each.
      const bench = await page.evaluate(async () => {
        const a = window.__ridelab;
        const api = await a.onDemandApi();
        const gpu = await api.GpuMaps.request();
        const times = { gpu: [], cpu: [] };
        for (let k = 0; k < 5; k++) {
          let t0 = performance.now();
          await gpu.hifiMap(a.state, 160, 120);
          times.gpu.push(performance.now() - t0);
          t0 = performance.now();
          const x = new api.Explorer(a.state);
          x.maps('hifi', 160, 120);
          times.cpu.push(performance.now() - t0);
          x.free();
        }
        return times;
      });
      const [g, c] = [median(bench.gpu), median(bench.cpu)];
      t.diagnostic(`160 x 120 HiFi map, median of 5: GPU (${hifi.gpu.adapter}) ${g.toFixed(0)} ms, CPU ${c.toFixed(0)} ms (GPU / CPU ${(g / c).toFixed(2)}); runs GPU ${bench.gpu.map((v) => v.toFixed(0))}, CPU ${bench.cpu.map((v) => v.toFixed(0))}`);
      assertClean(log);
      await context.close();
    }
  } finally {
    await browser.close();
  }
});
