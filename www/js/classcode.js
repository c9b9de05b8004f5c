// The class front's codes (issue #30): a student sends the teacher one short line that
// carries their design and the scenario they chose it on; no server is involved.
//
//   RL1-<car>-<scenario>-<ks>-<cs>[-<name>]-<check>      e.g. RL1-sedan-0kd4nj1-19960-1290-Anna-5la5 (the sedan on the default road)
//
//   RL1       the format's version (a page reads only the versions it knows, and says so)
//   car       the car's preset name (sedan, compact, suv) or `custom`
//   scenario  7 base-36 digits of FNV-1a (32 bit) of the page's scenario key (js/store.js
//             `scenarioKey`: car, road, speed, tracks, objectives, box, surrogate, pick;
//             everything but Ks and Cs), so the teacher's page can tell whether the
//             student explored the same scenario
//   ks        the front spring rate, N/m, a whole number (the page shows 4 significant
//             digits of kN/m, so rounding to 1 N/m changes nothing shown)
//   cs        the front damper rate, N s/m, a whole number
//   name      optional: the student's name, letters, digits, `_` and `.`, 1..20 of them
//   check     4 base-36 digits of FNV-1a of everything before it (`RL1-...-<name>`):
//             a changed, lost or swapped character is caught (a wrong code passes by
//             chance about once in 1.7 million)
//
// A code may sit inside other text on its line (a chat message, a link): the first
// `RL<n>-...` on the line is read. Pure functions, no DOM: the tests import this module.

/** The version this page writes and reads. */
const CODE_VERSION = 1;

/** The most codes one Apply reads; the rest are refused, each named. */
export const MAX_CODES = 60;

/** Whole N/m and N s/m a code may carry (the engine checks the design further). */
const RATE_RANGE = [1, 9_999_999];

/** FNV-1a (32 bit) of the UTF-16 code units of `text`, an unsigned integer. */
function fnv1a(text) {
  let h = 0x811c9dc5;
  for (let i = 0; i < text.length; i++) {
    h ^= text.charCodeAt(i);
    h = Math.imul(h, 0x01000193) >>> 0;
  }
  return h >>> 0;
}

/** 7 base-36 digits of the scenario key `key` (js/store.js `scenarioKey`). */
export function scenarioHash(key) {
  return fnv1a(key).toString(36).padStart(7, '0');
}

/** 4 base-36 digits guarding `body` (the code before its check). */
function checkOf(body) {
  return (fnv1a(body) % 36 ** 4).toString(36).padStart(4, '0');
}

/** A student's name as a code carries it: spaces to `_`, other characters left out, 20 at most ('' for none). */
export function cleanName(name) {
  return Array.from(String(name || '').trim().replace(/\s+/g, '_').replace(/[^\p{L}\p{N}_.]/gu, '')).slice(0, 20).join('');
}

/**
 * The code of design `ks` N/m, `cs` N s/m on car `car` (a preset name or 'custom') and
 * the scenario of key `key`, with the optional `name`.
 */
export function encodeCode({ car, key, ks, cs, name = '' }) {
  const parts = [`RL${CODE_VERSION}`, car, scenarioHash(key), String(Math.round(ks)), String(Math.round(cs))];
  const n = cleanName(name);
  if (n) parts.push(n);
  const body = parts.join('-');
  return `${body}-${checkOf(body)}`;
}

/**
 * One code's text read: `{code: {car, scenario, ks, cs, name}}` or `{error}` (why, in
 * words). `token` starts with `RL<n>-`.
 */
export function decodeCode(token) {
  const m = /^RL(\d+)-/i.exec(token);
  if (!m) return { error: 'it does not start with RL1-' };
  if (Number(m[1]) !== CODE_VERSION) return { error: `it is a version ${m[1]} code; this page reads version ${CODE_VERSION} (RL${CODE_VERSION}-…)` };
  const parts = token.split('-');
  if (parts.length !== 6 && parts.length !== 7) return { error: `it has ${parts.length} parts; a code has 6 or 7 (RL1-car-scenario-Ks-Cs[-name]-check)` };
  const check = parts.pop();
  if (checkOf(parts.join('-')) !== check.toLowerCase()) return { error: 'its check does not match (a character was changed, lost or added)' };
  const [, car, scenario, ksText, csText, name = ''] = parts;
  if (!/^[a-z0-9_]{1,40}$/.test(car)) return { error: `'${car}' is not a car name` };
  if (!/^[0-9a-z]{7}$/.test(scenario)) return { error: `'${scenario}' is not a scenario (7 letters and digits)` };
  const rate = (text, what, unit) => {
    const v = /^\d{1,7}$/.test(text) ? Number(text) : NaN;
    return Number.isFinite(v) && v >= RATE_RANGE[0] && v <= RATE_RANGE[1] ? null : `${what} '${text}' is not a whole number of ${unit} from ${RATE_RANGE[0]} to ${RATE_RANGE[1]}`;
  };
  const bad = rate(ksText, 'Ks', 'N/m') || rate(csText, 'Cs', 'N s/m');
  if (bad) return { error: bad };
  if (name && cleanName(name) !== name) return { error: `'${name}' is not a name (letters, digits, _ and ., up to 20)` };
  return { code: { car, scenario, ks: Number(ksText), cs: Number(csText), name } };
}

/**
 * The codes in `text` (one a line; blank lines skipped): `{codes, problems}`. `codes[i]`:
 * `{line, text, token, n, car, scenario, ks, cs, name}` (`text`: the line, `token`: the
 * code in it, `n`: the code's place among the codes read, 1..); `problems[j]`: `{line, text, reason}` for each line that has no code, a
 * malformed one, or one beyond MAX_CODES. Never throws.
 */
export function readCodes(text) {
  const codes = [];
  const problems = [];
  const lines = String(text ?? '').split(/\r\n|\r|\n/);
  lines.forEach((raw, i) => {
    const line = i + 1;
    const t = raw.trim();
    if (t === '') return;
    const shown = t.length > 80 ? `${t.slice(0, 77)}…` : t;
    const m = /(?:^|[^A-Za-z0-9])(RL\d+-[^\s,;&#"'<>()[\]]*)/i.exec(t);
    if (!m) {
      problems.push({ line, text: shown, reason: 'no RideLab code (RL1-…) on this line' });
      return;
    }
    const r = decodeCode(m[1]);
    if (r.error) problems.push({ line, text: shown, reason: r.error });
    else if (codes.length >= MAX_CODES) problems.push({ line, text: shown, reason: `more than ${MAX_CODES} codes: one Apply reads the first ${MAX_CODES}` });
    else codes.push({ line, text: shown, token: m[1], n: codes.length + 1, ...r.code });
  });
  return { codes, problems };
}
