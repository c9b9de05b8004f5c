// The view state in the URL hash, so that a link reproduces the view:
//   #car=sedan&ks=19960&cs=1290&class=B&speed=20&tracks=correlated&sws=7
//    &box=10000,40000,500,4000&bb=0.8,1.5&db=0.2,0.5&nw=0,1,0&sur=rba-mul-rbf-mq&plan=ae:10
//    &comfort=wk&pick=asf:0.3
//    &model=hifi&samples=0&scale=rel&axes=ratio&pal=cividis&proj=1&pz=0.1,0.6,0,0.5
// ks in N/m, cs in N s/m, speed in m/s (SI, as the CLI), sws (the SWS limit) in mm,
// box (Ks from, to, Cs from, to) in N/m and N s/m, bb (bounce band) in Hz, db (damping
// band) dimensionless, nw (no worse than datum: BAcc, DTL, SWS) as 0/1, comfort (bacc or
// wk) and pick (minmax, knee or asf:W) only when not the default; the view: the
// maps' model, their sample plan (samples=0 hides it), colour scale and palette, the
// objective plane's axes and projector mode (`large=1`, from earlier links, means proj=1).
// A custom car travels as its JSON text: car=custom&carjson=...
// The robust design's cases (issue #16) travel as their cases file, compact JSON:
// cases={"load_cases":[...],"operating":[...],"combine":"worst"}, and the case the maps
// show as case=K (left out for the robust maps).
// The designs kept to compare travel as keep=ks:cs,ks:cs (N/m : N s/m, at most MAX_SAVED);
// the page evaluates them again on the link's car and road.

import { MAX_SAVED } from './compare.js';
import { compactCases } from './robustcases.js';

const NUMBERS = { ks: 'ks', cs: 'cs', speed: 'speed', dm: 'dtlMargin' };

/** True for a lesson link's hash (`#lesson=...`). */
export function isLessonHash(hash) {
  return /^#?lesson=/.test(hash || '');
}

/**
 * The hash (with '#') for `state` (core state), `view` (page-only settings) and `kept`
 * (the designs kept to compare, `[[ks N/m, cs N s/m], ...]`).
 */
export function encodeHash(state, view, kept = []) {
  const p = new URLSearchParams();
  p.set('car', state.car);
  if (state.car === 'custom' && state.carJson) p.set('carjson', state.carJson);
  p.set('ks', String(state.ks));
  p.set('cs', String(state.cs));
  p.set('class', state.class);
  p.set('speed', String(state.speed));
  p.set('tracks', state.tracks);
  if (state.swsLimit !== null && state.swsLimit !== undefined) p.set('sws', String(+(state.swsLimit * 1000).toPrecision(12)));
  if (state.ksMin != null) p.set('box', [state.ksMin, state.ksMax, state.csMin, state.csMax].join(','));
  if (state.bounceBand) p.set('bb', state.bounceBand.join(','));
  if (state.dampingBand) p.set('db', state.dampingBand.join(','));
  if (state.noWorse) p.set('nw', state.noWorse.map((b) => (b ? 1 : 0)).join(','));
  if (state.dtlMargin != null) p.set('dm', String(state.dtlMargin));
  if (state.travel) p.set('tr', state.travel.join(','));
  if (state.surrogate) p.set('sur', state.surrogate);
  if (state.plan) p.set('plan', state.plan);
  if (state.comfort && state.comfort !== 'bacc') p.set('comfort', state.comfort);
  if (state.pick && state.pick !== 'minmax') p.set('pick', state.pick);
  if (state.cases) p.set('cases', compactCases(state.cases));
  if (state.cases && state.case && state.case !== 'robust') p.set('case', state.case);
  if (view.model && view.model !== 'lofi') p.set('model', view.model);
  if (view.plan === false) p.set('samples', '0');
  if (view.scale && view.scale !== 'abs') p.set('scale', view.scale);
  if (view.ratio) p.set('axes', 'ratio');
  if (view.palette && view.palette !== 'viridis') p.set('pal', view.palette);
  if (view.projector) p.set('proj', '1');
  if (view.planeZoom) p.set('pz', view.planeZoom.join(','));
  if (kept.length) p.set('keep', kept.map(([ks, cs]) => `${ks}:${cs}`).join(','));
  return '#' + p.toString();
}

/**
 * Reads a hash. Returns `{state, view, kept, problems}`: `state` holds only the keys
 * present and readable (the caller merges them over the defaults and lets the core
 * validate them, js/restore.js), `kept` the kept designs that are Ks:Cs pairs (`null`
 * when there are none), and `problems` names every key (or kept design) that could not
 * be read, with why; the others still apply.
 */
