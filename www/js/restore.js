// What of a link or a session file can be used. Each key is read on its own: a bad one
// keeps its default and is named, with its reason, among the `problems`; the good ones
// (a custom car's JSON and the kept designs included) apply. The core checks the state
// as a whole and names the field it refuses: that field goes back to its default and
// the check runs again, until the core accepts the state.

import { decodeHash } from './urlstate.js';
import { explain, plainWords } from './controls.js';
import { DEFAULT_VIEW, MODEL_NAMES } from './store.js';
import { MAX_SAVED } from './compare.js';

/** The state keys behind each field the core names (a refused field resets them all). */
const FIELD_KEYS = {
  box: ['ksMin', 'ksMax', 'csMin', 'csMax'],
  car: ['car', 'carJson'],
  cases: ['cases', 'case'],
};

/** How many refusals one state may take before it is given up as a whole. */
const MAX_TRIES = 40;

const same = (a, b) => JSON.stringify(a ?? null) === JSON.stringify(b ?? null);

/**
 * The keys of `s` whose values alone (over `defaults`) the core cannot even read (a
 * string for a number): the core names no field for those, so each key is tried alone.
 */
async function unreadable(check, s, defaults) {
  const bad = [];
  for (const k of Object.keys(s)) {
    if (same(s[k], defaults[k])) continue;
    try {
      await check({ ...defaults, [k]: s[k], ...(k === 'carJson' ? { car: 'custom' } : {}) });
    } catch (e) {
      if (e.field === 'state') bad.push({ key: k, e });
    }
  }
  return bad;
}

/**
 * `s` with every field the core refuses put back to its default (`check(state)`: the
 * core's check, rejecting with `{message, field}`). Each refusal is pushed to `problems`
 * in the page's words, naming the field (`label(key)`: how the source names a state key).
 * Resolves `{state, reset}` (`reset`: the keys put back); rejects with the core's failure
 * when a refusal names no field of the state.
 */
async function usableState(check, s, defaults, problems, label = (k) => k) {
  const state = { ...s };
  const reset = new Set();
  for (let tries = 0; tries < MAX_TRIES; tries++) {
    let failure;
    try {
      await check(state);
      return { state, reset };
    } catch (e) {
      failure = e;
    }
    let keys;
    if (failure.field === 'state') {
      const bad = await unreadable(check, state, defaults);
      for (const { key, e } of bad) problems.push(`${label(key)}: ${plainWords(e.message)}`);
      keys = bad.map((b) => b.key);
    } else {
      keys = (FIELD_KEYS[failure.field] || (Object.hasOwn(defaults, failure.field) ? [failure.field] : []))
        .filter((k) => !same(state[k], defaults[k]));
      if (keys.length) problems.push(explain(failure, failure.field));
    }
    if (!keys.length) throw failure;
    for (const k of keys) {
      state[k] = defaults[k];
      reset.add(k);
    }
  }
  throw { message: 'too many fields refused', field: '' };
}

/** How a link names each state key (its URL key). */
const LINK_KEYS = {
  carJson: 'carjson', swsLimit: 'sws', ksMin: 'box', ksMax: 'box', csMin: 'box', csMax: 'box', bounceBand: 'bb',
  dampingBand: 'db', noWorse: 'nw', dtlMargin: 'dm', travel: 'tr', surrogate: 'sur',
};

/**
 * The state, view and kept designs of a link's hash as far as they can be used:
 * `{state, view, kept, problems}` (`problems`: every bad key with its reason). The design
 * a link leaves out, or whose Ks or Cs is refused, is its car's own (datum) front spring
 * or damper. `compute`: js/compute.js (`checkState`, `describe`).
 */
