// Downloads: CSV of the maps and fronts on screen, slide-size PNGs of every chart, and a
// zip that bundles many files into one download (browsers drop bursts of downloads).
// Everything is made in the page; nothing is sent anywhere.

import { drawLineChart } from '../ridelab-first.js';

/** Saves `blob` as `name` through a temporary link (no request leaves the page). */
export function download(name, blob) {
  const url = URL.createObjectURL(blob);
  const link = document.createElement('a');
  link.href = url;
  link.download = name;
  document.body.append(link);
  link.click();
  link.remove();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
}

/**
 * CSV of map data `m` over design box `box` (`model`: lofi, hifi, surrogate; or error,
 * whose columns are the surrogate's signed error against the HiFi in %): one row per
 * cell, at its centre.
 */
export function mapsCsv(box, model, m) {
  const n = m.nx * m.ny;
  const lines = [
    model === 'error'
      ? 'ks_N_per_m,cs_Ns_per_m,bacc_error_percent,dtl_error_percent,sws_error_percent,feasible'
      : 'ks_N_per_m,cs_Ns_per_m,bacc_m_per_s2,dtl_N,sws_m,feasible',
  ];
  for (let j = 0; j < m.ny; j++) {
    const cs = box.cs_min + ((j + 0.5) * (box.cs_max - box.cs_min)) / m.ny;
    for (let i = 0; i < m.nx; i++) {
      const ks = box.ks_min + ((i + 0.5) * (box.ks_max - box.ks_min)) / m.nx;
      const k = j * m.nx + i;
      lines.push(`${ks},${cs},${m.values[k]},${m.values[n + k]},${m.values[2 * n + k]},${m.feasible[k]}`);
    }
  }
  return lines.join('\n') + '\n';
}

/**
 * CSV of the STM front, the NSGA-II one when computed (`{error}` results are left out)
 * and the adaptive loop's front when one runs (`adaptive`: js/chartspecs.js
 * `adaptivePlane`; method `adaptive`, its pick marked).
 */
export function frontCsv(front, nsga, adaptive = null) {
  const lines = ['method,ks_N_per_m,cs_Ns_per_m,bacc_m_per_s2,dtl_N,sws_m,pick'];
  const row = (name, p, pick) => lines.push(`${name},${p.ks},${p.cs},${p.bacc},${p.dtl},${p.sws},${pick ? 1 : 0}`);
  for (const [name, r] of [['stm', front], ['nsga2', nsga]]) {
    if (!r || r.error) continue;
    r.study.front.forEach((p, i) => row(name, p, i === r.study.pick.index));
  }
  if (adaptive) adaptive.front.forEach((p, i) => row('adaptive', p, i === adaptive.pick.index));
  return lines.join('\n') + '\n';
}

/** The PNG of a canvas. */
function pngOf(canvas) {
  return new Promise((resolve, reject) => canvas.toBlob((b) => (b ? resolve(b) : reject(new Error('the canvas made no PNG'))), 'image/png'));
}

/** Slide size: charts are laid out at this many logical px wide and drawn at `SLIDE_SCALE` px each. */
const SLIDE = { width: 800, height: 500, scale: 2 };

/**
 * A chart of `exportCharts` (js/svgexport.js) as a slide-size PNG (1600 px wide): line
 * charts drawn by plotters at twice their logical size, maps by their view.
 */
export function slidePng(chart) {
  if (chart.kind === 'map') return pngOf(chart.view.snapshot(SLIDE.width, SLIDE.width * 0.75, SLIDE.scale, 1));
  const c = document.createElement('canvas');
  const spec = { ...chart.spec, width: SLIDE.width, height: Math.round(SLIDE.width * (chart.spec.height / chart.spec.width)) };
  c.width = spec.width * SLIDE.scale;
  c.height = spec.height * SLIDE.scale;
  drawLineChart(c, spec, SLIDE.scale, 'all');
  return pngOf(c);
}

/**
 * Every chart of `charts` (js/svgexport.js `exportCharts`) as a slide-size PNG,
 * `[{name, data}]` with `name(chart)` as file name; `progress(n, total)` before each
 * chart and once at the end, the page painted in between (the charts take seconds).
 */
export async function slidePngs(charts, name, progress) {
  const files = [];
  for (const c of charts) {
    progress(files.length, charts.length);
    await new Promise((resolve) => setTimeout(resolve, 0));
    files.push({ name: name(c), data: await slidePng(c) });
  }
  progress(files.length, charts.length);
  return files;
}

// ---------------------------------------------------------------- zip

/** The entries' date: 1980-01-01, the first a zip can hold (the files are made now, not dated). */
const DOS_DATE = (1 << 5) | 1;

let crcTable = null;

/** CRC-32 (IEEE) of `bytes`. */
export function crc32(bytes) {
  if (!crcTable) {
    crcTable = new Uint32Array(256);
    for (let n = 0; n < 256; n++) {
      let c = n;
      for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
      crcTable[n] = c >>> 0;
    }
  }
  let c = 0xffffffff;
  for (let i = 0; i < bytes.length; i++) c = crcTable[(c ^ bytes[i]) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

/**
 * A zip archive (stored, no compression: PNGs are compressed already) of `files`
 * (`[{name, data}]`, `data` a Blob or a string) as a Blob.
 */
export async function zip(files) {
  const enc = new TextEncoder();
  const parts = [];
  const central = [];
  let offset = 0;
  for (const f of files) {
    const data = typeof f.data === 'string' ? enc.encode(f.data) : new Uint8Array(await f.data.arrayBuffer());
    const name = enc.encode(f.name);
    const crc = crc32(data);
    const local = new DataView(new ArrayBuffer(30));
    local.setUint32(0, 0x04034b50, true);
    local.setUint16(4, 20, true); // version needed
    local.setUint16(6, 0x0800, true); // UTF-8 names
    local.setUint16(8, 0, true); // stored
    local.setUint16(12, DOS_DATE, true);
    local.setUint32(14, crc, true);
    local.setUint32(18, data.length, true);
    local.setUint32(22, data.length, true);
    local.setUint16(26, name.length, true);
    parts.push(local, name, data);
    const cd = new DataView(new ArrayBuffer(46));
    cd.setUint32(0, 0x02014b50, true);
    cd.setUint16(4, 20, true);
    cd.setUint16(6, 20, true);
    cd.setUint16(8, 0x0800, true);
    cd.setUint16(14, DOS_DATE, true);
    cd.setUint32(16, crc, true);
    cd.setUint32(20, data.length, true);
    cd.setUint32(24, data.length, true);
    cd.setUint16(28, name.length, true);
    cd.setUint32(42, offset, true);
    central.push(cd, name);
    offset += 30 + name.length + data.length;
  }
  const size = central.reduce((s, p) => s + p.byteLength, 0);
  const end = new DataView(new ArrayBuffer(22));
  end.setUint32(0, 0x06054b50, true);
  end.setUint16(8, files.length, true);
  end.setUint16(10, files.length, true);
  end.setUint32(12, size, true);
  end.setUint32(16, offset, true);
  return new Blob([...parts, ...central, end], { type: 'application/zip' });
}
