// Lessons, the model behind the lesson panel (js/lessonpanel.js). A lesson is a JSON
// object `{ridelab: "lesson", version: 1, title, steps}`; each step sets a view (`view`:
// the link's hash without '#', js/urlstate.js; '' is the default view), asks a
// `question`, may offer `options` for the class's prediction, and has a `reveal` whose
// `{placeholders}` are filled in with the numbers the page has computed for the current
// car and road; `highlight` lists the ids of what to look at once revealed, `hide` the
// ids veiled until the class has answered. This file holds the checks of that format
// (each message names the step and field), the placeholders and their resolution, and
// the lesson as a file and as a link (`#lesson=<base64url of the JSON>`).

import { decodeHash } from './urlstate.js';
import { fmt, fmtPct } from './format.js';

const LESSON_VERSION = 1;
/** Limits of a lesson file. */
const MAX_STEPS = 40;
const MAX_TEXT = 2000;
const MAX_OPTIONS = 6;

/** A step's keys; `answer` (optional): the number, 1.., of the right option, marked at the reveal. */
const STEP_KEYS = ['view', 'question', 'options', 'reveal', 'highlight', 'hide', 'answer'];

// ---------------------------------------------------------------- placeholders

const kn = (v) => `${fmt(v / 1000, 4)} kN/m`;
const kns = (v) => `${fmt(v / 1000, 4)} kNs/m`;

/** The criteria as the readout shows them (js/readout.js): value and its text with unit. */
const CRIT = {
  bacc: { name: 'BAcc', get: (r) => r.bacc, show: (v) => `${fmt(v, 4)} m/s²` },
  dtl: { name: 'DTL', get: (r) => r.dtl, show: (v) => `${fmt(v, 4)} N` },
  dtlrel: { name: 'DTL / static wheel load', get: (r) => r.dtl_relative, show: (v) => `${fmt(v * 100, 3)} %` },
  sws: { name: 'SWS', get: (r) => r.sws, show: (v) => `${fmt(v * 1000, 4)} mm` },
};
const MODELS = { lofi: 'LoFi quarter car', hifi: 'HiFi full car', sur: 'surrogate' };

/** The quarter car's variance intensity W (one-sided road velocity PSD / 2), m²/s³. */
const intensity = (d) => d.desc.velocityPsd / 2;

/** The objective plane's front study, or false when there is none (no design meets the objectives). */
const study = (d) => (d.front && !d.front.error ? d.front.study : false);

/**
 * Every placeholder: `needs` (the results it waits for: 'hifi', 'front', 'fit', 'maps'),
 * `get(d)` its value (SI, or text; `undefined` when there is none, e.g. no pick on an
 * infeasible road), `show(v)` its text with unit, `about` what it is.
 */
export const PLACEHOLDERS = {};

function def(name, about, get, show, needs = []) {
  PLACEHOLDERS[name] = { about, get, show, needs };
}

for (const [m, model] of Object.entries(MODELS)) {
  const needs = m === 'hifi' ? ['hifi'] : [];
  for (const [c, crit] of Object.entries(CRIT)) {
    def(`${m}.${c}`, `${crit.name} of the design, ${model}`, (d) => crit.get(d[m].design), crit.show, needs);
    def(`${m}.${c}.pct`, `${crit.name} of the design against the datum, ${model}, %`, (d) => crit.get(d[m].design) / crit.get(d[m].datum) - 1, fmtPct, needs);
    def(`${m}.datum.${c}`, `${crit.name} of the datum design, ${model}`, (d) => crit.get(d[m].datum), crit.show, needs);
  }
}
for (const [c, crit] of Object.entries(CRIT)) {
  def(`datum.${c}`, `${crit.name} of the datum design, HiFi full car (as hifi.datum.${c})`, (d) => crit.get(d.hifi.datum), crit.show, ['hifi']);
  if (c !== 'dtlrel') def(`gap.${c}`, `fidelity gap of ${crit.name}: HiFi against LoFi at the design, %`, (d) => crit.get(d.hifi.design) / crit.get(d.lofi.design) - 1, fmtPct, ['hifi']);
}
def('ks', 'the design spring rate Ks', (d) => d.state.ks, kn);
def('cs', 'the design damper rate Cs', (d) => d.state.cs, kns);
def('datum.ks', "the datum car's front spring rate", (d) => d.desc.datumKs, kn);
def('datum.cs', "the datum car's front damper rate", (d) => d.desc.datumCs, kns);
def('bounce', 'body bounce frequency of the design (LoFi)', (d) => d.lofi.design.body_bounce_hz, (v) => `${fmt(v, 3)} Hz`);
def('zeta', 'damping ratio of the design (LoFi)', (d) => d.lofi.design.damping_ratio, (v) => fmt(v, 3));
def('ms', "the quarter car's sprung mass ms = M b / (2 L)", (d) => d.desc.quarter.ms, (v) => `${fmt(v, 4)} kg`);
def('mu', "the quarter car's unsprung mass mu", (d) => d.desc.quarter.mu, (v) => `${fmt(v, 4)} kg`);
def('kt', 'the tyre rate kt', (d) => d.desc.quarter.kt, kn);
def('cs_opt', "the quarter car's comfort-optimal damping for the design's Ks: cs = ks √((ms + mu) / kt)",
  (d) => d.state.ks * Math.sqrt((d.desc.quarter.ms + d.desc.quarter.mu) / d.desc.quarter.kt), kns);