export async function fromLink(compute, defaults, hash) {
  const d = decodeHash(hash);
  const problems = [...d.problems];
  const s = { ...defaults, ...d.state };
  if (s.car !== 'custom') s.carJson = null;
  const check = (x) => compute.checkState(x);
  const label = (k) => LINK_KEYS[k] || k;
  let { state, reset } = await usableState(check, s, defaults, problems, label);
  const own = (k) => d.state[k] !== undefined && !reset.has(k);
  if (!own('ks') || !own('cs')) {
    const desc = await compute.describe({ ...state, ks: defaults.ks, cs: defaults.cs }).catch(() => null);
    if (desc) {
      if (!own('ks')) state.ks = desc.datumKs;
      if (!own('cs')) state.cs = desc.datumCs;
      ({ state } = await usableState(check, state, defaults, problems, label));
    }
  }
  return { state, view: d.view, kept: d.kept, problems };
}

/**
 * A session file's `{state, view, kept, problems}`: throws `{message}` only for text that
 * is not JSON, not a RideLab session or has no state; every other bad key (of the file,
 * its view, its state, its kept designs) is named in `problems` and left out or kept at
 * its default, and the rest applies.
 */
export async function fromSession(compute, defaults, text) {
  let s;
  try {
    s = JSON.parse(text);
  } catch {
    throw { message: 'not a RideLab session file (not JSON)' };
  }
  if (!s || typeof s !== 'object' || s.ridelab !== 'session') throw { message: 'not a RideLab session file (no "ridelab": "session")' };
  if (typeof s.state !== 'object' || s.state === null || Array.isArray(s.state)) throw { message: 'the session has no state' };
  const problems = [];
  for (const k of Object.keys(s)) {
    if (!['ridelab', 'version', 'state', 'view', 'kept'].includes(k)) problems.push(`unknown session key '${k}' (left out)`);
  }
  const view = sessionView(s.view, problems);
  const kept = sessionKept(s.kept, problems);
  const state = { ...defaults };
  for (const [k, v] of Object.entries(s.state)) {
    if (k === 'roadProfile') {
      if (v) problems.push(`state.roadProfile: a measured road's file is not kept in a session (its class is used; drop the file on the Car & road tab again)`);
    } else if (Object.hasOwn(defaults, k)) state[k] = v;
    else problems.push(`state: '${k}' is not a known field (left out)`);
  }
  const r = await usableState((x) => compute.checkState(x), state, defaults, problems, (k) => `state.${k}`);
  return { state: r.state, view, kept, problems };
}

/** A session's view: each bad key named in `problems` and left at its default. */
function sessionView(v, problems) {
  const view = { ...DEFAULT_VIEW };
  if (v === undefined) return view;
  if (!v || typeof v !== 'object' || Array.isArray(v)) {
    problems.push('view: must be an object (the default view is shown)');
    return view;
  }
  for (const [k, x] of Object.entries(v)) {
    const ok = {
      scale: ['abs', 'rel'].includes(x),
      model: Object.hasOwn(MODEL_NAMES, x),
      plan: typeof x === 'boolean',
      ratio: typeof x === 'boolean',
      projector: typeof x === 'boolean',
      palette: ['viridis', 'cividis'].includes(x),
      nsga: typeof x === 'boolean',
    }[k];
    if (ok === undefined) problems.push(`unknown view key '${k}' (left out)`);
    else if (!ok) problems.push(`view: ${k} cannot be ${JSON.stringify(x)} (kept the default)`);
    else view[k] = x;
  }
  return view;
}

/** A session's kept designs: each bad pair named in `problems` and left out; null for none. */
function sessionKept(kept, problems) {
  if (kept === undefined || kept === null) return null;
  if (!Array.isArray(kept)) {
    problems.push(`kept: must be a list of [Ks N/m, Cs N s/m] pairs (left out)`);
    return null;
  }
  const out = [];
  kept.forEach((xy, i) => {
    if (!(Array.isArray(xy) && xy.length === 2 && xy.every((x) => Number.isFinite(x) && x > 0))) {
      problems.push(`kept[${i}]: ${JSON.stringify(xy)} is not a [Ks N/m, Cs N s/m] pair of numbers > 0 (left out)`);
    } else if (out.length >= MAX_SAVED) {
      problems.push(`kept[${i}]: at most ${MAX_SAVED} designs are kept (left out)`);
    } else out.push(xy);
  });
  return out.length ? out : null;
}