export function decodeHash(hash) {
  const out = { state: {}, view: {}, kept: null, problems: [] };
  const text = (hash || '').replace(/^#/, '');
  if (text === '') return out;
  let p;
  try {
    p = new URLSearchParams(text);
  } catch (e) {
    out.problems.push('the link could not be read');
    return out;
  }
  for (const [key, raw] of p) {
    const v = raw.trim();
    if (key in NUMBERS) {
      const n = v === '' ? NaN : Number(v);
      if (!Number.isFinite(n)) out.problems.push(`${key}: '${raw}' is not a number`);
      else out.state[NUMBERS[key]] = n;
    } else if (key === 'sws') {
      const n = v === '' ? NaN : Number(v);
      if (!Number.isFinite(n)) out.problems.push(`sws: '${raw}' is not a number`);
      else out.state.swsLimit = n / 1000;
    } else if (key === 'car') {
      out.state.car = v;
    } else if (key === 'carjson') {
      out.state.carJson = raw;
    } else if (key === 'cases') {
      // The core reads and checks it (a bad one names the field, `cases.operating[0].speed`).
      out.state.cases = raw;
    } else if (key === 'case') {
      out.state.case = v.toLowerCase();
    } else if (key === 'class') {
      out.state.class = v.toUpperCase();
    } else if (key === 'tracks') {
      out.state.tracks = v.toLowerCase();
    } else if (key === 'box' || key === 'bb' || key === 'db' || key === 'tr') {
      const n = key === 'box' ? 4 : 2;
      const xs = v.split(',').map((x) => (x.trim() === '' ? NaN : Number(x)));
      if (xs.length !== n || !xs.every(Number.isFinite)) out.problems.push(`${key}: '${raw}' is not ${n} numbers`);
      else if (key === 'box') [out.state.ksMin, out.state.ksMax, out.state.csMin, out.state.csMax] = xs;
      else out.state[{ bb: 'bounceBand', db: 'dampingBand', tr: 'travel' }[key]] = xs;
    } else if (key === 'nw') {
      const xs = v.split(',');
      if (xs.length !== 3 || !xs.every((x) => x === '0' || x === '1')) out.problems.push(`nw: '${raw}' is not three 0/1 flags`);
      else out.state.noWorse = xs.map((x) => x === '1');
    } else if (key === 'sur') {
      out.state.surrogate = v.toLowerCase();
    } else if (key === 'plan') {
      out.state.plan = v.toLowerCase();
    } else if (key === 'comfort' || key === 'pick') {
      // The core validates both (js/restore.js keeps the default for a bad one).
      out.state[key] = v.toLowerCase();
    } else if (key === 'model') {
      if (['lofi', 'hifi', 'surrogate', 'error'].includes(v)) out.view.model = v;
      else out.problems.push(`model: '${raw}' is not lofi, hifi, surrogate or error`);
    } else if (key === 'samples') {
      if (v === '1' || v === '0') out.view.plan = v === '1';
      else out.problems.push(`samples: '${raw}' is not 0 or 1`);
    } else if (key === 'scale') {
      if (v === 'abs' || v === 'rel') out.view.scale = v;
      else out.problems.push(`scale: '${raw}' is not 'abs' or 'rel'`);
    } else if (key === 'axes') {
      if (v === 'abs' || v === 'ratio') out.view.ratio = v === 'ratio';
      else out.problems.push(`axes: '${raw}' is not 'abs' or 'ratio'`);
    } else if (key === 'pal') {
      if (v === 'viridis' || v === 'cividis') out.view.palette = v;
      else out.problems.push(`pal: '${raw}' is not 'viridis' or 'cividis'`);
    } else if (key === 'keep') {
      // Each design on its own: a bad one is named and left out, the others kept.
      const kept = [];
      for (const [i, text] of v.split(',').entries()) {
        const xy = text.split(':').map((y) => (y.trim() === '' ? NaN : Number(y)));
        if (!(xy.length === 2 && xy.every((x) => Number.isFinite(x) && x > 0))) {
          out.problems.push(`keep: '${text}' is not Ks:Cs pairs in N/m and N s/m (numbers > 0), design ${i + 1} left out`);
        } else if (kept.length >= MAX_SAVED) {
          out.problems.push(`keep: at most ${MAX_SAVED} designs are kept, design ${i + 1} left out`);
        } else kept.push(xy);
      }
      out.kept = kept.length ? kept : null;
    } else if (key === 'pz') {
      // The objective plane's zoom: x0,x1,y0,y1 as fractions of its fitted axes (js/planezoom.js).
      const z = v.split(',').map((x) => (x.trim() === '' ? NaN : Number(x)));
      if (z.length !== 4 || !z.every(Number.isFinite) || !(z[1] > z[0] && z[3] > z[2])) out.problems.push(`pz: '${raw}' is not x0,x1,y0,y1 with x0 < x1 and y0 < y1`);
      else out.view.planeZoom = z;
    } else if (key === 'proj' || key === 'large') {
      if (v === '1' || v === '0') out.view.projector = v === '1';
      else out.problems.push(`${key}: '${raw}' is not 0 or 1`);
    } else {
      out.problems.push(`unknown key '${key}'`);
    }
  }
  return out;
}