def('cs_dtl', "the quarter car's DTL-optimal damping for the design's Ks (from the closed form of var(DTL))", (d) => {
  const { ms, mu, kt } = d.desc.quarter;
  const ks = d.state.ks;
  const r = (ms + mu) / ms;
  return Math.sqrt((kt * kt * mu + r * r * ks * ks * (ms + mu) - 2 * ks * kt * mu * r) / (r * r * kt));
}, kns);
def('ks_dtl', "the quarter car's spring below which DTL rises again, whatever the damping: ks = kt mu ms / (ms + mu)²", (d) => {
  const { ms, mu, kt } = d.desc.quarter;
  return (kt * mu * ms) / ((ms + mu) * (ms + mu));
}, kn);
def('cs_sws', "the quarter car's least damping meeting the SWS limit: cs = W (ms + mu) / (2 limit²)", (d) => {
  const lim = d.desc.swsLimit;
  return lim == null ? undefined : (intensity(d) * (d.desc.quarter.ms + d.desc.quarter.mu)) / (2 * lim * lim);
}, kns);
def('speed', 'the speed', (d) => d.state.speed, (v) => `${fmt(v, 3)} m/s (${fmt(v * 3.6, 3)} km/h)`);
def('class', 'the ISO 8608 road class', (d) => d.state.class, (v) => v);
def('wheelbase', 'the wheelbase L = a + b', (d) => d.desc.car.a + d.desc.car.b, (v) => `${fmt(v, 4)} m`);
def('delay', 'the rear wheels\' delay L / v behind the front', (d) => d.desc.delay, (v) => `${fmt(v * 1000, 3)} ms`);
def('heave_null', 'the lowest frequency where front and rear inputs cancel in heave, 1 / (2 L / v)', (d) => 1 / (2 * d.desc.delay), (v) => `${fmt(v, 3)} Hz`);
def('sws_limit', 'the SWS limit', (d) => (d.desc.swsLimit == null ? undefined : d.desc.swsLimit), (v) => `${fmt(v * 1000, 4)} mm`);
def('box.cs_max', "the design box's largest Cs", (d) => d.desc.designBox.cs_max, kns);
def('feasible', 'the share of the design box meeting the design objectives (the maps shown)', (d) => d.maps.feasibleCount / (d.maps.nx * d.maps.ny), (v) => `${fmt(v * 100, 3)} %`, ['maps']);
def('grid.cells', 'the designs each map evaluates', (d) => d.maps.nx * d.maps.ny, (v) => String(v), ['maps']);
def('front.points', 'the designs on the Pareto front (objective plane)', (d) => (study(d) ? study(d).front.length : undefined), (v) => String(v), ['front']);
def('front.evals', 'the surrogate evaluations the front took', (d) => (study(d) ? study(d).evaluations : undefined), (v) => String(v), ['front']);
def('front.status', 'the front in words: its size, or why there is none', (d) =>
  (study(d) ? `${study(d).front.length} designs on the front` : `no design meets the objectives: ${d.front.error.replace(/^[\w.]+: (no feasible design: )?/, '')}`), (v) => v, ['front']);
def('pick.ks', "the min-max pick's Ks", (d) => (study(d) ? study(d).pick.ks : undefined), kn, ['front']);
def('pick.cs', "the min-max pick's Cs", (d) => (study(d) ? study(d).pick.cs : undefined), kns, ['front']);
['bacc', 'dtl', 'sws'].forEach((c, i) => {
  def(`pick.${c}.pct`, `the pick's ${CRIT[c].name} against the datum, as the surrogate predicts, %`,
    (d) => (study(d) ? study(d).pick.change_percent[i] / 100 : undefined), fmtPct, ['front']);
  def(`recheck.${c}`, `the pick's ${CRIT[c].name} re-checked on the HiFi`, (d) => (study(d) ? d.front.recheck.rechecked[c] : undefined), CRIT[c].show, ['front']);
  def(`recheck.${c}.pct`, `the pick's ${CRIT[c].name} against the HiFi datum, re-checked on the HiFi, %`,
    (d) => (study(d) ? d.front.recheck.rechecked_change_percent[i] / 100 : undefined), fmtPct, ['front']);
});
def('recheck.err', "the largest error of the surrogate's prediction at the pick against its HiFi re-check, %",
  (d) => (study(d) ? Math.max(...d.front.recheck.error_percent.map(Math.abs)) / 100 : undefined), (v) => `${fmt(v * 100, 2)} %`, ['front']);
def('plan', "the surrogate's sampling plan", (d) => d.state.plan, (v) => v);
def('samples', 'the HiFi runs the surrogate is fitted to', (d) => d.fit.samples.length, (v) => String(v), ['fit']);
for (const c of ['bacc', 'dtl', 'sws']) {
  def(`fit.rte.${c}`, `the surrogate's largest relative error in ${CRIT[c].name} on the 20 × 20 HiFi grid, %`, (d) => d.fit.metrics[c].rte_max_percent / 100, (v) => `${fmt(v * 100, 3)} %`, ['fit']);
  def(`fit.rte_mean.${c}`, `the surrogate's mean relative error in ${CRIT[c].name} on the 20 × 20 HiFi grid, %`, (d) => d.fit.metrics[c].rte_mean_percent / 100, (v) => `${fmt(v * 100, 3)} %`, ['fit']);
}

const PLACEHOLDER = /\{([a-z_][a-z0-9_.]*)\}/gi;

/** The placeholder names in `text`, in order. */
function placeholdersIn(text) {
  return [...text.matchAll(PLACEHOLDER)].map((m) => m[1]);
}

/**
 * `text` as parts: `{text}` for literal text, `{name, value, text}` for a placeholder
 * (`value` SI or undefined, `text` with unit), `{name, pending: true}` while a result it
 * needs is still being computed. `data`: `{state, desc, lofi, hifi, sur, front, fit,
 * maps}`, each result null while it is computed (`hifi`, `fit`, `maps` only when they
 * belong to the current state).
 */
export function resolve(text, data) {
  const parts = [];
  let at = 0;
  for (const m of text.matchAll(PLACEHOLDER)) {
    if (m.index > at) parts.push({ text: text.slice(at, m.index) });
    at = m.index + m[0].length;
    const p = PLACEHOLDERS[m[1]];
    if (!p) {
      // Checked on load; kept as typed while a teacher edits.
      parts.push({ text: m[0] });
      continue;
    }
    if (p.needs.some((n) => data[n] == null)) {
      parts.push({ name: m[1], pending: true });
      continue;
    }
    const value = p.get(data);
    const ok = value !== undefined && (typeof value === 'string' || Number.isFinite(value));
    parts.push({ name: m[1], value: ok ? value : undefined, text: ok ? p.show(value) : 'none (no design meets the objectives)' });
  }
  if (at < text.length) parts.push({ text: text.slice(at) });
  return parts;
}

// ---------------------------------------------------------------- the format

const fail = (message) => {
  throw { message };
};

function text(v, where, { optional = false } = {}) {
  if (v === undefined && optional) return undefined;
  if (typeof v !== 'string' || v.trim() === '') fail(`${where}: must be a non-empty string`);
  if (v.length > MAX_TEXT) fail(`${where}: longer than ${MAX_TEXT} characters`);
  const unknown = placeholdersIn(v).find((n) => !Object.hasOwn(PLACEHOLDERS, n));
  if (unknown) fail(`${where}: unknown placeholder {${unknown}}`);
  return v;
}

function ids(v, where) {
  if (v === undefined) return [];
  if (!Array.isArray(v)) fail(`${where}: must be a list of element ids`);
  v.forEach((x, i) => {
    if (typeof x !== 'string' || !/^[A-Za-z][\w-]*$/.test(x)) fail(`${where}[${i}]: must be an element id (letters, digits, - and _)`);
  });
  return [...v];
}

/**
 * The lesson in `obj` (a parsed file), checked and normalised (missing lists empty).
 * Throws `{message}` naming the step and field, e.g. `steps[2].question: must be a
 * non-empty string`. Element ids and view values are checked by the panel, which knows
 * the page and the core (js/lessonpanel.js).
 */
export function checkLesson(obj) {
  if (!obj || typeof obj !== 'object' || Array.isArray(obj)) fail('not a RideLab lesson (not a JSON object)');
  if (obj.ridelab !== 'lesson') fail('ridelab: must be "lesson" (not a RideLab lesson file)');
  if (obj.version !== LESSON_VERSION) fail(`version: must be ${LESSON_VERSION}`);
  const unknown = Object.keys(obj).find((k) => !['ridelab', 'version', 'title', 'steps'].includes(k));
  if (unknown) fail(`unknown key '${unknown}'`);
  const title = text(obj.title, 'title');
  if (!Array.isArray(obj.steps) || obj.steps.length === 0) fail('steps: must be a list of at least one step');
  if (obj.steps.length > MAX_STEPS) fail(`steps: at most ${MAX_STEPS} steps`);
  const steps = obj.steps.map((s, i) => {
    const at = `steps[${i}]`;
    if (!s || typeof s !== 'object' || Array.isArray(s)) fail(`${at}: must be an object`);
    const extra = Object.keys(s).find((k) => !STEP_KEYS.includes(k));
    if (extra) fail(`${at}: unknown key '${extra}'`);
    if (typeof s.view !== 'string') fail(`${at}.view: must be a string (a link's hash, '' for the default view)`);
    const problems = decodeHash(s.view).problems;
    if (problems.length) fail(`${at}.view: ${problems[0]}`);
    let options = [];
    if (s.options !== undefined) {
      const n = Array.isArray(s.options) ? s.options.length : -1;
      if (n !== 0 && (n < 2 || n > MAX_OPTIONS)) {
        fail(`${at}.options: must be a list of 2 to ${MAX_OPTIONS} answers (or empty, or left out)`);
      }
      options = s.options.map((o, j) => text(o, `${at}.options[${j}]`));
    }
    if (s.answer !== undefined && !(Number.isInteger(s.answer) && s.answer >= 1 && s.answer <= options.length)) {
      fail(`${at}.answer: must be the number of one of its options (1 to ${options.length})`);
    }
    return {
      view: s.view.replace(/^#/, ''),
      question: text(s.question, `${at}.question`),
      options,
      reveal: text(s.reveal, `${at}.reveal`),
      highlight: ids(s.highlight, `${at}.highlight`),
      hide: ids(s.hide, `${at}.hide`),
      ...(s.answer !== undefined ? { answer: s.answer } : {}),
    };
  });
  return { ridelab: 'lesson', version: LESSON_VERSION, title, steps };
}

/** A lesson file's text, checked (throws `{message}` as `checkLesson`). */
export function readLesson(textIn) {
  let obj;
  try {
    obj = JSON.parse(textIn);
  } catch {
    fail('not a RideLab lesson file (not JSON)');
  }
  return checkLesson(obj);
}

/** The lesson as a file's text (empty lists left out). */
export function lessonJson(lesson) {
  const steps = lesson.steps.map((s) => {
    const out = { view: s.view, question: s.question };
    if (s.options.length) out.options = s.options;
    out.reveal = s.reveal;
    if (s.highlight.length) out.highlight = s.highlight;
    if (s.hide.length) out.hide = s.hide;
    return out;
  });
  return JSON.stringify({ ridelab: 'lesson', version: LESSON_VERSION, title: lesson.title, steps }, null, 2) + '\n';
}

// ---------------------------------------------------------------- the link

function toBase64url(str) {
  let bin = '';
  for (const b of new TextEncoder().encode(str)) bin += String.fromCharCode(b);
  return btoa(bin).replace(/\+/g, '-').replace(/\//g, '_').replace(/=+$/, '');
}

function fromBase64url(s) {
  const bin = atob(s.replace(/-/g, '+').replace(/_/g, '/'));
  return new TextDecoder('utf-8', { fatal: true }).decode(Uint8Array.from(bin, (c) => c.charCodeAt(0)));
}

/** The link hash of a lesson: `#lesson=<base64url of its JSON>`. */
export function lessonHash(lesson) {
  return `#lesson=${toBase64url(JSON.stringify(JSON.parse(lessonJson(lesson))))}`;
}

/**
 * A lesson link's content: null when `hash` is no lesson link, `{id}` for a shipped
 * lesson (`#lesson=comfort`), `{lesson}` for an encoded one; throws `{message}` when the
 * link cannot be read or its lesson is malformed.
 */
export function readLessonHash(hash, shippedIds) {
  const m = /^#?lesson=(.*)$/s.exec(hash || '');
  if (!m) return null;
  const v = decodeURIComponent(m[1]);
  if (shippedIds.includes(v)) return { id: v };
  let textIn;
  try {
    textIn = fromBase64url(v);
  } catch {
    fail('the lesson link could not be read (not base64url)');
  }
  return { lesson: readLesson(textIn) };
}
